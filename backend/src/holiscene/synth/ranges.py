"""Every random range of the scene generator, in one place (the docs list these)."""

from __future__ import annotations

ROOM_DEPTH_M = (3.6, 7.0)  # along the camera's viewing direction
ROOM_WIDTH_M = (3.2, 6.0)
ROOM_HEIGHT_M = (2.4, 3.1)
ROOM_YAW_DEG = (-35.0, 35.0)  # the room's turn relative to the camera's heading
CAMERA_HEIGHT_M = (1.1, 1.7)
CAMERA_BACK_OFFSET_M = (0.25, 1.0)  # camera distance from the wall behind it
CAMERA_SIDEWAYS_SHARE = (-0.25, 0.25)  # camera off the room's centre line, share of width
CAMERA_PITCH_DEG = (0.0, 30.0)  # down
CAMERA_ROLL_DEG = (-10.0, 10.0)
CAMERA_HFOV_DEG = (45.0, 75.0)
IMAGE_SIZE = (640, 480)
SENSOR_NOISE_SIGMA = (1.5, 5.0)  # 8-bit grey levels
LIGHT_INTENSITY = (0.7, 1.3)
MIN_VISIBLE_PIXELS = 80  # fewer visible pixels and an object is not part of the scene's labels

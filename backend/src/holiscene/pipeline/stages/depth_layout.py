"""Camera and room from depth, after the line-based layout: the floor plane gives pitch, roll
and the camera's height (an exact metric scale), the walls and ceiling the depth sees are
plane fits, and the parts it does not see keep the line-based layout's priors, in metres.

Runs only when the photo came with depth (`Stage.needs_depth`).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ...geometry.camera import PinholeCamera
from ...geometry.depth_points import point_grid
from ...geometry.depth_room import fit_floor, points_reach, refine_yaw, seen_faces
from ...geometry.manhattan import ManhattanFrame
from ...geometry.room_layout import RoomHypothesis, room_to_world
from ...geometry.surface_labels import map_pixels
from ...placement.room import room_of, wrap_deg
from ..base import SceneContext, Stage, required
from ..registry import register_stage
from .layout import unseen_parts_from_priors, write_layout

GRID_STEP_PX = 4  # every 4th pixel: about 19 000 points for a 640x480 photo


def _frame(pitch: float, roll: float, yaw: float) -> ManhattanFrame:
    return ManhattanFrame(pitch, roll, yaw, np.zeros(0, dtype=np.int64), np.zeros(3))


def _prior_room(ctx: SceneContext, frame: ManhattanFrame, metres: float) -> RoomHypothesis:
    """The line-based room in camera heights of the new scale (its walls keep their metres),
    or a typical room when there was none."""
    room = room_of(ctx.layout)
    if room is None:
        return RoomHypothesis(4.67 / metres, 2.2 / metres, 2.2 / metres, 0.5, 1.0, 0.0, False)
    corners = np.asarray(required(ctx.layout, "layout").corners_3d, dtype=float)
    return RoomHypothesis.enclosing(corners @ room_to_world(frame) / metres)


def _with_faces(room: RoomHypothesis, faces: dict[str, float]) -> RoomHypothesis:
    """`room` with the faces given (camera heights) moved."""
    return dataclasses.replace(
        room,
        front=faces.get("front", room.front),
        left=faces.get("left", room.left),
        right=faces.get("right", room.right),
        ceiling=faces.get("ceiling", room.ceiling),
    )


@register_stage
class LayoutFromDepth(Stage):
    name = "layout_from_depth"
    requires = frozenset({"image", "intrinsics", "camera", "layout"})
    provides = frozenset({"camera", "vanishing_points", "layout"})
    needs_depth = True

    def run(self, ctx: SceneContext) -> None:
        K, source = required(ctx.intrinsics, "intrinsics")
        K = np.asarray(K, dtype=float)
        camera = required(ctx.camera, "camera")
        grid = point_grid(required(ctx.depth, "depth"), K, GRID_STEP_PX)
        guess = PinholeCamera(K, camera.pitch_deg or 0.0, camera.roll_deg or 0.0)
        floor = fit_floor(grid, guess.world_from_cv.T @ np.array([0.0, 1.0, 0.0]))
        if floor is None:
            ctx.notes[self.name] = "the depth shows no floor: the layout from lines is kept"
            return
        level = PinholeCamera(K, floor.pitch_deg, floor.roll_deg)
        room = room_of(ctx.layout)
        yaw = refine_yaw(grid, level, wrap_deg(room.yaw_deg, 90.0) if room else 0.0)
        frame = _frame(floor.pitch_deg, floor.roll_deg, yaw)
        metres = floor.camera_height
        seen = seen_faces(grid, level, yaw)
        prior = _prior_room(ctx, frame, metres)
        # Camera heights, as the room search's (the ceiling's: above the camera).
        fields = {face: distance / metres for face, distance in seen.items()}
        hypothesis = _with_faces(dataclasses.replace(prior, ceiling_seen="ceiling" in seen), fields)
        rays_room = level.ray(map_pixels(ctx.width, ctx.height)) @ room_to_world(frame)
        # The priors fill what the depth does not see; what it sees stays as measured.
        hypothesis = unseen_parts_from_priors(hypothesis, metres, rays_room)
        # ... and a part the depth does not see lies beyond every point it does.
        for face, reach in points_reach(grid, level, yaw).items():
            fields.setdefault(face, max(getattr(hypothesis, face), reach / metres))
        hypothesis = _with_faces(hypothesis, fields)
        corners = hypothesis.corners_room() @ room_to_world(frame).T * metres
        parts = ", ".join(sorted(seen)) or "nothing"
        note = (
            f"depth: camera height {metres:.3f} m from the floor plane ({floor.inliers} points), "
            f"pitch {floor.pitch_deg:.2f}, roll {floor.roll_deg:.2f}; planes fitted: {parts}; "
            "the rest are priors"
        )
        write_layout(ctx, source, frame, corners, metres, note, height_source="depth")
        ctx.reports[self.name] = note

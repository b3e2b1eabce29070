"""A hand-set room layout: the room box and camera pitch/roll re-fitted from dragged corners.

The app fits the same corners with the TypeScript twin of `geometry.room_fit` while the
annotator drags them (frontend/src/editors/layoutEditor.ts); the server fits them again here
and stores the result, so what is saved is what the 3D view showed. Both sides take the
metric scale from the camera's height in the same order: the edit's `camera_height_m` (set by
hand), else the camera's `height_m`, else the stored room's floor, else the layout stage's
prior.
"""

from __future__ import annotations

import math

import numpy as np
from holiscene_schema import Camera, HeightSource, Layout, Scene, SetLayout

from ..geometry.metric_scale import CAMERA_HEIGHT_PRIOR
from ..geometry.room_fit import RoomStart, fit_room, project_room_corners, room_box_of_corners

CAMERA_HEIGHT_PRIOR_M = CAMERA_HEIGHT_PRIOR[0]  # the layout stage's prior
# A known corner may lie outside the photo (a room corner beside or behind the frame), but not
# absurdly far: within this many image widths (heights) of the image on each side. A corner
# near the camera's plane projects thousands of pixels away (12 image widths for synth-12's
# room); the layout stage stores such corners and the page fits with them, so the bound only
# stops numbers no room gives.
MAX_IMAGES_OUTSIDE = 1000.0
# A room smaller than this on a side is a mistake (and placement ignores such rooms).
MIN_ROOM_SIDE_M = 0.5
MAX_ROOM_SIDE_M = 100.0
# Corners that no box fits to within this share of the photo's diagonal (root mean square) are
# not one room: one of them was dropped in the wrong place.
MAX_FIT_ERROR = 0.05


class LayoutEditError(ValueError):
    """The corners do not give a room (the message says why)."""


def camera_height(scene: Scene) -> tuple[float, HeightSource]:
    """Metres from the camera down to the floor (the scale of the room fit), and its source."""
    camera = scene.camera
    if camera is not None and camera.height_m is not None and camera.height_m > 0:
        return camera.height_m, camera.height_source or "estimated"
    corners = scene.layout.corners_3d
    if corners is not None:
        floor = -float(np.mean([c[1] for c in corners[:4]]))
        if floor > 0:
            return floor, "estimated"
    return CAMERA_HEIGHT_PRIOR_M, "prior"


def _check_corners(scene: Scene, edit: SetLayout) -> None:
    width, height = scene.image.width, scene.image.height
    for index, corner in enumerate(edit.corners_2d):
        if corner is None:
            continue
        x, y = corner
        if not (math.isfinite(x) and math.isfinite(y)):
            raise LayoutEditError(f"corner {index} is not a finite pixel position")
        if not (
            -MAX_IMAGES_OUTSIDE * width <= x <= (1 + MAX_IMAGES_OUTSIDE) * width
            and -MAX_IMAGES_OUTSIDE * height <= y <= (1 + MAX_IMAGES_OUTSIDE) * height
        ):
            raise LayoutEditError(
                f"corner {index} at ({x:.0f}, {y:.0f}) is more than {MAX_IMAGES_OUTSIDE:.0f} "
                f"image sizes outside the {width}x{height} photo"
            )


def _stored_room(scene: Scene) -> RoomStart | None:
    """The room the scene has now: where the fit starts when the dragged corners give no
    start of their own (the page starts from the room it showed, which is this one or close)."""
    camera, corners = scene.camera, scene.layout.corners_3d
    if camera is None or corners is None or camera.pitch_deg is None or camera.roll_deg is None:
        return None
    return RoomStart(camera.pitch_deg, camera.roll_deg, room_box_of_corners(corners))


def apply_set_layout(scene: Scene, edit: SetLayout) -> Scene:
    """The scene with the layout and camera pitch/roll fitted to the edit's corners."""
    if scene.camera is None:
        raise LayoutEditError("the scene has no camera intrinsics yet: run the pipeline first")
    _check_corners(scene, edit)
    metres, height_source = camera_height(scene)
    if edit.camera_height_m is not None:
        metres, height_source = edit.camera_height_m, "manual"
    K = np.asarray(scene.camera.K, dtype=float)
    try:
        fit = fit_room(
            K,
            edit.corners_2d,
            metres,
            unseen_wall_distance=edit.unseen_wall_distance,
            start=_stored_room(scene),
        )
    except ValueError as error:
        raise LayoutEditError(str(error)) from error
    size = fit.room.size
    if not (np.all(size >= MIN_ROOM_SIDE_M) and np.all(size <= MAX_ROOM_SIDE_M)):
        sides = " x ".join(f"{s:.2f}" for s in size)
        raise LayoutEditError(
            f"the corners give a room of {sides} m: each side must be between "
            f"{MIN_ROOM_SIDE_M} and {MAX_ROOM_SIDE_M:.0f} m"
        )
    limit = MAX_FIT_ERROR * math.hypot(scene.image.width, scene.image.height)
    if fit.rms_px > limit:
        raise LayoutEditError(
            f"the corners do not fit one room box: they are {fit.rms_px:.0f} px off on "
            f"average (at most {limit:.0f} px)"
        )
    pitch, roll = round(fit.pitch_deg, 4), round(fit.roll_deg, 4)
    corners_3d = fit.corners_3d.round(4)
    # Stored as the fitted box's own projections, so corners_2d stays the image of corners_3d.
    projected = project_room_corners(K, pitch, roll, corners_3d)
    known = sum(c is not None for c in edit.corners_2d)
    note = f"set by hand: {known} corners, fit error {fit.rms_px:.1f} px"
    if edit.camera_height_m is not None:
        note += f", camera {metres:.2f} m above the floor"
    if not fit.converged:
        note += " (the fit stopped before converging)"
    camera: Camera = scene.camera.model_copy(
        update={
            "pitch_deg": pitch,
            "roll_deg": roll,
            "height_m": round(metres, 4),
            "height_source": height_source,
            "note": None,
        }
    )
    layout = Layout(
        corners_2d=[None if p is None else [round(v, 2) for v in p] for p in projected],
        corners_3d=corners_3d.tolist(),
        source="manual",
        note=note,
    )
    return scene.model_copy(update={"camera": camera, "layout": layout})


def describe_set_layout(edit: SetLayout) -> str:
    known = sum(c is not None for c in edit.corners_2d)
    if edit.camera_height_m is None:
        return f"room layout set from {known} corners"
    return f"room layout set from {known} corners, camera {edit.camera_height_m:.2f} m high"

"""Camera and room layout from the photo's lines: Manhattan frame, room hypotheses, metric
scale (`geometry.metric_scale` says which priors give metres and how wrong they can be)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from holiscene_schema import Camera, HeightSource, Layout, SceneObject
from numpy.typing import NDArray

from ...geometry.camera import FloatArray, PinholeCamera
from ...geometry.lines import detect_segments
from ...geometry.manhattan import ManhattanFrame, estimate_manhattan_frame
from ...geometry.metric_scale import (
    ROOM_HEIGHT_PRIOR,
    Mounted,
    bottom_may_be_hidden,
    camera_height,
    floor_contacts,
    mounting_points,
    too_large_to_stand_there,
)
from ...geometry.room_layout import RoomHypothesis, SurfaceEvidence, estimate_room, room_to_world
from ...geometry.room_width import unseen_side_wall_distance
from ...geometry.surface_labels import map_pixels
from ...geometry.surface_map import (
    DEFAULT_SURFACE_MODEL,
    SurfaceMap,
    SurfaceModel,
    load_surface_model,
)
from ..base import SceneContext, Stage, required
from ..registry import register_stage

MIN_CEILING_ABOVE_CAMERA = 0.15  # camera heights: a camera is never at the ceiling
BACK_WALL_DISTANCE_M = 0.65  # people photograph a room standing a little way from a wall


def unseen_parts_from_priors(
    room: RoomHypothesis, metres: float, rays_room: FloatArray
) -> RoomHypothesis:
    """The parts the photo does not show, in metres now that the scale is known: the wall
    behind the camera at a typical distance, a ceiling not seen at the typical room height
    (the line search's guess, from wall colours alone, was off by a quarter on average; this
    is off by about the room-height prior's spread), and a side wall not seen when the other
    is, from the room's width prior (`room_width`). `rays_room` are the photo's rays."""
    back = BACK_WALL_DISTANCE_M / metres
    if room.ceiling_seen:
        room = dataclasses.replace(room, back=back)
    else:
        ceiling = max(ROOM_HEIGHT_PRIOR[0] / metres - 1.0, MIN_CEILING_ABOVE_CAMERA)
        room = dataclasses.replace(room, back=back, ceiling=ceiling)
    sides_seen = [wall for wall in ("left", "right") if wall in room.faces_in_view(rays_room)]
    if len(sides_seen) != 1:  # both seen, or neither: the room search's priors decide
        return room
    seen = sides_seen[0]
    unseen = "right" if seen == "left" else "left"
    distance = unseen_side_wall_distance(
        getattr(room, seen) * metres, room.nearest_out_of_view(unseen, rays_room) * metres
    )
    if distance is None:
        return room
    if unseen == "left":
        return dataclasses.replace(room, left=distance / metres)
    return dataclasses.replace(room, right=distance / metres)


def mounted_heights(
    room: RoomHypothesis,
    camera: PinholeCamera,
    to_room: FloatArray,
    objects: list[SceneObject],
    image_height: int,
) -> Mounted:
    """Things on walls with the height above the floor (camera heights) where their lower edge
    meets the room's walls (`metric_scale.mounting_points` says which end of it to believe)."""
    points = mounting_points(objects, image_height)
    if not points:
        return []
    rays = camera.ray(np.concatenate([ends for _, ends in points])) @ to_room
    heights = room.height_on_walls(rays).reshape(len(points), 2)
    out = []
    for (obj, _), pair in zip(points, heights, strict=True):
        seen = pair[np.isfinite(pair)]  # the other end's ray may meet the floor first
        if len(seen):
            out.append((obj, float(seen.max())))
    return out


@dataclass(frozen=True)
class LayoutEstimate:
    """What the photo says of the camera and the room, before it is written to the scene."""

    frame: ManhattanFrame
    camera: PinholeCamera
    to_room: FloatArray  # room axes -> world
    room: RoomHypothesis  # camera heights
    metres: float  # the camera's height
    priors: str  # which priors decided `metres`, and how far off it may be
    # The measurements `metres` was fused from (the scale's calibration measures these).
    contacts: list[tuple[SceneObject, FloatArray]]  # floor contacts, camera height 1
    mounted: Mounted  # things on walls, their lower edges' heights

    def corners_world(self) -> FloatArray:
        """The room's 8 corners in the world frame, metres (contract order)."""
        result: FloatArray = self.room.corners_room() @ self.to_room.T * self.metres
        return result


def estimate_layout(
    image: NDArray[np.uint8],
    K: FloatArray,
    objects: list[SceneObject],
    surface_model: SurfaceModel | None,
) -> LayoutEstimate | None:
    """Manhattan frame -> room search (with the Surface Network's labels when there is a
    model) -> metric scale -> the parts out of view in metres (back wall, unseen ceiling and
    side wall);
    None when too few vertical lines are seen."""
    height, width = image.shape[:2]
    segments = detect_segments(image)
    frame = estimate_manhattan_frame(segments, K)
    if frame is None:
        return None
    camera = PinholeCamera(K, frame.pitch_deg, frame.roll_deg)
    contacts = floor_contacts(camera, objects, height)
    to_room = room_to_world(frame)
    boxes = [o.bbox for o in objects]
    # Points surely inside the room: contacts whose bottom edge no nearer object may hide, of
    # objects of a believable size standing there.
    inside = [
        p
        for o, p in contacts
        if not bottom_may_be_hidden(o, objects)
        and not too_large_to_stand_there(camera, o.cls, o.bbox)
    ]
    # The objects' scale turns the priors on wall distances (metres) into camera heights; the
    # seen ceiling and front wall then join the final scale.
    metres_from_objects = camera_height(camera, contacts, None, width).metres
    surface_map = (
        SurfaceMap.predict(surface_model, image, camera, to_room) if surface_model else None
    )
    room = estimate_room(
        camera,
        frame,
        segments,
        (width, height),
        np.array(inside) if inside else None,
        SurfaceEvidence(camera, image, boxes, to_room),
        boxes,
        surface_map,
        metres=metres_from_objects,
    )
    # The room found, things on walls join the scale: their lower edges' heights.
    mounted = mounted_heights(room, camera, to_room, objects, height)
    ceiling = room.ceiling if room.ceiling_seen else None
    # The rays of the map's cells say which faces the photo shows (the map has them already).
    rays_room = (
        surface_map.rays_room if surface_map else camera.ray(map_pixels(width, height)) @ to_room
    )
    front = room.front if "front" in room.faces_in_view(rays_room) else None
    scale = camera_height(camera, contacts, ceiling, width, mounted=mounted, front_wall=front)
    room = unseen_parts_from_priors(room, scale.metres, rays_room)
    return LayoutEstimate(
        frame, camera, to_room, room, scale.metres, scale.describe(), contacts, mounted
    )


@register_stage
class LayoutFromLines(Stage):
    name = "layout_from_lines"
    requires = frozenset({"image", "intrinsics", "objects"})
    provides = frozenset({"camera", "vanishing_points", "layout"})

    def __init__(self, surface_model: Path | None = DEFAULT_SURFACE_MODEL) -> None:
        """`surface_model`: the Surface Network's ONNX file; None scores rooms by colours and
        lines alone (how the layout was found before the network, kept for comparison)."""
        self.surface_model = load_surface_model(surface_model) if surface_model else None

    def run(self, ctx: SceneContext) -> None:
        K, source = required(ctx.intrinsics, "intrinsics")
        estimate = estimate_layout(
            ctx.image, K, required(ctx.objects, "objects"), self.surface_model
        )
        if estimate is None:
            ctx.notes[self.name] = "too few vertical lines: pitch, roll and layout unknown"
            ctx.camera = Camera(
                K=K.tolist(),
                K_source=source,
                pitch_deg=None,
                roll_deg=None,
                note=ctx.notes[self.name],
            )
            ctx.layout = Layout(note=ctx.notes[self.name])
            ctx.vanishing_points = np.zeros((0, 3))  # none found; later stages check the shape
            return
        note = f"scale from {estimate.priors}; the back wall's distance is a prior"
        write_layout(ctx, source, estimate.frame, estimate.corners_world(), estimate.metres, note)
        ctx.reports[self.name] = note


def image_corners(camera: PinholeCamera, corners: FloatArray) -> list[list[float] | None]:
    """The stored 2D corners of stored 3D ones: None for a corner behind the camera."""
    return [
        None if np.isnan(p).any() else [round(float(v), 2) for v in p]
        for p in camera.project(corners)
    ]


def write_layout(
    ctx: SceneContext,
    K_source: str,
    frame: ManhattanFrame,
    corners_world: FloatArray,
    metres: float,
    note: str,
    height_source: HeightSource = "estimated",
) -> None:
    """Set the camera, the vanishing points and the room (corners in metres, world frame) on
    the context, as a scene stores them; `height_source` says how `metres` (the camera's
    height) was found."""
    K = np.asarray(required(ctx.intrinsics, "intrinsics")[0], dtype=float)
    camera = PinholeCamera(K, frame.pitch_deg, frame.roll_deg)
    # Stored rounded; the 2D corners are those of the stored 3D ones (a corner near the
    # camera's plane projects far away, where the rounding would show).
    corners = corners_world.round(4)
    ctx.vanishing_points = frame.vanishing_points(K)
    ctx.camera = Camera(
        K=K.tolist(),
        K_source=K_source,
        pitch_deg=round(frame.pitch_deg, 4),
        roll_deg=round(frame.roll_deg, 4),
        height_m=round(metres, 4),
        height_source=height_source,
    )
    ctx.layout = Layout(
        corners_2d=image_corners(camera, corners),
        corners_3d=corners.tolist(),
        source="estimated",
        note=note,
    )

"""Camera and room layout from the photo's lines: Manhattan frame, room hypotheses, metric scale.

Metric scale is the one thing a single photo cannot give. It comes from three priors, fused
in log space: the camera's height (1.4 m, sd ~15%), the room's height when the ceiling's
edges are seen (2.75 m, sd ~10%), and the typical heights of floor-standing furniture
(sd ~30% each). Each prior is wrong by its spread on a given photo; together they are
usually within 10%.
"""

from __future__ import annotations

import math

import numpy as np
from holiscene_schema import Camera, Layout, SceneObject

from ...geometry.camera import FloatArray, PinholeCamera
from ...geometry.ground import height_above, hit_horizontal_plane
from ...geometry.lines import detect_segments
from ...geometry.manhattan import estimate_manhattan_frame
from ...geometry.room_layout import RoomHypothesis, SurfaceEvidence, estimate_room, room_to_world
from ...knowledge.object_sizes import height_spread, middle_size
from ..base import SceneContext, Stage, required
from ..registry import register_stage

CAMERA_HEIGHT_PRIOR = (1.4, 0.12)  # metres, sd of log
ROOM_HEIGHT_PRIOR = (2.75, 0.15)
MEASUREMENT_SD = 0.1  # log error of one object's measured height (edges, occlusion)
# Classes standing on the floor whose bottom edge is where they meet it (doors included:
# their heights vary least of all, so they weigh most).
FLOOR_CLASSES = frozenset(
    {"bed", "sofa", "chair", "table", "desk", "dresser", "night_stand", "cabinet", "bookshelf",
     "shelves", "counter", "refrigerator", "toilet", "bathtub", "door"}
)  # fmt: skip


def _floor_contacts(
    camera: PinholeCamera, objects: list[SceneObject], height: int
) -> list[tuple[SceneObject, FloatArray]]:
    """Floor points (camera height 1) under furniture whose bottom edge is in the photo."""
    out = []
    for obj in objects:
        x1, _, x2, y2 = obj.bbox
        if obj.cls not in FLOOR_CLASSES or y2 >= height - 2:
            continue
        hits = hit_horizontal_plane(camera, np.array([[(x1 + x2) / 2, y2]]), -1.0)
        if hits is not None:
            out.append((obj, hits[0]))
    return out


def camera_height(
    camera: PinholeCamera, room: RoomHypothesis, contacts: list[tuple[SceneObject, FloatArray]]
) -> tuple[float, str]:
    """Metres per unit (the camera's height), and which priors decided it."""
    logs = [(math.log(CAMERA_HEIGHT_PRIOR[0]), CAMERA_HEIGHT_PRIOR[1])]
    used = ["camera height"]
    if room.ceiling_seen:
        logs.append((math.log(ROOM_HEIGHT_PRIOR[0] / (1.0 + room.ceiling)), ROOM_HEIGHT_PRIOR[1]))
        used.append("room height")
    sized = [
        (estimate, math.hypot(height_spread(obj.cls), MEASUREMENT_SD))
        for obj, base in contacts
        if (estimate := _size_estimate(camera, obj, base)) is not None
    ]
    if sized:
        # Drop objects far from the others (a box measured across an occluder, say).
        centre = float(np.median([e for e, _ in sized]))
        kept = [(e, sd) for e, sd in sized if abs(e - centre) < 2.5 * sd]
        logs += kept
        used.append(f"{len(kept)} object size(s)")
    weights = np.array([1 / sd**2 for _, sd in logs])
    values = np.array([v for v, _ in logs])
    return float(math.exp((weights @ values) / weights.sum())), " + ".join(used)


def _size_estimate(camera: PinholeCamera, obj: SceneObject, base: FloatArray) -> float | None:
    """log(camera height) implied by the object's typical height, or None.

    Seen from above, a box's top edge in the photo is its far top edge, about one depth
    behind the contact point: the vertical is moved back by the class's depth (in units of
    the camera height, so a few fixed-point steps)."""
    x1, y1, x2, _ = obj.bbox
    if y1 <= 2:
        return None  # the top is cut off: its height is unknown
    depth, height, _ = middle_size(obj.cls)
    heading = np.array([base[0], 0.0, base[2]]) / max(float(np.hypot(base[0], base[2])), 1e-9)
    metres = CAMERA_HEIGHT_PRIOR[0]
    for _ in range(3):
        unit_height = height_above(
            camera, base + heading * depth / metres, np.array([[(x1 + x2) / 2, y1]])
        )
        if unit_height <= 0.05:
            return None
        metres = height / unit_height
    return math.log(metres)


@register_stage
class LayoutFromLines(Stage):
    name = "layout_from_lines"
    requires = frozenset({"image", "intrinsics", "objects"})
    provides = frozenset({"camera", "vanishing_points", "layout"})

    def run(self, ctx: SceneContext) -> None:
        K, source = required(ctx.intrinsics, "intrinsics")
        objects = required(ctx.objects, "objects")
        segments = detect_segments(ctx.image)
        frame = estimate_manhattan_frame(segments, K)
        if frame is None:
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
        camera = PinholeCamera(K, frame.pitch_deg, frame.roll_deg)
        contacts = _floor_contacts(camera, objects, ctx.height)
        evidence = SurfaceEvidence(
            camera, ctx.image, [o.bbox for o in objects], room_to_world(frame)
        )
        room = estimate_room(
            camera,
            frame,
            segments,
            (ctx.width, ctx.height),
            np.array([p for _, p in contacts]) if contacts else None,
            evidence,
            [o.bbox for o in objects],
        )
        metres, priors = camera_height(camera, room, contacts)
        corners = room.corners_room() @ room_to_world(frame).T * metres
        projected = camera.project(corners)
        note = f"scale from {priors}; the back wall's distance is a prior"
        ctx.vanishing_points = frame.vanishing_points(K)
        ctx.camera = Camera(
            K=K.tolist(),
            K_source=source,
            pitch_deg=round(frame.pitch_deg, 4),
            roll_deg=round(frame.roll_deg, 4),
            height_m=round(metres, 4),
            height_source="estimated",
        )
        ctx.layout = Layout(
            corners_2d=[
                None if np.isnan(p).any() else [round(float(v), 2) for v in p] for p in projected
            ],
            corners_3d=corners.round(4).tolist(),
            source="estimated",
            note=note,
        )
        ctx.notes[self.name] = note

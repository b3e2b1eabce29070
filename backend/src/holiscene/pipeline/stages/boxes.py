"""3D boxes of objects standing on the floor or on another object, from where they touch it.

For an object supported from below, the bottom edge of its 2D box is where it meets its
supporter's top surface: the ray through that edge, cut with the supporter's plane, gives
its position and width; the top edge gives its height; the depth comes from its class's
typical proportions. Boxes face the camera (yaw along the viewing ray). Objects on walls need
the room layout, which this pipeline does not estimate yet: their box stays null.
"""

from __future__ import annotations

import math

import numpy as np
from holiscene_schema import Box3D, SceneObject, SupportRelation

from ...geometry.camera import PinholeCamera
from ...geometry.ground import height_above, hit_horizontal_plane
from ...knowledge.object_sizes import middle_size
from ...placement.support_order import supporters_first
from ..base import SceneContext, Stage, required
from ..registry import register_stage


def box_on_plane(camera: PinholeCamera, obj: SceneObject, plane_y: float) -> Box3D | None:
    x1, y1, x2, y2 = obj.bbox
    xc = (x1 + x2) / 2.0
    hits = hit_horizontal_plane(camera, np.array([[x1, y2], [xc, y2], [x2, y2]]), plane_y)
    if hits is None:
        return None
    left, centre, right = hits
    width = float(np.linalg.norm(right - left))
    height = height_above(camera, centre, np.array([[xc, y1]]))
    typical_depth, typical_height, typical_width = middle_size(obj.cls)
    if not 0.02 < height < 4.0:
        height = typical_height
    depth = float(np.clip(width * typical_depth / typical_width, 0.05, 3.0))
    heading = np.array([centre[0], 0.0, centre[2]])
    heading /= max(float(np.linalg.norm(heading)), 1e-9)
    middle = centre + heading * depth / 2.0 + np.array([0.0, height / 2.0, 0.0])
    yaw = math.degrees(math.atan2(heading[2], -heading[0]))  # the box's front faces the camera
    return Box3D(
        center=[round(float(v), 4) for v in middle],
        size=[round(depth, 4), round(height, 4), round(width, 4)],
        yaw_deg=round(yaw, 3),
    )


@register_stage
class BoxesOnSupporters(Stage):
    name = "boxes_on_supporters"
    requires = frozenset({"objects", "camera", "supports"})
    provides = frozenset({"boxes_3d"})

    def run(self, ctx: SceneContext) -> None:
        objects = required(ctx.objects, "objects")
        cam = required(ctx.camera, "camera")
        boxes: dict[str, Box3D | None] = {o.id: None for o in objects}
        ctx.boxes_3d = boxes
        if cam.pitch_deg is None or cam.roll_deg is None or cam.height_m is None:
            ctx.notes[self.name] = "camera pitch and roll unknown: no 3D boxes"
            return
        camera = PinholeCamera(np.array(cam.K), cam.pitch_deg, cam.roll_deg)
        by_id = {o.id: o for o in objects}
        support_of = {s.child: s for s in required(ctx.supports, "supports")}
        for obj in supporters_first(objects, support_of):
            support = support_of.get(obj.id)
            plane_y = _resting_plane(support, boxes, -cam.height_m)
            if plane_y is None:
                ctx.object_notes[obj.id] = _why_no_plane(support)
                continue
            boxes[obj.id] = box_on_plane(camera, by_id[obj.id], plane_y)
            if boxes[obj.id] is None:
                ctx.object_notes[obj.id] = (
                    "no 3D box: its bottom edge does not meet the supporting plane in view"
                )
        missing = sum(box is None for box in boxes.values())
        if missing:
            ctx.notes[self.name] = (
                f"{missing} object(s) without a 3D box (on walls, or their supporter has none)"
            )


def _resting_plane(
    support: SupportRelation | None, boxes: dict[str, Box3D | None], floor_y: float
) -> float | None:
    if support is None or support.type != "below":
        return None
    if support.parent == "floor":
        return floor_y
    parent_box = boxes.get(support.parent)
    if parent_box is None:
        return None
    return parent_box.center[1] + parent_box.size[1] / 2.0


def _why_no_plane(support: SupportRelation | None) -> str:
    if support is None:
        return "no 3D box: the object has no supporter"
    if support.type == "behind":
        return "no 3D box: objects supported from behind need the room layout (not estimated yet)"
    return f"no 3D box: its supporter {support.parent} has none"

"""3D boxes and heights from the depth under each mask, after the placement stage
(`placement.depth_box`): objects are taken from the floor up, so each rests on its
supporter's box; an object whose mask holds too little depth keeps the placement's box.

Runs only when the photo came with depth (`Stage.needs_depth`).
"""

from __future__ import annotations

from holiscene_schema import Box3D, SupportRelation

from ...placement.depth_box import Support, box_from_points, object_points, quarter_turn
from ...placement.room import pinhole, room_of
from ...placement.support_order import supporters_first
from ..base import SceneContext, Stage, required
from ..registry import register_stage


def _support(
    relation: SupportRelation | None, boxes: dict[str, Box3D | None], floor_y: float
) -> Support:
    """The height the object's bottom rests at: the floor's, its supporter's top, or (hung on
    a wall, or its supporter unplaced) wherever its points end."""
    if relation is None or relation.parent == "floor":
        return Support(floor_y)
    if relation.type != "below":
        return Support(None)
    below = boxes.get(relation.parent)
    if below is None:
        return Support(None)
    return Support(below.center[1] + below.size[1] / 2.0)


@register_stage
class BoxesFromDepth(Stage):
    name = "boxes_from_depth"
    requires = frozenset({"objects", "masks", "camera", "layout", "supports", "boxes_3d"})
    provides = frozenset({"boxes_3d", "heights"})
    needs_depth = True

    def run(self, ctx: SceneContext) -> None:
        objects = required(ctx.objects, "objects")
        masks = required(ctx.masks, "masks")
        depth = required(ctx.depth, "depth")
        camera = pinhole(required(ctx.camera, "camera"))
        room = room_of(required(ctx.layout, "layout"))
        boxes = dict(required(ctx.boxes_3d, "boxes_3d"))
        if camera is None or room is None:
            ctx.notes[self.name] = "no camera or room: the placement's boxes are kept"
            return
        support_of = {s.child: s for s in required(ctx.supports, "supports")}
        heights = dict(ctx.heights or {})
        kept = []
        for obj in supporters_first(objects, support_of):
            mask = masks.get(obj.id)
            points = object_points(mask.pixels, depth, camera) if mask is not None else None
            if points is None:
                kept.append(obj.id)
                continue
            placed = boxes.get(obj.id)
            turn = quarter_turn(placed.yaw_deg if placed else None, room.yaw_deg)
            support = _support(support_of.get(obj.id), boxes, room.floor_y)
            box = box_from_points(points, obj.cls, room, support, turn)
            boxes[obj.id] = box
            heights[obj.id] = box.size[1]
            ctx.object_notes.pop(obj.id, None)
        ctx.boxes_3d = boxes
        ctx.heights = heights
        found = len(objects) - len(kept)
        ctx.reports[self.name] = f"{found} of {len(objects)} boxes from the depth"
        if kept:
            ctx.notes[self.name] = "too little depth under the mask, placement kept: " + ", ".join(
                kept
            )

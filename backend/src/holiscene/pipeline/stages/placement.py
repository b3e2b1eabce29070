"""3D boxes by maximising IoU(projected box, mask) under the support constraints.

See `holiscene.placement.solver` (thesis Eq. 4.4-4.6): objects are placed from the floor up;
those supported from below rest on their supporter's top (or a surface inside it) with their
centre over it, those supported from behind hang on a wall of the layout or on a face of
their supporter's box. Each box starts from the mask's contact edge and the measured height,
then DIRECT and BOBYQA refine its position and size for each candidate orientation.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from holiscene_schema import Box3D, SupportRelation

from ...placement.room import pinhole, room_of
from ...placement.solver import Placement, PlacementOptions, Placer
from ...placement.support_order import supporters_first
from ..base import PipelineBuildError, SceneContext, Stage, required
from ..registry import register_stage


@register_stage
class PlacementStage(Stage):
    name = "placement"
    requires = frozenset({"objects", "masks", "camera", "layout", "supports", "heights"})
    provides = frozenset({"boxes_3d"})

    def __init__(self, **options: Any) -> None:
        known = set(PlacementOptions.__dataclass_fields__)
        unknown = set(options) - known
        if unknown:
            raise PipelineBuildError(
                f"stage {self.name!r} takes options {sorted(known)}, got {sorted(unknown)}"
            )
        self.options = PlacementOptions(**options)
        self.last: dict[str, Placement] = {}  # the latest run's details, for tests and tools

    def run(self, ctx: SceneContext) -> None:
        objects = required(ctx.objects, "objects")
        masks = required(ctx.masks, "masks")
        heights = required(ctx.heights, "heights")
        contract_camera = required(ctx.camera, "camera")
        support_of: dict[str, SupportRelation] = {
            s.child: s for s in required(ctx.supports, "supports")
        }
        boxes: dict[str, Box3D | None] = {o.id: None for o in objects}
        ctx.boxes_3d = boxes
        camera = pinhole(contract_camera)
        room = room_of(required(ctx.layout, "layout"))
        if room is not None:
            floor_y = room.floor_y
        elif contract_camera.height_m is not None:
            floor_y = -contract_camera.height_m
        else:
            floor_y = None
        if camera is None or floor_y is None:
            ctx.notes[self.name] = "camera pitch, roll or floor unknown: no 3D boxes"
            for obj in objects:
                ctx.object_notes[obj.id] = "no 3D box: the camera or the floor is unknown"
            return
        placer = Placer(camera, room, floor_y, {o.id: o.cls for o in objects}, self.options)
        for obj in supporters_first(objects, support_of):
            mask = masks.get(obj.id)
            height = heights.get(obj.id)
            if mask is None or height is None:
                ctx.object_notes[obj.id] = (
                    "no 3D box: no mask" if mask is None else ("no 3D box: no height")
                )
                continue
            result = placer.place(obj, mask.pixels, support_of.get(obj.id), float(height))
            if isinstance(result, str):
                ctx.object_notes[obj.id] = result
                continue
            boxes[obj.id] = result.box
        self.last = dict(placer.placed)
        missing = [obj_id for obj_id, box in boxes.items() if box is None]
        problems = []
        if room is None:
            problems.append("no room layout: objects on walls are not placed")
        if missing:
            # Each with its reason, where the warning is read ("d1 (its bottom edge does not
            # meet the floor in view)"): a person can then fix the supporter or the box.
            reasons = [
                f"{obj_id} ({why.removeprefix('no 3D box: ')})"
                if (why := ctx.object_notes.get(obj_id))
                else obj_id
                for obj_id in missing
            ]
            problems.append(f"no 3D box for {', '.join(reasons)}")
        if problems:
            ctx.notes[self.name] = "; ".join(problems)
        if self.last:
            ious = [p.iou for p in self.last.values()]
            ctx.reports[self.name] = f"mean IoU(projection, mask) {float(np.mean(ious)):.2f}"

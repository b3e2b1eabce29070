"""3D boxes refined by the learned box refiner (thesis Ch. 5; `learning.box_refiner`), after
the placement: each box is moved along its ray and resized by what the network reads from
the placement's boxes, the masks, supports and camera, and the other objects, and given the
chance that it is right (`SceneObject.box_3d_confidence`). On held-out synthetic rooms this
finds more true boxes than the placement alone (docs/benchmarks.md, "Learned box
refinement"); `--stages` without it keeps the placement's boxes.

Skipped for a photo with depth (`Stage.single_photo_only`): the depth's boxes are better.
"""

from __future__ import annotations

from ...learning.box_refiner.confidence import DOUBTFUL_CHANCE
from ...learning.box_refiner.features import SceneView
from ...learning.box_refiner.runtime import box_refiner
from ..base import SceneContext, Stage, required
from ..registry import register_stage


@register_stage
class BoxesByRefiner(Stage):
    name = "boxes_by_refiner"
    requires = frozenset({"objects", "masks", "camera", "supports", "boxes_3d"})
    provides = frozenset({"boxes_3d"})
    single_photo_only = True

    def run(self, ctx: SceneContext) -> None:
        camera = required(ctx.camera, "camera")
        boxes = dict(required(ctx.boxes_3d, "boxes_3d"))
        objects = required(ctx.objects, "objects")
        if not objects:  # an empty scene is told once, by the stage that made the objects
            ctx.reports[self.name] = "no objects to refine"
            return
        if camera.height_m is None:
            ctx.notes[self.name] = "no camera height (metric scale): the placement's boxes are kept"
            return
        if not any(boxes.values()):
            ctx.notes[self.name] = "no object has a 3D box to refine"
            return
        masks = required(ctx.masks, "masks")
        view = SceneView(
            objects=objects,
            boxes=boxes,
            mask_pixels={i: int(m.pixels.sum()) for i, m in masks.items()},
            supports=required(ctx.supports, "supports"),
            camera=camera,
            width=ctx.width,
            height=ctx.height,
        )
        refined = box_refiner().refine(view)
        boxes.update({object_id: r.box for object_id, r in refined.items()})
        ctx.boxes_3d = boxes
        ctx.box_confidences.update({object_id: r.confidence for object_id, r in refined.items()})
        doubtful = sum(r.confidence < DOUBTFUL_CHANCE for r in refined.values())
        ctx.reports[self.name] = (
            f"{len(refined)} boxes refined, {doubtful} of them more likely wrong than right"
        )

"""Objects from the 2D boxes given with the photo (objects[i] is detections[i])."""

from __future__ import annotations

from holiscene_schema import SceneObject

from ..base import Detection, SceneContext, Stage
from ..people import keep_people_objects
from ..registry import register_stage


@register_stage
class ObjectsFromDetections(Stage):
    name = "objects_from_detections"
    requires = frozenset({"detections"})
    provides = frozenset({"objects"})

    def run(self, ctx: SceneContext) -> None:
        if ctx.detections is None:
            ctx.objects = keep_people_objects([], ctx.pinned_objects, ctx.removed_objects)
            ctx.notes[self.name] = (
                "no detections.json was given and this pipeline has no object detector"
            )
            return
        ctx.objects = keep_people_objects(
            objects_from_detections(ctx.detections), ctx.pinned_objects, ctx.removed_objects
        )


def objects_from_detections(detections: list[Detection]) -> list[SceneObject]:
    """One object per box, in order, with ids o0, o1, ..."""
    return [
        SceneObject(
            id=f"o{index}",
            cls=det.cls,  # normalised to NYU-40 on import
            source_class=det.source_class,
            bbox=list(det.bbox),
            source="given",
        )
        for index, det in enumerate(detections)
    ]

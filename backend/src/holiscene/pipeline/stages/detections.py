"""Objects from the 2D boxes given with the photo (objects[i] is detections[i])."""

from __future__ import annotations

from holiscene_schema import SceneObject

from ..base import Detection, SceneContext, Stage
from ..people import keep_people_objects
from ..registry import register_stage

# A scene imported with an empty detections.json (objects to be added by people).
NO_GIVEN_OBJECTS = (
    "detections.json lists no objects: add them on the scene page (Detect objects, or the box tool)"
)


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
        unknown = unknown_class_note(ctx.detections)
        if unknown:
            ctx.notes[self.name] = unknown
        elif not ctx.objects:
            ctx.notes[self.name] = NO_GIVEN_OBJECTS


def unknown_class_note(detections: list[Detection]) -> str | None:
    """What to tell about class names no vocabulary knew (they became otherprop), or None."""
    names = sorted({d.source_class or "" for d in detections if not d.class_known})
    if not names:
        return None
    shown = ", ".join(repr(n) for n in names[:8]) + (", ..." if len(names) > 8 else "")
    return (
        f"{len(names)} class name(s) are neither NYU-40 nor a known alias and became "
        f"otherprop (the name is kept on the object): {shown}; a class_map.json beside the "
        "photo maps them"
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
            mask=det.mask,
        )
        for index, det in enumerate(detections)
    ]

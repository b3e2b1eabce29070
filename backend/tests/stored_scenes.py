"""Hand-made scenes for the workflow tests: a few objects whose supports and confidences the
test chooses, stored with a tiny photo (no pipeline run needed)."""

from __future__ import annotations

import itertools

import cv2
import numpy as np
from holiscene.inputs import InputFiles, load_photo
from holiscene.store.scenes import SceneStore
from holiscene_schema import ImageInfo, Scene, SceneObject, SupportRelation

# (id, class) of every test scene; the wall needs no supporter.
OBJECTS = (("o0", "table"), ("o1", "lamp"), ("o2", "books"), ("o3", "chair"), ("w", "wall"))
Support = tuple[str, str, str]  # child, parent, type


# Each stored scene gets a photo of its own (a number in its first pixels): scenes of one photo
# share a side of the held-out split, and these stand for scenes of different photos.
_photo_numbers = itertools.count()


def _png(number: int) -> bytes:
    pixels = np.full((48, 64, 3), 200, np.uint8)
    pixels[0, :4, 0] = list(number.to_bytes(4, "big"))
    ok, data = cv2.imencode(".png", pixels)
    assert ok
    return bytes(data.tobytes())


def make_scene(
    supports: list[Support], confidences: dict[str, float | None] | None = None
) -> Scene:
    """A 64x48 scene with OBJECTS and the given supports, as the pipeline guessed them
    (source auto) with the given confidence per child (default 0.9)."""
    confidences = confidences or {}
    objects = [
        SceneObject.model_validate(
            {"id": object_id, "class": cls, "bbox": [i * 10.0, 5.0, i * 10.0 + 8.0, 40.0]}
        )
        for i, (object_id, cls) in enumerate(OBJECTS)
    ]
    relations = [
        SupportRelation(
            child=child,
            parent=parent,
            type=kind,  # type: ignore[arg-type]
            source="auto",
            confidence=confidences.get(child, 0.9),
        )
        for child, parent, kind in supports
    ]
    return Scene(
        name="hand-made",
        image=ImageInfo(file="img.png", width=64, height=48),
        objects=objects,
        supports=relations,
    )


# What the pipeline "predicts" for every test scene unless a test says otherwise.
PREDICTED: list[Support] = [
    ("o0", "floor", "below"),
    ("o1", "o0", "below"),
    ("o2", "o0", "below"),
    ("o3", "floor", "below"),
]


def store_predicted_scene(
    scenes: SceneStore,
    name: str = "hand-made",
    confidences: dict[str, float | None] | None = None,
    supports: list[Support] | None = None,
    with_objects: bool = True,
) -> str:
    """Import a scene (state new) and store a pipeline result on it (state predicted), by
    the store's own code paths; `with_objects=False`: the pipeline found no objects."""
    photo = load_photo(_png(next(_photo_numbers)))
    imported = make_scene([]).model_copy(update={"name": name, "supports": []})
    scene_id = scenes.create(InputFiles(photo=photo, K=None, detections=None), imported, "test").id
    predicted = make_scene(supports if supports is not None else PREDICTED, confidences)
    if not with_objects:
        predicted = predicted.model_copy(update={"objects": [], "supports": []})
    scenes.commit_pipeline_result(scene_id, predicted.model_copy(update={"name": name}), None)
    return scene_id

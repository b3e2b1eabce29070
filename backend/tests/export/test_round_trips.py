"""Each export format that can be imported again gives back what was stored: a synthetic room
with masks, supports (some edited by a person) and ground truth is exported with `holiscene
export`, the export imported into a fresh store as `holiscene import` reads it, and the
classes, boxes (1 px), masks (IoU > 0.99), supports and ground truth compared."""

from __future__ import annotations

from contextlib import AbstractContextManager
from pathlib import Path

import numpy as np
import pytest
from holiscene.cli import main
from holiscene.cli.export import scene_store
from holiscene.core.settings import Settings
from holiscene.inputs import InputFiles, read_input_folder
from holiscene.inputs.datasets import dataset_items
from holiscene.segmentation.rle import decode_mask
from holiscene.services.workbench import imported_scene
from holiscene.store.scenes import SceneStore
from holiscene_schema import Scene, SupportRelation


def _edited_room(inputs: InputFiles) -> Scene:
    """The room's ground truth (camera, layout, 3D boxes, masks, supports), edited: a support
    changed and credited to a person, one removed (an object left unsupported), one left as
    the pipeline's guess, and an object's class set by hand."""
    assert inputs.ground_truth is not None
    scene = inputs.ground_truth.model_copy(deep=True)
    scene.name = "room"
    first = scene.supports[0]
    scene.supports[0] = SupportRelation(
        child=first.child, parent="floor", type="below", source="manual", author="ana"
    )
    del scene.supports[1]
    guess = scene.supports[1]
    scene.supports[1] = guess.model_copy(
        update={"source": "auto", "author": None, "time": None, "confidence": 0.7}
    )
    scene.objects[3].cls = "otherprop"
    return scene


def _supports_by_position(scene: Scene) -> set[tuple[int, int | str, str]]:
    position = {obj.id: i for i, obj in enumerate(scene.objects)}
    return {(position[s.child], position.get(s.parent, s.parent), s.type) for s in scene.supports}


def _store(data_dir: Path) -> AbstractContextManager[SceneStore]:
    data_dir.mkdir(parents=True, exist_ok=True)
    return scene_store(Settings(data_dir=data_dir))


def _imported(fmt: str, out: Path) -> InputFiles:
    """What `holiscene import` reads from the export."""
    if fmt == "coco":
        (item,) = dataset_items(out)
        assert item.inputs is not None, item.error
        return item.inputs
    (folder,) = out.iterdir()
    return read_input_folder(folder)


@pytest.mark.parametrize("fmt", ["coco", "scene", "total3d"])
def test_an_export_imports_back_to_the_same_labels(
    synthetic_folder: Path, tmp_path: Path, fmt: str
) -> None:
    inputs = read_input_folder(synthetic_folder)
    stored = _edited_room(inputs)
    with _store(tmp_path / "a") as scenes:
        scenes.create(inputs, stored, "import")
    out = tmp_path / "export"
    export = ["export", "--format", fmt, "-o", str(out), "--data-dir", str(tmp_path / "a")]
    assert main(export) == 0

    again = _imported(fmt, out)
    with _store(tmp_path / "b") as scenes:
        summary = scenes.create(again, imported_scene(again, "room"), "import")
        back = scenes.document(summary.id).scene

    assert [o.cls for o in back.objects] == [o.cls for o in stored.objects]
    width, height = stored.image.width, stored.image.height
    for obj, before in zip(back.objects, stored.objects, strict=True):
        assert np.allclose(obj.bbox, before.bbox, atol=1.0), (obj.bbox, before.bbox)
        assert obj.mask is not None and before.mask is not None
        mask, expected = (
            decode_mask(obj.mask, width, height),
            decode_mask(before.mask, width, height),
        )
        iou = (mask & expected).sum() / (mask | expected).sum()
        assert iou > 0.99, (before.id, iou)
    assert _supports_by_position(back) == _supports_by_position(stored)

    # Who set each support comes back: a person's name, and a guess stays a guess (an
    # unchecked guess imported as a person's label would train and count as one).
    def provenance(scene: Scene) -> set[tuple[str, str, str | None, float | None]]:
        return {
            (s.child, s.source, s.author, s.confidence if s.source == "auto" else None)
            for s in scene.supports
        }

    assert ("o2", "auto", None, 0.7) in provenance(stored)
    assert provenance(back) == provenance(stored)
    if fmt != "coco":  # the intrinsics go out as cam_K.txt, the ground truth as gt.json
        assert again.K is not None
        assert np.allclose(again.K, stored.camera.K, atol=1e-5)  # type: ignore[union-attr]
        assert again.ground_truth == inputs.ground_truth
    if fmt == "scene":  # scene.json beside the photo gives the room and camera back as stored
        assert stored.layout.corners_3d is not None
        assert back.layout == stored.layout and back.camera == stored.camera

"""`holiscene import` of COCO and LabelMe datasets and `holiscene export`: what goes out comes
back in (classes, boxes within 1 px, masks at IoU 0.99 or more), supports go out too, and bad
items are refused one by one with nothing of them stored."""

from __future__ import annotations

import json
import re
import zipfile
from pathlib import Path

import numpy as np
import pytest
from holiscene.cli import main
from holiscene.cli.export import scene_store
from holiscene.core.settings import Settings
from holiscene.segmentation.rle import decode_mask
from holiscene_schema import Scene, SceneObject

from ..inputs.datasets.files import coco_file, labelme_file, shape

ROUND_TRIP_SEED = 11


def _stored(data_dir: Path) -> list[Scene]:
    with scene_store(Settings(data_dir=data_dir)) as scenes:
        return [scenes.document(s.id).scene for s in scenes.list_summaries()]


def _iou(a: np.ndarray, b: np.ndarray) -> float:
    return float((a & b).sum()) / float((a | b).sum())


def _assert_same_objects(
    found: list[SceneObject], expected: list[SceneObject], scene: Scene
) -> None:
    width, height = scene.image.width, scene.image.height
    assert [o.cls for o in found] == [o.cls for o in expected]
    for obj, truth in zip(found, expected, strict=True):
        assert np.allclose(obj.bbox, truth.bbox, atol=1.0), (obj.bbox, truth.bbox)
        assert obj.mask is not None and truth.mask is not None
        assert obj.mask.source == "given"
        iou = _iou(decode_mask(obj.mask, width, height), decode_mask(truth.mask, width, height))
        assert iou >= 0.99, (obj.id, iou)


def _export(data_dir: Path, out: Path, fmt: str = "coco", *extra: str) -> int:
    return main(["export", "--format", fmt, "-o", str(out), "--data-dir", str(data_dir), *extra])


def test_a_synthetic_scene_round_trips_through_coco(tmp_path: Path) -> None:
    from holiscene.synth.generate import synthesize, write_scene

    synthetic = synthesize(ROUND_TRIP_SEED)
    folder = write_scene(synthetic, tmp_path / "synth")
    truth = synthetic.truth
    # The ground truth's outlines given with the boxes, as a labelled dataset gives them.
    (folder / "detections.json").write_text(
        json.dumps(
            [
                {"bbox": o.bbox, "class": o.cls, "mask": o.mask.model_dump(mode="json")}
                for o in truth.objects
                if o.mask is not None
            ]
        )
    )
    expected = [o for o in truth.objects if o.mask is not None]
    assert main(["import", str(folder), "--data-dir", str(tmp_path / "a")]) == 0
    (first,) = _stored(tmp_path / "a")
    _assert_same_objects(first.objects, expected, truth)  # the pipeline kept the given masks

    assert _export(tmp_path / "a", tmp_path / "coco") == 0
    coco = json.loads((tmp_path / "coco" / "annotations.json").read_text())
    assert [i["file_name"] for i in coco["images"]] == [f"{first.name}.png"]
    assert (tmp_path / "coco" / "images" / f"{first.name}.png").is_file()
    supports = {s.child: s for s in first.supports}
    assert supports
    for annotation in coco["annotations"]:
        support = supports[annotation["holiscene_id"]]
        written = annotation["holiscene_support"]
        assert (written["parent"], written["type"]) == (support.parent, support.type)
        # The pipeline's guesses go out as guesses, with their confidence.
        assert written.get("source") == ("auto" if support.source == "auto" else None)

    assert main(["import", str(tmp_path / "coco"), "--data-dir", str(tmp_path / "b")]) == 0
    (second,) = _stored(tmp_path / "b")
    assert second.name == first.name
    _assert_same_objects(second.objects, expected, truth)


def test_a_labelme_file_round_trips_through_coco(tmp_path: Path) -> None:
    path = labelme_file(
        tmp_path / "labelme" / "room.json",
        [
            shape("couch", [[5, 30], [60, 30], [60, 60], [5, 60]]),
            shape("lamp", [[70, 5], [90, 5], [85, 40], [72, 40]]),
            shape("teapot", [[30, 10], [45, 12], [40, 25]]),
        ],
    )
    assert main(["import", str(path), "--data-dir", str(tmp_path / "a")]) == 0
    (first,) = _stored(tmp_path / "a")
    assert [o.cls for o in first.objects] == ["sofa", "lamp", "otherprop"]
    assert [o.source_class for o in first.objects] == ["couch", "lamp", "teapot"]
    assert _export(tmp_path / "a", tmp_path / "coco") == 0
    assert main(["import", str(tmp_path / "coco"), "--data-dir", str(tmp_path / "b")]) == 0
    (second,) = _stored(tmp_path / "b")
    _assert_same_objects(second.objects, first.objects, first)


def test_bad_dataset_items_are_reported_and_the_rest_imported(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    coco = coco_file(
        tmp_path / "coco",
        [
            {"id": 1, "image_id": 1, "category_id": 1, "bbox": [5, 5, 30, 30]},
            {"id": 2, "image_id": 2, "category_id": 1, "segmentation": [[1, 1, 20, 20]]},
        ],
        images=("good.png", "two_points.png", "gone.png"),
        written=("good.png", "two_points.png"),
    )
    labelme = tmp_path / "labelme"
    labelme_file(labelme / "fine.json", [shape("bed", [[5, 5], [40, 5], [40, 40]])])
    (labelme / "broken.json").write_text("{")
    code = main(["import", str(coco.parent), str(labelme), "--data-dir", str(tmp_path / "data")])
    assert code == 1
    out, err = capsys.readouterr()
    assert "good.png: scene" in out and "fine.json: scene" in out
    assert "error: two_points.png: annotation 2: a polygon needs at least 3 points" in err
    assert "error: gone.png: the image file gone.png is missing" in err
    assert f"error: {labelme / 'broken.json'}: broken.json is not valid JSON" in err
    stored = _stored(tmp_path / "data")
    assert sorted(s.name for s in stored) == ["fine", "good"]
    scene_folders = [p for p in (tmp_path / "data").rglob("img.png")]
    assert len(scene_folders) == 2  # nothing of the refused photos was stored


def test_input_folders_still_import(tmp_path: Path, synthetic_folder: Path) -> None:
    assert main(["import", str(synthetic_folder), "--data-dir", str(tmp_path / "data")]) == 0
    (scene,) = _stored(tmp_path / "data")
    assert scene.name == synthetic_folder.name


def test_scene_export_writes_a_folder_per_scene(tmp_path: Path) -> None:
    path = labelme_file(tmp_path / "in" / "room.json", [shape("bed", [[5, 5], [40, 5], [40, 40]])])
    assert main(["import", str(path), "--data-dir", str(tmp_path / "data")]) == 0
    assert _export(tmp_path / "data", tmp_path / "out", "scene") == 0
    scene = Scene.model_validate_json((tmp_path / "out" / "room" / "scene.json").read_text())
    assert scene.name == "room" and [o.cls for o in scene.objects] == ["bed"]
    assert (tmp_path / "out" / "room" / scene.image.file).is_file()


def test_export_refusals_write_nothing(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = labelme_file(tmp_path / "in" / "room.json", [shape("bed", [[5, 5], [40, 5], [40, 40]])])
    assert main(["import", str(path), "--data-dir", str(tmp_path / "data")]) == 0
    capsys.readouterr()
    out = tmp_path / "out"
    assert _export(tmp_path / "data", out, "coco", "--scene", "nosuchscene") == 2
    assert "no scene 'nosuchscene'" in capsys.readouterr().err
    assert not out.exists()
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    assert _export(tmp_path / "data", out, "coco") == 2
    assert "not an empty folder; use --force" in capsys.readouterr().err
    assert sorted(p.name for p in out.iterdir()) == ["keep.txt"]
    assert _export(tmp_path / "data", out, "coco", "--force") == 0
    assert (out / "annotations.json").is_file() and (out / "keep.txt").is_file()


def test_total3d_training_export_says_what_it_wrote_and_what_it_left_out(
    tmp_path: Path, synthetic_folder: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    plain = labelme_file(tmp_path / "in" / "room.json", [shape("bed", [[5, 5], [40, 5], [40, 40]])])
    assert main(["import", str(plain), "--data-dir", str(tmp_path / "data")]) == 0
    capsys.readouterr()
    assert _export(tmp_path / "data", tmp_path / "none", "total3d-training") == 2
    assert "no scene can be a Total3D training sample" in capsys.readouterr().err
    assert not any((tmp_path / "none").iterdir())

    assert main(["import", str(synthetic_folder), "--data-dir", str(tmp_path / "data")]) == 0
    capsys.readouterr()
    assert _export(tmp_path / "data", tmp_path / "t3d", "total3d-training") == 0
    printed = capsys.readouterr().out
    # One sample, on the side the scene's (random) id hashes to.
    assert re.search(
        r"^(1 training and 0|0 training and 1) test sample\(s\); 1 scene\(s\) left out",
        printed,
        re.M,
    )
    index = json.loads((tmp_path / "t3d" / "holiscene-index.json").read_text())
    (sample,) = index["samples"]
    assert sample["name"] == synthetic_folder.name and sample["labels"] == "ground truth"
    assert (tmp_path / "t3d" / "sunrgbd_train_test_data" / "1.pkl").is_file()


def test_importing_twice_adds_nothing(
    tmp_path: Path, synthetic_folder: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The same files are recognised (an interrupted import resumes); changed labels are new
    files; --again imports anyway."""
    labelme = tmp_path / "labelme"
    labelme_file(labelme / "fine.json", [shape("bed", [[5, 5], [40, 5], [40, 40]])])
    data = ["--data-dir", str(tmp_path / "data")]
    assert main(["import", str(synthetic_folder), *data]) == 0
    capsys.readouterr()
    assert main(["import", str(synthetic_folder), str(labelme), *data]) == 0
    out = capsys.readouterr().out
    assert f"{synthetic_folder}: imported before as scene" in out and "skipped" in out
    assert "fine.json: scene" in out  # new files are imported beside the skipped ones
    assert len(_stored(tmp_path / "data")) == 2
    assert main(["import", str(synthetic_folder), str(labelme), *data]) == 0
    assert capsys.readouterr().out.count("skipped") == 2
    assert len(_stored(tmp_path / "data")) == 2
    # Other labels for the same photo are other files.
    labelme_file(labelme / "fine.json", [shape("lamp", [[5, 5], [40, 5], [40, 40]])])
    assert main(["import", str(labelme), *data]) == 0
    assert len(_stored(tmp_path / "data")) == 3
    assert main(["import", str(synthetic_folder), "--again", *data]) == 0
    assert len(_stored(tmp_path / "data")) == 4


def test_a_zip_of_exported_scenes_imports(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`holiscene import` takes a .zip (the app's "Download selected" archive is a zip of
    scene folders): named after the zip in what it prints, skipped the second time; a file
    that is no zip is an error and imports nothing."""
    path = labelme_file(tmp_path / "in" / "room.json", [shape("bed", [[5, 5], [40, 5], [40, 40]])])
    assert main(["import", str(path), "--data-dir", str(tmp_path / "a")]) == 0
    assert _export(tmp_path / "a", tmp_path / "out", "scene") == 0
    archive = tmp_path / "scenes.zip"
    with zipfile.ZipFile(archive, "w") as packed:
        for file in (tmp_path / "out").rglob("*"):
            packed.write(file, Path("scenes") / file.relative_to(tmp_path / "out"))
    data = ["--data-dir", str(tmp_path / "b"), "--no-pipeline"]
    capsys.readouterr()
    assert main(["import", str(archive), *data]) == 0
    out = capsys.readouterr().out
    assert str(archive) in out and "holiscene-import-" not in out
    [scene] = _stored(tmp_path / "b")
    assert scene.name == "room" and [o.cls for o in scene.objects] == ["bed"]
    assert main(["import", str(archive), *data]) == 0
    assert "skipped" in capsys.readouterr().out
    assert len(_stored(tmp_path / "b")) == 1

    broken = tmp_path / "broken.zip"
    broken.write_bytes(b"not a zip at all")
    assert main(["import", str(broken), *data]) == 1
    assert f"error: {broken}: the upload is not a .zip file" in capsys.readouterr().err
    assert len(_stored(tmp_path / "b")) == 1


def test_export_of_the_scenes_in_one_workflow_state(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from holiscene.editing.workflow_rules import Actor
    from holiscene.store.workflow import WorkflowStore

    data = tmp_path / "data"
    for name in ("kept", "draft"):
        room = labelme_file(
            tmp_path / "in" / f"{name}.json", [shape("bed", [[5, 5], [40, 5], [40, 40]])]
        )
        assert main(["import", str(room), "--data-dir", str(data)]) == 0
    assert _export(data, tmp_path / "none", "scene", "--state", "accepted") == 2
    assert "no scene is accepted" in capsys.readouterr().err
    assert not (tmp_path / "none").exists()

    with scene_store(Settings(data_dir=data)) as scenes:
        (kept,) = [s for s in scenes.list_summaries() if s.name == "kept"]
        workflow, person = WorkflowStore(scenes.engine, scenes), Actor("local", "admin", local=True)
        workflow.take(kept.id, person)
        workflow.submit(kept.id, kept.revision, person)
        workflow.accept(kept.id, kept.revision, person, None)
    assert _export(data, tmp_path / "out", "scene", "--state", "accepted") == 0
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["kept"]
    assert "exported 1 scene(s)" in capsys.readouterr().out

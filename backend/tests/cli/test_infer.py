"""`holiscene infer` on a real photo, and its refusals of bad input folders."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import cv2
import numpy as np
import pytest
import trimesh
from holiscene.cli import main
from holiscene_schema import STRUCTURAL_SUPPORTERS, Scene

from ..bad_inputs import BAD_DETECTIONS, NOT_AN_IMAGE, png_header_only, truncated


def test_infer_writes_scene_json_and_glb(t3d5: Path, tmp_path: Path) -> None:
    out = tmp_path / "out"
    completed = subprocess.run(
        [sys.executable, "-m", "holiscene.cli", "infer", str(t3d5), "-o", str(out)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert completed.returncode == 0, completed.stderr
    data = json.loads((out / "scene.json").read_text())
    Scene.model_validate(data)
    detections = json.loads((t3d5 / "detections.json").read_text())

    # objects[i] is detections[i]: same order, none dropped, NYU-40 classes.
    assert len(data["objects"]) == len(detections)
    for obj, det in zip(data["objects"], detections, strict=True):
        assert obj["bbox"] == [float(v) for v in det["bbox"]]
        assert obj["class"] == det["class"]  # t3d-5's names are NYU-40 already
        assert obj["corners_3d"] is None or len(obj["corners_3d"]) == 8

    ids = {o["id"] for o in data["objects"]}
    children = [s["child"] for s in data["supports"]]
    assert sorted(children) == sorted(ids), "one support per non-structural object"
    for support in data["supports"]:
        assert support["parent"] in ids | STRUCTURAL_SUPPORTERS
        assert support["type"] in ("below", "behind")

    camera = data["camera"]
    assert camera["K"] == [[529.5, 0.0, 365.0], [0.0, 529.5, 265.0], [0.0, 0.0, 1.0]]
    assert camera["pitch_deg"] is not None and -10 < camera["pitch_deg"] < 40
    assert camera["roll_deg"] is not None and abs(camera["roll_deg"]) < 15
    layout = data["layout"]
    assert layout["source"] == "estimated"
    assert len(layout["corners_2d"]) == 8 and len(layout["corners_3d"]) == 8
    floor_y = [c[1] for c in layout["corners_3d"][:4]]
    assert floor_y == pytest.approx([-camera["height_m"]] * 4, abs=1e-3)
    assert "scale from" in layout["note"]

    loaded = trimesh.load(out / "scene.glb", force="scene")
    placed = {o["id"] for o in data["objects"] if o["corners_3d"] is not None}
    assert placed, "floor-standing furniture gets 3D boxes"
    assert placed <= set(loaded.geometry)


def _input_folder(tmp_path: Path, source: Path) -> Path:
    folder = tmp_path / "input"
    shutil.copytree(source, folder)
    return folder


@pytest.mark.parametrize(
    ("image_name", "make_image", "message"),
    [
        ("img.jpg", lambda real: NOT_AN_IMAGE, "not a JPEG or PNG"),
        ("img.jpg", truncated, "cannot be decoded"),
        ("img.png", lambda real: png_header_only(20000, 20000), "too large"),
        ("img.png", lambda real: png_header_only(8000, 6000), "8000x6000"),
    ],
)
def test_infer_refuses_bad_photos(
    t3d5: Path,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    image_name,
    make_image,
    message,  # type: ignore[no-untyped-def]
) -> None:
    folder = _input_folder(tmp_path, t3d5)
    real = (folder / "img.jpg").read_bytes()
    (folder / "img.jpg").unlink()
    (folder / image_name).write_bytes(make_image(real))
    out = tmp_path / "out"
    assert main(["infer", str(folder), "-o", str(out)]) == 2
    assert message in capsys.readouterr().err
    assert not out.exists()


@pytest.mark.parametrize("case", sorted(BAD_DETECTIONS))
def test_infer_refuses_bad_detections(
    t3d5: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str], case: str
) -> None:
    folder = _input_folder(tmp_path, t3d5)
    data, message = BAD_DETECTIONS[case]
    (folder / "detections.json").write_bytes(data)
    out = tmp_path / "out"
    assert main(["infer", str(folder), "-o", str(out)]) == 2
    assert message in capsys.readouterr().err
    assert not out.exists()


def test_infer_refuses_unknown_stage(
    t3d5: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["infer", str(t3d5), "-o", str(tmp_path / "o"), "--stages", "intrinsics,nope"]) == 2
    assert "unknown stage 'nope'" in capsys.readouterr().err


def test_infer_on_a_plain_photo_makes_objects_with_the_detector(
    real_photos: Path, tmp_path: Path
) -> None:
    folder = _input_folder(tmp_path, real_photos / "mm3d-1")
    (folder / "detections.json").unlink()
    (folder / "cam_K.txt").unlink()
    out = tmp_path / "out"
    assert main(["infer", str(folder), "-o", str(out)]) == 0
    scene = Scene.model_validate_json((out / "scene.json").read_text())
    assert scene.objects, "the detector found nothing in a bedroom"
    assert all(o.source == "detector" and o.score is not None for o in scene.objects)
    assert all(o.mask is not None for o in scene.objects)
    assert scene.camera is not None and scene.camera.K_source == "assumed"
    assert (out / "scene.glb").is_file()


def test_infer_on_a_black_photo_gives_an_empty_flagged_scene(tmp_path: Path) -> None:
    folder = tmp_path / "black"
    folder.mkdir()
    cv2.imwrite(str(folder / "img.jpg"), np.zeros((240, 320, 3), np.uint8))
    assert main(["infer", str(folder), "-o", str(tmp_path / "out")]) == 0
    scene = Scene.model_validate_json((tmp_path / "out" / "scene.json").read_text())
    assert scene.objects == []
    runs = {s.name: s for s in scene.stages}
    assert runs["objects_from_detector"].warning
    assert "one flat colour" in (runs["objects_from_detector"].note or "")


def test_infer_refuses_a_strip_of_a_photo(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    folder = tmp_path / "strip"
    folder.mkdir()
    cv2.imwrite(str(folder / "img.png"), np.full((1, 4000, 3), 90, np.uint8))
    assert main(["infer", str(folder), "-o", str(tmp_path / "out")]) == 2
    assert "4000x1 pixels" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_infer_refuses_a_missing_models_folder(
    t3d5: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "out"
    assert main(["infer", str(t3d5), "-o", str(out), "--models", str(tmp_path / "none")]) == 2
    assert "does not exist" in capsys.readouterr().err
    assert not out.exists()


def test_train_rn_refuses_a_non_empty_output_and_bad_numbers(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "old").mkdir()
    (tmp_path / "old" / "model.onnx").write_bytes(b"x")
    assert main(["train-rn", "-o", str(tmp_path / "old")]) == 2
    assert "not empty" in capsys.readouterr().err
    assert main(["train-rn", "-o", str(tmp_path / "new"), "--max-epochs", "0"]) == 2
    assert "--max-epochs" in capsys.readouterr().err
    assert not (tmp_path / "new").exists()


def test_train_rn_with_nothing_to_learn_says_so(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "model"
    args = ["train-rn", "-o", str(out), "--synthetic-scenes", "0", "--with-store"]
    assert main([*args, "--data-dir", str(tmp_path / "data")]) == 2
    assert "no labelled objects" in capsys.readouterr().err
    assert not (out / "model.onnx").exists()


def test_train_rn_registers_a_candidate_model(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    pytest.importorskip("torch", reason="the train extra (PyTorch) is not installed")
    from holiscene.core.settings import Settings
    from holiscene.services.workbench import Workbench
    from holiscene.store.model_registry import active_model_dir

    data = tmp_path / "data"
    out = tmp_path / "model"
    args = ["train-rn", "-o", str(out), "--synthetic-scenes", "3", "--max-epochs", "1"]
    assert main([*args, "--register", "--data-dir", str(data)]) == 0
    assert "registered as model" in capsys.readouterr().out
    workbench = Workbench(Settings(data_dir=data))
    try:
        models = workbench.models.list_models()
        assert [m.status for m in models] == ["candidate", "default"]
        # Registered, not active: the seeded default model stays in use until an admin acts.
        assert active_model_dir(Settings(data_dir=data)) == workbench.models.folder(models[1].id)
    finally:
        workbench.close()


def test_infer_keeps_the_supports_given_in_supports_json(
    t3d5: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    folder = _input_folder(tmp_path, t3d5)
    given = [{"child": 0, "parent": "wall", "type": "behind", "author": "ana"}]
    (folder / "supports.json").write_text(json.dumps(given))
    out = tmp_path / "out"
    assert (
        main(
            [
                "infer",
                str(folder),
                "-o",
                str(out),
                "--stages",
                "objects_from_detector,intrinsics,masks_grabcut,supports_from_network",
            ]
        )
        == 0
    )
    scene = Scene.model_validate_json((out / "scene.json").read_text())
    kept = [s for s in scene.supports if s.child == "o0"]
    assert [(s.parent, s.type, s.source, s.author) for s in kept] == [
        ("wall", "behind", "manual", "ana")
    ]
    assert len(scene.supports) > 1  # the pipeline still gives the other objects theirs

    (folder / "supports.json").write_text(json.dumps([{"child": 0, "parent": 0, "type": "below"}]))
    assert main(["infer", str(folder), "-o", str(tmp_path / "again")]) == 2
    assert "supports.json: object 'o0' cannot support itself" in capsys.readouterr().err


def test_infer_keeps_a_room_layout_set_by_hand_in_scene_json(t3d5: Path, tmp_path: Path) -> None:
    """A folder exported from the app carries its scene.json: a room layout set by hand there
    (and the camera fitted to it) is kept, as a re-run in the app keeps it; an estimated one
    is estimated again."""
    folder = _input_folder(tmp_path, t3d5)
    assert main(["infer", str(folder), "-o", str(tmp_path / "first")]) == 0
    estimated = Scene.model_validate_json((tmp_path / "first" / "scene.json").read_text())
    assert estimated.layout.corners_3d is not None and estimated.camera is not None
    # The room as a person moved it: half a metre deeper, marked as set by hand.
    moved = [[x + 0.5, y, z] for x, y, z in estimated.layout.corners_3d]
    by_hand = estimated.model_copy(
        update={
            "layout": estimated.layout.model_copy(update={"corners_3d": moved, "source": "manual"})
        }
    )
    (folder / "scene.json").write_text(by_hand.model_dump_json(by_alias=True))
    assert main(["infer", str(folder), "-o", str(tmp_path / "kept")]) == 0
    kept = Scene.model_validate_json((tmp_path / "kept" / "scene.json").read_text())
    assert kept.layout.source == "manual" and kept.layout.corners_3d == moved
    assert kept.camera is not None
    assert (kept.camera.pitch_deg, kept.camera.roll_deg) == (
        estimated.camera.pitch_deg,
        estimated.camera.roll_deg,
    )
    names = [s.name for s in kept.stages]
    assert "layout_from_revision" in names and "layout_from_lines" not in names
    assert all(o.box_3d is not None for o in kept.objects if o.cls not in STRUCTURAL_SUPPORTERS)

    # The same room not marked as set by hand is the pipeline's to estimate again.
    estimated_again = by_hand.model_copy(
        update={"layout": by_hand.layout.model_copy(update={"source": "estimated"})}
    )
    (folder / "scene.json").write_text(estimated_again.model_dump_json(by_alias=True))
    assert main(["infer", str(folder), "-o", str(tmp_path / "again")]) == 0
    again = Scene.model_validate_json((tmp_path / "again" / "scene.json").read_text())
    assert "layout_from_lines" in [s.name for s in again.stages]
    assert again.layout.corners_3d != moved

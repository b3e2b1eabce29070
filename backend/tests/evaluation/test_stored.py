"""`holiscene eval --store`: stored synthetic rooms imported with their exact ground truth are
scored at their current revision (people's labels count) or with the pipeline run afresh
(people's labels ignored); scenes without ground truth are skipped, metrics a ground truth
lacks are left out, a broken gt.json is that scene's error. The folder form still works."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import pytest
from holiscene.cli import main
from holiscene.cli.export import scene_store
from holiscene.core.settings import Settings
from holiscene.inputs import read_input_folder
from holiscene.services.workbench import imported_scene
from holiscene.synth.generate import synthesize_to
from holiscene_schema import Layout, Scene, SupportRelation

SEEDS = (950000, 950001)


def _store(data_dir: Path, folder: Path, truth: Scene | None, wrong_labels: bool = False) -> str:
    """Import the folder's photo and boxes without running the pipeline: revision 1 holds the
    boxes and, as people's labels, the true supports (or every one wrong)."""
    supports = list(truth.supports) if truth is not None else []
    if wrong_labels:
        supports = [
            SupportRelation(child=s.child, parent="ceiling", type="behind", source="manual")
            for s in supports
        ]
    inputs = replace(read_input_folder(folder), supports=tuple(supports), ground_truth=truth)
    data_dir.mkdir(parents=True, exist_ok=True)
    with scene_store(Settings(data_dir=data_dir)) as scenes:
        return scenes.create(inputs, imported_scene(inputs, folder.name), "import").id


def _truth(folder: Path) -> Scene:
    return Scene.model_validate_json((folder / "gt.json").read_text())


@pytest.fixture(scope="module")
def rooms(tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    root = tmp_path_factory.mktemp("rooms")
    return [synthesize_to(seed, root) for seed in SEEDS]


def _eval(data_dir: Path, out: Path, *extra: str) -> int:
    return main(["eval", "--store", "--data-dir", str(data_dir), "--out", str(out), *extra])


def test_current_revisions_are_scored_and_scenes_without_truth_skipped(
    rooms: list[Path], tmp_path: Path
) -> None:
    data = tmp_path / "data"
    labelled = _store(data, rooms[0], _truth(rooms[0]))
    plain = _store(data, rooms[1], None)
    assert _eval(data, tmp_path / "out") == 0
    summary = json.loads((tmp_path / "out" / "eval.json").read_text())
    assert summary["scenes"] == 1
    assert [s["id"] for s in summary["store"]["scenes"]] == [labelled]
    assert [s["id"] for s in summary["store"]["skipped_without_ground_truth"]] == [plain]
    assert summary["store"]["scored"] == "current revision"
    # Revision 1 holds the true supports as people's labels, and nothing the pipeline
    # estimates: no camera pitch, no layout, no 3D boxes (each then counts as wrong).
    assert summary["support"]["accuracy"] == 1.0
    assert summary["camera"]["scenes_without_estimate"] == 1
    assert summary["layout"]["iou_3d"] == 0.0
    assert summary["detection_3d"]["recall"] == 0.0
    assert summary["scenes_scored"] == dict.fromkeys(
        ("support", "camera", "layout", "detection_3d", "mask"), 1
    )
    report = (tmp_path / "out" / "eval.md").read_text()
    assert f"Skipped, no ground truth: {plain} ({rooms[1].name})" in report


def test_the_rerun_ignores_peoples_labels(rooms: list[Path], tmp_path: Path) -> None:
    data = tmp_path / "data"
    scene_id = _store(data, rooms[0], _truth(rooms[0]), wrong_labels=True)
    assert _eval(data, tmp_path / "current") == 0
    current = json.loads((tmp_path / "current" / "eval.json").read_text())
    assert current["support"]["accuracy"] == 0.0

    assert _eval(data, tmp_path / "rerun", "--rerun", "--scene", scene_id) == 0
    rerun = json.loads((tmp_path / "rerun" / "eval.json").read_text())
    assert rerun["store"]["scored"] == "pipeline re-run"
    assert rerun["store"]["models"]["relation_network"] == "the committed model"
    assert rerun["support"]["accuracy"] > 0.5
    assert rerun["camera"]["pitch_mae_deg"] < 5.0
    assert rerun["layout"]["iou_3d"] > 0.2
    assert rerun["detection_3d"]["map"] > 0.2
    # The stored scene is as it was: a re-run for scoring stores nothing.
    with scene_store(Settings(data_dir=data)) as scenes:
        assert scenes.document(scene_id).revision == 1


def test_metrics_the_truth_lacks_are_left_out_not_zero(rooms: list[Path], tmp_path: Path) -> None:
    data = tmp_path / "data"
    full = _truth(rooms[0])
    # A dataset with supports but no 3D boxes, layout or camera tilt.
    bare = full.model_copy(
        update={
            "objects": [o.model_copy(update={"corners_3d": None}) for o in full.objects],
            "layout": Layout(),
            "camera": None,
        }
    )
    _store(data, rooms[0], bare)
    assert _eval(data, tmp_path / "out") == 0
    summary = json.loads((tmp_path / "out" / "eval.json").read_text())
    assert summary["scenes_scored"] == {
        "support": 1,
        "camera": 0,
        "layout": 0,
        "detection_3d": 0,
        "mask": 1,
    }
    assert summary["layout"]["iou_3d"] is None
    assert summary["camera"]["pitch_mae_deg"] is None
    assert summary["detection_3d"]["map"] is None
    assert summary["detection_3d"]["ap_per_class"] == {}
    assert summary["support"]["accuracy"] == 1.0
    assert "left out for that scene" in (tmp_path / "out" / "eval.md").read_text()


def test_a_broken_ground_truth_is_that_scenes_error(
    rooms: list[Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    data = tmp_path / "data"
    broken = _store(data, rooms[0], _truth(rooms[0]))
    good = _store(data, rooms[1], _truth(rooms[1]))
    (data / "scenes" / broken / "gt.json").write_text('{"name": "x"')
    assert _eval(data, tmp_path / "out") == 1
    assert f"error: {broken}: " in capsys.readouterr().err
    summary = json.loads((tmp_path / "out" / "eval.json").read_text())
    assert [s["id"] for s in summary["store"]["scenes"]] == [good]
    assert broken in summary["store"]["errors"]


def test_an_unknown_scene_stops_before_anything_is_written(
    rooms: list[Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    data = tmp_path / "data"
    _store(data, rooms[0], _truth(rooms[0]))
    assert _eval(data, tmp_path / "out", "--scene", "0123456789ab") == 2
    assert "0123456789ab" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()
    assert main(["eval", "--store", str(tmp_path), "--data-dir", str(data)]) == 2


def test_the_folder_form_scores_infer_output(rooms: list[Path], tmp_path: Path) -> None:
    room = rooms[0]
    predictions = tmp_path / "pred"
    assert main(["infer", str(room), "-o", str(predictions / room.name)]) == 0
    assert main(["eval", str(predictions), str(room.parent)]) == 0
    summary = json.loads((predictions / "eval.json").read_text())
    assert summary["scenes"] == len(SEEDS)  # the other room has no prediction: scored empty
    assert summary["missing_predictions"] == [rooms[1].name]
    assert summary["support"]["accuracy"] > 0.2


def test_the_rerun_scores_as_the_folder_form_scores_infer(
    rooms: list[Path], tmp_path: Path
) -> None:
    data = tmp_path / "data"
    for room in rooms:
        _store(data, room, _truth(room))
    assert _eval(data, tmp_path / "store", "--rerun") == 0
    from_store = json.loads((tmp_path / "store" / "eval.json").read_text())
    predictions = tmp_path / "pred"
    assert main(["infer", str(rooms[0].parent), "-o", str(predictions)]) == 0
    assert main(["eval", str(predictions), str(rooms[0].parent)]) == 0
    from_folders = json.loads((predictions / "eval.json").read_text())
    assert from_folders.pop("missing_predictions") == []
    assert from_store.pop("store")["scenes"][0]["name"] == rooms[0].name  # by name
    assert from_store == from_folders

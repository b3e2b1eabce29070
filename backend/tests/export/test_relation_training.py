"""`holiscene export --format relation-training`: the written set holds the supports people
set on the stored scenes, as the retraining's own samples, and says where each came from."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from holiscene.cli import main
from holiscene.cli.export import scene_store
from holiscene.core.settings import Settings
from holiscene.export.relation_training import FORMAT_FILE, LABELS_FILE, PAIRS_FILE
from holiscene.inputs import read_input_folder
from holiscene.services.relation_retraining import stored_samples
from holiscene.services.workbench import imported_scene
from holiscene.synth.generate import synthesize_to
from holiscene_schema import Scene, SupportRelation
from holiscene_schema.relation_model import STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER

SEEDS = (950010, 950011, 950012)


def _store(data_dir: Path, folder: Path, supports: list[SupportRelation]) -> str:
    inputs = replace(read_input_folder(folder), supports=tuple(supports))
    with scene_store(Settings(data_dir=data_dir)) as scenes:
        return scenes.create(inputs, imported_scene(inputs, folder.name), "import").id


def _export(data_dir: Path, out: Path) -> int:
    return main(
        ["export", "--format", "relation-training", "-o", str(out), "--data-dir", str(data_dir)]
    )


@pytest.fixture(scope="module")
def rooms(tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    root = tmp_path_factory.mktemp("rooms")
    return [synthesize_to(seed, root) for seed in SEEDS]


def test_the_set_holds_the_stored_supports_people_set(rooms: list[Path], tmp_path: Path) -> None:
    data = tmp_path / "data"
    data.mkdir()
    truths = [Scene.model_validate_json((room / "gt.json").read_text()) for room in rooms[:2]]
    # The first room fully labelled, the second with one label changed by hand.
    first = _store(data, rooms[0], list(truths[0].supports))
    changed = truths[1].supports[0].model_copy(update={"parent": "wall", "type": "behind"})
    second = _store(data, rooms[1], [changed, *truths[1].supports[1:]])
    unlabelled = _store(data, rooms[2], [])
    assert _export(data, tmp_path / "out") == 0

    expected = {(first, s.child, s.parent, s.type) for s in truths[0].supports}
    expected |= {(second, s.child, s.parent, s.type) for s in [changed, *truths[1].supports[1:]]}

    lines = (tmp_path / "out" / LABELS_FILE).read_text().splitlines()
    from_lines = {
        (r["scene_id"], r["child"], r["parent"], r["type"]) for r in map(json.loads, lines)
    }
    assert from_lines == expected

    described = json.loads((tmp_path / "out" / FORMAT_FILE).read_text())
    samples = described["samples"]
    # The store lists its newest scene first.
    assert [(s["scene_id"], s["revision"]) for s in samples] == [(second, 1), (first, 1)]
    assert [s["scene_id"] for s in described["left_out"]] == [unlabelled]
    assert described["left_out"][0]["why"] == "no supports set by a person"

    arrays = np.load(tmp_path / "out" / PAIRS_FILE)
    start = arrays["object_start"]
    from_pairs = set()
    for sample, index, column, kind in arrays["pairs"].tolist():
        ids = samples[sample]["object_ids"]
        parent = ids[column] if column < len(ids) else STRUCTURAL_COLUMNS[column - len(ids)]
        from_pairs.add((samples[sample]["scene_id"], ids[index], parent, SUPPORT_TYPE_ORDER[kind]))
        assert arrays["targets"][start[sample] + index] == column * 2 + kind
    assert from_pairs == expected
    assert int((arrays["targets"] >= 0).sum()) == len(expected)

    # The arrays are the retraining's own samples, in the same order.
    with scene_store(Settings(data_dir=data)) as scenes:
        retraining = stored_samples(scenes)
    assert [s.name for s in retraining] == [f"{second}@r1", f"{first}@r1"]
    for name in ("image", "masks", "boxes", "classes"):
        assert np.array_equal(arrays[name], np.concatenate([s.inputs[name] for s in retraining]))
    assert np.array_equal(arrays["targets"], np.concatenate([s.targets for s in retraining]))
    assert arrays["heldout"].tolist() == [s["heldout"] for s in samples]
    assert sum(arrays["heldout"].tolist()) == 1  # two scenes: one learnt from, one held out


def test_no_labelled_scene_is_refused_with_nothing_written(
    rooms: list[Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    data = tmp_path / "data"
    data.mkdir()
    _store(data, rooms[0], [])
    assert _export(data, tmp_path / "out") == 2
    assert "nothing to train on" in capsys.readouterr().err
    assert list((tmp_path / "out").iterdir()) == []

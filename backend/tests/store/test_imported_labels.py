"""Support labels and ground truth given with a photo (a dataset's) are stored with it: the
supports in revision 1 as people's labels, the ground truth as gt.json beside the scene."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from holiscene.core.settings import Settings
from holiscene.inputs import InputFiles, read_input_folder
from holiscene.services.workbench import Workbench, imported_scene
from holiscene.store.files import GROUND_TRUTH_FILE
from holiscene_schema import Scene, SupportRelation


def _labelled(folder: Path) -> tuple[InputFiles, InputFiles]:
    # The folder's gt.json is read as its ground truth; `plain` is the folder without it.
    plain = replace(read_input_folder(folder), ground_truth=None)
    truth = Scene.model_validate_json((folder / "gt.json").read_text())
    assert plain.detections is not None and len(plain.detections) >= 2
    supports = (
        SupportRelation(child="o1", parent="o0", type="below", source="manual", author="dataset"),
    )
    return plain, replace(plain, supports=supports, ground_truth=truth)


def test_supports_and_ground_truth_are_stored_and_change_the_digest(
    synthetic_folder: Path, settings: Settings
) -> None:
    plain, labelled = _labelled(synthetic_folder)
    assert plain.digest != labelled.digest

    revision_1 = imported_scene(labelled, "room")
    assert [(s.child, s.parent, s.source) for s in revision_1.supports] == [("o1", "o0", "manual")]

    workbench = Workbench(settings)
    try:
        summary = workbench.scenes.create(labelled, revision_1, "import")
        stored = workbench.scenes.document(summary.id).scene
        assert [(s.child, s.parent) for s in stored.supports] == [("o1", "o0")]
        truth_file = workbench.scenes.files.ground_truth_path(summary.id)
        assert truth_file.name == GROUND_TRUTH_FILE
        kept = Scene.model_validate_json(truth_file.read_text())
        assert kept == labelled.ground_truth

        without = workbench.scenes.create(plain, imported_scene(plain, "room"), "import")
        assert not workbench.scenes.files.ground_truth_path(without.id).exists()
    finally:
        workbench.close()

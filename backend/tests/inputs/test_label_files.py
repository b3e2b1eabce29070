"""supports.json and gt.json in an input folder: people's support labels over the boxes and a
dataset's ground truth, read with checks that name the file and the item."""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from typing import Any

import pytest
from holiscene.inputs import InputError, read_input_folder
from holiscene_schema import Layout, Scene


@pytest.fixture()
def folder(synthetic_folder: Path, tmp_path: Path) -> Path:
    """A writable copy of the synthetic room (img.png, cam_K.txt, detections.json, gt.json)."""
    return Path(shutil.copytree(synthetic_folder, tmp_path / "room"))


def _write_supports(folder: Path, items: Any) -> None:
    (folder / "supports.json").write_text(json.dumps(items))


def test_supports_become_people_labels_over_the_boxes_by_position(folder: Path) -> None:
    _write_supports(
        folder,
        [
            {"child": 1, "parent": 0, "type": "below", "author": "ana"},
            {"child": 2, "parent": "wall", "type": "behind"},
        ],
    )
    inputs = read_input_folder(folder)
    assert [(s.child, s.parent, s.type, s.source, s.author) for s in inputs.supports] == [
        ("o1", "o0", "below", "manual", "ana"),
        ("o2", "wall", "behind", "manual", "import"),
    ]


def test_a_pipeline_guess_stays_a_guess(folder: Path) -> None:
    """An export writes the pipeline's supports with source auto: they import as guesses."""
    _write_supports(
        folder,
        [
            {"child": 1, "parent": 0, "type": "below", "source": "auto", "confidence": 0.75},
            {"child": 2, "parent": "floor", "type": "below", "source": "auto"},
        ],
    )
    supports = read_input_folder(folder).supports
    assert [(s.child, s.source, s.confidence, s.author) for s in supports] == [
        ("o1", "auto", 0.75, None),
        ("o2", "auto", None, None),
    ]


def test_scene_json_gives_the_camera_and_the_room(folder: Path) -> None:
    truth = Scene.model_validate_json((folder / "gt.json").read_text())
    assert truth.layout.corners_3d is not None and truth.camera is not None
    (folder / "scene.json").write_text(truth.model_dump_json())
    inputs = read_input_folder(folder)
    assert inputs.layout == truth.layout and inputs.camera == truth.camera
    (folder / "scene.json").write_text(
        truth.model_copy(update={"layout": Layout()}).model_dump_json()
    )
    assert read_input_folder(folder).layout is None  # a scene without a room gives none
    (folder / "scene.json").write_text("{}")
    with pytest.raises(InputError, match=r"scene\.json is not a scene"):
        read_input_folder(folder)


def test_gt_json_is_the_ground_truth_scene(folder: Path) -> None:
    inputs = read_input_folder(folder)
    expected = Scene.model_validate_json((folder / "gt.json").read_text())
    assert inputs.ground_truth == expected
    assert inputs.supports == ()  # the ground truth's supports are for evaluation only
    (folder / "gt.json").unlink()
    assert read_input_folder(folder).ground_truth is None


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ("[{", "supports.json is not valid JSON"),
        ({"child": 1}, "must be a list"),
        ([{"child": 1, "parent": 0}], "item 0 must be an object with 'child', 'parent'"),
        ([{"child": 99, "parent": 0, "type": "below"}], "item 0: child 99 is not the number"),
        ([{"child": 1, "parent": -1, "type": "below"}], "parent -1 is not the number"),
        ([{"child": 1, "parent": "table", "type": "below"}], "nor floor, wall or ceiling"),
        ([{"child": 1, "parent": 0, "type": "on"}], "neither 'below' nor 'behind'"),
        ([{"child": True, "parent": 0, "type": "below"}], "child True"),
        ([{"child": 1, "parent": 0, "type": "below", "author": ""}], "'author'"),
        ([{"child": 1, "parent": 0, "type": "below", "source": "x"}], "neither 'manual' nor"),
        (
            [{"child": 1, "parent": 0, "type": "below", "source": "auto", "confidence": 2}],
            "'confidence' must be a number from 0 to 1",
        ),
        (
            [{"child": 1, "parent": "wall", "type": "behind", "source": "auto", "author": "adam"}],
            "source 'auto' (the pipeline's guess) with an author",
        ),
        (
            [
                {"child": 1, "parent": 2, "type": "below"},
                {"child": 2, "parent": 1, "type": "below"},
            ],
            "support cycle: o1 -> o2 -> o1",
        ),
        (
            [
                {"child": 1, "parent": 0, "type": "below"},
                {"child": 1, "parent": "floor", "type": "below"},
            ],
            "'o1' has more than one supporter",
        ),
        ([{"child": 3, "parent": 3, "type": "below"}], "cannot support itself"),
    ],
)
def test_bad_supports_are_refused_naming_the_file_and_item(
    folder: Path, content: Any, message: str
) -> None:
    if isinstance(content, str):
        (folder / "supports.json").write_text(content)
    else:
        _write_supports(folder, content)
    with pytest.raises(InputError, match=r"supports\.json") as refused:
        read_input_folder(folder)
    assert message in str(refused.value)


def test_supports_need_the_boxes_they_number(folder: Path) -> None:
    _write_supports(folder, [{"child": 1, "parent": 0, "type": "below"}])
    (folder / "detections.json").unlink()
    with pytest.raises(InputError, match=r"supports\.json needs detections\.json"):
        read_input_folder(folder)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda text: text[: len(text) // 2], "gt.json is not a scene"),
        (lambda text: "[]", "gt.json is not a scene"),
        (lambda text: text.replace('"width": 640', '"width": 320'), "a 320x480 photo"),
    ],
)
def test_a_bad_ground_truth_is_refused(folder: Path, change: Any, message: str) -> None:
    truth = folder / "gt.json"
    truth.write_text(change(truth.read_text()))
    with pytest.raises(InputError, match=message):
        read_input_folder(folder)

"""The learned layout and box stages (`layout_by_network`, `boxes_by_network`) in `holiscene
infer --stages`, on a synthetic room no network trained on, scored by `holiscene eval`; and a
broken model file refused with a clear error."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from holiscene.cli import main
from holiscene.learning.scene_net.runtime import SceneNetModelError, SceneNetwork
from holiscene.pipeline.runner import DEFAULT_STAGES
from holiscene_schema import Scene

SEED = 900_003  # held out: never a training room of any network
COUNT = 3
LEARNED = (
    "objects_from_detector,intrinsics,masks_grabcut,layout_by_network,supports_from_network,"
    "boxes_by_network,shapes_fit,scene_mesh"
)


@pytest.fixture(scope="module")
def rooms(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("synth")
    assert main(["synth", "--seed", str(SEED), "--count", str(COUNT), "-o", str(out)]) == 0
    return out


def test_the_learned_path_gives_a_camera_a_room_and_boxes(rooms: Path, tmp_path: Path) -> None:
    assert "layout_by_network" not in DEFAULT_STAGES and "boxes_by_network" not in DEFAULT_STAGES
    out = tmp_path / "pred"
    errors = []
    for room in sorted(rooms.iterdir()):
        target = out / room.name
        assert main(["infer", str(room), "-o", str(target), "--no-depth", "--stages", LEARNED]) == 0
        scene = Scene.model_validate_json((target / "scene.json").read_text())
        truth = Scene.model_validate_json((room / "gt.json").read_text())
        assert scene.camera is not None and scene.camera.pitch_deg is not None
        assert truth.camera is not None and truth.camera.pitch_deg is not None
        errors.append(abs(scene.camera.pitch_deg - truth.camera.pitch_deg))
        errors.append(abs((scene.camera.roll_deg or 0.0) - (truth.camera.roll_deg or 0.0)))
        assert scene.layout is not None and scene.layout.corners_3d is not None
        assert all(o.box_3d is not None for o in scene.objects)
        names = [s.name for s in scene.stages]
        assert "layout_by_network" in names and "placement" not in names
    # About 2 degrees each on 200 validation rooms; a photo alone can be 5 off.
    assert sum(errors) / len(errors) < 4.0

    assert main(["eval", str(out), str(rooms)]) == 0
    report = json.loads((out / "eval.json").read_text())
    assert report["layout"]["iou_3d"] > 0.3
    assert report["detection_3d"]["recall"] is not None


def test_a_broken_model_file_is_refused(tmp_path: Path) -> None:
    with pytest.raises(SceneNetModelError, match="no scene network"):
        SceneNetwork(tmp_path)
    (tmp_path / "model.onnx").write_bytes(b"not a model")
    with pytest.raises(SceneNetModelError, match="cannot load"):
        SceneNetwork(tmp_path)

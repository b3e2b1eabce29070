"""`holiscene train-3d`: one command for the three learned networks of thesis Ch. 5."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from holiscene.cli import main
from holiscene.cli.learned_3d import NETWORK_FOLDERS, plan_all


def test_all_scales_every_default_and_names_the_folders_as_the_committed_models(
    tmp_path: Path,
) -> None:
    scene, meshes, refiner = plan_all(tmp_path, None, 0.1, seed=3)
    assert scene.out == tmp_path / "scene_net_model" and scene.cache == tmp_path / "scene_net_cache"
    assert meshes.out == tmp_path / "mesh_net_model"
    assert refiner.out == tmp_path / "box_refiner_model"
    assert (scene.rooms, scene.validation_rooms, scene.time_budget) == (240, 20, 120.0)
    assert (meshes.views, meshes.validation_views, meshes.time_budget) == (1600, 40, 150.0)
    assert (refiner.rooms, refiner.epochs, refiner.members) == (1200, 3, 2)
    assert {scene.seed, meshes.seed, refiner.seed} == {3}
    # At full scale each run is its own command's default.
    full = plan_all(tmp_path, tmp_path / "cache", 1.0, seed=0)
    assert (full[0].rooms, full[0].cache, full[1].views, full[2].rooms) == (
        2400,
        tmp_path / "cache",
        16000,
        12000,
    )
    # The committed models live in the folders the runs are named after.
    learning = Path(__file__).parents[2] / "src" / "holiscene" / "learning"
    assert all((learning / folder / "model.onnx").is_file() for folder in NETWORK_FOLDERS.values())


@pytest.mark.parametrize("scale", ["0", "1.5", "-0.1"])
def test_a_scale_outside_zero_to_one_is_refused(
    scale: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["train-3d", "all", "-o", str(tmp_path / "out"), "--scale", scale]) == 2
    assert "--scale" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_a_zero_count_is_refused_before_any_work(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code = main(["train-3d", "meshes", "-o", str(tmp_path / "out"), "--views", "0"])
    assert code == 2 and "--views must be at least 1" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_all_trains_the_three_networks_into_models_the_run_time_reads(tmp_path: Path) -> None:
    pytest.importorskip("torch")
    from holiscene.learning.box_refiner.runtime import BoxRefiner
    from holiscene.learning.mesh_net.runtime import MeshGenerator
    from holiscene.learning.scene_net.runtime import SceneNetwork

    out = tmp_path / "models"
    assert main(["train-3d", "all", "-o", str(out), "--scale", "0.002"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert list(summary) == ["scene-net", "meshes", "box-refiner"]
    assert 0.0 <= summary["scene-net"]["metrics"]["layout_iou"] <= 1.0
    assert summary["meshes"]["metrics"]["onnx_max_abs_difference"] < 1e-4
    assert 0.0 <= summary["box-refiner"]["metrics"]["validation_mean_confidence"] <= 1.0
    for folder in NETWORK_FOLDERS.values():
        for name in ("model.onnx", "metadata.json", "metrics.json", "curve.png"):
            assert (out / folder / name).is_file(), (folder, name)
    SceneNetwork(out / "scene_net_model")
    MeshGenerator(out / "mesh_net_model")
    BoxRefiner(out / "box_refiner_model")

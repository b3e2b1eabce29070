"""The shape completion stage on a synthetic room with depth (`holiscene infer`), the scene's
mesh references and GLB, `holiscene eval --shapes`, and the single-photo path without it."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from holiscene.cli import main
from holiscene.viewer.meshes import glb_object_meshes
from holiscene_schema import Scene

SEED = 900_000  # held out: the completion benchmark's first room


@pytest.fixture(scope="module")
def rooms(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("synth")
    assert main(["synth", "--seed", str(SEED), "--count", "1", "-o", str(out)]) == 0
    return out


def _infer(room: Path, out: Path, *extra: str) -> Scene:
    assert main(["infer", str(room), "-o", str(out), *extra]) == 0
    return Scene.model_validate_json((out / "scene.json").read_text())


def test_objects_with_depth_get_completed_meshes_in_the_glb(rooms: Path, tmp_path: Path) -> None:
    room = rooms / f"synth-{SEED}"
    scene = _infer(room, tmp_path / "pred" / room.name)
    libraries = {o.id: o.mesh.library for o in scene.objects if o.mesh is not None}
    completed = [i for i, library in libraries.items() if library == "completion"]
    assert len(completed) >= len(scene.objects) / 2
    glb = glb_object_meshes((tmp_path / "pred" / room.name / "scene.glb").read_bytes())
    assert set(completed) <= set(glb)
    stage = next(s for s in scene.stages if s.name == "shape_completion")
    assert f"{len(completed)} of" in (stage.note or "") or stage.warning

    assert main(["eval", str(tmp_path / "pred"), str(rooms), "--shapes"]) == 0
    shapes = json.loads((tmp_path / "pred" / "eval.json").read_text())["shapes"]
    assert shapes["completion"]["count"] == len(completed)
    assert shapes["partial_points"]["count"] > 0
    assert 0.0 < shapes["completion"]["normal_consistency"] <= 1.0
    assert shapes["completion"]["chamfer"] < shapes["partial_points"]["chamfer"]


def test_without_depth_no_object_is_completed(rooms: Path, tmp_path: Path) -> None:
    room = rooms / f"synth-{SEED}"
    scene = _infer(room, tmp_path / "flat", "--no-depth")
    assert "shape_completion" not in {s.name for s in scene.stages}
    libraries = {o.mesh.library for o in scene.objects if o.mesh is not None}
    assert libraries and libraries <= {"builtin", "learned"}

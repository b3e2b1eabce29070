"""The mesh network's stage on a synthetic room without depth (`holiscene infer`): the learned
meshes in the scene's mesh references and GLB, scored by `holiscene eval --shapes`."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from holiscene.cli import main
from holiscene.learning.mesh_net.inputs import MESH_CLASSES
from holiscene.pipeline.runner import DEFAULT_STAGES, PLACEMENT_STAGES
from holiscene.viewer.meshes import glb_object_meshes, object_meshes
from holiscene_schema import Scene

SEED = 900_001  # held out: never a training room of any network


@pytest.fixture(scope="module")
def rooms(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("synth")
    assert main(["synth", "--seed", str(SEED), "--count", "1", "-o", str(out)]) == 0
    return out


def test_objects_of_known_classes_get_learned_meshes(rooms: Path, tmp_path: Path) -> None:
    room = rooms / f"synth-{SEED}"
    assert "shapes_by_mesh_net" in DEFAULT_STAGES and "shapes_by_mesh_net" in PLACEMENT_STAGES
    out = tmp_path / "pred" / room.name
    assert main(["infer", str(room), "-o", str(out), "--no-depth"]) == 0
    scene = Scene.model_validate_json((out / "scene.json").read_text())
    placed = [o for o in scene.objects if o.box_3d is not None and o.mask is not None]
    learned = [o.id for o in placed if o.mesh is not None and o.mesh.library == "learned"]
    known = [o.id for o in placed if o.cls in MESH_CLASSES]
    assert known and sorted(learned) == sorted(known)
    glb = (out / "scene.glb").read_bytes()
    assert set(learned) <= set(glb_object_meshes(glb))
    # The viewer takes the learned meshes from the GLB; they cannot be rebuilt from a reference.
    plan = object_meshes(scene, glb)
    assert set(learned) <= set(plan.meshes)
    stage = next(s for s in scene.stages if s.name == "shapes_by_mesh_net")
    assert f"{len(learned)} of" in (stage.note or "")

    assert main(["eval", str(tmp_path / "pred"), str(rooms), "--shapes"]) == 0
    shapes = json.loads((tmp_path / "pred" / "eval.json").read_text())["shapes"]
    assert shapes["learned"]["count"] == len(learned)
    assert shapes["learned, own box"]["chamfer"] < shapes["learned"]["chamfer"]


def test_the_library_fit_stays_without_the_stage(rooms: Path, tmp_path: Path) -> None:
    room = rooms / f"synth-{SEED}"
    stages = ",".join(s for s in DEFAULT_STAGES if s != "shapes_by_mesh_net")
    out = tmp_path / "library"
    assert main(["infer", str(room), "-o", str(out), "--no-depth", "--stages", stages]) == 0
    scene = Scene.model_validate_json((out / "scene.json").read_text())
    libraries = {o.mesh.library for o in scene.objects if o.mesh is not None}
    assert libraries == {"builtin"}

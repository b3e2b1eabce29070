"""The prediction of the synthetic room `synthetic_folder` (../conftest.py), and viewers."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path

import numpy as np
import pytest
import trimesh
import viser
from holiscene.export.glb import scene_glb
from holiscene.placement.shape_choice import placed as placed_mesh
from holiscene.shapes import generate_shape
from holiscene.viewer import SceneViewer, ViewerInput, start_viewer
from holiscene_schema import Box3D, Scene


@pytest.fixture(scope="package")
def predicted_folder(synthetic_folder: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """scene.json and scene.glb as `holiscene infer -o` writes them (the photo stays in the
    input folder), made from the truth so the test does not depend on the pipeline's
    accuracy: no MeshRefs, one object left without a 3D box, and each model fitted a
    quarter turn from its box's yaw (a turn the pipeline may choose and no MeshRef records),
    written by the GLB exporter the pipeline uses."""
    truth = Scene.model_validate_json((synthetic_folder / "gt.json").read_text())
    unplaced = next(o.id for o in truth.objects if o.cls not in ("picture", "door", "window"))
    objects = [
        o.model_copy(update={"mesh": None})
        if o.id != unplaced
        else o.model_copy(update={"mesh": None, "box_3d": None, "corners_3d": None})
        for o in truth.objects
    ]
    predicted = truth.model_copy(update={"objects": objects})
    placed: dict[str, tuple[str, Box3D]] = {}
    meshes: dict[str, trimesh.Trimesh] = {}
    for obj in objects:
        if obj.box_3d is None:
            continue
        box = obj.box_3d
        depth, height, width = box.size
        model = generate_shape(obj.cls, (width, height, depth), np.random.default_rng(1)).mesh
        meshes[obj.id] = placed_mesh(model, np.array(box.center), box.yaw_deg + 90.0)
        placed[obj.id] = (obj.cls, box)
    assert predicted.layout.corners_3d is not None
    glb = scene_glb(placed, None, meshes, np.array(predicted.layout.corners_3d))
    assert glb is not None
    out = tmp_path_factory.mktemp("pred")
    (out / "scene.json").write_text(predicted.model_dump_json(indent=1))
    (out / "scene.glb").write_bytes(glb)
    return out


@pytest.fixture()
def open_viewer() -> Iterator[Callable[[ViewerInput], SceneViewer]]:
    """Starts viewers on free ports of 127.0.0.1 and stops them after the test."""
    servers: list[viser.ViserServer] = []

    def start(data: ViewerInput) -> SceneViewer:
        server, viewer = start_viewer(data, port=0)
        servers.append(server)
        return viewer

    yield start
    for server in servers:
        server.stop()

"""User models: a folder per class, loaded into the canonical frame, fitted into boxes."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import trimesh
from holiscene.shapes import load_model_folder, shape_from_mesh


def _marked_box(extents: tuple[float, float, float], front_axis: int) -> trimesh.Trimesh:
    """A box off the origin with a small bump on its +`front_axis` face."""
    body = trimesh.creation.box(extents=extents)
    offset = np.zeros(3)
    offset[front_axis] = extents[front_axis] / 2 + 0.05
    bump = trimesh.creation.box(extents=(0.1, 0.1, 0.1))
    bump.apply_translation(offset)
    mesh = trimesh.util.concatenate([body, bump])
    mesh.apply_translation([5.0, 3.0, -2.0])
    return mesh


def _bump_in_front(mesh: trimesh.Trimesh) -> bool:
    """True when the frontmost (max x) vertices are the small bump's, not a whole face."""
    front = mesh.vertices[mesh.vertices[:, 0] > mesh.bounds[1, 0] - 1e-9]
    return bool(np.ptp(front[:, 2]) < 0.2 * mesh.extents[2])


@pytest.fixture()
def model_folder(tmp_path: Path) -> Path:
    root = tmp_path / "models"
    (root / "chair").mkdir(parents=True)
    (root / "Night Stand").mkdir()
    (root / "tv").mkdir()
    (root / ".cache").mkdir()  # hidden: ignored
    _marked_box((2.0, 1.0, 4.0), front_axis=0).export(root / "chair" / "b_chair.obj")
    trimesh.creation.box(extents=(1.0, 1.0, 1.0)).export(root / "chair" / "a_cube.OBJ")
    (root / "chair" / "b_chair.mtl").write_text("newmtl wood\n")  # beside an OBJ: ignored
    (root / "chair" / "notes.txt").write_text("not a model")
    trimesh.creation.cylinder(radius=0.2, height=0.5, sections=12).export(
        root / "Night Stand" / "n.ply"
    )
    scene = trimesh.Scene(
        [trimesh.creation.box(extents=(0.1, 0.6, 1.0)), trimesh.creation.icosphere()]
    )
    scene.export(root / "tv" / "screen.glb")
    (root / "README.md").write_text("a loose file at the top: ignored")
    return root


def test_models_are_grouped_by_normalised_class(model_folder: Path) -> None:
    models = load_model_folder(model_folder)
    assert sorted(models) == ["chair", "night_stand", "television"]
    assert len(models["chair"]) == 2
    assert len(models["night_stand"]) == 1 and len(models["television"]) == 1


def test_models_are_centred_with_unit_largest_side_and_kept_proportions(model_folder: Path) -> None:
    for meshes in load_model_folder(model_folder).values():
        for mesh in meshes:
            np.testing.assert_allclose(mesh.bounds.mean(axis=0), 0.0, atol=1e-9)
            assert mesh.extents.max() == pytest.approx(1.0)
    cube, chair = load_model_folder(model_folder)["chair"]  # sorted by file name
    np.testing.assert_allclose(cube.extents, [1.0, 1.0, 1.0])
    # 2 x 1 x 4 plus the 0.1 bump sticking out 0.05..0.15 in front of the +x face.
    np.testing.assert_allclose(chair.extents, np.array([2.1, 1.0, 4.0]) / 4.0, atol=1e-9)
    assert _bump_in_front(chair)


def test_a_front_along_z_is_turned_to_face_x(tmp_path: Path) -> None:
    (tmp_path / "sofa").mkdir()
    _marked_box((2.0, 1.0, 4.0), front_axis=2).export(tmp_path / "sofa" / "s.ply")
    (sofa,) = load_model_folder(tmp_path, front="+z")["sofa"]
    np.testing.assert_allclose(sofa.extents, np.array([4.1, 1.0, 2.0]) / 4.1, atol=1e-9)
    assert _bump_in_front(sofa)


def test_an_unknown_class_folder_is_an_error_naming_it(tmp_path: Path) -> None:
    (tmp_path / "chair").mkdir()
    (tmp_path / "spaceships").mkdir()
    with pytest.raises(ValueError, match="spaceships"):
        load_model_folder(tmp_path)


def test_a_missing_folder_is_an_error(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError):
        load_model_folder(tmp_path / "nowhere")


def test_a_model_becomes_a_shape_filling_any_box(model_folder: Path) -> None:
    (model,) = load_model_folder(model_folder)["night_stand"]
    shape = shape_from_mesh(model, (0.45, 0.6, 0.5))
    np.testing.assert_allclose(
        shape.mesh.bounds, [[-0.225, -0.3, -0.25], [0.225, 0.3, 0.25]], atol=1e-9
    )
    assert shape.parts == ["model"] and len(shape.face_part) == len(shape.mesh.faces)
    assert shape.support_surfaces == []
    np.testing.assert_allclose(model.extents.max(), 1.0)  # the library copy is untouched

"""Mesh primitives and the box fit: closed, outward, exactly where they were asked to be."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from holiscene.shapes import fit_to_box, primitives
from holiscene.shapes.builder import vary
from holiscene.shapes.fitting import BoxFit


def _assert_solid(mesh: trimesh.Trimesh) -> None:
    assert mesh.is_watertight
    assert mesh.is_winding_consistent
    assert mesh.volume > 0  # outward normals


def test_box_is_exactly_its_intervals() -> None:
    mesh = primitives.box((-1.0, 2.0), (0.5, 0.75), (3.0, 4.0))
    _assert_solid(mesh)
    np.testing.assert_allclose(mesh.bounds, [[-1.0, 0.5, 3.0], [2.0, 0.75, 4.0]])


@pytest.mark.parametrize("bad", [(1.0, 1.0), (2.0, 1.0)])
def test_empty_interval_is_refused(bad: tuple[float, float]) -> None:
    with pytest.raises(ValueError, match="interval"):
        primitives.box(bad, (0.0, 1.0), (0.0, 1.0))


def test_round_primitives_reach_their_radii() -> None:
    disc = primitives.disc((1.0, -1.0), (0.5, 0.25), (0.0, 0.1))
    _assert_solid(disc)
    np.testing.assert_allclose(disc.bounds, [[0.5, 0.0, -1.25], [1.5, 0.1, -0.75]], atol=1e-12)

    cone = primitives.frustum((0.0, 0.0), (0.4, 0.4), (0.0, 1.0), top_ratio=0.5)
    _assert_solid(cone)
    top = cone.vertices[np.isclose(cone.vertices[:, 1], 1.0)]
    assert np.abs(top[:, [0, 2]]).max() == pytest.approx(0.2)


def test_square_revolve_fills_a_rectangle() -> None:
    profile = [(0.0, 0.0), (0.8, 0.0), (1.0, 0.3), (0.9, 0.3), (0.6, 0.1), (0.0, 0.1)]
    basin = primitives.revolved(profile, (0.0, 0.0), (0.3, 0.2), square=True)
    _assert_solid(basin)
    np.testing.assert_allclose(basin.bounds, [[-0.3, 0.0, -0.2], [0.3, 0.3, 0.2]], atol=1e-12)
    assert len(basin.faces) < 60


def test_rod_tapered_box_band_and_cushion_are_solid() -> None:
    rod = primitives.rod((0, 0, 0), (0, 0, 1), 0.1)
    _assert_solid(rod)
    assert rod.extents[2] == pytest.approx(1.0)

    tapered = primitives.tapered_box(
        1, (0.0, 1.0), [(0.0, 1.0), (0.0, 1.0)], [(0.25, 0.75), (0.4, 0.6)]
    )
    _assert_solid(tapered)
    top = tapered.vertices[tapered.vertices[:, 1] == 1.0]
    np.testing.assert_allclose(top[:, 0].min(), 0.25)

    z = np.linspace(-1.0, 1.0, 50)
    band = primitives.band(np.column_stack([0.05 * np.sin(8 * z), z]), 0.01, (0.2, 2.0))
    _assert_solid(band)
    assert band.bounds[0, 1] == pytest.approx(0.2) and band.bounds[1, 1] == pytest.approx(2.0)

    cushion = primitives.superellipsoid((0.0, 0.5), (0.0, 0.15), (0.0, 0.7), 0.3, 0.5)
    _assert_solid(cushion)
    np.testing.assert_allclose(cushion.bounds, [[0.0, 0.0, 0.0], [0.5, 0.15, 0.7]], atol=1e-12)


def test_turned_to_x_points_the_axis_forward() -> None:
    mesh = primitives.turned_to_x(primitives.disc((0.0, 0.0), (0.5, 0.3), (0.0, 0.02)))
    np.testing.assert_allclose(mesh.extents, [0.02, 1.0, 0.6], atol=1e-12)


def test_vary_scales_its_range_to_the_cap() -> None:
    rng = np.random.default_rng(0)
    free = [vary(rng, 0.02, 0.04) for _ in range(200)]
    capped = [vary(rng, 0.02, 0.04, 0.01) for _ in range(200)]
    assert min(free) >= 0.02 and max(free) <= 0.04
    assert min(capped) >= 0.005 and max(capped) <= 0.01
    assert len(set(capped)) == 200  # still varies under the cap


def test_fit_to_box_maps_bounds_exactly_and_keeps_flat_axes_flat() -> None:
    mesh = trimesh.creation.icosphere(subdivisions=1)
    mesh.apply_translation([3.0, -2.0, 7.0])
    fitted = fit_to_box(mesh, (0.5, 1.0, 2.0))
    np.testing.assert_allclose(fitted.bounds, [[-0.25, -0.5, -1.0], [0.25, 0.5, 1.0]], atol=1e-12)
    assert np.allclose(mesh.bounds[0], [2.0, -3.0, 6.0], atol=0.2)  # the input is untouched

    quad = trimesh.Trimesh(
        vertices=[[1.0, 0, 0], [1.0, 1, 0], [1.0, 1, 1], [1.0, 0, 1]], faces=[[0, 1, 2], [0, 2, 3]]
    )
    flat = fit_to_box(quad, (0.1, 2.0, 3.0))
    np.testing.assert_allclose(flat.bounds, [[0.0, -1.0, -1.5], [0.0, 1.0, 1.5]], atol=1e-12)


@pytest.mark.parametrize("size", [(0.0, 1.0, 1.0), (1.0, -1.0, 1.0), (1.0, 1.0)])
def test_box_fit_refuses_bad_sizes(size: tuple[float, ...]) -> None:
    with pytest.raises(ValueError, match="positive"):
        BoxFit.between(np.array([[0.0, 0, 0], [1.0, 1, 1]]), size)

"""The room fit: the shared test vectors, project-then-fit round trips, the optimiser, errors."""

from __future__ import annotations

import json
import math
import re
from functools import cache
from typing import Any

import numpy as np
import pytest
from holiscene.geometry import room_fit
from holiscene.geometry.boxes import box_corners
from holiscene.geometry.room_fit import corner_coverage_problem, fit_room, project_room_corners
from holiscene.twin_vectors import room_fit as v
from holiscene_schema import BOX_CORNER_SIGNS
from hypothesis import assume, given, settings
from hypothesis import strategies as st

ANGLE_TOL_DEG = 1e-6
LENGTH_TOL_M = 1e-6


@cache
def vector_file() -> dict[str, Any]:
    data: dict[str, Any] = json.loads(v.ROOM_FIT_VECTORS.read_text())
    return data


def cases(*kinds: str) -> list[Any]:
    return [pytest.param(c, id=c["name"]) for c in vector_file()["cases"] if c["kind"] in kinds]


def assert_fit_matches(fit: room_fit.RoomFit, expected: dict[str, Any]) -> None:
    assert fit.converged
    assert fit.pitch_deg == pytest.approx(expected["pitch_deg"], abs=ANGLE_TOL_DEG)
    assert fit.roll_deg == pytest.approx(expected["roll_deg"], abs=ANGLE_TOL_DEG)
    assert fit.room.yaw_deg == pytest.approx(expected["room"]["yaw_deg"], abs=ANGLE_TOL_DEG)
    np.testing.assert_allclose(fit.room.center, expected["room"]["center"], atol=LENGTH_TOL_M)
    np.testing.assert_allclose(fit.room.size, expected["room"]["size"], atol=LENGTH_TOL_M)
    np.testing.assert_allclose(fit.corners_3d, expected["corners_3d"], atol=LENGTH_TOL_M)
    assert fit.rms_px == pytest.approx(expected["rms_px"], abs=1e-6)


def test_vector_file_follows_the_contract() -> None:
    data = vector_file()
    assert data["box_corner_signs"] == [list(s) for s in BOX_CORNER_SIGNS]
    kinds = [c["kind"] for c in data["cases"]]
    assert {k: kinds.count(k) for k in v.COUNTS} == v.COUNTS
    assert kinds.count("error") >= 6
    assert v.ROOM_FIT_VECTORS.stat().st_size < 200_000


@pytest.mark.parametrize("case", cases("exact", "unseen_wall"))
def test_exact_vectors_are_projections_of_their_truth(case: dict[str, Any]) -> None:
    truth, fit_input = case["expected"], case["input"]
    room = truth["room"]
    corners = box_corners(np.array(room["center"]), np.array(room["size"]), room["yaw_deg"])
    np.testing.assert_allclose(corners, truth["corners_3d"], atol=1e-12)
    projected = project_room_corners(fit_input["K"], truth["pitch_deg"], truth["roll_deg"], corners)
    assert [p is None for p in projected] == [c is None for c in fit_input["corners_2d"]]
    for got, stored in zip(projected, fit_input["corners_2d"], strict=True):
        if got is not None:
            np.testing.assert_allclose(got, stored, rtol=1e-12, atol=1e-9)


@pytest.mark.parametrize("case", cases("exact", "unseen_wall", "noisy"))
def test_fit_reproduces_the_vectors(case: dict[str, Any]) -> None:
    """Exact cases give back the truth; noisy ones the stored output of this implementation."""
    assert_fit_matches(fit_room(**case["input"]), case["expected"])


@pytest.mark.parametrize("case", cases("noisy"))
def test_noisy_fits_stay_near_the_truth(case: dict[str, Any]) -> None:
    fit, truth = fit_room(**case["input"]), case["truth"]
    assert fit.rms_px < 2.0 * case["noise_px"]
    assert fit.pitch_deg == pytest.approx(truth["pitch_deg"], abs=1.0)
    assert fit.roll_deg == pytest.approx(truth["roll_deg"], abs=1.0)


@pytest.mark.parametrize("case", cases("error"))
def test_fit_refuses_the_error_vectors(case: dict[str, Any]) -> None:
    with pytest.raises(ValueError, match=re.escape(case["expected"]["error"])):
        fit_room(**case["input"])


def _scenes() -> st.SearchStrategy[v.RoomScene]:
    def between(bounds: tuple[float, float]) -> st.SearchStrategy[float]:
        return st.floats(*bounds, allow_nan=False)

    offset = st.floats(-v.PRINCIPAL_OFFSET_PX, v.PRINCIPAL_OFFSET_PX)
    return st.builds(
        v.RoomScene,
        image_size=st.sampled_from(v.IMAGE_SIZES),
        hfov_deg=between(v.HFOV_DEG),
        principal_offset=st.tuples(offset, offset),
        aspect=between(v.ASPECT),
        size=st.tuples(between(v.ROOM_DEPTH_M), between(v.ROOM_HEIGHT_M), between(v.ROOM_WIDTH_M)),
        yaw_deg=between(v.ROOM_YAW_DEG),
        pitch_deg=between(v.PITCH_DEG),
        roll_deg=between(v.ROLL_DEG),
        camera_height=between(v.CAMERA_HEIGHT_M),
        back_distance=between(v.BACK_WALL_DISTANCE_M),
        # Drawn independently of the width, so kept inside the narrowest room.
        left_distance=between((v.SIDE_WALL_MARGIN_M, v.ROOM_WIDTH_M[0] - v.SIDE_WALL_MARGIN_M)),
    )


@settings(max_examples=150, deadline=None)
@given(scene=_scenes())
def test_project_then_fit_round_trip(scene: v.RoomScene) -> None:
    assume(scene.nearest_corner_depth() >= v.MIN_CORNER_DEPTH_M)
    fit_input = scene.fit_input()
    assume(
        corner_coverage_problem(
            fit_input["corners_2d"], unseen_wall_distance=fit_input["unseen_wall_distance"]
        )
        is None
    )
    fit = fit_room(**fit_input)
    assert_fit_matches(fit, scene.truth())
    again = project_room_corners(fit_input["K"], fit.pitch_deg, fit.roll_deg, fit.corners_3d)
    for got, given_corner in zip(again, fit_input["corners_2d"], strict=True):
        assert (got is None) == (given_corner is None)
        if got is not None:
            np.testing.assert_allclose(got, given_corner, rtol=1e-9, atol=1e-6)


def _exact_observations(seed: int) -> tuple[v.RoomScene, Any]:
    """A generated scene that the fit can take, and its checked observations."""
    rng = np.random.default_rng(seed)
    while True:
        scene = v.sample_scene(rng)
        fit_input = scene.fit_input()
        if scene.nearest_corner_depth() >= v.MIN_CORNER_DEPTH_M and not corner_coverage_problem(
            fit_input["corners_2d"], unseen_wall_distance=fit_input["unseen_wall_distance"]
        ):
            return scene, room_fit._observations(**fit_input)


def _true_params(scene: v.RoomScene) -> np.ndarray[Any, np.dtype[np.float64]]:
    cx, _, cz = scene.center()
    depth, height, width = scene.size
    angles = np.radians([scene.pitch_deg, scene.roll_deg, scene.yaw_deg])
    return np.array([*angles, cx, cz, depth, height, width])


@pytest.mark.parametrize("seed", range(12))
def test_optimiser_converges_from_a_perturbed_start(seed: int) -> None:
    """The closed-form start is exact on exact corners; start the optimiser elsewhere."""
    scene, observations = _exact_observations(seed)
    truth = _true_params(scene)
    rng = np.random.default_rng(1000 + seed)
    start = truth + rng.normal(0.0, [0.02, 0.02, 0.03, 0.1, 0.1, 0.1, 0.05, 0.1])
    params, residuals, _, converged = room_fit._levenberg_marquardt(observations, start)
    assert converged
    np.testing.assert_allclose(params, truth, atol=1e-8)
    assert np.abs(residuals).max() < 1e-6


@pytest.mark.parametrize("seed", range(6))
def test_jacobian_matches_finite_differences(seed: int) -> None:
    scene, observations = _exact_observations(seed)
    params = _true_params(scene) + np.random.default_rng(seed).normal(0.0, 0.05, 8)
    evaluated = room_fit._residuals_and_jacobian(params, observations)
    assert evaluated is not None
    step = 1e-6
    numeric = np.empty_like(evaluated[1])
    for j in range(8):
        delta = np.zeros(8)
        delta[j] = step
        plus = room_fit._residuals_and_jacobian(params + delta, observations)
        minus = room_fit._residuals_and_jacobian(params - delta, observations)
        assert plus is not None and minus is not None
        numeric[:, j] = (plus[0] - minus[0]) / (2 * step)
    scale = np.abs(numeric).max(axis=1, keepdims=True) + 1.0
    np.testing.assert_allclose(evaluated[1] / scale, numeric / scale, atol=1e-5)


def test_unseen_wall_prior_is_ignored_when_every_wall_is_seen() -> None:
    case = cases("exact")[0].values[0]
    fit = fit_room(**{**case["input"], "unseen_wall_distance": 100.0})
    assert_fit_matches(fit, case["expected"])


def test_corner_labels_fix_the_yaw() -> None:
    """Naming the room's corners from its side wall turns the yaw by 90 degrees (not folded
    into (-45, 45]) and swaps depth and width; the corners stay in the order given."""
    relabelled = 0
    for param in cases("exact"):
        case = param.values[0]
        room = case["expected"]["room"]
        depth, height, width = room["size"]
        yaw = room["yaw_deg"] + 90.0
        corners = box_corners(np.array(room["center"]), np.array([width, height, depth]), yaw)
        K, pitch, roll = (
            case["input"]["K"],
            case["expected"]["pitch_deg"],
            case["expected"]["roll_deg"],
        )
        corners_2d = project_room_corners(K, pitch, roll, corners)
        if corner_coverage_problem(corners_2d) is not None:
            continue
        fit = fit_room(K, corners_2d, case["input"]["camera_height"])
        assert fit.room.yaw_deg == pytest.approx(yaw if yaw <= 180 else yaw - 360, abs=1e-6)
        np.testing.assert_allclose(fit.room.size, [width, height, depth], atol=1e-6)
        np.testing.assert_allclose(fit.corners_3d, corners, atol=1e-6)
        relabelled += 1
    assert relabelled >= 3


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"K": [[500.0, 0.0], [0.0, 500.0]]}, "K must be a 3x3 matrix"),
        ({"K": [[500.0, 0.0, 320.0], [0.0, 500.0], [0.0, 0.0, 1.0]]}, "K must be a 3x3 matrix"),
        ({"K": [[math.nan, 0, 320], [0, 500, 240], [0, 0, 1]]}, "K must be a 3x3 matrix"),
        ({"camera_height": -1.4}, "camera_height must be a positive"),
        ({"camera_height": math.inf}, "camera_height must be a positive"),
        ({"unseen_wall_distance": -0.5}, "unseen_wall_distance must be a positive"),
    ],
)
def test_bad_arguments_are_refused(change: dict[str, Any], message: str) -> None:
    case = cases("exact")[0].values[0]
    with pytest.raises(ValueError, match=message):
        fit_room(**{**case["input"], **change})


def test_malformed_corner_is_refused() -> None:
    fit_input = cases("exact")[0].values[0]["input"]
    corners = list(fit_input["corners_2d"])
    known = next(i for i, c in enumerate(corners) if c is not None)
    for bad in ([math.nan, 10.0], [10.0, 20.0, 1.0], ["a", 3.0]):
        corners[known] = bad
        with pytest.raises(ValueError, match="two finite pixel coordinates"):
            fit_room(**{**fit_input, "corners_2d": corners})


def test_floor_and_ceiling_swapped_is_refused() -> None:
    fit_input = cases("exact")[0].values[0]["input"]
    swapped = [fit_input["corners_2d"][(i + 4) % 8] for i in range(8)]
    with pytest.raises(ValueError, match="is not below the horizon"):
        fit_room(**{**fit_input, "corners_2d": swapped})


# A room with one floor corner (1) in the photo (730 x 530) and the others extrapolated far
# outside it, as the layout stage stores such a room.
_ONE_IN_VIEW_K = [[632.2, 0.0, 365.0], [0.0, 632.2, 265.0], [0.0, 0.0, 1.0]]
_ONE_IN_VIEW: list[list[float] | None] = [
    [-1179.94, 1080.88],
    [219.33, 223.45],
    [962.6, 295.86],
    None,
    [-22135.56, -6569.82],
    [157.64, -172.67],
    [1205.78, -352.11],
    None,
]


def test_a_drag_the_closed_form_start_cannot_take_starts_from_the_room_shown() -> None:
    shown = fit_room(_ONE_IN_VIEW_K, _ONE_IN_VIEW, 1.77)
    assert shown.rms_px < 1.0
    dragged = [list(c) if c is not None else None for c in _ONE_IN_VIEW]
    dragged[1] = [199.33, 253.45]  # 20 px left, 30 px down
    with pytest.raises(ValueError, match="initial guess puts a known corner behind the camera"):
        fit_room(_ONE_IN_VIEW_K, dragged, 1.77)

    start = room_fit.RoomStart(
        shown.pitch_deg, shown.roll_deg, room_fit.room_box_of_corners(shown.corners_3d)
    )
    assert np.allclose(start.room.center, shown.room.center, atol=1e-9)
    assert np.allclose(start.room.size, shown.room.size, atol=1e-9)
    assert start.room.yaw_deg == pytest.approx(shown.room.yaw_deg, abs=1e-9)
    fit = fit_room(_ONE_IN_VIEW_K, dragged, 1.77, start=start)
    assert fit.converged
    assert fit.rms_px < 20.0  # the far corners hold the rest of the room in place
    assert np.all((fit.room.size > 0.5) & (fit.room.size < 10.0))
    # A start the corners can take themselves is unchanged by `start`.
    same = fit_room(_ONE_IN_VIEW_K, _ONE_IN_VIEW, 1.77, start=start)
    assert same.rms_px == pytest.approx(shown.rms_px) and same.trials == shown.trials

"""Room cuboid and camera pitch/roll from the room's layout corners in the image.

`fit_room(K, corners_2d, camera_height)` takes the 8 room corners in the image (the order of
BOX_CORNER_SIGNS, None for a corner behind the camera; corners outside the image are fine) and
finds 8 unknowns: the camera's pitch and roll, and the room box's yaw, centre x and z, and size
(depth along its own x, height, width along its own z). The floor is the plane
y = -camera_height, which fixes the scale and the centre's y. Every known corner is used.

What the corners must show: two vertical room edges with both corners known (i and i + 4), for
the vertical direction, and a known corner on three of the four vertical edges, for the walls.
With only two (adjacent) vertical edges seen, one wall has no known corner (typically the wall
behind the camera) and nothing in the image places it: pass `unseen_wall_distance`, its distance
from the camera (e.g. the current fit's, while an annotator drags the other corners); it is
ignored when every wall has a known corner.

Algorithm. frontend/src/geometry/roomFit.ts follows it step for step and both are checked
against shared_schema/vectors/room_fit.json: change them together and regenerate the vectors
(shared_schema/vectors/generate_room_fit.py).
1. Vertical direction: each vertical room edge with both corners known spans a plane through
   the camera centre, and the world's vertical lies in all of them: it is the sum of the cross
   products of every pair of plane normals, each turned to point up in the image. It gives
   pitch and roll.
2. Ceiling: on each such edge, the floor corner's ray meets the floor; the ceiling corner's ray
   passes above that point at the ceiling's height. Their mean is the ceiling.
3. Floor plan: each vertical edge's position comes from its floor corner on the floor, or else
   its ceiling corner on the ceiling. The yaw is the mean direction of the known plan edges,
   each wall's position the mean of its known plan corners along the room's axes (an unseen
   wall: `unseen_wall_distance` from the camera).
   When this start puts a known corner behind the camera (or the corners give no start at
   all), and the caller passes `start` (the room shown before the last corner moved, as an
   annotator drags), Levenberg-Marquardt starts from that room instead. With one corner in
   view, the rest extrapolated far outside the photo, a drag of a few tens of pixels could
   tip the closed-form start over while the room it leads to is fine.
4. Levenberg-Marquardt on the reprojection error of every known corner (plus, for an unseen
   wall, its distance from the camera against `unseen_wall_distance`, weighted by fx so it
   reads as pixels at 1 m; no corner depends on that wall, so the prior holds exactly):
   analytic Jacobian, Marquardt's scaling by diag(J^T J), damping from LAMBDA_INIT updated as
   Nielsen's (a step is taken when it lowers the error; lambda then shrinks by up to 3 as the
   gain ratio, actual over predicted decrease, nears 1; after a refused step lambda doubles,
   then quadruples, ...). It stops when a proposed step moves no parameter by more than
   STEP_TOLERANCE * (1 + max |parameter|), when lambda passes LAMBDA_MAX (no step helps any
   more), or after MAX_TRIALS proposed steps (then `converged` is False). Nielsen's update,
   rather than x10 / 10, matters for corners far outside the image (just in front of the
   camera plane), whose strongly curved residuals made the x10 schedule zigzag.

The yaw is not folded into (-45, 45]: the corner order already fixes the room's axes (local +x
runs from corner 0 to corner 1, +z from corner 0 to corner 3), so exactly one (centre, positive
size, yaw) has these corners, and relabelling to fold the yaw would break the contract that
corners_3d[i] is the corner that corners_2d[i] shows (the one an annotator drags). The yaw is
reported in (-180, 180]; layouts that call the wall the camera faces the front (+x), as the
synthetic scenes and the layout stage do, get a yaw in (-45, 45].
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from holiscene_schema import BOX_CORNER_SIGNS

from .boxes import box_corners
from .camera import FloatArray, PinholeCamera, pitch_roll_from_up_direction, rot_y

MIN_CORNERS = 4
MAX_TRIALS = 200
LAMBDA_INIT = 1e-3
LAMBDA_MAX = 1e10
STEP_TOLERANCE = 1e-10
# A known corner must stay this far in front of the camera (metres along the optical axis).
MIN_DEPTH = 1e-6
# Below this a cross product or a ray's vertical component counts as zero (unit vectors).
PARALLEL_TOLERANCE = 1e-9

_SIGNS = np.array(BOX_CORNER_SIGNS, dtype=float)
# The floor-plan edges between vertical edges (a, b): direction a -> b is the room's local +x
# (axis 0) or +z (axis 2).
_PLAN_EDGES = ((0, 1, 0), (3, 2, 0), (0, 3, 2), (1, 2, 2))
# Walls as (axis in the plan: 0 = local x, 1 = local z; side -1 or +1) and their vertical edges.
_WALLS = {(0, -1): (0, 3), (0, 1): (1, 2), (1, -1): (0, 1), (1, 1): (2, 3)}
# Parameter vector: pitch, roll, yaw (radians), centre x, centre z, depth, height, width.
_N_PARAMS = 8


@dataclass(frozen=True)
class RoomBox:
    center: FloatArray  # (3,) world, metres
    size: FloatArray  # (3,) depth (own x), height, width (own z)
    yaw_deg: float  # about world +y, in (-180, 180]


@dataclass(frozen=True)
class RoomStart:
    """A room to start from when the corners give no usable start (see step 3)."""

    pitch_deg: float
    roll_deg: float
    room: RoomBox


@dataclass(frozen=True)
class RoomFit:
    pitch_deg: float
    roll_deg: float
    room: RoomBox
    corners_3d: FloatArray  # (8, 3) world, in the order of corners_2d
    rms_px: float  # root mean square distance between known and fitted corners, pixels
    trials: int  # Levenberg-Marquardt steps proposed
    converged: bool


def corner_coverage_problem(
    corners_2d: Sequence[Sequence[float] | None], *, unseen_wall_distance: float | None = None
) -> str | None:
    """Why the known corners cannot determine the room, or None when they can."""
    if len(corners_2d) != 8:
        count = len(corners_2d)
        return f"expected 8 layout corners (null for a corner behind the camera), got {count}"
    known = [corner is not None for corner in corners_2d]
    if sum(known) < MIN_CORNERS:
        return f"fewer than {MIN_CORNERS} known corners ({sum(known)}): the room is not determined"
    if sum(known[i] and known[i + 4] for i in range(4)) < 2:
        return (
            "fewer than two vertical room edges with both corners known (corners i and i + 4): "
            "the vertical direction, hence pitch and roll, is not determined"
        )
    located = [known[i] or known[i + 4] for i in range(4)]
    if sum(located) >= 3:
        return None
    if located[0] == located[2]:
        return "only two opposite vertical room edges have known corners: the yaw is not determined"
    if unseen_wall_distance is None:
        return (
            "a wall has no known corner: its position is not determined "
            "(give unseen_wall_distance, its distance from the camera)"
        )
    return None


def fit_room(
    K: Sequence[Sequence[float]] | FloatArray,
    corners_2d: Sequence[Sequence[float] | None],
    camera_height: float,
    *,
    unseen_wall_distance: float | None = None,
    start: RoomStart | None = None,
) -> RoomFit:
    """Camera pitch/roll and room box from the layout corners; ValueError when not determined.
    `start`: the room to start from when the corners' own start fails (step 3)."""
    observations = _observations(K, corners_2d, camera_height, unseen_wall_distance)
    fallback = _params_of(start) if start is not None else None
    try:
        guess = _initial_guess(observations)
    except ValueError:
        if fallback is None:
            raise
        guess = fallback
    params, residuals, trials, converged = _levenberg_marquardt(observations, guess, fallback)
    if min(params[5], params[6], params[7]) <= 0.0:
        raise ValueError("the fit turned the room inside out: the corners are inconsistent")
    center, size, yaw_deg = _room_box(params, observations.camera_height)
    n = len(observations.pixels)
    corner_residuals = residuals[: 2 * n]
    return RoomFit(
        pitch_deg=math.degrees(params[0]),
        roll_deg=math.degrees(params[1]),
        room=RoomBox(center=center, size=size, yaw_deg=yaw_deg),
        corners_3d=box_corners(center, size, yaw_deg),
        rms_px=math.sqrt(float(corner_residuals @ corner_residuals) / n),
        trials=trials,
        converged=converged,
    )


def project_room_corners(
    K: Sequence[Sequence[float]] | FloatArray,
    pitch_deg: float,
    roll_deg: float,
    corners_3d: FloatArray,
) -> list[list[float] | None]:
    """The layout's corners_2d for world corners: pixels, None for a corner behind the camera."""
    pixels = PinholeCamera(np.asarray(K, dtype=float), pitch_deg, roll_deg).project(corners_3d)
    return [None if np.isnan(p).any() else [float(p[0]), float(p[1])] for p in pixels]


@dataclass(frozen=True)
class _Observations:
    K: FloatArray
    indices: list[int]  # which of the 8 corners are known
    pixels: FloatArray  # (n, 2) their image points
    camera_height: float
    unseen_wall: tuple[int, int] | None  # (plan axis, side) of the wall without known corners
    unseen_wall_distance: float


def _observations(
    K: Sequence[Sequence[float]] | FloatArray,
    corners_2d: Sequence[Sequence[float] | None],
    camera_height: float,
    unseen_wall_distance: float | None,
) -> _Observations:
    """Checked inputs, with the known corners gathered."""
    K_array = _finite_array(K, (3, 3), "K must be a 3x3 matrix of finite numbers")
    if abs(np.linalg.det(K_array)) < 1e-12:
        raise ValueError("K must be invertible")
    if not (math.isfinite(camera_height) and camera_height > 0.0):
        raise ValueError("camera_height must be a positive number of metres")
    if unseen_wall_distance is not None and not (
        math.isfinite(unseen_wall_distance) and unseen_wall_distance > 0.0
    ):
        raise ValueError("unseen_wall_distance must be a positive number of metres")
    problem = corner_coverage_problem(corners_2d, unseen_wall_distance=unseen_wall_distance)
    if problem is not None:
        raise ValueError(problem)
    indices = [i for i, corner in enumerate(corners_2d) if corner is not None]
    pixels = _finite_array(
        [corners_2d[i] for i in indices],
        (len(indices), 2),
        "each known corner must be two finite pixel coordinates",
    )
    unseen = [
        wall
        for wall, edges in _WALLS.items()
        if not any(i in indices or i + 4 in indices for i in edges)
    ]
    return _Observations(
        K=K_array,
        indices=indices,
        pixels=pixels,
        camera_height=camera_height,
        unseen_wall=unseen[0] if unseen else None,
        unseen_wall_distance=unseen_wall_distance or 0.0,
    )


def _finite_array(value: object, shape: tuple[int, ...], message: str) -> FloatArray:
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):  # ragged or not numbers
        raise ValueError(message) from None
    if array.shape != shape or not np.all(np.isfinite(array)):
        raise ValueError(message)
    return array


def _unit(vector: FloatArray, what: str) -> FloatArray:
    norm = float(np.linalg.norm(vector))
    if norm < PARALLEL_TOLERANCE:
        raise ValueError(f"degenerate layout: {what}")
    result: FloatArray = vector / norm
    return result


def _initial_guess(observations: _Observations) -> FloatArray:
    """Closed-form start for the optimiser (steps 1-3 of the module docstring)."""
    h = observations.camera_height
    rays_cv = np.hstack([observations.pixels, np.ones((len(observations.pixels), 1))])
    rays_cv = rays_cv @ np.linalg.inv(observations.K).T
    ray_cv = dict(zip(observations.indices, rays_cv, strict=True))
    edges = [i for i in range(4) if i in ray_cv and i + 4 in ray_cv]

    # 1. Vertical direction (in OpenCV camera coordinates) -> pitch, roll.
    normals = [
        _unit(np.cross(ray_cv[i], ray_cv[i + 4]), f"corners {i} and {i + 4} coincide")
        for i in edges
    ]
    vertical = np.zeros(3)
    for a in range(len(normals)):
        for b in range(a + 1, len(normals)):
            meet = np.cross(normals[a], normals[b])
            vertical += -meet if meet[1] > 0 else meet  # up in the image: negative OpenCV y
    vertical = _unit(vertical, "the vertical room edges lie on one line in the image")
    pitch_deg, roll_deg = pitch_roll_from_up_direction(vertical)
    world_from_cv = PinholeCamera(observations.K, pitch_deg, roll_deg).world_from_cv
    ray = {i: world_from_cv @ r for i, r in ray_cv.items()}

    def on_plane(i: int, y: float) -> FloatArray:
        """Where corner i's ray meets the horizontal plane at height y."""
        if ray[i][1] * y <= PARALLEL_TOLERANCE * abs(y):
            side = "below" if y < 0 else "above"
            raise ValueError(f"corner {i} is not {side} the horizon: check the corner order")
        result: FloatArray = ray[i] * (y / ray[i][1])
        return result

    # 2. Ceiling height: the point of each ceiling ray above its floor corner.
    ceiling_heights = []
    for i in edges:
        floor_point, up_ray = on_plane(i, -h), ray[i + 4]
        t = (up_ray[0] * floor_point[0] + up_ray[2] * floor_point[2]) / (
            up_ray[0] ** 2 + up_ray[2] ** 2
        )
        ceiling_heights.append(t * up_ray[1])
    ceiling = float(np.mean(ceiling_heights))
    if ceiling + h <= 0.0:
        raise ValueError("the ceiling corners lie below the floor: check the corner order")

    # 3. Floor plan: (x, z) of each vertical edge from its floor corner, else its ceiling corner.
    plan: dict[int, FloatArray] = {}
    for i in range(4):
        if i in ray:
            plan[i] = on_plane(i, -h)[[0, 2]]
        elif i + 4 in ray:
            plan[i] = on_plane(i + 4, ceiling)[[0, 2]]
    # Each plan edge, turned to local +x, votes (cos yaw, sin yaw) weighted by its length:
    # local +x is world (cos yaw, -sin yaw) and local +z is (sin yaw, cos yaw) in (x, z).
    heading = np.zeros(2)
    for a, b, axis in _PLAN_EDGES:
        if a in plan and b in plan:
            dx, dz = plan[b] - plan[a]
            heading += (dx, -dz) if axis == 0 else (dz, dx)
    heading = _unit(heading, "the room's corners coincide on the floor plan")
    yaw = math.atan2(heading[1], heading[0])
    cos_yaw, sin_yaw = math.cos(yaw), math.sin(yaw)
    local = {
        i: (p[0] * cos_yaw - p[1] * sin_yaw, p[0] * sin_yaw + p[1] * cos_yaw)
        for i, p in plan.items()
    }

    def wall(axis: int, side: int) -> float:
        """The wall's local coordinate: mean of its known plan corners, or the prior."""
        on_wall = [local[i][axis] for i in _WALLS[axis, side] if i in local]
        if not on_wall:
            return side * observations.unseen_wall_distance
        return float(np.mean(on_wall))

    x_lo, x_hi, z_lo, z_hi = wall(0, -1), wall(0, 1), wall(1, -1), wall(1, 1)
    depth, width, height = x_hi - x_lo, z_hi - z_lo, ceiling + h
    if depth <= 0.0 or width <= 0.0:
        raise ValueError(
            "the room comes out inside out: the corners are not in the order of BOX_CORNER_SIGNS"
        )
    mid_x, mid_z = (x_lo + x_hi) / 2, (z_lo + z_hi) / 2
    return np.array(
        [
            math.radians(pitch_deg),
            math.radians(roll_deg),
            yaw,
            mid_x * cos_yaw + mid_z * sin_yaw,
            -mid_x * sin_yaw + mid_z * cos_yaw,
            depth,
            height,
            width,
        ]
    )


def _params_of(start: RoomStart) -> FloatArray:
    """The parameter vector of a room (its centre's height is the floor's, not a parameter)."""
    room = start.room
    return np.array(
        [
            math.radians(start.pitch_deg),
            math.radians(start.roll_deg),
            math.radians(room.yaw_deg),
            room.center[0],
            room.center[2],
            room.size[0],
            room.size[1],
            room.size[2],
        ]
    )


def room_box_of_corners(corners_3d: Sequence[Sequence[float]] | FloatArray) -> RoomBox:
    """The box whose corners (in the order of BOX_CORNER_SIGNS) these are."""
    corners = np.asarray(corners_3d, dtype=float)
    x_axis, z_axis = corners[1] - corners[0], corners[3] - corners[0]
    height = corners[4:, 1].mean() - corners[:4, 1].mean()
    return RoomBox(
        center=corners.mean(axis=0),
        size=np.array([np.linalg.norm(x_axis), height, np.linalg.norm(z_axis)]),
        yaw_deg=math.degrees(math.atan2(-x_axis[2], x_axis[0])),
    )


def _room_box(params: FloatArray, camera_height: float) -> tuple[FloatArray, FloatArray, float]:
    """(centre, size, yaw in degrees within (-180, 180]) of a parameter vector."""
    _, _, yaw, cx, cz, depth, height, width = (float(p) for p in params)
    yaw_deg = math.degrees(yaw)
    yaw_deg -= 360.0 * math.ceil((yaw_deg - 180.0) / 360.0)  # into (-180, 180]
    center = np.array([cx, height / 2 - camera_height, cz])
    return center, np.array([depth, height, width]), yaw_deg


def _residuals_and_jacobian(
    params: FloatArray, observations: _Observations
) -> tuple[FloatArray, FloatArray] | None:
    """Residuals (2n corner coordinates, then the unseen wall's if any) and their Jacobian
    (rows, 8); None if a known corner is behind the camera."""
    pitch, roll, yaw, cx, cz, depth, height, width = (float(p) for p in params)
    signs = _SIGNS[observations.indices]
    half = signs * np.array([depth, height, width]) / 2  # corners in the room's frame
    rotation = rot_y(yaw)
    center = np.array([cx, height / 2 - observations.camera_height, cz])
    world = half @ rotation.T + center
    cam_from_world = PinholeCamera(
        observations.K, math.degrees(pitch), math.degrees(roll)
    ).world_from_cv.T
    cam = world @ cam_from_world.T
    if np.any(cam[:, 2] <= MIN_DEPTH):
        return None
    K = observations.K
    homogeneous = cam @ K.T
    pixels = homogeneous[:, :2] / homogeneous[:, 2:]
    residuals = (pixels - observations.pixels).ravel()

    # d(camera point)/d(parameter), (n, 3, 8). Pitch turns the world point about world z
    # before the camera rotation; roll turns the camera point about the optical axis.
    n = len(cam)
    d_cam = np.zeros((n, 3, _N_PARAMS))
    turned = np.stack([-world[:, 1], world[:, 0], np.zeros(n)], axis=1)
    d_cam[:, :, 0] = turned @ cam_from_world.T
    d_cam[:, 0, 1], d_cam[:, 1, 1] = cam[:, 1], -cam[:, 0]
    cos_yaw, sin_yaw = math.cos(yaw), math.sin(yaw)
    d_rotation = np.array([[-sin_yaw, 0.0, cos_yaw], [0.0, 0.0, 0.0], [-cos_yaw, 0.0, -sin_yaw]])
    d_world = np.zeros((n, 3, 6))  # yaw, centre x, centre z, depth, height, width
    d_world[:, :, 0] = half @ d_rotation.T
    d_world[:, 0, 1] = 1.0
    d_world[:, 2, 2] = 1.0
    d_world[:, :, 3] = signs[:, 0:1] / 2 * rotation[:, 0]
    d_world[:, 1, 4] = (1 + signs[:, 1]) / 2
    d_world[:, :, 5] = signs[:, 2:3] / 2 * rotation[:, 2]
    d_cam[:, :, 2:] = np.einsum("ij,njk->nik", cam_from_world, d_world)
    # d(pixel)/d(camera point), (n, 2, 3): (row of K - pixel * last row of K) / w.
    d_pixel = (K[None, :2, :] - pixels[:, :, None] * K[None, 2:, :]) / homogeneous[:, 2, None, None]
    jacobian = np.einsum("nij,njk->nik", d_pixel, d_cam).reshape(-1, _N_PARAMS)
    if observations.unseen_wall is None:
        return residuals, jacobian

    # The unseen wall's local coordinate (the centre's along the wall's axis, plus or minus
    # half the size) against side * unseen_wall_distance, weighted by fx.
    axis, side = observations.unseen_wall
    weight = K[0, 0]
    wall_row = np.zeros(_N_PARAMS)
    if axis == 0:  # local x = x cos(yaw) - z sin(yaw)
        middle = cx * cos_yaw - cz * sin_yaw
        wall_row[2:6] = (-cx * sin_yaw - cz * cos_yaw, cos_yaw, -sin_yaw, side / 2)
        position = middle + side * depth / 2
    else:  # local z = x sin(yaw) + z cos(yaw)
        middle = cx * sin_yaw + cz * cos_yaw
        wall_row[2:5] = (cx * cos_yaw - cz * sin_yaw, sin_yaw, cos_yaw)
        wall_row[7] = side / 2
        position = middle + side * width / 2
    wall_residual = weight * (position - side * observations.unseen_wall_distance)
    return np.append(residuals, wall_residual), np.vstack([jacobian, weight * wall_row])


def _levenberg_marquardt(
    observations: _Observations, params: FloatArray, fallback: FloatArray | None = None
) -> tuple[FloatArray, FloatArray, int, bool]:
    """Minimise the squared residuals from params (from `fallback` when params put a known
    corner behind the camera): (params, residuals, trials, converged)."""
    evaluated = _residuals_and_jacobian(params, observations)
    if evaluated is None and fallback is not None:
        params = fallback
        evaluated = _residuals_and_jacobian(params, observations)
    if evaluated is None:
        raise ValueError("the initial guess puts a known corner behind the camera")
    residuals, jacobian = evaluated
    cost = float(residuals @ residuals)
    normal, gradient = jacobian.T @ jacobian, jacobian.T @ residuals
    damping, growth = LAMBDA_INIT, 2.0
    for trial in range(1, MAX_TRIALS + 1):
        scale = np.diag(normal)
        scale = np.maximum(scale, 1e-12 * scale.max())  # keeps the damped system regular
        try:
            step = np.linalg.solve(normal + damping * np.diag(scale), -gradient)
        except np.linalg.LinAlgError:
            step = None
        if step is not None:
            if np.max(np.abs(step)) <= STEP_TOLERANCE * (1.0 + np.max(np.abs(params))):
                return params, residuals, trial, True
            evaluated = _residuals_and_jacobian(params + step, observations)
            if evaluated is not None:
                new_cost = float(evaluated[0] @ evaluated[0])
                # Gain ratio: the actual decrease over the one the linear model predicts.
                gain = (cost - new_cost) / float(step @ (damping * scale * step - gradient))
                if gain > 0.0:
                    params, (residuals, jacobian), cost = params + step, evaluated, new_cost
                    normal, gradient = jacobian.T @ jacobian, jacobian.T @ residuals
                    damping *= max(1.0 / 3.0, 1.0 - (2.0 * gain - 1.0) ** 3)
                    growth = 2.0
                    continue
        damping *= growth
        growth *= 2.0
        if damping > LAMBDA_MAX:  # no step lowers the error any more: a minimum
            return params, residuals, trial, True
    return params, residuals, MAX_TRIALS, False

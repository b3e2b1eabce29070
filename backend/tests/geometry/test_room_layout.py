"""Vanishing points, camera and room layout from the lines of synthetic renders."""

from __future__ import annotations

import math
from functools import cache

import numpy as np
import pytest
from holiscene.evaluation.box_iou import iou_3d
from holiscene.geometry.camera import PinholeCamera, rot_y
from holiscene.geometry.lines import detect_segments
from holiscene.geometry.manhattan import estimate_manhattan_frame
from holiscene.geometry.room_layout import (
    RoomHypothesis,
    SurfaceEvidence,
    estimate_room,
    room_to_world,
)
from holiscene.geometry.room_width import unseen_side_wall_distance
from holiscene.geometry.surface_labels import SURFACES, map_pixels
from holiscene.geometry.surface_map import SurfaceMap, load_surface_model
from holiscene.pipeline import SceneContext, build_pipeline
from holiscene.pipeline.base import Detection
from holiscene.pipeline.stages.layout import mounted_heights, unseen_parts_from_priors
from holiscene.synth.generate import SyntheticScene, synthesize

SEEDS = range(4100, 4108)


@cache
def scene(seed: int) -> SyntheticScene:
    return synthesize(seed)


def _true_room_yaw(synthetic: SyntheticScene) -> float:
    corners = np.array(synthetic.truth.layout.corners_3d)
    edge = corners[1] - corners[0]  # along the room's own x axis
    yaw = math.degrees(math.atan2(-edge[2], edge[0]))
    return (yaw + 45.0) % 90.0 - 45.0


def _angle_deg(a: np.ndarray, b: np.ndarray) -> float:
    cos = abs(float(a @ b)) / (np.linalg.norm(a) * np.linalg.norm(b))
    return math.degrees(math.acos(min(1.0, cos)))


@pytest.mark.parametrize("seed", SEEDS)
def test_vanishing_points_within_a_degree(seed: int) -> None:
    synthetic = scene(seed)
    truth = synthetic.truth
    assert truth.camera is not None
    frame = estimate_manhattan_frame(detect_segments(synthetic.frame.rgb), synthetic.K)
    assert frame is not None
    # Compare the directions the vanishing points stand for, in the camera frame.
    true_camera = PinholeCamera(
        synthetic.K, truth.camera.pitch_deg or 0.0, truth.camera.roll_deg or 0.0
    )
    est_camera = PinholeCamera(synthetic.K, frame.pitch_deg, frame.roll_deg)
    up_true = true_camera.world_from_cv.T @ np.array([0.0, 1.0, 0.0])
    up_est = est_camera.world_from_cv.T @ np.array([0.0, 1.0, 0.0])
    assert _angle_deg(up_true, up_est) < 1.0
    if min(frame.support[1:]) > 300:  # both horizontal directions seen well enough
        yaw_error = abs((frame.yaw_deg - _true_room_yaw(synthetic) + 45.0) % 90.0 - 45.0)
        assert yaw_error < 1.0


def test_layout_stage_outputs_a_consistent_room() -> None:
    pipeline = build_pipeline(["objects_from_detections", "intrinsics", "layout_from_lines"])
    ious = []
    for seed in SEEDS:
        synthetic = scene(seed)
        truth = synthetic.truth
        detections = [
            Detection(o.cls, (o.bbox[0], o.bbox[1], o.bbox[2], o.bbox[3])) for o in truth.objects
        ]
        ctx = SceneContext(image=synthetic.frame.rgb, given_K=synthetic.K, detections=detections)
        pipeline.run(ctx)
        assert (
            ctx.layout is not None and ctx.layout.corners_3d is not None and ctx.camera is not None
        )
        corners = np.array(ctx.layout.corners_3d)
        # The floor is where the camera height says, and the 2D corners are the 3D ones seen.
        assert corners[:4, 1] == pytest.approx(-(ctx.camera.height_m or 0.0), abs=1e-3)
        camera = PinholeCamera(
            np.array(ctx.camera.K), ctx.camera.pitch_deg or 0.0, ctx.camera.roll_deg or 0.0
        )
        for point_2d, point in zip(
            ctx.layout.corners_2d or [], camera.project(corners), strict=True
        ):
            if point_2d is not None:
                assert point_2d == pytest.approx(point.tolist(), rel=1e-3, abs=0.02)
        # Walls are axis-aligned with the estimated room yaw.
        edge = corners[1] - corners[0]
        assert np.allclose(rot_y(0.0) @ edge, edge)
        ious.append(iou_3d(corners, np.array(truth.layout.corners_3d)))
    # A guard against regressions: 0.5-0.6 mean here when written (today's layout figures are
    # in docs/benchmarks.md).
    assert float(np.mean(ious)) > 0.4, ious


def test_a_wall_out_of_view_keeps_its_distance_in_metres() -> None:
    """The wall priors are in metres: with a taller camera (as the objects tell it) a wall the
    photo does not show comes nearer in camera heights, while the walls it shows stay put."""
    synthetic = scene(4101)  # shows the front and right walls, not the left one
    image, K = synthetic.frame.rgb, synthetic.K
    segments = detect_segments(image)
    frame = estimate_manhattan_frame(segments, K)
    assert frame is not None
    camera = PinholeCamera(K, frame.pitch_deg, frame.roll_deg)
    to_room = room_to_world(frame)
    surface_map = SurfaceMap.predict(load_surface_model(), image, camera, to_room)
    boxes = [o.bbox for o in synthetic.truth.objects]
    evidence = SurfaceEvidence(camera, image, boxes, to_room)
    short, tall = (
        estimate_room(
            camera, frame, segments, (640, 480), None, evidence, boxes, surface_map, metres=m
        )
        for m in (1.2, 1.6)
    )
    seen = {SURFACES[i] for i in np.unique(short.surfaces_seen(surface_map.rays_room))}
    assert {"front", "right"} <= seen and "left" not in seen
    for wall in ("front", "right"):
        assert getattr(tall, wall) == pytest.approx(getattr(short, wall), rel=0.05)
    # 1.6 / 1.2 = 1.33 in a perfect search; its grid steps by about 17%.
    assert 1.15 < short.left / tall.left < 1.6


def test_a_side_wall_out_of_view_is_placed_from_the_seen_one() -> None:
    """With one side wall in view the other goes where the room's width prior puts it, in
    metres; with both in view the search's walls stay."""
    camera = PinholeCamera(np.array([[400.0, 0, 320], [0, 400, 240], [0, 0, 1]]), 12.0, 0.0)
    rays = camera.ray(map_pixels(640, 480))  # no yaw: room axes are the world's
    metres = 1.4
    one_side = RoomHypothesis(3.0, 1.2, 9.0, 0.5, 1.0, 0.0, True)
    assert one_side.faces_in_view(rays) >= {"front", "left"}
    assert "right" not in one_side.faces_in_view(rays)
    placed = unseen_parts_from_priors(one_side, metres, rays)
    expected = unseen_side_wall_distance(
        1.2 * metres, placed.nearest_out_of_view("right", rays) * metres
    )
    assert expected is not None
    assert placed.right * metres == pytest.approx(expected)
    assert (placed.front, placed.left) == (3.0, 1.2)
    assert "right" not in placed.faces_in_view(rays)
    both_sides = RoomHypothesis(3.0, 1.2, 1.5, 0.5, 1.0, 0.0, True)
    assert {"left", "right"} <= both_sides.faces_in_view(rays)
    kept = unseen_parts_from_priors(both_sides, metres, rays)
    assert (kept.left, kept.right) == (1.2, 1.5)


def test_wall_objects_edges_are_measured_at_their_heights_in_the_true_room() -> None:
    """In the true room, the ray through the lower edge of a thing hung on a wall (a picture,
    a window) meets the wall at that edge's true height above the floor."""
    measured = 0
    for seed in SEEDS:
        synthetic = scene(seed)
        truth = synthetic.truth
        assert truth.camera is not None and truth.camera.height_m is not None
        frame = estimate_manhattan_frame(detect_segments(synthetic.frame.rgb), synthetic.K)
        assert frame is not None
        camera = PinholeCamera(synthetic.K, frame.pitch_deg, frame.roll_deg)
        to_room = room_to_world(frame)
        height = truth.camera.height_m
        room = RoomHypothesis.enclosing(np.array(truth.layout.corners_3d) @ to_room / height)
        for obj, measured_height in mounted_heights(room, camera, to_room, truth.objects, 480):
            assert obj.corners_3d is not None
            true_height = (np.array(obj.corners_3d)[:, 1].min() + height) / height
            if obj.box_3d is not None and obj.box_3d.size[0] < 0.1:  # flat on the wall
                assert measured_height == pytest.approx(true_height, rel=0.03), obj.id
            else:  # a box standing out of the wall: its near edge's ray meets the wall beyond
                assert measured_height == pytest.approx(true_height, rel=0.08), obj.id
            measured += 1
    assert measured >= 4  # the seeds hang enough pictures and windows to mean something

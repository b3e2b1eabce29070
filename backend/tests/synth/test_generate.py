"""Synthetic scenes: deterministic, valid, and geometrically consistent with their labels."""

from __future__ import annotations

from collections import defaultdict
from functools import cache
from pathlib import Path

import cv2
import numpy as np
import pytest
from holiscene.cli import main
from holiscene.evaluation.run import evaluate_folders
from holiscene.geometry.camera import PinholeCamera
from holiscene.segmentation.rle import decode_mask
from holiscene.synth.generate import SyntheticScene, synthesize
from holiscene_schema import STRUCTURAL_SUPPORTERS, Scene

SEEDS = range(900, 912)


@cache
def scene(seed: int) -> SyntheticScene:
    return synthesize(seed)


def test_same_seed_same_scene() -> None:
    a, b = synthesize(901), scene(901)
    assert np.array_equal(a.frame.rgb, b.frame.rgb)
    assert a.truth == b.truth


@pytest.mark.parametrize("seed", SEEDS)
def test_truth_is_complete_and_consistent(seed: int) -> None:
    synthetic = scene(seed)
    truth = Scene.model_validate_json(synthetic.truth.model_dump_json())
    ids = {o.id for o in truth.objects}
    assert truth.objects, "every scene shows some objects"
    assert sorted(s.child for s in truth.supports) == sorted(ids)
    assert all(s.parent in ids | STRUCTURAL_SUPPORTERS for s in truth.supports)
    assert truth.layout.corners_3d is not None and truth.camera is not None
    camera = PinholeCamera(
        np.array(truth.camera.K), truth.camera.pitch_deg or 0.0, truth.camera.roll_deg or 0.0
    )
    w, h = truth.image.width, truth.image.height
    for obj in truth.objects:
        assert obj.mask is not None and obj.corners_3d is not None
        mask = decode_mask(obj.mask, w, h)
        ys, xs = np.nonzero(mask)
        assert obj.bbox == [xs.min(), ys.min(), xs.max() + 1, ys.max() + 1]
        # The labelled 3D box, projected with the labelled camera, covers the visible pixels.
        projected = camera.project(np.array(obj.corners_3d))
        if not np.isnan(projected).any():
            x0, y0 = projected.min(axis=0)
            x1, y1 = projected.max(axis=0)
            assert x0 - 2 <= xs.min() and xs.max() <= x1 + 2, obj.id
            assert y0 - 2 <= ys.min() and ys.max() <= y1 + 2, obj.id


@pytest.mark.parametrize("seed", SEEDS)
def test_objects_rest_on_their_supporters(seed: int) -> None:
    truth = scene(seed).truth
    camera_height = truth.camera.height_m if truth.camera else None
    assert camera_height is not None
    boxes = {o.id: np.array(o.corners_3d) for o in truth.objects}
    for s in truth.supports:
        if s.type != "below":
            continue
        bottom = boxes[s.child][:, 1].min()
        if s.parent == "floor":
            assert bottom == pytest.approx(-camera_height, abs=0.02)
        else:
            parent = boxes[s.parent]
            assert parent[:, 1].min() - 0.01 <= bottom <= parent[:, 1].max() + 0.01


def test_depth_matches_the_labelled_geometry(tmp_path: Path) -> None:
    synthetic = scene(903)
    depth = synthetic.frame.depth
    assert (depth > 0).mean() > 0.99  # the room is closed: every ray hits something
    assert depth[depth > 0].min() > 0.1 and depth.max() < 12.0


def test_supports_are_not_predictable_from_class_alone() -> None:
    supporters: dict[str, set[str]] = defaultdict(set)
    classes = {}
    for seed in SEEDS:
        truth = scene(seed).truth
        cls = {o.id: o.cls for o in truth.objects}
        classes.update(cls)
        for s in truth.supports:
            supporters[cls[s.child]].add(cls.get(s.parent, s.parent))
    assert len(supporters["box"]) >= 2, supporters["box"]


def test_cli_synth_then_eval_truth_against_itself_is_perfect(tmp_path: Path) -> None:
    out = tmp_path / "scenes"
    assert main(["synth", "--seed", "905", "--count", "2", "-o", str(out), "--workers", "1"]) == 0
    folders = sorted(out.iterdir())
    assert [f.name for f in folders] == ["synth-905", "synth-906"]
    for folder in folders:
        assert {p.name for p in folder.iterdir()} == {
            "img.png",
            "cam_K.txt",
            "detections.json",
            "gt.json",
            "depth.png",
        }
        assert cv2.imread(str(folder / "img.png")).shape == (480, 640, 3)
        assert cv2.imread(str(folder / "depth.png"), cv2.IMREAD_UNCHANGED).dtype == np.uint16
        (folder / "scene.json").write_text((folder / "gt.json").read_text())
    summary = evaluate_folders(out, out).evaluation.summary()
    assert summary["support"]["accuracy"] == 1.0
    assert summary["camera"]["pitch_mae_deg"] == 0.0
    assert summary["layout"]["iou_3d"] == pytest.approx(1.0)
    assert summary["detection_3d"]["map"] == pytest.approx(1.0)
    assert summary["mask"]["mean_iou"] == 1.0

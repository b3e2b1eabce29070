"""Object shapes against the true meshes of synthetic scenes (`holiscene eval --shapes`).

For every ground-truth object of a folder from `holiscene synth` (its mesh is the library's
class + seed, rebuilt exactly in its true box) and its predicted object (matched as the other
metrics match them), three candidates are scored when they exist: the predicted mesh from
scene.glb, labelled by its MeshRef's library (`builtin` for the library fit, `completion`,
`user`), and the raw partial points (the true mask's pixels with depth, back-projected).
Scores are `shape_metrics`' Chamfer distance, EMD approximation and normal consistency on
2048 surface samples per mesh, in the true box's frame scaled by its longest side (the object
fits the unit cube, as ShapeNet objects are normalised for completion benchmarks; one scale
for all three axes, so a picture's 2 cm thickness does not magnify its errors 50 times).

A predicted mesh is also scored in its own box (`<library>, own box`): its samples in the
predicted box's frame scaled by that box's longest side, against the true mesh in the true
box's, the best of four quarter turns about the vertical (a box's yaw does not say where the
object's front is). That leaves out where the box is, how big and how turned, and keeps the
shape and its proportions: how good the model is, apart from the placement.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import trimesh
from holiscene_schema import Box3D, SceneObject

from ..geometry.camera import rot_y
from ..inputs.depth import read_depth_file
from ..placement.depth_box import object_points
from ..placement.room import pinhole
from ..segmentation.rle import decode_mask
from ..shapes import generate_shape
from .matching import match_objects
from .run import PREDICTION_FILE, TRUTH_FILE, EvaluationInputError, _load
from .shape_metrics import chamfer_distance, emd_approximation, normal_consistency

SAMPLES = 2048
GLB_FILE = "scene.glb"
DEPTH_FILE = "depth.png"


def _true_mesh(obj: SceneObject) -> trimesh.Trimesh | None:
    if obj.mesh is None or obj.mesh.library != "builtin" or obj.box_3d is None:
        return None
    box = obj.box_3d
    size = (float(box.size[0]), float(box.size[1]), float(box.size[2]))
    mesh = generate_shape(obj.cls, size, np.random.default_rng(obj.mesh.seed or 0)).mesh
    transform = np.eye(4)
    transform[:3, :3] = rot_y(math.radians(box.yaw_deg))
    transform[:3, 3] = box.center
    return mesh.copy().apply_transform(transform)


def unit_frame(points: np.ndarray, box: Box3D) -> np.ndarray:
    """World points in the box's frame, scaled so its longest side is 1."""
    local = (points - np.asarray(box.center)) @ rot_y(math.radians(box.yaw_deg))
    result: np.ndarray = local / max(box.size)
    return result


def _samples(mesh: trimesh.Trimesh, box: Box3D, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """Surface samples and their normals, in the box's unit frame."""
    points, faces = trimesh.sample.sample_surface(mesh, SAMPLES, seed=seed)
    normals = mesh.face_normals[faces] @ rot_y(math.radians(box.yaw_deg))
    return unit_frame(points, box), normals


def _own_box_score(
    mesh: trimesh.Trimesh, box: Box3D, seed: int, truth: tuple[np.ndarray, np.ndarray]
) -> dict[str, float]:
    """Scores of a mesh in its own box's unit frame, at the quarter turn nearest the truth."""
    points, normals = _samples(mesh, box, seed)
    turned = []
    for k in range(4):
        turn = rot_y(k * math.pi / 2)
        turned.append((points @ turn.T, normals @ turn.T))
    best = min(turned, key=lambda pair: chamfer_distance(pair[0], truth[0]))
    return _score(*best, truth)


def _score(
    points: np.ndarray, normals: np.ndarray | None, truth: tuple[np.ndarray, np.ndarray]
) -> dict[str, float]:
    scores = {
        "chamfer": chamfer_distance(points, truth[0]),
        "emd_approx": emd_approximation(points, truth[0]),
    }
    if normals is not None:
        scores["normal_consistency"] = normal_consistency(points, normals, *truth)
    return scores


class ShapeEvaluation:
    """Scores per object (`<scene>/<true id>`) and per candidate (a mesh library, or
    `partial_points`)."""

    def __init__(self) -> None:
        self.records: dict[str, dict[str, dict[str, float]]] = {}

    def add_folder(self, pred_dir: Path, gt_dir: Path) -> None:
        from ..viewer.meshes import glb_object_meshes

        truth = _load(gt_dir / TRUTH_FILE)
        predicted = _load(pred_dir / PREDICTION_FILE)
        glb_file = pred_dir / GLB_FILE
        glb = glb_object_meshes(glb_file.read_bytes()) if glb_file.is_file() else {}
        camera = pinhole(truth.camera) if truth.camera is not None else None
        depth_file = gt_dir / DEPTH_FILE
        points: dict[str, np.ndarray | None] = {}
        if depth_file.is_file() and camera is not None:
            w, h = truth.image.width, truth.image.height
            depth = read_depth_file(depth_file.read_bytes(), w, h, what=str(depth_file)).metres
            for gt in truth.objects:
                if gt.mask is not None:
                    points[gt.id] = object_points(decode_mask(gt.mask, w, h), depth, camera)
        matched = match_objects(predicted.objects, truth.objects)
        by_id = {o.id: o for o in predicted.objects}
        for gt in truth.objects:
            pred = by_id.get(matched.get(gt.id, ""))
            mesh = glb.get(pred.id) if pred is not None and pred.mesh is not None else None
            library = pred.mesh.library if pred is not None and pred.mesh is not None else ""
            own_box = pred.box_3d if pred is not None else None
            key = f"{truth.name}/{gt.id}"
            self._add_object(key, gt, library, mesh, points.get(gt.id), own_box)

    def _add_object(
        self,
        key: str,
        gt: SceneObject,
        library: str,
        mesh: trimesh.Trimesh | None,
        observed: np.ndarray | None,
        own_box: Box3D | None = None,
    ) -> None:
        true_mesh = _true_mesh(gt)
        if true_mesh is None or gt.box_3d is None:
            return
        seed = len(self.records)
        target = _samples(true_mesh, gt.box_3d, seed)
        row = self.records.setdefault(key, {})
        if mesh is not None:
            row[library] = _score(*_samples(mesh, gt.box_3d, seed + 1), target)
            if own_box is not None:
                row[f"{library}, own box"] = _own_box_score(mesh, own_box, seed + 1, target)
        if observed is not None:
            row["partial_points"] = _score(unit_frame(observed, gt.box_3d), None, target)

    def summary(self, keys: set[str] | None = None) -> dict[str, Any]:
        """Mean scores per candidate, over every object or over `keys`."""
        rows = [r for k, r in self.records.items() if keys is None or k in keys]
        out: dict[str, Any] = {"objects": len(rows)}
        for name in sorted({c for r in rows for c in r}):
            scored = [r[name] for r in rows if name in r]
            metrics = sorted({m for row in scored for m in row})
            out[name] = {
                "count": len(scored),
                **{m: float(np.mean([row[m] for row in scored if m in row])) for m in metrics},
            }
        return out


def evaluate_shapes(predictions: Path, truth: Path) -> dict[str, Any]:
    """Shape scores of every truth/<name>/ with a predictions/<name>/ beside it."""
    folders = sorted(p.parent for p in truth.glob(f"*/{TRUTH_FILE}"))
    if not folders:
        raise EvaluationInputError(f"{truth} holds no */{TRUTH_FILE}")
    evaluation = ShapeEvaluation()
    for gt_dir in folders:
        if (predictions / gt_dir.name / PREDICTION_FILE).is_file():
            evaluation.add_folder(predictions / gt_dir.name, gt_dir)
    return evaluation.summary()


def markdown_shapes(summary: dict[str, Any]) -> str:
    lines = [
        "",
        "## Shapes (true box's frame, longest side 1)",
        "",
        f"{summary['objects']} objects with a true mesh. `own box`: the mesh in its predicted box's"
        " frame against the true mesh in the true box's, the best quarter turn (its shape alone,"
        " not its placement).",
        "",
        "| shapes | objects | Chamfer | EMD (Sinkhorn + greedy, approx.) | normal consistency |",
        "| --- | --- | --- | --- | --- |",
    ]
    for name, row in summary.items():
        if not isinstance(row, dict):
            continue
        normal = row.get("normal_consistency")
        lines.append(
            f"| {name} | {row['count']} | {row['chamfer']:.4f} | {row['emd_approx']:.4f} | "
            + (f"{normal:.3f} |" if normal is not None else "n/a |")
        )
    return "\n".join(lines) + "\n"

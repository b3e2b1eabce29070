"""The thesis's metrics on pairs of (predicted, ground-truth) scenes.

- Support accuracy at object level: supporter and type both right (thesis Table 4.2), plus the
  two parts on their own ("per question": which supporter, which type).
- Layout 3D IoU of the room cuboids (Total3DUnderstanding's layout metric), and the same IoU
  of only the parts inside the camera's view (no photo shows the walls behind or beside the
  camera; SUN RGB-D's layouts, annotated on depth scans, barely contain them either).
- Camera pitch and roll mean absolute error in degrees.
- 3D detection average precision at 3D IoU 0.15 per class and its mean (VOC all-point AP;
  boxes ranked by `score_3d`).
- 2D mask IoU per ground-truth object.
A prediction that lacks a value scores as wrong (IoU 0, support missing) and is counted, never
silently skipped. A ground truth that lacks a kind of label (a dataset without support labels,
3D boxes, layout or camera) leaves that metric out for the scene; `scored` counts the scenes
each metric was measured on.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from holiscene_schema import STRUCTURAL_SUPPORTERS, Scene, SceneObject

from ..geometry.camera import PinholeCamera
from ..segmentation.rle import decode_mask
from .box_iou import iou_3d, iou_3d_in_view
from .matching import match_objects

AP_IOU = 0.15
SUPPORT_TYPES = ("below", "behind", "none")
# The metrics in the order of the summary; `Evaluation.scored` counts scenes per metric.
METRICS = ("support", "camera", "layout", "detection_3d", "mask")


@dataclass
class Evaluation:
    scenes: int = 0
    support_total: int = 0
    support_both: int = 0
    support_parent: int = 0
    support_type: int = 0
    support_confusion: dict[str, dict[str, int]] = field(
        default_factory=lambda: {t: dict.fromkeys(SUPPORT_TYPES, 0) for t in SUPPORT_TYPES}
    )
    pitch_errors: list[float] = field(default_factory=list)
    roll_errors: list[float] = field(default_factory=list)
    camera_missing: int = 0
    layout_ious: list[float] = field(default_factory=list)
    layout_ious_in_view: list[float] = field(default_factory=list)
    layout_missing: int = 0
    mask_ious: list[float] = field(default_factory=list)
    # class -> list of (score, is_true_positive) and the count of ground-truth boxes
    detections: dict[str, list[tuple[float, bool]]] = field(
        default_factory=lambda: defaultdict(list)
    )
    gt_boxes: dict[str, int] = field(default_factory=lambda: defaultdict(int))
    scored: dict[str, int] = field(default_factory=lambda: dict.fromkeys(METRICS, 0))

    def add(self, predicted: Scene, truth: Scene) -> None:
        self.scenes += 1
        matched = match_objects(predicted.objects, truth.objects)
        present = truth_metrics(truth)
        for metric in present:
            self.scored[metric] += 1
        self._add_supports(predicted, truth, matched)
        self._add_camera(predicted, truth)
        self._add_layout(predicted, truth)
        self._add_masks(predicted, truth, matched)
        if "detection_3d" in present:
            # Without true 3D boxes every predicted box would count as a false positive.
            self._add_detections(predicted, truth)

    def _add_supports(self, predicted: Scene, truth: Scene, matched: dict[str, str]) -> None:
        pred_support = {s.child: s for s in predicted.supports}
        pred_to_gt = {p: g for g, p in matched.items()}
        for gt in truth.supports:
            self.support_total += 1
            pred = pred_support.get(matched.get(gt.child, ""))
            pred_type = pred.type if pred else "none"
            self.support_confusion[gt.type][pred_type] += 1
            if pred is None:
                continue
            parent = (
                pred.parent if pred.parent in STRUCTURAL_SUPPORTERS else pred_to_gt.get(pred.parent)
            )
            parent_ok = parent == gt.parent
            type_ok = pred.type == gt.type
            self.support_parent += parent_ok
            self.support_type += type_ok
            self.support_both += parent_ok and type_ok

    def _add_camera(self, predicted: Scene, truth: Scene) -> None:
        pc, tc = predicted.camera, truth.camera
        if tc is None or tc.pitch_deg is None or tc.roll_deg is None:
            return
        if pc is None or pc.pitch_deg is None or pc.roll_deg is None:
            self.camera_missing += 1
            return
        self.pitch_errors.append(abs(pc.pitch_deg - tc.pitch_deg))
        self.roll_errors.append(abs(pc.roll_deg - tc.roll_deg))

    def _add_layout(self, predicted: Scene, truth: Scene) -> None:
        if truth.layout.corners_3d is None:
            return
        true = np.array(truth.layout.corners_3d)
        # The in-view IoU needs the true camera: scenes without its pitch and roll are left out
        # of that mean (a missed layout counts 0 in both means otherwise).
        camera = truth.camera
        view = None
        if camera is not None and camera.pitch_deg is not None and camera.roll_deg is not None:
            view = PinholeCamera(np.array(camera.K), camera.pitch_deg, camera.roll_deg)
        if predicted.layout.corners_3d is None:
            self.layout_missing += 1
            self.layout_ious.append(0.0)
            if view is not None:
                self.layout_ious_in_view.append(0.0)
            return
        estimate = np.array(predicted.layout.corners_3d)
        self.layout_ious.append(iou_3d(estimate, true))
        if view is not None:
            size = (truth.image.width, truth.image.height)
            self.layout_ious_in_view.append(iou_3d_in_view(estimate, true, view, size))

    def _add_masks(self, predicted: Scene, truth: Scene, matched: dict[str, str]) -> None:
        pred_by_id = {o.id: o for o in predicted.objects}
        w, h = truth.image.width, truth.image.height
        for gt in truth.objects:
            if gt.mask is None:
                continue
            pred = pred_by_id.get(matched.get(gt.id, ""))
            if pred is None or pred.mask is None:
                self.mask_ious.append(0.0)
                continue
            a, b = decode_mask(gt.mask, w, h), decode_mask(pred.mask, w, h)
            union = np.logical_or(a, b).sum()
            self.mask_ious.append(float(np.logical_and(a, b).sum() / union) if union else 0.0)

    def _add_detections(self, predicted: Scene, truth: Scene) -> None:
        """Greedy VOC matching per class: highest score first, each ground truth used once."""
        for cls in {o.cls for o in truth.objects} | {o.cls for o in predicted.objects}:
            gts = [np.array(o.corners_3d) for o in truth.objects if o.cls == cls and o.corners_3d]
            self.gt_boxes[cls] += len(gts)
            preds = [o for o in predicted.objects if o.cls == cls and o.corners_3d]
            preds.sort(key=lambda o: -score_3d(o))
            used: set[int] = set()
            for pred in preds:
                ious = [iou_3d(np.array(pred.corners_3d), g) for g in gts]
                best = max(
                    (i for i in range(len(gts)) if i not in used),
                    key=lambda i: ious[i],
                    default=None,
                )
                hit = best is not None and ious[best] >= AP_IOU
                if hit and best is not None:
                    used.add(best)
                self.detections[cls].append((score_3d(pred), hit))

    # -- summaries ---------------------------------------------------------------------

    def average_precision(self) -> dict[str, float]:
        """AP per class that has ground-truth boxes (all-point interpolated precision)."""
        return {
            cls: all_point_average_precision(self.detections.get(cls, []), count)
            for cls, count in sorted(self.gt_boxes.items())
            if count > 0
        }

    def box_recall(self) -> float | None:
        """Share of all ground-truth boxes some prediction matched at AP_IOU, every box
        counting the same: steadier than mAP over a few scenes, where a class with one box
        moves the mean by 1 / classes."""
        total = sum(self.gt_boxes.values())
        found = sum(hit for found_in_class in self.detections.values() for _, hit in found_in_class)
        return found / total if total else None

    def summary(self) -> dict[str, Any]:
        ap = self.average_precision()

        def mean(values: list[float]) -> float | None:
            return float(np.mean(values)) if values else None

        total = max(self.support_total, 1)
        return {
            "scenes": self.scenes,
            "support": {
                "objects": self.support_total,
                "accuracy": self.support_both / total if self.support_total else None,
                "supporter_accuracy": self.support_parent / total if self.support_total else None,
                "type_accuracy": self.support_type / total if self.support_total else None,
                "type_confusion": self.support_confusion,
            },
            "camera": {
                "pitch_mae_deg": mean(self.pitch_errors),
                "roll_mae_deg": mean(self.roll_errors),
                "scenes_without_estimate": self.camera_missing,
            },
            "layout": {
                "iou_3d": mean(self.layout_ious),
                "iou_3d_in_view": mean(self.layout_ious_in_view),
                "scenes_without_layout": self.layout_missing,
            },
            "detection_3d": {
                "iou_threshold": AP_IOU,
                "ap_per_class": ap,
                "map": float(np.mean(list(ap.values()))) if ap else None,
                "recall": self.box_recall(),
            },
            "mask": {"mean_iou": mean(self.mask_ious), "objects": len(self.mask_ious)},
            "scenes_scored": dict(self.scored),
        }


def truth_metrics(truth: Scene) -> list[str]:
    """The metrics a ground-truth scene has the labels for."""
    camera = truth.camera
    has = {
        "support": bool(truth.supports),
        "camera": camera is not None and None not in (camera.pitch_deg, camera.roll_deg),
        "layout": truth.layout.corners_3d is not None,
        "detection_3d": any(o.corners_3d for o in truth.objects),
        "mask": any(o.mask is not None for o in truth.objects),
    }
    return [metric for metric in METRICS if has[metric]]


def score_3d(obj: SceneObject) -> float:
    """How a 3D box ranks among its class's boxes: its detection score times how sure the box
    refiner is of the box (as monocular 3D detectors rank by 2D score times 3D confidence); a
    value no model gave counts as 1."""
    detection = obj.score if obj.score is not None else 1.0
    box = obj.box_3d_confidence if obj.box_3d_confidence is not None else 1.0
    return detection * box


def all_point_average_precision(scored_hits: list[tuple[float, bool]], truth_count: int) -> float:
    """VOC all-point AP of one class: (score, is a true positive) per prediction, against
    `truth_count` ground-truth boxes."""
    if truth_count <= 0 or not scored_hits:
        return 0.0
    ranked = sorted(scored_hits, key=lambda d: -d[0])
    hits = np.array([hit for _, hit in ranked], dtype=float)
    tp = np.cumsum(hits)
    recall = tp / truth_count
    precision = tp / np.arange(1, len(hits) + 1)
    # Precision envelope, then area under the recall steps.
    envelope = np.maximum.accumulate(precision[::-1])[::-1]
    recall_steps = np.concatenate([[0.0], recall])
    return float(np.sum((recall_steps[1:] - recall_steps[:-1]) * envelope))

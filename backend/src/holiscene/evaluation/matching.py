"""Which predicted object is which ground-truth object: greedy matching on 2D box IoU."""

from __future__ import annotations

from holiscene_schema import SceneObject

from .box_iou import iou_2d

MIN_MATCH_IOU = 0.5


def match_objects(predicted: list[SceneObject], truth: list[SceneObject]) -> dict[str, str]:
    """Ground-truth id -> predicted id, each used once, pairs of the same class first.

    When a pipeline ran on the ground-truth boxes this is the identity on indices.
    """
    pairs = []
    for gt in truth:
        for pred in predicted:
            iou = iou_2d(gt.bbox, pred.bbox)
            if iou >= MIN_MATCH_IOU:
                pairs.append((gt.cls == pred.cls, iou, gt.id, pred.id))
    pairs.sort(reverse=True)
    matched: dict[str, str] = {}
    used: set[str] = set()
    for _, _, gt_id, pred_id in pairs:
        if gt_id not in matched and pred_id not in used:
            matched[gt_id] = pred_id
            used.add(pred_id)
    return matched

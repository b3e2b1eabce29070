"""The evaluation as JSON and as a Markdown report a person reads."""

from __future__ import annotations

from typing import Any


def _fmt(value: float | None, scale: float = 1.0, digits: int = 2) -> str:
    return "n/a" if value is None else f"{value * scale:.{digits}f}"


_METRIC_NAMES = {
    "support": "supports",
    "camera": "camera",
    "layout": "layout",
    "detection_3d": "3D boxes",
    "mask": "masks",
}


def _scored_line(scored: dict[str, int]) -> str:
    counts = ", ".join(f"{_METRIC_NAMES[m]} {n}" for m, n in scored.items())
    return (
        f"Scenes measured per metric: {counts}. A metric whose labels a scene's ground truth "
        "lacks is left out for that scene, not counted as 0."
    )


def markdown_report(summary: dict[str, Any], title: str) -> str:
    support, camera, layout = summary["support"], summary["camera"], summary["layout"]
    det, mask = summary["detection_3d"], summary["mask"]
    lines = [
        f"# {title}",
        "",
        f"{summary['scenes']} scenes.",
        "",
        "| metric | value |",
        "| --- | --- |",
        f"| support accuracy, supporter and type (%) | {_fmt(support['accuracy'], 100)} |",
        f"| supporter right (%) | {_fmt(support['supporter_accuracy'], 100)} |",
        f"| support type right (%) | {_fmt(support['type_accuracy'], 100)} |",
        f"| camera pitch MAE (deg) | {_fmt(camera['pitch_mae_deg'])} |",
        f"| camera roll MAE (deg) | {_fmt(camera['roll_mae_deg'])} |",
        f"| scenes without a camera estimate | {camera['scenes_without_estimate']} |",
        f"| layout 3D IoU (%) | {_fmt(layout['iou_3d'], 100)} |",
        f"| layout 3D IoU of the parts in view (%) | {_fmt(layout['iou_3d_in_view'], 100)} |",
        f"| scenes without a layout (IoU 0) | {layout['scenes_without_layout']} |",
        f"| 3D detection mAP at IoU {det['iou_threshold']} (%) | {_fmt(det['map'], 100)} |",
        f"| 3D boxes found at IoU {det['iou_threshold']}, all classes (%) | "
        f"{_fmt(det['recall'], 100)} |",
        f"| 2D mask IoU (%) | {_fmt(mask['mean_iou'], 100)} over {mask['objects']} objects |",
        "",
        _scored_line(summary["scenes_scored"]),
        "",
        f"## Support types ({support['objects']} supported objects)",
        "",
        "Rows: ground truth; columns: prediction (`none`: no supporter predicted).",
        "",
    ]
    confusion = support["type_confusion"]
    kinds = list(confusion)
    lines.append("| truth \\ predicted | " + " | ".join(kinds) + " |")
    lines.append("| --- |" + " --- |" * len(kinds))
    for truth in kinds:
        if truth == "none":
            continue
        lines.append(f"| {truth} | " + " | ".join(str(confusion[truth][p]) for p in kinds) + " |")
    lines += ["", "## 3D detection AP per class", "", "| class | AP (%) |", "| --- | --- |"]
    for cls, ap in det["ap_per_class"].items():
        lines.append(f"| {cls} | {ap * 100:.1f} |")
    return "\n".join(lines) + "\n"

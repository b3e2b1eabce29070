"""Make docs/img/synth_examples.png: renders beside their ground-truth masks, support arrows,
layout and depth. Run: .venv/bin/python scripts/synth_docs_sheet.py [first_seed] [count]"""

from __future__ import annotations

import sys
from pathlib import Path

import cv2
import numpy as np
from holiscene.export.glb import class_colour
from holiscene.segmentation.rle import decode_mask
from holiscene.synth.generate import SyntheticScene, synthesize

OUT = Path(__file__).resolve().parent.parent / "docs" / "img" / "synth_examples.png"
RED, BLUE = (40, 40, 220), (220, 90, 30)  # BGR: from below, from behind
LAYOUT_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
                (0, 4), (1, 5), (2, 6), (3, 7)]  # fmt: skip


def _labels_panel(scene: SyntheticScene) -> np.ndarray:
    truth = scene.truth
    image = cv2.cvtColor(scene.frame.rgb, cv2.COLOR_RGB2BGR)
    overlay = image.copy()
    w, h = truth.image.width, truth.image.height
    centres = {}
    for obj in truth.objects:
        if obj.mask is None:
            continue
        mask = decode_mask(obj.mask, w, h)
        r, g, b, _ = class_colour(obj.cls)
        overlay[mask] = (b, g, r)
        ys, xs = np.nonzero(mask)
        centres[obj.id] = (int(xs.mean()), int(ys.mean()))
    panel = cv2.addWeighted(image, 0.35, overlay, 0.65, 0)
    corners = truth.layout.corners_2d or []
    for a, b in LAYOUT_EDGES:
        corner_a, corner_b = corners[a], corners[b]
        if corner_a is not None and corner_b is not None:
            pa = tuple(int(v) for v in np.clip(corner_a, -5000, 5000))
            pb = tuple(int(v) for v in np.clip(corner_b, -5000, 5000))
            cv2.line(panel, pa, pb, (0, 255, 255), 1, cv2.LINE_AA)
    for s in truth.supports:
        if s.child not in centres:
            continue
        end = centres[s.child]
        start = centres.get(
            s.parent, (end[0], h - 4) if s.parent == "floor" else (end[0] - 25, end[1])
        )
        cv2.arrowedLine(
            panel, start, end, RED if s.type == "below" else BLUE, 2, cv2.LINE_AA, tipLength=0.15
        )
    return panel


def _depth_panel(scene: SyntheticScene) -> np.ndarray:
    depth = scene.frame.depth
    scaled = np.clip(depth / max(float(depth.max()), 1e-6) * 255, 0, 255).astype(np.uint8)
    coloured: np.ndarray = cv2.applyColorMap(255 - scaled, cv2.COLORMAP_VIRIDIS)
    return coloured


def main() -> int:
    first = int(sys.argv[1]) if len(sys.argv) > 1 else 1
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 4
    rows = []
    for seed in range(first, first + count):
        scene = synthesize(seed)
        photo = cv2.cvtColor(scene.frame.rgb, cv2.COLOR_RGB2BGR)
        row = np.hstack([photo, _labels_panel(scene), _depth_panel(scene)])
        cv2.putText(
            row,
            f"seed {seed}: {scene.truth.layout.note}",
            (8, 22),
            cv2.FONT_HERSHEY_SIMPLEX,
            0.6,
            (255, 255, 255),
            2,
            cv2.LINE_AA,
        )
        rows.append(row)
    sheet = cv2.resize(np.vstack(rows), None, fx=0.5, fy=0.5, interpolation=cv2.INTER_AREA)
    OUT.parent.mkdir(parents=True, exist_ok=True)
    cv2.imwrite(str(OUT), sheet)
    print(OUT)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

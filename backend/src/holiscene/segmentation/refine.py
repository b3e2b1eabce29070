"""GrabCut in a box steered by a person's brush strokes (the workbench's "refine" tool).

The box starts GrabCut as in `grabcut_in_box` (outside is background, inside probably the
object); pixels under foreground strokes are fixed as the object and under background strokes
as not. The cut runs on a crop scaled down to `max_side` so a 400x400 box stays well under
the 300 ms an interactive tool can afford, and the painted pixels are then set again at full
resolution, so what a person painted is always what they get.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from itertools import pairwise

import cv2
import numpy as np

from ..core.errors import DomainError


class RefineInputError(DomainError, ValueError):
    """A refine request that cannot be cut (box or strokes outside the photo, empty box)."""

    def detail(self) -> str:
        return f"cannot refine the mask: {self}"


@dataclass(frozen=True)
class BrushStroke:
    """A polyline of (x, y) pixel points painted with a round brush of `radius` pixels."""

    points: Sequence[Sequence[float]]
    radius: float


@dataclass(frozen=True)
class RefineCut:
    """Settings of the refine cut; finer than the pipeline's box cut, since a person is
    looking at the outline, yet small enough for ~100 ms on a 400x400 box."""

    max_side: int = 160  # long side of the crop GrabCut runs on
    margin: float = 0.1  # context around the box to learn background colours from
    min_margin: int = 4
    iterations: int = 2
    seed: int = 0


def check_refine_input(
    width: int,
    height: int,
    bbox: Sequence[float],
    foreground: Sequence[BrushStroke],
    background: Sequence[BrushStroke],
) -> None:
    """Raise RefineInputError with the reason when the box or a stroke does not fit the photo."""
    x1, y1, x2, y2 = bbox
    if not all(np.isfinite(v) for v in bbox):
        raise RefineInputError("the box has a coordinate that is not a number")
    if x1 < 0 or y1 < 0 or x2 > width or y2 > height:
        raise RefineInputError(
            f"the box {list(bbox)} is not inside the photo (0, 0, {width}, {height})"
        )
    if x2 - x1 < 1 or y2 - y1 < 1:
        raise RefineInputError(f"the box {list(bbox)} is empty: x2 > x1 and y2 > y1 by 1 px")
    for kind, strokes in (("foreground", foreground), ("background", background)):
        for index, stroke in enumerate(strokes):
            for x, y in stroke.points:
                if not (0 <= x <= width and 0 <= y <= height):
                    raise RefineInputError(
                        f"{kind} stroke {index} has the point ({x}, {y}) outside the photo "
                        f"(0, 0, {width}, {height})"
                    )


def paint_strokes(
    shape: tuple[int, int],
    strokes: Sequence[BrushStroke],
    scale: float = 1.0,
    offset: tuple[float, float] = (0.0, 0.0),
) -> np.ndarray:
    """A bool (H, W) image of the pixels under the strokes: a round brush dragged along each
    polyline, in a frame where photo point p lands on (p - offset) * scale."""
    canvas = np.zeros(shape, dtype=np.uint8)
    ox, oy = offset
    for stroke in strokes:
        radius = max(1, round(stroke.radius * scale))
        pts = [(round((x - ox) * scale), round((y - oy) * scale)) for x, y in stroke.points]
        for point in pts:  # a polyline of one point is a dab
            cv2.circle(canvas, point, radius, 1, thickness=-1)
        for start, end in pairwise(pts):
            cv2.line(canvas, start, end, 1, thickness=2 * radius + 1)
    return canvas.astype(bool)


def refine_in_box(
    image: np.ndarray,
    bbox: Sequence[float],
    foreground: Sequence[BrushStroke] = (),
    background: Sequence[BrushStroke] = (),
    cut: RefineCut | None = None,
) -> np.ndarray:
    """The object's bool (H, W) mask, inside `bbox` of an RGB uint8 image; empty when the
    strokes leave nothing. Call `check_refine_input` first."""
    cut = cut or RefineCut()
    height, width = image.shape[:2]
    x1, y1 = max(0, int(np.floor(bbox[0]))), max(0, int(np.floor(bbox[1])))
    x2, y2 = min(width, int(np.ceil(bbox[2]))), min(height, int(np.ceil(bbox[3])))
    mx = max(cut.min_margin, round(cut.margin * (x2 - x1)))
    my = max(cut.min_margin, round(cut.margin * (y2 - y1)))
    cx1, cy1, cx2, cy2 = max(0, x1 - mx), max(0, y1 - my), min(width, x2 + mx), min(height, y2 + my)
    crop_w, crop_h = cx2 - cx1, cy2 - cy1
    scale = min(1.0, cut.max_side / max(crop_w, crop_h))
    small_w, small_h = max(1, round(crop_w * scale)), max(1, round(crop_h * scale))
    sx, sy = small_w / crop_w, small_h / crop_h

    labels = np.full((small_h, small_w), cv2.GC_BGD, dtype=np.uint8)
    bx1, by1 = int(np.floor((x1 - cx1) * sx)), int(np.floor((y1 - cy1) * sy))
    bx2, by2 = (
        max(bx1 + 1, int(np.ceil((x2 - cx1) * sx))),
        max(by1 + 1, int(np.ceil((y2 - cy1) * sy))),
    )
    labels[by1:by2, bx1:bx2] = cv2.GC_PR_FGD
    in_box = np.zeros_like(labels, dtype=bool)
    in_box[by1:by2, bx1:bx2] = True
    small_shape = (small_h, small_w)
    painted_fg = paint_strokes(small_shape, foreground, scale, (cx1, cy1)) & in_box
    painted_bg = paint_strokes(small_shape, background, scale, (cx1, cy1))
    labels[painted_fg] = cv2.GC_FGD
    labels[painted_bg] = cv2.GC_BGD  # a person's "not this" wins where both were painted
    if not (labels == cv2.GC_BGD).any():
        # A box filling the photo leaves no margin to learn the background from: its rim is
        # the likeliest background there is.
        rim = in_box.copy()
        rim[by1 + 1 : by2 - 1, bx1 + 1 : bx2 - 1] = False
        labels[rim & (labels == cv2.GC_PR_FGD)] = cv2.GC_BGD

    foreground_small = np.isin(labels, (cv2.GC_FGD, cv2.GC_PR_FGD))
    unknown = int(np.isin(labels, (cv2.GC_PR_FGD, cv2.GC_PR_BGD)).sum())
    has_both = foreground_small.any() and (~foreground_small).any()
    if unknown and has_both:  # GrabCut needs samples of both kinds and something to decide
        small = cv2.resize(
            image[cy1:cy2, cx1:cx2], (small_w, small_h), interpolation=cv2.INTER_AREA
        )
        cv2.setRNGSeed(cut.seed)  # its colour models start with k-means
        bgd_model, fgd_model = np.zeros((1, 65), np.float64), np.zeros((1, 65), np.float64)
        cv2.grabCut(
            small, labels, (0, 0, 0, 0), bgd_model, fgd_model, cut.iterations, cv2.GC_INIT_WITH_MASK
        )
        foreground_small = np.isin(labels, (cv2.GC_FGD, cv2.GC_PR_FGD))

    # Linear upscaling and a 0.5 threshold give smoother outlines than nearest neighbour.
    full = (
        cv2.resize(
            foreground_small.astype(np.float32), (crop_w, crop_h), interpolation=cv2.INTER_LINEAR
        )
        >= 0.5
    )
    # What was painted is exact at full resolution, and the object never leaves its box.
    full |= paint_strokes((crop_h, crop_w), foreground, offset=(cx1, cy1))
    full &= ~paint_strokes((crop_h, crop_w), background, offset=(cx1, cy1))
    out = np.zeros((height, width), dtype=bool)
    out[y1:y2, x1:x2] = full[y1 - cy1 : y2 - cy1, x1 - cx1 : x2 - cx1]
    return out

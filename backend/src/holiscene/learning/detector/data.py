"""Detector training data: photos with boxes, domain randomisation, and CenterNet targets.

Synthetic rooms have exact boxes for every object but look like renders, so every training
photo is changed at random before the frozen backbone sees it: patterns on objects' surfaces
(`retexture.py`, when asked), a crop, a flip, colour, white balance, contrast, gamma, a smooth
light field (uneven lighting and texture), noise, blur and JPEG compression. Numpy and OpenCV
only.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial
from multiprocessing import get_context
from pathlib import Path
from typing import TYPE_CHECKING

import cv2
import numpy as np
from holiscene_schema import NYU40_CLASSES, Mask

from ...inputs import read_input_folder
from .retexture import retexture

if TYPE_CHECKING:
    from ...synth.plan import RoomStyle

MIN_VISIBLE = 0.4  # share of a box that must stay in a crop for the box to be kept
MIN_SIDE_PX = 6.0


@dataclass
class BoxedPhoto:
    rgb: np.ndarray  # (H, W, 3) uint8
    boxes: np.ndarray  # (N, 4) float x1, y1, x2, y2 in pixels
    classes: list[str]  # NYU-40, one per box
    # The visible masks of a synthetic room's objects (its gt.json), for repainting surfaces.
    masks: tuple[Mask, ...] = ()


def classes_in(photos: Sequence[BoxedPhoto]) -> list[str]:
    """The NYU-40 classes the photos' boxes hold, in NYU-40 order: what a detector learns."""
    return [c for c in NYU40_CLASSES if any(c in p.classes for p in photos)]


def _crop(photo: BoxedPhoto, rng: np.random.Generator) -> BoxedPhoto:
    height, width = photo.rgb.shape[:2]
    scale = rng.uniform(0.55, 1.0)
    aspect = np.exp(rng.uniform(-0.2, 0.2))
    crop_w = int(min(width, width * scale * aspect))
    crop_h = int(min(height, height * scale / aspect))
    x0 = int(rng.integers(0, width - crop_w + 1))
    y0 = int(rng.integers(0, height - crop_h + 1))
    boxes = photo.boxes - [x0, y0, x0, y0]
    clipped = np.clip(boxes, 0, [crop_w, crop_h, crop_w, crop_h])
    area = (boxes[:, 2] - boxes[:, 0]) * (boxes[:, 3] - boxes[:, 1])
    visible = (clipped[:, 2] - clipped[:, 0]) * (clipped[:, 3] - clipped[:, 1])
    keep = (
        (visible >= MIN_VISIBLE * np.maximum(area, 1e-9))
        & (clipped[:, 2] - clipped[:, 0] >= MIN_SIDE_PX)
        & (clipped[:, 3] - clipped[:, 1] >= MIN_SIDE_PX)
    )
    return BoxedPhoto(
        photo.rgb[y0 : y0 + crop_h, x0 : x0 + crop_w],
        clipped[keep],
        [c for c, k in zip(photo.classes, keep, strict=True) if k],
    )


def _flip(photo: BoxedPhoto) -> BoxedPhoto:
    width = photo.rgb.shape[1]
    boxes = photo.boxes.copy()
    boxes[:, [0, 2]] = width - photo.boxes[:, [2, 0]]
    return BoxedPhoto(photo.rgb[:, ::-1], boxes, photo.classes)


def _light_field(shape: tuple[int, int], rng: np.random.Generator) -> np.ndarray:
    """A smooth random gain field (uneven light, large-scale texture), about 1."""
    cells = int(rng.integers(2, 9))
    coarse = rng.uniform(1 - 0.25, 1 + 0.25, size=(cells, cells, 1)).astype(np.float32)
    field = cv2.resize(coarse, (shape[1], shape[0]), interpolation=cv2.INTER_CUBIC)
    return field.reshape(shape[0], shape[1], 1)


def _colour(rgb: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    image = rgb.astype(np.float32)
    if rng.random() < 0.5:  # hue turn
        hsv = cv2.cvtColor(rgb, cv2.COLOR_RGB2HSV)
        hsv[..., 0] = (hsv[..., 0].astype(np.int32) + int(rng.integers(0, 180))) % 180
        image = cv2.cvtColor(hsv, cv2.COLOR_HSV2RGB).astype(np.float32)
    gray = image.mean(axis=2, keepdims=True)
    image = gray + (image - gray) * rng.uniform(0.4, 1.6)  # saturation
    image = image * rng.uniform(0.8, 1.2, size=3)  # white balance
    mean = image.mean()
    image = mean + (image - mean) * rng.uniform(0.6, 1.4) + rng.uniform(-35, 35)
    image = image * _light_field(image.shape[:2], rng)
    out: np.ndarray = 255.0 * (np.clip(image, 0, 255) / 255.0) ** rng.uniform(0.7, 1.5)
    return out


def _degrade(image: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    if rng.random() < 0.4:
        size = int(rng.choice([3, 5]))
        image = cv2.GaussianBlur(image, (size, size), 0)
    image = image + rng.normal(0, rng.uniform(0, 10), size=image.shape)
    out = np.clip(image, 0, 255).astype(np.uint8)
    if rng.random() < 0.7:
        quality = int(rng.integers(25, 96))
        ok, data = cv2.imencode(".jpg", out[..., ::-1], [cv2.IMWRITE_JPEG_QUALITY, quality])
        decoded = cv2.imdecode(data, cv2.IMREAD_COLOR) if ok else None
        if decoded is not None:
            out = decoded[..., ::-1]
    return np.ascontiguousarray(out)


def photometric(rgb: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """The randomisation that moves no pixel (colour, light, noise, blur, JPEG): for
    networks whose targets depend on the camera, which a crop or a flip would change."""
    return _degrade(_colour(rgb, rng), rng)


def randomise(
    photo: BoxedPhoto, rng: np.random.Generator, retexture_chance: float = 0.0
) -> BoxedPhoto:
    """One random training view of a photo (the domain randomisation above); with
    `retexture_chance` > 0 each object of a synthetic room is repainted with that chance."""
    if retexture_chance > 0 and photo.masks:
        rgb = retexture(photo.rgb, photo.masks, rng, retexture_chance)
        photo = BoxedPhoto(rgb, photo.boxes, photo.classes)
    if rng.random() < 0.7:
        photo = _crop(photo, rng)
    if rng.random() < 0.5:
        photo = _flip(photo)
    return BoxedPhoto(photometric(photo.rgb, rng), photo.boxes, photo.classes)


def center_targets(
    boxes: np.ndarray, class_index: np.ndarray, num_classes: int, cells: int, stride: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """CenterNet targets on a cells x cells grid for boxes in input pixels:
    heatmap [K, cells, cells] (an elliptic Gaussian per box, 1 at its centre cell), the centre
    cells [N, 2] (row, column) and the boxes' sides from those cells [N, 4] (left, top, right,
    bottom, input pixels)."""
    heatmap = np.zeros((num_classes, cells, cells), dtype=np.float32)
    centres = np.zeros((len(boxes), 2), dtype=np.int64)
    sides = np.zeros((len(boxes), 4), dtype=np.float32)
    grid = np.arange(cells, dtype=np.float32)
    for n, (box, cls) in enumerate(zip(boxes, class_index, strict=True)):
        cx = min(int((box[0] + box[2]) / 2 / stride), cells - 1)
        cy = min(int((box[1] + box[3]) / 2 / stride), cells - 1)
        sigma_x = max((box[2] - box[0]) / stride * 0.54 / 6, 0.5)
        sigma_y = max((box[3] - box[1]) / stride * 0.54 / 6, 0.5)
        gauss_x = np.exp(-((grid - cx) ** 2) / (2 * sigma_x**2))
        gauss_y = np.exp(-((grid - cy) ** 2) / (2 * sigma_y**2))
        np.maximum(heatmap[cls], np.outer(gauss_y, gauss_x), out=heatmap[cls])
        centres[n] = (cy, cx)
        px, py = cx * stride, cy * stride
        sides[n] = (px - box[0], py - box[1], box[2] - px, box[3] - py)
    return heatmap, centres, sides


def boxed_photo(folder: Path) -> BoxedPhoto:
    """A photo and its given boxes from an input folder (img + detections.json), with its
    objects' masks when it holds a gt.json (a synthetic room)."""
    inputs = read_input_folder(folder)
    detections = inputs.detections or []
    boxes = np.array([d.bbox for d in detections], dtype=np.float64).reshape(-1, 4)
    truth = inputs.ground_truth.objects if inputs.ground_truth else []
    masks = tuple(o.mask for o in truth if o.mask is not None)
    return BoxedPhoto(inputs.photo.rgb, boxes, [d.cls for d in detections], masks)


def render_rooms(
    seeds: Sequence[int],
    cache_dir: Path,
    progress: Callable[[int, int], None] | None = None,
    workers: int = 2,
    style: RoomStyle | None = None,
) -> dict[int, Path]:
    """The folders of the synthetic rooms of `seeds` in `style` (the generator's default when
    None), rendered into `cache_dir` once as `holiscene synth` writes them."""
    from ...synth.generate import synthesize_to  # the renderer is heavy: only when rendering
    from ...synth.plan import DEFAULT_STYLE

    style = style or DEFAULT_STYLE
    folders = {s: cache_dir / f"synth-{s}{style.folder_suffix}" for s in seeds}
    missing = [s for s in seeds if not (folders[s] / "detections.json").is_file()]
    if missing:
        cache_dir.mkdir(parents=True, exist_ok=True)
        render = partial(synthesize_to, out_dir=cache_dir, style=style)
        with get_context("spawn").Pool(workers) as pool:
            for done, _ in enumerate(pool.imap_unordered(render, missing), start=1):
                if progress:
                    progress(done, len(missing))
    return folders


def synthetic_photos(
    seeds: Sequence[int],
    cache_dir: Path,
    progress: Callable[[int, int], None] | None = None,
    workers: int = 2,
    style: RoomStyle | None = None,
) -> list[BoxedPhoto]:
    """Synthetic rooms of `seeds` (`render_rooms`) with their exact boxes."""
    folders = render_rooms(seeds, cache_dir, progress, workers, style)
    return [boxed_photo(folders[s]) for s in seeds]

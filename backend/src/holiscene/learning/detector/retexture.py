"""Texture randomisation of synthetic objects, for detector training (numpy and OpenCV).

The renderer paints surfaces plain, wood-grained, tiled or faintly woven; real rooms'
bedspreads, pillows, pictures, books and rugs are striped, checked and printed. A head that
has only seen plain surfaces calls any small patterned patch "books" on a real photo and
misses patterned pillows (docs/detector.md). So, before the other randomisation, each
object's visible pixels may get a random pattern, multiplied by the render's own shading
(each pixel's brightness over the object's median brightness): outlines, shading and
shadows stay as rendered, only the surface changes.
"""

from __future__ import annotations

from collections.abc import Sequence

import cv2
import numpy as np
from holiscene_schema import Mask

from ...segmentation.rle import decode_mask

PATTERNS = ("stripes", "checks", "print", "speckle")


def _colour(rng: np.random.Generator) -> np.ndarray:
    """A random colour, from vivid to muted (mixed toward a random grey)."""
    vivid = rng.uniform(0, 255, size=3)
    muted = rng.uniform(0, 0.8)
    return (vivid * (1 - muted) + rng.uniform(40, 220) * muted).astype(np.float32)


def _stripes(height: int, width: int, rng: np.random.Generator) -> np.ndarray:
    """0/1 stripes at a random angle and period (a few pixels to a few dozen)."""
    angle = rng.uniform(0, np.pi)
    period = rng.uniform(3, 40)
    duty = rng.uniform(0.2, 0.8)
    y, x = np.mgrid[0:height, 0:width].astype(np.float32)
    phase = (x * np.cos(angle) + y * np.sin(angle)) / period + rng.uniform(0, 1)
    stripes: np.ndarray = (np.mod(phase, 1.0) < duty).astype(np.float32)
    return stripes


def pattern(height: int, width: int, rng: np.random.Generator) -> np.ndarray:
    """A random surface pattern, float32 RGB (height, width, 3) in 0-255."""
    kind = PATTERNS[int(rng.integers(len(PATTERNS)))]
    first, second = _colour(rng), _colour(rng)
    painted: np.ndarray
    if kind == "stripes":
        weight = _stripes(height, width, rng)[..., None]
        painted = first * (1 - weight) + second * weight
    elif kind == "checks":  # two stripe sets crossed, a third colour where they meet
        a, b = _stripes(height, width, rng)[..., None], _stripes(height, width, rng)[..., None]
        base = first * (1 - a) + second * a
        painted = (base * (1 - a * b) + _colour(rng) * a * b) * (0.75 + 0.25 * b)
    elif kind == "print":  # colourful blobs: prints, florals, paintings
        cells = int(rng.integers(2, 12))
        coarse = rng.uniform(0, 255, size=(cells, cells, 3)).astype(np.float32)
        painted = cv2.resize(coarse, (width, height), interpolation=cv2.INTER_CUBIC)
    else:  # speckle: carpet, granite, tweed
        noise = rng.normal(0, 1, size=(height, width)).astype(np.float32)
        weight = np.clip(0.5 + 0.35 * cv2.GaussianBlur(noise, (0, 0), 0.8), 0, 1)[..., None]
        painted = first * (1 - weight) + second * weight
    return np.clip(painted, 0, 255).astype(np.float32)


def retexture(
    rgb: np.ndarray, masks: Sequence[Mask], rng: np.random.Generator, chance: float
) -> np.ndarray:
    """The photo (uint8 RGB) with each object (its visible mask), with probability `chance`,
    given a random pattern in its own shading."""
    height, width = rgb.shape[:2]
    out = rgb.astype(np.float32)
    for encoded in masks:
        if rng.random() >= chance:
            continue
        mask = decode_mask(encoded, width, height)  # only the masks drawn for repainting
        rows, cols = np.flatnonzero(mask.any(axis=1)), np.flatnonzero(mask.any(axis=0))
        if len(rows) == 0:
            continue
        y0, y1, x0, x1 = rows[0], rows[-1] + 1, cols[0], cols[-1] + 1
        inside = mask[y0:y1, x0:x1]
        window = out[y0:y1, x0:x1]
        brightness = window.mean(axis=2)
        shade = np.clip(brightness / max(float(np.median(brightness[inside])), 1.0), 0.25, 1.6)
        painted = pattern(int(y1 - y0), int(x1 - x0), rng) * shade[..., None]
        strength = rng.uniform(0.6, 1.0)  # some of the rendered colour may stay
        window[inside] = (1 - strength) * window[inside] + strength * painted[inside]
    result: np.ndarray = np.clip(out, 0, 255).astype(np.uint8)
    return result

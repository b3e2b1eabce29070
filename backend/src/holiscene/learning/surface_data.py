"""Training data for the Surface Network: synthetic photos at the network's size with their
true surface-label maps (`geometry.surface_labels`), rendered on both cores and cached.

A set of seeds is cached as one compressed file (about 30 kB a scene) keyed by the seeds and
the label map's size, so changing either renders afresh and a killed run leaves no half file.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from multiprocessing import get_context
from pathlib import Path

import cv2
import numpy as np
from numpy.typing import NDArray

from ..geometry.surface_labels import INPUT_SIZE, MAP_SIZE, true_surface_map

CACHE_VERSION = f"v1-{INPUT_SIZE[0]}x{INPUT_SIZE[1]}-{MAP_SIZE[0]}x{MAP_SIZE[1]}"


@dataclass(frozen=True)
class SurfaceSet:
    images: NDArray[np.uint8]  # (N, H, W, 3) RGB at INPUT_SIZE
    labels: NDArray[np.uint8]  # (N, h, w) surface classes at MAP_SIZE

    def __len__(self) -> int:
        return len(self.labels)


def default_cache_dir() -> Path:
    return Path.home() / ".cache" / "holiscene" / "surface-maps" / CACHE_VERSION


def _render(seed: int) -> tuple[NDArray[np.uint8], NDArray[np.uint8]]:
    from ..synth.generate import synthesize  # the renderer is heavy; import in the worker

    scene = synthesize(seed)
    image = cv2.resize(scene.frame.rgb, INPUT_SIZE, interpolation=cv2.INTER_AREA)
    return image.astype(np.uint8), true_surface_map(scene.truth)


def surface_set(
    seeds: Sequence[int],
    cache_dir: Path | None = None,
    progress: Callable[[int, int], None] | None = None,
    workers: int = 2,
) -> SurfaceSet:
    """Photos and label maps for `seeds`, rendered once and then read from the cache."""
    cache = cache_dir or default_cache_dir()
    digest = hashlib.sha256(",".join(map(str, seeds)).encode()).hexdigest()[:16]
    path = cache / f"{digest}.npz"
    if path.exists():
        with np.load(path) as data:
            return SurfaceSet(data["images"], data["labels"])
    images, labels = [], []
    with get_context("spawn").Pool(workers) as pool:
        for done, (image, label) in enumerate(pool.imap(_render, seeds, chunksize=4), start=1):
            images.append(image)
            labels.append(label)
            if progress:
                progress(done, len(seeds))
    result = SurfaceSet(np.stack(images), np.stack(labels))
    cache.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp.npz")
    np.savez_compressed(tmp, images=result.images, labels=result.labels)
    tmp.replace(path)
    return result

"""Writing and reading NYU Depth v2's labelled file and support labels, without the pipeline.

    python benchmarks/bench_nyu.py [--images 20] [--objects 40] [--seed 0]

Scenes the size of NYU's photos (640x480), each with `--objects` rectangles of random sizes
(later ones partly in front of earlier ones) and a support each (on the floor or on an earlier
object), are written by `holiscene export --format nyu-supports`'s writer, then read back as
`holiscene import` reads them (inputs.datasets.dataset_items: the HDF5 arrays, the regions and
their masks, the support rows, the photo as a PNG). Figures: milliseconds per image for each
direction, the files' size per image, and how many objects and supports came back (all of
them, unless a rectangle ended up under 10 pixels or hidden).
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np
from holiscene.export.archive import ArchivedScene
from holiscene.export.nyu_supports import write_nyu_supports
from holiscene.inputs.datasets import dataset_items
from holiscene.segmentation.rle import encode_mask
from holiscene_schema import ImageInfo, Scene, SceneObject, SupportRelation
from PIL import Image

WIDTH, HEIGHT = 640, 480
CLASSES = ("chair", "table", "lamp", "box", "books", "pillow", "bag", "picture")


def scene(rng: np.random.Generator, number: int, objects: int, folder: Path) -> ArchivedScene:
    photo = folder / f"photo{number}.png"
    Image.fromarray(rng.integers(0, 255, (HEIGHT, WIDTH, 3), dtype=np.uint8)).save(photo)
    items, supports = [], []
    for index in range(objects):
        w, h = (int(v) for v in rng.integers(20, 160, 2))
        x, y = int(rng.integers(0, WIDTH - w)), int(rng.integers(0, HEIGHT - h))
        pixels = np.zeros((HEIGHT, WIDTH), dtype=bool)
        pixels[y : y + h, x : x + w] = True
        mask = encode_mask(pixels, "given")
        cls = CLASSES[index % len(CLASSES)]
        items.append(SceneObject(id=f"o{index}", cls=cls, bbox=[x, y, x + w, y + h], mask=mask))
        parent = "floor" if index == 0 or rng.random() < 0.5 else f"o{rng.integers(0, index)}"
        supports.append(
            SupportRelation(child=f"o{index}", parent=parent, type="below", source="manual")
        )
    stored = Scene(
        name=f"room_{number:04d}",
        image=ImageInfo(file="img.png", width=WIDTH, height=HEIGHT),
        objects=items,
        supports=supports,
    )
    return ArchivedScene(f"{number:012x}", 1, stored, photo, None)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--images", type=int, default=20)
    parser.add_argument("--objects", type=int, default=40)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    with tempfile.TemporaryDirectory(prefix="bench-nyu-") as tmp:
        folder = Path(tmp)
        scenes = [scene(rng, n, args.objects, folder) for n in range(args.images)]
        out = folder / "export"
        out.mkdir()
        began = time.perf_counter()
        write_nyu_supports(scenes, out)
        write_ms = (time.perf_counter() - began) * 1000 / args.images
        size = sum(f.stat().st_size for f in out.iterdir()) / args.images
        began = time.perf_counter()
        items = list(dataset_items(out))
        read_ms = (time.perf_counter() - began) * 1000 / args.images
    errors = [i.error for i in items if i.error]
    objects = sum(len(i.inputs.detections or []) for i in items if i.inputs)
    supports = sum(len(i.inputs.supports) for i in items if i.inputs)
    print(f"{args.images} images of {WIDTH}x{HEIGHT}, {args.objects} objects each")
    print(f"  write: {write_ms:.0f} ms per image, {size / 1e6:.2f} MB per image")
    print(f"  read:  {read_ms:.0f} ms per image")
    print(
        f"  back: {objects} of {args.images * args.objects} objects, {supports} supports, "
        f"{len(errors)} errors"
    )
    if errors:
        print("  first error:", errors[0])


if __name__ == "__main__":
    main()

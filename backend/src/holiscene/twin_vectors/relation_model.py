"""Test vectors for the Relation Network's preprocessing and model: `python -m
holiscene.twin_vectors.relation_model` writes shared_schema/vectors/relation_model.json.

The backend (holiscene.learning.preprocess + onnxruntime) and the browser
(frontend/src/inference/preprocess.ts + onnxruntime-web) turn a photo and its objects into the
contract's input tensors and run the same ONNX file; both are tested against these vectors.
Like room_fit.py this is a development tool that imports the backend.

Deterministic (one seeded generator). Each case is a small random RGB image with objects
(random blob masks in the contract's RLE, their boxes, NYU-40 classes); some cases add a
structural object (left out of the model's inputs, as samples.py does) and an object without
a mask (its box stands in for it). Expected: the input tensors from `relation_inputs`, rounded
to 7 significant digits, and `support_logits` from onnxruntime running the committed default
model, exactly (each float32 as its float64). The model file's sha256 is stored, so a test fails
when the vectors are stale relative to the model: run it again (`make relation-vectors`) after
changing the default model or the preprocessing.
"""

from __future__ import annotations

import argparse
import base64
import hashlib
import json
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from holiscene_schema.classes import NYU40_CLASSES, STRUCTURAL_CLASSES
from holiscene_schema.relation_model import INPUT_NAMES, OUTPUT_NAME
from holiscene_schema.scene import ImageInfo, Scene, SceneObject

from ..core.settings import REPO_ROOT
from ..learning.preprocess import relation_inputs
from ..learning.samples import object_masks
from ..segmentation.rle import encode_mask

RELATION_VECTORS = REPO_ROOT / "shared_schema" / "vectors" / "relation_model.json"
DEFAULT_MODEL = REPO_ROOT / "backend" / "src" / "holiscene" / "learning" / "default_model"
DEFAULT_MODEL_FILE = DEFAULT_MODEL / "model.onnx"
SEED = 20260505
INPUT_DIGITS = 7  # significant digits of the stored input tensors


@dataclass(frozen=True)
class CaseSpec:
    name: str
    width: int
    height: int
    objects: int  # objects with a mask
    box_only: int = 0  # objects whose box stands in for a mask
    structural: int = 0  # structural objects (not model inputs)
    palette: bool = False  # channel values on multiples of 51 (short decimals in the file)


# Images smaller and larger than the model's 128 x 128 and 64 x 64 grids, so the area resize
# meets cells of one pixel (repeated) and of several (uneven) pixels. Every image tensor has
# 49152 values whatever the photo's size; the small images draw from a palette, whose values
# (k / 5) print short, to keep the file small.
CASES = (
    CaseSpec("one-object-40x30", 40, 30, 1, palette=True),
    CaseSpec("three-objects-150x130", 150, 130, 2, box_only=1, structural=1),
    CaseSpec("twenty-objects-97x61", 97, 61, 18, box_only=2, palette=True),
)
OBJECT_CLASSES = tuple(c for c in NYU40_CLASSES if c not in STRUCTURAL_CLASSES)

Json = dict[str, Any]


def sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def random_mask(rng: np.random.Generator, width: int, height: int) -> np.ndarray:
    """A blob: an ellipse with ragged edges and a few holes, somewhere in (or over the edge of)
    the image; never empty."""
    ys, xs = np.mgrid[0:height, 0:width]
    while True:
        cx, cy = rng.uniform(-0.1, 1.1) * width, rng.uniform(-0.1, 1.1) * height
        rx, ry = rng.uniform(0.05, 0.45) * width, rng.uniform(0.05, 0.45) * height
        radius = ((xs - cx) / rx) ** 2 + ((ys - cy) / ry) ** 2
        mask: np.ndarray = radius + rng.normal(0.0, 0.15, (height, width)) < 1.0
        mask &= rng.random((height, width)) > 0.05
        if mask.sum() >= 4:
            return mask


def random_box(rng: np.random.Generator, width: int, height: int) -> list[float]:
    """A box in pixels on half-pixel steps, so rounding it to pixels meets ties."""
    x0, x1 = sorted(rng.uniform(0, width, 2))
    y0, y1 = sorted(rng.uniform(0, height, 2))
    return [round(v * 2) / 2 for v in (x0, y0, x1 + 1, y1 + 1)]


def make_scene(spec: CaseSpec, rng: np.random.Generator) -> tuple[Scene, np.ndarray]:
    if spec.palette:
        image = (rng.integers(0, 6, (spec.height, spec.width, 3)) * 51).astype(np.uint8)
    else:
        image = rng.integers(0, 256, (spec.height, spec.width, 3), dtype=np.uint8)
    objects: list[SceneObject] = []
    kinds = ["mask"] * spec.objects + ["box"] * spec.box_only + ["structural"] * spec.structural
    for i, kind in enumerate(rng.permutation(kinds)):
        if kind == "box":
            box = random_box(rng, spec.width, spec.height)
            cls, mask = str(rng.choice(OBJECT_CLASSES)), None
        else:
            bits = random_mask(rng, spec.width, spec.height)
            rows, cols = np.flatnonzero(bits.any(axis=1)), np.flatnonzero(bits.any(axis=0))
            # Detector boxes are not pixel-exact: a little jitter around the mask's extent.
            jitter = rng.uniform(-0.5, 0.5, 4)
            extent = [cols[0], rows[0], cols[-1] + 1, rows[-1] + 1]
            box = [round(float(e + j), 3) for e, j in zip(extent, jitter, strict=True)]
            cls = "floor" if kind == "structural" else str(rng.choice(OBJECT_CLASSES))
            mask = encode_mask(bits, "given")
        objects.append(
            SceneObject.model_validate({"id": f"o{i + 1}", "class": cls, "bbox": box, "mask": mask})
        )
    scene = Scene(
        name=spec.name,
        image=ImageInfo(file="img.png", width=spec.width, height=spec.height),
        objects=objects,
    )
    return scene, image


def model_inputs(scene: Scene, image: np.ndarray) -> tuple[list[str], dict[str, np.ndarray]]:
    """The model's object ids and input tensors, as samples.py makes them from a scene."""
    kept = [o for o in scene.objects if o.cls not in STRUCTURAL_CLASSES]
    masks = object_masks(scene.model_copy(update={"objects": kept}))
    inputs = relation_inputs(image, masks, [o.bbox for o in kept], [o.cls for o in kept])
    return [o.id for o in kept], inputs


def run_model(model: Path, inputs: dict[str, np.ndarray]) -> np.ndarray:
    import onnxruntime as ort

    session = ort.InferenceSession(str(model), providers=["CPUExecutionProvider"])
    logits: np.ndarray = session.run([OUTPUT_NAME], {k: inputs[k] for k in INPUT_NAMES})[0]
    return logits


def rounded(values: np.ndarray, digits: int = INPUT_DIGITS) -> list[float | int]:
    """Flat values to `digits` significant digits; whole numbers as integers."""
    out: list[float | int] = []
    for v in values.reshape(-1).tolist():
        r = float(f"{v:.{digits}g}")
        out.append(int(r) if r.is_integer() else r)
    return out


def exact_float32(values: np.ndarray) -> list[float]:
    """Flat float32 values, each exactly (the float64 of the same value)."""
    out: list[float] = values.astype(np.float32).astype(np.float64).reshape(-1).tolist()
    return out


def tensor(values: np.ndarray, flat: list[Any]) -> Json:
    return {"shape": list(values.shape), "data": flat}


def generate(model: Path) -> Json:
    rng = np.random.default_rng(SEED)
    cases: list[Json] = []
    for spec in CASES:
        scene, image = make_scene(spec, rng)
        ids, inputs = model_inputs(scene, image)
        logits = run_model(model, inputs)
        expected = {
            "image": tensor(inputs["image"], rounded(inputs["image"])),
            "masks": tensor(inputs["masks"], rounded(inputs["masks"])),
            "boxes": tensor(inputs["boxes"], rounded(inputs["boxes"])),
            "classes": tensor(inputs["classes"], inputs["classes"].tolist()),
            OUTPUT_NAME: tensor(logits, exact_float32(logits)),
        }
        cases.append(
            {
                "name": spec.name,
                "image": {
                    "width": spec.width,
                    "height": spec.height,
                    "rgb_base64": base64.b64encode(image.tobytes()).decode("ascii"),
                },
                "objects": [
                    o.model_dump(by_alias=True, include={"id", "cls", "bbox", "mask"})
                    for o in scene.objects
                ],
                "model_objects": ids,
                "expected": expected,
            }
        )
    return {
        "about": "Test vectors of the Relation Network: see "
        "holiscene/twin_vectors/relation_model.py",
        "seed": SEED,
        "model": {
            "path": model.resolve().relative_to(REPO_ROOT).as_posix()
            if model.resolve().is_relative_to(REPO_ROOT)
            else str(model),
            "sha256": sha256(model),
        },
        "tolerance": {"inputs": 1e-6, "support_logits": 1e-4},
        "cases": cases,
    }


def to_json(data: Json) -> str:
    """Indented JSON with each list of numbers (a flat tensor, a box, a run list) on one line."""
    text = json.dumps(data, indent=1)
    return (
        re.sub(r"\[\s+([^\[\]{}\"]*?)\s+\]", lambda m: "[" + re.sub(r",\s+", ",", m[1]) + "]", text)
        + "\n"
    )


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0] if __doc__ else None)
    parser.add_argument("--model", type=Path, default=DEFAULT_MODEL_FILE, help="ONNX file")
    parser.add_argument("-o", "--output", type=Path, default=RELATION_VECTORS)
    args = parser.parse_args(argv)
    args.output.parent.mkdir(exist_ok=True)
    args.output.write_text(to_json(generate(args.model)))
    print(f"wrote {args.output} ({args.output.stat().st_size // 1024} KiB) from {args.model}")


if __name__ == "__main__":
    main()

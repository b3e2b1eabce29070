"""What the scripts that convert a shipped model share: file digests and the photos to check on."""

from __future__ import annotations

import argparse
import hashlib
import json
import shutil
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import cv2
import numpy as np
from holiscene.learning.detector.runtime import preprocess
from tqdm import tqdm


def sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


# The photos a conversion is checked on by default: the shared real photos beside the repo.
DEFAULT_PHOTOS = Path(__file__).resolve().parents[2] / "shared" / "data" / "real"


def conversion_parser(description: str, out: Path) -> argparse.ArgumentParser:
    """The options every conversion script takes: --photos, --out, --tolerance."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--photos", type=Path, default=DEFAULT_PHOTOS)
    parser.add_argument("--out", type=Path, default=out)
    parser.add_argument("--tolerance", type=float, default=1e-3)
    return parser


def photo_paths(photos: Path) -> list[Path]:
    """The photos a conversion is checked on: */img.jpg (dataset folders) and *.jpg; none is an
    error."""
    found = sorted(p for p in photos.glob("*/img.jpg"))
    found += sorted(p for p in photos.glob("*.jpg"))
    if not found:
        raise SystemExit(f"no photos (*/img.jpg or *.jpg) in {photos} to check with")
    return found


def contract_inputs(photos: list[Path], desc: str) -> Iterator[tuple[str, np.ndarray]]:
    """Each photo's name in the check (p000, p001, ...) and the contract's input tensor."""
    for index, path in enumerate(tqdm(photos, desc=desc, unit="photo")):
        bgr = cv2.imread(str(path), cv2.IMREAD_COLOR)
        if bgr is None:
            raise SystemExit(f"cannot read photo {path}")
        yield f"p{index:03d}", preprocess(cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB))


def write_detector_dir(
    out: Path, model_file: Path, licence: Path, metadata: dict[str, Any]
) -> None:
    """A checked detector into `out`: model.onnx, the package's LICENSE, and metadata.json with
    the model file's digest."""
    out.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(model_file, out / "model.onnx")
    shutil.copyfile(licence, out / "LICENSE")
    metadata = {**metadata, "model_sha256": sha256(out / "model.onnx")}
    (out / "metadata.json").write_text(json.dumps(metadata, indent=2) + "\n")
    print(f"wrote {out / 'model.onnx'} ({(out / 'model.onnx').stat().st_size} bytes)")

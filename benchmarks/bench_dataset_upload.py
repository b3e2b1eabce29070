"""A COCO dataset uploaded as one .zip (POST /api/imports), without the pipeline.

    python benchmarks/bench_dataset_upload.py [--photos 100] [--objects 10] [--seed 0]

A zip of `--photos` random 640x480 PNG photos with `--objects` polygons each (a COCO
annotations.json beside images/) is posted to an in-process server on a fresh data
directory (SQLite), with run_pipeline false. Figures: the zip's size, the time until the
answer (upload, unpack, recognising the format), the time until the import job ended, photos
stored per second; then the same zip again, every photo skipped as imported before.
"""

from __future__ import annotations

import argparse
import io
import json
import tempfile
import time
import zipfile
from pathlib import Path
from typing import Any

import numpy as np
from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.core.settings import Settings
from PIL import Image

WIDTH, HEIGHT = 640, 480


def coco_zip(photos: int, objects: int, seed: int) -> bytes:
    rng = np.random.default_rng(seed)
    images: list[dict[str, Any]] = []
    annotations: list[dict[str, Any]] = []
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for number in range(1, photos + 1):
            pixels = rng.integers(0, 255, (HEIGHT, WIDTH, 3), dtype=np.uint8)
            png = io.BytesIO()
            Image.fromarray(pixels).save(png, "PNG")
            name = f"photo{number:04d}.png"
            archive.writestr(f"coco/images/{name}", png.getvalue())
            images.append({"id": number, "file_name": name, "width": WIDTH, "height": HEIGHT})
            for _ in range(objects):
                w, h = (int(v) for v in rng.integers(20, 160, 2))
                x, y = int(rng.integers(0, WIDTH - w)), int(rng.integers(0, HEIGHT - h))
                annotations.append(
                    {
                        "id": len(annotations) + 1,
                        "image_id": number,
                        "category_id": 1 + len(annotations) % 3,
                        "bbox": [x, y, w, h],
                        "segmentation": [[x, y, x + w, y, x + w, y + h, x, y + h]],
                    }
                )
        categories = [
            {"id": 1, "name": "chair"},
            {"id": 2, "name": "table"},
            {"id": 3, "name": "lamp"},
        ]
        coco = {"images": images, "annotations": annotations, "categories": categories}
        archive.writestr("coco/annotations.json", json.dumps(coco))
    return buffer.getvalue()


def timed_import(client: TestClient, data: bytes) -> tuple[float, float, dict[str, Any]]:
    """Seconds until the answer, seconds until the job ended, and the job."""
    start = time.perf_counter()
    answer = client.post(
        "/api/imports",
        files={"archive": ("coco.zip", data, "application/zip")},
        data={"run_pipeline": "false"},
    )
    answered = time.perf_counter() - start
    answer.raise_for_status()
    job: dict[str, Any] = answer.json()
    while job["status"] not in ("succeeded", "failed"):
        time.sleep(0.05)
        job = client.get(f"/api/imports/{job['id']}").json()
    return answered, time.perf_counter() - start, job


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--photos", type=int, default=100)
    parser.add_argument("--objects", type=int, default=10)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    data = coco_zip(args.photos, args.objects, args.seed)
    print(f"zip: {args.photos} photos, {args.objects} objects each, {len(data) / 1e6:.1f} MB")
    with tempfile.TemporaryDirectory() as tmp:
        settings = Settings(data_dir=Path(tmp) / "data", web_dir=Path(tmp) / "no-web")
        # The test client names the server 127.0.0.1, a name it answers to.
        with TestClient(create_app(settings), base_url="http://127.0.0.1") as client:
            for run in ("first upload", "same zip again"):
                answered, ended, job = timed_import(client, data)
                print(
                    f"{run}: answered in {answered:.2f} s, ended after {ended:.2f} s "
                    f"({len(job['imported'])} imported, {len(job['skipped'])} skipped, "
                    f"{len(job['errors'])} errors; {job['done'] / ended:.1f} photos/s)"
                )


if __name__ == "__main__":
    main()

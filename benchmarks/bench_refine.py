"""Time of the mask tools' refine call on 400x400 boxes of the real photos: `make bench-refine`.

    python benchmarks/bench_refine.py [--real DIR] [--repeat 3]

Per photo in ../shared/data/real, 400x400 boxes at the four corners and the centre (the photos
are 730x530 or 561x427, so every box fits), each with one foreground stroke through its middle
and one background stroke along its top, as a person refining a mask paints them. Two figures:
the cut alone (`refine_in_box` on a decoded photo), and the whole HTTP call
(`POST /api/scenes/{id}/mask-refine` through the app: validation, the cut, the mask's RLE and
JSON), and the cut's CPU time, which other work on the machine does not inflate. Target
(issue 19): under 300 ms.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.core.settings import Settings
from holiscene.inputs import load_photo
from holiscene.segmentation.refine import BrushStroke, refine_in_box

REPO = Path(__file__).resolve().parent.parent
REAL = REPO.parent / "shared" / "data" / "real"
SIDE = 400


def boxes(width: int, height: int) -> list[list[float]]:
    corners = [(0, 0), (width - SIDE, 0), (0, height - SIDE), (width - SIDE, height - SIDE)]
    corners.append(((width - SIDE) // 2, (height - SIDE) // 2))
    return [[float(x), float(y), float(x + SIDE), float(y + SIDE)] for x, y in corners]


def strokes(box: list[float]) -> tuple[BrushStroke, BrushStroke]:
    x1, y1, x2, y2 = box
    cx, cy = (x1 + x2) / 2, (y1 + y2) / 2
    foreground = BrushStroke(points=[[cx, cy - 80], [cx, cy + 80]], radius=8)
    background = BrushStroke(points=[[x1 + 20, y1 + 15], [x2 - 20, y1 + 15]], radius=6)
    return foreground, background


def as_json(stroke: BrushStroke) -> dict[str, object]:
    return {"points": [list(p) for p in stroke.points], "radius": stroke.radius}


def summary(name: str, milliseconds: list[float]) -> str:
    return (
        f"{name:<22} median {statistics.median(milliseconds):6.1f} ms   "
        f"95th {statistics.quantiles(milliseconds, n=20)[-1]:6.1f} ms   "
        f"max {max(milliseconds):6.1f} ms   ({len(milliseconds)} calls)"
    )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--real", type=Path, default=REAL)
    parser.add_argument("--repeat", type=int, default=3, help="calls per box")
    args = parser.parse_args()
    folders = sorted(p for p in args.real.iterdir() if (p / "img.jpg").is_file())
    if not folders:
        print(f"no photos in {args.real}", file=sys.stderr)
        return 1

    cut_ms: list[float] = []
    cpu_ms: list[float] = []  # the process's CPU time: what the cut costs whatever else runs
    for folder in folders:
        image = load_photo((folder / "img.jpg").read_bytes()).rgb
        for box in boxes(image.shape[1], image.shape[0]):
            foreground, background = strokes(box)
            for _ in range(args.repeat):
                start, start_cpu = time.perf_counter(), time.process_time()
                refine_in_box(image, box, [foreground], [background])
                cut_ms.append((time.perf_counter() - start) * 1000)
                cpu_ms.append((time.process_time() - start_cpu) * 1000)

    call_ms: list[float] = []
    with tempfile.TemporaryDirectory(prefix="bench-refine-") as scratch:
        settings = Settings(data_dir=Path(scratch) / "data", web_dir=Path(scratch) / "no-web")
        # A loopback Host, as a browser on this machine sends (the server refuses others).
        with TestClient(create_app(settings), base_url="http://127.0.0.1") as client:
            for folder in folders:
                photo = (folder / "img.jpg").read_bytes()
                files = {"image": ("img.jpg", photo, "image/jpeg")}
                imported = client.post("/api/scenes", files=files, data={"run_pipeline": "false"})
                imported.raise_for_status()
                scene = imported.json()["scene"]
                url = f"/api/scenes/{scene['id']}/mask-refine"
                for box in boxes(scene["width"], scene["height"]):
                    foreground, background = strokes(box)
                    body = {
                        "bbox": box,
                        "foreground": [as_json(foreground)],
                        "background": [as_json(background)],
                    }
                    for _ in range(args.repeat):
                        start = time.perf_counter()
                        client.post(url, json=body).raise_for_status()
                        call_ms.append((time.perf_counter() - start) * 1000)

    print(f"refine, {SIDE}x{SIDE} boxes on {len(folders)} real photos")
    print(summary("cut (refine_in_box)", cut_ms))
    print(summary("cut, CPU time", cpu_ms))
    print(summary("POST .../mask-refine", call_ms))
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""What the 3D view's depth points cost: GET /api/scenes/{id}/depth-points on synthetic rooms.

    OMP_NUM_THREADS=1 python benchmarks/bench_depth_points.py [--seed 5] [--count 3]

Each room (`holiscene synth`, with its depth.png) is uploaded with its depth to a server on a
temporary data directory (in-process, FastAPI's test client) and goes through the pipeline;
then its depth points are asked for: the first answer (the server loads the completion network
once), the median of five more, the answer's size and the points it holds.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import tempfile
import time
from pathlib import Path

from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.cli import main as holiscene
from holiscene.core.settings import Settings

FILES = (
    ("image", "img.png", "image/png"),
    ("cam_k", "cam_K.txt", "text/plain"),
    ("detections", "detections.json", "application/json"),
    ("depth", "depth.png", "image/png"),
)


def pipeline_scene(client: TestClient, room: Path) -> str:
    files = {field: (name, (room / name).read_bytes(), mime) for field, name, mime in FILES}
    imported = client.post("/api/scenes", files=files).json()
    job = imported["job"]["id"]
    while client.get(f"/api/jobs/{job}").json()["status"] not in ("succeeded", "failed"):
        time.sleep(0.2)
    scene_id: str = imported["scene"]["id"]
    return scene_id


def timed(client: TestClient, url: str) -> tuple[float, bytes]:
    start = time.perf_counter()
    response = client.get(url)
    response.raise_for_status()
    return time.perf_counter() - start, response.content


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seed", type=int, default=5)
    parser.add_argument("--count", type=int, default=3)
    args = parser.parse_args()
    work = Path(tempfile.mkdtemp(prefix="bench-depth-points-"))
    synth = ["synth", "--seed", str(args.seed), "--count", str(args.count), "-o", str(work)]
    if holiscene([*synth, "--workers", "1"]) != 0:
        return 1
    settings = Settings(data_dir=work / "data", web_dir=work / "no-web")
    print("| room | objects | with completed points | points | first | warm (median of 5) | size |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    with TestClient(create_app(settings), base_url="http://127.0.0.1") as client:
        for room in sorted(work.glob("synth-*")):
            url = f"/api/scenes/{pipeline_scene(client, room)}/depth-points"
            first, body = timed(client, url)
            warm = statistics.median(timed(client, url)[0] for _ in range(5))
            objects = json.loads(body)["objects"]
            points = sum(len(o["partial"]) + len(o["completed"] or []) for o in objects)
            completed = sum(o["completed"] is not None for o in objects)
            print(
                f"| {room.name} | {len(objects)} | {completed} | {points} | {first:.2f} s | "
                f"{warm:.2f} s | {len(body) / 1000:.0f} kB |"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())

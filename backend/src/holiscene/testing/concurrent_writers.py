"""Many annotators saving at once, through the HTTP API: the workload of the concurrent-writers
test (correctness on SQLite and PostgreSQL) and of benchmarks/bench_writers.py (latency).

Writers are real threads sharing one server (as browsers do): the test's app in this process
(a TestClient) or a `holiscene serve` of its own (an HTTP client). Writer i edits scene
i % scenes, so with fewer scenes than writers some of them race for the same revision: the
loser gets a 409, reloads and tries again, as the workbench does. Every request that saved is
timed; its author name (writer and save number) makes each save findable in the history.
"""

from __future__ import annotations

import json
import random
import statistics
import threading
import time
from dataclasses import dataclass, field
from typing import Any

import cv2
import numpy as np
from httpx2 import Client

_MAX_TRIES = 200  # per save: a writer that keeps losing the race fails the run, never hangs


@dataclass
class WriterRun:
    """What the writers did: every saved request's time, and each scene's saves by author."""

    writers: int
    pause_s: float = 0.0
    save_ms: list[float] = field(default_factory=list)
    # Each writer's first save, also in save_ms: the first on a scene takes it for annotation.
    first_save_ms: list[float] = field(default_factory=list)
    conflicts: int = 0
    saved: dict[str, set[str]] = field(default_factory=dict)
    errors: list[str] = field(default_factory=list)
    seconds: float = 0.0

    def percentile(self, fraction: float) -> float:
        ordered = sorted(self.save_ms)
        return ordered[min(len(ordered) - 1, round(fraction * (len(ordered) - 1)))]

    @property
    def requests(self) -> int:
        """Requests sent: the saves and the ones that lost a race and were sent again."""
        return len(self.save_ms) + self.conflicts

    @property
    def p50(self) -> float:
        return statistics.median(self.save_ms)

    @property
    def p95(self) -> float:
        return self.percentile(0.95)

    def describe(self) -> str:
        saves = len(self.save_ms)
        pace = f", {self.pause_s * 1000:.0f} ms pauses" if self.pause_s else ""
        first = self.first_save_ms
        firsts = (
            f"; first saves median {statistics.median(first):.0f} ms, max {max(first):.0f} ms"
            if first
            else ""
        )
        return (
            f"{self.writers} writer(s){pace}: {saves} saves in {self.seconds:.1f} s, "
            f"{self.conflicts} conflicts retried, save p50 {self.p50:.0f} ms, "
            f"p95 {self.p95:.0f} ms{firsts}"
        )


def small_photo() -> bytes:
    ok, data = cv2.imencode(".png", np.full((48, 64, 3), 180, np.uint8))
    if not ok:
        raise RuntimeError("could not encode a PNG")
    return bytes(data.tobytes())


def import_scenes(client: Client, count: int) -> list[str]:
    """`count` scenes with two detected objects each, imported without a pipeline run."""
    detections = json.dumps(
        [{"bbox": [4, 8, 30, 40], "class": "table"}, {"bbox": [34, 4, 60, 20], "class": "lamp"}]
    ).encode()
    scene_ids = []
    for number in range(count):
        response = client.post(
            "/api/scenes",
            files={
                "image": ("img.png", small_photo(), "image/png"),
                "detections": ("detections.json", detections, "application/json"),
            },
            data={"name": f"writers {number}", "run_pipeline": "false"},
        )
        if response.status_code != 201:
            raise RuntimeError(f"import failed: {response.status_code} {response.text}")
        scene_ids.append(response.json()["scene"]["id"])
    return scene_ids


def run_writers(
    client: Client,
    scene_ids: list[str],
    writers: int,
    saves_per_writer: int,
    pause_s: float = 0.0,
) -> WriterRun:
    """`writers` threads, each saving `saves_per_writer` edits to its scene, all started at
    once. `pause_s`: a writer's mean pause before each of its saves (a person works between
    two, and people do not all start in the same instant; uniform from 0 to twice that);
    0: back to back."""
    run = WriterRun(
        writers=writers, pause_s=pause_s, saved={scene_id: set() for scene_id in scene_ids}
    )
    lock = threading.Lock()  # guards `run`
    start = threading.Barrier(writers)

    def writer(number: int) -> None:
        scene_id = scene_ids[number % len(scene_ids)]
        loaded = client.get(f"/api/scenes/{scene_id}").json()
        objects = [o["id"] for o in loaded["scene"]["objects"]]
        base = loaded["revision"]
        pauses = random.Random(number)
        start.wait()
        for save in range(saves_per_writer):
            if pause_s:
                time.sleep(pauses.uniform(0, 2 * pause_s))
            author = f"w{number}-{save}"
            # Alternate the first object's supporter, so each save changes the scene.
            parent = "floor" if save % 2 == 0 else objects[1]
            edit = {"kind": "set_support", "child": objects[0], "parent": parent, "type": "below"}
            outcome = _save_until_stored(client, scene_id, base, author, edit)
            with lock:
                if isinstance(outcome, str):
                    run.errors.append(f"{author}: {outcome}")
                    return
                elapsed_ms, conflicts, base = outcome
                run.save_ms.append(elapsed_ms)
                if save == 0:
                    run.first_save_ms.append(elapsed_ms)
                run.conflicts += conflicts
                run.saved[scene_id].add(author)

    threads = [threading.Thread(target=writer, args=(n,)) for n in range(writers)]
    began = time.perf_counter()
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    run.seconds = time.perf_counter() - began
    return run


def _save_until_stored(
    client: Client, scene_id: str, base: int, author: str, edit: dict[str, Any]
) -> tuple[float, int, int] | str:
    """(milliseconds of the request that saved, conflicts before it, the revision it made),
    or what went wrong. `base`: the revision the writer has, as the workbench keeps the one
    its last save returned."""
    for conflicts in range(_MAX_TRIES):
        body = {"base_revision": base, "author": author, "edits": [edit]}
        began = time.perf_counter()
        response = client.post(f"/api/scenes/{scene_id}/edits", json=body)
        elapsed_ms = (time.perf_counter() - began) * 1000
        if response.status_code == 200:
            return elapsed_ms, conflicts, int(response.json()["revision"])
        if response.status_code != 409:
            return f"HTTP {response.status_code}: {response.text[:300]}"
        base = response.json()["detail"]["current_revision"]  # someone saved first: again
    return f"still conflicting after {_MAX_TRIES} tries"


def history_problems(client: Client, run: WriterRun) -> list[str]:
    """What the scenes' histories say against the run: every save exactly once, as an edit
    revision, and the revision numbers 1, 2, ... without a gap. Empty when all is well."""
    problems = list(run.errors)
    for scene_id, authors in run.saved.items():
        revisions = client.get(f"/api/scenes/{scene_id}/revisions").json()
        numbers = [r["number"] for r in revisions]
        if numbers != list(range(1, len(numbers) + 1)):
            problems.append(f"{scene_id}: revisions {numbers} are not 1..{len(numbers)}")
        edits = [r["author"] for r in revisions if r["kind"] == "edit"]
        if sorted(edits) != sorted(authors):
            problems.append(f"{scene_id}: {len(authors)} saves, history has edits {sorted(edits)}")
        current = client.get(f"/api/scenes/{scene_id}").json()["revision"]
        if numbers and current != numbers[-1]:
            problems.append(f"{scene_id}: at revision {current}, history ends at {numbers[-1]}")
    return problems

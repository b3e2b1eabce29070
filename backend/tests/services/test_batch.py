"""`holiscene batch` and `holiscene import --run-pipeline` on a real local Ray (127.0.0.1
only, two CPUs), started once for the module: Ray takes seconds to start on two cores.

The results are in the store as a pipeline job's, a second batch skips them, a scene that
fails is reported while the others finish, people's supports survive, and a failure on a
worker comes back as that scene's error."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path

import pytest
from holiscene.cli import main
from holiscene.core.data_dir_owner import batch_presence
from holiscene.core.settings import Settings
from holiscene.inputs import read_input_folder
from holiscene.services.batch import (
    BATCH_STARTER,
    STOPPED,
    new_batch_job,
    ray_runtime,
    run_batch,
)
from holiscene.services.workbench import Workbench, imported_scene
from holiscene.store.jobs import BATCH_ORPHANED, BATCH_STAGE
from holiscene.synth.generate import synthesize_to
from holiscene_schema import SupportRelation

ROOM_SEEDS = (500, 501, 502)  # rooms of a few objects each: quick through the pipeline


@pytest.fixture(scope="module")
def local_ray() -> Iterator[None]:
    with ray_runtime(None, 2):
        yield


@pytest.fixture(scope="module")
def rooms(tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    folder = tmp_path_factory.mktemp("rooms")
    return [synthesize_to(seed, folder) for seed in ROOM_SEEDS]


def _store(data_dir: Path, room: Path, supports: tuple[SupportRelation, ...] = ()) -> str:
    """Store the room's photo and boxes as scene revision 1, with `supports` as people's
    labels (as a dataset's are imported); no pipeline."""
    inputs = replace(read_input_folder(room), supports=supports)
    workbench = Workbench(Settings(data_dir=data_dir))
    try:
        return workbench.scenes.create(inputs, imported_scene(inputs, room.name), "import").id
    finally:
        workbench.close()


def _revisions(data_dir: Path, scene_id: str) -> list[str]:
    workbench = Workbench(Settings(data_dir=data_dir))
    try:
        return [r.kind for r in workbench.scenes.revisions(scene_id)]
    finally:
        workbench.close()


def test_a_batch_stores_results_keeps_people_supports_reports_failures_and_resumes(
    local_ray: None, rooms: list[Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    data = tmp_path / "data"
    labelled = SupportRelation(
        child="o1", parent="o0", type="behind", source="manual", author="dataset"
    )
    kept = _store(data, rooms[0], (labelled,))
    plain = _store(data, rooms[1])
    broken = _store(data, rooms[2])
    photo = data / "scenes" / broken / "img.png"
    good_photo = photo.read_bytes()
    photo.write_bytes(b"not a photo")

    assert main(["batch", "--data-dir", str(data)]) == 1
    out, err = capsys.readouterr()
    assert f"error: scene {broken} ({rooms[2].name}): " in err
    assert "2 scene(s) pre-annotated, 1 failed" in out
    for scene_id in (kept, plain):
        assert _revisions(data, scene_id) == ["import", "pipeline"]
    assert _revisions(data, broken) == ["import"]

    workbench = Workbench(Settings(data_dir=data))
    try:
        result = workbench.scenes.document(kept).scene
        assert result.objects and result.stages
        assert [s for s in result.supports if s.source == "manual"] == [labelled]
        jobs = workbench.jobs.latest_for_scenes()
        assert [jobs[s].status for s in (kept, plain, broken)] == ["succeeded"] * 2 + ["failed"]
        assert jobs[kept].result_revision == 2 and jobs[kept].started_by == "import"
    finally:
        workbench.close()

    # Run again: the done scenes are skipped, the broken one fails again.
    assert main(["batch", "--data-dir", str(data)]) == 1
    out, err = capsys.readouterr()
    assert "2 scene(s) already have a pipeline result, skipped" in out
    assert f"error: scene {broken}" in err
    assert _revisions(data, kept) == ["import", "pipeline"]

    photo.write_bytes(good_photo)  # mended: the next batch does it, and only it
    assert main(["batch", "--data-dir", str(data), "--scene", broken, "--scene", kept]) == 0
    out, _ = capsys.readouterr()
    assert "1 scene(s) pre-annotated, 0 failed" in out
    assert _revisions(data, broken) == ["import", "pipeline"]
    assert main(["batch", "--data-dir", str(data), "--scene", "0123456789ab"]) == 2


def test_import_with_run_pipeline_stores_every_photo_then_runs_the_batch(
    local_ray: None, rooms: list[Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    data = str(tmp_path / "data")
    command = ["import", *map(str, rooms[:2]), "--run-pipeline", "--workers", "2"]
    assert main([*command, "--data-dir", data]) == 0
    out, _ = capsys.readouterr()
    stored = [line for line in out.splitlines() if line.endswith(", stored")]
    assert len(stored) == 2
    assert out.index(stored[-1]) < out.index("2 scene(s) pre-annotated, 0 failed")
    scene_ids = [line.split("scene ")[1].split(",")[0] for line in stored]
    for scene_id in scene_ids:
        assert _revisions(tmp_path / "data", scene_id) == ["import", "pipeline"]

    assert main([*command, "--data-dir", data]) == 0  # all done: nothing is added or run
    out, _ = capsys.readouterr()
    assert out.count("imported before") == 2
    assert "2 scene(s) already have a pipeline result, skipped" in out
    assert "nothing to run" in out

    assert main(["import", str(rooms[2]), "--workers", "2", "--data-dir", data]) == 2
    assert main(["import", str(rooms[2]), "--no-pipeline", "--data-dir", data]) == 0
    out, _ = capsys.readouterr()
    (line,) = [line for line in out.splitlines() if line.endswith(", stored")]
    assert _revisions(tmp_path / "data", line.split("scene ")[1].split(",")[0]) == ["import"]


def test_a_failure_on_a_worker_is_reported_as_that_scenes_error(
    local_ray: None, rooms: list[Path], tmp_path: Path
) -> None:
    # The user's own shapes travel to the workers; a folder named after no class makes the
    # pipeline refuse to build there.
    models = tmp_path / "models"
    (models / "spaceship").mkdir(parents=True)
    (models / "spaceship" / "saucer.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    data = tmp_path / "data"
    scene_id = _store(data, rooms[0])
    workbench = Workbench(Settings(data_dir=data, models_dir=models))
    try:
        report = run_batch(workbench, [scene_id], workers=1)
        assert report.done == []
        error = report.failed[scene_id]
        assert error.startswith("PipelineBuildError: stage 'shapes_fit'"), error
        assert "'spaceship' is not an NYU-40 class" in error
        job = workbench.jobs.latest_for_scenes()[scene_id]
        assert job.status == "failed" and job.error == error
        assert [r.kind for r in workbench.scenes.revisions(scene_id)] == ["import"]
    finally:
        workbench.close()


def test_a_new_batch_takes_the_scenes_a_killed_batch_left_running(
    local_ray: None, rooms: list[Path], tmp_path: Path
) -> None:
    """A batch killed with SIGKILL runs no `finally`: its jobs stay running and would keep
    their scenes from every later batch. The next batch fails them, unless another batch
    still runs (they may be its own)."""
    data = tmp_path / "data"
    scene_id = _store(data, rooms[0])
    workbench = Workbench(Settings(data_dir=data))
    try:
        left = workbench.jobs.create(scene_id, 1, started_by=BATCH_STARTER)
        workbench.jobs.progress(left.id, BATCH_STAGE, 0.0)  # what the killed batch left
        with batch_presence(data):  # another batch runs: the job may be its own
            report = run_batch(workbench, [scene_id], workers=1)
        assert "already" in report.failed[scene_id], report.failed
        assert workbench.jobs.get(left.id).status == "running"
        report = run_batch(workbench, [scene_id], workers=1)
        assert report.done == [scene_id], report.failed
        orphan = workbench.jobs.get(left.id)
        assert (orphan.status, orphan.error) == ("failed", BATCH_ORPHANED)
        assert [r.kind for r in workbench.scenes.revisions(scene_id)] == ["import", "pipeline"]
    finally:
        workbench.close()


def test_a_new_batch_takes_a_scene_whose_job_a_killed_batch_made_but_never_sent(
    local_ray: None, rooms: list[Path], tmp_path: Path
) -> None:
    """Killed between making a scene's job and sending its photo to a worker, a batch leaves
    the job queued. It is the batch's from the start, so the next batch fails it too."""
    data = tmp_path / "data"
    scene_id = _store(data, rooms[1])
    workbench = Workbench(Settings(data_dir=data))
    try:
        left = new_batch_job(workbench, scene_id)  # where the killed batch stopped
        assert workbench.jobs.get(left.id).status == "queued"
        report = run_batch(workbench, [scene_id], workers=1)
        assert report.done == [scene_id], report.failed
        orphan = workbench.jobs.get(left.id)
        assert (orphan.status, orphan.error) == ("failed", BATCH_ORPHANED)
    finally:
        workbench.close()


def _descendants(pid: int) -> list[int]:
    children = [
        int(child)
        for task in Path(f"/proc/{pid}/task").iterdir()
        for child in (task / "children").read_text().split()
    ]
    return [c for child in children for c in (child, *_descendants(child))]


def _listening_addresses(pids: list[int]) -> set[str]:
    """The local addresses (hex, as /proc/net/tcp* writes them) the processes listen on."""
    inodes = set()
    for pid in pids:
        for fd in Path(f"/proc/{pid}/fd").iterdir():
            target = os.readlink(fd) if fd.is_symlink() else ""
            if target.startswith("socket:["):
                inodes.add(target[8:-1])
    found = set()
    for table in ("/proc/net/tcp", "/proc/net/tcp6"):
        for row in Path(table).read_text().splitlines()[1:]:
            fields = row.split()
            if fields[3] == "0A" and fields[9] in inodes:  # 0A: LISTEN
                found.add(fields[1].split(":")[0])
    return found


def test_the_local_ray_listens_on_127_0_0_1_only(local_ray: None) -> None:
    ray_processes = _descendants(os.getpid())
    addresses = _listening_addresses(ray_processes)
    assert addresses  # the GCS, the raylet and the workers listen
    # 127.0.0.1 as IPv4, and as IPv6's IPv4-mapped address.
    assert addresses <= {"0100007F", "0000000000000000FFFF00000100007F"}, addresses


def test_ray_is_not_loaded_by_the_server_or_the_other_commands() -> None:
    loaded = subprocess.run(
        [
            sys.executable,
            "-c",
            "import sys, holiscene.cli, holiscene.api.app, holiscene.services.workbench; "
            "print('ray' in sys.modules)",
        ],
        check=True,
        capture_output=True,
        text=True,
    )
    assert loaded.stdout.strip() == "False"


def test_a_batch_stopped_by_sigterm_fails_the_jobs_it_had_out(
    rooms: list[Path], tmp_path: Path
) -> None:
    """A process manager's SIGTERM stops a batch as Ctrl+C does: the photos out on workers
    are marked failed (a new run takes them), none is left "running"."""
    data = tmp_path / "data"
    for room in rooms:
        _store(data, room)
    batch = subprocess.Popen(
        [sys.executable, "-m", "holiscene.cli", "batch", "--data-dir", str(data), "--workers", "1"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    workbench = Workbench(Settings(data_dir=data))
    try:
        deadline = time.monotonic() + 120
        while not workbench.jobs.unfinished("pipeline") and time.monotonic() < deadline:
            assert batch.poll() is None, batch.communicate()
            time.sleep(0.02)
        assert workbench.jobs.unfinished("pipeline"), "the batch never started a job"
        batch.send_signal(signal.SIGTERM)
        _, err = batch.communicate(timeout=60)
        assert batch.returncode == 130, err
        assert "interrupted: run the batch again to go on" in err
        assert workbench.jobs.unfinished("pipeline") == []
        stopped = [j for j in workbench.jobs.latest_for_scenes().values() if j.status == "failed"]
        assert stopped and all(j.error == STOPPED for j in stopped)
    finally:
        if batch.poll() is None:
            batch.kill()
        workbench.close()

"""Who may start pipeline and placement jobs, and how many wait: not on a scene another
annotator holds (an admin may), one per scene at a time (two requests at once included, with
real threads), a bounded queue over all scenes, and every job says who started it.

The pipeline's one worker is kept busy by a real thread waiting on an event, so the jobs
queued meanwhile stay queued until the test lets it go."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator

import pytest
from holiscene.store.tables import JobRow
from holiscene_schema import Job
from httpx import Response
from sqlalchemy import select
from sqlalchemy.orm import Session

from ..stored_scenes import store_predicted_scene
from .at_once import at_once
from .conftest import Accounts

# Store and workflow behaviour: on both databases (databases.py).
pytestmark = pytest.mark.both_databases


@pytest.fixture()
def busy_worker(accounts: Accounts) -> Iterator[threading.Event]:
    release = threading.Event()
    accounts.workbench._executor.submit(release.wait, 120)
    try:
        yield release
    finally:
        release.set()


def _start(accounts: Accounts, who: str, scene_id: str, kind: str = "pipeline") -> Response:
    return accounts.client.post(
        f"/api/scenes/{scene_id}/{kind}-jobs", headers=accounts.headers(who)
    )


def _jobs_of(accounts: Accounts, scene_id: str) -> set[str]:
    """Ids of every job of the scene that is still waiting or running."""
    with Session(accounts.workbench.engine) as session:
        return set(
            session.scalars(
                select(JobRow.id).where(
                    JobRow.scene_id == scene_id, JobRow.status.in_(["queued", "running"])
                )
            )
        )


def test_jobs_on_a_scene_another_annotator_holds_are_refused(
    accounts: Accounts, busy_worker: threading.Event
) -> None:
    scene_id = store_predicted_scene(accounts.workbench.scenes)
    taken = accounts.client.post(f"/api/scenes/{scene_id}/take", headers=accounts.headers("ann"))
    assert taken.status_code == 200, taken.text
    revision = accounts.workbench.scenes.summary(scene_id).revision

    for kind in ("pipeline", "placement"):
        refused = _start(accounts, "bob", scene_id, kind)
        assert refused.status_code == 409, refused.text
        assert "ann is annotating this scene" in refused.json()["detail"]
    assert _jobs_of(accounts, scene_id) == set()
    assert accounts.workbench.scenes.summary(scene_id).revision == revision

    # An admin may (as they may take the scene over); the job says who asked.
    started = _start(accounts, "ada", scene_id)
    assert started.status_code == 202, started.text
    job = started.json()
    assert (job["status"], job["started_by"]) == ("queued", "ada")
    read = accounts.client.get(f"/api/jobs/{job['id']}", headers=accounts.headers("ann"))
    assert read.json()["started_by"] == "ada"


def test_a_job_that_waited_while_the_scene_was_taken_does_not_run(
    accounts: Accounts, busy_worker: threading.Event
) -> None:
    scene_id = store_predicted_scene(accounts.workbench.scenes)
    queued = _start(accounts, "bob", scene_id)  # nobody holds it yet: allowed
    assert queued.status_code == 202, queued.text
    taken = accounts.client.post(f"/api/scenes/{scene_id}/take", headers=accounts.headers("ann"))
    assert taken.status_code == 200, taken.text
    revision = accounts.workbench.scenes.summary(scene_id).revision

    busy_worker.set()
    job = _wait_finished(accounts, queued.json()["id"])
    assert job.status == "failed"
    assert job.error is not None and "ann is annotating this scene" in job.error
    assert accounts.workbench.scenes.summary(scene_id).revision == revision


def test_one_job_per_scene_at_a_time(accounts: Accounts, busy_worker: threading.Event) -> None:
    scene_id = store_predicted_scene(accounts.workbench.scenes)
    first = _start(accounts, "ann", scene_id)
    assert first.status_code == 202, first.text
    first_id = first.json()["id"]
    again = _start(accounts, "ann", scene_id)
    assert again.status_code == 409, again.text
    assert first_id in again.json()["detail"]
    assert _jobs_of(accounts, scene_id) == {first_id}


def test_two_requests_at_once_queue_one_job(
    accounts: Accounts, busy_worker: threading.Event
) -> None:
    for _ in range(8):
        scene_id = store_predicted_scene(accounts.workbench.scenes)
        answers = at_once(accounts, scene_id, (_start, "ann"), (_start, "bob"))
        codes = sorted(answer.status_code for answer in answers)
        assert codes == [202, 409], [answer.text for answer in answers]
        winner = next(a for a in answers if a.status_code == 202).json()
        assert _jobs_of(accounts, scene_id) == {winner["id"]}


def test_the_job_queue_is_bounded(accounts: Accounts, busy_worker: threading.Event) -> None:
    accounts.workbench.settings.max_queued_jobs = 3
    scenes = [store_predicted_scene(accounts.workbench.scenes) for _ in range(4)]
    for scene_id in scenes[:3]:
        assert _start(accounts, "ann", scene_id).status_code == 202
    full = _start(accounts, "ann", scenes[3])
    assert full.status_code == 503, full.text
    assert "3 pipeline jobs are queued or running" in full.json()["detail"]
    assert _jobs_of(accounts, scenes[3]) == set()

    busy_worker.set()  # the queue drains; there is room again
    for scene_id in scenes[:3]:
        for job_id in _jobs_of(accounts, scene_id):
            _wait_finished(accounts, job_id)
    assert _start(accounts, "ann", scenes[3]).status_code == 202


def _wait_finished(accounts: Accounts, job_id: str, timeout: float = 120.0) -> Job:
    deadline = time.monotonic() + timeout
    while (job := accounts.workbench.jobs.get(job_id)).status in ("queued", "running"):
        assert time.monotonic() < deadline, f"job {job_id} did not finish in {timeout} s"
        time.sleep(0.05)
    return job

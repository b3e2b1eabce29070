"""Twenty annotators saving at once through the API, on SQLite and on PostgreSQL: every save
lands in the history exactly once and the revisions stay contiguous. The save latencies are
printed; the latency target is checked by `make bench-writers`, not here (a shared test
machine's timings prove nothing)."""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient
from holiscene.testing.concurrent_writers import history_problems, import_scenes, run_writers

pytestmark = pytest.mark.both_databases

WRITERS = 20
SCENES = 8  # fewer than writers: two or three writers race on each scene
SAVES = 5


def test_twenty_writers_keep_every_save_and_contiguous_revisions(
    client: TestClient, database_url: str | None, capsys: pytest.CaptureFixture[str]
) -> None:
    scene_ids = import_scenes(client, SCENES)
    run = run_writers(client, scene_ids, WRITERS, SAVES)
    database = "PostgreSQL" if database_url else "SQLite"
    with capsys.disabled():
        print(f"\n{database}: {run.describe()}")
    assert history_problems(client, run) == []
    assert len(run.save_ms) == WRITERS * SAVES
    assert run.conflicts > 0  # the writers really raced for revisions

"""Running batches on a data directory, told by their lock files (core.data_dir_owner)."""

from __future__ import annotations

import signal
import subprocess
import sys
from pathlib import Path

from holiscene.core.data_dir_owner import BATCH_FOLDER, batch_presence, running_batches

HOLD = (
    "import sys, time\n"
    "from pathlib import Path\n"
    "from holiscene.core.data_dir_owner import batch_presence\n"
    "with batch_presence(Path(sys.argv[1])) as others:\n"
    "    print(others, flush=True)\n"
    "    time.sleep(120)\n"
)


def test_a_batch_is_counted_while_it_runs_and_not_after(tmp_path: Path) -> None:
    assert running_batches(tmp_path) == 0
    with batch_presence(tmp_path) as others:
        assert others == 0
        assert running_batches(tmp_path) == 1
        with batch_presence(tmp_path) as others_then:
            assert others_then == 1
            assert running_batches(tmp_path) == 2
        assert running_batches(tmp_path) == 1
    assert running_batches(tmp_path) == 0
    assert list((tmp_path / BATCH_FOLDER).iterdir()) == []


def test_a_batch_killed_with_sigkill_is_not_counted_and_its_file_goes(tmp_path: Path) -> None:
    batch = subprocess.Popen(
        [sys.executable, "-c", HOLD, str(tmp_path)], stdout=subprocess.PIPE, text=True
    )
    try:
        assert batch.stdout is not None and batch.stdout.readline().strip() == "0"
        assert running_batches(tmp_path) == 1
        with batch_presence(tmp_path) as others:
            assert others == 1
        batch.send_signal(signal.SIGKILL)  # no finally runs: its lock file stays behind
        batch.wait(timeout=30)
        assert len(list((tmp_path / BATCH_FOLDER).glob("*.lock"))) == 1
        assert running_batches(tmp_path) == 0
        assert list((tmp_path / BATCH_FOLDER).glob("*.lock")) == []
    finally:
        if batch.poll() is None:
            batch.kill()

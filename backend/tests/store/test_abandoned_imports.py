"""An import killed midway (kill -9, a real process) leaves its staging folder under
scenes/; the next server start removes it, and leaves alone a folder another process is
still filling."""

from __future__ import annotations

import signal
import subprocess
import sys
import textwrap
from pathlib import Path

from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.core.settings import Settings

# What an import does first: a staging folder, filled, renamed into place at the end. This
# one never ends: it says where its folder is and waits to be killed.
_FILLING = textwrap.dedent(
    """
    import sys, time
    from pathlib import Path
    from holiscene.store.files import SceneFiles

    with SceneFiles(Path(sys.argv[1])).new_folder(sys.argv[2]) as staging:
        (staging / "img.png").write_bytes(b"half a photo")
        print(staging, flush=True)
        time.sleep(600)
    """
)


def _start_import(data_dir: Path, scene_id: str) -> tuple[subprocess.Popen[str], Path]:
    process = subprocess.Popen(
        [sys.executable, "-c", _FILLING, str(data_dir), scene_id],
        stdout=subprocess.PIPE,
        text=True,
    )
    assert process.stdout is not None
    staging = Path(process.stdout.readline().strip())
    assert staging.is_dir() and staging.parent == data_dir / "scenes", staging
    return process, staging


def _start_server(settings: Settings) -> None:
    with TestClient(create_app(settings)) as client:
        assert client.get("/api/health").status_code == 200


def test_start_up_removes_the_staging_folder_of_a_dead_import(settings: Settings) -> None:
    killed, abandoned = _start_import(settings.data_dir, "deadbeef0001")
    alive, filling = _start_import(settings.data_dir, "cafe00000002")
    try:
        killed.send_signal(signal.SIGKILL)
        killed.wait(timeout=30)
        assert abandoned.is_dir()  # what the kill left behind

        _start_server(settings)
        assert not abandoned.exists()
        assert (filling / "img.png").read_bytes() == b"half a photo"  # still being filled
    finally:
        alive.kill()
        alive.wait(timeout=30)

    _start_server(settings)
    assert not filling.exists()
    assert not list((settings.data_dir / "scenes").iterdir())

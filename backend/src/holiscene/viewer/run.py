"""`holiscene view`: one viewer on 127.0.0.1 until Ctrl+C (or SIGTERM)."""

from __future__ import annotations

import sys
import time
from pathlib import Path

from ..core.interrupts import stop_signals_interrupt
from ..core.settings import Settings
from .server import start_viewer, viewer_url
from .sources import load_scene_argument


def serve_until_interrupted(scene: str, settings: Settings, port: int, photo: Path | None) -> int:
    data = load_scene_argument(scene, settings, photo)
    server, _viewer = start_viewer(data, port)
    url = viewer_url(server)
    busy = f" (port {port} was busy)" if port not in (0, server.get_port()) else ""
    # Ctrl+C and a process manager's SIGTERM both end the viewer cleanly. The address is
    # printed inside the handler: whoever reads it may stop the viewer at once.
    try:
        with stop_signals_interrupt():
            print(f"viewer of {data.origin}: {url}{busy}", flush=True)
            print("press Ctrl+C to stop", file=sys.stderr, flush=True)
            while True:
                time.sleep(3600)
    except KeyboardInterrupt:
        pass
    finally:
        server.stop()
    return 0

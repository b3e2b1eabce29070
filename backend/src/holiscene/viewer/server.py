"""Running viewers: one viser server on 127.0.0.1 for the CLI, and a pool for the web app.

Viewers only ever bind the loopback address: the viewer has no accounts and shows the
user's photos. The web app's pool keeps one viewer per scene (reused; rebuilt in place when
the scene's revision changed) and at most `max_viewers` of them, stopping the least recently
opened one beyond that.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable
from dataclasses import dataclass

import viser

from .scene_viewer import SceneViewer
from .sources import ViewerInput

HOST = "127.0.0.1"


def start_viewer(data: ViewerInput, port: int) -> tuple[viser.ViserServer, SceneViewer]:
    """A viser server on 127.0.0.1 showing `data`. Port 0 takes any free port; a busy port
    makes viser try the next ones, so read the port from `server.get_port()`."""
    server = viser.ViserServer(host=HOST, port=port, label=data.scene.name, verbose=False)
    try:
        return server, SceneViewer(server, data)
    except BaseException:
        server.stop()
        raise


def viewer_url(server: viser.ViserServer) -> str:
    return f"http://{HOST}:{server.get_port()}"


@dataclass
class _Running:
    server: viser.ViserServer
    viewer: SceneViewer
    version: Hashable


class ViewerPool:
    """Viewers by key (a scene id), each on its own free port."""

    def __init__(self, max_viewers: int = 4) -> None:
        if max_viewers < 1:
            raise ValueError("max_viewers must be at least 1")
        self.max_viewers = max_viewers
        self._running: OrderedDict[str, _Running] = OrderedDict()
        self._lock = threading.Lock()

    def open(self, key: str, version: Hashable, load: Callable[[], ViewerInput]) -> str:
        """The URL of the viewer for `key`, started (or rebuilt, when `version` differs from
        what it shows) with `load()`."""
        with self._lock:
            running = self._running.get(key)
            if running is not None:
                self._running.move_to_end(key)
                if running.version != version:
                    running.viewer.rebuild(load())
                    running.version = version
                return viewer_url(running.server)
            data = load()
            while len(self._running) >= self.max_viewers:
                _, oldest = self._running.popitem(last=False)
                oldest.server.stop()
            server, viewer = start_viewer(data, port=0)
            self._running[key] = _Running(server, viewer, version)
            return viewer_url(server)

    def get(self, key: str) -> SceneViewer | None:
        with self._lock:
            running = self._running.get(key)
            return running.viewer if running is not None else None

    def keys(self) -> list[str]:
        with self._lock:
            return list(self._running)

    def close(self) -> None:
        with self._lock:
            while self._running:
                _, running = self._running.popitem()
                running.server.stop()

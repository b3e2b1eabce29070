"""Request bodies are capped before they are read: a declared length over the cap is
refused at once, a chunked body when it passes the cap; photo imports have a larger cap."""

from __future__ import annotations

import io
import socket
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
import uvicorn
from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.core.settings import Settings
from PIL import Image


@pytest.fixture()
def small_limits(tmp_path: Path) -> Settings:
    return Settings(
        data_dir=tmp_path / "data", web_dir=tmp_path / "no-web", max_request_mb=1, max_upload_mb=4
    )


@pytest.fixture()
def live_port(small_limits: Settings) -> Iterator[int]:
    """The app served by uvicorn on a free loopback port, as `holiscene serve` does."""
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    config = uvicorn.Config(
        create_app(small_limits), host="127.0.0.1", port=port, log_level="warning"
    )
    server = uvicorn.Server(config)
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 30
    while not server.started:
        assert time.monotonic() < deadline, "the server did not start"
        time.sleep(0.05)
    yield port
    server.should_exit = True
    thread.join(timeout=10)


def _status_line(conn: socket.socket) -> str:
    conn.settimeout(10)
    answer = b""
    while b"\r\n\r\n" not in answer:
        data = conn.recv(65536)
        if not data:
            break
        answer += data
    return answer.split(b"\r\n", 1)[0].decode()


def test_a_declared_length_over_the_cap_is_refused_unread(live_port: int) -> None:
    # No login, no body sent at all: the answer cannot have waited for 200 MB to arrive.
    with socket.create_connection(("127.0.0.1", live_port)) as conn:
        conn.sendall(
            b"POST /api/scenes/nosuch/edits HTTP/1.1\r\n"
            + f"Host: 127.0.0.1:{live_port}\r\n".encode()
            + b"Content-Type: application/json\r\nContent-Length: 200000000\r\n\r\n"
        )
        started = time.monotonic()
        assert _status_line(conn) == "HTTP/1.1 413 Request Entity Too Large"
        assert time.monotonic() - started < 5


def test_a_chunked_body_is_cut_off_at_the_cap(live_port: int) -> None:
    chunk = b"[" * 65536
    with socket.create_connection(("127.0.0.1", live_port)) as conn:
        conn.sendall(
            b"POST /api/scenes/nosuch/edits HTTP/1.1\r\n"
            + f"Host: 127.0.0.1:{live_port}\r\n".encode()
            + b"Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n"
        )
        sent = 0
        try:  # 8 MB, 8 times the cap, never finished: only a cut-off answers
            while sent < 8 * 1024 * 1024:
                conn.sendall(b"%x\r\n%s\r\n" % (len(chunk), chunk))
                sent += len(chunk)
        except (BrokenPipeError, ConnectionResetError):
            pass  # the server closed the connection after answering
        assert _status_line(conn) == "HTTP/1.1 413 Request Entity Too Large"


def _noise_png(width: int, height: int) -> bytes:
    pixels = np.random.default_rng(0).integers(0, 256, (height, width, 3), dtype=np.uint8)
    out = io.BytesIO()
    Image.fromarray(pixels).save(out, format="PNG", compress_level=0)
    return out.getvalue()


def test_photo_imports_may_be_larger_than_other_requests(small_limits: Settings) -> None:
    photo = _noise_png(1000, 700)  # 2.1 MB: over the 1 MB cap, under the import's
    assert 1024 * 1024 < len(photo) < 4 * 1024 * 1024
    with TestClient(create_app(small_limits)) as client:
        imported = client.post(
            "/api/scenes",
            files={"image": ("room.png", photo, "image/png")},
            data={"run_pipeline": "false"},
        )
        assert imported.status_code == 201, imported.text
        scene_id = imported.json()["scene"]["id"]

        edit = {"kind": "remove_support", "child": "x" * (2 * 1024 * 1024)}
        body = {"base_revision": 1, "author": "ann", "edits": [edit]}
        too_large = client.post(f"/api/scenes/{scene_id}/edits", json=body)
        assert too_large.status_code == 413
        assert (
            too_large.json()["detail"] == "the request body is larger than the 1 MB accepted here"
        )

        huge = client.post(
            "/api/scenes",
            files={"image": ("room.png", b"\0" * (15 * 1024 * 1024), "image/png")},
        )
        assert huge.status_code == 413 and "14 MB" in huge.json()["detail"]
        assert len(client.get("/api/scenes").json()) == 1

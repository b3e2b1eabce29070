"""Depth uploaded with a photo (POST /api/scenes `depth`, `depth_units`): a 16-bit PNG of
millimetres, SUN RGB-D's rotated bits or a .npy of float metres, stored as the scene's
depth.png and served back raw and as a colour preview; anything that cannot be this photo's
depth is refused with a message, and nothing is stored."""

from __future__ import annotations

import io
from pathlib import Path
from typing import Any

import cv2
import numpy as np
import pytest
from fastapi.testclient import TestClient
from holiscene.core.settings import Settings

from ...conftest import wait_for_job


def _png(array: np.ndarray) -> bytes:
    ok, data = cv2.imencode(".png", array)
    assert ok
    return bytes(data.tobytes())


def _npy(array: np.ndarray) -> bytes:
    buffer = io.BytesIO()
    np.save(buffer, array, allow_pickle=False)
    return buffer.getvalue()


def _post(
    client: TestClient, folder: Path, depth: bytes | None, name: str = "depth.png", **form: str
) -> Any:
    files = {
        "image": ("img.png", (folder / "img.png").read_bytes(), "image/png"),
        "cam_k": ("cam_K.txt", (folder / "cam_K.txt").read_bytes(), "text/plain"),
    }
    if depth is not None:
        files["depth"] = (name, depth, "application/octet-stream")
    return client.post("/api/scenes", files=files, data={"run_pipeline": "false", **form})


def _stored_mm(client: TestClient, scene_id: str) -> np.ndarray:
    response = client.get(f"/api/scenes/{scene_id}/depth.png")
    assert response.status_code == 200 and response.headers["content-type"] == "image/png"
    decoded = cv2.imdecode(np.frombuffer(response.content, np.uint8), cv2.IMREAD_UNCHANGED)
    assert decoded.dtype == np.uint16
    return decoded


def _true_mm(folder: Path) -> np.ndarray:
    return cv2.imread(str(folder / "depth.png"), cv2.IMREAD_UNCHANGED)


def test_png_of_millimetres_is_stored_and_served(
    client: TestClient, synthetic_folder: Path
) -> None:
    true_mm = _true_mm(synthetic_folder)
    true_mm[:20, :30] = 0  # a patch the sensor did not see
    response = _post(client, synthetic_folder, _png(true_mm))
    assert response.status_code == 201, response.text
    scene_id = response.json()["scene"]["id"]
    scene = client.get(f"/api/scenes/{scene_id}").json()["scene"]
    assert scene["depth"] == {"file": "depth.png", "metres_per_unit": 0.001}
    assert (_stored_mm(client, scene_id) == true_mm).all()

    preview = client.get(f"/api/scenes/{scene_id}/depth-preview.png")
    assert preview.status_code == 200
    rgba = cv2.imdecode(np.frombuffer(preview.content, np.uint8), cv2.IMREAD_UNCHANGED)
    assert rgba.shape == (*true_mm.shape, 4)
    assert (rgba[:20, :30, 3] == 0).all() and (rgba[100:, 100:, 3] == 255).all()
    # Near and far get other colours.
    near = np.unravel_index(np.argmin(np.where(true_mm > 0, true_mm, 65535)), true_mm.shape)
    far = np.unravel_index(np.argmax(true_mm), true_mm.shape)
    assert (rgba[near][:3] != rgba[far][:3]).any()


def test_sun_rgbd_bits_and_npy_metres_give_the_same_depth(
    client: TestClient, synthetic_folder: Path
) -> None:
    true_mm = _true_mm(synthetic_folder)
    rotated = np.bitwise_or(np.left_shift(true_mm, 3), np.right_shift(true_mm, 13))
    sun = _post(client, synthetic_folder, _png(rotated), depth_units="sunrgbd")
    assert sun.status_code == 201, sun.text
    assert (_stored_mm(client, sun.json()["scene"]["id"]) == true_mm).all()

    metres = (true_mm * 0.001).astype(np.float64)
    metres[0, :] = np.nan  # NaN pixels of a float file are pixels without depth
    npy = _post(client, synthetic_folder, _npy(metres), name="depth.npy")
    assert npy.status_code == 201, npy.text
    stored = _stored_mm(client, npy.json()["scene"]["id"])
    assert (stored[0] == 0).all() and (stored[1:] == true_mm[1:]).all()


def test_a_pipeline_job_keeps_the_depth(client: TestClient, synthetic_folder: Path) -> None:
    depth = (synthetic_folder / "depth.png").read_bytes()
    response = _post(client, synthetic_folder, depth, run_pipeline="true")
    assert response.status_code == 201, response.text
    job = wait_for_job(client, response.json()["job"]["id"], timeout=120)
    assert job["status"] == "succeeded", job
    doc = client.get(f"/api/scenes/{response.json()['scene']['id']}").json()
    assert doc["revision"] == 2 and doc["scene"]["depth"]["file"] == "depth.png"


def _all_nan(shape: tuple[int, int]) -> np.ndarray:
    return np.full(shape, np.nan, np.float32)


# Each bad file: how to make it from the photo's (height, width), its name, the units sent
# (None: not sent), and what the refusal says.
BAD_DEPTH: dict[str, tuple[Any, str, str | None, str]] = {
    "another size": (
        lambda hw: _png(np.full((hw[0], hw[1] - 1), 2000, np.uint16)),
        "depth.png",
        None,
        "639x480 pixels, the photo is 640x480",
    ),
    "all zeros": (
        lambda hw: _png(np.zeros(hw, np.uint16)),
        "depth.png",
        None,
        "holds no depth",
    ),
    "8-bit": (lambda hw: _png(np.full(hw, 90, np.uint8)), "depth.png", None, "8-bit image"),
    "colour": (
        lambda hw: _png(np.full((*hw, 3), 2000, np.uint16)),
        "depth.png",
        None,
        "3 channels",
    ),
    "NaN in a float file": (
        lambda hw: _npy(_all_nan(hw)),
        "depth.npy",
        None,
        "holds no depth (every pixel is 0, NaN or out of range)",
    ),
    "a float file of millimetres": (
        lambda hw: _npy(np.full(hw, 2500.0, np.float32)),
        "depth.npy",
        None,
        "holds metres",
    ),
    "integers in a .npy": (
        lambda hw: _npy(np.full(hw, 2500, np.uint16)),
        "depth.npy",
        None,
        "must hold float metres",
    ),
    "a .npy of another size": (
        lambda hw: _npy(np.full((10, 10), 2.0, np.float32)),
        "depth.npy",
        None,
        "10x10 pixels",
    ),
    "a truncated .npy": (
        lambda hw: _npy(np.full(hw, 2.0, np.float32))[:1000],
        "depth.npy",
        None,
        "cut short",
    ),
    "sunrgbd units on a .npy": (
        lambda hw: _npy(np.full(hw, 2.0, np.float32)),
        "depth.npy",
        "sunrgbd",
        "are for a 16-bit PNG",
    ),
    "metres units on a PNG": (
        lambda hw: _png(np.full(hw, 2000, np.uint16)),
        "depth.png",
        "m",
        "is not one",
    ),
    "not an image": (lambda hw: b"GIF89a...", "depth.gif", None, "not a PNG image"),
}


@pytest.mark.parametrize("case", sorted(BAD_DEPTH))
def test_bad_depth_is_refused_and_nothing_is_stored(
    client: TestClient, settings: Settings, synthetic_folder: Path, case: str
) -> None:
    make, name, units, message = BAD_DEPTH[case]
    form = {"depth_units": units} if units else {}
    response = _post(client, synthetic_folder, make((480, 640)), name=name, **form)
    assert response.status_code == 422, response.text
    assert message in response.json()["detail"]
    assert client.get("/api/scenes").json() == []
    assert list((settings.data_dir / "scenes").iterdir()) == []


def test_units_without_a_file_and_unknown_units_are_refused(
    client: TestClient, synthetic_folder: Path
) -> None:
    alone = _post(client, synthetic_folder, None, depth_units="mm")
    assert alone.status_code == 422 and "without a depth file" in alone.json()["detail"]
    depth = (synthetic_folder / "depth.png").read_bytes()
    unknown = _post(client, synthetic_folder, depth, depth_units="inches")
    assert unknown.status_code == 422 and "depth_units" in str(unknown.json()["detail"])
    assert client.get("/api/scenes").json() == []


def test_a_scene_without_depth_has_none_to_serve(
    client: TestClient, synthetic_folder: Path
) -> None:
    response = _post(client, synthetic_folder, None)
    scene_id = response.json()["scene"]["id"]
    assert client.get(f"/api/scenes/{scene_id}").json()["scene"]["depth"] is None
    for file in ("depth.png", "depth-preview.png"):
        missing = client.get(f"/api/scenes/{scene_id}/{file}")
        assert missing.status_code == 404 and "has no depth" in missing.json()["detail"]
    assert client.get("/api/scenes/nope/depth.png").status_code == 404

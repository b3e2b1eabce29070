"""POST /api/scenes/{id}/mask-refine on the real t3d-5 photo (730x530): a mask, nothing stored."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient
from holiscene.segmentation.rle import decode_mask
from holiscene_schema import Mask

from ...conftest import upload

BOX = [400.0, 200.0, 580.0, 360.0]


@pytest.fixture()
def scene_id(client: TestClient, t3d5: Path) -> str:
    result = upload(client, t3d5, name="t3d-5", run_pipeline="false")
    return str(result["scene"]["id"])


def _refine(client: TestClient, scene_id: str, **body: Any) -> Any:
    return client.post(f"/api/scenes/{scene_id}/mask-refine", json=body)


def test_refine_answers_a_manual_mask_in_the_box_and_stores_nothing(
    client: TestClient, scene_id: str
) -> None:
    before = client.get(f"/api/scenes/{scene_id}/revisions").json()
    response = _refine(
        client,
        scene_id,
        bbox=BOX,
        foreground=[{"points": [[412, 215], [412, 345]], "radius": 4}],
        background=[{"points": [[450, 290], [540, 290]], "radius": 5}],
    )
    assert response.status_code == 200, response.text
    result = response.json()
    assert result["mask"]["source"] == "manual"
    assert 0 <= result["milliseconds"] < 5000
    pixels = decode_mask(Mask.model_validate(result["mask"]), 730, 530)
    ys, xs = np.nonzero(pixels)
    assert xs.min() >= 400 and xs.max() < 580 and ys.min() >= 200 and ys.max() < 360
    assert pixels[280:300, 412].all() and not pixels[290, 450:540].any()
    assert client.get(f"/api/scenes/{scene_id}/revisions").json() == before


@pytest.mark.parametrize(
    ("body", "reason"),
    [
        ({"bbox": [600, 100, 800, 300]}, "not inside the photo"),
        ({"bbox": [100, 100, 100, 300]}, "empty"),
        (
            {"bbox": BOX, "foreground": [{"points": [[450, 250], [750, 250]], "radius": 3}]},
            "foreground stroke 0 has the point (750",
        ),
        (
            {"bbox": BOX, "background": [{"points": [[490, 280]], "radius": 300}]},
            "nothing of it is left",
        ),
        ({"bbox": BOX, "foreground": [{"points": [], "radius": 3}]}, "foreground.0.points"),
    ],
)
def test_bad_refine_requests_are_422_with_the_reason(
    client: TestClient, scene_id: str, body: dict[str, Any], reason: str
) -> None:
    response = _refine(client, scene_id, **body)
    assert response.status_code == 422
    assert reason in response.json()["detail"]


def test_refine_on_an_unknown_scene_is_404(client: TestClient) -> None:
    response = _refine(client, "nosuchscene", bbox=BOX)
    assert response.status_code == 404
    assert "nosuchscene" in response.json()["detail"]

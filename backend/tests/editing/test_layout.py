"""Setting the room layout by its corners: the re-fit, its refusals, and the edit API."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient
from holiscene.editing.edits import InvalidEditError, apply_edits
from holiscene.editing.layout import CAMERA_HEIGHT_PRIOR_M, camera_height
from holiscene.geometry.boxes import box_corners
from holiscene.geometry.room_fit import project_room_corners
from holiscene.inputs import read_input_folder
from holiscene.pipeline import (
    DEFAULT_STAGES,
    KEPT_LAYOUT_STAGES,
    PLACEMENT_STAGES,
    PipelineBuildError,
    build_pipeline,
)
from holiscene.pipeline.registry import registered_stages
from holiscene.services.reconstruction import reconstruct_scene
from holiscene.store.clock import utcnow
from holiscene_schema import Camera, ImageInfo, Layout, Scene, SetLayout

from ..conftest import upload, wait_for_job

K = [[500.0, 0.0, 320.0], [0.0, 500.0, 240.0], [0.0, 0.0, 1.0]]
PITCH, ROLL, HEIGHT = 12.0, -3.0, 1.5


def room(center: list[float], size: list[float], yaw: float) -> np.ndarray:
    return box_corners(np.array(center), np.array(size), yaw)


def scene_with_room(corners: np.ndarray) -> Scene:
    return Scene(
        name="room",
        image=ImageInfo(file="img.png", width=640, height=480),
        camera=Camera(
            K=K,
            K_source="given",
            pitch_deg=PITCH,
            roll_deg=ROLL,
            height_m=HEIGHT,
            height_source="estimated",
        ),
        layout=Layout(
            corners_2d=project_room_corners(K, PITCH, ROLL, corners),
            corners_3d=corners.tolist(),
            source="estimated",
        ),
    )


def wall_behind(centre: list[float], depth: float, yaw_deg: float) -> float:
    """Distance from the camera to the room's -x wall, along the room's own x axis."""
    yaw = np.radians(yaw_deg)
    return float(depth / 2 - (centre[0] * np.cos(yaw) - centre[2] * np.sin(yaw)))


def set_layout(corners_2d: list[list[float] | None], **extra: float) -> SetLayout:
    return SetLayout.model_validate({"corners_2d": corners_2d, **extra})


# The camera stands 1 m inside the room's back half, looking at the far wall (x = 4).
OLD = room([1.5, 2.6 / 2 - HEIGHT, 0.2], [5.0, 2.6, 4.0], 4.0)


def test_set_layout_refits_room_and_camera_from_the_corners() -> None:
    # The annotator moved the room: far wall 0.5 m further, turned 3 degrees more, and the
    # camera turned (pitch 10, roll -1): the corners are this new room's image.
    new = room([1.75, 2.6 / 2 - HEIGHT, 0.2], [5.5, 2.6, 4.0], 7.0)
    corners_2d = project_room_corners(K, 10.0, -1.0, new)
    # The near corners are behind the camera: the wall there needs its distance.
    assert [c is not None for c in corners_2d] == [False, True, True, False] * 2
    edit = set_layout(corners_2d, unseen_wall_distance=wall_behind([1.75, 0, 0.2], 5.5, 7.0))
    edited = apply_edits(scene_with_room(OLD), [edit], "ann", utcnow())
    assert edited.camera is not None
    assert edited.camera.pitch_deg == pytest.approx(10.0, abs=1e-3)
    assert edited.camera.roll_deg == pytest.approx(-1.0, abs=1e-3)
    assert edited.camera.height_m == HEIGHT
    assert edited.layout.source == "manual"
    assert edited.layout.corners_3d is not None
    np.testing.assert_allclose(edited.layout.corners_3d, new, atol=2e-3)
    # corners_2d stays the image of corners_3d.
    stored = edited.layout.corners_2d
    assert stored is not None
    for got, want in zip(stored, corners_2d, strict=True):
        assert (got is None) == (want is None)
        if got is not None and want is not None:
            np.testing.assert_allclose(got, want, atol=0.05)
    assert "fit error" in (edited.layout.note or "")


def test_out_of_view_corners_left_to_the_fit_with_an_unseen_wall() -> None:
    # Only the far wall's four corners known (the others left to the fit): the wall behind the
    # camera takes the distance the app sends (the current room's).
    corners_2d = project_room_corners(K, PITCH, ROLL, OLD)
    known: list[list[float] | None] = [
        c if i in (1, 2, 5, 6) else None for i, c in enumerate(corners_2d)
    ]
    edit = set_layout(known, unseen_wall_distance=wall_behind([1.5, 0, 0.2], 5.0, 4.0))
    edited = apply_edits(scene_with_room(OLD), [edit], "ann", utcnow())
    assert edited.layout.corners_3d is not None
    np.testing.assert_allclose(edited.layout.corners_3d, OLD, atol=2e-3)
    with pytest.raises(InvalidEditError, match="unseen_wall_distance"):
        apply_edits(scene_with_room(OLD), [set_layout(known)], "ann", utcnow())


def test_a_camera_height_set_by_hand_scales_the_room_and_stays() -> None:
    corners_2d = project_room_corners(K, PITCH, ROLL, OLD)
    known: list[list[float] | None] = [
        c if i in (1, 2, 5, 6) else None for i, c in enumerate(corners_2d)
    ]
    behind = wall_behind([1.5, 0, 0.2], 5.0, 4.0)
    edit = set_layout(known, unseen_wall_distance=behind * 1.2, camera_height_m=1.8)
    edited = apply_edits(scene_with_room(OLD), [edit], "ann", utcnow())
    assert edited.camera is not None
    assert edited.camera.height_m == pytest.approx(1.8)
    assert edited.camera.height_source == "manual"
    # Same corners in the photo, 20% taller camera: the same room 20% larger about the camera.
    assert edited.layout.corners_3d is not None
    np.testing.assert_allclose(edited.layout.corners_3d, OLD * 1.2, atol=2e-3)
    assert "camera 1.80 m above the floor" in (edited.layout.note or "")
    # A later edit without a height keeps the one set by hand.
    again = apply_edits(edited, [set_layout(known, unseen_wall_distance=behind)], "ann", utcnow())
    assert again.camera is not None
    assert again.camera.height_m == pytest.approx(1.8)
    assert again.camera.height_source == "manual"


@pytest.mark.parametrize("height", [0.0, -1.0, 25.0])
def test_an_impossible_camera_height_is_refused(height: float) -> None:
    corners_2d = project_room_corners(K, PITCH, ROLL, OLD)
    with pytest.raises(ValueError, match="camera_height_m"):
        set_layout(corners_2d, camera_height_m=height)


@pytest.mark.parametrize(
    ("corners", "message"),
    [
        (
            [[300.0, 400.0], [320.0, 300.0], [500.0, 300.0]] + [None] * 5,
            "fewer than 4 known corners",
        ),
        ([[1e6, 400.0]] + [[320.0, 300.0]] * 7, "image sizes outside"),
    ],
)
def test_bad_corners_are_refused_with_the_reason(
    corners: list[list[float] | None], message: str
) -> None:
    scene = scene_with_room(OLD)
    with pytest.raises(InvalidEditError, match=message):
        apply_edits(scene, [set_layout(corners)], "ann", utcnow())


def test_inconsistent_corners_are_refused() -> None:
    corners_2d = project_room_corners(K, PITCH, ROLL, OLD)
    # Floor and ceiling corners swapped: the room would be upside down.
    swapped = corners_2d[4:] + corners_2d[:4]
    with pytest.raises(InvalidEditError, match="room layout"):
        apply_edits(scene_with_room(OLD), [set_layout(swapped)], "ann", utcnow())


def test_corners_no_box_fits_are_refused() -> None:
    # A room seen whole from outside (all 8 corners known): one corner dragged far off.
    box = room([6.0, 2.6 / 2 - HEIGHT, 0.0], [2.0, 2.6, 3.0], 10.0)
    corners_2d = project_room_corners(K, PITCH, ROLL, box)
    assert all(c is not None for c in corners_2d)
    fits = apply_edits(scene_with_room(box), [set_layout(corners_2d)], "ann", utcnow())
    assert fits.layout.note is not None and "fit error 0.0 px" in fits.layout.note
    moved = [list(c) for c in corners_2d if c is not None]
    moved[2][0] -= 200.0
    with pytest.raises(InvalidEditError, match="do not fit one room box"):
        apply_edits(scene_with_room(box), [set_layout(moved)], "ann", utcnow())


def test_a_scene_without_camera_cannot_take_a_layout() -> None:
    scene = scene_with_room(OLD).model_copy(update={"camera": None})
    corners_2d = project_room_corners(K, PITCH, ROLL, OLD)
    with pytest.raises(InvalidEditError, match="no camera"):
        apply_edits(scene, [set_layout(corners_2d)], "ann", utcnow())


def test_camera_height_comes_from_camera_then_floor_then_prior() -> None:
    scene = scene_with_room(OLD)
    assert camera_height(scene) == (HEIGHT, "estimated")
    assert scene.camera is not None
    no_height = scene.model_copy(
        update={"camera": scene.camera.model_copy(update={"height_m": None})}
    )
    assert camera_height(no_height)[0] == pytest.approx(HEIGHT)
    assert camera_height(no_height.model_copy(update={"layout": Layout()})) == (
        CAMERA_HEIGHT_PRIOR_M,
        "prior",
    )


def _edit(client: TestClient, scene_id: str, base: int, *edits: dict) -> object:  # type: ignore[type-arg]
    body = {"base_revision": base, "author": "ann", "edits": list(edits)}
    return client.post(f"/api/scenes/{scene_id}/edits", json=body)


def _moved_corners(doc: dict, dy: float) -> list[list[float] | None]:  # type: ignore[type-arg]
    """The stored corners with the far floor corners (1, 2) moved down by dy pixels."""
    corners: list[list[float] | None] = doc["scene"]["layout"]["corners_2d"]
    return [
        [c[0], c[1] + dy] if c is not None and i in (1, 2) else c for i, c in enumerate(corners)
    ]


def _layout_set_by_hand(client: TestClient, t3d5: Path) -> tuple[str, Any, Any, Any]:
    """t3d-5 through the pipeline, then its far floor corners moved down 25 px by hand: the
    scene id, the pipeline's document, the `set_layout` edit and the document it saved."""
    result = upload(client, t3d5, name="t3d-5")
    assert wait_for_job(client, result["job"]["id"])["status"] == "succeeded"
    scene_id = result["scene"]["id"]
    doc = client.get(f"/api/scenes/{scene_id}").json()
    edit = {"kind": "set_layout", "corners_2d": _moved_corners(doc, 25.0)}
    response = _edit(client, scene_id, doc["revision"], edit)
    assert response.status_code == 200, response.text  # type: ignore[attr-defined]
    return scene_id, doc, edit, response.json()  # type: ignore[attr-defined]


def test_layout_edit_and_placement_job_through_the_api(client: TestClient, t3d5: Path) -> None:
    scene_id, doc, edit, edited = _layout_set_by_hand(client, t3d5)
    assert edited["revision"] == doc["revision"] + 1
    layout = edited["scene"]["layout"]
    assert layout["source"] == "manual"
    assert layout["corners_3d"] != doc["scene"]["layout"]["corners_3d"]
    assert edited["scene"]["camera"]["pitch_deg"] != doc["scene"]["camera"]["pitch_deg"]
    history = client.get(f"/api/scenes/{scene_id}/revisions").json()
    assert history[-1]["kind"] == "edit"
    assert history[-1]["summary"].startswith("room layout set from")
    assert history[-1]["edits"][0]["kind"] == "set_layout"

    # The same edit on the old base is a conflict; a bad one is refused; neither writes.
    assert _edit(client, scene_id, doc["revision"], edit).status_code == 409  # type: ignore[attr-defined]
    bad = {"kind": "set_layout", "corners_2d": [[10.0, 10.0]] * 3 + [None] * 5}
    refused = _edit(client, scene_id, edited["revision"], bad)
    assert refused.status_code == 422  # type: ignore[attr-defined]
    assert "room layout" in refused.json()["detail"]  # type: ignore[attr-defined]
    assert client.get(f"/api/scenes/{scene_id}").json()["revision"] == edited["revision"]
    too_high = {**edit, "camera_height_m": 25.0}
    refused = _edit(client, scene_id, edited["revision"], too_high)
    assert refused.status_code == 422  # type: ignore[attr-defined]
    assert "camera_height_m" in refused.text  # type: ignore[attr-defined]
    assert client.get(f"/api/scenes/{scene_id}").json()["revision"] == edited["revision"]

    # Re-place the objects in the new room: a placement job makes a new revision.
    started = client.post(f"/api/scenes/{scene_id}/placement-jobs")
    assert started.status_code == 202, started.text
    job = wait_for_job(client, started.json()["id"], timeout=60)
    assert (job["kind"], job["status"], job["base_revision"]) == (
        "placement",
        "succeeded",
        edited["revision"],
    )
    placed = client.get(f"/api/scenes/{scene_id}").json()
    assert placed["revision"] == job["result_revision"] == edited["revision"] + 1
    assert placed["scene"]["layout"] == layout
    assert placed["scene"]["camera"] == edited["scene"]["camera"]
    rerun = {
        "heights_by_metrology",
        "placement",
        "boxes_by_refiner",
        "shapes_fit",
        "shapes_by_mesh_net",
        "scene_mesh",
    }
    earlier = edited["scene"]["stages"]
    assert rerun < {s["name"] for s in earlier}
    runs = placed["scene"]["stages"]
    assert [s["name"] for s in runs] == ["scene_from_revision", *[s["name"] for s in earlier]]
    # What the stages it did not run said (masks left as boxes...) still shows on the page.
    assert [s for s in runs[1:] if s["name"] not in rerun] == [
        s for s in earlier if s["name"] not in rerun
    ]
    boxes_before = [o["box_3d"] for o in edited["scene"]["objects"]]
    boxes_after = [o["box_3d"] for o in placed["scene"]["objects"]]
    assert all(b is not None for b in boxes_after)
    assert boxes_after != boxes_before  # placed in the new room, under the new camera
    assert placed["scene"]["supports"] == edited["scene"]["supports"]
    masks = [o["mask"] for o in placed["scene"]["objects"]]
    assert masks == [o["mask"] for o in edited["scene"]["objects"]]
    glb = client.get(f"/api/scenes/{scene_id}/scene.glb")
    assert glb.status_code == 200 and glb.content[:4] == b"glTF"
    assert client.get("/api/scenes").json()[0]["latest_job"]["id"] == job["id"]


def test_pipeline_rerun_keeps_a_layout_set_by_hand(client: TestClient, t3d5: Path) -> None:
    """As with people's supports, a full re-run keeps a room layout set by hand before it, and
    the camera fitted to it, and runs the other stages again around them: the objects end up
    where a placement job puts them in that room."""
    scene_id, estimated, _, edited = _layout_set_by_hand(client, t3d5)
    layout, camera = edited["scene"]["layout"], edited["scene"]["camera"]
    assert layout["source"] == "manual"
    assert layout["corners_3d"] != estimated["scene"]["layout"]["corners_3d"]
    # Where the objects belong in the hand-set room: a placement job's answer.
    placement = client.post(f"/api/scenes/{scene_id}/placement-jobs").json()
    assert wait_for_job(client, placement["id"], timeout=60)["status"] == "succeeded"
    placed = client.get(f"/api/scenes/{scene_id}").json()["scene"]

    started = client.post(f"/api/scenes/{scene_id}/pipeline-jobs")
    assert started.status_code == 202, started.text
    job = wait_for_job(client, started.json()["id"], timeout=90)
    assert job["status"] == "succeeded", job["error"]
    assert (
        "layout_from_revision: kept the room layout set by hand, and the camera's pitch, roll "
        "and height fitted to it" in job["message"]
    )
    rerun = client.get(f"/api/scenes/{scene_id}").json()
    assert rerun["revision"] == job["result_revision"]
    scene = rerun["scene"]
    assert scene["layout"] == layout  # the corners (2D and 3D), source and note as set
    assert scene["camera"] == camera
    # The photo has no depth: the depth stages are skipped.
    stages = registered_stages()
    ran = [name for name in KEPT_LAYOUT_STAGES if not stages[name].needs_depth]
    assert [s["name"] for s in scene["stages"]] == ran
    assert "layout_from_lines" not in KEPT_LAYOUT_STAGES
    # The other stages ran again, and placed every object in the hand-set room.
    assert [o["mask"] for o in scene["objects"]] == [o["mask"] for o in placed["objects"]]
    for before, after in zip(placed["objects"], scene["objects"], strict=True):
        assert before["box_3d"] is not None and after["box_3d"] is not None
        np.testing.assert_allclose(after["box_3d"]["center"], before["box_3d"]["center"], atol=0.02)
        np.testing.assert_allclose(after["box_3d"]["size"], before["box_3d"]["size"], atol=0.02)
    boxes = [o["box_3d"] for o in scene["objects"]]
    assert boxes != [o["box_3d"] for o in estimated["scene"]["objects"]]  # not the old room's


def test_placement_job_needs_a_layout(client: TestClient, t3d5: Path) -> None:
    result = upload(client, t3d5, name="t3d-5", run_pipeline="false")
    response = client.post(f"/api/scenes/{result['scene']['id']}/placement-jobs")
    assert response.status_code == 422
    assert "run the whole pipeline" in response.json()["detail"]
    assert client.post("/api/scenes/nope/placement-jobs").status_code == 404


def test_a_room_set_by_hand_before_any_run(client: TestClient, t3d5: Path) -> None:
    """The intrinsics given with the photo are the scene's camera from revision 1 (pitch and
    roll unknown), so a room can be set by hand before the pipeline runs, and then the
    objects placed in it."""
    result = upload(client, t3d5, name="t3d-5", run_pipeline="false")
    scene_id = result["scene"]["id"]
    doc = client.get(f"/api/scenes/{scene_id}").json()
    given = np.loadtxt(t3d5 / "cam_K.txt")
    camera = doc["scene"]["camera"]
    assert np.allclose(camera["K"], given)
    assert (camera["K_source"], camera["pitch_deg"], camera["roll_deg"]) == ("given", None, None)
    assert doc["scene"]["layout"]["corners_3d"] is None

    # The back wall 5 m ahead, the wall behind the camera 1 m behind it (out of view).
    corners = project_room_corners(
        given, 5.0, -1.0, room([2.0, 1.3 - 1.4, 0.0], [6.0, 2.6, 4.0], 0)
    )
    assert [i for i, c in enumerate(corners) if c is not None] == [1, 2, 5, 6]
    edit = {"kind": "set_layout", "corners_2d": corners, "unseen_wall_distance": 1.0}
    response = _edit(client, scene_id, doc["revision"], edit)
    assert response.status_code == 200, response.text  # type: ignore[attr-defined]
    saved = response.json()["scene"]  # type: ignore[attr-defined]
    assert saved["layout"]["source"] == "manual"
    assert saved["camera"]["pitch_deg"] == pytest.approx(5.0, abs=1e-3)
    assert saved["camera"]["roll_deg"] == pytest.approx(-1.0, abs=1e-3)
    # Its objects have no masks before a run: placing them waits for the pipeline, which
    # keeps the room set by hand.
    refused = client.post(f"/api/scenes/{scene_id}/placement-jobs")
    assert refused.status_code == 422
    assert "no masks yet" in refused.json()["detail"]
    run = client.post(f"/api/scenes/{scene_id}/pipeline-jobs")
    assert run.status_code == 202, run.text
    assert wait_for_job(client, run.json()["id"], timeout=60)["status"] == "succeeded"
    after = client.get(f"/api/scenes/{scene_id}").json()["scene"]
    assert after["layout"]["source"] == "manual"
    assert after["camera"]["pitch_deg"] == pytest.approx(5.0, abs=1e-3)
    assert any(o["box_3d"] is not None for o in after["objects"])


def test_placement_stages_on_an_unchanged_scene_place_as_the_full_pipeline(t3d5: Path) -> None:
    inputs = read_input_folder(t3d5)
    # Without the walls moved to the objects after placement (a placement job does not move
    # them, and places in the walls as stored): the same room in, the same boxes out.
    stages = tuple(s for s in DEFAULT_STAGES if s != "layout_holds_hung_objects")
    full = reconstruct_scene(inputs, name="x", image_file="img.jpg", stages=stages).scene
    again = reconstruct_scene(
        inputs,
        name="x",
        image_file="img.jpg",
        stages=PLACEMENT_STAGES,
        stage_options={"scene_from_revision": {"scene": full}},
    ).scene
    assert again.layout == full.layout and again.camera == full.camera
    assert again.supports == full.supports
    for before, after in zip(full.objects, again.objects, strict=True):
        assert before.mask == after.mask
        assert before.box_3d is not None and after.box_3d is not None
        # Same inputs up to the stored rounding (1e-4 degrees, 0.1 mm): the same boxes.
        np.testing.assert_allclose(after.box_3d.center, before.box_3d.center, atol=0.02)
        np.testing.assert_allclose(after.box_3d.size, before.box_3d.size, atol=0.02)


@pytest.mark.parametrize("stages", [PLACEMENT_STAGES, KEPT_LAYOUT_STAGES])
def test_placement_pipeline_needs_the_stored_scene(stages: tuple[str, ...]) -> None:
    with pytest.raises(PipelineBuildError, match="needs the stored scene"):
        build_pipeline(stages)

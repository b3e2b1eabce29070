"""Object edits (add, remove, class, box, mask, restore) through the edit API, on the real
t3d-5 photo (730x530, objects o0 bed, o1 night stand, o2 and o3 dressers)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient
from holiscene.segmentation.rle import decode_mask
from holiscene_schema import Mask

from ...conftest import imported_scene, wait_for_job
from ...conftest import post_edits as _edit

WIDTH, HEIGHT = 730, 530
# A box around the left dresser's drawers (o2's box is [419, 226, 564, 343]).
DRESSER_BOX = [425.0, 230.0, 560.0, 340.0]


def _imported(client: TestClient, folder: Path, run_pipeline: bool = False) -> dict[str, Any]:
    return imported_scene(client, folder, "t3d-5", run_pipeline)


def _add(object_id: str, cls: str, bbox: list[float], **extra: Any) -> dict[str, Any]:
    return {"kind": "add_object", "id": object_id, "class": cls, "bbox": bbox, **extra}


def _object(doc: dict[str, Any], object_id: str) -> dict[str, Any] | None:
    return next((o for o in doc["scene"]["objects"] if o["id"] == object_id), None)


def _support(doc: dict[str, Any], child: str) -> dict[str, Any] | None:
    return next((s for s in doc["scene"]["supports"] if s["child"] == child), None)


def _history(client: TestClient, doc: dict[str, Any]) -> list[dict[str, Any]]:
    history: list[dict[str, Any]] = client.get(f"/api/scenes/{doc['scene_id']}/revisions").json()
    return history


def _pixels(mask: dict[str, Any]) -> np.ndarray:
    return decode_mask(Mask.model_validate(mask), WIDTH, HEIGHT)


def _inside(pixels: np.ndarray, bbox: list[float]) -> bool:
    ys, xs = np.nonzero(pixels)
    x1, y1, x2, y2 = bbox
    return bool(xs.min() >= np.floor(x1) and xs.max() < np.ceil(x2)) and bool(
        ys.min() >= np.floor(y1) and ys.max() < np.ceil(y2)
    )


def test_add_object_without_mask_gets_a_grabcut_mask_in_its_box(
    client: TestClient, t3d5: Path
) -> None:
    doc = _imported(client, t3d5)
    edit = _add("det-1", "Night Stand", DRESSER_BOX, score=0.8, source="detector")
    response = _edit(client, doc, edit)
    assert response.status_code == 200, response.text
    added = response.json()
    assert added["revision"] == doc["revision"] + 1
    obj = _object(added, "det-1")
    assert obj is not None
    assert obj["class"] == "night_stand" and obj["source_class"] == "Night Stand"
    assert obj["source"] == "detector" and obj["score"] == 0.8
    assert obj["bbox"] == DRESSER_BOX and obj["box_3d"] is None
    assert obj["mask"]["source"] == "grabcut"
    pixels = _pixels(obj["mask"])
    box_area = (DRESSER_BOX[2] - DRESSER_BOX[0]) * (DRESSER_BOX[3] - DRESSER_BOX[1])
    assert 0.1 * box_area <= pixels.sum() <= box_area
    assert _inside(pixels, DRESSER_BOX)
    assert _support(added, "det-1") is None  # no supporter yet: flagged like any other
    last = _history(client, added)[-1]
    assert last["kind"] == "edit" and last["author"] == "ann"
    assert last["edits"] == [{**edit, "mask": None}]
    assert "det-1 added" in last["summary"]


def test_a_box_too_small_to_cut_gets_its_own_pixels(client: TestClient, t3d5: Path) -> None:
    doc = _imported(client, t3d5)
    bbox = [100.5, 50.0, 106.0, 58.0]
    added = _edit(client, doc, _add("cup", "cup", bbox)).json()
    obj = _object(added, "cup")
    assert obj is not None
    assert obj["class"] == "otherprop" and obj["source_class"] == "cup"
    assert obj["source"] == "manual" and obj["score"] is None
    assert obj["mask"] == {"origin": [100, 50], "size": [6, 8], "rle": [0, 48], "source": "box"}


def test_add_object_keeps_the_mask_it_was_given(client: TestClient, t3d5: Path) -> None:
    doc = _imported(client, t3d5)
    mask = {"origin": [10, 20], "size": [3, 2], "rle": [1, 4, 1], "source": "model"}
    added = _edit(client, doc, _add("lamp1", "lamp", [10, 20, 13, 22], mask=mask)).json()
    obj = _object(added, "lamp1")
    assert obj is not None and obj["mask"] == mask
    assert obj["class"] == "lamp" and obj["source_class"] is None


def test_add_object_and_set_its_support_in_one_request(client: TestClient, t3d5: Path) -> None:
    doc = _imported(client, t3d5)
    response = _edit(
        client,
        doc,
        _add("pillow1", "pillow", [200, 200, 300, 260]),
        {"kind": "set_support", "child": "pillow1", "parent": "o0", "type": "below"},
        {"kind": "set_support", "child": "o0", "parent": "floor", "type": "below"},
    )
    assert response.status_code == 200, response.text
    edited = response.json()
    assert edited["revision"] == doc["revision"] + 1
    assert _object(edited, "pillow1") is not None
    support = _support(edited, "pillow1")
    assert support is not None
    assert (support["parent"], support["type"], support["source"]) == ("o0", "below", "manual")
    assert support["author"] == "ann"


def test_remove_object_frees_the_objects_it_supported(client: TestClient, t3d5: Path) -> None:
    doc = _imported(client, t3d5)
    supported = _edit(
        client,
        doc,
        {"kind": "set_support", "child": "o0", "parent": "floor", "type": "below"},
        {"kind": "set_support", "child": "o1", "parent": "floor", "type": "below"},
        _add("pillow1", "pillow", [200, 200, 300, 260]),
        {"kind": "set_support", "child": "pillow1", "parent": "o0", "type": "below"},
        {"kind": "set_support", "child": "o2", "parent": "o0", "type": "behind"},
    ).json()
    response = _edit(client, supported, {"kind": "remove_object", "id": "o0"})
    assert response.status_code == 200, response.text
    removed = response.json()
    assert removed["revision"] == supported["revision"] + 1
    assert [o["id"] for o in removed["scene"]["objects"]] == ["o1", "o2", "o3", "pillow1"]
    assert [s["child"] for s in removed["scene"]["supports"]] == ["o1"]
    current = client.get(f"/api/scenes/{doc['scene_id']}").json()
    assert current["scene"] == removed["scene"]
    # History is kept: the revision before still has the object and its supports.
    before = client.get(f"/api/scenes/{doc['scene_id']}/revisions/{supported['revision']}").json()
    assert _object(before, "o0") is not None and _support(before, "pillow1") is not None
    assert "o0 removed" in _history(client, removed)[-1]["summary"]


def test_remove_object_takes_its_3d_data_and_a_rerun_stays_valid(
    client: TestClient, t3d5: Path
) -> None:
    doc = _imported(client, t3d5, run_pipeline=True)
    placed = _object(doc, "o1")
    assert placed is not None and placed["box_3d"] is not None
    edited = _edit(
        client,
        doc,
        {"kind": "remove_object", "id": "o1"},
        _add("vase1", "vase", [450, 200, 480, 240]),
        {"kind": "set_support", "child": "o3", "parent": "vase1", "type": "below"},
    ).json()
    assert _object(edited, "o1") is None
    assert all(o["box_3d"] is not None for o in edited["scene"]["objects"] if o["id"] != "vase1")
    # A full re-run works from the photo's boxes again: a supporter added by hand that the run
    # lacks must not leave a support naming it.
    job = client.post(f"/api/scenes/{doc['scene_id']}/pipeline-jobs").json()
    assert wait_for_job(client, job["id"])["status"] == "succeeded"
    rerun = client.get(f"/api/scenes/{doc['scene_id']}").json()
    ids = {o["id"] for o in rerun["scene"]["objects"]}
    assert all(
        s["parent"] in ids | {"floor", "wall", "ceiling"} for s in rerun["scene"]["supports"]
    )


_VALID = {"kind": "set_support", "child": "o1", "parent": "floor", "type": "below"}
BAD_REQUESTS: dict[str, tuple[list[dict[str, Any]], str]] = {
    "box outside the photo": (
        [_add("x1", "chair", [700, 100, WIDTH + 10, 200])],
        "is not inside the 730x530 photo",
    ),
    "box above the photo": ([_add("x1", "chair", [10, -5, 50, 40])], "is not inside"),
    "empty box": ([_add("x1", "chair", [100, 100, 100, 150])], "is empty"),
    "inverted box": ([_add("x1", "chair", [100, 150, 150, 100])], "is empty"),
    "existing id": ([_add("o2", "chair", [10, 10, 50, 50])], "'o2' is already used"),
    "id added twice": (
        [_add("x1", "chair", [10, 10, 50, 50]), _add("x1", "lamp", [60, 10, 90, 50])],
        "'x1' is already used",
    ),
    "structural id": ([_add("floor", "chair", [10, 10, 50, 50])], "reserved"),
    "id with a space": ([_add("a b", "chair", [10, 10, 50, 50])], "should match pattern"),
    "unknown class": ([_add("x1", "spaceship", [10, 10, 50, 50])], "unknown class name"),
    "mask runs": (
        [
            _add(
                "x1",
                "lamp",
                [10, 20, 13, 22],
                mask={"origin": [10, 20], "size": [3, 2], "rle": [1, 4], "source": "model"},
            )
        ],
        "mask runs do not add up",
    ),
    "mask outside the photo": (
        [
            _add(
                "x1",
                "lamp",
                [720, 20, 730, 22],
                mask={"origin": [728, 20], "size": [3, 2], "rle": [0, 6], "source": "model"},
            )
        ],
        "mask window",
    ),
    "score above 1": ([_add("x1", "lamp", [10, 10, 50, 50], score=1.5)], "score"),
    "unknown source": ([_add("x1", "lamp", [10, 10, 50, 50], source="given")], "source"),
    "remove a missing object": ([{"kind": "remove_object", "id": "ghost"}], "'ghost'"),
    "remove twice": (
        [{"kind": "remove_object", "id": "o3"}, {"kind": "remove_object", "id": "o3"}],
        "cannot remove 'o3'",
    ),
    "support of a removed object": (
        [{"kind": "remove_object", "id": "o3"}, {**_VALID, "child": "o3"}],
        "no object 'o3'",
    ),
    "class of a missing object": (
        [{"kind": "set_class", "id": "ghost", "class": "bed"}],
        "'ghost'",
    ),
    "unknown class set": (
        [{"kind": "set_class", "id": "o1", "class": "spaceship"}],
        "unknown class name",
    ),
    "box set outside the photo": (
        [{"kind": "set_bbox", "id": "o1", "bbox": [10, 10, 800, 50]}],
        "is not inside the 730x530 photo",
    ),
    "mask set with bad runs": (
        [
            {
                "kind": "set_mask",
                "id": "o1",
                "mask": {"origin": [10, 20], "size": [3, 2], "rle": [0, 5], "source": "manual"},
            }
        ],
        "mask runs do not add up",
    ),
    "empty mask set": (
        [
            {
                "kind": "set_mask",
                "id": "o1",
                "mask": {"origin": [10, 20], "size": [3, 2], "rle": [6], "source": "manual"},
            }
        ],
        "has no pixels",
    ),
    "restore from a missing revision": (
        [{"kind": "restore_object", "id": "o1", "from_revision": 99}],
        "no revision 99",
    ),
}


@pytest.mark.parametrize("case", list(BAD_REQUESTS))
def test_bad_object_edits_are_refused_whole(client: TestClient, t3d5: Path, case: str) -> None:
    doc = _imported(client, t3d5)
    edits, reason = BAD_REQUESTS[case]
    response = _edit(client, doc, _VALID, *edits)
    assert response.status_code == 422, response.text
    assert reason in response.json()["detail"]
    assert len(_history(client, doc)) == 1
    assert client.get(f"/api/scenes/{doc['scene_id']}").json()["revision"] == doc["revision"]


def test_object_edits_on_a_stale_revision_conflict(client: TestClient, t3d5: Path) -> None:
    doc = _imported(client, t3d5)
    assert _edit(client, doc, _VALID).status_code == 200
    for edit in (_add("x1", "chair", [10, 10, 50, 50]), {"kind": "remove_object", "id": "o1"}):
        stale = _edit(client, doc, edit)
        assert stale.status_code == 409, stale.text
        assert stale.json()["detail"]["current_revision"] == doc["revision"] + 1
    assert len(_history(client, doc)) == 2


def _revision(client: TestClient, doc: dict[str, Any], number: int) -> dict[str, Any]:
    found: dict[str, Any] = client.get(f"/api/scenes/{doc['scene_id']}/revisions/{number}").json()
    return found


def _without_time(doc: dict[str, Any]) -> dict[str, Any]:
    """The scene's objects and supports (what object edits and their undo change)."""
    return {"objects": doc["scene"]["objects"], "supports": doc["scene"]["supports"]}


def test_set_class_stores_the_nyu40_class_and_marks_it_set_by_a_person(
    client: TestClient, t3d5: Path
) -> None:
    doc = _imported(client, t3d5)
    changed = _edit(client, doc, {"kind": "set_class", "id": "o1", "class": "Night Stand"})
    assert changed.status_code == 200, changed.text
    obj = _object(changed.json(), "o1")
    assert obj is not None and obj["set_by_person"] == ["class"]
    assert obj["class"] == "night_stand" and obj["source_class"] == "Night Stand"
    assert "o1 is a Night Stand" in _history(client, doc)[-1]["summary"]


def test_set_bbox_cuts_a_box_made_mask_again_and_clips_a_drawn_one(
    client: TestClient, t3d5: Path
) -> None:
    doc = _imported(client, t3d5, run_pipeline=True)
    moved = _edit(client, doc, {"kind": "set_bbox", "id": "o2", "bbox": DRESSER_BOX})
    assert moved.status_code == 200, moved.text
    obj = _object(moved.json(), "o2")
    assert obj is not None and obj["bbox"] == DRESSER_BOX and "bbox" in obj["set_by_person"]
    assert obj["mask"]["source"] in {"grabcut", "box"}
    assert _inside(_pixels(obj["mask"]), DRESSER_BOX)
    # A drawn mask (a filled 60x40 rectangle) is clipped to a smaller box, not cut again.
    drawn = {"origin": [430, 240], "size": [60, 40], "rle": [0, 2400], "source": "manual"}
    painted = _edit(client, moved.json(), {"kind": "set_mask", "id": "o2", "mask": drawn}).json()
    clipped = _edit(
        client, painted, {"kind": "set_bbox", "id": "o2", "bbox": [440.0, 240.0, 490.0, 280.0]}
    ).json()
    obj = _object(clipped, "o2")
    assert obj is not None and obj["mask"]["source"] == "manual"
    assert int(_pixels(obj["mask"]).sum()) == 50 * 40


def test_set_mask_stores_a_manual_mask_and_its_extent_as_the_box(
    client: TestClient, t3d5: Path
) -> None:
    doc = _imported(client, t3d5)
    # Two rows of a 4x3 window: an L shape of 5 pixels.
    mask = {"origin": [100, 50], "size": [4, 3], "rle": [0, 1, 3, 1, 3, 4], "source": "grabcut"}
    changed = _edit(client, doc, {"kind": "set_mask", "id": "o1", "mask": mask})
    assert changed.status_code == 200, changed.text
    obj = _object(changed.json(), "o1")
    assert obj is not None and obj["mask"]["source"] == "manual"
    assert int(_pixels(obj["mask"]).sum()) == 6
    assert obj["bbox"] == [100.0, 50.0, 104.0, 53.0]
    assert set(obj["set_by_person"]) == {"mask", "bbox"}


def test_undo_of_a_removal_brings_back_the_object_its_mask_and_every_support(
    client: TestClient, t3d5: Path
) -> None:
    doc = _imported(client, t3d5, run_pipeline=True)
    supported = _edit(
        client,
        doc,
        _add("pillow1", "pillow", [200, 250, 260, 290]),
        {"kind": "set_support", "child": "pillow1", "parent": "o0", "type": "below"},
    ).json()
    removed = _edit(client, supported, {"kind": "remove_object", "id": "o0"}).json()
    assert _object(removed, "o0") is None and _support(removed, "pillow1") is None
    undo = {"kind": "restore_object", "id": "o0", "from_revision": supported["revision"]}
    restored = _edit(client, removed, undo)
    assert restored.status_code == 200, restored.text
    assert _without_time(restored.json()) == _without_time(supported)
    history = client.get(f"/api/scenes/{removed['scene_id']}/revisions").json()
    assert history[-1]["summary"] == f"o0 back, as revision {supported['revision']} had it"


@pytest.mark.parametrize(
    "edit",
    [
        {"kind": "set_class", "id": "o3", "class": "bookshelf"},
        {"kind": "set_bbox", "id": "o3", "bbox": [10.0, 10.0, 120.0, 90.0]},
        {
            "kind": "set_mask",
            "id": "o3",
            "mask": {"origin": [5, 5], "size": [2, 2], "rle": [0, 4], "source": "manual"},
        },
        {"kind": "add_object", "id": "new1", "class": "lamp", "bbox": [20, 20, 60, 80]},
    ],
    ids=lambda edit: edit["kind"],
)
def test_undo_and_redo_of_each_object_edit_are_exact(
    client: TestClient, t3d5: Path, edit: dict[str, Any]
) -> None:
    doc = _imported(client, t3d5, run_pipeline=True)
    changed = _edit(client, doc, edit).json()
    assert _without_time(changed) != _without_time(doc)
    undo = {"kind": "restore_object", "id": edit["id"], "from_revision": doc["revision"]}
    undone = _edit(client, changed, undo).json()
    assert _without_time(undone) == _without_time(doc)
    redo = {"kind": "restore_object", "id": edit["id"], "from_revision": changed["revision"]}
    redone = _edit(client, undone, redo).json()
    assert _without_time(redone) == _without_time(changed)
    assert _revision(client, doc, doc["revision"])["revision"] == doc["revision"]


def test_a_pipeline_rerun_keeps_what_people_set_on_objects(client: TestClient, t3d5: Path) -> None:
    doc = _imported(client, t3d5, run_pipeline=True)
    drawn = {"origin": [430, 240], "size": [60, 40], "rle": [0, 2400], "source": "manual"}
    edited = _edit(
        client,
        doc,
        {"kind": "set_class", "id": "o1", "class": "cabinet"},
        {"kind": "set_bbox", "id": "o3", "bbox": [10.0, 10.0, 120.0, 90.0]},
        {"kind": "set_mask", "id": "o2", "mask": drawn},
        _add("lamp1", "lamp", [300, 60, 360, 160]),
    ).json()
    job = client.post(f"/api/scenes/{doc['scene_id']}/pipeline-jobs").json()
    assert wait_for_job(client, job["id"])["status"] == "succeeded"
    rerun = client.get(f"/api/scenes/{doc['scene_id']}").json()
    assert rerun["revision"] > edited["revision"]
    for object_id in ("o1", "o2", "o3", "lamp1"):
        kept, before = _object(rerun, object_id), _object(edited, object_id)
        assert kept is not None and before is not None, object_id
        assert (kept["class"], kept["bbox"], kept["set_by_person"]) == (
            before["class"],
            before["bbox"],
            before["set_by_person"],
        ), object_id
    o2 = _object(rerun, "o2")
    assert o2 is not None and o2["mask"] == _object(edited, "o2")["mask"]  # type: ignore[index]
    # The given box o3 was moved from is not found again as a second object.
    assert len(rerun["scene"]["objects"]) == len(edited["scene"]["objects"])
    # Placement ran on the kept objects too: a 3D box, or a note saying why there is none.
    unplaced = [o["id"] for o in rerun["scene"]["objects"] if not (o["box_3d"] or o["note"])]
    assert not unplaced, unplaced


def test_an_object_a_person_removed_stays_out_after_a_rerun_until_undone(
    client: TestClient, t3d5: Path
) -> None:
    doc = _imported(client, t3d5, run_pipeline=True)
    removed = _edit(client, doc, {"kind": "remove_object", "id": "o2"}).json()
    assert [r["id"] for r in removed["scene"]["removed_by_person"]] == ["o2"]
    job = client.post(f"/api/scenes/{doc['scene_id']}/pipeline-jobs").json()
    assert wait_for_job(client, job["id"])["status"] == "succeeded"
    rerun = client.get(f"/api/scenes/{doc['scene_id']}").json()
    assert _object(rerun, "o2") is None
    assert len(rerun["scene"]["objects"]) == len(doc["scene"]["objects"]) - 1
    undo = {"kind": "restore_object", "id": "o2", "from_revision": doc["revision"]}
    restored = _edit(client, rerun, undo).json()
    assert _object(restored, "o2") is not None and restored["scene"]["removed_by_person"] == []

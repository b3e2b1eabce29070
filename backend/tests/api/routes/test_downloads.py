"""Downloads: a scene's scene.json and coco.json, and several scenes as one zip, on the real
t3d-5 photo (730x530)."""

from __future__ import annotations

import io
import json
import zipfile
from pathlib import Path
from typing import Any, get_args

import numpy as np
from fastapi.testclient import TestClient
from holiscene.export.coco import decode_coco_rle
from holiscene.export.folders import EXPORT_FORMATS
from holiscene.segmentation.rle import decode_mask
from holiscene_schema import ExportFormatName, Mask

from ...conftest import upload, wait_for_job


def _import(client: TestClient, folder: Path, name: str, run_pipeline: bool = False) -> str:
    result = upload(client, folder, name=name, run_pipeline=str(run_pipeline).lower())
    if run_pipeline:
        assert wait_for_job(client, result["job"]["id"], 60)["status"] == "succeeded"
    return str(result["scene"]["id"])


def _document(client: TestClient, scene_id: str) -> dict[str, Any]:
    doc: dict[str, Any] = client.get(f"/api/scenes/{scene_id}").json()
    return doc


def _add_object(client: TestClient, scene_id: str) -> dict[str, Any]:
    doc = _document(client, scene_id)
    edit = {"kind": "add_object", "id": "mine", "class": "dresser", "bbox": [425, 230, 560, 340]}
    body = {"base_revision": doc["revision"], "author": "ann", "edits": [edit]}
    response = client.post(f"/api/scenes/{scene_id}/edits", json=body)
    assert response.status_code == 200, response.text
    added: dict[str, Any] = response.json()
    return added


def test_scene_json_is_the_current_scene_as_a_named_file(client: TestClient, t3d5: Path) -> None:
    scene_id = _import(client, t3d5, "bedroom t3d-5")
    doc = _add_object(client, scene_id)
    response = client.get(f"/api/scenes/{scene_id}/scene.json")
    assert response.status_code == 200
    assert response.headers["content-type"].startswith("application/json")
    assert 'filename="bedroom_t3d-5.scene.json"' in response.headers["content-disposition"]
    assert json.loads(response.content) == doc["scene"]


def test_coco_json_holds_the_objects_masks(client: TestClient, t3d5: Path) -> None:
    scene_id = _import(client, t3d5, "t3d-5")
    doc = _add_object(client, scene_id)
    response = client.get(f"/api/scenes/{scene_id}/coco.json")
    assert response.status_code == 200
    assert 'filename="t3d-5.coco.json"' in response.headers["content-disposition"]
    coco = response.json()
    assert coco["images"][0]["width"] == 730 and coco["images"][0]["height"] == 530
    objects = {o["id"]: o for o in doc["scene"]["objects"]}
    annotations = {a["holiscene_id"]: a for a in coco["annotations"]}
    assert set(annotations) == set(objects)
    mine = objects["mine"]
    assert mine["mask"] is not None  # cut by the server when the object was added
    ours = decode_mask(Mask.model_validate(mine["mask"]), 730, 530)
    assert np.array_equal(decode_coco_rle(annotations["mine"]["segmentation"]), ours)
    assert annotations["mine"]["category_id"] == 17  # dresser is NYU-40 label 17


def test_the_archive_has_a_folder_per_scene_with_its_files(
    client: TestClient, t3d5: Path, real_photos: Path
) -> None:
    placed = _import(client, t3d5, "placed", run_pipeline=True)
    plain = _import(client, real_photos / "im3d-8", "plain")
    response = client.post("/api/scenes/archive", json={"scene_ids": [placed, plain, placed]})
    assert response.status_code == 200, response.text
    assert response.headers["content-type"] == "application/zip"
    assert 'filename="holiscene-2-scenes.zip"' in response.headers["content-disposition"]
    archive = zipfile.ZipFile(io.BytesIO(response.content))
    index = json.loads(archive.read("index.json"))["scenes"]
    assert [s["scene_id"] for s in index] == [placed, plain]
    assert [s["has_glb"] for s in index] == [True, False]
    # The GLB is the pipeline run's, made at the scene's revision: nothing to note.
    assert [s["glb_revision"] for s in index] == [_document(client, placed)["revision"], None]
    assert "glb_note" not in index[0]
    for entry in index:
        folder, scene_id = entry["folder"], entry["scene_id"]
        doc = _document(client, scene_id)
        assert entry["revision"] == doc["revision"]
        assert json.loads(archive.read(f"{folder}/scene.json")) == doc["scene"]
        coco = json.loads(archive.read(f"{folder}/coco.json"))
        assert len(coco["annotations"]) == len(doc["scene"]["objects"])
        photo = archive.read(f"{folder}/{doc['scene']['image']['file']}")
        assert photo == client.get(f"/api/scenes/{scene_id}/image").content
    glb = archive.read(f"{index[0]['folder']}/scene.glb")
    assert glb[:4] == b"glTF" and glb == client.get(f"/api/scenes/{placed}/scene.glb").content
    assert f"{index[1]['folder']}/scene.glb" not in archive.namelist()


def test_unknown_scenes_are_404_naming_them_and_an_empty_list_is_422(
    client: TestClient, t3d5: Path
) -> None:
    known = _import(client, t3d5, "t3d-5")
    response = client.post("/api/scenes/archive", json={"scene_ids": [known, "nope1", "nope2"]})
    assert response.status_code == 404
    assert "nope1, nope2" in response.json()["detail"]
    empty = client.post("/api/scenes/archive", json={"scene_ids": []})
    assert empty.status_code == 422 and "scene_ids" in empty.json()["detail"]
    for file in ("scene.json", "coco.json"):
        missing = client.get(f"/api/scenes/nope1/{file}")
        assert missing.status_code == 404 and "nope1" in missing.json()["detail"]


def test_scene_glb_is_a_named_file_and_answers_a_range(client: TestClient, t3d5: Path) -> None:
    """The Download menu asks for the first bytes only, to learn whether there is one."""
    placed = _import(client, t3d5, "placed room", run_pipeline=True)
    plain = _import(client, t3d5, "plain")
    first = client.get(f"/api/scenes/{placed}/scene.glb", headers={"Range": "bytes=0-3"})
    assert first.status_code == 206 and first.content == b"glTF"
    # Which revision's run made it: the pipeline's; an edit after it makes none.
    made = client.get(f"/api/scenes/{placed}").json()["revision"]
    assert first.headers["x-glb-revision"] == str(made)
    doc = client.get(f"/api/scenes/{placed}").json()
    child = doc["scene"]["objects"][0]["id"]
    edit = {"kind": "set_support", "child": child, "parent": "floor", "type": "below"}
    body = {"base_revision": made, "author": "ann", "edits": [edit]}
    assert client.post(f"/api/scenes/{placed}/edits", json=body).status_code == 200
    again = client.get(f"/api/scenes/{placed}/scene.glb", headers={"Range": "bytes=0-3"})
    assert again.headers["x-glb-revision"] == str(made)
    assert client.get(f"/api/scenes/{placed}").json()["revision"] == made + 1
    whole = client.get(f"/api/scenes/{placed}/scene.glb")
    assert 'filename="placed_room.glb"' in whole.headers["content-disposition"]
    assert whole.content[:4] == b"glTF" and len(whole.content) > 1000
    missing = client.get(f"/api/scenes/{plain}/scene.glb", headers={"Range": "bytes=0-3"})
    assert missing.status_code == 404


def test_the_archive_says_when_a_scene_glb_is_older_than_the_scene(
    client: TestClient, t3d5: Path
) -> None:
    placed = _import(client, t3d5, "edited after placement", run_pipeline=True)
    made = _document(client, placed)["revision"]
    _add_object(client, placed)
    response = client.post("/api/scenes/archive", json={"scene_ids": [placed]})
    [entry] = json.loads(zipfile.ZipFile(io.BytesIO(response.content)).read("index.json"))["scenes"]
    assert (entry["revision"], entry["glb_revision"]) == (made + 1, made)
    assert entry["glb_note"] == (
        f"scene.glb was made at revision {made}: the edits of revision {made + 1} are not in it"
    )


def test_the_archive_in_an_export_format_holds_what_the_export_command_writes(
    client: TestClient, t3d5: Path
) -> None:
    placed = _import(client, t3d5, "t3d-5", run_pipeline=True)
    response = client.post("/api/scenes/archive", json={"scene_ids": [placed], "format": "coco"})
    assert response.status_code == 200, response.text
    assert "holiscene-1-scenes-coco.zip" in response.headers["content-disposition"]
    archive = zipfile.ZipFile(io.BytesIO(response.content))
    assert sorted(archive.namelist()) == ["annotations.json", "images/t3d-5.jpg"]
    coco = json.loads(archive.read("annotations.json"))
    assert len(coco["annotations"]) == len(_document(client, placed)["scene"]["objects"])
    assert archive.read("images/t3d-5.jpg") == (t3d5 / "img.jpg").read_bytes()

    # Every format the export command has can be asked for (the schema's list is its table).
    assert set(get_args(ExportFormatName)) == set(EXPORT_FORMATS)


def test_an_export_format_with_nothing_to_write_is_422_with_its_reason(
    client: TestClient, t3d5: Path
) -> None:
    unlabelled = _import(client, t3d5, "t3d-5")  # no supports set by a person
    body = {"scene_ids": [unlabelled], "format": "relation-training"}
    response = client.post("/api/scenes/archive", json=body)
    assert response.status_code == 422
    assert response.json()["detail"] == (
        "none of the 1 scene(s) has supports set by a person: nothing to train on"
    )
    wrong = client.post("/api/scenes/archive", json={"scene_ids": [unlabelled], "format": "obj"})
    assert wrong.status_code == 422 and "format" in wrong.json()["detail"]

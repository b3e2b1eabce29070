"""The scene list's "Download selected" zip imports back through "Import a dataset": the
bytes POST /api/scenes/archive gives, posted to POST /api/imports, make scenes with the same
classes, boxes (1 px), masks (IoU > 0.99), supports and room layout in another store; the
same zip again adds nothing, nor does it in the store it came from unless edited since; and
a pipeline run on the imported scene keeps a layout a person set. Unzipped, the download is
a folder `holiscene import` takes as it is."""

from __future__ import annotations

import io
import json
import zipfile
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.cli import main
from holiscene.cli.export import scene_store
from holiscene.core.settings import Settings
from holiscene.inputs.datasets.uploaded import REJECTED_NOTE
from holiscene.segmentation.rle import decode_mask
from holiscene.store.tables import SceneRow
from holiscene_schema import Mask
from sqlalchemy import update
from sqlalchemy.orm import Session

from ...conftest import upload, wait_for_job
from .test_dataset_import import _imported


def _document(client: TestClient, scene_id: str) -> dict[str, Any]:
    doc: dict[str, Any] = client.get(f"/api/scenes/{scene_id}").json()
    return doc


def _edited(client: TestClient, scene_id: str) -> dict[str, Any]:
    """A person's work on a placed scene: an object drawn (the server cuts its mask), its
    support set, another object's class changed, and the room layout set by hand."""
    doc = _document(client, scene_id)
    first = doc["scene"]["objects"][0]["id"]
    edits = [
        {"kind": "add_object", "id": "mine", "class": "dresser", "bbox": [425, 230, 560, 340]},
        {"kind": "set_support", "child": "mine", "parent": "floor", "type": "below"},
        {"kind": "set_class", "id": first, "class": "otherfurniture"},
        {"kind": "set_layout", "corners_2d": doc["scene"]["layout"]["corners_2d"]},
    ]
    body = {"base_revision": doc["revision"], "author": "ann", "edits": edits}
    response = client.post(f"/api/scenes/{scene_id}/edits", json=body)
    assert response.status_code == 200, response.text
    edited: dict[str, Any] = response.json()
    assert edited["scene"]["layout"]["source"] == "manual"
    return edited


def _pixels(obj: dict[str, Any], width: int, height: int) -> np.ndarray:
    return decode_mask(Mask.model_validate(obj["mask"]), width, height)


def _supports(scene: dict[str, Any]) -> set[tuple[Any, ...]]:
    position = {obj["id"]: i for i, obj in enumerate(scene["objects"])}
    return {
        (position[s["child"]], position.get(s["parent"], s["parent"]), s["type"], s["source"])
        for s in scene["supports"]
    }


def _assert_same_labels(back: dict[str, Any], before: dict[str, Any]) -> None:
    assert [o["class"] for o in back["objects"]] == [o["class"] for o in before["objects"]]
    width, height = before["image"]["width"], before["image"]["height"]
    for obj, was in zip(back["objects"], before["objects"], strict=True):
        assert np.allclose(obj["bbox"], was["bbox"], atol=1.0), (obj["bbox"], was["bbox"])
        assert (obj["mask"] is None) == (was["mask"] is None)
        if was["mask"] is not None:
            a, b = _pixels(obj, width, height), _pixels(was, width, height)
            assert (a & b).sum() / (a | b).sum() > 0.99
    assert _supports(back) == _supports(before)
    assert back["layout"] == before["layout"]
    assert back["camera"] == before["camera"]


def _with_last_box_dropped(archive: bytes, folder_prefix: str) -> bytes:
    """The zip with the last box of one folder's detections.json taken out (and its supports
    with it): labels edited in the files an import reads, scene.json as downloaded."""
    out = io.BytesIO()
    with zipfile.ZipFile(io.BytesIO(archive)) as source, zipfile.ZipFile(out, "w") as target:
        for info in source.infolist():
            if info.filename.startswith(folder_prefix) and info.filename.endswith("/supports.json"):
                continue
            data = source.read(info)
            if info.filename.startswith(folder_prefix) and info.filename.endswith(
                "/detections.json"
            ):
                data = json.dumps(json.loads(data)[:-1]).encode()
            target.writestr(info, data)
    return out.getvalue()


def _with_scene_file_changed(archive: bytes, folder_prefix: str, name: str) -> bytes:
    """The zip with the scene.json of the folder starting with `folder_prefix` renamed to
    `name`: a download edited before it is uploaded again."""
    out = io.BytesIO()
    with zipfile.ZipFile(io.BytesIO(archive)) as source, zipfile.ZipFile(out, "w") as target:
        for info in source.infolist():
            data = source.read(info)
            if info.filename.startswith(folder_prefix) and info.filename.endswith("/scene.json"):
                scene = json.loads(data)
                scene["name"] = name
                data = json.dumps(scene).encode()
            target.writestr(info, data)
    return out.getvalue()


def test_the_download_imports_back_to_the_same_scenes(
    client: TestClient, t3d5: Path, real_photos: Path, tmp_path: Path
) -> None:
    placed = upload(client, t3d5, name="bedroom", run_pipeline="true")
    assert wait_for_job(client, placed["job"]["id"], 60)["status"] == "succeeded"
    placed_id = placed["scene"]["id"]
    edited = _edited(client, placed_id)["scene"]
    plain_id = upload(client, real_photos / "im3d-8", name="plain")["scene"]["id"]
    plain = _document(client, plain_id)["scene"]
    # A reviewer rejected the plain one: the zip says so, and so does its import elsewhere.
    workbench = client.app.state.workbench  # type: ignore[attr-defined]
    with Session(workbench.engine) as session:
        session.execute(update(SceneRow).where(SceneRow.id == plain_id).values(state="rejected"))
        session.commit()

    response = client.post("/api/scenes/archive", json={"scene_ids": [placed_id, plain_id]})
    assert response.status_code == 200, response.text
    index = json.loads(zipfile.ZipFile(io.BytesIO(response.content)).read("index.json"))
    assert [entry["state"] for entry in index["scenes"]] == ["in_annotation", "rejected"]

    # Into the store it came from, unchanged: no copies, the scenes it was written from.
    home = _imported(client, response.content)
    assert home["imported"] == [] and home["errors"] == [], home
    assert [item["scene_id"] for item in home["skipped"]] == [placed_id, plain_id]
    # Each names the scene it is, whatever the folder in the zip is called.
    assert [item["scene_name"] for item in home["skipped"]] == ["bedroom", "plain"]
    # Edited after download, a scene comes in as a new one.
    renamed = _with_scene_file_changed(response.content, "plain-", "plain, edited")
    changed = _imported(client, renamed)
    assert [item["scene_id"] for item in changed["skipped"]] == [placed_id]
    (copy,) = changed["imported"]
    assert _document(client, copy["scene_id"])["scene"]["name"] == "plain, edited"
    assert copy["scene_name"] == "plain, edited"
    # So does one whose boxes were edited (an import reads detections.json, not scene.json).
    fewer = _imported(client, _with_last_box_dropped(response.content, "bedroom-"))
    # (the plain folder's files are those the copy above was imported from: that copy)
    assert [item["scene_id"] for item in fewer["skipped"]] == [copy["scene_id"]]
    (boxes_edited,) = fewer["imported"]
    objects = _document(client, boxes_edited["scene_id"])["scene"]["objects"]
    assert len(objects) == len(_document(client, placed_id)["scene"]["objects"]) - 1

    # Into another store: new scenes with the same labels; the same zip again adds nothing.
    other = Settings(data_dir=tmp_path / "other", web_dir=tmp_path / "no-web")
    with TestClient(create_app(other)) as elsewhere:
        job = _imported(elsewhere, response.content)
        assert job["status"] == "succeeded" and job["errors"] == [], job
        assert job["format"] == "input folders"
        assert len(job["imported"]) == 2
        new_ids = [item["scene_id"] for item in job["imported"]]
        for new_id, before in zip(new_ids, [edited, plain], strict=True):
            back = _document(elsewhere, new_id)["scene"]
            _assert_same_labels(back, before)
            assert back["name"] == before["name"], "named as before, not after the folder"
        assert [REJECTED_NOTE in item["notes"] for item in job["imported"]] == [False, True]

        again = _imported(elsewhere, response.content)
        assert again["imported"] == [] and len(again["skipped"]) == 2, again
        assert [item["scene_id"] for item in again["skipped"]] == new_ids

        # The layout a person set stays through a pipeline run on the imported scene.
        rerun = elsewhere.post(f"/api/scenes/{new_ids[0]}/pipeline-jobs")
        assert rerun.status_code == 202, rerun.text
        assert wait_for_job(elsewhere, rerun.json()["id"], 60)["status"] == "succeeded"
        assert _document(elsewhere, new_ids[0])["scene"]["layout"] == edited["layout"]


def test_holiscene_import_takes_the_download(
    client: TestClient, real_photos: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The zip as downloaded, and the same zip unpacked: one scene, the second time skipped."""
    scene_id = upload(client, real_photos / "im3d-8", name="plain")["scene"]["id"]
    doc = _document(client, scene_id)
    edits = [
        {"kind": "add_object", "id": "mine", "class": "couch", "bbox": [40, 60, 200, 180]},
        {"kind": "set_support", "child": "mine", "parent": "floor", "type": "below"},
    ]
    body = {"base_revision": doc["revision"], "author": "ann", "edits": edits}
    edited = client.post(f"/api/scenes/{scene_id}/edits", json=body).json()["scene"]
    response = client.post("/api/scenes/archive", json={"scene_ids": [scene_id]})
    (tmp_path / "scenes.zip").write_bytes(response.content)
    zipfile.ZipFile(io.BytesIO(response.content)).extractall(tmp_path / "download")

    data_dir = tmp_path / "other"
    for path in ("scenes.zip", "download"):
        command = ["import", str(tmp_path / path), "--no-pipeline", "--data-dir", str(data_dir)]
        assert main(command) == 0
    second = capsys.readouterr().out.strip().splitlines()[-1]
    assert second.endswith("skipped"), second
    with scene_store(Settings(data_dir=data_dir)) as scenes:
        (summary,) = scenes.list_summaries()
        assert summary.name == "plain"
        back = scenes.document(summary.id).scene.model_dump(mode="json", by_alias=True)
    _assert_same_labels(back, edited)

"""POST /api/imports: a dataset uploaded as a .zip (COCO, LabelMe, a folder of input folders)
imported in the background, photo by photo; a broken photo is reported and the rest imported,
the same zip twice adds nothing, and an unsafe zip (zip slip, a link, a bomb) or one of
nothing importable is refused with nothing stored."""

from __future__ import annotations

import io
import json
import stat
import time
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import h5py
import pytest
from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.api.upload_login import UploadLogin
from holiscene.core.settings import Settings
from holiscene_schema import FINISHED_JOB_STATUSES

from ...inputs.datasets.files import coco_file, labelme_file, photo_bytes, shape
from ...inputs.datasets.sunrgbd_files import write_sun_folder
from ..conftest import Accounts

COUCH = [[10.0, 20.0], [40.0, 20.0], [40.0, 50.0], [10.0, 50.0]]


def _zip_folder(folder: Path, top: str | None = None) -> bytes:
    """The folder's files zipped, under `top/` when given (as a zipped folder is)."""
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for path in sorted(folder.rglob("*")):
            if path.is_file():
                name = path.relative_to(folder).as_posix()
                archive.write(path, f"{top}/{name}" if top else name)
    return buffer.getvalue()


def _zip_entries(entries: dict[str, bytes], link: str | None = None) -> bytes:
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in entries.items():
            archive.writestr(name, data)
        if link is not None:
            info = zipfile.ZipInfo(link)
            info.external_attr = (stat.S_IFLNK | 0o777) << 16
            archive.writestr(info, "/etc/passwd")
    return buffer.getvalue()


def _post(client: TestClient, data: bytes, name: str = "dataset.zip") -> Any:
    return client.post(
        "/api/imports",
        files={"archive": (name, data, "application/zip")},
        data={"run_pipeline": "false"},
    )


def _finished(client: TestClient, job_id: str) -> dict[str, Any]:
    return _finished_as(client, job_id, {})


def _finished_as(client: TestClient, job_id: str, headers: dict[str, str]) -> dict[str, Any]:
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        job: dict[str, Any] = client.get(f"/api/imports/{job_id}", headers=headers).json()
        if job["status"] in FINISHED_JOB_STATUSES:
            return job
        time.sleep(0.05)
    raise AssertionError(f"import {job_id} did not finish: {job}")


def _imported(client: TestClient, data: bytes) -> dict[str, Any]:
    answer = _post(client, data)
    assert answer.status_code == 202, answer.text
    return _finished(client, answer.json()["id"])


def _coco_dataset(folder: Path, written: tuple[str, ...] | None = None) -> Path:
    annotation = {
        "id": 1,
        "image_id": 1,
        "category_id": 1,
        "bbox": [10, 20, 30, 30],
        "segmentation": [[10, 20, 39, 20, 39, 49, 10, 49]],
    }
    coco_file(folder, [annotation], images=("a.png", "b.png"), written=written)
    return folder


def _nothing_stored(client: TestClient, settings: Settings) -> None:
    assert client.get("/api/scenes").json() == []
    imports = settings.data_dir / "imports"
    assert not imports.exists() or not any(imports.iterdir())


def test_a_coco_zip_becomes_scenes_with_their_objects(client: TestClient, tmp_path: Path) -> None:
    job = _imported(client, _zip_folder(_coco_dataset(tmp_path / "coco"), top="export"))
    assert (job["status"], job["format"], job["total"], job["done"]) == ("succeeded", "COCO", 2, 2)
    assert [p["name"] for p in job["imported"]] == ["a.png", "b.png"]
    assert job["errors"] == [] and job["skipped"] == []
    scene_id = job["imported"][0]["scene_id"]
    scene = client.get(f"/api/scenes/{scene_id}").json()["scene"]
    assert scene["name"] == "a"
    assert [(o["class"], o["source_class"]) for o in scene["objects"]] == [("sofa", "couch")]
    assert scene["objects"][0]["mask"]["source"] == "given"


def test_a_labelme_zip_is_imported(client: TestClient, tmp_path: Path) -> None:
    labelme_file(tmp_path / "lm" / "room1.json", [shape("chair", COUCH)])
    labelme_file(
        tmp_path / "lm" / "room2.json", [shape("table", [[10.0, 20.0], [40.0, 50.0]], "rectangle")]
    )
    job = _imported(client, _zip_folder(tmp_path / "lm"))
    assert (job["format"], len(job["imported"]), job["errors"]) == ("LabelMe", 2, [])
    names = sorted(s["name"] for s in client.get("/api/scenes").json())
    assert names == ["room1", "room2"]


def test_a_broken_photo_is_reported_and_the_others_imported(
    client: TestClient, tmp_path: Path
) -> None:
    folder = _coco_dataset(tmp_path / "coco", written=("a.png",))  # b.png is missing
    job = _imported(client, _zip_folder(folder))
    assert job["status"] == "succeeded"
    assert [p["name"] for p in job["imported"]] == ["a.png"]
    assert [e["name"] for e in job["errors"]] == ["b.png"]
    assert "b.png" in job["errors"][0]["message"]
    assert "/" not in job["errors"][0]["message"].replace("images/", "")  # no server path
    assert len(client.get("/api/scenes").json()) == 1


def test_an_upload_cannot_name_a_photo_outside_itself(client: TestClient, tmp_path: Path) -> None:
    """A server's other images (an absolute path, "../") are no photo an upload can import:
    each such photo is refused, the rest imported."""
    secret = tmp_path / "elsewhere" / "secret.png"
    secret.parent.mkdir()
    secret.write_bytes(photo_bytes(9))
    labelme_file(tmp_path / "lm" / "fine.json", [shape("chair", COUCH)])
    for name, image_path in (
        ("absolute", str(secret)),
        ("upward", "../" * 40 + str(secret).lstrip("/")),
    ):
        path = labelme_file(tmp_path / "lm" / f"{name}.json", [shape("chair", COUCH)])
        document = json.loads(path.read_text())
        document["imagePath"] = image_path
        path.write_text(json.dumps(document))
        path.with_suffix(".png").unlink()
    job = _imported(client, _zip_folder(tmp_path / "lm"))
    assert [p["name"].rsplit("/", 1)[-1] for p in job["imported"]] == ["fine.json"]
    errors = {e["name"].rsplit("/", 1)[-1]: e["message"] for e in job["errors"]}
    assert set(errors) == {"absolute.json", "upward.json"}
    assert all("points outside the uploaded files" in m for m in errors.values()), errors

    coco = _coco_dataset(tmp_path / "coco")
    data = json.loads((coco / "annotations.json").read_text())
    data["images"][0]["file_name"] = str(secret)
    (coco / "annotations.json").write_text(json.dumps(data))
    job = _imported(client, _zip_folder(coco))
    assert [p["name"] for p in job["imported"]] == ["b.png"]
    (error,) = job["errors"]
    assert "points outside the uploaded files" in error["message"]


def test_the_same_zip_twice_adds_nothing(client: TestClient, tmp_path: Path) -> None:
    data = _zip_folder(_coco_dataset(tmp_path / "coco"))
    first = _imported(client, data)
    second = _imported(client, data)
    assert second["imported"] == []
    assert second["skipped"] == first["imported"]  # the same photos, the same scenes
    assert len(client.get("/api/scenes").json()) == 2


def test_a_photo_stored_before_with_other_labels_is_a_new_scene_with_a_note(
    client: TestClient, tmp_path: Path
) -> None:
    first = _imported(client, _zip_folder(_coco_dataset(tmp_path / "coco")))
    coco = _coco_dataset(tmp_path / "relabelled")
    data = json.loads((coco / "annotations.json").read_text())
    data["annotations"][0]["bbox"] = [12, 20, 28, 30]  # a box drawn again
    (coco / "annotations.json").write_text(json.dumps(data))
    second = _imported(client, _zip_folder(coco))
    assert [p["name"] for p in second["imported"]] == ["a.png"]
    assert [p["name"] for p in second["skipped"]] == ["b.png"]  # the very same labels
    (relabelled,) = second["imported"]
    assert relabelled["scene_id"] != first["imported"][0]["scene_id"]
    assert relabelled["notes"] == [
        "the same photo as scene a, stored before with other labels: kept as a scene of its own"
    ]
    assert first["imported"][0]["notes"] == []


def test_a_zip_of_input_folders_queues_their_pipeline(client: TestClient, tmp_path: Path) -> None:
    for name in ("kitchen", "hall"):
        (tmp_path / "rooms" / name).mkdir(parents=True)
        (tmp_path / "rooms" / name / "img.png").write_bytes(photo_bytes(len(name)))
    answer = client.post(
        "/api/imports",
        files={"archive": ("rooms.zip", _zip_folder(tmp_path / "rooms"), "application/zip")},
    )
    job = _finished(client, answer.json()["id"])
    assert (job["format"], job["run_pipeline"]) == ("input folders", True)
    assert sorted(p["name"] for p in job["imported"]) == ["hall", "kitchen"]
    scenes = client.get("/api/scenes").json()
    assert all(s["latest_job"]["kind"] == "pipeline" for s in scenes)


def test_a_photo_skipped_as_an_archived_scene_says_where_that_scene_is(
    client: TestClient, tmp_path: Path
) -> None:
    (tmp_path / "shots").mkdir()
    (tmp_path / "shots" / "blurry.jpg").write_bytes(photo_bytes(3))
    upload = {"archive": ("shots.zip", _zip_folder(tmp_path / "shots"), "application/zip")}
    first = _finished(client, client.post("/api/imports", files=upload).json()["id"])
    [stored] = first["imported"]
    assert client.post(f"/api/scenes/{stored['scene_id']}/archive").status_code == 200
    again = _finished(client, client.post("/api/imports", files=upload).json()["id"])
    [skipped] = again["skipped"]
    assert skipped["scene_id"] == stored["scene_id"]
    assert skipped["notes"] == ["archived by local: the list's Archived filter shows it"]


def test_a_zip_of_plain_photos_makes_a_scene_of_each(client: TestClient, tmp_path: Path) -> None:
    (tmp_path / "snapshots").mkdir()
    for seed, name in enumerate(("kitchen.jpg", "Bedroom.PNG")):
        (tmp_path / "snapshots" / name).write_bytes(photo_bytes(seed))
    (tmp_path / "snapshots" / "readme.txt").write_text("taken on Monday")
    answer = client.post(
        "/api/imports",
        files={"archive": ("snaps.zip", _zip_folder(tmp_path / "snapshots"), "application/zip")},
    )
    job = _finished(client, answer.json()["id"])
    assert (job["format"], job["total"], job["errors"]) == ("photos", 2, [])
    assert sorted(p["name"] for p in job["imported"]) == ["Bedroom.PNG", "kitchen.jpg"]
    scenes = client.get("/api/scenes").json()
    assert sorted(s["name"] for s in scenes) == ["Bedroom", "kitchen"]


@pytest.mark.parametrize(
    ("entries", "link", "status", "words"),
    [
        ({"../evil.json": b"{}", "a/img.png": b"x"}, None, 422, "outside its folder"),
        ({"/etc/evil.json": b"{}"}, None, 422, "outside its folder"),
        ({"a/img.png": b"x"}, "a/detections.json", 422, "symbolic link"),
        ({"notes.txt": b"hello"}, None, 422, "holds no COCO"),
        ({"a/notes.txt": b"hello", "b/img.txt": b"x"}, None, 422, "or photo (.jpg, .png)"),
    ],
)
def test_unsafe_or_empty_zips_are_refused_with_nothing_stored(
    client: TestClient,
    settings: Settings,
    entries: dict[str, bytes],
    link: str | None,
    status: int,
    words: str,
) -> None:
    answer = _post(client, _zip_entries(entries, link))
    assert answer.status_code == status, answer.text
    assert words in answer.json()["detail"]
    _nothing_stored(client, settings)


def test_not_a_zip_is_refused(client: TestClient, settings: Settings) -> None:
    answer = _post(client, photo_bytes(), "photo.png")
    assert answer.status_code == 415
    _nothing_stored(client, settings)


def test_nyu_is_left_to_the_command_line(
    client: TestClient, settings: Settings, tmp_path: Path
) -> None:
    with h5py.File(tmp_path / "nyu_depth_v2_labeled.mat", "w") as labelled:
        labelled["images"] = [[0]]
    answer = _post(
        client,
        _zip_entries(
            {"nyu_depth_v2_labeled.mat": (tmp_path / "nyu_depth_v2_labeled.mat").read_bytes()}
        ),
    )
    assert answer.status_code == 422
    assert "holiscene import" in answer.json()["detail"]
    _nothing_stored(client, settings)


@pytest.fixture()
def small_client(settings: Settings) -> Iterator[TestClient]:
    """A server taking zips of at most 1 MB unpacked and 5 files."""
    small = settings.model_copy(update={"max_import_unpacked_mb": 1, "max_import_files": 5})
    with TestClient(create_app(small)) as test_client:
        yield test_client


def test_zip_bombs_are_refused_before_unpacking(
    small_client: TestClient, settings: Settings
) -> None:
    bomb = _zip_entries({"zeros.json": bytes(20 * 1024 * 1024)})  # 20 MB of zeros, 20 kB zipped
    assert len(bomb) < 100_000
    answer = _post(small_client, bomb)
    assert answer.status_code == 413
    assert "more than 1 MB" in answer.json()["detail"]
    many = _zip_entries({f"f{i}.json": b"{}" for i in range(6)})
    answer = _post(small_client, many)
    assert (answer.status_code, answer.json()["detail"]) == (413, "the zip holds more than 5 files")
    _nothing_stored(small_client, settings)


def test_an_import_needs_a_login_and_is_recorded_as_its_user(
    accounts: Accounts, tmp_path: Path
) -> None:
    data = _zip_folder(_coco_dataset(tmp_path / "coco"))
    files = {"archive": ("coco.zip", data, "application/zip")}
    client = accounts.client
    assert client.post("/api/imports", files=files).status_code == 401
    started = client.post(
        "/api/imports",
        files=files,
        data={"run_pipeline": "false"},
        headers=accounts.headers("ann"),
    )
    assert started.status_code == 202
    assert started.json()["started_by"] == "ann"
    job_id = started.json()["id"]
    assert client.get(f"/api/imports/{job_id}").status_code == 401
    headers = accounts.headers("ann")
    assert _finished_as(client, job_id, headers)["imported"][0]["name"] == "a.png"


def test_an_import_a_stopped_server_left_is_failed_and_its_upload_removed(
    settings: Settings,
) -> None:
    with TestClient(create_app(settings)) as client:
        workbench = client.app.state.workbench  # type: ignore[attr-defined]
        job = workbench.imports.jobs.create("rooms.zip", "COCO", 3, False, "ann")
        workbench.imports.jobs.start(job.id)
    left = settings.data_dir / "imports" / job.id / "coco"
    left.mkdir(parents=True)
    with TestClient(create_app(settings)) as client:
        failed = client.get(f"/api/imports/{job.id}").json()
    assert failed["status"] == "failed"
    assert "upload the zip again" in failed["error"]
    assert not (settings.data_dir / "imports").exists()


def test_the_login_is_checked_before_an_import_is_read(client: TestClient) -> None:
    gates = [m for m in client.app.user_middleware if m.cls is UploadLogin]  # type: ignore[attr-defined]
    assert ("POST", "/api/imports") in gates[0].kwargs["routes"]


def test_a_zip_of_sun_rgbd_image_folders_names_each_folder_by_its_path_in_the_zip(
    client: TestClient, tmp_path: Path, synthetic_folder: Path
) -> None:
    sun = tmp_path / "SUNRGBD" / "kv1" / "NYUdata"
    write_sun_folder(synthetic_folder, sun / "NYU0001")
    write_sun_folder(synthetic_folder, sun / "NYU0002")
    (sun / "NYU0002" / "intrinsics.txt").write_text("1 0 0 0 1 0 0 0\n")
    job = _imported(client, _zip_folder(tmp_path / "SUNRGBD", top="SUNRGBD"))
    assert (job["format"], job["total"]) == ("SUN RGB-D", 2)
    assert [p["name"] for p in job["imported"]] == ["SUNRGBD/kv1/NYUdata/NYU0001"]
    assert [e["name"] for e in job["errors"]] == ["SUNRGBD/kv1/NYUdata/NYU0002"]
    assert "9 numbers" in job["errors"][0]["message"]
    scene = client.get(f"/api/scenes/{job['imported'][0]['scene_id']}").json()["scene"]
    assert scene["name"] == "NYU0001"
    assert job["imported"][0]["notes"] == []


def test_an_outline_too_short_to_draw_is_left_out_with_a_note_on_its_photo(
    client: TestClient, tmp_path: Path, synthetic_folder: Path
) -> None:
    folder = tmp_path / "SUNRGBD" / "NYU0003"
    write_sun_folder(synthetic_folder, folder)
    index = folder / "annotation2Dfinal" / "index.json"
    annotation = json.loads(index.read_text())
    first = annotation["frames"][0]["polygon"][0]
    first["x"], first["y"] = first["x"][:2], first["y"][:2]  # a stray pair of clicks
    index.write_text(json.dumps(annotation))
    job = _imported(client, _zip_folder(tmp_path / "SUNRGBD", top="SUNRGBD"))
    (photo,) = job["imported"]
    assert job["errors"] == []
    (note,) = photo["notes"]
    assert note.startswith(f"polygon 0 of object {first['object']} (") and "2 point(s)" in note
    scene = client.get(f"/api/scenes/{photo['scene_id']}").json()["scene"]
    stage = next(s for s in scene["stages"] if s["name"] == "import")
    assert stage["warning"] and note in stage["note"]

"""A dataset uploaded as a .zip, imported in the background: unpacked and recognised while the
request waits (so a zip that is unsafe or holds nothing importable is refused at once), then
each photo stored as `holiscene import` stores it, one at a time, on a worker of its own.

Each photo is all or nothing (SceneStore.create), one whose files were imported before is
skipped, and one that does not read is reported and left out; so an import stopped midway
(a server restart) goes on where it stopped when the same zip is uploaded again.
"""

from __future__ import annotations

import logging
import shutil
import threading
import uuid
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import IO, TYPE_CHECKING

from holiscene_schema import ImportJob, SceneSummary

from ..core.errors import user_facing_error
from ..export.archive import scene_json
from ..export.input_folder import given_intrinsics, scene_label_files
from ..inputs import InputError, InputFiles
from ..inputs.archive import ArchiveLimits, unpack_zip
from ..inputs.datasets.items import confined_to
from ..inputs.datasets.uploaded import PhotoSource, UploadContents, upload_contents
from ..store.import_jobs import ImportJobStore
from ..store.jobs import JobQueueFullError
from ..store.scenes import SceneNotFoundError, SceneStore

if TYPE_CHECKING:
    from .workbench import Workbench

log = logging.getLogger(__name__)

# Where uploads are unpacked while their import runs (inside the data directory).
IMPORTS_FOLDER = "imports"
# How long an import waits for room in the pipeline queue before asking again.
QUEUE_WAIT_S = 2.0
RESTART_MESSAGE = (
    "the server stopped during this import; upload the zip again to go on (the photos "
    "imported so far are skipped)"
)


class DatasetImports:
    def __init__(self, workbench: Workbench, stop: threading.Event) -> None:
        self.workbench = workbench
        self.jobs = ImportJobStore(workbench.engine)
        self.root = workbench.settings.data_dir / IMPORTS_FOLDER
        self._stop = stop
        # One import at a time: two at once could both miss a photo the other is storing.
        self._executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="import")

    @property
    def limits(self) -> ArchiveLimits:
        settings = self.workbench.settings
        return ArchiveLimits.of_uploads(settings.max_import_unpacked_mb, settings.max_import_files)

    def start(
        self, upload: IO[bytes], archive: str, run_pipeline: bool, started_by: str
    ) -> ImportJob:
        """Unpack and recognise the zip, then queue its import. InputError (4xx) when it
        cannot be unpacked safely or holds nothing importable; nothing is kept then."""
        staging = self.root / f".upload-{uuid.uuid4().hex}"
        unpack_zip(upload, staging, self.limits)
        try:
            contents = upload_contents(staging)
            job = self.jobs.create(
                archive, contents.format, contents.total, run_pipeline, started_by
            )
        except BaseException:
            shutil.rmtree(staging, ignore_errors=True)
            raise
        folder = self.root / job.id
        staging.rename(folder)
        moved = UploadContents(
            contents.format,
            contents.total,
            tuple(folder / p.relative_to(staging) for p in contents.paths),
        )
        self._executor.submit(self.run, job, folder, moved)
        return job

    def run(self, job: ImportJob, folder: Path, contents: UploadContents) -> None:
        """Import every photo of the unpacked upload; the folder is removed at the end."""
        try:
            self.jobs.start(job.id)
            with confined_to(folder):
                for source in contents.sources():
                    if self._stop.is_set():
                        self.jobs.fail(job.id, RESTART_MESSAGE)
                        return
                    self._import_photo(job, source, folder)
            self.jobs.finish(job.id)
        except Exception as exc:
            log.exception("import job %s failed", job.id)
            self.jobs.fail(job.id, f"{user_facing_error(exc)} (details in the server log)")
        finally:
            shutil.rmtree(folder, ignore_errors=True)

    def _import_photo(self, job: ImportJob, source: PhotoSource, folder: Path) -> None:
        label = _shown(source.label, folder)
        try:
            inputs = source.read()
        except InputError as exc:
            self.jobs.photo_failed(job.id, label, _shown(str(exc), folder))
            return
        earlier = stored_before(self.workbench.scenes, inputs, source)
        if earlier is not None:
            # An archived scene is not in the list: the summary says where it is.
            hidden = (
                (f"archived by {earlier.archived_by}: the list's Archived filter shows it",)
                if earlier.archived_at is not None
                else ()
            )
            self.jobs.photo_done(job.id, "skipped", label, earlier, hidden)
            return
        # Another labelling of a photo stored before: kept, and said (it also shares that
        # scene's side of the held-out split).
        twin = self.workbench.scenes.first_with_photo(inputs.photo.data)
        also = (
            ()
            if twin is None
            else (
                f"the same photo as scene {twin.name}, stored before with other labels: kept "
                "as a scene of its own",
            )
        )
        author = job.started_by or "import"
        stored = self.workbench.import_scene(inputs, source.name, author, run_pipeline=False)
        if job.run_pipeline:
            self._queue_pipeline(stored.scene.id, author)
        self.jobs.photo_done(job.id, "imported", label, stored.scene, (*inputs.notes, *also))

    def _queue_pipeline(self, scene_id: str, author: str) -> None:
        """Queue the scene's pipeline, waiting while the queue is full (the server's
        max_queued_jobs bounds it for imports as for everyone)."""
        while not self._stop.is_set():
            try:
                self.workbench.start_pipeline(scene_id, author)
                return
            except JobQueueFullError:
                self._stop.wait(QUEUE_WAIT_S)

    def recover_after_restart(self) -> None:
        """Fail the imports a stopped server left and remove their unpacked uploads."""
        count = self.jobs.fail_unfinished(RESTART_MESSAGE)
        if count:
            log.warning("marked %d unfinished import(s) failed after restart", count)
        shutil.rmtree(self.root, ignore_errors=True)

    def close(self) -> None:
        self._executor.shutdown(wait=True, cancel_futures=True)


def stored_before(
    scenes: SceneStore, inputs: InputFiles, source: PhotoSource
) -> SceneSummary | None:
    """The scene this photo was stored as before, or None: the scene these very files were
    imported as, or the scene a folder of the app's download zip was written from when the
    folder's photo and scene.json are still as downloaded (uploading a download again adds no
    copy of it; a scene edited after download comes in as a new scene)."""
    earlier = scenes.imported_from(inputs)
    downloaded = source.downloaded_from
    if earlier is not None or downloaded is None:
        return earlier
    try:
        document = scenes.document(downloaded.scene_id, downloaded.revision)
        photo = scenes.image_path(downloaded.scene_id).read_bytes()
    except (SceneNotFoundError, OSError):  # another store's scene, or deleted since
        return None
    if photo != inputs.photo.data or downloaded.scene_file.read_bytes() != scene_json(
        document.scene
    ):
        return None
    # The labels an import reads: detections.json, supports.json, cam_K.txt (an edit there,
    # scene.json untouched, was skipped as "already stored" and lost).
    folder = downloaded.scene_file.parent
    written = scene_label_files(document.scene, K=given_intrinsics(document.scene))
    for name, data in written.items():
        file = folder / name
        if not file.is_file() or file.read_bytes() != data:
            return None
    return scenes.summary(downloaded.scene_id)


def _shown(text: str, folder: Path) -> str:
    """A name or message with the upload's folder on the server left out."""
    return text.replace(f"{folder}/", "").replace(str(folder), "the zip")

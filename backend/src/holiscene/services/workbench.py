"""The application's use cases, shared by the HTTP API and the CLI: import a photo, run the
pipeline on a scene as a background job, retrain the Relation Network or the object detector,
and read jobs. No HTTP here."""

from __future__ import annotations

import json
import logging
import shutil
import threading
from collections.abc import Iterator, Sequence
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from holiscene_schema import (
    FINISHED_JOB_STATUSES,
    ImportResult,
    Job,
    JobKind,
    ModelKind,
    RetrainReadiness,
    RetrainRequest,
    Scene,
    StageRun,
)

from ..core.data_dir_owner import running_batches
from ..core.db import make_engine, migrate
from ..core.errors import DomainError, user_facing_error
from ..core.settings import Settings
from ..editing.workflow_rules import LOCAL_USER, Actor, WorkflowError
from ..inputs import InputFiles, read_input_folder
from ..learning.detector import runtime as detector_runtime
from ..learning.training_api import METRICS_FILE
from ..pipeline import PLACEMENT_STAGES
from ..store import model_registry
from ..store.files import SceneFiles
from ..store.jobs import BATCH_ORPHANED, JobNotFoundError, JobStore, RetrainFinishedError
from ..store.model_registry import (
    KIND_FOLDERS,
    ModelNotFoundError,
    ModelStore,
    Registration,
    model_label,
)
from ..store.scenes import SceneChangedError, SceneStore
from ..store.users import UserStore
from ..store.workflow import WorkflowStore
from .dataset_import import DatasetImports
from .detector_retraining import (
    BOXED_SCENES,
    ROOMS_FOLDER,
    DetectorRetrainJob,
    boxed_scenes,
    check_can_retrain_detector,
    detector_train_config,
)
from .heldout import heldout_split
from .reconstruction import (
    SUPPORT_STAGES,
    Reconstruction,
    full_run_stages,
    imported_scene,
    reconstruct_scene,
)
from .relation_retraining import (
    LABELLED_SCENES,
    MIN_LABELLED_SCENES,
    RetrainJob,
    TrainingJob,
    check_can_retrain,
    labelled_scenes,
    train_config,
)

log = logging.getLogger(__name__)


class PlacementNotPossibleError(DomainError, ValueError):
    """The scene has no camera pitch/roll or room layout to place its objects in."""


@dataclass(frozen=True)
class JobRun:
    """A job's computation: the inputs and the keyword arguments of reconstruct_scene (but its
    progress callback), and the revision they were read from."""

    revision: int
    inputs: InputFiles
    arguments: dict[str, Any]
    # The stage runs of the revision read: a placement job keeps those of the stages it skips.
    earlier_stages: tuple[StageRun, ...] = ()


# The retrain job kind of each model kind.
RETRAIN_JOB_KINDS: dict[ModelKind, JobKind] = {
    "relation": "retrain",
    "detector": "detector_retrain",
}


class Workbench:
    def __init__(
        self,
        settings: Settings,
        default_model_dir: Path | None = None,
        default_detector_dir: Path | None = None,
    ) -> None:
        """`default_model_dir`, `default_detector_dir`: the Relation Network and the detector
        empty registries start from (the committed ones unless given)."""
        settings.data_dir.mkdir(parents=True, exist_ok=True)
        self.settings = settings
        self.engine = make_engine(settings.resolved_database_url)
        migrate(self.engine)
        self.scenes = SceneStore(self.engine, SceneFiles(settings.data_dir))
        self.jobs = JobStore(self.engine)
        self.users = UserStore(self.engine, settings.session_idle_timeout)
        self.workflow = WorkflowStore(self.engine, self.scenes)
        self.models = ModelStore(
            self.engine,
            settings.data_dir / KIND_FOLDERS["relation"],
            # Looked up per instance (not as a default argument) so tests can point it away.
            default_model_dir or model_registry.DEFAULT_MODEL_DIR,
        )
        self.models.seed_if_empty()
        self.detectors = ModelStore(
            self.engine,
            settings.data_dir / KIND_FOLDERS["detector"],
            default_detector_dir or model_registry.default_detector_dir(),
            kind="detector",
        )
        self.detectors.seed_if_empty()
        if default_detector_dir is None:
            self._offer_shipped_detectors()
        # One worker: the pipeline uses both cores through numpy/OpenCV already.
        self._executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="pipeline")
        # Retraining gets its own single worker: a run takes minutes and must not hold up
        # imports queued behind it; one at a time (RetrainRunningError otherwise).
        self._training = ThreadPoolExecutor(max_workers=1, thread_name_prefix="retrain")
        # The retrain jobs queued or running in this process, by job id: an admin may cancel.
        self._retrains: dict[str, TrainingJob] = {}
        self._retrain_lock = threading.Lock()
        # The queue bound's count and the insert after it, one request at a time.
        self._queue_lock = threading.Lock()
        self._stop = threading.Event()
        # Datasets uploaded as a .zip: their own worker, one import at a time.
        self.imports = DatasetImports(self, self._stop)

    def _offer_shipped_detectors(self) -> None:
        """Register the detectors shipped with the code that the registry does not hold yet,
        not active (model_registry.OFFERED_DETECTOR_DIRS, and the default when the registry
        was seeded with an older one): an admin chooses on the models page."""
        registered = [self.detectors.folder(model.id) for model in self.detectors.list_models()]
        for folder in (
            *model_registry.DEFAULT_DETECTOR_DIRS,
            *model_registry.OFFERED_DETECTOR_DIRS,
        ):
            if not (folder / detector_runtime.MODEL_FILE).is_file() or any(
                _same_detector(folder, r) for r in registered
            ):
                continue
            # A converted model has no training metrics; a trained one has its validation mAP.
            metrics_file = folder / METRICS_FILE
            metrics = json.loads(metrics_file.read_text()) if metrics_file.is_file() else {}
            self.detectors.register(
                folder,
                Registration(
                    status="candidate",
                    validation_accuracy=metrics.get("validation_map_at_0_5"),
                    data={"source": f"committed detector {folder.name}"},
                    note=(
                        "the default shipped with the code now; this registry began with "
                        "an older one (see docs/detector.md)"
                        if folder in model_registry.DEFAULT_DETECTOR_DIRS
                        else "shipped with the code, not the default (see docs/detector.md)"
                    ),
                ),
            )

    @property
    def training_dir(self) -> Path:
        """Where retrain jobs train; nothing in it outlives its job."""
        return self.settings.data_dir / "training"

    def registry(self, kind: ModelKind) -> ModelStore:
        """The registry of one kind of model."""
        return self.detectors if kind == "detector" else self.models

    def registry_of(self, model_id: str) -> ModelStore:
        """The registry holding a model, whatever its kind; ModelNotFoundError otherwise."""
        for store in (self.models, self.detectors):
            try:
                store.get(model_id)
            except ModelNotFoundError:
                continue
            return store
        raise ModelNotFoundError(f"no model {model_id!r}")

    def recover_after_restart(self) -> None:
        """Settle what a stopped server left: unfinished jobs, half-written models and
        import folders. Only for the data directory's owner (`holiscene serve` holds its
        lock, core.data_dir_owner): another server's jobs would be failed under it."""
        for kind, job_kind in RETRAIN_JOB_KINDS.items():
            self._recover_retrain_jobs(job_kind, self.registry(kind))
        # A live batch's jobs are its own to finish (core.data_dir_owner); a dead batch's
        # were never this server's: they fail as the next batch would fail them.
        count = 0
        if running_batches(self.settings.data_dir) == 0:
            count += self.jobs.fail_unfinished(BATCH_ORPHANED, batch_jobs=True)
        count += self.jobs.fail_unfinished(
            "the server stopped before this job finished; run it again", batch_jobs=False
        )
        if count:
            log.warning("marked %d unfinished job(s) failed after restart", count)
        self.imports.recover_after_restart()
        # Half-trained models and half-copied registry folders of the jobs just failed.
        shutil.rmtree(self.training_dir, ignore_errors=True)
        for registry in (self.models, self.detectors):
            for path in registry.remove_leftovers():
                log.warning("removed an incomplete model folder %s", path)
        for path in self.scenes.files.remove_abandoned_staging():
            log.warning("removed the folder of an import that did not finish: %s", path)

    def _recover_retrain_jobs(self, job_kind: JobKind, registry: ModelStore) -> None:
        for job in self.jobs.unfinished(job_kind):
            # Registration is the job's last step: a model from it is complete and in use.
            model = registry.by_job(job.id)
            if model is not None:
                self.jobs.succeed_retrain(
                    job.id, model.id, f"v{model.version} was registered before the restart"
                )
            else:
                self.jobs.fail(
                    job.id,
                    "the server stopped while this model was training; no model was "
                    "registered from it and the active model is unchanged: retrain again",
                )

    def close(self) -> None:
        self._stop.set()  # a running retrain stops at its next progress report
        self.imports.close()  # before the pipeline worker: an import queues pipeline jobs
        self._training.shutdown(wait=True, cancel_futures=True)
        self._executor.shutdown(wait=True, cancel_futures=True)
        self.engine.dispose()

    # -- use cases ---------------------------------------------------------------------

    def import_scene(
        self, inputs: InputFiles, name: str, author: str, run_pipeline: bool = True
    ) -> ImportResult:
        if run_pipeline:  # a full queue refuses the import before its scene is stored
            self.jobs.check_queue_room(self.settings.max_queued_jobs)
        # Names tell scenes apart in lists and notices: a taken one gets a number ("im3d-2 2").
        name = self.scenes.unused_name(name)
        same_photo = self.scenes.first_with_photo(inputs.photo.data)
        summary = self.scenes.create(inputs, imported_scene(inputs, name), author)
        job = self.start_pipeline(summary.id, author) if run_pipeline else None
        return ImportResult(
            scene=summary.model_copy(update={"latest_job": job}), job=job, same_photo=same_photo
        )

    def start_pipeline(self, scene_id: str, started_by: str) -> Job:
        """Queue a pipeline job on the scene's latest revision. SceneJobRunningError when the
        scene has a job waiting or running, JobQueueFullError when the queue is full."""
        revision = self.scenes.summary(scene_id).revision
        return self._queue(scene_id, revision, "pipeline", started_by)

    def _queue(self, scene_id: str, revision: int, kind: JobKind, started_by: str) -> Job:
        with self._queue_lock:
            job = self.jobs.create(
                scene_id, revision, kind, started_by, max_waiting=self.settings.max_queued_jobs
            )
        self._executor.submit(self.run_job, job.id)
        return job

    def start_placement(self, scene_id: str, started_by: str) -> Job:
        """Queue a placement job: the stages after the layout, on the current revision's
        camera, layout, masks and supports (after a person moved the layout)."""
        current = self.scenes.document(scene_id)
        scene = current.scene
        camera = scene.camera
        if camera is None or camera.pitch_deg is None or scene.layout.corners_3d is None:
            raise PlacementNotPossibleError(
                "the scene has no camera pitch/roll or room layout yet: run the whole pipeline, "
                "or set the room by hand (Edit layout) and save it"
            )
        if scene.objects and all(o.mask is None for o in scene.objects):
            raise PlacementNotPossibleError(
                "the objects have no masks yet: run the whole pipeline "
                "(it keeps a room set by hand)"
            )
        return self._queue(scene_id, current.revision, "placement", started_by)

    def retrain_readiness(self, kind: ModelKind = "relation") -> RetrainReadiness:
        """How many stored scenes a retraining of the kind would learn from, and how many it
        needs: the models page says so before an admin presses Retrain."""
        if kind == "detector":
            ids, what = [s.scene_id for s in boxed_scenes(self.scenes)], BOXED_SCENES
        else:
            ids, what = [s.scene_id for s in labelled_scenes(self.scenes)], LABELLED_SCENES
        return RetrainReadiness(
            labelled_scenes=len(ids),
            heldout_scenes=len(heldout_split(ids, self.scenes.split_keys(ids))[1]),
            needed=MIN_LABELLED_SCENES,
            what=what,
            other_retrain=self.jobs.other_retrain(RETRAIN_JOB_KINDS[kind]),
        )

    def start_retrain(self, request: RetrainRequest, kind: ModelKind = "relation") -> Job:
        """Queue a retrain job of a kind of model (admin). NotEnoughLabelsError when too few
        scenes are labelled, RetrainRunningError when a retrain job is queued or running."""
        if kind == "detector":
            check_can_retrain_detector(self.scenes)
        else:
            check_can_retrain(self.scenes)
        with self._retrain_lock:
            job = self.jobs.create_retrain(RETRAIN_JOB_KINDS[kind], started_by=request.author)
        retrain: TrainingJob
        if kind == "detector":
            retrain = self.retrain_detector_job(job.id, request)
            options = (
                f"epochs={retrain.config.epochs}, synthetic_rooms={retrain.config.synthetic_rooms}"
            )
        else:
            retrain = self.retrain_job(job.id, request)
            options = (
                f"max_epochs={retrain.config.max_epochs}, "
                f"synthetic_scenes={retrain.config.synthetic_scenes}"
            )
        self.jobs.append_log(job.id, f"queued by {request.author}: {options}")
        self._retrains[job.id] = retrain
        self._training.submit(self._run_retrain, retrain)
        return self.jobs.get(job.id)

    def _run_retrain(self, retrain: TrainingJob) -> None:
        try:
            retrain.run()
        finally:
            self._retrains.pop(retrain.job_id, None)

    def cancel_retrain(self, job_id: str, by: str) -> Job:
        """Cancel a queued or running retrain job (admin): it ends cancelled, at its next step
        or epoch, and registers nothing. RetrainFinishedError when it has ended already."""
        job = self.jobs.get(job_id)  # JobNotFoundError for an unknown id
        if job.kind not in RETRAIN_JOB_KINDS.values():
            raise JobNotFoundError(f"no retrain job {job_id!r}")
        retrain = self._retrains.get(job_id)
        if job.status in FINISHED_JOB_STATUSES or retrain is None:
            raise RetrainFinishedError(
                f"the retrain job {job_id} is not running: nothing to cancel"
            )
        retrain.cancel(by)
        self.jobs.append_log(job_id, f"cancel asked by {by}: stopping at the next step")
        return self.jobs.get(job_id)

    def retrain_job(self, job_id: str, request: RetrainRequest) -> RetrainJob:
        return RetrainJob(
            job_id=job_id,
            jobs=self.jobs,
            scenes=self.scenes,
            models=self.models,
            work_root=self.training_dir,
            config=train_config(request),
            author=request.author,
            promote_min_items=self.settings.promote_min_heldout_items,
            stop=self._stop,
        )

    def retrain_detector_job(self, job_id: str, request: RetrainRequest) -> DetectorRetrainJob:
        return DetectorRetrainJob(
            job_id=job_id,
            jobs=self.jobs,
            scenes=self.scenes,
            models=self.detectors,
            work_root=self.training_dir,
            config=detector_train_config(request, self.settings.data_dir / ROOMS_FOLDER),
            author=request.author,
            promote_min_items=self.settings.promote_min_heldout_items,
            stop=self._stop,
        )

    def run_job(self, job_id: str) -> None:
        """Run a queued pipeline job to its end; every failure is recorded on the job."""
        job = self.jobs.get(job_id)
        with self.recording_outcome(job):
            run = self.job_run(job)
            result = reconstruct_scene(
                run.inputs,
                **run.arguments,
                progress=lambda stage, fraction: self.jobs.progress(job_id, stage, fraction),
            )
            self.store_job_result(job, run, result)

    def job_run(self, job: Job) -> JobRun:
        """What a pipeline or placement job computes from, read now. The computation itself
        (reconstruct_scene) needs neither the store nor this machine's files but the models'
        folders, so it can run elsewhere (services.batch) and come back to store_job_result."""
        if job.scene_id is None or job.base_revision is None:
            raise ValueError(f"job {job.id} is not a pipeline job")
        # Someone may have taken the scene while the job waited in the queue.
        self.workflow.check_job_allowed(job.scene_id, self.job_starter(job))
        placement = job.kind == "placement"
        # A placement job: the revision it was asked on (the layout the person saw when
        # asking); a pipeline job: the latest.
        current = self.scenes.document(job.scene_id, job.base_revision if placement else None)
        stages, stage_options = job_stages(placement, current.scene)
        arguments: dict[str, Any] = {
            "name": current.scene.name,
            "image_file": current.scene.image.file,
            "pinned_supports": [s for s in current.scene.supports if s.source == "manual"],
            "pinned_objects": [o for o in current.scene.objects if o.set_by_person],
            "removed_objects": current.scene.removed_by_person,
            "stages": stages,
            "models_dir": self.settings.models_dir,
            **self._active_models(),
            "stage_options": stage_options,
        }
        # The depth stored with the scene, so a placement job measures the boxes from it too.
        inputs = read_input_folder(
            self.scenes.files.folder(job.scene_id), use_depth=current.scene.depth is not None
        )
        return JobRun(
            revision=current.revision,
            inputs=inputs,
            arguments=arguments,
            earlier_stages=tuple(current.scene.stages),
        )

    def _active_models(self) -> dict[str, Any]:
        """reconstruct_scene's model arguments, from one look at each registry: the promoted
        Relation Network's and detector's folders (None: the committed defaults) and their
        names by the stages that run them, so the names are those of the models run."""
        relation = self.models.active_or_none()
        detector = self.detectors.active_or_none()
        names = {stage: model_label(relation) for stage in SUPPORT_STAGES if relation}
        if detector:
            names["objects_from_detector"] = model_label(detector)
        return {
            "support_model_dir": self.models.folder(relation.id) if relation else None,
            "detector_model_dir": self.detectors.folder(detector.id) if detector else None,
            "model_names": names,
        }

    def store_job_result(self, job: Job, run: JobRun, result: Reconstruction) -> None:
        """Store a job's computed result as the scene's next revision and finish the job."""
        assert job.scene_id is not None and job.base_revision is not None  # job_run checked
        if job.kind == "placement":
            placed = result.scene.model_copy(
                update={"stages": with_earlier_runs(run.earlier_stages, result.scene.stages)}
            )
            # The stages this job ran (the revision keeps the earlier ones' notes too), and
            # who asked: the history reads "re-placed objects", not a whole pipeline run.
            ran = [
                s.name.replace("_", " ")  # read by people in the history: "boxes by refiner"
                for s in result.scene.stages
                if s.name != "scene_from_revision"
            ]
            revision = self.scenes.commit_placement_result(
                job.scene_id,
                job.base_revision,
                placed,
                result.glb,
                author=job.started_by or "pipeline",
                summary=f"objects placed again: {', '.join(ran)}",
            )
        else:
            # A layout set by hand up to the revision read above is in the result (kept);
            # one set after it would be overwritten, so that refuses the result.
            revision = self.scenes.commit_pipeline_result(
                job.scene_id,
                result.scene,
                result.glb,
                base_revision=run.revision,
                author=job.started_by or "pipeline",
            )
        notes = [f"{s.name}: {s.note}" for s in result.scene.stages if s.note]
        self.jobs.succeed(job.id, revision, " | ".join(notes) or "done")

    @contextmanager
    def recording_outcome(self, job: Job) -> Iterator[None]:
        """Record on the job whatever fails in the block: the job is failed with a message
        for its starter, and nothing is raised."""
        try:
            yield
        except SceneChangedError as changed:
            log.warning("job %s not stored: %s", job.id, changed)
            self.jobs.fail(job.id, scene_changed_message(job, changed))
        except WorkflowError as refused:  # e.g. submitted for review while the job ran
            log.warning("job %s not stored: %s", job.id, refused)
            self.jobs.fail(job.id, str(refused))
        except Exception as exc:
            log.exception("pipeline job %s failed", job.id)  # the traceback: for the admin
            self.jobs.fail(job.id, f"{user_facing_error(exc)} (details in the server log)")

    def job_starter(self, job: Job) -> Actor:
        """Who started a job, with their role now: the local user plays every part; a name
        without an account ("import", or a job from before this was recorded) may do what an
        annotator may."""
        name = job.started_by or "import"
        if name == LOCAL_USER:
            return Actor(LOCAL_USER, "admin", local=True)
        return Actor(name, self.users.roles().get(name, "annotator"))

    def import_folder(self, folder: Path, name: str | None = None) -> ImportResult:
        """Import an input folder and run the pipeline on it now (for demo data and scripts)."""
        return self.import_and_run(read_input_folder(folder), name or folder.name)

    def import_and_run(self, inputs: InputFiles, name: str) -> ImportResult:
        """Import checked inputs (a folder's, a dataset's photo) and run the pipeline on them
        now, in this thread."""
        result = self.import_scene(inputs, name, "import", False)
        job = self.jobs.create(result.scene.id, result.scene.revision, started_by="import")
        self.run_job(job.id)
        finished = self.jobs.get(job.id)
        return ImportResult(scene=self.scenes.summary(result.scene.id, finished), job=finished)


def _same_detector(shipped: Path, registered: Path) -> bool:
    """The same detector files. Runs at every start: the model files (megabytes) are read only
    when their sizes and the small metadata files already agree (retrained heads share the
    shipped head's size, not its metadata)."""
    model, copy = shipped / detector_runtime.MODEL_FILE, registered / detector_runtime.MODEL_FILE
    metadata = detector_runtime.METADATA_FILE
    return (
        copy.is_file()
        and (registered / metadata).is_file()
        and model.stat().st_size == copy.stat().st_size
        and (shipped / metadata).read_bytes() == (registered / metadata).read_bytes()
        and model.read_bytes() == copy.read_bytes()
    )


def with_earlier_runs(earlier: Sequence[StageRun], rerun: Sequence[StageRun]) -> list[StageRun]:
    """A placement job's stage runs over the pipeline's: it re-runs only the stages after the
    layout, and what the others said (masks left as boxes, a detector that found nothing)
    still holds, so the scene page keeps showing it."""
    again = {run.name: run for run in rerun}
    kept = [again.pop(run.name, run) for run in earlier]
    return [*again.values(), *kept]


def job_stages(
    placement: bool, scene: Scene
) -> tuple[tuple[str, ...], dict[str, dict[str, Any]] | None]:
    """The stages of a placement or pipeline job on `scene` (the revision it read), and their
    options: a placement job starts from the stored scene; a full re-run keeps a room layout
    set by hand (and its camera), as it keeps people's supports."""
    if placement:
        return PLACEMENT_STAGES, {"scene_from_revision": {"scene": scene}}
    return full_run_stages(scene)


def scene_changed_message(job: Job, changed: SceneChangedError) -> str:
    """Why a job's result was not stored, and what to do."""
    moved = f"revision {changed.base_revision} -> {changed.current_revision}"
    if job.kind == "placement":
        return (
            f"the scene changed while objects were being re-placed ({moved}); nothing was "
            "overwritten; run re-place again"
        )
    return (
        f"the room layout was set by hand while the pipeline ran ({moved}); the run's result "
        "was not stored, so that layout stays; a new run keeps it"
    )

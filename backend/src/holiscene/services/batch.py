"""Pre-annotating many stored scenes on Ray (`holiscene batch`, `holiscene import
--run-pipeline`).

Ray workers only compute: each gets one scene's checked inputs and the arguments of
reconstruct_scene in memory (the models' folders travel as bytes through Ray's object store,
so the nodes of a cluster need not see the data directory) and returns the scene and its GLB.
The driver alone writes to the store, exactly as a pipeline job does (Workbench.job_run and
store_job_result): people's supports, objects and hand-set layout are kept, and a scene
changed in a way the result cannot be merged with is left as it is, the job failed.

Ray is imported here only, when a batch starts: the server and the other commands never load
it (it takes a while to import and to start).
"""

from __future__ import annotations

import hashlib
import os
import shutil
import tempfile
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..core.data_dir_owner import batch_presence
from ..core.errors import NotFoundError
from ..core.interrupts import stop_signals_deferred
from ..inputs import InputFiles
from ..store.jobs import BATCH_ORPHANED, BATCH_STAGE, SceneJobRunningError
from .reconstruction import Reconstruction, reconstruct_scene

if TYPE_CHECKING:
    from holiscene_schema import Job

    from ..store.scenes import SceneStore
    from .workbench import JobRun, Workbench

# Who batch jobs are started by: the name import's own pipeline runs carry, so a scene a
# person holds is refused to them as to any annotator's job (workflow_rules.check_job_allowed).
BATCH_STARTER = "import"
# Ray's single-machine mode (meant for macOS and Windows, where it is the default): the node's
# address is the loopback one, and every Ray process listens on 127.0.0.1 only. Read by Ray
# when it is imported, and inherited by the processes it starts.
LOCAL_ONLY_ENV = ("RAY_ENABLE_WINDOWS_OR_OSX_CLUSTER", "0")
# Token authentication between the local Ray's processes, which Ray turns on by default for a
# local Ray anyway; asked for explicitly, Ray does not print a warning about it.
LOCAL_AUTH_ENV = ("RAY_AUTH_MODE", "token")
LOOPBACK = "127.0.0.1"
# reconstruct_scene's arguments that name folders on the driver's machine.
FOLDER_ARGUMENTS = ("models_dir", "support_model_dir", "detector_model_dir")
STOPPED = "the batch stopped before this scene was done; run holiscene batch again"


class UnknownScenesError(NotFoundError):
    """Scene ids asked for that the store does not hold."""


@dataclass
class BatchReport:
    """What a batch did: the scenes stored, and the ones that failed with why."""

    done: list[str] = field(default_factory=list)
    failed: dict[str, str] = field(default_factory=dict)


# Called once per scene when it is finished: its id and, when it failed, why.
SceneFinished = Callable[[str, str | None], None]


def scenes_to_run(
    scenes: SceneStore, wanted: Sequence[str] = (), again: bool = False
) -> tuple[list[str], list[str]]:
    """The scenes a batch runs (oldest first), and the ones it skips because the pipeline
    already stored a result on them (all of them with `again`: none skipped). `wanted`: only
    these scenes (UnknownScenesError when one is not stored), else every stored one."""
    stored = [s.id for s in reversed(scenes.list_summaries())]
    if wanted:
        unknown = sorted(set(wanted) - set(stored))
        if unknown:
            raise UnknownScenesError(f"no stored scene {', '.join(unknown)}")
        stored = [s for s in stored if s in set(wanted)]
    done = set() if again else scenes.with_pipeline_result()
    return [s for s in stored if s not in done], [s for s in stored if s in done]


@contextmanager
def ray_runtime(address: str | None, workers: int | None) -> Iterator[int]:
    """Ray for one batch: a local Ray of `workers` CPUs on 127.0.0.1 only (no dashboard),
    stopped at the end, or the cluster at `address`; a Ray this process started already is
    used as it is (the tests start one for all their batches). Yields how many photos to
    compute at once: `workers`, else the machine's or the cluster's CPU count."""
    if address is None:
        os.environ[LOCAL_ONLY_ENV[0]] = LOCAL_ONLY_ENV[1]
        os.environ.setdefault(*LOCAL_AUTH_ENV)
    import ray

    started = not ray.is_initialized()
    if started and address is None:
        ray.init(
            address="local",  # a Ray of its own, never one RAY_ADDRESS or an earlier run names
            num_cpus=workers or os.cpu_count() or 1,
            include_dashboard=False,
            configure_logging=False,
            log_to_driver=False,  # a photo's failure comes back as its error, not as log lines
        )
        _check_loopback()
    elif started:
        ray.init(address=address, configure_logging=False, log_to_driver=False)
    try:
        cpus = ray.cluster_resources().get("CPU", 1)  # type: ignore[no-untyped-call]
        yield workers or max(1, int(cpus))
    finally:
        if started:
            ray.shutdown()


def _check_loopback() -> None:
    """Stop a local Ray that came up on another address than the loopback one (Ray was
    imported before LOCAL_ONLY_ENV was set)."""
    import ray

    if ray.util.get_node_ip_address() != LOOPBACK:  # type: ignore[no-untyped-call]
        ray.shutdown()
        raise RuntimeError(
            "Ray was loaded before the batch started and would not listen on "
            "127.0.0.1 only; run the batch in a process of its own"
        )


def run_batch(
    workbench: Workbench,
    scene_ids: Sequence[str],
    workers: int,
    on_finished: SceneFinished | None = None,
) -> BatchReport:
    """Run the pipeline on the scenes on Ray (inside ray_runtime), `workers` photos at a time,
    storing each result as it comes back. A scene that fails is reported and the rest go on;
    if the batch itself stops (interrupted), the jobs of the photos still out are failed, so
    the next batch takes those scenes again. Killed (no `finally` runs), it leaves them
    running: the next batch fails them when no other batch runs (core.data_dir_owner)."""
    import ray

    batch = _Batch(workbench, on_finished)
    waiting = deque(scene_ids)
    with batch_presence(workbench.settings.data_dir) as others:
        if not others:  # what a killed batch left out is nobody's: its scenes can run again
            workbench.jobs.fail_unfinished(BATCH_ORPHANED, batch_jobs=True)
        try:
            while waiting or batch.out:
                while waiting and len(batch.out) < workers:
                    batch.start(waiting.popleft())
                if batch.out:
                    (ready,), _ = ray.wait(list(batch.out), num_returns=1)
                    batch.collect(ready)
        finally:
            for scene in batch.out.values():
                workbench.jobs.fail(scene.job_id, STOPPED)
    return batch.report


def new_batch_job(workbench: Workbench, scene_id: str) -> Job:
    """The scene's job on its latest revision, marked the batch's (BATCH_STAGE) from the
    start: a batch killed before it sends the photo out leaves a job that the next batch
    recognises as a killed batch's and fails, as it does those left out on a worker."""
    revision = workbench.scenes.summary(scene_id).revision
    return workbench.jobs.create(scene_id, revision, started_by=BATCH_STARTER, stage=BATCH_STAGE)


@dataclass(frozen=True)
class _Out:
    """A scene whose photo is on a worker."""

    scene_id: str
    job_id: str
    run: JobRun


class _Batch:
    """The driver's side: starts each scene's job and sends its photo to a worker, stores
    what comes back, and keeps the report."""

    def __init__(self, workbench: Workbench, on_finished: SceneFinished | None) -> None:
        import ray

        self.workbench = workbench
        self.on_finished = on_finished
        self.report = BatchReport()
        self.out: dict[Any, _Out] = {}  # Ray's reference to a result -> its scene
        self._compute = ray.remote(num_cpus=1, max_retries=0)(compute_scene)
        self._shipped = _ShippedFolders()

    def start(self, scene_id: str) -> None:
        """Make the scene's job and send its computation to a worker; a job that could not
        be made or read finishes the scene at once."""
        workbench = self.workbench
        # A stop that comes once the job is made waits until it is out (run_batch then
        # fails it), so no job is left queued.
        with stop_signals_deferred():
            try:
                job = new_batch_job(workbench, scene_id)
            except SceneJobRunningError as busy:  # a server runs it: its result is not ours
                self._finished(scene_id, str(busy))
                return
            run = None
            with workbench.recording_outcome(job):
                run = workbench.job_run(job)
                workbench.jobs.progress(job.id, BATCH_STAGE, 0.0)  # out on a Ray worker
            if run is None:
                self._finished(scene_id, workbench.jobs.get(job.id).error)
                return
            ref = self._compute.remote(run.inputs, self._shipped.arguments(run.arguments))
            self.out[ref] = _Out(scene_id, job.id, run)

    def collect(self, ref: Any) -> None:
        """Store a worker's result as its job's, or record the worker's failure on the job."""
        from ray.exceptions import RayTaskError

        # Taken off the list and stored as one step: a stop between the two would leave
        # the job running with no one to fail it.
        with stop_signals_deferred():
            scene = self.out.pop(ref)
            job = self.workbench.jobs.get(scene.job_id)
            with self.workbench.recording_outcome(job):
                try:
                    result = _ray_get(ref)
                except RayTaskError as failed:  # the exception raised on the worker, as it was
                    raise failed.cause or failed from None
                self.workbench.store_job_result(job, scene.run, result)
        job = self.workbench.jobs.get(scene.job_id)
        self._finished(scene.scene_id, None if job.status == "succeeded" else job.error)

    def _finished(self, scene_id: str, error: str | None) -> None:
        if error is None:
            self.report.done.append(scene_id)
        else:
            self.report.failed[scene_id] = error
        if self.on_finished is not None:
            self.on_finished(scene_id, error)


def _ray_get(ref: Any) -> Reconstruction:
    import ray

    result: Reconstruction = ray.get(ref)
    return result


def compute_scene(inputs: InputFiles, arguments: dict[str, Any]) -> Reconstruction:
    """One photo through the pipeline on a Ray worker: the folders in `arguments` arrive as
    references to PackedFolder objects and are rebuilt on this node first."""
    import ray

    local = dict(arguments)
    for name in FOLDER_ARGUMENTS:
        if local.get(name) is not None:
            local[name] = ray.get(local[name]).unpacked()
    return reconstruct_scene(inputs, **local)


@dataclass(frozen=True)
class PackedFolder:
    """A folder's files as bytes (relative path -> content), to rebuild on a worker."""

    files: dict[str, bytes]

    @classmethod
    def of(cls, folder: Path) -> PackedFolder:
        files = sorted(p for p in folder.rglob("*") if p.is_file())
        return cls({p.relative_to(folder).as_posix(): p.read_bytes() for p in files})

    @property
    def digest(self) -> str:
        hasher = hashlib.sha256()
        for name, data in sorted(self.files.items()):
            hasher.update(f"{name}\0{len(data)}\0".encode())
            hasher.update(data)
        return hasher.hexdigest()[:16]

    def unpacked(self) -> Path:
        """The folder rebuilt in this node's temporary directory, once per content: the same
        path for every task, so the models loaded from it stay cached in the worker."""
        target = Path(tempfile.gettempdir()) / "holiscene-batch" / self.digest
        if target.is_dir():
            return target
        target.parent.mkdir(parents=True, exist_ok=True)
        staging = Path(tempfile.mkdtemp(prefix=f".{self.digest}-", dir=target.parent))
        try:
            for name, data in self.files.items():
                (staging / name).parent.mkdir(parents=True, exist_ok=True)
                (staging / name).write_bytes(data)
            os.replace(staging, target)
        except OSError:
            if not target.is_dir():  # not another worker of this node that was faster
                raise
        finally:
            shutil.rmtree(staging, ignore_errors=True)
        return target


class _ShippedFolders:
    """The driver's folders put into Ray's object store, each once per batch."""

    def __init__(self) -> None:
        self._refs: dict[Path, Any] = {}

    def arguments(self, arguments: dict[str, Any]) -> dict[str, Any]:
        """`arguments` with each folder replaced by its reference in the object store."""
        import ray

        shipped = dict(arguments)
        for name in FOLDER_ARGUMENTS:
            folder = shipped.get(name)
            if folder is not None:
                if folder not in self._refs:
                    self._refs[folder] = ray.put(PackedFolder.of(Path(folder)))
                shipped[name] = self._refs[folder]
        return shipped

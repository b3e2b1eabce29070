"""Retraining the Relation Network from the stored labelled scenes (an admin's background job).

A retrain job gathers the scenes people labelled, keeps a fixed share of them out of training,
trains a new model in a temporary folder, measures it and the active model on the held-out
scenes, registers it whatever the outcome, and makes it active only if it does better there
(one exactly as good is kept as a candidate: heldout_verdict).

Nothing half-made reaches the registry: training writes under `<data_dir>/training/<job>/`,
which is deleted when the job ends and at every start; the registry copies a model in only
after training and evaluation finished.
"""

from __future__ import annotations

import dataclasses
import logging
import re
import shutil
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from holiscene_schema import ModelInfo, ModelStatus, RetrainRequest, Scene, SceneSummary
from holiscene_schema.api import FEW_HELDOUT_ITEMS

from ..core.errors import DomainError, user_facing_error
from ..inputs import load_photo
from ..learning.samples import SupportSample, sample_from_scene
from ..learning.training_api import TrainConfig, percent
from ..store.jobs import JobStore
from ..store.model_registry import ModelStore, Registration
from ..store.scenes import SceneStore
from .heldout import heldout_split

log = logging.getLogger(__name__)

MIN_LABELLED_SCENES = 2  # one to learn from, one to judge by
# "<what> <done>/<total>": a counter line of the training log.
_COUNTER = re.compile(r"^(.*?)\s*\d+\s*/\s*\d+\s*$")
# Share of the job's progress bar each step takes (training is nearly all of it).
GATHER_END, TRAIN_END = 0.05, 0.9


class NotEnoughLabelsError(DomainError, ValueError):
    """Retraining needs labelled scenes to learn from and to judge the new model by."""


class RetrainStopped(RuntimeError):
    """The server is shutting down: the job ends failed and registers nothing."""


@dataclass(frozen=True)
class LabelledScene:
    scene_id: str
    revision: int
    scene: Scene  # the current revision, with only the supports people set

    @property
    def key(self) -> str:
        return f"{self.scene_id}@r{self.revision}"


def people_labelled(scene_id: str, revision: int, scene: Scene) -> LabelledScene | None:
    """The revision with only the supports a person set (`source == "manual"`), or None when
    it has none.

    Supports the pipeline guessed are left out: training on them would teach the network its
    own priors, and judging by them would reward agreeing with the priors."""
    manual = [s for s in scene.supports if s.source == "manual"]
    if not manual:
        return None
    return LabelledScene(scene_id, revision, scene.model_copy(update={"supports": manual}))


def scenes_to_learn_from(scenes: SceneStore) -> list[SceneSummary]:
    """The stored scenes a retraining of any kind may read labels from: all but the rejected
    ones (a reviewer said their labels are wrong; they count again once fixed and resubmitted)."""
    return [summary for summary in scenes.list_summaries() if summary.state != "rejected"]


def labelled_scenes(scenes: SceneStore) -> list[LabelledScene]:
    """Scenes to learn from (`scenes_to_learn_from`) whose current revision has supports set
    by a person."""
    found = []
    for summary in scenes_to_learn_from(scenes):
        doc = scenes.document(summary.id)
        item = people_labelled(summary.id, doc.revision, doc.scene)
        if item is not None:
            found.append(item)
    return found


def labelled_sample(item: LabelledScene, photo: Path) -> SupportSample | None:
    """The training sample of a labelled scene, named `<scene id>@r<revision>`; None when none
    of its labels is one the network learns (e.g. only walls' supports)."""
    sample = sample_from_scene(item.scene, load_photo(photo.read_bytes()).rgb)
    if sample is None or sample.labelled == 0:
        return None
    # Named by scene and revision: data.json then says exactly what was seen.
    return dataclasses.replace(sample, name=item.key)


def stored_samples(
    scenes: SceneStore,
    labelled: Sequence[LabelledScene] | None = None,
    before_each: Callable[[], None] = lambda: None,
) -> list[SupportSample]:
    """The training samples of labelled scenes (all of the store's when not given)."""
    samples = []
    for item in labelled_scenes(scenes) if labelled is None else labelled:
        before_each()
        sample = labelled_sample(item, scenes.image_path(item.scene_id))
        if sample is not None:
            samples.append(sample)
    return samples


def train_config(request: RetrainRequest, cache_dir: Path | None = None) -> TrainConfig:
    """The training configuration: the defaults, with what the admin chose."""
    changes: dict[str, Any] = {}
    if request.max_epochs is not None:
        changes["max_epochs"] = request.max_epochs
    if request.synthetic_scenes is not None:
        changes["synthetic_scenes"] = request.synthetic_scenes
    if cache_dir is not None:
        changes["cache_dir"] = cache_dir
    return dataclasses.replace(TrainConfig(), **changes)


# What a labelled scene is for the Relation Network, as the models page says it.
LABELLED_SCENES = "scenes with supports set by a person, rejected ones left out"


def check_can_retrain(scenes: SceneStore) -> int:
    """The number of labelled scenes; NotEnoughLabelsError when there are too few."""
    ids = [s.scene_id for s in labelled_scenes(scenes)]
    if len(ids) < MIN_LABELLED_SCENES:
        raise NotEnoughLabelsError(
            f"retraining needs at least {MIN_LABELLED_SCENES} labelled scenes ({LABELLED_SCENES}), "
            f"{len(ids)} found: correct the supports of more scenes"
        )
    require_two_photos(scenes, ids, "labelled scenes")
    return len(ids)


def require_two_photos(scenes: SceneStore, scene_ids: Sequence[str], what: str) -> None:
    """NotEnoughLabelsError when the scenes are all of one photo: scenes of one photo share a
    side of the held-out split (heldout.py), so none could judge a model that learned it."""
    if len(set(scenes.split_keys(scene_ids).values())) < MIN_LABELLED_SCENES:
        raise NotEnoughLabelsError(
            f"the {len(scene_ids)} {what} are all of one photo, and a model is never judged on "
            "a photo it learned from: label a scene of another photo"
        )


@dataclass(kw_only=True)
class TrainingJob:
    """What every retrain job shares (the Relation Network's below, the object detector's in
    detector_retraining.py): `run` records every outcome on the job and never raises, the
    training folder is removed at the end, and progress and log lines go to the job."""

    job_id: str
    jobs: JobStore
    scenes: SceneStore
    models: ModelStore  # the registry of the kind being retrained
    work_root: Path  # <data_dir>/training
    author: str
    # Held-out items a better model needs to be made active by itself (heldout_verdict).
    promote_min_items: int = FEW_HELDOUT_ITEMS
    stop: threading.Event = dataclasses.field(default_factory=threading.Event)
    # An admin's cancel of this job (the server's stop is `stop`): who asked, once asked.
    cancelled_by: str | None = dataclasses.field(default=None, init=False)
    _started: float = dataclasses.field(default_factory=time.monotonic, init=False)
    _last_counter: str | None = dataclasses.field(default=None, init=False)

    def run(self) -> None:
        self._started = time.monotonic()
        work_dir = self.work_root / self.job_id
        try:
            self._run(work_dir)
        except RetrainStopped as exc:
            self._log(f"stopped: {exc}")
            outcome = f"{exc}; no model was registered from this job"
            if self.cancelled_by is not None:
                self.jobs.cancelled(self.job_id, outcome)
            else:
                self.jobs.fail(self.job_id, outcome)
        except Exception as exc:
            log.exception("retrain job %s failed", self.job_id)
            self._log(f"failed: {user_facing_error(exc)}")
            self.jobs.fail(
                self.job_id,
                f"{user_facing_error(exc)}; no model was registered from this job",
            )
        finally:
            shutil.rmtree(work_dir, ignore_errors=True)

    def _run(self, work_dir: Path) -> None:
        raise NotImplementedError

    # -- job reporting -------------------------------------------------------------------

    def _step(self, stage: str, fraction: float) -> None:
        self._check_stop()
        self.jobs.progress(self.job_id, stage, fraction)
        self._log(f"{stage}…")

    def _training_progress(self, fraction: float, line: str) -> None:
        """A training run's report: its share of the progress bar, and its line in the log."""
        self._check_stop()
        share = GATHER_END + (TRAIN_END - GATHER_END) * min(max(fraction, 0.0), 1.0)
        self.jobs.progress(self.job_id, "training", share)
        if line:
            self._log(line)

    def _log(self, line: str) -> None:
        # A counter ("synthetic scenes 7/1200") replaces its previous value instead of
        # adding a line per step; everything else is kept.
        counter = _COUNTER.match(line)
        replace = counter is not None and counter.group(1) == self._last_counter
        self._last_counter = counter.group(1) if counter else None
        elapsed = time.monotonic() - self._started
        self.jobs.append_log(self.job_id, f"[{elapsed:6.1f} s] {line}", replace_last=replace)

    def cancel(self, by: str) -> None:
        """Stop at the next progress report (a step or an epoch); nothing is registered."""
        self.cancelled_by = by

    def _check_stop(self) -> None:
        if self.cancelled_by is not None:
            raise RetrainStopped(f"cancelled by {self.cancelled_by}")
        if self.stop.is_set():
            raise RetrainStopped("the server stopped while this job ran")


@dataclass(kw_only=True)
class RetrainJob(TrainingJob):
    """One Relation Network retrain job's run."""

    config: TrainConfig

    # -- steps ---------------------------------------------------------------------------

    def _run(self, work_dir: Path) -> None:
        self._step("gathering labelled scenes", 0.0)
        labelled = labelled_scenes(self.scenes)
        if len(labelled) < MIN_LABELLED_SCENES:
            raise NotEnoughLabelsError(
                f"retraining needs at least {MIN_LABELLED_SCENES} labelled scenes, "
                f"{len(labelled)} found"
            )
        ids = [s.scene_id for s in labelled]
        train_ids, heldout_ids = heldout_split(ids, self.scenes.split_keys(ids))
        by_id = {s.scene_id: s for s in labelled}
        train = self._samples([by_id[i] for i in train_ids])
        heldout = self._samples([by_id[i] for i in heldout_ids])
        if not heldout:
            raise NotEnoughLabelsError("none of the held-out scenes has a labelled object")
        heldout_objects = sum(s.labelled for s in heldout)
        self._log(
            f"{len(labelled)} labelled scenes: {len(train)} to train on, "
            f"{len(heldout)} held out ({heldout_objects} labelled "
            f"{'object' if heldout_objects == 1 else 'objects'})"
        )
        self.models.seed_if_empty()
        parent = self.models.active_or_none()
        self._log(f"active model: v{parent.version}" if parent else "no model is active yet")

        self._step("training", GATHER_END)
        result = self._train(train, work_dir / "model")
        self._check_stop()
        self._log(f"trained: validation accuracy {percent(result.validation_accuracy)}")

        self._step("evaluating on the held-out scenes", TRAIN_END)
        new_accuracy = _accuracy(result.model_dir, heldout)
        self._log(f"new model: held-out accuracy {percent(new_accuracy)}")
        parent_accuracy: float | None = None
        if parent is not None:
            try:
                parent_accuracy = _accuracy(self.models.folder(parent.id), heldout)
                self._log(f"active model v{parent.version}: {percent(parent_accuracy)}")
            except Exception as exc:  # a broken active model must not block a working one
                self._log(f"the active model v{parent.version} could not be evaluated: {exc}")
        self._check_stop()

        verdict = heldout_verdict(
            [new_accuracy],
            None if parent_accuracy is None else [parent_accuracy],
            parent.version if parent else None,
            heldout_objects,
            self.promote_min_items,
        )
        info = self._register(
            result.model_dir,
            result.validation_accuracy,
            parent,
            new_accuracy,
            parent_accuracy,
            verdict,
            [by_id[i].key for i in train_ids],
            [by_id[i].key for i in heldout_ids],
            heldout_objects,
        )
        message = _outcome(info, new_accuracy, parent, parent_accuracy)
        self._log(message)
        self.jobs.succeed_retrain(self.job_id, info.id, message)

    def _samples(self, labelled: Sequence[LabelledScene]) -> list[SupportSample]:
        return stored_samples(self.scenes, labelled, before_each=self._check_stop)

    def _train(self, samples: Sequence[SupportSample], out_dir: Path) -> Any:
        # PyTorch only here, in the job: the server's request path never imports it.
        from ..learning.train import train_relation_model

        out_dir.mkdir(parents=True, exist_ok=True)
        started = time.monotonic()
        result = train_relation_model(
            self.config, samples, out_dir, progress=self._training_progress
        )
        self._log(f"training took {time.monotonic() - started:.1f} s")
        return result

    def _register(
        self,
        model_dir: Path,
        validation_accuracy: float,
        parent: ModelInfo | None,
        new_accuracy: float,
        parent_accuracy: float | None,
        verdict: Verdict,
        train_keys: list[str],
        heldout_keys: list[str],
        heldout_objects: int,
    ) -> ModelInfo:
        registration = Registration(
            status=verdict.status,
            note=verdict.note,
            parent_id=parent.id if parent else None,
            job_id=self.job_id,
            heldout_accuracy=new_accuracy,
            parent_heldout_accuracy=parent_accuracy,
            validation_accuracy=validation_accuracy,
            data={
                "training_scenes": train_keys,
                "heldout_scenes": heldout_keys,
                "heldout_items": heldout_objects,
                "config": jsonable(dataclasses.asdict(self.config)),
                "started_by": self.author,
            },
        )
        return self.models.register(
            model_dir,
            registration,
            promote=verdict.promote,
            expected_active=parent.id if parent else None,
            actor=self.author,
        )


def _accuracy(model_dir: Path, samples: Sequence[SupportSample]) -> float:
    from ..learning.runtime import SupportModel

    return float(SupportModel.load(model_dir).accuracy(samples))


def _outcome(
    info: ModelInfo, accuracy: float, parent: ModelInfo | None, parent_accuracy: float | None
) -> str:
    against = (
        f"v{parent.version}'s {percent(parent_accuracy)}"
        if parent is not None and parent_accuracy is not None
        else "no comparable active model"
    )
    if info.active:
        return f"v{info.version} is active: held-out accuracy {percent(accuracy)} against {against}"
    if info.status == "candidate":
        return (
            f"v{info.version} kept as a candidate ({info.note}): {percent(accuracy)} vs {against}"
        )
    return (
        f"v{info.version} rejected: held-out accuracy {percent(accuracy)} is worse than {against}"
    )


@dataclass(frozen=True)
class Verdict:
    """What a retrained model's held-out scores make of it."""

    status: ModelStatus  # accepted (made active), candidate (a tie) or rejected
    note: str | None = None

    @property
    def promote(self) -> bool:
        return self.status == "accepted"


def heldout_verdict(
    new: Sequence[float],
    active: Sequence[float] | None,
    active_version: int | None,
    items: int,
    enough_items: int = FEW_HELDOUT_ITEMS,
) -> Verdict:
    """The new model against the active one on the same held-out scenes, score by score (the
    first decides, the next break its ties). Better: made active, unless the held-out scenes
    hold fewer than `enough_items` items to score, too few to tell two models apart: then a
    candidate, to make active by hand. Exactly as good: the scenes cannot tell the two apart,
    so the active model stays and the new one is a candidate. Worse: rejected (kept, to
    inspect)."""
    if active is None:
        return Verdict("accepted")
    mine, theirs = [round(x, 9) for x in new], [round(x, 9) for x in active]
    if mine > theirs and items < enough_items:
        return Verdict(
            "candidate",
            f"better on {items} held-out {'item' if items == 1 else 'items'} only, too few "
            f"to tell it from v{active_version}, which stays active",
        )
    if mine > theirs:
        return Verdict("accepted")
    if mine == theirs:
        few = (
            f" on {items} held-out {'item' if items == 1 else 'items'} only"
            if items < enough_items
            else ""
        )
        return Verdict(
            "candidate",
            f"the same held-out scores as v{active_version}{few}, which stays active",
        )
    return Verdict("rejected")


def jsonable(value: Any) -> Any:
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [jsonable(v) for v in value]
    if isinstance(value, Path):
        return str(value)
    return value

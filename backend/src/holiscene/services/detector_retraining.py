"""Retraining the object detector from the boxes people confirmed (an admin's background job).

As the Relation Network's retraining (relation_retraining.py) does: gather the stored scenes with
confirmed boxes, hold the same fixed fifth of them out (heldout_split, decided by photo),
fine-tune a new detector head on synthetic rooms plus the other stored scenes
(learning.detector.train, PyTorch, imported only inside the job), score the new detector and
the active one on the held-out scenes (mAP@0.5 and recall at IoU 0.5), register the new one
whatever the outcome, and make it active only if it does better there (mAP@0.5 first, recall
on a tie); one exactly as good is kept as a candidate (heldout_verdict).

The boxes that count as confirmed, in each scene's current revision (walls, floors and
ceilings are never the detector's to find):
- objects a person drew (source "manual") and boxes given with the photo ("given");
- detector objects a person accepted: added by an add_object edit with source "detector" in a
  revision a person saved, still with the same id and box;
- every object of a scene a reviewer accepted (workflow state "accepted"): the annotator kept
  them and a reviewer checked the scene, the pipeline's detections included.
The pipeline's other detections (no one vouched for them) are not trained on; in a held-out
scene a prediction on one of them is left out of the score rather than counted as a false
alarm, since it may be right.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from holiscene_schema import (
    STRUCTURAL_CLASSES,
    AddObject,
    ModelInfo,
    RetrainRequest,
    RevisionInfo,
    SceneObject,
    SceneSummary,
)
from holiscene_schema.detector_model import SCORE_THRESHOLD

from ..evaluation.detection_2d import MAP_SCORE_THRESHOLD, DetectionEvaluation, ScoredBox
from ..inputs import load_photo
from ..learning.detector.data import BoxedPhoto
from ..learning.detector.runtime import Detector, box_iou
from ..learning.training_api import percent
from ..store.model_registry import Registration
from ..store.scenes import SceneStore
from .heldout import heldout_split
from .relation_retraining import (
    GATHER_END,
    MIN_LABELLED_SCENES,
    TRAIN_END,
    NotEnoughLabelsError,
    TrainingJob,
    Verdict,
    heldout_verdict,
    jsonable,
    require_two_photos,
    scenes_to_learn_from,
)

# Synthetic rooms for the detector: seeds no benchmark or other training uses (as
# `holiscene train-detector`).
DETECTOR_TRAIN_SEED = 400_000
DETECTOR_VALIDATION_SEED = 460_000
EVALUATION_IOU = 0.5
ROOMS_FOLDER = "detector-rooms"  # under the data directory: rendered rooms, kept between jobs

Box = tuple[float, float, float, float]


@dataclass(frozen=True)
class DetectorRetrainConfig:
    synthetic_rooms: int = 300  # rendered once, then cached (about 4 MB of features each)
    epochs: int = 12
    stored_repeats: int = 4  # random views of each stored training scene per epoch
    coco_weight: float = 1.0  # the COCO model's share for the classes it knows (0: head alone)
    # The committed model's recipe (docs/detector.md): the head's own copy of the backbone's
    # stride-32 blocks is tuned too, and synthetic objects may be repainted.
    tune_deep_blocks: bool = True
    retexture: float = 0.0  # chance that a synthetic object is repainted
    cushion_rows: bool = False  # training rooms dressed with rows of cushions (synth/plan.py)
    seed: int = 0
    cache_dir: Path | None = None  # where rendered rooms are kept

    @property
    def validation_rooms(self) -> int:
        """Synthetic rooms that pick the best epoch (never a stored scene)."""
        return min(max(self.synthetic_rooms // 10, 2), 40)


def detector_train_config(
    request: RetrainRequest, cache_dir: Path | None = None
) -> DetectorRetrainConfig:
    """The configuration: the defaults, with what the admin chose (max_epochs -> epochs,
    synthetic_scenes -> synthetic rooms)."""
    changes: dict[str, Any] = {"cache_dir": cache_dir}
    if request.max_epochs is not None:
        changes["epochs"] = request.max_epochs
    if request.synthetic_scenes is not None:
        changes["synthetic_rooms"] = request.synthetic_scenes
    return dataclasses.replace(DetectorRetrainConfig(), **changes)


@dataclass(frozen=True)
class BoxedScene:
    """A stored scene's confirmed boxes (NYU-40 classes), and the boxes no one confirmed."""

    scene_id: str
    revision: int
    boxes: tuple[Box, ...]
    classes: tuple[str, ...]
    unconfirmed: tuple[Box, ...] = ()

    @property
    def key(self) -> str:
        return f"{self.scene_id}@r{self.revision}"


def _box(values: Sequence[float]) -> Box:
    return (
        round(float(values[0]), 3),
        round(float(values[1]), 3),
        round(float(values[2]), 3),
        round(float(values[3]), 3),
    )


def accepted_detector_boxes(revisions: Sequence[RevisionInfo]) -> set[tuple[str, Box]]:
    """(object id, box) of each detector suggestion a person accepted (an add_object edit
    with source "detector" in a revision a person saved)."""
    accepted = set()
    for revision in revisions:
        if revision.kind != "edit" or not revision.edits:
            continue
        for edit in revision.edits:
            if isinstance(edit, AddObject) and edit.source == "detector":
                accepted.add((edit.id, _box(edit.bbox)))
    return accepted


def is_confirmed(obj: SceneObject, accepted: set[tuple[str, Box]], scene_accepted: bool) -> bool:
    if scene_accepted or obj.source in ("manual", "given"):
        return True
    return obj.source == "detector" and (obj.id, _box(obj.bbox)) in accepted


def boxed_scene(scenes: SceneStore, summary: SceneSummary) -> BoxedScene | None:
    """The scene's confirmed boxes, or None when it has none."""
    document = scenes.document(summary.id)
    objects = [o for o in document.scene.objects if o.cls not in STRUCTURAL_CLASSES]
    scene_accepted = summary.state == "accepted"
    needs_history = not scene_accepted and any(o.source == "detector" for o in objects)
    accepted = accepted_detector_boxes(scenes.revisions(summary.id)) if needs_history else set()
    confirmed = {o.id for o in objects if is_confirmed(o, accepted, scene_accepted)}
    if not confirmed:
        return None
    return BoxedScene(
        scene_id=summary.id,
        revision=document.revision,
        boxes=tuple(_box(o.bbox) for o in objects if o.id in confirmed),
        classes=tuple(o.cls for o in objects if o.id in confirmed),
        unconfirmed=tuple(_box(o.bbox) for o in objects if o.id not in confirmed),
    )


def boxed_scenes(scenes: SceneStore) -> list[BoxedScene]:
    """Every scene to learn from (`scenes_to_learn_from`) with at least one confirmed box."""
    found = (boxed_scene(scenes, summary) for summary in scenes_to_learn_from(scenes))
    return [item for item in found if item is not None]


# What a labelled scene is for the detector, as the models page says it.
BOXED_SCENES = (
    "scenes with boxes a person confirmed: drawn, given with the photo, accepted suggestions, "
    "or an accepted scene; rejected scenes left out"
)


def check_can_retrain_detector(scenes: SceneStore) -> int:
    """The number of scenes with confirmed boxes; NotEnoughLabelsError when too few."""
    ids = [item.scene_id for item in boxed_scenes(scenes)]
    if len(ids) < MIN_LABELLED_SCENES:
        raise NotEnoughLabelsError(
            f"retraining the detector needs at least {MIN_LABELLED_SCENES} {BOXED_SCENES}, "
            f"{len(ids)} found"
        )
    require_two_photos(scenes, ids, "scenes with confirmed boxes")
    return len(ids)


def boxed_photo(scenes: SceneStore, item: BoxedScene) -> BoxedPhoto:
    photo = load_photo(scenes.image_path(item.scene_id).read_bytes())
    boxes = np.array(item.boxes, dtype=np.float64).reshape(-1, 4)
    return BoxedPhoto(photo.rgb, boxes, list(item.classes))


@dataclass(frozen=True)
class DetectorScore:
    """A detector on the held-out scenes: mAP@0.5 decides, recall and precision inform."""

    map: float
    recall: float
    precision: float | None
    truth_boxes: int

    def text(self) -> str:
        return f"mAP@0.5 {percent(self.map)}, recall {percent(self.recall)}"


def without_unconfirmed(
    found: list[ScoredBox], truth: list[ScoredBox], unconfirmed: Sequence[Box], iou: float
) -> list[ScoredBox]:
    """The predictions, less those on a box no one confirmed (and on no confirmed box)."""
    if not unconfirmed:
        return found
    others = np.array(unconfirmed, dtype=np.float64).reshape(-1, 4)
    truth_boxes = np.array([t.bbox for t in truth], dtype=np.float64).reshape(-1, 4)
    kept = []
    for box in found:
        where = np.array(box.bbox, dtype=np.float64)
        on_truth = len(truth_boxes) > 0 and box_iou(where, truth_boxes).max() >= iou
        if on_truth or box_iou(where, others).max() < iou:
            kept.append(box)
    return kept


def score_detector(
    model_dir: Path, heldout: Sequence[tuple[BoxedPhoto, BoxedScene]]
) -> DetectorScore:
    """A detector directory's score on held-out photos: mAP@0.5 over every prediction down
    to MAP_SCORE_THRESHOLD, recall and precision of those the pipeline keeps."""
    detector = Detector(model_dir)  # not the cached loader: the new model's folder goes away
    ranked = DetectionEvaluation(iou=EVALUATION_IOU)
    operating = DetectionEvaluation(iou=EVALUATION_IOU)
    for photo, item in heldout:
        truth = [ScoredBox(b, c) for b, c in zip(item.boxes, item.classes, strict=True)]
        found = [
            ScoredBox(d.bbox, d.cls, d.score)
            for d in detector.detect(photo.rgb, MAP_SCORE_THRESHOLD)
        ]
        found = without_unconfirmed(found, truth, item.unconfirmed, EVALUATION_IOU)
        ranked.add(found, truth)
        operating.add([f for f in found if f.score >= SCORE_THRESHOLD], truth)
    summary = operating.summary()
    return DetectorScore(
        map=float(ranked.summary()["map"] or 0.0),
        recall=float(summary["recall_right_class"] or 0.0),
        precision=summary["precision"],
        truth_boxes=int(summary["truth_boxes"]),
    )


@dataclass(kw_only=True)
class DetectorRetrainJob(TrainingJob):
    """One detector retrain job's run (`models` is the detector registry)."""

    config: DetectorRetrainConfig

    def _run(self, work_dir: Path) -> None:
        self._step("gathering scenes with confirmed boxes", 0.0)
        train_items, heldout_items = self._split()
        train = [self._photo(item) for item in train_items]
        heldout = [(self._photo(item), item) for item in heldout_items]
        self.models.seed_if_empty()
        parent = self.models.active_or_none()
        self._log(f"active detector: v{parent.version}" if parent else "no detector is active")

        self._step("training", GATHER_END)
        model_dir = work_dir / "model"
        validation_map = self._train(train, model_dir)
        self._check_stop()

        self._step("evaluating on the held-out scenes", TRAIN_END)
        new_score = score_detector(model_dir, heldout)
        self._log(f"new detector: {new_score.text()}")
        parent_score = self._score_parent(parent, heldout)
        others = self._score_others(parent, heldout)
        self._check_stop()

        verdict = heldout_verdict(
            [new_score.map, new_score.recall],
            None if parent_score is None else [parent_score.map, parent_score.recall],
            parent.version if parent else None,
            sum(len(item.boxes) for item in heldout_items),
            self.promote_min_items,
        )
        registration = self._registration(
            parent, new_score, parent_score, verdict, validation_map, train_items, heldout_items
        )
        registration.data["heldout_others"] = [
            {"model_id": model.id, "accuracy": score.map, "recall": score.recall}
            for model, score in others
        ]
        info = self.models.register(
            model_dir,
            registration,
            promote=verdict.promote,
            expected_active=parent.id if parent else None,
            actor=self.author,
        )
        message = _outcome(info, new_score, parent, parent_score)
        self._log(message)
        self.jobs.succeed_retrain(self.job_id, info.id, message)

    def _split(self) -> tuple[list[BoxedScene], list[BoxedScene]]:
        items = boxed_scenes(self.scenes)
        if len(items) < MIN_LABELLED_SCENES:
            raise NotEnoughLabelsError(
                f"retraining the detector needs at least {MIN_LABELLED_SCENES} scenes with "
                f"confirmed boxes, {len(items)} found"
            )
        ids = [item.scene_id for item in items]
        train_ids, heldout_ids = heldout_split(ids, self.scenes.split_keys(ids))
        by_id = {item.scene_id: item for item in items}
        train, heldout = [by_id[i] for i in train_ids], [by_id[i] for i in heldout_ids]
        self._log(
            f"{len(items)} scenes with confirmed boxes: {len(train)} to train on "
            f"({sum(len(i.boxes) for i in train)} boxes), {len(heldout)} held out "
            f"({sum(len(i.boxes) for i in heldout)} boxes)"
        )
        return train, heldout

    def _photo(self, item: BoxedScene) -> BoxedPhoto:
        self._check_stop()
        return boxed_photo(self.scenes, item)

    def _train(self, stored: Sequence[BoxedPhoto], out_dir: Path) -> float:
        """Train on synthetic rooms plus the stored photos; the run's validation mAP@0.5."""
        # PyTorch only here, in the job: the server's request path never imports it.
        from ..learning.detector.data import synthetic_photos
        from ..learning.detector.train import DetectorTrainConfig, train_detector

        config = self.config
        train_config = DetectorTrainConfig(
            seed=config.seed,
            epochs=config.epochs,
            coco_weight=config.coco_weight,
            tune_deep_blocks=config.tune_deep_blocks,
            retexture=config.retexture,
            cushion_rows=config.cushion_rows,
        )
        cache = config.cache_dir or self.work_root.parent / ROOMS_FOLDER  # the data dir's

        # Of the training's share of the bar, rendering the rooms (cached after the first run)
        # takes the first 30%, the training run the rest.
        def rendered(what: str, before: int, total_rooms: int) -> Callable[[int, int], None]:
            def report(done: int, total: int) -> None:
                self._training_progress(0.3 * (before + done) / max(total_rooms, 1), "")
                self._log(f"rendering {what} {done}/{total}")

            return report

        first, validation_first = DETECTOR_TRAIN_SEED, DETECTOR_VALIDATION_SEED
        all_rooms = config.synthetic_rooms + config.validation_rooms
        rooms = synthetic_photos(
            range(first, first + config.synthetic_rooms),
            cache,
            rendered("training rooms", 0, all_rooms),
            style=train_config.room_style,
        )
        validation = synthetic_photos(
            range(validation_first, validation_first + config.validation_rooms),
            cache,
            rendered("validation rooms", config.synthetic_rooms, all_rooms),
        )
        photos = [*rooms, *(p for p in stored for _ in range(config.stored_repeats))]
        self._log(
            f"training on {len(rooms)} synthetic rooms and {len(stored)} stored scenes "
            f"(x{config.stored_repeats}), {len(validation)} synthetic rooms to validate"
        )
        started = time.monotonic()
        metrics = train_detector(
            photos,
            validation,
            train_config,
            out_dir,
            lambda fraction, line: self._training_progress(0.3 + 0.7 * fraction, line),
        )
        self._log(f"training took {time.monotonic() - started:.1f} s")
        return float(metrics["validation_map_at_0_5"])

    def _score_parent(
        self, parent: ModelInfo | None, heldout: Sequence[tuple[BoxedPhoto, BoxedScene]]
    ) -> DetectorScore | None:
        return None if parent is None else self._score_logged(parent, heldout, "active detector")

    def _score_logged(
        self, model: ModelInfo, heldout: Sequence[tuple[BoxedPhoto, BoxedScene]], name: str
    ) -> DetectorScore | None:
        """A registered detector on the held-out scenes, its figures (or why none) logged; a
        broken one must not block the retrain."""
        try:
            score = score_detector(self.models.folder(model.id), heldout)
        except Exception as exc:
            self._log(f"the {name} v{model.version} could not be evaluated: {exc}")
            return None
        self._log(f"{name} v{model.version}: {score.text()}")
        return score

    def _score_others(
        self, parent: ModelInfo | None, heldout: Sequence[tuple[BoxedPhoto, BoxedScene]]
    ) -> list[tuple[ModelInfo, DetectorScore]]:
        """Every other registered detector on the same held-out scenes: a shipped detector
        that is not active is compared no other way, and "Make active" needs its figures."""
        scored = []
        for model in self.models.list_models():
            if parent is not None and model.id == parent.id:
                continue
            self._check_stop()
            score = self._score_logged(model, heldout, "detector")
            if score is not None:
                scored.append((model, score))
        return scored

    def _registration(
        self,
        parent: ModelInfo | None,
        score: DetectorScore,
        parent_score: DetectorScore | None,
        verdict: Verdict,
        validation_map: float,
        train_items: Sequence[BoxedScene],
        heldout_items: Sequence[BoxedScene],
    ) -> Registration:
        return Registration(
            status=verdict.status,
            note=verdict.note,
            parent_id=parent.id if parent else None,
            job_id=self.job_id,
            heldout_accuracy=score.map,
            parent_heldout_accuracy=parent_score.map if parent_score else None,
            heldout_recall=score.recall,
            parent_heldout_recall=parent_score.recall if parent_score else None,
            validation_accuracy=validation_map,
            data={
                "training_scenes": [item.key for item in train_items],
                "heldout_scenes": [item.key for item in heldout_items],
                "heldout_items": sum(len(item.boxes) for item in heldout_items),
                "heldout": {
                    "new": dataclasses.asdict(score),
                    "active": dataclasses.asdict(parent_score) if parent_score else None,
                },
                "config": jsonable(dataclasses.asdict(self.config)),
                "started_by": self.author,
            },
        )


def _outcome(
    info: ModelInfo,
    score: DetectorScore,
    parent: ModelInfo | None,
    parent_score: DetectorScore | None,
) -> str:
    against = (
        f"v{parent.version}'s {parent_score.text()}"
        if parent is not None and parent_score is not None
        else "no comparable active detector"
    )
    if info.active:
        return f"detector v{info.version} is active: {score.text()} against {against}"
    if info.status == "candidate":
        return f"detector v{info.version} kept as a candidate ({info.note}): {against}"
    return f"detector v{info.version} rejected: {score.text()} is worse than {against}"

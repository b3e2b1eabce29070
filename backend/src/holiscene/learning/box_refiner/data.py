"""Training rooms for the box refiner: synthetic rooms (exact boxes) run through the
single-photo pipeline up to the placement, each estimated box paired with its true one.
No PyTorch here: worker processes make the rooms."""

from __future__ import annotations

import hashlib
import json
import multiprocessing
import pickle
import tempfile
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from holiscene_schema import Box3D, Scene
from numpy.typing import NDArray

from ...evaluation.matching import match_objects
from ...inputs import read_input_folder
from ...pipeline import DEFAULT_STAGES
from ...synth.generate import synthesize_to
from .features import SceneView, feature_names, object_features, pair_features, targets

# The single-photo pipeline up to the boxes the refiner reads.
STAGES_BEFORE_REFINER: tuple[str, ...] = DEFAULT_STAGES[: DEFAULT_STAGES.index("placement") + 1]


def scene_view(scene: Scene) -> SceneView:
    """What the refiner reads of a stored or freshly made scene."""
    if scene.camera is None:
        raise ValueError("the scene has no camera")
    width, height = scene.image.width, scene.image.height
    return SceneView(
        objects=scene.objects,
        boxes={o.id: o.box_3d for o in scene.objects},
        # The runs alternate background and object, starting with background.
        mask_pixels={o.id: sum(o.mask.rle[1::2]) for o in scene.objects if o.mask},
        supports=scene.supports,
        camera=scene.camera,
        width=width,
        height=height,
    )


@dataclass(frozen=True)
class RoomSample:
    """One room: the refiner's inputs for its placed objects, their targets, and both boxes
    (to score the refined boxes against the truth); `missed` counts true objects with no
    estimated box (they count against the found share)."""

    seed: int
    features: NDArray[np.float32]
    pairs: NDArray[np.float32]
    targets: NDArray[np.float32]
    estimates: list[Box3D]
    truths: list[Box3D]
    missed: int


def room_sample(estimate: Scene, truth: Scene, classes: Sequence[str], seed: int) -> RoomSample:
    true_boxes = sum(o.box_3d is not None for o in truth.objects)
    if estimate.camera is None or estimate.camera.height_m is None:
        # No vanishing points, so no camera and no boxes: nothing to learn, all missed.
        empty = np.zeros((0, len(feature_names(classes))), np.float32)
        return RoomSample(
            seed,
            empty,
            np.zeros((0, 0, 4), np.float32),
            np.zeros((0, 4), np.float32),
            [],
            [],
            missed=true_boxes,
        )
    view = scene_view(estimate)
    placed = view.placed()
    features = object_features(view, classes)
    matched = {e: t for t, e in match_objects(estimate.objects, truth.objects).items()}
    true_by_id = {o.id: o for o in truth.objects}
    keep, estimates, truths = [], [], []
    for index, obj in enumerate(placed):
        true_object = true_by_id.get(matched.get(obj.id, ""))
        if true_object is None or true_object.box_3d is None or obj.box_3d is None:
            continue
        keep.append(index)
        estimates.append(obj.box_3d)
        truths.append(true_object.box_3d)
    pairs = pair_features(placed)[np.ix_(keep, keep)] if keep else np.zeros((0, 0, 4), np.float32)
    return RoomSample(
        seed=seed,
        features=features[keep],
        pairs=pairs,
        targets=np.stack([targets(e, t) for e, t in zip(estimates, truths, strict=True)])
        if keep
        else np.zeros((0, 4), np.float32),
        estimates=estimates,
        truths=truths,
        missed=true_boxes - len(keep),
    )


def _make_room(job: tuple[int, tuple[str, ...]]) -> RoomSample | str:
    """The room's sample, or why the pipeline failed on it (the run goes on without it)."""
    seed, classes = job
    try:
        return _pipeline_room(seed, classes)
    except Exception as error:  # one bad room must not end a long run
        return f"room {seed}: {type(error).__name__}: {error}"


def _pipeline_room(seed: int, classes: tuple[str, ...]) -> RoomSample:
    from ...services.reconstruction import reconstruct_scene

    with tempfile.TemporaryDirectory() as tmp:
        folder = synthesize_to(seed, Path(tmp))
        inputs = read_input_folder(folder, use_depth=False)
        estimate = reconstruct_scene(
            inputs,
            name=folder.name,
            image_file="img.png",
            stages=STAGES_BEFORE_REFINER,
        ).scene
        truth = Scene.model_validate_json((folder / "gt.json").read_text())
    return room_sample(estimate, truth, classes, seed)


class RoomCache:
    """Room samples kept on disk, one file per seed, so a longer run makes only the rooms an
    earlier one did not. The folder is tied to what shapes a sample (the classes, the features
    and the stages run): a cache made by another version is refused, not mixed in. A change to
    a stage's code does not show in that key: clear the folder after one."""

    def __init__(self, folder: Path, classes: Sequence[str]) -> None:
        self.folder = folder
        key = json.dumps([list(classes), feature_names(classes), list(STAGES_BEFORE_REFINER)])
        self.key = hashlib.sha256(key.encode()).hexdigest()[:16]
        folder.mkdir(parents=True, exist_ok=True)
        key_file = folder / "key.txt"
        if not key_file.exists():
            key_file.write_text(self.key + "\n")
        elif key_file.read_text().strip() != self.key:
            raise ValueError(
                f"{folder} holds rooms made for other classes, features or stages: "
                "give another folder or empty this one"
            )

    def _path(self, seed: int) -> Path:
        return self.folder / f"{seed}.pkl"

    def get(self, seed: int) -> RoomSample | None:
        path = self._path(seed)
        if not path.exists():
            return None
        sample: RoomSample = pickle.loads(path.read_bytes())
        return sample

    def put(self, sample: RoomSample) -> None:
        # Written aside and renamed, so a run stopped mid-write leaves no half file behind.
        tmp = self._path(sample.seed).with_suffix(".tmp")
        tmp.write_bytes(pickle.dumps(sample))
        tmp.replace(self._path(sample.seed))


def make_rooms(
    seeds: Iterable[int], classes: Sequence[str], workers: int, cache: RoomCache | None = None
) -> Iterator[RoomSample | str]:
    """Room samples in seed order, made by `workers` processes (or read from `cache`, where
    the new ones are kept); a room the pipeline failed on comes as the message saying why."""
    seeds = list(seeds)
    cached = {seed: cache.get(seed) for seed in seeds} if cache else {}
    jobs = [(seed, tuple(classes)) for seed in seeds if cached.get(seed) is None]
    made = _made_rooms(jobs, workers)
    for seed in seeds:
        known = cached.get(seed)
        if known is not None:
            yield known
            continue
        room = next(made)
        if cache is not None and isinstance(room, RoomSample):
            cache.put(room)
        yield room


def _made_rooms(
    jobs: list[tuple[int, tuple[str, ...]]], workers: int
) -> Iterator[RoomSample | str]:
    if workers <= 1:
        yield from map(_make_room, jobs)
        return
    with multiprocessing.get_context("spawn").Pool(workers) as pool:
        yield from pool.imap(_make_room, jobs, chunksize=4)

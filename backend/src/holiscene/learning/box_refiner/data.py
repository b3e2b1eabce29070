"""Training rooms for the box refiner: synthetic rooms (exact boxes) run through the
single-photo pipeline up to the placement, each estimated box paired with its true one.
No PyTorch here: worker processes make the rooms."""

from __future__ import annotations

import multiprocessing
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


def make_rooms(
    seeds: Iterable[int], classes: Sequence[str], workers: int
) -> Iterator[RoomSample | str]:
    """Room samples in seed order, made by `workers` processes; a room the pipeline failed on
    comes as the message saying why."""
    jobs = [(seed, tuple(classes)) for seed in seeds]
    if workers <= 1:
        yield from map(_make_room, jobs)
        return
    with multiprocessing.get_context("spawn").Pool(workers) as pool:
        yield from pool.imap(_make_room, jobs, chunksize=4)

"""Training photos for the layout and object networks: synthetic rooms (exact camera, room and
boxes) randomised in colour and light as the detector's are (`detector.data.photometric`; no
crop or flip, which would change the camera), their features (`features.photo_features`) and
targets (`targets`), cached per room as .npz so a second run skips the backbone. No PyTorch."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, fields
from pathlib import Path

import numpy as np
from holiscene_schema import Scene
from numpy.typing import NDArray

from ...geometry.boxes import corners_of
from ...geometry.camera import PinholeCamera
from ...inputs.validation import read_input_folder
from ..box_refiner.features import pair_features, typical_size
from ..detector.backbone import FeatureExtractor
from ..detector.data import photometric
from .bins import LOG_DISTANCE_BINS, OBJECT_YAW_BINS, PITCH_BINS, ROLL_BINS, ROOM_YAW_BINS
from .features import photo_features
from .targets import ObjectTargets, RoomTargets

CENTRE_OFFSET_LIMIT = 1.5  # box sizes: a centre the photo's edge cuts off is taught this far


@dataclass(frozen=True)
class PhotoSample:
    """One randomised photo of a room: the networks' inputs and every target, per object in
    the order of the inputs (objects whose centre is behind the camera are left out)."""

    room: NDArray[np.float16]
    camera: NDArray[np.float32]
    objects: NDArray[np.float16]
    pairs: NDArray[np.float32]
    pitch_roll: NDArray[np.float32]  # (2,) the true camera's, degrees
    room_bins: NDArray[np.float32]  # pitch, roll, yaw: (bin, offset) each
    log_height: NDArray[np.float32]  # (1,)
    log_distances: NDArray[np.float32]  # (5,)
    centre_offset: NDArray[np.float32]  # (n, 2)
    object_bins: NDArray[np.float32]  # (n, 4): distance (bin, offset), yaw (bin, offset)
    log_size: NDArray[np.float32]  # (n, 3)
    bbox: NDArray[np.float32]  # (n, 4)
    typical_size: NDArray[np.float32]  # (n, 3)
    true_corners: NDArray[np.float32]  # (n, 8, 3)
    world_from_pixel: NDArray[np.float32]  # (3, 3), the true camera's
    true_layout: NDArray[np.float32]  # (8, 3)
    K: NDArray[np.float32]  # (3, 3)
    classes: NDArray[np.str_]  # (n,)


def _pair(bins_and_offsets: tuple[NDArray[np.int64], NDArray[np.float64]]) -> NDArray[np.float32]:
    index, offset = bins_and_offsets
    return np.stack([index.astype(np.float32), offset.astype(np.float32)], axis=-1)


def photo_sample(
    extractor: FeatureExtractor, rgb: NDArray[np.uint8], K: NDArray[np.float64], truth: Scene
) -> PhotoSample | None:
    """The sample of a photo with its true scene; None without a camera or room."""
    camera_truth, corners = truth.camera, truth.layout.corners_3d if truth.layout else None
    if camera_truth is None or corners is None or camera_truth.pitch_deg is None:
        return None
    pitch, roll = camera_truth.pitch_deg, camera_truth.roll_deg or 0.0
    camera = PinholeCamera(K, pitch, roll)
    room = RoomTargets.of_truth(pitch, roll, np.asarray(corners))
    kept, targets = [], []
    for obj in truth.objects:
        target = (
            ObjectTargets.of_truth(obj.box_3d, tuple(obj.bbox), obj.cls, camera)
            if obj.box_3d
            else None
        )
        if target is not None:
            kept.append(obj)
            targets.append(target)
    features = photo_features(extractor, rgb, K, [o.bbox for o in kept], [o.cls for o in kept])
    room_bins = [
        _pair(bins.encode(np.array([value])))[0]
        for bins, value in ((PITCH_BINS, pitch), (ROLL_BINS, roll), (ROOM_YAW_BINS, room.yaw_deg))
    ]
    n = len(kept)
    distance = _pair(LOG_DISTANCE_BINS.encode(np.array([t.log_distance for t in targets])))
    yaw = _pair(OBJECT_YAW_BINS.encode(np.array([t.yaw_deg for t in targets])))
    return PhotoSample(
        room=features.room.astype(np.float16),
        camera=features.camera,
        objects=features.objects.astype(np.float16),
        pairs=pair_features(kept),
        pitch_roll=np.array([pitch, roll], np.float32),
        room_bins=np.stack(room_bins).astype(np.float32),
        log_height=np.array([np.log(room.camera_height_m)], np.float32),
        log_distances=np.log(room.distances).astype(np.float32),
        centre_offset=np.clip(
            np.array([t.centre_offset for t in targets]).reshape(n, 2),
            -CENTRE_OFFSET_LIMIT,
            CENTRE_OFFSET_LIMIT,
        ).astype(np.float32),
        object_bins=np.concatenate([distance.reshape(n, 2), yaw.reshape(n, 2)], axis=1),
        log_size=np.array([t.log_size for t in targets], np.float32).reshape(n, 3),
        bbox=np.array([o.bbox for o in kept], np.float32).reshape(n, 4),
        typical_size=np.array([typical_size(o.cls) for o in kept], np.float32).reshape(n, 3),
        true_corners=np.array([corners_of(o.box_3d) for o in kept if o.box_3d], np.float32).reshape(
            n, 8, 3
        ),
        world_from_pixel=camera._world_from_pixel.astype(np.float32),
        true_layout=np.asarray(corners, np.float32),
        K=np.asarray(K, np.float32),
        classes=np.array([o.cls for o in kept], dtype=np.str_),
    )


def room_samples(
    extractor: FeatureExtractor,
    folders: Sequence[Path],
    cache_dir: Path | None,
    seed: int,
    randomised: bool,
    progress: bool = True,
) -> list[PhotoSample]:
    """One sample per room folder (with gt.json), randomised or not; read from `cache_dir`
    when an earlier run cached it there."""
    from tqdm import tqdm

    names = [f.name for f in fields(PhotoSample)]
    rows = []
    for index, folder in enumerate(
        tqdm(folders, desc="photos", unit="photo", disable=not progress)
    ):
        cached = cache_dir / f"{folder.name}-{seed}-{int(randomised)}.npz" if cache_dir else None
        if cached is not None and cached.is_file():
            with np.load(cached) as stored:
                rows.append(PhotoSample(**{name: stored[name] for name in names}))
            continue
        inputs = read_input_folder(folder, use_depth=False)
        if inputs.ground_truth is None or inputs.K is None:
            continue
        rgb = inputs.photo.rgb
        if randomised:
            rgb = photometric(rgb, np.random.default_rng([seed, index]))
        sample = photo_sample(extractor, rgb, inputs.K, inputs.ground_truth)
        if sample is None:
            continue
        if cached is not None:
            cached.parent.mkdir(parents=True, exist_ok=True)
            np.savez(cached, **{name: getattr(sample, name) for name in names})
        rows.append(sample)
    return rows

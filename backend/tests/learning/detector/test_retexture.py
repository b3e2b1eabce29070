"""Texture randomisation for detector training: only objects' visible pixels change, the
render's shading survives the new pattern, a chance of 0 leaves the photo as it was, and a
rendered room's gt.json gives one visible mask per object, inside its box."""

from __future__ import annotations

import numpy as np
import pytest
from holiscene.learning.detector.data import BoxedPhoto, randomise, synthetic_photos
from holiscene.learning.detector.retexture import pattern, retexture
from holiscene.segmentation.rle import decode_mask, encode_mask
from holiscene_schema import Mask


def _scene() -> tuple[np.ndarray, list[np.ndarray]]:
    """A photo and its one object's mask (bool)."""
    rgb = np.full((60, 80, 3), 120, np.uint8)
    mask = np.zeros((60, 80), bool)
    mask[10:40, 20:60] = True
    rgb[10:40, 20:40] = 50  # the object's shaded half
    rgb[10:40, 40:60] = 200  # its lit half
    return rgb, [mask]


def _encoded(masks: list[np.ndarray]) -> list[Mask]:
    return [m for m in (encode_mask(mask, "ground_truth") for mask in masks) if m is not None]


def test_only_the_objects_pixels_change() -> None:
    rgb, masks = _scene()
    out = retexture(rgb, _encoded(masks), np.random.default_rng(0), chance=1.0)
    assert out.dtype == np.uint8 and out.shape == rgb.shape
    assert np.array_equal(out[~masks[0]], rgb[~masks[0]])
    assert not np.array_equal(out[masks[0]], rgb[masks[0]])


def test_a_chance_of_zero_changes_nothing() -> None:
    rgb, masks = _scene()
    assert np.array_equal(
        retexture(rgb, _encoded(masks), np.random.default_rng(0), chance=0.0), rgb
    )


def test_the_shading_stays_under_the_new_pattern() -> None:
    rgb, masks = _scene()
    ratios = []
    for seed in range(30):
        out = retexture(rgb, _encoded(masks), np.random.default_rng(seed), chance=1.0).astype(float)
        ratios.append(out[10:40, 20:40].mean() / max(out[10:40, 40:60].mean(), 1.0))
    assert float(np.median(ratios)) < 0.6  # the shaded half stays darker


def test_patterns_are_colour_images_of_the_asked_size() -> None:
    rng = np.random.default_rng(1)
    for _ in range(20):
        painted = pattern(13, 29, rng)
        assert painted.shape == (13, 29, 3)
        assert painted.min() >= 0 and painted.max() <= 255


@pytest.fixture(scope="module")
def room(tmp_path_factory: pytest.TempPathFactory) -> BoxedPhoto:
    return synthetic_photos([932_000], tmp_path_factory.mktemp("rooms"), workers=1)[0]


def test_a_rendered_rooms_masks_lie_in_its_boxes(room: BoxedPhoto) -> None:
    height, width = room.rgb.shape[:2]
    masks = [decode_mask(m, width, height) for m in room.masks]
    assert len(masks) == len(room.boxes) > 0
    for mask in masks:
        rows, cols = np.flatnonzero(mask.any(axis=1)), np.flatnonzero(mask.any(axis=0))
        box = [cols[0], rows[0], cols[-1] + 1, rows[-1] + 1]
        assert any(np.allclose(box, b) for b in room.boxes)


def test_randomise_repaints_synthetic_rooms_only_when_asked(room: BoxedPhoto) -> None:
    plain = randomise(room, np.random.default_rng(2))
    again = randomise(room, np.random.default_rng(2), retexture_chance=0.0)
    assert np.array_equal(plain.rgb, again.rgb)
    painted = randomise(room, np.random.default_rng(2), retexture_chance=1.0)
    assert not np.array_equal(plain.rgb, painted.rgb)
    # A photo without a gt.json (a real one) is randomised as before.
    real = BoxedPhoto(room.rgb, room.boxes, room.classes)
    assert np.array_equal(
        randomise(real, np.random.default_rng(2), retexture_chance=1.0).rgb, plain.rgb
    )

"""The refine cut (GrabCut in a box steered by strokes) on the real t3d-5 photo, around its
left dresser (o2, box [419, 226, 564, 343]; 730x530)."""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np
import pytest
from holiscene.inputs import load_photo
from holiscene.segmentation.refine import (
    BrushStroke,
    RefineInputError,
    check_refine_input,
    paint_strokes,
    refine_in_box,
)

BOX = [400.0, 200.0, 580.0, 360.0]


@cache
def photo(folder: Path) -> np.ndarray:
    return load_photo((folder / "img.jpg").read_bytes()).rgb


def test_without_strokes_it_cuts_the_dresser_from_its_surroundings(t3d5: Path) -> None:
    mask = refine_in_box(photo(t3d5), BOX)
    inside = mask[200:360, 400:580]
    assert 0.25 < inside.mean() < 0.75  # neither the whole box nor nothing
    assert mask[290, 490]  # the dresser's drawers, in the middle of the box
    assert not mask[205, 405]  # the wall in the box's corner


def test_foreground_strokes_add_their_pixels_and_background_strokes_remove_theirs(
    t3d5: Path,
) -> None:
    image = photo(t3d5)
    plain = refine_in_box(image, BOX)
    keep = BrushStroke(points=[[412, 215], [412, 345]], radius=4)  # the wall left of it
    drop = BrushStroke(points=[[450, 290], [540, 290]], radius=5)  # across the drawers
    steered = refine_in_box(image, BOX, foreground=[keep], background=[drop])
    painted_in = paint_strokes(plain.shape, [keep])
    painted_out = paint_strokes(plain.shape, [drop])
    # The strokes were painted where the plain cut said the opposite ...
    assert plain[painted_in].mean() < 0.5 and plain[painted_out].mean() > 0.9
    # ... and now the painted pixels are what the person said.
    assert steered[painted_in].all()
    assert not steered[painted_out].any()


def test_a_few_strokes_take_out_the_vases_on_the_dresser_not_only_where_painted(
    t3d5: Path,
) -> None:
    """A loose box over the dresser and the vases on it: the plain cut keeps some of the
    vases; two short background strokes on them teach GrabCut their colours, so all of them
    go, and a foreground stroke keeps the dresser."""
    image = photo(t3d5)
    box = [400.0, 160.0, 580.0, 360.0]
    vases = (slice(170, 215), slice(440, 500))
    dresser = (slice(240, 320), slice(440, 540))
    on_vases = [
        BrushStroke(points=[[450, 185], [470, 185]], radius=6),
        BrushStroke(points=[[485, 180], [485, 215]], radius=5),
    ]
    on_dresser = [BrushStroke(points=[[440, 250], [520, 300]], radius=5)]
    plain = refine_in_box(image, box)
    steered = refine_in_box(image, box, foreground=on_dresser, background=on_vases)
    unpainted = ~paint_strokes(plain.shape, on_vases)
    assert plain[vases][unpainted[vases]].mean() > 0.25
    assert steered[vases][unpainted[vases]].mean() < 0.02
    assert steered[dresser].mean() > 0.97


def test_the_mask_stays_inside_the_box_whatever_is_painted(t3d5: Path) -> None:
    outside = BrushStroke(points=[[300, 150], [650, 420]], radius=20)  # leaves the box
    mask = refine_in_box(photo(t3d5), BOX, foreground=[outside])
    ys, xs = np.nonzero(mask)
    assert xs.min() >= 400 and xs.max() < 580 and ys.min() >= 200 and ys.max() < 360
    assert mask[200:360, 400:580][paint_strokes((160, 180), [outside], offset=(400, 200))].all()


def test_a_box_filling_the_photo_still_cuts(t3d5: Path) -> None:
    """No margin around the box to learn the background from: its rim stands in."""
    image = photo(t3d5)
    mask = refine_in_box(image, [0, 0, image.shape[1], image.shape[0]])
    assert 0.05 < mask.mean() < 0.95


def test_background_strokes_over_the_whole_box_leave_nothing(t3d5: Path) -> None:
    everything = BrushStroke(points=[[490, 280]], radius=200)
    assert not refine_in_box(photo(t3d5), BOX, background=[everything]).any()


@pytest.mark.parametrize(
    ("bbox", "strokes", "reason"),
    [
        ([-5, 10, 100, 100], [], "not inside the photo"),
        ([10, 10, 731, 100], [], "not inside the photo"),
        ([10, 10, 10.5, 100], [], "empty"),
        ([50, 50, 40, 100], [], "empty"),
        ([10, 10, 100, 100], [BrushStroke(points=[[20, 20], [20, 540]], radius=3)], "outside"),
    ],
)
def test_boxes_and_strokes_that_do_not_fit_the_photo_are_refused(
    bbox: list[float], strokes: list[BrushStroke], reason: str
) -> None:
    with pytest.raises(RefineInputError, match=reason):
        check_refine_input(730, 530, bbox, [], strokes)

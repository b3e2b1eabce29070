"""Room styles: rows of cushions on beds and sofas, and the default rooms left as they were."""

from __future__ import annotations

import json
import math
from collections import defaultdict
from functools import cache
from itertools import pairwise
from pathlib import Path

import numpy as np
import pytest
from holiscene.cli import main
from holiscene.geometry.camera import rot_y
from holiscene.learning.detector.data import synthetic_photos
from holiscene.synth.plan import PlannedObject, RoomPlan, RoomStyle, plan_room

ROWS = RoomStyle(cushion_rows=True)


@cache
def plan(seed: int, style: RoomStyle) -> RoomPlan:
    return plan_room(np.random.default_rng(seed), style)


@cache
def seeds_with_cushioned(theme: str, count: int) -> list[int]:
    """The first seeds from 5000 whose room of `theme` holds cushions in rows."""
    found: list[int] = []
    seed = 5000
    while len(found) < count:
        room = plan(seed, ROWS)
        if room.theme == theme and any(o.cls == "pillow" for o in room.objects):
            found.append(seed)
        seed += 1
    return found


def in_parent_frame(obj: PlannedObject, parent: PlannedObject) -> np.ndarray:
    return rot_y(math.radians(parent.yaw_deg)).T @ (obj.center - parent.center)


@pytest.mark.parametrize("theme", ["bedroom", "living"])
def test_cushions_line_up_against_the_back_in_matching_rows(theme: str) -> None:
    for seed in seeds_with_cushioned(theme, 6):
        room = plan(seed, ROWS)
        by_key = {o.key: o for o in room.objects}
        rows: dict[int, list[PlannedObject]] = defaultdict(list)
        for cushion in (o for o in room.objects if o.cls == "pillow"):
            parent = by_key[int(cushion.parent)]
            assert parent.cls in ("bed", "sofa") and cushion.support_type == "below"
            assert cushion.yaw_deg == parent.yaw_deg
            # The back half of the parent (its own -x), resting on top of its surface.
            local = in_parent_frame(cushion, parent)
            assert local[0] < 0.0, (seed, local)
            assert cushion.center[1] - cushion.size[1] / 2 > parent.center[1] - parent.size[1] / 2
            rows[cushion.key if cushion.looks_like is None else cushion.looks_like].append(cushion)
        for row in rows.values():
            # One size, one material, side by side across the width without overlapping.
            assert all(np.allclose(c.size, row[0].size) for c in row)
            across = sorted(in_parent_frame(c, by_key[int(c.parent)])[2] for c in row)
            assert all(b - a >= row[0].size[2] - 1e-9 for a, b in pairwise(across))


def test_a_bed_gets_a_row_at_its_headboard_more_often_than_not() -> None:
    seeds = [s for s in range(5000, 5200) if plan(s, ROWS).theme == "bedroom"]
    cushioned = [s for s in seeds if any(o.cls == "pillow" for o in plan(s, ROWS).objects)]
    assert len(seeds) > 20
    assert len(cushioned) / len(seeds) > 0.6


def test_a_style_changes_the_room_only_from_its_first_cushion() -> None:
    """The room, camera and everything placed before the cushions are the default's: the style
    is the same room dressed otherwise."""
    seed = seeds_with_cushioned("bedroom", 1)[0]
    default, styled = plan(seed, RoomStyle()), plan(seed, ROWS)
    assert (default.depth, default.width, default.pitch_deg) == (
        styled.depth,
        styled.width,
        styled.pitch_deg,
    )
    first = next(i for i, o in enumerate(styled.objects) if o.cls == "pillow")
    for a, b in zip(default.objects[:first], styled.objects[:first], strict=True):
        assert (a.cls, a.seed) == (b.cls, b.seed)
        assert np.allclose(a.center, b.center)
    assert all(o.looks_like is None for o in default.objects)


def test_cli_synth_names_styled_rooms_apart(tmp_path: Path) -> None:
    seed = seeds_with_cushioned("bedroom", 1)[0]
    out = tmp_path / "rooms"
    args = ["synth", "--seed", str(seed), "--count", "1", "-o", str(out), "--workers", "1"]
    assert main([*args, "--cushion-rows"]) == 0
    assert main(args) == 0
    assert sorted(f.name for f in out.iterdir()) == [f"synth-{seed}", f"synth-{seed}-cushion-rows"]
    styled = json.loads((out / f"synth-{seed}-cushion-rows" / "gt.json").read_text())
    assert styled["name"] == f"synth-{seed}-cushion-rows"
    classes = {o["id"]: o["class"] for o in styled["objects"]}
    cushions = {o["id"] for o in styled["objects"] if o["class"] == "pillow"}
    parents = [classes[s["parent"]] for s in styled["supports"] if s["child"] in cushions]
    assert cushions and parents == ["bed"] * len(cushions)


def test_detector_rooms_of_a_style_are_cached_apart(tmp_path: Path) -> None:
    seed = seeds_with_cushioned("bedroom", 1)[0]
    styled = synthetic_photos([seed], tmp_path, workers=1, style=ROWS)[0]
    default = synthetic_photos([seed], tmp_path, workers=1)[0]
    assert {f.name for f in tmp_path.iterdir()} == {f"synth-{seed}", f"synth-{seed}-cushion-rows"}
    assert styled.classes.count("pillow") > 0
    assert not np.array_equal(styled.rgb, default.rgb)

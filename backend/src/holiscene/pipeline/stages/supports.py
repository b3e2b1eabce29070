"""Support relations: from the Relation Network (default) or from counted priors alone.

Both read the support priors counted with the model in use (its priors.json), both keep the
supports people pinned, and both return a tree: every object gets exactly one supporter.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from holiscene_schema import (
    STRUCTURAL_CLASSES,
    STRUCTURAL_SUPPORTERS,
    SceneObject,
    SupportRelation,
)
from holiscene_schema.relation_model import STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER
from holiscene_schema.support_geometry import (
    FLOOR_BEFORE_WALL,
    FLOOR_RAY_MIN_DROP_DEG,
    HIDING_GAP,
    HIDING_OVERLAP,
    PIXELS_HIDING_SHARE,
    SUPPORTER_OVERLAP,
)
from numpy.typing import NDArray

from ...geometry.camera import PinholeCamera
from ...geometry.metric_scale import too_large_to_stand_there
from ...learning.decode import DecodeMode, decode_supports
from ...learning.preprocess import relation_inputs
from ...learning.priors import SupportPriors
from ...learning.runtime import DEFAULT_MODEL_DIR, SupportModel, model_priors
from ...learning.training_api import MODEL_FILE
from ...placement.room import Room, pinhole, room_of
from ..base import PipelineBuildError, SceneContext, Stage, required
from ..registry import register_stage


def _width(b: list[float]) -> float:
    return max(1.0, b[2] - b[0])


def _overlap_x(a: list[float], b: list[float]) -> float:
    """Pixels of the two boxes' horizontal overlap (0 when apart)."""
    return max(0.0, min(a[2], b[2]) - max(a[0], b[0]))


def _height(b: list[float]) -> float:
    return max(1.0, b[3] - b[1])


def image_plausibility(child: list[float], parent: list[float], kind: str) -> float:
    """How well two boxes fit `parent` supporting `child` in the image (0 = impossible).

    Below: the child overlaps the parent horizontally and its bottom edge lies within the
    parent's box (it rests on the visible top). Behind: the child lies inside the parent.
    Only larger boxes can support smaller ones, which also keeps the graph acyclic.
    """
    if _width(child) * _height(child) >= _width(parent) * _height(parent):
        return 0.0
    overlap_x = _overlap_x(child, parent) / _width(child)
    if kind == "behind":
        overlap_y = max(0.0, min(child[3], parent[3]) - max(child[1], parent[1])) / _height(child)
        return overlap_x * overlap_y if overlap_x * overlap_y > 0.6 else 0.0
    slack = 0.15 * _height(parent)
    if not (parent[1] - slack <= child[3] <= parent[3] + 0.05 * _height(parent)):
        return 0.0
    return overlap_x if overlap_x >= 0.3 else 0.0


# The figures of the geometry's rules are the shared contract's (the browser's live
# suggestions apply the same rules): holiscene_schema.support_geometry says what each means.
# The floor meets the image below its horizon: a ray through a bottom edge at most this steep
# downwards cannot rest on the floor.
FLOOR_RAY_MIN_DROP = np.sin(np.radians(FLOOR_RAY_MIN_DROP_DEG))


def off_the_floor(
    camera: PinholeCamera | None,
    boxes: list[list[float]],
    height: int,
    objects: list[SceneObject] | None = None,
    masks: list[NDArray[np.bool_]] | None = None,
) -> list[bool]:
    """Per 2D box: whether the floor cannot hold it up from below. Either its bottom edge is
    at or above the floor's horizon (a picture high on a wall, a shelf's books) with no box
    just below it that could hide a lower bottom; or, given the `objects` (the boxes' own,
    for their classes) and their `masks`, it would be far too large for one standing where
    that edge meets the floor (a shelf on a wall, cut by the photo's top and side, read as a
    bookcase 12 m away) with no other object's pixels just below it. False without a camera."""
    if camera is None:
        return [False] * len(boxes)
    bottoms = np.array([[(b[0] + b[2]) / 2.0, b[3]] for b in boxes], dtype=float).reshape(-1, 2)
    drops = -camera.ray(bottoms)[:, 1] if len(boxes) else np.zeros(0)
    result = []
    for n, (box, drop) in enumerate(zip(boxes, drops, strict=True)):
        if drop < FLOOR_RAY_MIN_DROP:
            result.append(not _box_below_may_hide(n, boxes, height))
        elif objects is not None and masks is not None:
            too_large = too_large_to_stand_there(camera, objects[n].cls, box)
            result.append(too_large and not _pixels_below_may_hide(n, boxes, masks, height))
        else:
            result.append(False)
    return result


def _box_below_may_hide(n: int, boxes: list[list[float]], height: int) -> bool:
    """Whether another box starts just below box n's bottom edge (or above it) and reaches
    lower, across enough of its width to hide where it really stands."""
    box = boxes[n]
    return any(
        other[1] <= box[3] + HIDING_GAP * height
        and other[3] > box[3]
        and _overlap_x(box, other) >= HIDING_OVERLAP * _width(box)
        for m, other in enumerate(boxes)
        if m != n
    )


def _pixels_below_may_hide(
    n: int, boxes: list[list[float]], masks: list[NDArray[np.bool_]], height: int
) -> bool:
    """Whether other objects' pixels fill the strip just below box n's bottom edge across
    most of its width (PIXELS_HIDING_SHARE): where the strip shows no object, the bottom edge
    is seen and the object ends there. Finer than the boxes: a bed's box reaches up to its
    headboard at one side, its pixels do not."""
    x1, _, x2, y2 = (round(v) for v in boxes[n])
    strip = max(round(HIDING_GAP * height), 1)
    if y2 + strip > height or x2 <= x1:
        return True  # the photo's bottom edge cuts the strip: what is below is not seen
    below = np.zeros(x2 - x1, dtype=bool)
    for m, mask in enumerate(masks):
        if m != n:
            below |= mask[y2 : y2 + strip, x1:x2].any(axis=0)
    return bool(below.mean() >= PIXELS_HIDING_SHARE)


def rule_out_impossible(scores: np.ndarray, child: SceneObject, objects: list[SceneObject]) -> None:
    """For an object the floor cannot hold (off_the_floor): zero the floor from below and
    every object beside it in the photo (whatever holds it up, from below or from behind,
    spans at least part of its width), in its row of the network's scores [supporters of
    `objects` then the structural ones, types], unless nothing would be left. The vertical
    gap is not judged: a lamp's foot may be hidden."""
    kept = scores.copy()
    floor = len(objects) + STRUCTURAL_COLUMNS.index("floor")
    kept[floor, SUPPORT_TYPE_ORDER.index("below")] = 0.0
    least = SUPPORTER_OVERLAP * _width(child.bbox)
    for column, other in enumerate(objects):
        if other.id == child.id or _overlap_x(child.bbox, other.bbox) < least:
            kept[column] = 0.0
    _keep_unless_empty(scores, kept)


def _keep_unless_empty(scores: np.ndarray, kept: np.ndarray) -> None:
    """Write `kept` (a copy of `scores` with answers zeroed) into `scores`, unless it zeroed
    every answer: then the geometry was wrong, and the scores stay as they were."""
    if kept.sum() > 0:
        scores[...] = kept


# FLOOR_BEFORE_WALL (the contract's): on 120 synthetic rooms (seeds 950000 and 980000, the
# estimated rooms) the true wall-hung things reach 1.4 (a door, its bottom on the floor, on a
# wall estimated too far); on the real photos the books on im3d-1's table 2.7.


def seen_against_the_floor(
    camera: PinholeCamera | None, room: Room | None, boxes: list[list[float]]
) -> list[bool]:
    """Per 2D box: whether the ray through the middle of its bottom edge meets the room's
    floor well before the wall it leaves the room through (FLOOR_BEFORE_WALL); False without a
    camera or a room, or with the camera outside the room (a layout too wrong to say; the
    browser's twin is inference/supportGeometry.ts)."""
    if camera is None or room is None or not room.holds(np.zeros(3)):
        return [False] * len(boxes)
    result = []
    for x1, _, x2, y2 in boxes:
        ray = camera.ray(np.array([[(x1 + x2) / 2.0, y2]]))[0]
        walls = room.walls_by_ray(ray)
        wall_at = walls[0].hit(ray) if walls else None
        floor_at = room.floor_y / ray[1] if ray[1] < -1e-9 else None
        result.append(
            wall_at is not None and floor_at is not None and wall_at > FLOOR_BEFORE_WALL * floor_at
        )
    return result


def rule_out_the_wall(scores: np.ndarray, objects: list[SceneObject]) -> None:
    """For an object seen against the floor (seen_against_the_floor): zero the wall from
    behind in its row of the network's scores, unless nothing would be left."""
    kept = scores.copy()
    kept[len(objects) + STRUCTURAL_COLUMNS.index("wall"), SUPPORT_TYPE_ORDER.index("behind")] = 0
    _keep_unless_empty(scores, kept)


def geometry_rules(
    ctx: SceneContext, objects: list[SceneObject], masks: list[NDArray[np.bool_]] | None
) -> list[tuple[bool, bool]]:
    """Per object: whether the floor cannot hold it from below (off_the_floor) and whether it
    is seen against the floor, so no wall holds it from behind (seen_against_the_floor)."""
    camera = scene_camera(ctx)
    boxes = [o.bbox for o in objects]
    return list(
        zip(
            off_the_floor(camera, boxes, ctx.height, objects, masks),
            seen_against_the_floor(camera, room_of(ctx.layout), boxes),
            strict=True,
        )
    )


def scene_camera(ctx: SceneContext) -> PinholeCamera | None:
    """The photo's camera with pitch and roll, when an earlier stage found them."""
    return pinhole(ctx.camera) if ctx.camera is not None else None


def prior_candidates(
    child: SceneObject, objects: list[SceneObject], priors: SupportPriors
) -> list[tuple[float, str, str]]:
    """(score, parent, type) for every supporter the priors and the boxes allow, best first.

    Structural supporters need no image check, so the list is never empty."""
    found: list[tuple[float, str, str]] = []
    for parent_cls, kind, prior in priors.ranked(child.cls):
        if parent_cls in STRUCTURAL_CLASSES:
            found.append((prior, parent_cls, kind))
            continue
        for other in objects:
            if other.id != child.id and other.cls == parent_cls:
                score = prior * image_plausibility(child.bbox, other.bbox, kind)
                if score > 0:
                    found.append((score, other.id, kind))
    return sorted(found, key=lambda x: -x[0])


def _model_dir(model_dir: str | Path | None) -> Path:
    return Path(model_dir) if model_dir is not None else DEFAULT_MODEL_DIR


def _load_model(stage: str, model_dir: Path) -> SupportModel:
    try:
        return SupportModel.load(model_dir)
    except FileNotFoundError as error:
        raise PipelineBuildError(f"stage {stage!r}: {error}") from error


@register_stage
class SupportsFromPriors(Stage):
    """Chapter 3's inference: counted class priors, each candidate checked on the 2D boxes
    (vertical order, overlap, size), the most probable one that keeps the graph a tree."""

    name = "supports_from_priors"
    requires = frozenset({"objects", "pinned_supports"})
    provides = frozenset({"supports"})

    def __init__(self, model_dir: str | Path | None = None, **rest: Any) -> None:
        super().__init__(**rest)
        # Only the model's counted priors: no ONNX session is needed for this method.
        folder = _model_dir(model_dir)
        if not (folder / MODEL_FILE).is_file():
            raise PipelineBuildError(f"stage {self.name!r}: no Relation Network model at {folder}")
        self.priors = model_priors(folder)

    def run(self, ctx: SceneContext) -> None:
        objects = [o for o in required(ctx.objects, "objects") if o.cls not in STRUCTURAL_CLASSES]
        ids = [o.id for o in objects]
        pinned = kept_pins(ctx, ids)
        candidates = {o.id: prior_candidates(o, objects, self.priors) for o in objects}
        masks = [ctx.masks[o.id].pixels for o in objects] if ctx.masks is not None else None
        for obj, (off, floored) in zip(objects, geometry_rules(ctx, objects, masks), strict=True):
            ruled_out = [("floor", "below")] * off + [("wall", "behind")] * floored
            kept = [c for c in candidates[obj.id] if c[1:] not in ruled_out]
            candidates[obj.id] = kept or candidates[obj.id]
        ctx.supports = tree_from_candidates(ids, candidates, pinned)


def kept_pins(ctx: SceneContext, ids: list[str]) -> list[SupportRelation]:
    """The supports people pinned on the objects `ids` whose supporter this run also has: an
    object added by hand is not among a run's objects, so a support naming it is dropped."""
    supporters = {o.id for o in required(ctx.objects, "objects")} | STRUCTURAL_SUPPORTERS
    return [s for s in ctx.pinned_supports if s.child in ids and s.parent in supporters]


def tree_from_candidates(
    ids: list[str],
    candidates: dict[str, list[tuple[float, str, str]]],
    pinned: list[SupportRelation],
) -> list[SupportRelation]:
    """Each unpinned object's best candidate that keeps the graph a tree."""
    # Scores as a probability table so the network's decoder does the tree building.
    columns = {name: c for c, name in enumerate([*ids, *STRUCTURAL_COLUMNS])}
    table = np.zeros((len(ids), len(columns), len(SUPPORT_TYPE_ORDER)))
    for row, child in enumerate(ids):
        for score, parent, kind in candidates.get(child, []):
            table[row, columns[parent], SUPPORT_TYPE_ORDER.index(kind)] += score
        total = table[row].sum()
        if total > 0:
            table[row] /= total
    return decode_supports(table, ids, ["?"] * len(ids), pinned)


@register_stage
class SupportsFromNetwork(Stage):
    """The Relation Network (ONNX, onnxruntime) on the photo and the masks, decoded into a
    tree, combined with the counted priors as in Eq. 4.1 (`decode="network"` for the network
    alone). On synthetic test scenes the two are within 0.1 point; on real photos, far from
    the synthetic rooms the network learned from, the priors keep a bed on the floor."""

    name = "supports_from_network"
    requires = frozenset({"objects", "masks", "pinned_supports"})
    provides = frozenset({"supports"})

    def __init__(
        self,
        model_dir: str | Path | None = None,
        decode: DecodeMode = "network+priors",
        **rest: Any,
    ) -> None:
        super().__init__(**rest)
        if decode not in ("network", "network+priors"):
            raise PipelineBuildError(f"stage {self.name!r}: unknown decode {decode!r}")
        self.decode: DecodeMode = decode
        self.model = _load_model(self.name, _model_dir(model_dir))

    def run(self, ctx: SceneContext) -> None:
        objects = [o for o in required(ctx.objects, "objects") if o.cls not in STRUCTURAL_CLASSES]
        masks = required(ctx.masks, "masks")
        ids = [o.id for o in objects]
        pinned = kept_pins(ctx, ids)
        if not objects:
            ctx.supports = pinned
            return
        pixels = [masks[o.id].pixels for o in objects]
        inputs = relation_inputs(
            ctx.image, pixels, [o.bbox for o in objects], [o.cls for o in objects]
        )
        probabilities = self.model.probabilities(inputs)
        for row, (off, floored) in enumerate(geometry_rules(ctx, objects, pixels)):
            if off:
                rule_out_impossible(probabilities[row], objects[row], objects)
            if floored:
                rule_out_the_wall(probabilities[row], objects)
        ctx.supports = decode_supports(
            probabilities,
            ids,
            [o.cls for o in objects],
            pinned,
            self.model.priors,
            self.decode,
        )

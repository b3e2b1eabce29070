"""Object-level support accuracy of the support methods on the same labelled samples.

An object counts as right when both its supporter (the instance, or floor/wall/ceiling) and
the support type are right, after decoding into a tree, as in the thesis's Table 4.2.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

from holiscene_schema import SceneObject, SupportRelation
from holiscene_schema.relation_model import STRUCTURAL_COLUMNS

from ..pipeline.stages.supports import prior_candidates, tree_from_candidates
from .decode import DecodeMode, decode_supports
from .priors import SupportPriors
from .runtime import SupportModel
from .samples import NO_LABEL, SupportSample, decode_answer

SupportMethod = Callable[[SupportSample], list[SupportRelation]]


@dataclass(frozen=True)
class MethodScore:
    name: str
    right: int
    total: int
    supporter_right: int
    type_right: int

    @property
    def accuracy(self) -> float:
        return self.right / self.total if self.total else 0.0


def true_supports(sample: SupportSample) -> dict[str, tuple[str, str]]:
    """child id -> (supporter id or structural name, type) for the labelled objects."""
    names = [*sample.object_ids, *STRUCTURAL_COLUMNS]
    found = {}
    for i, target in enumerate(sample.targets.tolist()):
        if target != NO_LABEL:
            column, kind = decode_answer(target)
            found[sample.object_ids[i]] = (names[column], kind)
    return found


def score(name: str, method: SupportMethod, samples: Sequence[SupportSample]) -> MethodScore:
    right = total = supporter_right = type_right = 0
    for sample in samples:
        predicted = {s.child: (s.parent, s.type) for s in method(sample)}
        for child, (parent, kind) in true_supports(sample).items():
            guess = predicted.get(child)
            total += 1
            supporter_right += guess is not None and guess[0] == parent
            type_right += guess is not None and guess[1] == kind
            right += guess == (parent, kind)
    return MethodScore(name, right, total, supporter_right, type_right)


def network_method(model: SupportModel, mode: DecodeMode) -> SupportMethod:
    def run(sample: SupportSample) -> list[SupportRelation]:
        probabilities = model.probabilities(sample.inputs)
        return decode_supports(
            probabilities, sample.object_ids, sample.classes, (), model.priors, mode
        )

    return run


def prior_method(priors: SupportPriors, image_size: tuple[int, int]) -> SupportMethod:
    """Chapter 3's prior-only inference on the samples' boxes (given in pixels of
    `image_size`, width and height)."""
    width, height = image_size

    def run(sample: SupportSample) -> list[SupportRelation]:
        boxes = sample.inputs["boxes"].astype(float) * [width, height, width, height]
        objects = [
            SceneObject.model_validate({"id": i, "class": c, "bbox": [float(v) for v in b]})
            for i, c, b in zip(sample.object_ids, sample.classes, boxes, strict=True)
        ]
        candidates = {o.id: prior_candidates(o, objects, priors) for o in objects}
        return tree_from_candidates(list(sample.object_ids), candidates, [])

    return run

"""Supports from class priors, each candidate supporter checked against the 2D boxes."""

from __future__ import annotations

from holiscene_schema import (
    STRUCTURAL_CLASSES,
    STRUCTURAL_SUPPORTERS,
    SceneObject,
    SupportRelation,
    support_graph_problems,
)

from ...knowledge.support_priors import support_priors
from ..base import SceneContext, Stage, required
from ..registry import register_stage


def _width(b: list[float]) -> float:
    return max(1.0, b[2] - b[0])


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
    overlap_x = max(0.0, min(child[2], parent[2]) - max(child[0], parent[0])) / _width(child)
    if kind == "behind":
        overlap_y = max(0.0, min(child[3], parent[3]) - max(child[1], parent[1])) / _height(child)
        return overlap_x * overlap_y if overlap_x * overlap_y > 0.6 else 0.0
    slack = 0.15 * _height(parent)
    if not (parent[1] - slack <= child[3] <= parent[3] + 0.05 * _height(parent)):
        return 0.0
    return overlap_x if overlap_x >= 0.3 else 0.0


def _candidates(child: SceneObject, objects: list[SceneObject]) -> list[tuple[float, str, str]]:
    """(score, parent, type) for every supporter the priors and the boxes allow.

    Every class's priors name a structural supporter, so the list is never empty and a
    child always gets a supporter (structural edges cannot close a cycle)."""
    found: list[tuple[float, str, str]] = []
    for parent_cls, kind, prior in support_priors(child.cls):
        if parent_cls in STRUCTURAL_SUPPORTERS:
            found.append((prior, parent_cls, kind))
            continue
        for other in objects:
            if other.id != child.id and other.cls == parent_cls:
                score = prior * image_plausibility(child.bbox, other.bbox, kind)
                if score > 0:
                    found.append((score, other.id, kind))
    return sorted(found, reverse=True)


@register_stage
class SupportsFromPriors(Stage):
    name = "supports_from_priors"
    requires = frozenset({"objects", "pinned_supports"})
    provides = frozenset({"supports"})

    def run(self, ctx: SceneContext) -> None:
        objects = required(ctx.objects, "objects")
        ids = [o.id for o in objects]
        supports = [s for s in ctx.pinned_supports if s.child in ids]
        pinned = {s.child for s in supports}
        for child in objects:
            if child.cls in STRUCTURAL_CLASSES or child.id in pinned:
                continue
            candidates = _candidates(child, objects)
            total = sum(score for score, _, _ in candidates)
            for score, parent, kind in candidates:
                edges = [(s.child, s.parent) for s in supports] + [(child.id, parent)]
                if not support_graph_problems(ids, edges):
                    supports.append(
                        SupportRelation(
                            child=child.id,
                            parent=parent,
                            type=kind,
                            source="auto",
                            confidence=round(score / total, 4),
                        )
                    )
                    break
        ctx.supports = supports

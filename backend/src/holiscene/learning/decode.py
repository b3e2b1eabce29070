"""From Relation Network probabilities to a support tree: one supporter per object, no cycle.

Two readings of the scores:
- `network`: each object takes its most probable (supporter, type) that keeps the graph a
  tree, the most confident objects first.
- `network+priors` (Eq. 4.1 for an instance-level network): the network's five most probable
  supporter categories are the candidates; among their instances the one with the highest
  network probability times the counted prior P(supporter class | class, type) wins.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Literal

import numpy as np
from holiscene_schema import STRUCTURAL_SUPPORT_TYPES, SupportRelation, support_graph_problems
from holiscene_schema.relation_model import STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER

from .priors import SupportPriors

DecodeMode = Literal["network", "network+priors"]
TOP_CATEGORIES = 5  # |SC(O_i)| in Eq. 4.1

Candidate = tuple[float, str, str]  # (score, supporter id or structural name, type)


def ranked_candidates(
    probabilities: np.ndarray,
    row: int,
    object_ids: Sequence[str],
    classes: Sequence[str],
    priors: SupportPriors | None = None,
    mode: DecodeMode = "network",
) -> list[Candidate]:
    """Every (supporter, type) for object `row`, best first; scores sum to 1."""
    n = len(object_ids)
    names = [*object_ids, *STRUCTURAL_COLUMNS]
    column_classes = [*classes, *STRUCTURAL_COLUMNS]
    scores = probabilities[row].astype(np.float64).copy()  # (N + 3, T)
    scores[row] = 0.0
    # The room's parts hold things up one way only (the floor from below; walls and the
    # ceiling from behind): the other type is no candidate, whatever the network says.
    for k, name in enumerate(STRUCTURAL_COLUMNS):
        for t, kind in enumerate(SUPPORT_TYPE_ORDER):
            if kind != STRUCTURAL_SUPPORT_TYPES[name]:
                scores[n + k, t] = 0.0
    if mode == "network+priors" and priors is not None:
        category_mass: dict[str, float] = {}
        for column, cls in enumerate(column_classes):
            category_mass[cls] = category_mass.get(cls, 0.0) + float(scores[column].sum())
        top = set(sorted(category_mass, key=lambda c: -category_mass[c])[:TOP_CATEGORIES])
        for column, cls in enumerate(column_classes):
            for t, kind in enumerate(SUPPORT_TYPE_ORDER):
                prior = priors.conditional(cls, classes[row], kind) if cls in top else 0.0
                scores[column, t] *= prior
    total = float(scores.sum())
    if total <= 0 and mode == "network+priors":
        # The priors ruled everything out: fall back to the network alone.
        return ranked_candidates(probabilities, row, object_ids, classes)
    total = total if total > 0 else 1.0  # nothing has mass: every candidate scores 0
    found = [
        (float(scores[c, t]) / total, names[c], kind)
        for c in range(n + len(STRUCTURAL_COLUMNS))
        for t, kind in enumerate(SUPPORT_TYPE_ORDER)
        if c != row
    ]
    return sorted(found, key=lambda x: -x[0])


def decode_supports(
    probabilities: np.ndarray,
    object_ids: Sequence[str],
    classes: Sequence[str],
    pinned: Sequence[SupportRelation] = (),
    priors: SupportPriors | None = None,
    mode: DecodeMode = "network",
) -> list[SupportRelation]:
    """A supporter for every object without a pinned one; pinned supports are kept as they
    are. Objects are decided most confident first, so a doubtful one cannot block a sure one
    by closing a cycle."""
    ids = list(object_ids)
    supports = [s for s in pinned if s.child in ids]
    decided = {s.child for s in supports}
    rankings = {
        i: ranked_candidates(probabilities, i, ids, classes, priors, mode)
        for i in range(len(ids))
        if ids[i] not in decided
    }
    for i in sorted(rankings, key=lambda i: -rankings[i][0][0]):
        edges = [(s.child, s.parent) for s in supports]
        for score, parent, kind in rankings[i]:
            if not support_graph_problems(ids, [*edges, (ids[i], parent)]):
                supports.append(
                    SupportRelation(
                        child=ids[i],
                        parent=parent,
                        type=kind,
                        source="auto",
                        confidence=round(score, 4),
                    )
                )
                break
    order = {child: k for k, child in enumerate(ids)}
    return sorted(supports, key=lambda s: order[s.child])

"""Support priors counted from labelled scenes: how often class p holds up class c by type t.

The thesis (Appendix B.2, Eq. 4.1) counts P(C(O_j) | C(O_i), T_k) on its training data; here the
counts come from the synthetic training scenes plus the stored annotated scenes, and travel
with each trained model (priors.json), so a retrained model brings its own counts.
"""

from __future__ import annotations

import json
from collections import defaultdict
from collections.abc import Iterable
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

from holiscene_schema.relation_model import STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER

from .samples import NO_LABEL, SupportSample, decode_answer

# Pseudo-count spread over the (supporter, type) pairs seen for any class, so a pair never
# seen for a class keeps a small probability instead of zero.
SMOOTHING = 0.5


def supporter_class(sample: SupportSample, column: int) -> str:
    n = len(sample.classes)
    return sample.classes[column] if column < n else STRUCTURAL_COLUMNS[column - n]


@dataclass
class SupportPriors:
    # child class -> "supporter class|type" -> count
    counts: dict[str, dict[str, float]] = field(default_factory=dict)

    @staticmethod
    def _key(parent_cls: str, support_type: str) -> str:
        return f"{parent_cls}|{support_type}"

    @cached_property
    def _background(self) -> dict[str, float]:
        totals: dict[str, float] = defaultdict(float)
        for row in self.counts.values():
            for key, count in row.items():
                totals[key] += count
        grand = sum(totals.values()) or 1.0
        return {key: count / grand for key, count in totals.items()}

    def joint(self, parent_cls: str, child_cls: str, support_type: str) -> float:
        """P(supporter class, type | child class), smoothed."""
        row = self.counts.get(child_cls, {})
        key = self._key(parent_cls, support_type)
        background = self._background.get(key, 0.0)
        if not row and not background:
            # Nothing counted at all: every structural supporter below is equally likely.
            return 1.0 / len(STRUCTURAL_COLUMNS) if support_type == "below" else 0.0
        return (row.get(key, 0.0) + SMOOTHING * background) / (sum(row.values()) + SMOOTHING)

    def conditional(self, parent_cls: str, child_cls: str, support_type: str) -> float:
        """P(supporter class | child class, type), as Eq. 4.1 uses it."""
        type_total = self._type_totals.get((child_cls, support_type))
        if type_total is None:  # decoding asks for the same few totals again and again
            type_total = sum(
                self.joint(p, child_cls, support_type) for p in self.supporter_classes(child_cls)
            )
            self._type_totals[(child_cls, support_type)] = type_total
        if type_total <= 0:
            return 0.0
        return self.joint(parent_cls, child_cls, support_type) / type_total

    @cached_property
    def _type_totals(self) -> dict[tuple[str, str], float]:
        return {}

    def supporter_classes(self, child_cls: str) -> frozenset[str]:
        """Every supporter class counted for any child (candidates for smoothing)."""
        return self._all_supporters

    @cached_property
    def _all_supporters(self) -> frozenset[str]:
        seen = {key.split("|")[0] for row in self.counts.values() for key in row}
        return frozenset(seen | set(STRUCTURAL_COLUMNS))

    def ranked(self, child_cls: str) -> list[tuple[str, str, float]]:
        """(supporter class, type, P) for this class, most probable first."""
        pairs = [
            (p, t, self.joint(p, child_cls, t))
            for p in self.supporter_classes(child_cls)
            for t in SUPPORT_TYPE_ORDER
        ]
        return sorted((x for x in pairs if x[2] > 0), key=lambda x: (-x[2], x[0], x[1]))

    def to_json(self) -> str:
        rows = {c: dict(sorted(r.items())) for c, r in sorted(self.counts.items())}
        return json.dumps({"smoothing": SMOOTHING, "counts": rows}, indent=1) + "\n"

    @classmethod
    def from_json(cls, text: str) -> SupportPriors:
        data = json.loads(text)
        return cls({c: {k: float(v) for k, v in r.items()} for c, r in data["counts"].items()})

    @classmethod
    def load(cls, path: Path) -> SupportPriors:
        return cls.from_json(path.read_text())


def count_priors(samples: Iterable[SupportSample]) -> SupportPriors:
    counts: dict[str, dict[str, float]] = defaultdict(lambda: defaultdict(float))
    for sample in samples:
        for i, target in enumerate(sample.targets.tolist()):
            if target == NO_LABEL:
                continue
            column, support_type = decode_answer(target)
            key = SupportPriors._key(supporter_class(sample, column), support_type)
            counts[sample.classes[i]][key] += 1.0
    return SupportPriors({c: dict(r) for c, r in counts.items()})

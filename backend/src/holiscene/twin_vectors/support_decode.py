"""Test vectors for the support-tree decoder: `python -m holiscene.twin_vectors.support_decode`
writes shared_schema/vectors/support_decode.json.

The decoder (Relation Network probabilities -> one supporter per object, no cycle, the most
confident objects first, pinned supports kept) is written twice: in Python
(holiscene.learning.decode, `decode_supports`, which the pipeline runs) and in TypeScript
(frontend/src/inference/treeDecode.ts, which re-decodes in the browser after each correction).
Both readings are covered: "network" and "network+priors" (Eq. 4.1, with counted priors; the
pipeline's default). Both sides are tested against these vectors. A development tool: it
imports the backend.

Deterministic (one seeded generator). Each case is a probability table [N, N + 3, 2] (rows
sum to 1, values rounded to 9 decimals so both sides read the same numbers) with object ids,
and pinned supports; expected = decode_supports on exactly that table. Tables are peaked and
built so that objects often prefer each other (the cycles the decoder must break); one case
has exact ties (uniform rows) to pin down the order among equals. The "network+priors" cases
carry their own small priors table (random counts over a few classes, one class never counted,
so the smoothing and the fallbacks are exercised) and the objects' classes.
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np
from holiscene_schema.relation_model import STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER
from holiscene_schema.scene import SupportRelation

from ..core.settings import REPO_ROOT
from ..learning.decode import DecodeMode, decode_supports
from ..learning.priors import SupportPriors

DECODE_VECTORS = REPO_ROOT / "shared_schema" / "vectors" / "support_decode.json"
SEED = 20260611
DIGITS = 9
TYPES = len(SUPPORT_TYPE_ORDER)


def _table(rng: np.random.Generator, n: int, peak: float) -> np.ndarray:
    """A random probability table whose rows favour a few columns, often another object."""
    logits = rng.normal(0.0, 1.0, (n, n + len(STRUCTURAL_COLUMNS), TYPES))
    for i in range(n):
        favourite = int(rng.integers(0, n + len(STRUCTURAL_COLUMNS)))
        logits[i, favourite, int(rng.integers(0, TYPES))] += peak
        if n > 1 and rng.random() < 0.6:  # prefer an object: pairs that want each other
            other = int(rng.integers(0, n))
            if other != i:
                logits[i, other, 0] += peak * 1.1
    table = np.exp(logits)
    table /= table.sum(axis=(1, 2), keepdims=True)
    return np.round(table, DIGITS)


def _pinned(rng: np.random.Generator, ids: list[str], count: int) -> list[SupportRelation]:
    """`count` pinned supports that form no cycle (parents are earlier ids or structural)."""
    pinned: list[SupportRelation] = []
    for child_index in rng.permutation(len(ids))[:count]:
        earlier = ids[: int(child_index)]
        choices = [*earlier, *STRUCTURAL_COLUMNS]
        parent = choices[int(rng.integers(0, len(choices)))]
        kind = SUPPORT_TYPE_ORDER[int(rng.integers(0, TYPES))]
        pinned.append(
            SupportRelation(
                child=ids[int(child_index)],
                parent=parent,
                type=kind,
                source="manual",
            )
        )
    return pinned


CLASSES = ("bed", "books", "box", "lamp", "table", "pillow", "night_stand", "counter")
NEVER_COUNTED = "bathtub"


def _priors(rng: np.random.Generator) -> SupportPriors:
    """Random counts: each class (but one) held up by a few of the others or by structure."""
    supporters = [*CLASSES, *STRUCTURAL_COLUMNS]
    counts: dict[str, dict[str, float]] = {}
    for child in CLASSES:
        picks = rng.choice(len(supporters), size=int(rng.integers(1, 5)), replace=False)
        counts[child] = {
            f"{supporters[int(k)]}|{SUPPORT_TYPE_ORDER[int(rng.integers(0, TYPES))]}": float(
                rng.integers(1, 200)
            )
            for k in picks
            if supporters[int(k)] != child
        } or {"floor|below": 1.0}
    return SupportPriors(counts)


def _case(
    name: str,
    table: np.ndarray,
    pinned: list[SupportRelation],
    classes: list[str] | None = None,
    priors: SupportPriors | None = None,
) -> dict[str, Any]:
    n = table.shape[0]
    ids = [f"o{i}" for i in range(n)]
    mode: DecodeMode = "network+priors" if priors is not None else "network"
    decoded = decode_supports(table, ids, classes or ["?"] * n, pinned, priors, mode)
    extra: dict[str, Any] = {}
    if priors is not None:
        extra = {"classes": classes, "priors": json.loads(priors.to_json())}
    return {
        "name": name,
        "mode": mode,
        **extra,
        "ids": ids,
        "probabilities": {"shape": list(table.shape), "data": table.reshape(-1).tolist()},
        "pinned": [{"child": s.child, "parent": s.parent, "type": s.type} for s in pinned],
        "expected": [
            {"child": s.child, "parent": s.parent, "type": s.type, "confidence": s.confidence}
            for s in decoded
        ],
    }


def build() -> dict[str, Any]:
    rng = np.random.default_rng(SEED)
    cases = []
    for k, n in enumerate((1, 2, 3, 5, 8, 12, 16, 20)):
        peak = float(rng.uniform(2.0, 6.0))
        table = _table(rng, n, peak)
        ids = [f"o{i}" for i in range(n)]
        cases.append(_case(f"free-{n}", table, []))
        count = int(rng.integers(1, max(2, n // 2 + 1)))
        cases.append(_case(f"pinned-{n}-{k}", table, _pinned(rng, ids, min(count, n))))
    # Exact ties everywhere: the order among equals decides every answer.
    uniform = np.full((4, 4 + len(STRUCTURAL_COLUMNS), TYPES), 1.0 / ((4 + 3) * TYPES))
    cases.append(_case("ties-4", np.round(uniform, DIGITS), []))
    # Two objects that each want the other most: one of them must take its second answer.
    pair = np.full((2, 5, TYPES), 0.01)
    pair[0, 1, 0] = 0.9
    pair[1, 0, 0] = 0.8
    pair[0, 3, 0] = 0.05
    pair[1, 3, 1] = 0.07
    pair /= pair.sum(axis=(1, 2), keepdims=True)
    cases.append(_case("mutual-pair", np.round(pair, DIGITS), []))
    cases.append(
        _case(
            "mutual-pair-corrected",
            np.round(pair, DIGITS),
            [SupportRelation(child="o1", parent="o0", type="below", source="manual")],
        )
    )
    priors = _priors(rng)
    pool = [*CLASSES, NEVER_COUNTED]
    for n in (1, 3, 6, 10, 16):
        table = _table(rng, n, float(rng.uniform(1.0, 4.0)))
        classes = [pool[int(rng.integers(0, len(pool)))] for _ in range(n)]
        ids = [f"o{i}" for i in range(n)]
        cases.append(_case(f"priors-free-{n}", table, [], classes, priors))
        pins = _pinned(rng, ids, max(1, n // 3))
        cases.append(_case(f"priors-pinned-{n}", table, pins, classes, priors))
    return {
        "seed": SEED,
        "structural_columns": list(STRUCTURAL_COLUMNS),
        "support_types": list(SUPPORT_TYPE_ORDER),
        "cases": cases,
    }


def main() -> None:
    DECODE_VECTORS.write_text(json.dumps(build(), separators=(",", ":")) + "\n")
    print(f"wrote {DECODE_VECTORS}")


if __name__ == "__main__":
    main()

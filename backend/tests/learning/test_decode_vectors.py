"""The support-tree decoder's shared vectors (shared_schema/vectors/support_decode.json) on the
Python side: the committed file is exactly what holiscene.learning.decode gives today, so the
TypeScript twin (frontend/src/inference/treeDecode.test.ts) is held to the pipeline's decoder.
After changing the decoder, run `python -m holiscene.twin_vectors.support_decode` and change the
TypeScript decoder to match."""

from __future__ import annotations

import json

import numpy as np
from holiscene.learning.decode import decode_supports
from holiscene.twin_vectors import support_decode as dv
from holiscene_schema import SupportRelation
from holiscene_schema.relation_model import STRUCTURAL_COLUMNS


def test_committed_vectors_are_what_the_decoder_gives() -> None:
    committed = json.loads(dv.DECODE_VECTORS.read_text())
    assert committed == json.loads(json.dumps(dv.build())), (
        "stale: run `python -m holiscene.twin_vectors.support_decode`"
    )


def test_vectors_have_cycles_to_break_and_pinned_supports_kept() -> None:
    cases = json.loads(dv.DECODE_VECTORS.read_text())["cases"]
    broke_a_cycle = 0
    for case in cases:
        table = np.asarray(case["probabilities"]["data"]).reshape(case["probabilities"]["shape"])
        ids = case["ids"]
        decoded = {s["child"]: s for s in case["expected"]}
        assert set(decoded) == set(ids)
        for pin in case["pinned"]:
            assert decoded[pin["child"]]["parent"] == pin["parent"]
            assert decoded[pin["child"]]["confidence"] is None
        pinned = {p["child"] for p in case["pinned"]}
        for row, child in enumerate(ids):
            if child in pinned:
                continue
            scores = table[row].copy()
            scores[row] = 0.0
            best = np.unravel_index(int(np.argmax(scores)), scores.shape)
            names = [*ids, *STRUCTURAL_COLUMNS]
            if names[best[0]] != decoded[child]["parent"]:
                broke_a_cycle += 1
    # Several objects did not get their best answer: the decoder's cycle rule is exercised.
    assert broke_a_cycle >= 5


def test_a_pinned_correction_moves_the_other_object() -> None:
    table = np.full((2, 5, 2), 0.01)
    # Columns: a, b, ceiling, floor, wall. Each wants the other; b is less sure.
    table[0, 1, 0], table[1, 0, 0], table[0, 3, 0], table[1, 3, 0] = 0.9, 0.4, 0.05, 0.05
    ids = ["a", "b"]
    free = decode_supports(table, ids, ["?", "?"])
    assert [(s.child, s.parent) for s in free] == [("a", "b"), ("b", "floor")]
    pin = SupportRelation(child="b", parent="a", type="below", source="manual")
    corrected = decode_supports(table, ids, ["?", "?"], [pin])
    assert [(s.child, s.parent) for s in corrected] == [("a", "floor"), ("b", "a")]

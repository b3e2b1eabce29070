"""The held-out split every retraining and training export shares.

A fixed fifth of the stored scenes is kept out of training to judge models by. The side is
decided by a hash, so a scene stays on its side in every retrain and no model is ever judged on a
scene an earlier model was trained on. The hash is of a split key: the id of the first scene
stored with the same photo (SceneStore.split_keys), so a scene downloaded, edited and imported
again cannot be trained on while its twin is held out.
"""

from __future__ import annotations

import hashlib
from collections.abc import Mapping, Sequence

HELDOUT_FRACTION = 0.2


def _hash_fraction(key: str) -> float:
    digest = hashlib.sha256(key.encode()).digest()
    return int.from_bytes(digest[:8], "big") / 2**64


def heldout_split(
    scene_ids: Sequence[str],
    split_keys: Mapping[str, str] | None = None,
    fraction: float = HELDOUT_FRACTION,
) -> tuple[list[str], list[str]]:
    """(training ids, held-out ids). Scenes with one split key (default: their own id) go to
    one side together. With two or more keys, at least one is held out and at least one is
    trained on; scenes of a single photo are all trained on (none could be held out without
    its twin being seen)."""
    keys = split_keys or {}

    def key_of(scene_id: str) -> str:
        return keys.get(scene_id, scene_id)

    ordered = sorted({key_of(s) for s in scene_ids}, key=_hash_fraction)
    held = [k for k in ordered if _hash_fraction(k) < fraction]
    if len(ordered) < 2:
        held = []  # one photo: held out, nothing would be left to learn from
    elif not held:
        held = ordered[:1]
    elif len(held) == len(ordered):
        held = held[:-1]
    held_set = set(held)
    return (
        [s for s in scene_ids if key_of(s) not in held_set],
        [s for s in scene_ids if key_of(s) in held_set],
    )

"""`holiscene export --format relation-training`: the Relation Network training set the
retraining builds from people's support labels (services/relation_retraining.py), written for
someone's own training code.

DIR/pairs.npz holds the network's input tensors of every labelled scene, concatenated, and
the labelled (object, supporter, type) pairs; DIR/labels.jsonl the same pairs by object id, one
JSON object a line; DIR/README-format.json says what every array means, the contract's
vocabularies, and which scene and revision each sample came from.
"""

from __future__ import annotations

import io
import json
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from holiscene_schema import NYU40_CLASSES
from holiscene_schema.relation_model import (
    IMAGE_SIZE,
    MASK_SIZE,
    STRUCTURAL_COLUMNS,
    SUPPORT_TYPE_ORDER,
)

from ..core.atomic_files import write_atomic
from .archive import ArchivedScene, split_keys_of
from .errors import ExportRefusedError

if TYPE_CHECKING:
    from ..learning.samples import SupportSample
    from ..services.relation_retraining import LabelledScene

PAIRS_FILE = "pairs.npz"
LABELS_FILE = "labels.jsonl"
FORMAT_FILE = "README-format.json"
FORMAT_NAME = "holiscene-relation-training"
FORMAT_VERSION = 1

_ARRAYS = {
    "image": (
        "float32",
        f"[S, 3, {IMAGE_SIZE}, {IMAGE_SIZE}]",
        "each sample's photo: RGB / 255, area-resized",
    ),
    "object_start": (
        "int64",
        "[S + 1]",
        "sample s's objects are rows object_start[s] to object_start[s + 1] - 1 of masks, "
        "boxes, classes and targets (N = object_start[s + 1] - object_start[s])",
    ),
    "masks": (
        "float32",
        f"[O, {MASK_SIZE}, {MASK_SIZE}]",
        "each object's mask, area-resized (share of pixels)",
    ),
    "boxes": ("float32", "[O, 4]", "each object's 2D box (x0, y0, x1, y1) / (W, H, W, H)"),
    "classes": ("int64", "[O]", "each object's index in `classes`"),
    "targets": (
        "int64",
        "[O]",
        "each object's answer: supporter column * 2 + type index in its sample's flattened "
        "(N + 3) x 2 output row; -1 when it has no label (no loss)",
    ),
    "pairs": (
        "int64",
        "[P, 4]",
        "one row per labelled object: sample, object index in the sample, supporter column "
        "(an object index, or N + the index in `structural_columns`), type index in "
        "`support_types`",
    ),
    "heldout": (
        "bool",
        "[S]",
        "the sample is on the side a retrain job holds out to judge a model by",
    ),
}


def write_relation_training(chosen: list[ArchivedScene], out: Path) -> None:
    """DIR/pairs.npz, DIR/labels.jsonl and DIR/README-format.json over the chosen scenes'
    current revisions; scenes without supports set by a person are listed as left out."""
    from tqdm import tqdm

    from ..services.heldout import heldout_split
    from ..services.relation_retraining import labelled_sample, people_labelled

    kept: list[tuple[LabelledScene, SupportSample]] = []
    left_out: list[dict[str, Any]] = []
    for item in tqdm(chosen, desc="relation-training", unit="scene", file=sys.stderr):
        labelled = people_labelled(item.scene_id, item.revision, item.scene)
        sample = labelled_sample(labelled, item.photo) if labelled is not None else None
        if labelled is None or sample is None:
            why = "no supports set by a person" if labelled is None else "no label to learn"
            left_out.append(_source(item.scene_id, item.revision, item.scene.name) | {"why": why})
        else:
            kept.append((labelled, sample))
    if not kept:
        raise ExportRefusedError(
            f"none of the {len(chosen)} scene(s) has supports set by a person: nothing to train on"
        )
    _, heldout_ids = heldout_split(
        [labelled.scene_id for labelled, _ in kept], split_keys_of(chosen)
    )
    heldout = np.array([labelled.scene_id in heldout_ids for labelled, _ in kept])
    write_atomic(out / PAIRS_FILE, _arrays([s for _, s in kept], heldout))
    write_atomic(out / LABELS_FILE, _label_lines(kept))
    write_atomic(out / FORMAT_FILE, _format_document(kept, heldout, left_out))


def _source(scene_id: str, revision: int, name: str) -> dict[str, Any]:
    return {"scene_id": scene_id, "revision": revision, "name": name}


def _pairs(sample: SupportSample) -> list[tuple[int, int, int]]:
    """(object index, supporter column, type index) of each labelled object of a sample."""
    from ..learning.samples import NO_LABEL, decode_answer

    pairs = []
    for index, target in enumerate(sample.targets.tolist()):
        if target != NO_LABEL:
            column, kind = decode_answer(target)
            pairs.append((index, column, SUPPORT_TYPE_ORDER.index(kind)))
    return pairs


def _arrays(samples: list[SupportSample], heldout: np.ndarray) -> bytes:
    counts = [len(s.object_ids) for s in samples]
    pairs = [(i, *pair) for i, s in enumerate(samples) for pair in _pairs(s)]
    buffer = io.BytesIO()
    np.savez_compressed(
        buffer,
        image=np.concatenate([s.inputs["image"] for s in samples]),
        object_start=np.concatenate([[0], np.cumsum(counts)]).astype(np.int64),
        masks=np.concatenate([s.inputs["masks"] for s in samples]),
        boxes=np.concatenate([s.inputs["boxes"] for s in samples]),
        classes=np.concatenate([s.inputs["classes"] for s in samples]),
        targets=np.concatenate([s.targets for s in samples]),
        pairs=np.array(pairs, dtype=np.int64).reshape(-1, 4),
        heldout=heldout,
    )
    return buffer.getvalue()


def _label_lines(kept: list[tuple[LabelledScene, SupportSample]]) -> bytes:
    """One line per labelled object, by id: what pairs.npz's `pairs` hold, readable."""
    lines = []
    for number, (labelled, sample) in enumerate(kept):
        ids = sample.object_ids
        for index, column, kind in _pairs(sample):
            parent = ids[column] if column < len(ids) else STRUCTURAL_COLUMNS[column - len(ids)]
            line = {
                "sample": number,
                "scene_id": labelled.scene_id,
                "revision": labelled.revision,
                "child": ids[index],
                "child_class": sample.classes[index],
                "parent": parent,
                "type": SUPPORT_TYPE_ORDER[kind],
            }
            lines.append(json.dumps(line) + "\n")
    return "".join(lines).encode()


def _format_document(
    kept: list[tuple[LabelledScene, SupportSample]],
    heldout: np.ndarray,
    left_out: list[dict[str, Any]],
) -> bytes:
    document = {
        "format": FORMAT_NAME,
        "version": FORMAT_VERSION,
        "about": "Relation Network training samples from supports people set in HoliScene. "
        f"{PAIRS_FILE} (numpy.load) holds the arrays below, S samples (one per scene), O "
        f"objects over all samples, P labelled objects; {LABELS_FILE} the labelled pairs by "
        "object id. The network's output for a sample of N objects is N x (N + 3) x 2: row = "
        "the supported object, column = its supporter (N objects, then the structural "
        "columns), last axis = support type.",
        "arrays": {
            name: {"dtype": dtype, "shape": shape, "meaning": meaning}
            for name, (dtype, shape, meaning) in _ARRAYS.items()
        },
        "image_size": IMAGE_SIZE,
        "mask_size": MASK_SIZE,
        "structural_columns": list(STRUCTURAL_COLUMNS),
        "support_types": list(SUPPORT_TYPE_ORDER),
        "classes": list(NYU40_CLASSES),
        "samples": [
            _source(labelled.scene_id, labelled.revision, labelled.scene.name)
            | {
                "object_ids": list(sample.object_ids),
                "labelled": sample.labelled,
                "heldout": bool(held),
            }
            for (labelled, sample), held in zip(kept, heldout, strict=True)
        ],
        "left_out": left_out,
    }
    return (json.dumps(document, indent=1) + "\n").encode()

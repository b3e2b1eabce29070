"""The Relation Network's ONNX contract: tensor names, shapes, dtypes and their meaning.

Training (PyTorch), the backend (onnxruntime) and the browser (onnxruntime-web) all read this,
so one model file serves all three. Preprocessing is deliberately plain arithmetic that both
languages compute the same way (area averages over integer pixel ranges), so shared vectors
can prove the two agree.

Inputs, for a scene with N >= 1 labelled objects in an image of W x H pixels:
- `image`   float32 [1, 3, IMAGE_SIZE, IMAGE_SIZE]: RGB / 255, area-resized (see below).
- `masks`   float32 [N, MASK_SIZE, MASK_SIZE]: each object's mask, area-resized (the share of
            mask pixels in each cell).
- `boxes`   float32 [N, 4]: each object's 2D box (x0, y0, x1, y1) divided by (W, H, W, H).
- `classes` int64   [N]: each object's index in NYU40_CLASSES.

Output:
- `support_logits` float32 [N, N + 3, 2]: row i = object i (the supported one); column j < N =
  object j as its supporter, columns N, N+1, N+2 = STRUCTURAL_SUPPORTERS in that order; last
  axis = SUPPORT_TYPES. A softmax over each row's (N + 3) * 2 entries gives P(supporter, type).
  The diagonal (an object on itself) is masked to a large negative number by the model.

Area resize of an H x W array to S x S: output cell (r, c) is the mean of the input rows
floor(r * H / S) .. max(floor((r + 1) * H / S), floor(r * H / S) + 1) - 1 and the columns
likewise, summed in float64 and rounded once to float32.
"""

from __future__ import annotations

from typing import Any

from .support_graph import STRUCTURAL_SUPPORTERS

IMAGE_SIZE = 128
MASK_SIZE = 64
INPUT_NAMES: tuple[str, ...] = ("image", "masks", "boxes", "classes")
OUTPUT_NAME = "support_logits"
# Column order of the structural supporters after the N object columns.
STRUCTURAL_COLUMNS: tuple[str, ...] = tuple(sorted(STRUCTURAL_SUPPORTERS))
SUPPORT_TYPE_ORDER: tuple[str, ...] = ("below", "behind")
OPSET = 18


def relation_model_contract() -> dict[str, Any]:
    """The contract as JSON, written to jsonschema/vocabulary.json for the TypeScript side."""
    return {
        "image_size": IMAGE_SIZE,
        "mask_size": MASK_SIZE,
        "inputs": {
            "image": {"dtype": "float32", "shape": [1, 3, IMAGE_SIZE, IMAGE_SIZE]},
            "masks": {"dtype": "float32", "shape": ["N", MASK_SIZE, MASK_SIZE]},
            "boxes": {"dtype": "float32", "shape": ["N", 4]},
            "classes": {"dtype": "int64", "shape": ["N"]},
        },
        "input_order": list(INPUT_NAMES),
        "output": {"name": OUTPUT_NAME, "dtype": "float32", "shape": ["N", "N+3", 2]},
        "structural_columns": list(STRUCTURAL_COLUMNS),
        "support_types": list(SUPPORT_TYPE_ORDER),
        "opset": OPSET,
    }

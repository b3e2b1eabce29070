"""The object detector's ONNX contract: tensor names, preprocessing, decoding, class mapping.

The backend (onnxruntime) and the browser (onnxruntime-web) both read this, so one model file
serves both and shared vectors can hold them to the same numbers.

Input `images` float32 [1, INPUT_SIZE, INPUT_SIZE, 3]: the photo's RGB values (0-255, not
scaled) stretched to INPUT_SIZE x INPUT_SIZE by bilinear resampling with half-pixel centres
and no antialiasing: output pixel (r, c) samples the photo at y = (r + 0.5) * H / S - 0.5,
x = (c + 0.5) * W / S - 0.5, clamped to [0, H - 1] and [0, W - 1], computed in float64 and
rounded once to float32.

Output `detections` float32 [1, MAX_DETECTIONS, 6]: the model's best peaks, best first; each
row is x1, y1, x2, y2 in input pixels, score in [0, 1], class index (a float holding an
integer) into the model's own class list (`classes` in the model directory's metadata). The
model does no non-maximum suppression; decoding does (`decode` below, both languages):

1. keep rows with score >= the threshold;
2. scale boxes to the photo (x * W / S, y * H / S) and clip them to it;
3. map each class to NYU-40 (`COCO_TO_NYU40` for the COCO model; an NYU-40 model's classes
   are already NYU-40); rows of classes mapped to None are dropped;
4. greedy NMS per NYU-40 class at NMS_IOU, best score first (ties: the earlier row first);
5. drop boxes smaller than MIN_BOX_PX on either side.
"""

from __future__ import annotations

from typing import Any

INPUT_NAME = "images"
OUTPUT_NAME = "detections"
INPUT_SIZE = 512
MAX_DETECTIONS = 100
SCORE_THRESHOLD = 0.3
NMS_IOU = 0.5
# Above this IoU two boxes are one place whatever their classes (NMS is per class, so one thing
# can come as a "sofa" and as a "bed"): where boxes become objects or suggestions, the likelier
# one stands for that place (not part of `decode`, whose rows also feed the class hints).
SAME_PLACE_IOU = 0.7
MIN_BOX_PX = 4.0
# A photo whose grey levels (0-255) vary less than this (standard deviation) is one flat
# colour: it is not given to the detector, which still "sees" objects in a blank frame.
FLAT_PHOTO_STD = 2.0
OPSET = 17

# The 80 COCO classes in the order of the pretrained model's class index.
COCO_CLASSES: tuple[str, ...] = (
    "person", "bicycle", "car", "motorcycle", "airplane", "bus", "train", "truck", "boat",
    "traffic light", "fire hydrant", "stop sign", "parking meter", "bench", "bird", "cat",
    "dog", "horse", "sheep", "cow", "elephant", "bear", "zebra", "giraffe", "backpack",
    "umbrella", "handbag", "tie", "suitcase", "frisbee", "skis", "snowboard", "sports ball",
    "kite", "baseball bat", "baseball glove", "skateboard", "surfboard", "tennis racket",
    "bottle", "wine glass", "cup", "fork", "knife", "spoon", "bowl", "banana", "apple",
    "sandwich", "orange", "broccoli", "carrot", "hot dog", "pizza", "donut", "cake", "chair",
    "couch", "potted plant", "bed", "dining table", "toilet", "tv", "laptop", "mouse",
    "remote", "keyboard", "cell phone", "microwave", "oven", "toaster", "sink",
    "refrigerator", "book", "clock", "vase", "scissors", "teddy bear", "hair drier",
    "toothbrush",
)  # fmt: skip

# COCO class -> NYU-40 class; None: not an indoor object people label (animals, vehicles,
# outdoor things), dropped. Small things on tables and shelves become `otherprop`.
_COCO_NAMED: dict[str, str | None] = {
    "person": "person",
    "bench": "otherfurniture",
    "backpack": "bag",
    "handbag": "bag",
    "suitcase": "bag",
    "chair": "chair",
    "couch": "sofa",
    "bed": "bed",
    "dining table": "table",
    "toilet": "toilet",
    "tv": "television",
    "sink": "sink",
    "refrigerator": "refrigerator",
    "book": "books",
    "potted plant": "otherprop",
    "laptop": "otherprop",
    "bottle": "otherprop",
    "wine glass": "otherprop",
    "cup": "otherprop",
    "bowl": "otherprop",
    "vase": "otherprop",
    "clock": "otherprop",
    "microwave": "otherprop",
    "oven": "otherfurniture",
    "toaster": "otherprop",
    "keyboard": "otherprop",
    "mouse": "otherprop",
    "remote": "otherprop",
    "cell phone": "otherprop",
    "teddy bear": "otherprop",
    "umbrella": "otherprop",
    "sports ball": "otherprop",
    "scissors": "otherprop",
    "hair drier": "otherprop",
    "toothbrush": "otherprop",
    "fork": "otherprop",
    "knife": "otherprop",
    "spoon": "otherprop",
}
COCO_TO_NYU40: tuple[str | None, ...] = tuple(_COCO_NAMED.get(name) for name in COCO_CLASSES)


def detector_contract() -> dict[str, Any]:
    """The contract as JSON, written to jsonschema/vocabulary.json for the TypeScript side."""
    return {
        "input": {"name": INPUT_NAME, "dtype": "float32", "shape": [1, INPUT_SIZE, INPUT_SIZE, 3]},
        "output": {"name": OUTPUT_NAME, "dtype": "float32", "shape": [1, MAX_DETECTIONS, 6]},
        "input_size": INPUT_SIZE,
        "score_threshold": SCORE_THRESHOLD,
        "nms_iou": NMS_IOU,
        "same_place_iou": SAME_PLACE_IOU,
        "min_box_px": MIN_BOX_PX,
        "flat_photo_std": FLAT_PHOTO_STD,
        "coco_classes": list(COCO_CLASSES),
        "coco_to_nyu40": list(COCO_TO_NYU40),
        "opset": OPSET,
    }

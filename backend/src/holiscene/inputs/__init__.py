"""Reading and checking what users give: photos, intrinsics, 2D boxes, depth."""

from .depth import DepthMap, depth_from_metres, depth_from_png
from .validation import (
    InputError,
    InputFiles,
    Photo,
    load_photo,
    parse_class_map,
    parse_detections,
    parse_intrinsics,
    read_input_folder,
)

__all__ = [
    "DepthMap",
    "InputError",
    "InputFiles",
    "Photo",
    "depth_from_metres",
    "depth_from_png",
    "load_photo",
    "parse_class_map",
    "parse_detections",
    "parse_intrinsics",
    "read_input_folder",
]

"""Reading and checking what users give: photos, intrinsics, 2D boxes."""

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
    "InputError",
    "InputFiles",
    "Photo",
    "load_photo",
    "parse_class_map",
    "parse_detections",
    "parse_intrinsics",
    "read_input_folder",
]

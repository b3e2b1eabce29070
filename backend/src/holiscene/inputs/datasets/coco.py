"""COCO instance files: `images`, `annotations` (bbox [x, y, w, h], segmentation as polygons,
uncompressed RLE or compressed RLE), `categories`, and the image folder beside the file.

Each image is one item: its annotations become boxes with masks ("given"), its category
names NYU-40 classes (holiscene_schema.map_class_name, a class_map.json beside the file
first). Crowd regions (`iscrowd` 1) mark many objects at once and are left out.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
from holiscene_schema import STRUCTURAL_SUPPORTERS, SupportRelation

from ..validation import InputError, InputFiles, load_photo, support_relations
from .items import (
    DatasetItem,
    class_map_beside,
    labelled_detection,
    load_json,
    named_file,
    polygon_pixels,
)

IMAGE_FOLDER = "images"


def is_coco(data: Any) -> bool:
    return isinstance(data, dict) and "images" in data and "annotations" in data


def read_coco(path: Path) -> Iterator[DatasetItem]:
    """One item per image of the COCO file at `path`; a file that does not read is one item
    with its error."""
    try:
        data = load_json(path)
        if not is_coco(data):
            raise InputError(f"{path.name} is not a COCO instances file (no images/annotations)")
        categories = _categories(data)
        class_map = class_map_beside(path)
        images = data["images"]
        annotations = data["annotations"]
        if not isinstance(images, list) or not isinstance(annotations, list):
            raise InputError(f"{path.name}: 'images' and 'annotations' must be lists")
    except InputError as exc:
        yield DatasetItem(name=str(path), error=str(exc))
        return
    by_image: dict[Any, list[Any]] = {}
    for annotation in annotations:
        image_id = annotation.get("image_id") if isinstance(annotation, dict) else None
        by_image.setdefault(image_id, []).append(annotation)
    for number, image in enumerate(images):
        name = _image_name(image, number)
        try:
            inputs = _read_image(path, image, by_image, categories, class_map)
        except InputError as exc:
            yield DatasetItem(name=name, error=str(exc))
            continue
        yield DatasetItem(name=name, inputs=inputs)


def _image_name(image: Any, number: int) -> str:
    if isinstance(image, dict) and isinstance(image.get("file_name"), str):
        return str(image["file_name"])
    return f"image {number}"


def _categories(data: dict[str, Any]) -> dict[Any, str]:
    categories = data.get("categories", [])
    if not isinstance(categories, list) or not all(
        isinstance(c, dict) and isinstance(c.get("name"), str) and "id" in c for c in categories
    ):
        raise InputError("'categories' must be a list of {id, name}")
    return {c["id"]: c["name"] for c in categories}


def image_file(json_path: Path, file_name: str) -> Path:
    """The image of a COCO entry: relative to the JSON's folder, or in `images/` beside it."""
    folder = json_path.parent
    for candidate in (
        folder / file_name,
        folder / IMAGE_FOLDER / file_name,
        folder / IMAGE_FOLDER / Path(file_name).name,
    ):
        found = named_file(candidate, f"the image file {file_name}")
        if found is not None:
            return found
    raise InputError(
        f"the image file {file_name} is missing (looked beside {json_path.name} and in "
        f"{IMAGE_FOLDER}/)"
    )


def _read_image(
    path: Path,
    image: Any,
    by_image: dict[Any, list[Any]],
    categories: dict[Any, str],
    class_map: dict[str, str] | None,
) -> InputFiles:
    if not isinstance(image, dict) or not isinstance(image.get("file_name"), str):
        raise InputError("an image entry must have an 'id' and a 'file_name'")
    data = image_file(path, image["file_name"]).read_bytes()
    photo = load_photo(data)
    stated = (image.get("width"), image.get("height"))
    notes: list[str] = []
    unturned_size = (photo.height, photo.width)  # a square photo's size says nothing
    if photo.turned_sides and stated == unturned_size != (photo.width, photo.height):
        # The entry's size is the stored pixels': its labels were drawn without the EXIF turn.
        photo = load_photo(data, exif_turn=False)
        notes.append(
            "the photo's EXIF turn was left out: the COCO entry's size is the unturned one"
        )
    if stated != (None, None) and stated != (photo.width, photo.height):
        raise InputError(
            f"the file is {photo.width}x{photo.height} pixels, the COCO entry says "
            f"{stated[0]}x{stated[1]}"
        )
    detections = []
    kept: list[tuple[str, dict[str, Any]]] = []  # the annotations that became boxes, in order
    for index, annotation in enumerate(by_image.get(image.get("id"), [])):
        where = f"annotation {annotation.get('id', index)}"
        if annotation.get("iscrowd"):
            continue
        if annotation.get("category_id") not in categories:
            raise InputError(f"{where}: category {annotation.get('category_id')!r} is not listed")
        name = categories[annotation["category_id"]]
        pixels = _segmentation_pixels(
            where, annotation.get("segmentation"), photo.width, photo.height
        )
        bbox = _bbox_xyxy(where, annotation.get("bbox"))
        detections.append(
            labelled_detection(where, name, bbox, pixels, photo.width, photo.height, class_map)
        )
        kept.append((where, annotation))
    return InputFiles(
        photo=photo, K=None, detections=detections, supports=_supports(kept), notes=tuple(notes)
    )


def _supports(kept: list[tuple[str, dict[str, Any]]]) -> tuple[SupportRelation, ...]:
    """The `holiscene_support` {parent, type} of the image's annotations (as holiscene export
    writes them: the parent another annotation's `holiscene_id`, or floor/wall/ceiling) as
    people's support labels over the boxes."""
    numbers = {a["holiscene_id"]: i for i, (_, a) in enumerate(kept) if "holiscene_id" in a}
    labelled: list[tuple[str, Any]] = []
    for number, (where, annotation) in enumerate(kept):
        support = annotation.get("holiscene_support")
        if support is None:
            continue
        at = f"{where}: holiscene_support"
        if not isinstance(support, dict) or not {"parent", "type"} <= support.keys():
            raise InputError(f"{at} must be an object with 'parent' and 'type'")
        parent = support["parent"]
        if not (isinstance(parent, str) and parent in STRUCTURAL_SUPPORTERS):
            if not isinstance(parent, str) or parent not in numbers:
                raise InputError(
                    f"{at}: parent {parent!r} is neither floor, wall, ceiling nor the "
                    "holiscene_id of an annotation of this image"
                )
            parent = numbers[parent]
        labelled.append((at, {**support, "child": number, "parent": parent}))
    return support_relations(labelled, len(kept), "holiscene_support", "the image's i-th object")


def _bbox_xyxy(where: str, bbox: Any) -> list[float] | None:
    if bbox is None:
        return None
    if not isinstance(bbox, list) or len(bbox) != 4:
        raise InputError(f"{where}: 'bbox' must be [x, y, width, height]")
    x, y, w, h = bbox
    if not all(isinstance(v, int | float) and not isinstance(v, bool) for v in bbox):
        raise InputError(f"{where}: 'bbox' must be 4 numbers [x, y, width, height]")
    return [float(x), float(y), float(x + w), float(y + h)]


def _segmentation_pixels(
    where: str, segmentation: Any, width: int, height: int
) -> np.ndarray | None:
    """The mask of an annotation's segmentation (polygons or RLE), None when it has none."""
    if segmentation is None or segmentation == []:
        return None
    if isinstance(segmentation, list):
        mask = np.zeros((height, width), dtype=bool)
        for polygon in segmentation:
            mask |= polygon_pixels(where, polygon, width, height, at_pixel_centres=True)
        return mask
    if isinstance(segmentation, dict) and "counts" in segmentation and "size" in segmentation:
        if list(segmentation["size"]) != [height, width]:
            raise InputError(
                f"{where}: the RLE's size {segmentation['size']} is not the image's "
                f"[{height}, {width}]"
            )
        counts = segmentation["counts"]
        if isinstance(counts, str):
            counts = decode_rle_string(counts)
        try:
            return rle_pixels(counts, height, width)
        except ValueError as exc:
            raise InputError(f"{where}: {exc}") from exc
    raise InputError(f"{where}: 'segmentation' must be polygons or an RLE {{counts, size}}")


def rle_pixels(counts: Any, height: int, width: int) -> np.ndarray:
    """The bool (H, W) mask of COCO RLE counts: column-major runs, background first."""
    if not isinstance(counts, list) or not all(
        isinstance(c, int) and not isinstance(c, bool) and c >= 0 for c in counts
    ):
        raise ValueError("RLE counts must be whole numbers >= 0")
    if sum(counts) != height * width:
        raise ValueError(f"RLE counts add up to {sum(counts)}, not {height}x{width} pixels")
    values = np.arange(len(counts)) % 2 == 1
    return np.repeat(values, counts).reshape((height, width), order="F")


# COCO's compressed RLE: each count (after the first two, as the difference to the count two
# before it) in little-endian groups of 5 bits, one character per group: 48 + the bits, +32
# when another group follows; bit 16 of the last group is the sign.


def decode_rle_string(text: str) -> list[int]:
    counts: list[int] = []
    position = 0
    while position < len(text):
        value, shift, more = 0, 0, True
        while more:
            if position >= len(text):
                raise InputError("the compressed RLE string ends inside a count")
            group = ord(text[position]) - 48
            if not 0 <= group < 64:
                raise InputError(
                    f"the compressed RLE string has a stray character {text[position]!r}"
                )
            value |= (group & 0x1F) << shift
            more = bool(group & 0x20)
            position += 1
            shift += 5
            if not more and group & 0x10:
                value -= 1 << shift  # negative: sign-extend
        if len(counts) > 2:
            value += counts[-2]
        counts.append(value)
    if any(c < 0 for c in counts):
        raise InputError("the compressed RLE string decodes to a negative count")
    return counts


def encode_rle_string(counts: list[int]) -> str:
    """COCO's string form of RLE counts (the inverse of decode_rle_string)."""
    chars: list[str] = []
    for index, count in enumerate(counts):
        value = count - counts[index - 2] if index > 2 else count
        more = True
        while more:
            group = value & 0x1F
            value >>= 5
            more = value != -1 if group & 0x10 else value != 0
            chars.append(chr(48 + (group | (0x20 if more else 0))))
    return "".join(chars)

"""Input checks shared by the CLI and the server. Every failure is an InputError whose message
says which file is wrong and how, raised before anything is written."""

from __future__ import annotations

import hashlib
import io
import json
import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np
from holiscene_schema import (
    STRUCTURAL_SUPPORTERS,
    Camera,
    Layout,
    Mask,
    Scene,
    SupportRelation,
    UnknownClassError,
    class_key,
    map_class_name,
    normalise_class_name,
    support_graph_problems,
)
from PIL import ExifTags, Image, ImageOps, UnidentifiedImageError
from pydantic import ValidationError

from ..pipeline.base import Detection
from .depth import DEPTH_FILE, DepthMap, depth_from_png
from .errors import InputError as InputError  # re-exported: the readers import it from here

MAX_IMAGE_PIXELS = 40_000_000  # 40 MP: far above any indoor photo we expect, far below a bomb
# A room photo, not a strip: the pipeline's line, mask and layout steps need both sides.
MIN_IMAGE_SIDE = 32
MAX_ASPECT_RATIO = 8.0
BOX_TOLERANCE_PX = 2.0  # boxes may overhang the border by rounding, not more
_FORMATS = {"JPEG": ".jpg", "PNG": ".png"}
UPRIGHT_JPEG_QUALITY = 95  # a photo turned upright is encoded again; 95 keeps it near the original


@dataclass(frozen=True)
class Photo:
    rgb: np.ndarray  # (H, W, 3) uint8
    data: bytes  # the file as given
    suffix: str  # ".jpg" or ".png"
    # Read upright through an EXIF quarter turn: the file's own pixels are `rgb` on its side.
    turned_sides: bool = False

    @property
    def width(self) -> int:
        return int(self.rgb.shape[1])

    @property
    def height(self) -> int:
        return int(self.rgb.shape[0])


def load_photo(data: bytes, max_pixels: int = MAX_IMAGE_PIXELS, *, exif_turn: bool = True) -> Photo:
    """Decode a JPEG or PNG photo, checking its size from the header before decoding it.

    A photo with an EXIF turn (phones store the sensor's pixels and the turn) is read upright,
    as browsers and labelling tools show it, and its stored copy is encoded so; `exif_turn=False`
    reads the pixels as stored (labels made without the turn) and drops the turn instead."""
    if not data:
        raise InputError("the photo is empty", 400)
    try:
        image = Image.open(io.BytesIO(data))
    except Image.DecompressionBombError as exc:
        raise InputError(f"the photo is too large: {exc}", 413) from exc
    except (UnidentifiedImageError, OSError) as exc:
        raise InputError("the photo is not a JPEG or PNG image", 415) from exc
    if image.format not in _FORMATS:
        raise InputError(f"the photo is a {image.format} image; use JPEG or PNG", 415)
    width, height = image.size
    if width * height > max_pixels:
        raise InputError(
            f"the photo is too large: {width}x{height} pixels, at most "
            f"{max_pixels // 1_000_000} MP are accepted",
            413,
        )
    if min(width, height) < MIN_IMAGE_SIDE or max(width, height) > MAX_ASPECT_RATIO * min(
        width, height
    ):
        raise InputError(
            f"the photo is {width}x{height} pixels: a room photo needs both sides at least "
            f"{MIN_IMAGE_SIDE} pixels and the longer at most {MAX_ASPECT_RATIO:g} times the shorter"
        )
    try:
        image.load()
        orientation = _exif_orientation(image)
        if orientation == 1:
            return Photo(
                rgb=np.asarray(image.convert("RGB")), data=data, suffix=_FORMATS[image.format]
            )
        read = ImageOps.exif_transpose(image) if exif_turn else _without_turn(image)
        return Photo(
            rgb=np.asarray(read.convert("RGB")),
            data=_encoded_like(read, image),
            suffix=_FORMATS[image.format],
            turned_sides=exif_turn and orientation >= 5,  # orientations 5-8 swap the sides
        )
    except (OSError, SyntaxError, ValueError) as exc:
        raise InputError(f"the photo cannot be decoded (truncated or corrupt): {exc}") from exc


def _exif_orientation(image: Image.Image) -> int:
    """The EXIF turn a phone stores beside the sensor's pixels (1: none). Browsers and labelling
    tools show the photo turned, so its boxes, masks and K are in that upright frame."""
    try:
        orientation = image.getexif().get(ExifTags.Base.Orientation, 1)
    except (OSError, SyntaxError, ValueError):
        return 1  # an unreadable EXIF block: the pixels as stored
    return orientation if isinstance(orientation, int) and 2 <= orientation <= 8 else 1


def _without_turn(image: Image.Image) -> Image.Image:
    kept = image.copy()
    exif = kept.getexif()
    del exif[ExifTags.Base.Orientation]
    kept.info["exif"] = exif.tobytes()
    return kept


def _encoded_like(upright: Image.Image, original: Image.Image) -> bytes:
    """The upright photo in the original's format, without the turn, so every reader of the
    stored file (the page, the exports, the viewers) sees the pixels the pipeline saw."""
    buffer = io.BytesIO()
    options: dict[str, Any] = {"exif": upright.getexif().tobytes()}
    if "icc_profile" in original.info:
        options["icc_profile"] = original.info["icc_profile"]
    if original.format == "JPEG":
        options["quality"] = UPRIGHT_JPEG_QUALITY
        upright = upright.convert("RGB") if upright.mode not in ("RGB", "L", "CMYK") else upright
    upright.save(buffer, original.format, **options)
    return buffer.getvalue()


def parse_intrinsics(text: str) -> np.ndarray:
    """cam_K.txt: a 3x3 matrix [[fx, 0, cx], [0, fy, cy], [0, 0, 1]], one row per line."""
    try:
        rows = [
            [float(v) for v in line.split()] for line in text.strip().splitlines() if line.strip()
        ]
    except ValueError as exc:
        raise InputError(f"cam_K.txt must hold numbers only: {exc}") from exc
    if len(rows) != 3 or any(len(r) != 3 for r in rows):
        raise InputError("cam_K.txt must hold a 3x3 matrix, one row of 3 numbers per line")
    K = np.array(rows)
    if not np.all(np.isfinite(K)):
        raise InputError("cam_K.txt holds a value that is not finite")
    if K[0, 0] <= 0 or K[1, 1] <= 0 or not np.allclose(K[2], [0, 0, 1]) or K[1, 0] != 0:
        raise InputError(
            "cam_K.txt must be [[fx, s, cx], [0, fy, cy], [0, 0, 1]] with positive focal lengths"
        )
    return K


def parse_class_map(data: bytes) -> dict[str, str]:
    """class_map.json: {"dataset's name": "NYU-40 class", ...}, the user's own mapping, which
    wins over the built-in aliases (keys compared as holiscene_schema.class_key does)."""
    try:
        items = json.loads(data)
    except (json.JSONDecodeError, UnicodeDecodeError, RecursionError) as exc:
        raise InputError(f"class_map.json is not valid JSON: {exc}") from exc
    if not isinstance(items, dict):
        raise InputError('class_map.json must be an object {"name": "NYU-40 class", ...}')
    mapping: dict[str, str] = {}
    for name, target in items.items():
        if not isinstance(target, str):
            raise InputError(f"class_map.json: {name!r} must map to a class name (a string)")
        try:
            mapping[class_key(name)] = normalise_class_name(target)
        except UnknownClassError as exc:
            raise InputError(f"class_map.json: {name!r} maps to {exc}") from exc
    return mapping


def parse_detections(
    data: bytes, width: int, height: int, class_map: dict[str, str] | None = None
) -> list[Detection]:
    """detections.json: [{"bbox": [x1, y1, x2, y2], "class": NAME}, ...] in pixels. A NAME
    in no vocabulary becomes otherprop with the name kept, never a refusal; an item may also
    carry "source_class", the name it had before (the store writes it so), and "mask", the
    object's outline as the contract's Mask JSON (a labelled dataset's, kept by the store)."""
    try:
        items = json.loads(data)
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise InputError(f"detections.json is not valid JSON: {exc}") from exc
    except RecursionError as exc:  # the parser recurses once per level of [ or {
        raise InputError("detections.json is nested too deeply to be a list of boxes") from exc
    if not isinstance(items, list):
        raise InputError('detections.json must be a list of {"bbox": [...], "class": ...}')
    return [
        detection_from_item(f"detections.json item {i}", item, width, height, class_map or {})
        for i, item in enumerate(items)
    ]


def detection_from_item(
    where: str, item: Any, width: int, height: int, class_map: dict[str, str]
) -> Detection:
    """One detections.json item checked (`where` names it in the messages); the dataset
    readers build their boxes through it too."""
    if not isinstance(item, dict) or "bbox" not in item or "class" not in item:
        raise InputError(f"{where} must be an object with 'bbox' and 'class'")
    bbox, name = item["bbox"], item["class"]
    if (
        not isinstance(bbox, list)
        or len(bbox) != 4
        or not all(isinstance(v, int | float) and not isinstance(v, bool) for v in bbox)
        or not all(math.isfinite(v) for v in bbox)
    ):
        raise InputError(f"{where}: 'bbox' must be 4 numbers [x1, y1, x2, y2]")
    x1, y1, x2, y2 = (float(v) for v in bbox)
    if x2 <= x1 or y2 <= y1:
        raise InputError(f"{where}: box {bbox} is empty (x2 <= x1 or y2 <= y1)")
    tol = BOX_TOLERANCE_PX
    if x1 < -tol or y1 < -tol or x2 > width + tol or y2 > height + tol:
        raise InputError(f"{where}: box {bbox} lies outside the {width}x{height} image")
    if not isinstance(name, str) or not name.strip():
        raise InputError(f"{where}: 'class' must be a class name (a non-empty string)")
    source = item.get("source_class", name)
    if not isinstance(source, str) or not source.strip():
        raise InputError(f"{where}: 'source_class' must be a non-empty string")
    mapped = map_class_name(name, class_map)
    clipped = (max(0.0, x1), max(0.0, y1), min(float(width), x2), min(float(height), y2))
    mask = _parse_mask(where, item["mask"], width, height) if "mask" in item else None
    return Detection(
        cls=mapped.cls, bbox=clipped, source_class=source, class_known=mapped.known, mask=mask
    )


def _parse_mask(where: str, data: Any, width: int, height: int) -> Mask:
    """A box's given mask: the contract's Mask (runs filling the window) with its window
    inside the image; its source becomes "given" whatever it said."""
    try:
        mask = Mask.model_validate({**data, "source": "given"} if isinstance(data, dict) else data)
    except ValidationError as exc:
        problem = exc.errors()[0]
        at = ".".join(str(p) for p in problem["loc"])
        raise InputError(f"{where}: 'mask' is not a mask ({at}: {problem['msg']})") from exc
    (x0, y0), (w, h) = mask.origin, mask.size
    if x0 < 0 or y0 < 0 or w < 1 or h < 1 or x0 + w > width or y0 + h > height:
        raise InputError(
            f"{where}: the mask's window (origin {mask.origin}, size {mask.size}) lies outside "
            f"the {width}x{height} image"
        )
    return mask


@dataclass(frozen=True)
class InputFiles:
    """The contents of an input folder or of one photo of a dataset, checked.

    `supports` are support labels people made, given with the photo (a dataset's ground
    truth), over the object ids the detections get on import (o0, o1, ... in order); they
    enter revision 1 as people's labels. `ground_truth` is a scene with whatever the dataset
    measured (3D boxes, layout, camera), kept beside the stored scene as gt.json for
    `holiscene eval`; it is never shown as the scene's own estimate. `depth` is an RGB-D
    camera's depth, kept beside the scene as depth.png. `camera` and `layout` are a scene's
    own (scene.json beside the photo, as the app's downloads and `holiscene export --format
    scene` write it): revision 1 starts with them, and a layout set by hand is kept by the
    pipeline as on the scene they came from."""

    photo: Photo
    K: np.ndarray | None
    detections: list[Detection] | None
    supports: tuple[SupportRelation, ...] = ()
    ground_truth: Scene | None = None
    depth: DepthMap | None = None  # inputs/depth.py; registered to the photo
    camera: Camera | None = None
    layout: Layout | None = None
    # What the reader left out of the labels given with the photo, for the user (revision 1
    # shows it with the pipeline's warnings).
    notes: tuple[str, ...] = ()

    @cached_property
    def digest(self) -> str:
        """A fingerprint of the photo and its labels (SHA-256, hex): the same files imported
        twice give the same digest, any change to the photo, intrinsics or boxes another.
        Computed once: an import asks for it to look for an earlier one and to store it."""
        boxes = [
            {
                "class": d.cls,
                "bbox": list(d.bbox),
                "source_class": d.source_class,
                "mask": d.mask.model_dump(mode="json") if d.mask is not None else None,
            }
            for d in self.detections or []
        ]
        labels: dict[str, Any] = {
            "K": self.K.round(6).tolist() if self.K is not None else None,
            "detections": boxes if self.detections is not None else None,
        }
        # Only when present, so digests of imports made before these existed stay the same.
        if self.supports:
            labels["supports"] = [s.model_dump(mode="json") for s in self.supports]
        if self.ground_truth is not None:
            labels["ground_truth"] = self.ground_truth.model_dump(mode="json")
        if self.depth is not None:
            labels["depth"] = self.depth.digest
        if self.camera is not None:
            labels["camera"] = self.camera.model_dump(mode="json")
        if self.layout is not None:
            labels["layout"] = self.layout.model_dump(mode="json")
        hasher = hashlib.sha256(self.photo.data)
        hasher.update(json.dumps(labels, sort_keys=True).encode())
        return hasher.hexdigest()


SUPPORTS_AUTHOR = "import"  # a supports.json item's author when it names none


def parse_supports(data: bytes, box_count: int) -> tuple[SupportRelation, ...]:
    """supports.json: [{"child": 3, "parent": 0 | "floor" | "wall" | "ceiling", "type":
    "below" | "behind", "author": NAME (optional)}, ...], people's support labels over the
    boxes of detections.json by position (box i becomes object o<i>); an item with "source":
    "auto" (and an optional "confidence") is a pipeline's guess, as an export writes one."""
    try:
        items = json.loads(data)
    except (json.JSONDecodeError, UnicodeDecodeError, RecursionError) as exc:
        raise InputError(f"supports.json is not valid JSON: {exc}") from exc
    if not isinstance(items, list):
        raise InputError('supports.json must be a list of {"child", "parent", "type"}')
    labelled = [(f"supports.json item {i}", item) for i, item in enumerate(items)]
    return support_relations(labelled, box_count, "supports.json", "detections.json item i")


def support_relations(
    items: Sequence[tuple[str, Any]], box_count: int, source: str, numbering: str
) -> tuple[SupportRelation, ...]:
    """Support labels in supports.json's item form, each with where it came from (for the
    messages), checked against the boxes and as a graph; `numbering` tells the user what
    o<i> is (the dataset readers give their labels this way too)."""
    relations = tuple(_support_from_item(where, item, box_count) for where, item in items)
    ids = [f"o{i}" for i in range(box_count)]
    problems = support_graph_problems(ids, [(s.child, s.parent) for s in relations])
    if problems:
        raise InputError(f"{source}: {'; '.join(problems)} (o<i> is {numbering})")
    return relations


def _support_from_item(where: str, item: Any, box_count: int) -> SupportRelation:
    if not isinstance(item, dict) or not {"child", "parent", "type"} <= item.keys():
        raise InputError(f"{where} must be an object with 'child', 'parent' and 'type'")

    def box(key: str, or_else: str = "") -> str:
        index = item[key]
        if not isinstance(index, int) or isinstance(index, bool) or not 0 <= index < box_count:
            raise InputError(
                f"{where}: {key} {index!r} is not the number of a box (0 to "
                f"{box_count - 1}){or_else}"
            )
        return f"o{index}"

    parent = item["parent"]
    if not (isinstance(parent, str) and parent in STRUCTURAL_SUPPORTERS):
        parent = box("parent", ", nor floor, wall or ceiling")
    if item["type"] not in ("below", "behind"):
        raise InputError(f"{where}: type {item['type']!r} is neither 'below' nor 'behind'")
    source = item.get("source", "manual")
    if source == "auto" and "author" in item:
        # A guess edited by hand (its parent changed, an author added) would import as the
        # pipeline's, and a pipeline run would replace it: say which one it is.
        raise InputError(
            f"{where}: source 'auto' (the pipeline's guess) with an author: a person's label "
            "has no source 'auto', remove one of the two"
        )
    if source == "auto":  # a pipeline's guess (as an export writes one) stays a guess
        confidence = item.get("confidence")
        if confidence is not None and not (
            isinstance(confidence, int | float)
            and not isinstance(confidence, bool)
            and 0 <= confidence <= 1
        ):
            raise InputError(f"{where}: 'confidence' must be a number from 0 to 1")
        return SupportRelation(
            child=box("child"),
            parent=parent,
            type=item["type"],
            source="auto",
            confidence=confidence,
        )
    if source != "manual":
        raise InputError(f"{where}: source {source!r} is neither 'manual' nor 'auto'")
    author = item.get("author", SUPPORTS_AUTHOR)
    if not isinstance(author, str) or not author.strip():
        raise InputError(f"{where}: 'author' must be a non-empty string")
    return SupportRelation(
        child=box("child"), parent=parent, type=item["type"], source="manual", author=author
    )


def parse_ground_truth(data: bytes, width: int, height: int, file: str = "gt.json") -> Scene:
    """gt.json: a scene (the contract's Scene, as `holiscene synth` writes it) with what a
    dataset measured for the photo; `file` names it in the messages (scene.json is read so
    too)."""
    try:
        scene = Scene.model_validate_json(data)
    except ValidationError as exc:
        problem = exc.errors()[0]
        at = ".".join(str(p) for p in problem["loc"]) or "the file"
        raise InputError(f"{file} is not a scene ({at}: {problem['msg']})") from exc
    if (scene.image.width, scene.image.height) != (width, height):
        raise InputError(
            f"{file} describes a {scene.image.width}x{scene.image.height} photo, the photo "
            f"is {width}x{height}"
        )
    return scene


SCENE_FILE = "scene.json"


def scene_room(folder: Path, width: int, height: int) -> tuple[Camera | None, Layout | None]:
    """The camera and room layout of the folder's scene.json (the scene the folder was
    exported from), when it has them; scene.json's objects are not read: detections.json and
    supports.json are the labels."""
    file = folder / SCENE_FILE
    if not file.is_file():
        return None, None
    scene = parse_ground_truth(file.read_bytes(), width, height, SCENE_FILE)
    layout = scene.layout if scene.layout.corners_3d is not None else None
    return scene.camera, layout


# Beside a stored scene: what its import left out of the labels given with the photo (a JSON
# list of notes), so every pipeline run on it says so again.
IMPORT_NOTES_FILE = "import_notes.json"


def read_import_notes(folder: Path) -> tuple[str, ...]:
    path = folder / IMPORT_NOTES_FILE
    if not path.is_file():
        return ()
    try:
        notes = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise InputError(f"{IMPORT_NOTES_FILE} is not a JSON list of notes: {exc}") from exc
    if not isinstance(notes, list) or not all(isinstance(n, str) for n in notes):
        raise InputError(f"{IMPORT_NOTES_FILE} must be a JSON list of notes")
    return tuple(notes)


def read_input_folder(folder: Path, *, use_depth: bool = True) -> InputFiles:
    """Read img.jpg or img.png, and cam_K.txt, detections.json, class_map.json (the
    user's own class names, see parse_class_map), supports.json (parse_supports), gt.json
    (parse_ground_truth), scene.json's camera and layout (scene_room), depth.png
    (inputs/depth.py; unless not `use_depth`, for the single-photo path on a folder that has
    depth) and a stored scene's import_notes.json when present."""
    if not folder.is_dir():
        raise InputError(f"{folder} is not a folder")
    images = [folder / n for n in ("img.jpg", "img.jpeg", "img.png") if (folder / n).is_file()]
    if not images:
        raise InputError(f"{folder} holds no img.jpg or img.png")
    photo = load_photo(images[0].read_bytes())
    k_file, det_file = folder / "cam_K.txt", folder / "detections.json"
    map_file = folder / "class_map.json"
    K = parse_intrinsics(k_file.read_text()) if k_file.is_file() else None
    class_map = parse_class_map(map_file.read_bytes()) if map_file.is_file() else None
    detections = (
        parse_detections(det_file.read_bytes(), photo.width, photo.height, class_map)
        if det_file.is_file()
        else None
    )
    supports_file, truth_file = folder / "supports.json", folder / "gt.json"
    supports: tuple[SupportRelation, ...] = ()
    if supports_file.is_file():
        if detections is None:
            raise InputError(
                "supports.json needs detections.json: its numbers are positions in that list"
            )
        supports = parse_supports(supports_file.read_bytes(), len(detections))
    truth = (
        parse_ground_truth(truth_file.read_bytes(), photo.width, photo.height)
        if truth_file.is_file()
        else None
    )
    depth_file = folder / DEPTH_FILE
    depth = (
        depth_from_png(depth_file.read_bytes(), photo.width, photo.height)
        if use_depth and depth_file.is_file()
        else None
    )
    camera, layout = scene_room(folder, photo.width, photo.height)
    return InputFiles(
        photo=photo,
        K=K,
        detections=detections,
        supports=supports,
        ground_truth=truth,
        depth=depth,
        camera=camera,
        layout=layout,
        notes=read_import_notes(folder),
    )

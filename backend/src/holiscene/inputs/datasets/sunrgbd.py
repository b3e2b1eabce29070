"""SUN RGB-D image folders: each photo with its 2D outlines as objects, and what the dataset
measured (camera tilt, 3D boxes, room layout) as the scene's ground truth.

One image folder holds `image/<name>.jpg`, `intrinsics.txt` (K, 9 numbers row by row),
`extrinsics/<stamp>.txt` (the newest is used), `annotation2Dfinal/index.json` (polygons
`frames[0].polygon[i] = {x, y, object: k}` naming `objects[k].name`), and, when annotated,
`annotation3Dfinal/index.json` (a box per object) and `annotation3Dlayout/index.json` (the
room), and `depth/<name>.png` (the sensor's depth, millimetres with their bits rotated; the
filled-in `depth_bfx/` only when there is no `depth/`). Frames and their conversion:
sunrgbd_frames.py.

A 3D box belongs to the 2D object at the same index k of the two files' `objects` lists,
when both give it the same name; other 3D boxes are left out of the ground truth.
"""

from __future__ import annotations

import os
import re
import sys
from collections.abc import Iterator
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
from holiscene_schema import (
    STRUCTURAL_CLASSES,
    Box3D,
    Camera,
    ImageInfo,
    Layout,
    Scene,
    SceneObject,
)

from ...evaluation.box_iou import iou_2d
from ...geometry.boxes import box_corners
from ...geometry.camera import FloatArray, PinholeCamera
from ...pipeline.base import Detection
from ...segmentation.rle import decode_mask, encode_mask
from ..depth import DepthMap, depth_from_png
from ..validation import (
    InputError,
    InputFiles,
    Photo,
    load_photo,
    parse_class_map,
    parse_intrinsics,
)
from .items import CLASS_MAP_FILE, DatasetItem, labelled_detection, load_json, polygon_pixels
from .sunrgbd_frames import (
    camera_pitch_roll,
    object_box,
    room_corners,
    rotation_from_extrinsics,
    world_from_sun,
)

INTRINSICS_FILE = "intrinsics.txt"
IMAGE_FOLDER = "image"
EXTRINSICS_FOLDER = "extrinsics"
ANNOTATION_2D = Path("annotation2Dfinal") / "index.json"
ANNOTATION_3D = Path("annotation3Dfinal") / "index.json"
LAYOUT_3D = Path("annotation3Dlayout") / "index.json"
# The sensor's depth first: depth_bfx/ is the same with its holes filled in by a
# cross-bilateral filter, guesses rather than measurements.
DEPTH_FOLDERS = ("depth", "depth_bfx")
DECIMALS = 6


def is_image_folder(folder: Path) -> bool:
    """A SUN RGB-D image folder: intrinsics.txt beside image/ or annotation2Dfinal/."""
    return (folder / INTRINSICS_FILE).is_file() and (
        (folder / IMAGE_FOLDER).is_dir() or (folder / ANNOTATION_2D).parent.is_dir()
    )


def image_folders(root: Path) -> Iterator[Path]:
    """The image folders at or below `root`, in name order (not looking inside one)."""
    if is_image_folder(root):
        yield root
        return
    for top, dirs, _ in os.walk(root):
        dirs.sort()
        for name in list(dirs):
            if is_image_folder(Path(top) / name):
                dirs.remove(name)
                yield Path(top) / name


def is_sunrgbd(path: Path) -> bool:
    return path.is_dir() and next(image_folders(path), None) is not None


def read_sunrgbd(root: Path) -> Iterator[DatasetItem]:
    """One item per image folder at or below `root`, with a progress bar on stderr; a
    class_map.json in `root` maps the dataset's names for all of them."""
    from tqdm import tqdm

    try:
        map_file = root / CLASS_MAP_FILE
        class_map = parse_class_map(map_file.read_bytes()) if map_file.is_file() else None
    except InputError as exc:
        yield DatasetItem(name=str(root), error=str(exc))
        return
    for folder in tqdm(image_folders(root), desc="SUN RGB-D", unit="photo", file=sys.stderr):
        try:
            inputs = read_image_folder(folder, class_map)
        except InputError as exc:
            yield DatasetItem(name=str(folder), error=str(exc))
            continue
        yield DatasetItem(name=str(folder), inputs=inputs)


def read_image_folder(folder: Path, class_map: dict[str, str] | None = None) -> InputFiles:
    """The photo, K, objects and ground truth of one image folder."""
    photo = _photo(folder)
    K = read_intrinsics(folder / INTRINSICS_FILE)
    annotation = _annotation_2d(folder)
    labelled = _objects(annotation, photo, class_map) if annotation is not None else None
    notes = list(annotation.notes) if annotation is not None else []
    sun_from_cv = read_extrinsics(folder)
    truth = None
    if sun_from_cv is not None:
        measured = ground_truth(folder, photo, K, sun_from_cv, annotation, labelled or [])
        truth = measured.scene
        labelled = measured.labelled if labelled is not None else None  # None: no 2D file
        notes += measured.notes
    elif (folder / ANNOTATION_3D).is_file() or (folder / LAYOUT_3D).is_file():
        raise InputError(f"{EXTRINSICS_FOLDER}/ holds no .txt: the 3D annotations need the tilt")
    detections = [d for _, d in labelled] if labelled is not None else None
    depth = read_depth(folder, photo)
    return InputFiles(
        photo=photo, K=K, detections=detections, ground_truth=truth, depth=depth, notes=tuple(notes)
    )


def read_depth(folder: Path, photo: Photo) -> DepthMap | None:
    """The depth of `depth/` (else `depth_bfx/`): the PNG named as the photo, else the first
    by name; None when the folder has neither."""
    photo_stem = _image_files(folder)[0].stem
    for name in DEPTH_FOLDERS:
        files = sorted((folder / name).glob("*.png"))
        if not files:
            continue
        chosen = next((f for f in files if f.stem == photo_stem), files[0])
        return depth_from_png(
            chosen.read_bytes(),
            photo.width,
            photo.height,
            sunrgbd_bit_rotation=True,
            what=f"{name}/{chosen.name}",
        )
    return None


def _image_files(folder: Path) -> list[Path]:
    return sorted((folder / IMAGE_FOLDER).glob("*.jp*g")) + sorted(
        (folder / IMAGE_FOLDER).glob("*.png")
    )


def _photo(folder: Path) -> Photo:
    images = _image_files(folder)
    if not images:
        raise InputError(f"{IMAGE_FOLDER}/ holds no .jpg image")
    try:
        return load_photo(images[0].read_bytes())
    except InputError as exc:
        raise InputError(f"{IMAGE_FOLDER}/{images[0].name}: {exc}", exc.status) from exc


def _numbers(path: Path) -> list[float]:
    try:
        return [float(v) for v in path.read_text().split()]
    except ValueError as exc:
        raise InputError(f"{path.name} must hold numbers only: {exc}") from exc
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"{path.name} cannot be read: {exc}") from exc


def read_intrinsics(path: Path) -> FloatArray:
    """K from intrinsics.txt: 9 numbers, row by row."""
    values = _numbers(path)
    if len(values) != 9:
        raise InputError(
            f"{path.name} must hold 9 numbers (the 3x3 intrinsics), it holds {len(values)}"
        )
    rows = "\n".join(" ".join(repr(v) for v in values[i : i + 3]) for i in (0, 3, 6))
    try:
        return parse_intrinsics(rows)
    except InputError as exc:
        raise InputError(str(exc).replace("cam_K.txt", path.name)) from exc


def read_extrinsics(folder: Path) -> FloatArray | None:
    """E from the newest extrinsics file (the last by name: they are named by time)."""
    files = sorted((folder / EXTRINSICS_FOLDER).glob("*.txt"))
    if not files:
        return None
    try:
        return rotation_from_extrinsics(_numbers(files[-1]))
    except InputError as exc:
        raise InputError(f"{EXTRINSICS_FOLDER}/{files[-1].name}: {exc}") from exc


@dataclass(frozen=True)
class Annotation2D:
    """annotation2Dfinal: the name of each `objects[k]` (None for an unnamed one), and for
    each object with outlines, in order of first appearance, k and its polygons as flat
    [x, y, ...] lists."""

    objects: list[str | None]
    outlines: dict[int, list[list[Any]]]
    notes: list[str]  # the outlines left out (too few points to outline anything)


def sun_name(raw: Any) -> str:
    """A SUN RGB-D object name as a class name: the part before any ':' (the 3D tool's
    'name:label'), lower case, without the digits some names carry (chair2)."""
    if not isinstance(raw, str):
        return ""
    return " ".join(re.sub(r"[0-9]", "", raw.split(":")[0].lower()).replace("_", " ").split())


def _as_list(value: Any) -> list[Any]:
    """A coordinate list; MATLAB's JSON writer saves a one-element list as a bare number."""
    return value if isinstance(value, list) else [value]


def _annotation_2d(folder: Path) -> Annotation2D | None:
    path = folder / ANNOTATION_2D
    if not path.is_file():
        return None
    data = load_json(path)
    where = str(ANNOTATION_2D)
    objects = [
        sun_name(o.get("name")) or None if isinstance(o, dict) else None
        for o in _object_list(path, data)
    ]
    frames = data.get("frames")
    if not isinstance(frames, list) or not frames or not isinstance(frames[0], dict):
        raise InputError(f"{where}: 'frames' must be a list of frames")
    polygons = frames[0].get("polygon", [])
    if not isinstance(polygons, list):
        raise InputError(f"{where}: frames[0].polygon must be a list")
    outlines: dict[int, list[list[Any]]] = {}
    notes: list[str] = []
    for i, polygon in enumerate(polygons):
        if not isinstance(polygon, dict) or not {"x", "y", "object"} <= polygon.keys():
            raise InputError(f"{where}: polygon {i} must have 'x', 'y' and 'object'")
        k = polygon["object"]
        if not isinstance(k, int) or not 0 <= k < len(objects) or objects[k] is None:
            continue  # an outline of no named object: nothing to label it with
        xs, ys = _as_list(polygon["x"]), _as_list(polygon["y"])
        if len(xs) != len(ys):
            raise InputError(f"{where}: polygon {i} has {len(xs)} x and {len(ys)} y values")
        if len(xs) < 3:
            # SUN's annotators left such outlines (a click or two); the photo's others stand.
            notes.append(
                f"polygon {i} of object {k} ({objects[k]}) has {len(xs)} point(s): left out"
            )
            continue
        flat = [v for point in zip(xs, ys, strict=True) for v in point]
        outlines.setdefault(k, []).append(flat)
    return Annotation2D(objects, outlines, notes)


def _objects(
    annotation: Annotation2D, photo: Photo, class_map: dict[str, str] | None
) -> list[tuple[int, Detection]]:
    """Each outline as an object (its entry's index k, its detection), as the public readers
    of SUN RGB-D take them: an entry may outline several things of its kind (two bookshelves
    side by side), whose 3D boxes are then separate. Walls, floors and ceilings are the room,
    not objects: they are left out."""
    labelled = []
    for k, polygons in annotation.outlines.items():
        name = annotation.objects[k]
        assert name is not None  # outlines only hold named objects
        for polygon in polygons:
            where = f"{ANNOTATION_2D} object {k}"
            pixels = polygon_pixels(where, polygon, photo.width, photo.height)
            detection = labelled_detection(
                where, name, None, pixels, photo.width, photo.height, class_map
            )
            if detection.cls not in STRUCTURAL_CLASSES:
                labelled.append((k, detection))
    return labelled


@dataclass(frozen=True)
class MeasuredScene:
    scene: Scene
    # The outlines as objects, pieces of one object inside its 3D box joined (_join_pieces).
    labelled: list[tuple[int, Detection]]
    notes: list[str]


def ground_truth(
    folder: Path,
    photo: Photo,
    K: FloatArray,
    sun_from_cv: FloatArray,
    annotation: Annotation2D | None,
    labelled: list[tuple[int, Detection]],
) -> MeasuredScene:
    """The scene as SUN RGB-D measured it, in the world frame: the camera (K, pitch, roll,
    and its height when the room is annotated), the room cuboid, and the 2D objects (ids
    o0, o1, ... as the import gives them) with their 3D boxes where annotated."""
    to_world = world_from_sun(sun_from_cv)
    pitch, roll = camera_pitch_roll(sun_from_cv)
    pinhole = PinholeCamera(K, pitch, roll)
    layout, height = _layout(folder, to_world, pinhole)
    size = (photo.width, photo.height)
    boxes = _boxes_3d(folder, annotation, to_world, labelled, pinhole, size)
    notes: list[str] = []
    if annotation is not None:
        labelled, boxes, notes = _join_pieces(annotation, labelled, boxes, pinhole, size)
    objects = [
        _truth_object(f"o{i}", detection, boxes.get(i)) for i, (_, detection) in enumerate(labelled)
    ]
    camera = Camera(
        K=K.tolist(),
        K_source="given",
        pitch_deg=round(pitch, DECIMALS),
        roll_deg=round(roll, DECIMALS),
        height_m=round(height, DECIMALS) if height is not None and height > 0 else None,
        height_source="ground_truth" if height is not None and height > 0 else None,
    )
    scene = Scene(
        name=folder.name,
        image=ImageInfo(file=f"img{photo.suffix}", width=photo.width, height=photo.height),
        camera=camera,
        layout=layout,
        objects=objects,
    )
    return MeasuredScene(scene, labelled, notes)


Box = tuple[FloatArray, FloatArray, float]  # world centre, size (front, up, right), yaw


def _truth_object(object_id: str, detection: Detection, box: Box | None) -> SceneObject:
    mask = detection.mask.model_copy(update={"source": "ground_truth"}) if detection.mask else None
    box_3d = corners = None
    if box is not None:
        centre, size, yaw = box
        box_3d = Box3D(
            center=centre.round(DECIMALS).tolist(),
            size=size.round(DECIMALS).tolist(),
            yaw_deg=round(yaw, DECIMALS),
        )
        corners = box_corners(centre, size, yaw).round(DECIMALS).tolist()
    return SceneObject(
        id=object_id,
        cls=detection.cls,
        source_class=detection.source_class,
        bbox=list(detection.bbox),
        mask=mask,
        box_3d=box_3d,
        corners_3d=corners,
        source="given",
    )


def _floor_polygon(where: str, polygons: Any) -> tuple[list[float], list[float], float, float]:
    """X, Z, Ymin and Ymax of an annotation's first polygon (MATLAB's JSON writer saves a
    list of one as the element itself)."""
    polygon = polygons[0] if isinstance(polygons, list) and polygons else polygons
    if not isinstance(polygon, dict) or not {"X", "Z", "Ymin", "Ymax"} <= polygon.keys():
        raise InputError(f"{where}: a polygon must have 'X', 'Z', 'Ymin' and 'Ymax'")
    xs, zs = _as_list(polygon["X"]), _as_list(polygon["Z"])
    values = [*xs, *zs, polygon["Ymin"], polygon["Ymax"]]
    if not all(isinstance(v, int | float) and not isinstance(v, bool) for v in values):
        raise InputError(f"{where}: X, Z, Ymin and Ymax must be numbers")
    if len(xs) != len(zs):
        raise InputError(f"{where}: the polygon has {len(xs)} X and {len(zs)} Z values")
    if not np.all(np.isfinite(values)):
        raise InputError(f"{where}: the polygon holds a value that is not finite")
    return xs, zs, float(polygon["Ymin"]), float(polygon["Ymax"])


def _object_list(path: Path, data: Any) -> list[Any]:
    """The `objects` list of an annotation file (entries may be null)."""
    objects = data.get("objects") if isinstance(data, dict) else None
    if not isinstance(objects, list):
        raise InputError(f"{path.parent.name}/{path.name}: 'objects' must be a list")
    return objects


# A 3D box and a 2D object of its name are one object when the box's projection holds most of
# the object's 2D box (the visible part of a partly hidden object lies inside it); of several
# such objects, a box takes the one its projection overlaps most (IoU), as Total3D's
# preprocessing pairs SUN's boxes by class and overlap.
PAIRING_MIN_COVER = 0.5


def _boxes_3d(
    folder: Path,
    annotation: Annotation2D | None,
    to_world: FloatArray,
    labelled: list[tuple[int, Detection]],
    camera: PinholeCamera,
    size: tuple[int, int],
) -> dict[int, Box]:
    """The world boxes of annotation3Dfinal by position in `labelled`. A box goes to an
    outline of the 2D entry of its own index when the name is the same and the box fits it
    (the two files list the same objects); otherwise to the outline of its name it fits
    best (see PAIRING_MIN_COVER), else it is left out."""
    path = folder / ANNOTATION_3D
    if not path.is_file() or annotation is None:
        return {}
    bboxes = [list(d.bbox) for _, d in labelled]
    names = [annotation.objects[k] for k, _ in labelled]
    fitting: list[tuple[bool, float, int, int]] = []  # (own index, IoU, box, outline)
    found: list[Box] = []
    for k, item in enumerate(_object_list(path, load_json(path))):
        if not isinstance(item, dict) or not item.get("polygon"):
            continue  # an object with no 3D box
        name = sun_name(item.get("name"))
        own = [i for i, (entry, _) in enumerate(labelled) if entry == k and names[i] == name]
        where = f"{ANNOTATION_3D} object {k}"
        try:
            xs, zs, y_min, y_max = _floor_polygon(where, item["polygon"])
            box = object_box(xs, zs, y_min, y_max, to_world)
        except InputError as exc:
            if own:
                raise InputError(f"{where}: {exc}") from exc
            continue  # a broken box no object claims is not the photo's error
        bounds = _projected_bounds(box, camera, size)
        if bounds is None:
            continue  # behind the camera: it is no object of the photo
        found.append(box)
        for i, bbox in enumerate(bboxes):
            if names[i] == name and _cover(bounds, bbox) >= PAIRING_MIN_COVER:
                fitting.append((i in own, iou_2d(bounds, bbox), len(found) - 1, i))
    boxes: dict[int, Box] = {}
    placed: set[int] = set()
    for _, _, b, i in sorted(fitting, reverse=True):  # own index first, then the best fits
        if b not in placed and i not in boxes:
            boxes[i] = found[b]
            placed.add(b)
    return boxes


# An outline no 3D box claimed, this much inside the projection of the 3D box of another
# outline of its entry, is a piece of that object (drawn apart where something in front of
# it cuts it in two), not another thing of its kind.
PIECE_MIN_COVER = 0.8


def _join_pieces(
    annotation: Annotation2D,
    labelled: list[tuple[int, Detection]],
    boxes: dict[int, Box],
    camera: PinholeCamera,
    size: tuple[int, int],
) -> tuple[list[tuple[int, Detection]], dict[int, Box], list[str]]:
    """The objects with each piece joined to the outline whose 3D box holds it (mask and 2D
    box made one), the 3D boxes by the new positions, and a note per joined object. Without
    a 3D box nothing tells pieces from several things, so such outlines stay objects."""
    bounds = {i: _projected_bounds(box, camera, size) for i, box in boxes.items()}
    into: dict[int, int] = {}  # a piece's position -> the position of the outline it joins
    for i, (entry, detection) in enumerate(labelled):
        if i in boxes:
            continue
        covers = [
            (_cover(b, list(detection.bbox)), j)
            for j, b in bounds.items()
            if b is not None and labelled[j][0] == entry
        ]
        best = max(covers, default=(0.0, -1))
        if best[0] >= PIECE_MIN_COVER:
            into[i] = best[1]
    if not into:
        return labelled, boxes, []
    width, height = size
    joined: list[tuple[int, Detection]] = []
    joined_boxes: dict[int, Box] = {}
    notes = []
    for j, (entry, detection) in enumerate(labelled):
        if j in into:
            continue
        pieces = [labelled[i][1] for i, target in into.items() if target == j]
        if pieces:
            detection = _joined(detection, pieces, width, height)
            name = annotation.objects[entry]
            notes.append(
                f"{ANNOTATION_2D} object {entry} ({name}): {len(pieces) + 1} outlines inside "
                "its one 3D box joined as one object"
            )
        if j in boxes:
            joined_boxes[len(joined)] = boxes[j]
        joined.append((entry, detection))
    return joined, joined_boxes, notes


def _joined(detection: Detection, pieces: list[Detection], width: int, height: int) -> Detection:
    pixels = np.zeros((height, width), dtype=bool)
    for part in (detection, *pieces):
        if part.mask is not None:
            pixels |= decode_mask(part.mask, width, height)
    mask = encode_mask(pixels, "given")
    if mask is None:
        return detection
    (x0, y0), (w, h) = mask.origin, mask.size
    return replace(detection, bbox=(float(x0), float(y0), float(x0 + w), float(y0 + h)), mask=mask)


def _cover(bounds: list[float], bbox: list[float]) -> float:
    """How much of the 2D box `bbox` lies inside `bounds` (both [x1, y1, x2, y2])."""
    w = min(bounds[2], bbox[2]) - max(bounds[0], bbox[0])
    h = min(bounds[3], bbox[3]) - max(bounds[1], bbox[1])
    area = (bbox[2] - bbox[0]) * (bbox[3] - bbox[1])
    return max(w, 0.0) * max(h, 0.0) / area if area > 0 else 0.0


def _projected_bounds(box: Box, camera: PinholeCamera, size: tuple[int, int]) -> list[float] | None:
    """The 2D bounds of a world box's corners in front of the camera, clipped to the photo."""
    pixels = camera.project(box_corners(*box))
    pixels = pixels[np.isfinite(pixels).all(axis=1)]
    if not len(pixels):
        return None
    width, height = size
    low = np.clip(pixels.min(axis=0), 0, [width, height])
    high = np.clip(pixels.max(axis=0), 0, [width, height])
    return [float(low[0]), float(low[1]), float(high[0]), float(high[1])]


def _layout(
    folder: Path, to_world: FloatArray, camera: PinholeCamera
) -> tuple[Layout, float | None]:
    """The room of annotation3Dlayout (its first object with a polygon) as a cuboid, its
    corners in the image too (a room that is not a 4-cornered box is left out with a note),
    and how far below the camera its floor is (its Ymax, SUN's y pointing down), whatever
    its shape."""
    path = folder / LAYOUT_3D
    if not path.is_file():
        return Layout(), None
    for item in _object_list(path, load_json(path)):
        if not isinstance(item, dict) or not item.get("polygon"):
            continue
        xs, zs, y_min, y_max = _floor_polygon(str(LAYOUT_3D), item["polygon"])
        try:
            corners = room_corners(xs, zs, y_min, y_max, to_world)
        except InputError as exc:
            return Layout(note=f"{LAYOUT_3D}: {exc}; no layout kept"), y_max
        image = [
            None if np.isnan(p).any() else [round(float(p[0]), 2), round(float(p[1]), 2)]
            for p in camera.project(corners)
        ]
        corners_3d = corners.round(DECIMALS).tolist()
        return Layout(corners_2d=image, corners_3d=corners_3d, source="ground_truth"), y_max
    return Layout(note=f"{LAYOUT_3D} holds no room polygon"), None

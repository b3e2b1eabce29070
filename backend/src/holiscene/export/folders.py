"""Stored scenes written to a folder by `holiscene export`, one function per format, and the
table of formats the command offers (EXPORT_FORMATS: a new format is one writer and one row)."""

from __future__ import annotations

import io
import json
import shutil
import tempfile
import zipfile
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from ..core.atomic_files import write_atomic
from .archive import ArchivedScene, file_stem, glb_staleness, scene_json
from .coco import coco_dataset
from .input_folder import given_intrinsics, write_labels
from .nyu_supports import write_nyu_supports
from .relation_training import write_relation_training
from .total3d import write_total3d
from .total3d_training import write_total3d_training

COCO_FILE = "annotations.json"
COCO_IMAGES = "images"


def unique_stems(chosen: list[ArchivedScene]) -> list[str]:
    """A file or folder name per scene: its name, or <name>-<id> when an earlier scene took it
    (an import names the scene after its file, so the name is what people know it by)."""
    taken: set[str] = set()
    stems = []
    for item in chosen:
        stem = file_stem(item.scene.name, item.scene_id)
        if stem in taken:
            stem = f"{stem}-{item.scene_id}"
        taken.add(stem)
        stems.append(stem)
    return stems


def write_coco(chosen: list[ArchivedScene], out: Path) -> None:
    """DIR/images/<scene name><suffix> for each scene and DIR/annotations.json over them."""
    images = out / COCO_IMAGES
    images.mkdir(exist_ok=True)
    entries = []
    for item, stem in zip(chosen, unique_stems(chosen), strict=True):
        file_name = stem + item.photo.suffix
        shutil.copyfile(item.photo, images / file_name)
        entries.append((item.scene, file_name))
    description = "HoliScene scenes " + ", ".join(
        f"{item.scene_id} (revision {item.revision})" for item in chosen
    )
    document = coco_dataset(entries, description)
    write_atomic(out / COCO_FILE, (json.dumps(document) + "\n").encode())


def write_scene_folders(chosen: list[ArchivedScene], out: Path) -> str | None:
    """DIR/<scene name>/: scene.json, the photo, and scene.glb when the scene has one; and
    detections.json, supports.json, cam_K.txt (for intrinsics given with the photo), gt.json
    (for a scene imported with ground truth) and depth.png, so the folder is an input folder
    that imports back to the same objects, supports, room layout and ground truth. The note
    names the folders whose scene.glb is older than their scene.json."""
    stale: list[str] = []
    for item, stem in zip(chosen, unique_stems(chosen), strict=True):
        folder = out / stem
        folder.mkdir(exist_ok=True)
        write_atomic(folder / "scene.json", scene_json(item.scene))
        write_labels(item, folder, K=given_intrinsics(item.scene))
        shutil.copyfile(item.photo, folder / item.scene.image.file)
        if item.glb is not None:
            shutil.copyfile(item.glb, folder / "scene.glb")
        if (note := glb_staleness(item)) is not None:
            stale.append(f"{stem}: {note}")
    return "; ".join(stale) if stale else None


@dataclass(frozen=True)
class ExportFormat:
    write: Callable[[list[ArchivedScene], Path], str | None]  # returns a note for the user
    description: str  # what DIR holds afterwards, for the command's help


EXPORT_FORMATS: dict[str, ExportFormat] = {
    "coco": ExportFormat(
        write_coco,
        "DIR/annotations.json (an image per scene, NYU-40 categories, masks as RLE, each "
        "object's support in holiscene_support) and DIR/images/",
    ),
    "scene": ExportFormat(
        write_scene_folders,
        "DIR/<scene>/scene.json, scene.glb when the scene has one, and the photo, with "
        "detections.json, supports.json and cam_K.txt: an input folder",
    ),
    "total3d": ExportFormat(
        write_total3d,
        "DIR/<scene>/ with Total3DUnderstanding's demo input (img.jpg, cam_K.txt, "
        "detections.json with masks) and results (r_ex.mat, layout.mat, bdb_3d.mat, one "
        "<index>_<class id>.obj mesh per placed object), and "
        "supports.json",
    ),
    "total3d-training": ExportFormat(
        write_total3d_training,
        "DIR laid out as Total3DUnderstanding's data/sunrgbd/ for its training code: a pickle "
        "per scene with camera, layout and objects in its bins (sunrgbd_train_test_data/), "
        "splits/train.json and test.json, the averages in preprocessed/, and "
        "holiscene-index.json (which scene each sample is)",
    ),
    "relation-training": ExportFormat(
        write_relation_training,
        "DIR/pairs.npz (the Relation Network's inputs and the support pairs people "
        "labelled), DIR/labels.jsonl (the pairs by object id) and DIR/README-format.json",
    ),
    "nyu-supports": ExportFormat(
        write_nyu_supports,
        "DIR/nyu_depth_v2_labeled.mat (images, labels, instances, names; the scenes must "
        "share one size) and DIR/support_labels.mat, as NYU Depth v2 has them",
    ),
}

# What a zip of an export stores as it is (compressed already).
STORED_SUFFIXES = frozenset({".jpg", ".jpeg", ".png", ".glb", ".npz", ".mat"})
EXPORT_NOTE_FILE = "export-note.txt"


def exported_zip(chosen: list[ArchivedScene], format_name: str) -> bytes:
    """What `holiscene export --format` writes for `chosen`, as one zip (the format's note,
    when it has one, in export-note.txt). ExportRefusedError when the format refuses them."""
    with tempfile.TemporaryDirectory(prefix="holiscene-export-") as scratch:
        out = Path(scratch)
        note = EXPORT_FORMATS[format_name].write(chosen, out)
        buffer = io.BytesIO()
        with zipfile.ZipFile(buffer, "w", compression=zipfile.ZIP_DEFLATED) as archive:
            for path in sorted(p for p in out.rglob("*") if p.is_file()):
                stored = path.suffix.lower() in STORED_SUFFIXES
                archive.write(
                    path,
                    path.relative_to(out).as_posix(),
                    zipfile.ZIP_STORED if stored else zipfile.ZIP_DEFLATED,
                )
            if note:
                archive.writestr(EXPORT_NOTE_FILE, note + "\n")
    return buffer.getvalue()

"""A stored scene's labels as the files of an input folder (docs/importing.md), so that
`holiscene import` reads an exported folder (or the app's "Download selected" zip) back into
the same objects, supports and ground truth: detections.json (each object's box, class, name
as imported and mask, in the scene's order), supports.json (over those boxes by position),
cam_K.txt, gt.json and depth.png."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from holiscene_schema import STRUCTURAL_SUPPORTERS, Scene, SupportRelation

from ..core.atomic_files import write_atomic
from ..inputs.depth import DEPTH_FILE

if TYPE_CHECKING:  # archive.py builds its zip from label_files
    from .archive import ArchivedScene


def detections_items(scene: Scene, class_name: Callable[[str], str] = str) -> list[dict[str, Any]]:
    """detections.json's items: `class_name` spells an NYU-40 class as the reader wants it."""
    items = []
    for obj in scene.objects:
        item: dict[str, Any] = {"bbox": list(obj.bbox), "class": class_name(obj.cls)}
        if obj.source_class is not None:
            item["source_class"] = obj.source_class
        if obj.mask is not None:
            item["mask"] = obj.mask.model_dump(mode="json", exclude={"source"})
        items.append(item)
    return items


def supports_items(scene: Scene) -> list[dict[str, Any]]:
    """supports.json's items: child and parent as positions in detections.json (a parent may
    be floor, wall or ceiling), with the author of a person's label, or source "auto" and the
    confidence of the pipeline's guess."""
    position = {obj.id: index for index, obj in enumerate(scene.objects)}
    items = []
    for support in scene.supports:
        parent = support.parent
        items.append(
            {
                "child": position[support.child],
                "parent": parent if parent in STRUCTURAL_SUPPORTERS else position[parent],
                "type": support.type,
                **support_provenance(support),
            }
        )
    return items


def support_provenance(support: SupportRelation) -> dict[str, Any]:
    """Who set a support, as the importers read it back: the author of a person's label, or
    source "auto" and the confidence of the pipeline's guess (a guess imports as a guess, not
    as a person's label)."""
    if support.source == "auto":
        if support.confidence is None:
            return {"source": "auto"}
        return {"source": "auto", "confidence": support.confidence}
    return {"author": support.author} if support.author else {}


def intrinsics_text(K: np.ndarray | list[list[float]]) -> str:
    """cam_K.txt: the 3x3 matrix, one row per line."""
    return "\n".join(" ".join(f"{v:.6f}" for v in row) for row in np.asarray(K)) + "\n"


def given_intrinsics(scene: Scene) -> list[list[float]] | None:
    """The scene's K when it came with the photo (cam_K.txt); an assumed one is not written,
    so an import assumes it again rather than taking it as measured."""
    camera = scene.camera
    return camera.K if camera is not None and camera.K_source == "given" else None


def label_files(
    item: ArchivedScene, class_name: Callable[[str], str] = str, K: Any = None
) -> dict[str, bytes]:
    """The input folder's files besides the photo, by name: detections.json and supports.json
    of the scene, cam_K.txt when `K` is given, the ground truth (gt.json) when the scene was
    imported with one, and its depth (depth.png) when it has one."""
    files = scene_label_files(item.scene, class_name, K)
    if item.ground_truth is not None:
        files["gt.json"] = item.ground_truth.read_bytes()
    if item.depth is not None:
        files[DEPTH_FILE] = item.depth.read_bytes()
    return files


def scene_label_files(
    scene: Scene, class_name: Callable[[str], str] = str, K: Any = None
) -> dict[str, bytes]:
    """The label files written from the scene itself: detections.json, supports.json, and
    cam_K.txt when `K` is given. An import reads these, not scene.json, so an upload of a
    download counts as unchanged only while they are as written here."""
    files = {
        "detections.json": (json.dumps(detections_items(scene, class_name)) + "\n").encode(),
        "supports.json": (json.dumps(supports_items(scene)) + "\n").encode(),
    }
    if K is not None:
        files["cam_K.txt"] = intrinsics_text(K).encode()
    return files


def write_labels(
    item: ArchivedScene, folder: Path, class_name: Callable[[str], str] = str, K: Any = None
) -> None:
    """The files of label_files in `folder`."""
    for name, data in label_files(item, class_name, K).items():
        write_atomic(folder / name, data)

"""Several scenes as one zip: a folder per scene with what a tool outside the workbench
needs (scene.json as `holiscene infer` writes it, coco.json, the photo, scene.glb), which is
also an input folder (detections.json, supports.json, ...: export/input_folder.py), so the
zip imports back (`holiscene import`, POST /api/imports) to the same labels."""

from __future__ import annotations

import io
import json
import re
import zipfile
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from holiscene_schema import Scene

from ..inputs.datasets import ARCHIVE_INDEX  # the zip's list of folders, not LabelMe's
from ..inputs.depth import DEPTH_FILE
from .coco import coco_instances
from .input_folder import given_intrinsics, label_files

if TYPE_CHECKING:
    from ..store.scenes import SceneStore


def file_stem(name: str, fallback: str) -> str:
    """A scene name made safe as a file or folder name on every system."""
    stem = re.sub(r"[^A-Za-z0-9._-]+", "_", name).strip("._")[:60]
    return stem or fallback


def scene_json(scene: Scene) -> bytes:
    """The scene file as `holiscene infer` writes it."""
    return (json.dumps(scene.model_dump(mode="json"), indent=1) + "\n").encode()


def coco_json(scene: Scene, description: str) -> bytes:
    return (json.dumps(coco_instances(scene, description)) + "\n").encode()


@dataclass(frozen=True)
class ArchivedScene:
    scene_id: str
    revision: int
    scene: Scene
    photo: Path
    glb: Path | None
    ground_truth: Path | None = None  # gt.json, for a scene imported with ground truth
    depth: Path | None = None  # depth.png, for a scene with depth
    state: str | None = None  # the workflow state when downloaded (index.json says it)
    # Where the held-out split puts it (SceneStore.split_keys); None: its own id.
    split_key: str | None = None
    # The revision whose pipeline or placement run made the GLB (edits after it are not in it).
    glb_revision: int | None = None


def archived_scene(
    scenes: SceneStore, scene_id: str, split_key: str | None = None
) -> ArchivedScene:
    """A stored scene's current revision and its files (SceneNotFoundError for an unknown id)."""
    document = scenes.document(scene_id)
    made = scenes.glb_file(scene_id)
    glb_revision, glb = made if made is not None and made[1].is_file() else (None, None)
    truth = scenes.files.ground_truth_path(scene_id)
    depth = scenes.files.folder(scene_id) / DEPTH_FILE
    return ArchivedScene(
        scene_id=scene_id,
        revision=document.revision,
        scene=document.scene,
        photo=scenes.image_path(scene_id),
        glb=glb,
        glb_revision=glb_revision,
        ground_truth=truth if truth.is_file() else None,
        depth=depth if document.scene.depth is not None and depth.is_file() else None,
        state=scenes.summary(scene_id).state,
        split_key=split_key,
    )


def archived_scenes(scenes: SceneStore, scene_ids: list[str]) -> list[ArchivedScene]:
    """The scenes with their held-out split keys, read for all of them at once (the training
    exports hold out what a retrain would)."""
    keys = scenes.split_keys(scene_ids)
    return [archived_scene(scenes, i, keys.get(i)) for i in scene_ids]


def split_keys_of(items: Sequence[ArchivedScene]) -> dict[str, str]:
    """The held-out split keys the items carry, for heldout_split."""
    return {item.scene_id: item.split_key for item in items if item.split_key is not None}


def glb_staleness(item: ArchivedScene) -> str | None:
    """What the item's scene.glb lacks, when it was made before the revision exported."""
    made = item.glb_revision
    if item.glb is None or made is None or made >= item.revision:
        return None
    later = (
        f"revision {item.revision}"
        if made + 1 == item.revision
        else (f"revisions {made + 1}-{item.revision}")
    )
    return f"scene.glb was made at revision {made}: the edits of {later} are not in it"


def coco_description(scene_id: str, revision: int, scene: Scene) -> str:
    return f"HoliScene scene {scene.name} ({scene_id}, revision {revision})"


def scenes_zip(scenes: list[ArchivedScene]) -> bytes:
    """The zip: `<name>-<id>/scene.json`, `coco.json`, the photo, `scene.glb` when the
    scene has one, and the input folder's label files; `index.json` lists the folders with
    their scene id, revision, workflow state and the revision that made their scene.glb (with
    a note when edits came after it)."""
    buffer = io.BytesIO()
    index: list[dict[str, Any]] = []
    with zipfile.ZipFile(buffer, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        for item in scenes:
            folder = f"{file_stem(item.scene.name, item.scene_id)}-{item.scene_id}"
            description = coco_description(item.scene_id, item.revision, item.scene)
            archive.writestr(f"{folder}/scene.json", scene_json(item.scene))
            archive.writestr(f"{folder}/coco.json", coco_json(item.scene, description))
            for name, data in label_files(item, K=given_intrinsics(item.scene)).items():
                archive.writestr(f"{folder}/{name}", data)
            # Photos and GLBs are compressed already.
            archive.write(item.photo, f"{folder}/{item.scene.image.file}", zipfile.ZIP_STORED)
            if item.glb is not None:
                archive.write(item.glb, f"{folder}/scene.glb", zipfile.ZIP_STORED)
            entry: dict[str, Any] = {
                "folder": folder,
                "scene_id": item.scene_id,
                "revision": item.revision,
                "has_glb": item.glb is not None,
                "glb_revision": item.glb_revision,
                "state": item.state,
            }
            if (stale := glb_staleness(item)) is not None:
                entry["glb_note"] = stale
            index.append(entry)
        archive.writestr(ARCHIVE_INDEX, json.dumps({"scenes": index}, indent=1) + "\n")
    return buffer.getvalue()

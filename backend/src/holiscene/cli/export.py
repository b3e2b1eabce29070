"""`holiscene export`: stored scenes out of the store, as one COCO dataset (annotations.json
and images/) or as a folder per scene (scene.json, scene.glb, the photo)."""

from __future__ import annotations

import argparse
import json
import shutil
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING

from .common import CliError, settings_from, write_atomic

if TYPE_CHECKING:
    from ..core.settings import Settings
    from ..export.archive import ArchivedScene
    from ..store.scenes import SceneStore

FORMATS = ("coco", "scene")
COCO_FILE = "annotations.json"
COCO_IMAGES = "images"


def add_export_command(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    export = sub.add_parser(
        "export",
        help="write stored scenes as a COCO dataset or as scene folders",
        description="coco: DIR/annotations.json (an image per scene, NYU-40 categories, masks "
        "as RLE, each object's support in holiscene_support) and DIR/images/; scene: "
        "DIR/<scene>/scene.json, scene.glb when the scene has one, and the photo.",
    )
    export.add_argument("--format", choices=FORMATS, required=True)
    export.add_argument("-o", "--out", type=Path, required=True, metavar="DIR")
    export.add_argument(
        "--scene", dest="scene_ids", action="append", metavar="ID", help="(repeat; default: all)"
    )
    export.add_argument("--force", action="store_true", help="write into a non-empty DIR")
    export.add_argument("--data-dir", type=Path)
    export.add_argument("--database-url")
    export.set_defaults(handler=_export)


def _export(args: argparse.Namespace) -> int:
    out: Path = args.out
    if out.exists() and (not out.is_dir() or any(out.iterdir())) and not args.force:
        raise CliError(f"{out} is not an empty folder; use --force to write into it")
    # Everything is read (and every id checked) before anything is written.
    with scene_store(settings_from(args)) as scenes:
        chosen = _chosen_scenes(scenes, args.scene_ids)
    out.mkdir(parents=True, exist_ok=True)
    if args.format == "coco":
        write_coco(chosen, out)
    else:
        write_scene_folders(chosen, out)
    print(f"exported {len(chosen)} scene(s) as {args.format} to {out}")
    return 0


@contextmanager
def scene_store(settings: Settings) -> Iterator[SceneStore]:
    """The stored scenes, without starting the workbench (no models, no jobs)."""
    from ..core.db import make_engine, migrate
    from ..store.files import SceneFiles
    from ..store.scenes import SceneStore

    if not settings.data_dir.is_dir():
        raise CliError(f"{settings.data_dir} holds no scenes (no such folder)")
    engine = make_engine(settings.resolved_database_url)
    try:
        migrate(engine)
        yield SceneStore(engine, SceneFiles(settings.data_dir))
    finally:
        engine.dispose()


def _chosen_scenes(scenes: SceneStore, scene_ids: list[str] | None) -> list[ArchivedScene]:
    from ..export.archive import archived_scene
    from ..store.scenes import SceneNotFoundError

    ids = scene_ids or [s.id for s in scenes.list_summaries()]
    if not ids:
        raise CliError("the store holds no scenes")
    chosen = []
    for scene_id in dict.fromkeys(ids):  # each once, in the order given
        try:
            chosen.append(archived_scene(scenes, scene_id))
        except SceneNotFoundError as exc:
            raise CliError(f"no scene {scene_id!r} in the store") from exc
    return chosen


def write_coco(chosen: list[ArchivedScene], out: Path) -> None:
    """DIR/images/<scene name><suffix> (<name>-<id> when two scenes share a name) for each
    scene and DIR/annotations.json over them."""
    from ..export.archive import file_stem
    from ..export.coco import coco_dataset

    images = out / COCO_IMAGES
    images.mkdir(exist_ok=True)
    entries = []
    taken: set[str] = set()
    for item in chosen:
        # The scene's name (an import names the scene after the file again), unless taken.
        stem = file_stem(item.scene.name, item.scene_id)
        file_name = stem + item.photo.suffix
        if file_name in taken:
            file_name = f"{stem}-{item.scene_id}{item.photo.suffix}"
        taken.add(file_name)
        shutil.copyfile(item.photo, images / file_name)
        entries.append((item.scene, file_name))
    description = "HoliScene scenes " + ", ".join(
        f"{item.scene_id} (revision {item.revision})" for item in chosen
    )
    document = coco_dataset(entries, description)
    write_atomic(out / COCO_FILE, (json.dumps(document) + "\n").encode())


def write_scene_folders(chosen: list[ArchivedScene], out: Path) -> None:
    """DIR/<scene name>/ (or <name>-<id> when two scenes share a name): scene.json, the
    photo, and scene.glb when the scene has one."""
    from ..export.archive import file_stem, scene_json

    taken: set[str] = set()
    for item in chosen:
        folder_name = file_stem(item.scene.name, item.scene_id)
        if folder_name in taken:
            folder_name = f"{folder_name}-{item.scene_id}"
        taken.add(folder_name)
        folder = out / folder_name
        folder.mkdir(exist_ok=True)
        write_atomic(folder / "scene.json", scene_json(item.scene))
        shutil.copyfile(item.photo, folder / item.scene.image.file)
        if item.glb is not None:
            shutil.copyfile(item.glb, folder / "scene.glb")

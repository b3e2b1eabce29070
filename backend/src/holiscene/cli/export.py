"""`holiscene export`: stored scenes out of the store in one of the formats of
export.folders.EXPORT_FORMATS (a COCO dataset, a folder per scene, ...)."""

from __future__ import annotations

import argparse
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, get_args

from holiscene_schema import SceneState

from ..export.errors import ExportRefusedError
from ..export.folders import EXPORT_FORMATS
from .common import CliError, settings_from

if TYPE_CHECKING:
    from ..core.settings import Settings
    from ..export.archive import ArchivedScene
    from ..store.scenes import SceneStore


def add_export_command(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    export = sub.add_parser(
        "export",
        help="write stored scenes as a COCO dataset or as scene folders",
        description="; ".join(f"{name}: {f.description}" for name, f in EXPORT_FORMATS.items()),
    )
    export.add_argument("--format", choices=list(EXPORT_FORMATS), required=True)
    export.add_argument("-o", "--out", type=Path, required=True, metavar="DIR")
    export.add_argument(
        "--scene", dest="scene_ids", action="append", metavar="ID", help="(repeat; default: all)"
    )
    export.add_argument(
        "--state",
        choices=list(get_args(SceneState)),
        help="only the scenes in this workflow state (e.g. accepted: the reviewed labels)",
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
        chosen = _chosen_scenes(scenes, args.scene_ids, args.state)
    out.mkdir(parents=True, exist_ok=True)
    try:
        note = EXPORT_FORMATS[args.format].write(chosen, out)
    except ExportRefusedError as exc:
        raise CliError(str(exc)) from exc
    print(f"exported {len(chosen)} scene(s) as {args.format} to {out}")
    if note:
        print(note)
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


def _chosen_scenes(
    scenes: SceneStore, scene_ids: list[str] | None, state: SceneState | None = None
) -> list[ArchivedScene]:
    """The scenes asked for (each once, in the order given; default: all), only those in
    `state` when one is given."""
    from ..export.archive import archived_scenes

    state_of = {s.id: s.state for s in scenes.list_summaries(archived=None)}
    ids = list(dict.fromkeys(scene_ids)) if scene_ids else list(state_of)
    unknown = [i for i in ids if i not in state_of]
    if unknown:
        raise CliError(f"no scene {unknown[0]!r} in the store")
    if state is not None:
        ids = [i for i in ids if state_of[i] == state]
        if not ids:
            raise CliError(f"no scene{' of those given' if scene_ids else ''} is {state}")
    if not ids:
        raise CliError("the store holds no scenes")
    return archived_scenes(scenes, ids)

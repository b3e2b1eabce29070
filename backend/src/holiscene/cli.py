"""`holiscene`: run the pipeline on a folder, serve the workbench, load demo scenes."""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
from collections.abc import Sequence
from pathlib import Path

from .core.settings import REPO_ROOT, Settings

DEMO_PHOTOS = REPO_ROOT.parent / "shared" / "data" / "real"
DEMO_FOLDERS = ("t3d-5", "im3d-6", "mm3d-4", "im3d-3")


class CliError(Exception):
    """A message for the user; the command exits with status 2."""


def main(argv: Sequence[str] | None = None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)
    try:
        result: int = args.handler(args)
        return result
    except CliError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="holiscene", description=__doc__)
    sub = parser.add_subparsers(required=True, metavar="COMMAND")

    infer = sub.add_parser("infer", help="run the pipeline on an input folder")
    infer.add_argument(
        "input_dir", type=Path, help="folder with img.jpg|img.png [cam_K.txt] [detections.json]"
    )
    infer.add_argument(
        "-o", "--out", type=Path, required=True, help="folder for scene.json and scene.glb"
    )
    infer.add_argument("--stages", help="comma-separated stage names (default: the full pipeline)")
    infer.set_defaults(handler=_infer)

    serve = sub.add_parser("serve", help="start the workbench server")
    serve.add_argument("--host", help="address to bind (default 127.0.0.1)")
    serve.add_argument("--port", type=int, help="port (default 8000)")
    serve.add_argument("--data-dir", type=Path, help="data directory (default var/data)")
    serve.add_argument("--database-url", help="SQLAlchemy URL (default: SQLite in the data dir)")
    serve.add_argument(
        "--allow-remote",
        action="store_true",
        help="bind beyond loopback although the server has no user accounts yet",
    )
    serve.set_defaults(handler=_serve)

    demo = sub.add_parser("demo", help="load demo scenes into an empty database")
    demo.add_argument("--data-dir", type=Path)
    demo.add_argument("--database-url")
    demo.set_defaults(handler=_demo)

    imp = sub.add_parser("import", help="import input folders as scenes and run the pipeline")
    imp.add_argument("folders", type=Path, nargs="+")
    imp.add_argument("--data-dir", type=Path)
    imp.add_argument("--database-url")
    imp.set_defaults(handler=_import)
    return parser


def _settings(args: argparse.Namespace) -> Settings:
    overrides = {
        key: value
        for key, value in {
            "data_dir": getattr(args, "data_dir", None),
            "database_url": getattr(args, "database_url", None),
            "host": getattr(args, "host", None),
            "port": getattr(args, "port", None),
        }.items()
        if value is not None
    }
    return Settings(**overrides)


def _infer(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from .inference import infer_scene
    from .inputs import InputError, read_input_folder
    from .pipeline import DEFAULT_STAGES, PipelineBuildError

    stages = [s.strip() for s in args.stages.split(",")] if args.stages else list(DEFAULT_STAGES)
    try:
        inputs = read_input_folder(args.input_dir)
        with tqdm(total=len(stages), desc="pipeline", unit="stage", file=sys.stderr) as bar:

            def progress(stage: str, _fraction: float) -> None:
                bar.set_postfix_str(stage)
                if stage != stages[0]:
                    bar.update(1)

            result = infer_scene(
                inputs,
                name=args.input_dir.resolve().name,
                image_file=f"img{inputs.photo.suffix}",
                stages=stages,
                progress=progress,
            )
    except (InputError, PipelineBuildError) as exc:
        raise CliError(str(exc)) from exc
    args.out.mkdir(parents=True, exist_ok=True)
    scene_json = json.dumps(result.scene.model_dump(mode="json"), indent=1) + "\n"
    _write_atomic(args.out / "scene.json", scene_json.encode())
    if result.glb is not None:
        _write_atomic(args.out / "scene.glb", result.glb)
    for run in result.scene.stages:
        note = f"  ({run.note})" if run.note else ""
        print(f"{run.name:28s} {run.seconds:7.3f} s{note}", file=sys.stderr)
    print(args.out / "scene.json")
    return 0


def _write_atomic(path: Path, data: bytes) -> None:
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.")
    with os.fdopen(fd, "wb") as f:
        f.write(data)
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)


def _serve(args: argparse.Namespace) -> int:
    import uvicorn

    from .api.app import create_app

    settings = _settings(args)
    if settings.host not in ("127.0.0.1", "localhost", "::1") and not args.allow_remote:
        raise CliError(
            f"refusing to listen on {settings.host}: there are no user accounts yet, so anyone "
            "who can reach it could change scenes; pass --allow-remote to do it anyway"
        )
    uvicorn.run(create_app(settings), host=settings.host, port=settings.port, log_level="info")
    return 0


def _demo(args: argparse.Namespace) -> int:
    from .workbench import Workbench

    workbench = Workbench(_settings(args))
    try:
        if workbench.scenes.list_summaries():
            print("the database already holds scenes; no demo scenes loaded")
            return 0
        folders = [DEMO_PHOTOS / name for name in DEMO_FOLDERS if (DEMO_PHOTOS / name).is_dir()]
        if not folders:
            print(f"no demo photos found in {DEMO_PHOTOS}; the app starts empty", file=sys.stderr)
            return 0
        for folder in folders:
            result = workbench.import_folder(folder)
            print(f"loaded demo scene {folder.name}: {result.job.status if result.job else '-'}")
    finally:
        workbench.close()
    return 0


def _import(args: argparse.Namespace) -> int:
    from .inputs import InputError
    from .workbench import Workbench

    workbench = Workbench(_settings(args))
    failures = 0
    try:
        for folder in args.folders:
            try:
                result = workbench.import_folder(folder)
            except InputError as exc:
                print(f"error: {folder}: {exc}", file=sys.stderr)
                failures += 1
                continue
            job = result.job
            print(f"{folder}: scene {result.scene.id}, pipeline {job.status if job else '-'}")
            if job and job.status == "failed":
                failures += 1
    finally:
        workbench.close()
    return 1 if failures else 0


if __name__ == "__main__":
    raise SystemExit(main())

"""`holiscene view`: one scene in a viser viewer, from the store or from a scene.json."""

from __future__ import annotations

import argparse
from pathlib import Path

from .common import CliError, settings_from


def add_view_command(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    view = sub.add_parser("view", help="review a scene in a viser viewer on 127.0.0.1")
    view.add_argument("scene", help="a scene id of the store, or a scene.json path (or folder)")
    view.add_argument("--port", type=int, default=8080, help="port (default 8080; 0: any free)")
    view.add_argument("--photo", type=Path, help="the photo, when it is not beside scene.json")
    view.add_argument("--data-dir", type=Path, help="the store's data directory (scene ids)")
    view.add_argument("--database-url")
    view.set_defaults(handler=_view)


def _view(args: argparse.Namespace) -> int:
    from ..viewer import ViewerInputError
    from ..viewer.run import serve_until_interrupted

    if not 0 <= args.port <= 65535:
        raise CliError(f"--port {args.port} is not a port number")
    try:
        return serve_until_interrupted(args.scene, settings_from(args), args.port, args.photo)
    except ViewerInputError as exc:
        raise CliError(str(exc)) from exc

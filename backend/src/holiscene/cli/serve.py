"""`holiscene serve`: the workbench server, once it owns its data directory and database."""

from __future__ import annotations

import argparse
import contextlib
from pathlib import Path

from .common import CliError, settings_from


def add_serve_command(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    serve = sub.add_parser("serve", help="start the workbench server")
    serve.add_argument("--host", help="address to bind (default 127.0.0.1)")
    serve.add_argument("--port", type=int, help="port (default 8000)")
    serve.add_argument("--data-dir", type=Path, help="data directory (default var/data)")
    serve.add_argument("--database-url", help="SQLAlchemy URL (default: SQLite in the data dir)")
    serve.add_argument(
        "--allow-remote",
        action="store_true",
        help="bind beyond loopback (needs an admin account: holiscene users add)",
    )
    serve.set_defaults(handler=_serve)


def _serve(args: argparse.Namespace) -> int:
    import uvicorn

    from ..api.app import create_app
    from ..core.data_dir_owner import DataDirInUseError, own_data_dir
    from ..core.database_owner import DatabaseInUseError, own_database
    from .users import check_can_serve

    settings = settings_from(args)
    # Owned before anything reads or writes the data: start-up recovery fails unfinished jobs,
    # which must not happen to the jobs of a server already running on it.
    with contextlib.ExitStack() as held:
        try:
            held.enter_context(own_data_dir(settings.data_dir))
            held.enter_context(own_database(settings.resolved_database_url))
        except (DataDirInUseError, DatabaseInUseError) as exc:
            raise CliError(str(exc)) from exc
        check_can_serve(settings, args.allow_remote)
        uvicorn.run(create_app(settings), host=settings.host, port=settings.port, log_level="info")
    return 0

"""One server per data directory: `holiscene serve` holds an exclusive lock on
<data_dir>/server.lock for its whole life, taken before anything else touches the data.

Start-up recovery (failing unfinished jobs, removing half-trained models and abandoned
import folders) is only right when no other server is running those jobs; a second server
on the same data directory must therefore stop before it, with everything left as it was.
The lock is flock(2): the kernel drops it when the process ends, even on kill -9, so a
crashed server never leaves a stale lock behind.
"""

from __future__ import annotations

import fcntl
import os
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

LOCK_FILE = "server.lock"


class DataDirInUseError(RuntimeError):
    """Another process holds the data directory's lock."""


def try_lock(fd: int) -> bool:
    """Take an exclusive flock on an open file or folder without waiting; False when another
    open file description holds it."""
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        return False
    return True


@contextmanager
def own_data_dir(data_dir: Path) -> Iterator[None]:
    """Hold the data directory for the block (DataDirInUseError when another server does).
    The lock file stays afterwards: deleting it could let two servers lock two files."""
    data_dir.mkdir(parents=True, exist_ok=True)
    path = data_dir / LOCK_FILE
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
    try:
        if not try_lock(fd):
            holder = os.pread(fd, 64, 0).decode(errors="replace").strip() or "unknown"
            raise DataDirInUseError(
                f"the data directory {data_dir} is in use by another holiscene server "
                f"(process {holder}); stop it first, or pass another --data-dir"
            )
        # Written only by the holder, for the message above and for people looking.
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
        yield
    finally:
        os.close(fd)  # releases the lock

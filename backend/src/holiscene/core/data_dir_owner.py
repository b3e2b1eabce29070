"""One server per data directory: `holiscene serve` holds an exclusive lock on
<data_dir>/server.lock for its whole life, taken before anything else touches the data.
Each running `holiscene batch` holds a lock file of its own under <data_dir>/batches/, so a
server's recovery leaves the jobs of a live batch alone, and a new batch knows when the jobs
an earlier one left out belong to nobody (it was killed).

Start-up recovery (failing unfinished jobs, removing half-trained models and abandoned
import folders) is only right when no other server is running those jobs; a second server
on the same data directory must therefore stop before it, with everything left as it was.
The lock is flock(2): the kernel drops it when the process ends, even on kill -9, so a
crashed server never leaves a stale lock behind.
"""

from __future__ import annotations

import fcntl
import os
import uuid
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

LOCK_FILE = "server.lock"
BATCH_FOLDER = "batches"


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


@contextmanager
def batch_presence(data_dir: Path) -> Iterator[int]:
    """Mark this process as a running batch on the data directory for the block; yields how
    many other batches run on it now."""
    folder = data_dir / BATCH_FOLDER
    folder.mkdir(parents=True, exist_ok=True)
    name = f"{os.getpid()}-{uuid.uuid4().hex[:12]}"
    # Locked under another name first, then renamed: a file that is already *.lock is never
    # seen unlocked by running_batches, which would take it for a dead batch's.
    draft = folder / f"{name}.new"
    path = folder / f"{name}.lock"
    fd = os.open(draft, os.O_RDWR | os.O_CREAT | os.O_EXCL, 0o644)
    try:
        try_lock(fd)  # a file of our own: nobody else can hold it
        os.rename(draft, path)
        yield running_batches(data_dir) - 1
    finally:
        path.unlink(missing_ok=True)
        draft.unlink(missing_ok=True)
        os.close(fd)


def running_batches(data_dir: Path) -> int:
    """How many batches hold their lock under <data_dir>/batches/ now. The files of batches
    that ended without removing theirs (kill -9: the kernel dropped the lock) are removed."""
    folder = data_dir / BATCH_FOLDER
    running = 0
    for path in sorted(folder.glob("*.lock")) if folder.is_dir() else []:
        try:
            fd = os.open(path, os.O_RDWR)
        except FileNotFoundError:  # its batch just ended
            continue
        try:
            if try_lock(fd):
                path.unlink(missing_ok=True)
            else:
                running += 1
        finally:
            os.close(fd)
    return running

"""A dataset uploaded as one .zip, unpacked where nothing outside its folder can be touched.

A zip names its own paths and sizes, so each is checked before a byte is written: no entry
may leave the folder (an absolute path, `..`, a drive letter), no entry may be a symbolic
link, the entries' total size and count have limits, and the bytes written are counted too
(a header may understate them). macOS's `__MACOSX/` and `._*` companions are left out: they
are not the dataset's files and would read as broken JSON.
"""

from __future__ import annotations

import shutil
import stat
import zipfile
from dataclasses import dataclass
from pathlib import Path, PurePosixPath
from typing import IO

from .errors import InputError

MB = 1024 * 1024
_CHUNK = 1024 * 1024
_MAC_FOLDER = "__MACOSX"


@dataclass(frozen=True)
class ArchiveLimits:
    """The most an upload may unpack to: bytes in all and files."""

    max_bytes: int
    max_files: int

    @classmethod
    def of_uploads(cls, max_unpacked_mb: int, max_files: int) -> ArchiveLimits:
        """The limits of an uploaded dataset (Settings.max_import_unpacked_mb, max_import_files)."""
        return cls(max_unpacked_mb * MB, max_files)


def unpack_zip(source: IO[bytes], target: Path, limits: ArchiveLimits) -> int:
    """Unpack the zip read from `source` into the new folder `target`; returns the number of
    files written. InputError (415 not a zip, 413 too large, 422 unsafe) leaves no folder."""
    try:
        archive = zipfile.ZipFile(source)
    except (zipfile.BadZipFile, OSError, EOFError) as exc:
        raise InputError("the upload is not a .zip file", 415) from exc
    with archive:
        entries = _checked_entries(archive, limits)
        target.mkdir(parents=True)
        try:
            written = 0
            for info, relative in entries:
                written += _extract(archive, info, target / relative, limits.max_bytes - written)
        except BaseException:
            shutil.rmtree(target, ignore_errors=True)
            raise
    return len(entries)


def _checked_entries(
    archive: zipfile.ZipFile, limits: ArchiveLimits
) -> list[tuple[zipfile.ZipInfo, PurePosixPath]]:
    entries: list[tuple[zipfile.ZipInfo, PurePosixPath]] = []
    seen: set[PurePosixPath] = set()
    total = 0
    for info in archive.infolist():
        if info.is_dir():  # folders are made for the files in them
            continue
        relative = _safe_path(info.filename)
        if _is_mac_companion(relative):
            continue
        if stat.S_ISLNK(info.external_attr >> 16):
            raise InputError(f"the zip holds a symbolic link ({info.filename}): zip the files")
        if info.flag_bits & 0x1:
            raise InputError(f"{info.filename} is encrypted: zip it without a password")
        if relative in seen:
            raise InputError(f"the zip holds {info.filename} twice")
        seen.add(relative)
        total += info.file_size
        entries.append((info, relative))
        if len(entries) > limits.max_files:
            raise InputError(f"the zip holds more than {limits.max_files} files", 413)
        if total > limits.max_bytes:
            raise InputError(f"the zip unpacks to more than {limits.max_bytes // MB} MB", 413)
    if not entries:
        raise InputError("the zip holds no files")
    return entries


def _safe_path(name: str) -> PurePosixPath:
    """The entry's path inside the folder; InputError for one that would leave it."""
    path = PurePosixPath(name.replace("\\", "/"))
    parts = path.parts
    if not parts or path.is_absolute() or ".." in parts or ":" in parts[0] or "\x00" in name:
        raise InputError(f"the zip names a file outside its folder ({name!r}): refused")
    return PurePosixPath(*[p for p in parts if p != "."])


def _is_mac_companion(path: PurePosixPath) -> bool:
    return path.parts[0] == _MAC_FOLDER or path.name.startswith("._") or path.name == ".DS_Store"


def _extract(archive: zipfile.ZipFile, info: zipfile.ZipInfo, path: Path, room: int) -> int:
    """Write one entry, at most `room` bytes; the bytes written."""
    path.parent.mkdir(parents=True, exist_ok=True)
    written = 0
    try:
        with archive.open(info) as entry, path.open("xb") as out:
            while chunk := entry.read(_CHUNK):
                written += len(chunk)
                if written > room:
                    raise InputError("the zip unpacks to more than its headers say", 413)
                out.write(chunk)
    except (zipfile.BadZipFile, EOFError, NotImplementedError) as exc:
        raise InputError(f"{info.filename} cannot be unpacked: {exc}") from exc
    except OSError as exc:  # a file where the zip also has a folder of that name
        raise InputError(f"{info.filename} cannot be written: {exc.strerror or exc}") from exc
    return written

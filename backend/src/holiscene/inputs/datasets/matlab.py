"""Reading MATLAB .mat files, as far as the NYU Depth v2 files need them: a cell array of
numeric matrices (the support labels), a numeric matrix and a cell array of text (the names
and mapping of classMapping40.mat) in the level-5 format MATLAB writes by default, without
SciPy, and char arrays and cell arrays of a v7.3 file (HDF5, through h5py). Level-5 files are
written by export.matfile.

Level 5 (MATLAB's "MAT-File Format" document): a 128-byte header (text, subsystem offset,
version 0x0100, the endian mark "IM" on a little-endian file), then data elements, each an
8-byte tag (type, byte count) and its data padded to 8 bytes; a tag whose upper 16 bits are
set is a small element holding up to 4 bytes itself. A variable is a miMATRIX element: array
flags (class in the low byte), dimensions, name, then the cells (each a miMATRIX) or the real
part. MATLAB zlib-compresses each variable as a miCOMPRESSED element and stores a double
matrix of whole numbers in the smallest integer type that holds it.

v7.3 (HDF5): arrays are stored transposed (MATLAB is column-major), a char array as uint16
codes, a cell array as object references into `#refs#`, an empty array as its dimensions
with the attribute MATLAB_empty.
"""

from __future__ import annotations

import struct
import zlib
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

HEADER_BYTES = 128
MI_MATRIX, MI_COMPRESSED = 14, 15
MX_CELL, MX_CHAR = 1, 4
# Numeric miTYPE codes and the numpy type of their values (miUTF8 and miUTF16 hold text).
NUMERIC_TYPES = {1: "i1", 2: "u1", 3: "i2", 4: "u2", 5: "i4", 6: "u4", 7: "f4", 9: "f8"}
NUMERIC_TYPES |= {12: "i8", 13: "u8", 16: "u1", 17: "u2"}
# mxCLASS codes of numeric arrays (double, single, int8 ... uint64).
NUMERIC_CLASSES = frozenset(range(6, 16))


class MatFileError(ValueError):
    """A .mat file that does not hold what was expected; the message says what."""


class MissingVariableError(MatFileError):
    """A readable level-5 .mat file without the variable asked for."""


def read_cell_of_matrices(path: Path, variable: str) -> list[np.ndarray]:
    """The matrices of the cell array `variable` in column-major order (2-D float arrays),
    from a level-5 or a v7.3 file."""
    value = _read_variable(path, variable, _hdf5_cell)
    if not isinstance(value, list):
        raise MatFileError(f"{path.name}: {variable} is not a cell array")
    return value


def read_strings(path: Path, variable: str) -> list[str]:
    """The texts of the level-5 cell array of char arrays `variable`, in column-major order
    (a char array's codes are UTF-16 code units, one row of text each)."""
    value = _read_variable(path, variable, _hdf5_cell)
    if not isinstance(value, list):
        raise MatFileError(f"{path.name}: {variable} is not a cell array")
    return ["".join(chr(int(c)) for c in codes.ravel(order="F")) for codes in value]


def read_numeric_matrix(path: Path, variable: str) -> np.ndarray:
    """The numeric matrix `variable` (float, as MATLAB shows it), from a level-5 or a v7.3
    file."""
    value = _read_variable(path, variable, _hdf5_numeric)
    if isinstance(value, list):
        raise MatFileError(f"{path.name}: {variable} is a cell array, not a matrix")
    return value


def _read_variable(
    path: Path, variable: str, read_hdf5: Callable[[Path, str], np.ndarray | list[np.ndarray]]
) -> np.ndarray | list[np.ndarray]:
    import h5py

    try:
        data = path.read_bytes()
    except OSError as exc:
        raise MatFileError(f"{path.name} cannot be read: {exc.strerror or exc}") from exc
    if h5py.is_hdf5(path):
        return read_hdf5(path, variable)
    if len(data) < HEADER_BYTES or not data.startswith(b"MATLAB 5.0 MAT-file"):
        raise MatFileError(f"{path.name} is not a MATLAB .mat file (level 5 or v7.3)")
    endian = {b"IM": "<", b"MI": ">"}.get(data[126:128])
    if endian is None:
        raise MatFileError(f"{path.name}: the header's endian mark is neither IM nor MI")
    try:
        value = _level5_variable(data, endian, variable)
    except MatFileError as exc:
        raise MatFileError(f"{path.name}: {exc}") from exc
    except (struct.error, ValueError) as exc:  # sizes that do not fit the data
        raise MatFileError(f"{path.name} is corrupt: {exc}") from exc
    if value is None:
        raise MissingVariableError(f"{path.name} holds no variable {variable!r}")
    return value


def _level5_variable(
    data: bytes, endian: str, variable: str
) -> np.ndarray | list[np.ndarray] | None:
    for element_type, payload in _elements(data, HEADER_BYTES, len(data), endian):
        if element_type == MI_COMPRESSED:
            try:
                unpacked = zlib.decompress(payload)
            except zlib.error as exc:
                raise MatFileError("a compressed variable is corrupt (truncated?)") from exc
            inner = list(_elements(unpacked, 0, len(unpacked), endian))
            if len(inner) != 1:
                raise MatFileError("a compressed element holds more than one variable")
            element_type, payload = inner[0]
        # Only the variable asked for is decoded: the others may be of a class this reader
        # does not know (classMapping40.mat holds text and structs beside its mapping).
        if element_type == MI_MATRIX and _matrix_name(payload, endian) == variable:
            return _matrix(payload, endian)[1]
    return None


def _matrix_name(payload: bytes, endian: str) -> str:
    parts = []
    for part in _elements(payload, 0, len(payload), endian):
        parts.append(part)
        if len(parts) == 3:
            return part[1].decode("ascii", "replace")
    return ""


def _elements(data: bytes, position: int, end: int, endian: str) -> Iterator[tuple[int, bytes]]:
    while position < end:
        if end - position < 8:
            raise MatFileError("the file ends inside a data element (truncated)")
        element_type, count = struct.unpack_from(endian + "II", data, position)
        if element_type >> 16:  # small element: count and type share the first 4 bytes
            count, element_type = element_type >> 16, element_type & 0xFFFF
            yield element_type, data[position + 4 : position + 4 + count]
            position += 8
            continue
        payload = data[position + 8 : position + 8 + count]
        if len(payload) < count:
            raise MatFileError("the file ends inside a data element (truncated)")
        yield element_type, payload
        padding = 0 if element_type == MI_COMPRESSED else -count % 8
        position += 8 + count + padding


def _matrix(payload: bytes, endian: str) -> tuple[str, np.ndarray | list[np.ndarray]]:
    """(name, value) of a miMATRIX: a float array, or the list of a cell array's matrices."""
    if not payload:  # an empty matrix may be written as a bare tag
        return "", np.zeros((0, 0))
    parts = list(_elements(payload, 0, len(payload), endian))
    if len(parts) < 3:
        raise MatFileError("a matrix element lacks its flags, dimensions or name")
    (_, flags), (_, dims_bytes), (_, name_bytes) = parts[:3]
    mx_class = struct.unpack_from(endian + "I", flags)[0] & 0xFF
    dims = tuple(int(d) for d in np.frombuffer(dims_bytes, dtype=endian + "i4"))
    name = name_bytes.decode("ascii", "replace")
    if mx_class == MX_CELL:
        cells = []
        for cell_type, cell_payload in parts[3:]:
            if cell_type != MI_MATRIX:
                raise MatFileError("a cell of the cell array is not a matrix")
            cell = _matrix(cell_payload, endian)[1]
            if isinstance(cell, list):
                raise MatFileError("a cell holds another cell array, not a matrix")
            cells.append(cell)
        return name, cells
    if mx_class not in NUMERIC_CLASSES | {MX_CHAR}:  # text comes as its character codes
        raise MatFileError(f"a matrix of MATLAB class {mx_class} is not numeric")
    if len(parts) < 4:
        return name, np.zeros(dims)
    real_type, real = parts[3]
    if real_type not in NUMERIC_TYPES:
        raise MatFileError(f"a matrix's values have the unknown type {real_type}")
    values = np.frombuffer(real, dtype=endian + NUMERIC_TYPES[real_type]).astype(float)
    if values.size != int(np.prod(dims)):
        raise MatFileError(f"a matrix of size {dims} holds {values.size} values")
    return name, values.reshape(dims, order="F")


def _hdf5_cell(path: Path, variable: str) -> list[np.ndarray]:
    import h5py

    try:
        with h5py.File(path, "r") as file:
            if variable not in file:
                raise MatFileError(f"{path.name} holds no variable {variable!r}")
            references = np.asarray(file[variable]).ravel(order="F")
            return [hdf5_matrix(file, ref).T.astype(float) for ref in references]
    except (OSError, KeyError, TypeError) as exc:
        raise MatFileError(f"{path.name} cannot be read (truncated or corrupt?): {exc}") from exc


def _hdf5_numeric(path: Path, variable: str) -> np.ndarray:
    import h5py

    try:
        with h5py.File(path, "r") as file:
            if variable not in file:
                raise MatFileError(f"{path.name} holds no variable {variable!r}")
            return np.asarray(file[variable]).T.astype(float)
    except (OSError, KeyError, TypeError, ValueError) as exc:
        raise MatFileError(f"{path.name} cannot be read (truncated or corrupt?): {exc}") from exc


def hdf5_matrix(file: Any, reference: Any) -> np.ndarray:
    """The array a v7.3 reference points at, as stored (transposed); an empty array as
    zeros of its dimensions."""
    if not reference:
        raise MatFileError("a reference points nowhere (a null reference)")
    try:
        target = file[reference]
    except (KeyError, ValueError) as exc:
        raise MatFileError(f"a reference points at nothing: {exc}") from exc
    if target.attrs.get("MATLAB_empty"):
        return np.zeros(tuple(int(d) for d in np.asarray(target).ravel())[::-1])
    return np.asarray(target)


def hdf5_string(file: Any, reference: Any) -> str:
    """A v7.3 char array (uint16 codes) a reference points at, as text."""
    codes = hdf5_matrix(file, reference)
    return "".join(chr(int(c)) for c in codes.ravel(order="F"))

"""MATLAB 5 MAT-files (the format of MATLAB's `save -v6`, which scipy.io.loadmat reads), written
for the tools whose files are .mat: numeric matrices, char arrays (text), structs and cell
arrays.

The layout, from MATLAB's "MAT-File Format" reference: a 128-byte header, then one data
element per variable. An element is a tag (type, byte count) and its data padded to 8 bytes;
a variable is an miMATRIX element holding its array flags (class), dimensions, name and
values (numbers column-major; a struct's field names and then each field's value as a
nameless miMATRIX; a cell's elements likewise). Little-endian throughout.
"""

from __future__ import annotations

import struct
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Union

import numpy as np

# Data types of elements (miINT8, ...) and classes of arrays (mxDOUBLE_CLASS, ...).
MI_INT8, MI_UINT16, MI_INT32, MI_UINT32, MI_DOUBLE, MI_INT64, MI_MATRIX = 1, 4, 5, 6, 9, 12, 14
MX_CELL, MX_STRUCT, MX_CHAR, MX_DOUBLE, MX_INT64 = 1, 2, 4, 6, 14
FIELD_NAME_LENGTH = 32  # bytes per field name, with its terminating zero: MATLAB's own limit

_NUMERIC = {np.dtype(np.float64): (MX_DOUBLE, MI_DOUBLE), np.dtype(np.int64): (MX_INT64, MI_INT64)}


@dataclass(frozen=True)
class MatStruct:
    """A 1x1 struct: field name -> value."""

    fields: Mapping[str, MatValue]


@dataclass(frozen=True)
class MatCell:
    """A 1xN cell array, or Nx1 when `column` (NYU's support labels are one)."""

    items: Sequence[MatValue]
    column: bool = False


MatValue = Union[np.ndarray, str, MatStruct, MatCell]  # noqa: UP007 (a runtime alias)


def mat_file(variables: Mapping[str, MatValue], description: str = "HoliScene") -> bytes:
    """The bytes of a MAT-file holding `variables` (name -> value). Arrays must be float64 or
    int64; a 1-D array is saved as a row (1xN), as scipy.io.savemat does by default; a str is
    a 1xN char array (UTF-16 code units, as MATLAB stores text)."""
    text = f"MATLAB 5.0 MAT-file, written by {description}".encode("ascii")[:116]
    header = text.ljust(116, b" ") + bytes(8) + struct.pack("<H2s", 0x0100, b"IM")
    return header + b"".join(_matrix(name, value) for name, value in variables.items())


def _element(data_type: int, data: bytes) -> bytes:
    padding = -len(data) % 8
    return struct.pack("<II", data_type, len(data)) + data + bytes(padding)


def _matrix(name: str, value: MatValue) -> bytes:
    if isinstance(value, MatStruct):
        body = _struct_body(value)
        mx_class, dims = MX_STRUCT, (1, 1)
    elif isinstance(value, str):
        units = value.encode("utf-16-le")
        mx_class, dims = MX_CHAR, (1, len(units) // 2)
        body = _element(MI_UINT16, units)
    elif isinstance(value, MatCell):
        body = b"".join(_matrix("", item) for item in value.items)
        count = len(value.items)
        mx_class, dims = MX_CELL, ((count, 1) if value.column else (1, count))
    else:
        array = np.asarray(value)
        if array.dtype not in _NUMERIC:
            raise TypeError(
                f"{name or 'a value'}: only float64 and int64 arrays, not {array.dtype}"
            )
        mx_class, mi_type = _NUMERIC[array.dtype]
        if array.ndim < 2:
            array = array.reshape(1, -1)
        dims = array.shape
        body = _element(mi_type, array.astype(array.dtype.newbyteorder("<")).tobytes(order="F"))
    flags = _element(MI_UINT32, struct.pack("<II", mx_class, 0))
    dimensions = _element(MI_INT32, struct.pack(f"<{len(dims)}i", *dims))
    content = flags + dimensions + _element(MI_INT8, name.encode("ascii")) + body
    return _element(MI_MATRIX, content)


def _struct_body(value: MatStruct) -> bytes:
    names = list(value.fields)
    for name in names:
        if not name.isidentifier() or len(name) >= FIELD_NAME_LENGTH:
            raise ValueError(f"{name!r} cannot be a MATLAB field name")
    packed = b"".join(n.encode("ascii").ljust(FIELD_NAME_LENGTH, b"\0") for n in names)
    length = _element(MI_INT32, struct.pack("<i", FIELD_NAME_LENGTH))
    return (
        length + _element(MI_INT8, packed) + b"".join(_matrix("", value.fields[n]) for n in names)
    )

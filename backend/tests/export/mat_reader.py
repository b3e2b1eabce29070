"""A reader of uncompressed MATLAB 5 MAT-files for the tests (numeric matrices, structs, cell
arrays), following MATLAB's "MAT-File Format" reference: what the export writes must read
back as a MATLAB tool reads it."""

from __future__ import annotations

import struct
from typing import Any

import numpy as np

_TYPES = {1: "<i1", 2: "<u1", 3: "<i2", 4: "<u2", 5: "<i4", 6: "<u4", 7: "<f4", 9: "<f8"}
_TYPES |= {12: "<i8", 13: "<u8"}
MATRIX, CELL, STRUCT = 14, 1, 2


def read_mat(data: bytes) -> dict[str, Any]:
    """name -> value: an ndarray (its MATLAB shape), a dict for a 1x1 struct, a list for a cell."""
    assert data[:10] == b"MATLAB 5.0", "not a level-5 MAT-file"
    assert struct.unpack("<H2s", data[124:128]) == (0x0100, b"IM")
    variables = {}
    for kind, payload in _elements(data[128:]):
        assert kind == MATRIX
        name, value = _matrix(payload)
        variables[name] = value
    return variables


def _elements(data: bytes) -> list[tuple[int, bytes]]:
    elements, position = [], 0
    while position < len(data):
        kind, size = struct.unpack_from("<II", data, position)
        if kind >> 16:  # a small element: size and type in the first 4 bytes, data in 4
            kind, size = kind & 0xFFFF, kind >> 16
            elements.append((kind, data[position + 4 : position + 4 + size]))
            position += 8
            continue
        elements.append((kind, data[position + 8 : position + 8 + size]))
        position += 8 + size + (-size % 8)
    return elements


def _matrix(payload: bytes) -> tuple[str, Any]:
    parts = _elements(payload)
    (_, flags), (_, dims_bytes), (_, name_bytes) = parts[:3]
    mx_class = struct.unpack_from("<I", flags)[0] & 0xFF
    dims = tuple(np.frombuffer(dims_bytes, "<i4"))
    name = name_bytes.decode("ascii")
    if mx_class == CELL:
        return name, [_matrix(body)[1] for _, body in parts[3:]]
    if mx_class == STRUCT:
        assert dims == (1, 1), dims
        length = int(np.frombuffer(parts[3][1], "<i4")[0])
        raw = parts[4][1]
        fields = [raw[i : i + length].rstrip(b"\0").decode() for i in range(0, len(raw), length)]
        values = [_matrix(body)[1] for _, body in parts[5:]]
        return name, dict(zip(fields, values, strict=True))
    kind, raw_values = parts[3]
    return name, np.frombuffer(raw_values, _TYPES[kind]).reshape(dims, order="F")

"""Broken inputs, made on the fly, that every entry point must refuse."""

from __future__ import annotations

import json
import struct
import zlib


def png_header_only(width: int, height: int) -> bytes:
    """A PNG whose header claims width x height pixels, with a tiny (invalid) body."""

    def chunk(kind: bytes, body: bytes) -> bytes:
        crc = zlib.crc32(kind + body) & 0xFFFFFFFF
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", crc)

    ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", ihdr)
        + chunk(b"IDAT", zlib.compress(b"\x00" * 16))
        + chunk(b"IEND", b"")
    )


def truncated(data: bytes) -> bytes:
    return data[: len(data) // 3]


NOT_AN_IMAGE = b"this is a text file, not a photo\n"

# name -> (detections.json bytes, fragment of the expected message)
BAD_DETECTIONS: dict[str, tuple[bytes, str]] = {
    "wrong_shape": (json.dumps({"bbox": [1, 2, 3, 4], "class": "bed"}).encode(), "must be a list"),
    "bbox_not_four_numbers": (
        json.dumps([{"bbox": [1, 2, 3], "class": "bed"}]).encode(),
        "4 numbers",
    ),
    "box_outside_image": (
        json.dumps([{"bbox": [800, 10, 900, 100], "class": "bed"}]).encode(),
        "outside",
    ),
    "empty_class": (
        json.dumps([{"bbox": [10, 10, 100, 100], "class": " "}]).encode(),
        "non-empty string",
    ),
    "not_json": (b"[{bbox: oops", "not valid JSON"),
}

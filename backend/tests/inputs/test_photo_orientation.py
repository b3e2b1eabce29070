"""Phone photos: pixels stored as the sensor saw them plus an EXIF turn, which browsers and
labelling tools apply. The pipeline reads them upright, and stores them so."""

from __future__ import annotations

import io
import json
import shutil
from pathlib import Path

import numpy as np
import pytest
from holiscene.cli import main
from holiscene.inputs import load_photo
from PIL import ExifTags, Image, ImageCms

# How the stored pixels were turned from the upright photo, for each EXIF orientation.
STORED_FROM_UPRIGHT = {
    2: [Image.Transpose.FLIP_LEFT_RIGHT],
    3: [Image.Transpose.ROTATE_180],
    4: [Image.Transpose.FLIP_TOP_BOTTOM],
    5: [Image.Transpose.TRANSPOSE],
    6: [Image.Transpose.ROTATE_90],
    7: [Image.Transpose.TRANSVERSE],
    8: [Image.Transpose.ROTATE_270],
}


def _upright() -> Image.Image:
    """A photo no turn or mirror leaves the same: a red block in one corner, a ramp across."""
    pixels = np.zeros((60, 90, 3), dtype=np.uint8)
    pixels[..., 1] = np.linspace(0, 255, 90, dtype=np.uint8)[None, :]
    pixels[:20, :30, 0] = 255
    return Image.fromarray(pixels)


def _stored(upright: Image.Image, orientation: int, fmt: str, **options: object) -> bytes:
    stored = upright
    for turn in STORED_FROM_UPRIGHT.get(orientation, []):
        stored = stored.transpose(turn)
    exif = Image.Exif()
    exif[ExifTags.Base.Orientation] = orientation
    buffer = io.BytesIO()
    stored.save(buffer, fmt, exif=exif.tobytes(), **options)
    return buffer.getvalue()


@pytest.mark.parametrize("orientation", range(2, 9))
def test_every_exif_turn_gives_the_upright_pixels(orientation: int) -> None:
    upright = _upright()
    photo = load_photo(_stored(upright, orientation, "PNG"))
    np.testing.assert_array_equal(photo.rgb, np.asarray(upright))
    assert (photo.width, photo.height) == (90, 60) and photo.suffix == ".png"
    # What is stored is what the pipeline read, without the turn.
    with Image.open(io.BytesIO(photo.data)) as stored:
        assert stored.getexif().get(ExifTags.Base.Orientation, 1) == 1
        np.testing.assert_array_equal(np.asarray(stored.convert("RGB")), photo.rgb)
    assert load_photo(photo.data).data == photo.data


def test_a_turned_jpeg_is_stored_upright_with_its_colour_profile() -> None:
    profile = ImageCms.ImageCmsProfile(ImageCms.createProfile("sRGB")).tobytes()
    data = _stored(_upright(), 6, "JPEG", quality=98, icc_profile=profile)
    photo = load_photo(data)
    assert photo.rgb.shape == (60, 90, 3) and photo.suffix == ".jpg"
    assert photo.rgb[:20, :30, 0].mean() > 230 and photo.rgb[40:, 60:, 0].mean() < 25
    with Image.open(io.BytesIO(photo.data)) as stored:
        assert stored.format == "JPEG" and stored.size == (90, 60)
        assert stored.info.get("icc_profile") == profile
        assert stored.getexif().get(ExifTags.Base.Orientation, 1) == 1


def test_a_photo_without_a_turn_is_kept_byte_for_byte() -> None:
    for orientation in (1, None):
        buffer = io.BytesIO()
        exif = Image.Exif()
        if orientation is not None:
            exif[ExifTags.Base.Orientation] = orientation
        _upright().save(buffer, "JPEG", exif=exif.tobytes())
        assert load_photo(buffer.getvalue()).data == buffer.getvalue()


def test_infer_reads_a_turned_phone_photo_as_the_upright_one(t3d5: Path, tmp_path: Path) -> None:
    turned = tmp_path / "turned"
    shutil.copytree(t3d5, turned)
    with Image.open(t3d5 / "img.jpg") as upright:
        (turned / "img.jpg").write_bytes(_stored(upright, 6, "JPEG", quality=97))
    scenes = {}
    for name, folder in (("upright", t3d5), ("turned", turned)):
        assert main(["infer", str(folder), "-o", str(tmp_path / name)]) == 0
        scenes[name] = json.loads((tmp_path / name / "scene.json").read_text())
    upright_camera, turned_camera = scenes["upright"]["camera"], scenes["turned"]["camera"]
    assert scenes["turned"]["image"]["width"] == scenes["upright"]["image"]["width"] == 730
    assert turned_camera["pitch_deg"] == pytest.approx(upright_camera["pitch_deg"], abs=0.5)
    assert turned_camera["roll_deg"] == pytest.approx(upright_camera["roll_deg"], abs=0.5)

"""Masks given with the boxes (a labelled dataset's outlines): read from detections.json with
checks, kept by the masks stage as they are, and stored with the scene for a re-run."""

from __future__ import annotations

import io
import json
from pathlib import Path

import numpy as np
import pytest
from holiscene.core.settings import Settings
from holiscene.inputs import InputError, InputFiles, load_photo, parse_detections
from holiscene.inputs.validation import read_input_folder
from holiscene.pipeline.base import Detection, SceneContext
from holiscene.pipeline.stages.detections import objects_from_detections
from holiscene.pipeline.stages.grabcut import MasksGrabCut
from holiscene.segmentation.rle import decode_mask, encode_mask
from holiscene.services.workbench import Workbench
from PIL import Image

WIDTH, HEIGHT = 96, 64


def _disc(cx: int, cy: int, r: int) -> np.ndarray:
    yy, xx = np.mgrid[:HEIGHT, :WIDTH]
    return np.asarray((xx - cx) ** 2 + (yy - cy) ** 2 <= r * r)


def _mask_json(pixels: np.ndarray) -> dict:  # type: ignore[type-arg]
    mask = encode_mask(pixels, "given")
    assert mask is not None
    return mask.model_dump(mode="json")


def _png(width: int = WIDTH, height: int = HEIGHT) -> bytes:
    buffer = io.BytesIO()
    rng = np.random.default_rng(3)
    Image.fromarray(rng.integers(0, 255, (height, width, 3), dtype=np.uint8)).save(buffer, "PNG")
    return buffer.getvalue()


def test_a_given_mask_is_read_back_as_given() -> None:
    disc = _disc(30, 30, 10)
    data = json.dumps(
        [{"bbox": [20, 20, 41, 41], "class": "lamp", "mask": {**_mask_json(disc), "source": "x"}}]
    ).encode()
    (detection,) = parse_detections(data, WIDTH, HEIGHT)
    assert detection.mask is not None and detection.mask.source == "given"
    assert np.array_equal(decode_mask(detection.mask, WIDTH, HEIGHT), disc)


@pytest.mark.parametrize(
    ("mask", "message"),
    [
        ({"origin": [90, 0], "size": [10, 10], "rle": [100]}, "outside the 96x64 image"),
        ({"origin": [-1, 0], "size": [10, 10], "rle": [100]}, "outside"),
        ({"origin": [0, 0], "size": [10, 10], "rle": [99]}, "do not add up"),
        ({"origin": [0, 0], "size": [10], "rle": [10]}, "not a mask"),
        ([1, 2, 3], "not a mask"),
    ],
)
def test_a_bad_given_mask_is_refused(mask: object, message: str) -> None:
    data = json.dumps([{"bbox": [0, 0, 10, 10], "class": "lamp", "mask": mask}]).encode()
    with pytest.raises(InputError, match=message):
        parse_detections(data, WIDTH, HEIGHT)


def test_the_grabcut_stage_keeps_given_masks_and_cuts_the_rest() -> None:
    photo = load_photo(_png())
    disc = _disc(30, 30, 10)
    given = encode_mask(disc, "given")
    detections = [
        Detection(cls="lamp", bbox=(20.0, 20.0, 41.0, 41.0), mask=given),
        Detection(cls="box", bbox=(15.0, 15.0, 60.0, 50.0)),
    ]
    ctx = SceneContext(image=photo.rgb, detections=detections)
    ctx.objects = objects_from_detections(detections)
    assert ctx.objects[0].mask == given
    MasksGrabCut().run(ctx)
    assert ctx.masks is not None
    assert ctx.masks["o0"].source == "given"
    assert np.array_equal(ctx.masks["o0"].pixels, disc)
    # The given mask claimed its pixels first.
    assert not (ctx.masks["o1"].pixels & disc).any()


def test_the_stored_scene_keeps_given_masks_for_a_rerun(tmp_path: Path) -> None:
    disc = _disc(30, 30, 10)
    detections = [
        Detection(cls="lamp", bbox=(20.0, 20.0, 41.0, 41.0), mask=encode_mask(disc, "given")),
        Detection(cls="box", bbox=(50.0, 10.0, 90.0, 60.0)),
    ]
    inputs = InputFiles(photo=load_photo(_png()), K=None, detections=detections)
    workbench = Workbench(Settings(data_dir=tmp_path / "data", web_dir=tmp_path / "web"))
    try:
        result = workbench.import_scene(inputs, "given", "import", run_pipeline=False)
        stored = read_input_folder(workbench.scenes.files.folder(result.scene.id))
        document = workbench.scenes.document(result.scene.id)
    finally:
        workbench.close()
    assert stored.detections is not None
    assert stored.detections[0].mask == detections[0].mask
    assert stored.detections[1].mask is None
    assert document.scene.objects[0].mask == detections[0].mask

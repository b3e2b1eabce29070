"""Support arrows and colours of the viewer, on a hand-made room."""

from __future__ import annotations

import numpy as np
import pytest
from holiscene.geometry.boxes import box_corners
from holiscene.viewer.geometry import (
    ARROW_OVERSHOOT,
    MIN_ARROW_LENGTH,
    nearest_wall_point,
    support_arrows,
)
from holiscene_schema import Box3D, ImageInfo, Layout, Scene, SceneObject, SupportRelation

# A 4 m deep (x from 1 to 5), 3 m wide (z from -1.5 to 1.5), 2.5 m high room; camera 1.5 m up.
ROOM = box_corners(np.array([3.0, -0.25, 0.0]), np.array([4.0, 2.5, 3.0]), 0.0)


def _object(obj_id: str, cls: str, center: list[float], size: list[float]) -> SceneObject:
    return SceneObject(
        id=obj_id,
        cls=cls,
        bbox=[0, 0, 10, 10],
        box_3d=Box3D(center=center, size=size, yaw_deg=0.0),
    )


def _room_scene() -> Scene:
    return Scene(
        name="hand-made",
        image=ImageInfo(file="img.png", width=640, height=480),
        layout=Layout(corners_3d=ROOM.tolist()),
        objects=[
            _object("table", "table", [3.0, -1.15, 0.0], [0.8, 0.7, 1.2]),
            _object("lamp", "lamp", [3.0, -0.6, 0.3], [0.3, 0.4, 0.3]),
            _object("picture", "picture", [4.98, 0.2, -0.5], [0.04, 0.6, 0.8]),
        ],
        supports=[
            SupportRelation(child="table", parent="floor", type="below", source="auto"),
            SupportRelation(child="lamp", parent="table", type="below", source="auto"),
            SupportRelation(child="picture", parent="wall", type="behind", source="auto"),
        ],
    )


def test_arrows_run_from_supporter_through_the_object() -> None:
    plan = support_arrows(_room_scene())
    assert plan.skipped == {}
    arrows = {a.child: a for a in plan.arrows}

    table = arrows["table"]  # from the floor under it, head above its top
    assert table.start == pytest.approx([3.0, -1.5, 0.0])
    assert table.end == pytest.approx([3.0, -0.8 + ARROW_OVERSHOOT, 0.0])

    lamp = arrows["lamp"]  # from the table's centre, through the lamp
    assert lamp.start == pytest.approx([3.0, -1.15, 0.0])
    direction = (lamp.end - lamp.start) / np.linalg.norm(lamp.end - lamp.start)
    assert direction == pytest.approx(
        (np.array([3.0, -0.6, 0.3]) - lamp.start) / np.linalg.norm([0.0, 0.55, 0.3])
    )
    assert lamp.end[1] > -0.4  # beyond the lamp's top

    picture = arrows["picture"]  # horizontally out of the back wall, at least 30 cm long
    assert picture.end == pytest.approx([4.98 - 0.02 - ARROW_OVERSHOOT, 0.2, -0.5])
    assert picture.start[1] == pytest.approx(0.2) and picture.start[2] == pytest.approx(-0.5)
    assert np.linalg.norm(picture.end - picture.start) == pytest.approx(MIN_ARROW_LENGTH)
    assert picture.type == "behind"


def test_arrows_that_cannot_be_placed_are_skipped_with_a_reason() -> None:
    scene = _room_scene()
    no_box = scene.objects[0].model_copy(update={"box_3d": None})
    scene = scene.model_copy(update={"objects": [no_box, *scene.objects[1:]], "layout": Layout()})
    plan = support_arrows(scene)
    assert plan.skipped == {
        "table": "no 3D box",
        "lamp": "its supporter table has no 3D box",
    }
    # Without a layout the wall is taken behind the picture, seen from the camera.
    (picture,) = plan.arrows
    assert picture.start[0] > 4.98


def test_nearest_wall_point() -> None:
    assert nearest_wall_point(ROOM, np.array([4.5, 0.3, 0.2])) == pytest.approx([5.0, 0.3, 0.2])
    assert nearest_wall_point(ROOM, np.array([2.0, 0.0, -1.2])) == pytest.approx([2.0, 0.0, -1.5])

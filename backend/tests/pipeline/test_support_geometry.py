"""The floor holds up from below only what stands below its horizon, at a size its class allows
there (supports stages)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from holiscene.geometry.camera import PinholeCamera
from holiscene.inputs import read_input_folder
from holiscene.pipeline.stages.supports import off_the_floor, seen_against_the_floor
from holiscene.placement.room import Room
from holiscene.services.reconstruction import reconstruct_scene
from holiscene_schema import SceneObject

LEVEL = PinholeCamera(np.array([[500.0, 0, 320], [0, 500.0, 240], [0, 0, 1]]), 0.0, 0.0)


def test_a_bottom_edge_above_the_horizon_is_off_the_floor() -> None:
    high, low = [100.0, 40.0, 200.0, 120.0], [100.0, 300.0, 200.0, 420.0]
    assert off_the_floor(LEVEL, [high, low], 480) == [True, False]


def test_the_horizon_moves_with_the_pitch() -> None:
    # Pitched down 20 degrees the horizon is at y = 240 - 500 tan 20 = 58; up, at 422.
    down = PinholeCamera(LEVEL.K, 20.0, 0.0)
    assert off_the_floor(down, [[100.0, 0.0, 200.0, 40.0], [300.0, 0.0, 400.0, 80.0]], 480) == [
        True,
        False,
    ]
    up = PinholeCamera(LEVEL.K, -20.0, 0.0)
    assert off_the_floor(up, [[100.0, 300.0, 200.0, 400.0]], 480) == [True]


def test_a_box_just_below_may_hide_the_real_bottom_edge() -> None:
    wardrobe = [100.0, 20.0, 200.0, 200.0]  # its bottom hidden by the shelf in front
    shelf_in_front = [80.0, 205.0, 260.0, 400.0]
    far_aside = [400.0, 205.0, 500.0, 400.0]
    assert off_the_floor(LEVEL, [wardrobe, shelf_in_front], 480) == [False, False]
    assert off_the_floor(LEVEL, [wardrobe, far_aside], 480) == [True, False]


def test_without_a_camera_nothing_is_ruled_out() -> None:
    assert off_the_floor(None, [[100.0, 40.0, 200.0, 120.0]], 480) == [False]


def _masks_of(boxes: list[list[float]]) -> list[np.ndarray]:
    masks = []
    for x1, y1, x2, y2 in boxes:
        mask = np.zeros((480, 640), dtype=bool)
        mask[int(y1) : int(y2), int(x1) : int(x2)] = True
        masks.append(mask)
    return masks


def test_a_shelf_too_large_for_where_its_bottom_meets_the_floor_is_off_it() -> None:
    down = PinholeCamera(LEVEL.K, 20.0, 0.0)  # horizon at y = 58
    shelf = [400.0, 0.0, 560.0, 110.0]  # would span 3 m of floor 10 camera heights away
    bed = [0.0, 100.0, 420.0, 480.0]  # its box reaches above the shelf's bottom at one side
    objects = [
        SceneObject(id="o0", cls="shelves", bbox=shelf),
        SceneObject(id="o1", cls="bed", bbox=bed),
    ]
    boxes = [shelf, bed]
    assert off_the_floor(down, boxes, 480) == [False, False]  # without classes: below the horizon
    assert off_the_floor(down, boxes, 480, objects, _masks_of(boxes)) == [True, False]
    # Something right below it across most of its width may hide a nearer, lower bottom.
    dresser = [380.0, 115.0, 600.0, 300.0]
    objects.append(SceneObject(id="o2", cls="dresser", bbox=dresser))
    boxes.append(dresser)
    assert off_the_floor(down, boxes, 480, objects, _masks_of(boxes))[0] is False


def test_an_object_cut_by_the_photos_bottom_edge_is_never_too_large() -> None:
    down = PinholeCamera(LEVEL.K, 20.0, 0.0)
    cut = [100.0, 200.0, 600.0, 479.0]  # a bed whose foot the photo cuts off
    objects = [SceneObject(id="o0", cls="night_stand", bbox=cut)]
    assert off_the_floor(down, [cut], 480, objects, _masks_of([cut])) == [False]


def test_a_shelf_on_a_real_wall_is_not_stood_on_the_floor_nor_moves_the_wall_away(
    real_photos: Path,
) -> None:
    """im3d-6's o5 (shelves on the wall, cut by the photo's top and right side): its bottom
    edge read as a floor contact 12 m away made the room 16 m long, and the Relation Network
    stood it on the floor."""
    scene = reconstruct_scene(
        read_input_folder(real_photos / "im3d-6"), name="im3d-6", image_file="img.jpg"
    ).scene
    support = next(s for s in scene.supports if s.child == "o5")
    assert (support.parent, support.type) == ("wall", "behind")
    assert scene.layout is not None and scene.layout.corners_3d is not None
    corners = np.array(scene.layout.corners_3d)
    floor_sides = [float(np.linalg.norm(corners[(k + 1) % 4] - corners[k])) for k in range(4)]
    assert max(floor_sides) < 8.0


def test_a_thing_seen_against_the_floor_hangs_on_no_wall() -> None:
    down = PinholeCamera(LEVEL.K, 20.0, 0.0)
    # Camera 1.4 m above the floor of a room 6 m deep ahead (x) and 5 m wide (z).
    room = Room(centre=np.array([2.5, -0.1, 0.0]), yaw_deg=0.0, size=np.array([7.0, 2.6, 5.0]))
    floor_line = down.project(np.array([[6.0, -1.4, 0.0]]))[0]  # the far wall's foot, mid photo
    picture = [300.0, 40.0, 340.0, floor_line[1] - 60.0]  # seen against the far wall
    door = [300.0, 30.0, 340.0, floor_line[1] + 4.0]  # its foot on the floor line, about
    books = [300.0, 380.0, 340.0, 420.0]  # on a table near the camera: floor behind them
    assert seen_against_the_floor(down, room, [picture, door, books]) == [False, False, True]
    assert seen_against_the_floor(None, room, [books]) == [False]
    assert seen_against_the_floor(down, None, [books]) == [False]


def test_books_on_a_real_coffee_table_are_not_hung_on_the_wall(real_photos: Path) -> None:
    """im3d-1's o3 (books on the table in the middle of the room): the Relation Network
    hung them on the wall."""
    scene = reconstruct_scene(
        read_input_folder(real_photos / "im3d-1"), name="im3d-1", image_file="img.jpg"
    ).scene
    support = next(s for s in scene.supports if s.child == "o3")
    assert support.parent != "wall"


def test_a_region_high_on_a_real_wall_is_not_stood_on_the_floor(real_photos: Path) -> None:
    """im3d-3's o13 (the dataset's "void", top left, bottom edge well above the horizon):
    the Relation Network said floor; placement then had no 3D box for it."""
    scene = reconstruct_scene(
        read_input_folder(real_photos / "im3d-3"), name="im3d-3", image_file="img.jpg"
    ).scene
    support = next(s for s in scene.supports if s.child == "o13")
    assert (support.parent, support.type) == ("wall", "behind")
    assert next(o for o in scene.objects if o.id == "o13").box_3d is not None

"""The held-out split: fixed by a key per scene, and scenes of one photo on one side."""

from __future__ import annotations

from collections.abc import Iterator

import cv2
import numpy as np
import pytest
from holiscene.core.settings import Settings
from holiscene.inputs import InputFiles, load_photo
from holiscene.services.heldout import heldout_split
from holiscene.services.workbench import Workbench
from holiscene.store.scenes import SceneStore
from holiscene.store.tables import SceneRow
from sqlalchemy import update
from sqlalchemy.orm import Session

from ..stored_scenes import make_scene


def test_heldout_split_is_fixed_by_scene_id() -> None:
    ids = [f"scene{i:02d}" for i in range(30)]
    train, held = heldout_split(ids)
    assert sorted(train + held) == sorted(ids) and not set(train) & set(held)
    assert 2 <= len(held) <= 12  # about a fifth
    assert heldout_split(list(reversed(ids)))[1] == list(reversed(held))
    # Adding scenes never moves a scene to the other side.
    more_train, more_held = heldout_split([*ids, *(f"new{i}" for i in range(20))])
    assert set(held) <= set(more_held) and set(train) <= set(more_train)
    for pair in (["a", "b"], ["x1", "x2"]):
        train, held = heldout_split(pair)
        assert len(train) == 1 and len(held) == 1
    assert heldout_split(["only"]) == (["only"], [])


def test_scenes_with_one_split_key_go_to_one_side() -> None:
    ids = [f"scene{i:02d}" for i in range(30)]
    _, held = heldout_split(ids)
    # Each held-out scene has a copy (a re-import) keyed to it, and so does a trained one.
    trained_original = next(i for i in ids if i not in held)
    copies = {f"copy-of-{i}": i for i in [*held, trained_original]}
    train, held_with_copies = heldout_split([*ids, *copies], copies)
    assert set(held_with_copies) == set(held) | {c for c, i in copies.items() if i in held}
    assert f"copy-of-{trained_original}" in train
    # Scenes of one photo: none can be held out without its twin being trained on. Whichever
    # side that photo's key hashes to.
    for key in (f"photo{i}" for i in range(20)):
        assert heldout_split(["a", "b"], {"a": key, "b": key}) == (["a", "b"], [])


def _photo(shade: int) -> bytes:
    ok, data = cv2.imencode(".png", np.full((48, 64, 3), shade, np.uint8))
    assert ok
    return bytes(data.tobytes())


def _store(scenes: SceneStore, png: bytes, name: str) -> str:
    scene = make_scene([]).model_copy(update={"name": name})
    inputs = InputFiles(photo=load_photo(png), K=None, detections=None)
    return scenes.create(inputs, scene, "test").id


@pytest.fixture()
def scenes(settings: Settings) -> Iterator[SceneStore]:
    workbench = Workbench(settings)
    yield workbench.scenes
    workbench.close()


@pytest.mark.both_databases
def test_a_scene_imported_again_is_keyed_to_the_first_scene_of_its_photo(
    scenes: SceneStore,
) -> None:
    first = _store(scenes, _photo(100), "kitchen")
    other = _store(scenes, _photo(150), "bedroom")
    again = _store(scenes, _photo(100), "kitchen, edited and imported again")
    keys = scenes.split_keys([again, other, first])
    assert keys == {first: first, other: other, again: first}
    # Scenes stored before photos had digests get theirs from their files (when a store of
    # this version first opens the database).
    with Session(scenes.engine) as session, session.begin():
        session.execute(update(SceneRow).values(photo_digest=None))
    scenes = SceneStore(scenes.engine, scenes.files)
    assert scenes.split_keys([again, other]) == {other: other, again: first}
    with Session(scenes.engine) as session:
        assert all(row.photo_digest for row in session.query(SceneRow))

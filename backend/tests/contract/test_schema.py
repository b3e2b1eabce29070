"""The contract: models round-trip, generated files are fresh, the support graph is checked."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from holiscene.inputs import read_input_folder
from holiscene.services.reconstruction import reconstruct_scene
from holiscene_schema import (
    NYU40_CLASSES,
    ClassMapping,
    Scene,
    map_class_name,
    normalise_class_name,
    support_graph_problems,
)
from holiscene_schema.classes import CLASS_ALIASES
from holiscene_schema.export import SCHEMA_DIR, main, render_schemas
from jsonschema import Draft202012Validator
from pydantic import ValidationError


@pytest.fixture()
def scene(t3d5: Path) -> Scene:
    return reconstruct_scene(read_input_folder(t3d5), name="t3d-5", image_file="img.jpg").scene


def test_scene_round_trips_through_json(scene: Scene) -> None:
    text = scene.model_dump_json()
    again = Scene.model_validate_json(text)
    assert again == scene
    assert json.loads(text)["objects"][0]["class"] == scene.objects[0].cls


def test_committed_json_schema_is_fresh() -> None:
    assert main(["--check"]) == 0, "run `make schema`"
    for name, text in render_schemas().items():
        assert (SCHEMA_DIR / name).read_text() == text


def test_scene_json_validates_against_committed_schema(scene: Scene) -> None:
    schema = json.loads((SCHEMA_DIR / "scene.schema.json").read_text())
    errors = list(Draft202012Validator(schema).iter_errors(scene.model_dump(mode="json")))
    assert errors == []
    broken = scene.model_dump(mode="json")
    broken["supports"][0]["type"] = "above"
    assert list(Draft202012Validator(schema).iter_errors(broken))


def test_scene_rejects_self_support_and_cycles(scene: Scene) -> None:
    data = scene.model_dump(mode="json")
    data["supports"][0]["parent"] = data["supports"][0]["child"]
    with pytest.raises(ValidationError, match="cannot support itself"):
        Scene.model_validate(data)


@pytest.mark.parametrize(
    ("edges", "expected"),
    [
        ([("a", "floor"), ("b", "a")], []),
        ([("a", "a")], ["cannot support itself"]),
        ([("a", "b"), ("b", "c"), ("c", "a")], ["support cycle"]),
        ([("a", "floor"), ("a", "wall")], ["more than one supporter"]),
        ([("a", "sky")], ["neither an object nor structural"]),
        ([("z", "floor")], ["unknown object"]),
    ],
)
def test_support_graph_problems(edges: list[tuple[str, str]], expected: list[str]) -> None:
    problems = support_graph_problems(["a", "b", "c"], edges)
    assert len(problems) == len(expected)
    for problem, fragment in zip(problems, expected, strict=True):
        assert fragment in problem


def test_class_names_map_to_nyu40() -> None:
    assert normalise_class_name("night_stand") == "night_stand"
    assert normalise_class_name("refridgerator") == "refrigerator"
    assert normalise_class_name("dresser_mirror") == "mirror"
    assert normalise_class_name("Night Stand") == "night_stand"
    assert len(NYU40_CLASSES) == 40
    with pytest.raises(ValueError, match="unknown class name"):
        normalise_class_name("spaceship")


def test_imported_names_map_leniently_and_a_user_map_wins() -> None:
    assert map_class_name("couch") == ClassMapping("sofa", known=True)
    assert map_class_name("Night-Stand") == ClassMapping("night_stand", known=True)
    assert map_class_name("lamps") == ClassMapping("lamp", known=True)  # a plural
    assert map_class_name("books") == ClassMapping("books", known=True)  # NYU-40's own plural
    assert map_class_name("spaceship") == ClassMapping("otherprop", known=False)
    assert map_class_name("Space Ship", {"space_ship": "lamp"}) == ClassMapping("lamp", True)
    assert map_class_name("couch", {"couch": "chair"}) == ClassMapping("chair", True)
    # Every alias names a real NYU-40 class, and no alias hides an NYU-40 name.
    assert set(CLASS_ALIASES.values()) <= set(NYU40_CLASSES)
    assert not set(CLASS_ALIASES) & set(NYU40_CLASSES)
    # The class picker lists a whole-name match first: an alias that is the start of another
    # class's name would come before it when the class is typed ("dress" before "dresser").
    shadowing = {
        alias
        for alias, target in CLASS_ALIASES.items()
        for cls in NYU40_CLASSES
        if cls.startswith(alias) and cls != target
    }
    assert shadowing == {"book"}  # "book" is books, still one key from bookshelf

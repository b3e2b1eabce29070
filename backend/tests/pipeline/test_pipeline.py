"""Pipelines are checked when built; stages keep people's supports and say which of their
notes are warnings."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest
from holiscene.inputs import InputFiles, read_input_folder
from holiscene.learning.runtime import DEFAULT_MODEL_DIR, SupportModel
from holiscene.pipeline import DEFAULT_STAGES, PipelineBuildError, build_pipeline, registered_stages
from holiscene.pipeline.base import Detection
from holiscene.services.reconstruction import reconstruct_scene
from holiscene_schema import SupportRelation


def test_default_pipeline_builds() -> None:
    assert build_pipeline().names == list(DEFAULT_STAGES)


def test_unmet_input_fails_at_build_time() -> None:
    with pytest.raises(PipelineBuildError, match=r"'boxes_on_supporters' requires \['camera'"):
        build_pipeline(["objects_from_detections", "supports_from_priors", "boxes_on_supporters"])


def test_unknown_stage_and_stray_options_fail_at_build_time() -> None:
    with pytest.raises(PipelineBuildError, match="unknown stage"):
        build_pipeline(["objects_from_detections", "grabcut_everything"])
    with pytest.raises(PipelineBuildError, match="not in the pipeline"):
        build_pipeline(["objects_from_detections"], {"intrinsics": {}})
    with pytest.raises(PipelineBuildError, match="takes no options"):
        build_pipeline(["objects_from_detections"], {"objects_from_detections": {"x": 1}})


def test_every_stage_declares_known_slots() -> None:
    for stage in registered_stages().values():
        assert stage.requires and stage.provides


def test_every_class_has_a_structural_supporter_among_its_priors() -> None:
    priors = SupportModel.load(DEFAULT_MODEL_DIR).priors
    for cls in priors.counts:
        assert any(parent in ("floor", "wall") for parent, _, _ in priors.ranked(cls)), cls


def test_a_missing_model_fails_at_build_time(tmp_path: Path) -> None:
    with pytest.raises(PipelineBuildError, match="no Relation Network model"):
        build_pipeline(
            ["objects_from_detections", "masks_from_boxes", "supports_from_network"],
            {"supports_from_network": {"model_dir": tmp_path}},
        )


def test_pinned_supports_are_kept(t3d5: Path) -> None:
    pinned = SupportRelation(child="o1", parent="o0", type="behind", source="manual", author="ann")
    scene = reconstruct_scene(
        read_input_folder(t3d5), name="x", image_file="img.jpg", pinned_supports=[pinned]
    ).scene
    assert next(s for s in scene.supports if s.child == "o1") == pinned


def test_real_photos_get_one_supporter_each_and_floor_furniture(real_photos: Path) -> None:
    floor_classes = {"bed", "sofa", "dresser", "bookshelf", "refrigerator", "table", "desk"}
    for folder in sorted(real_photos.iterdir()):
        scene = reconstruct_scene(
            read_input_folder(folder), name=folder.name, image_file="img.jpg"
        ).scene
        children = [s.child for s in scene.supports]
        assert sorted(children) == sorted(o.id for o in scene.objects), folder.name
        by_child = {s.child: s for s in scene.supports}
        for obj in scene.objects:
            if obj.cls in floor_classes:
                assert by_child[obj.id].parent == "floor", (folder.name, obj.id, obj.cls)


def test_stage_notes_are_warnings_only_when_a_stage_could_not_do_something(t3d5: Path) -> None:
    given = read_input_folder(t3d5)
    full = reconstruct_scene(given, name="x", image_file="img.jpg").scene
    layout = next(run for run in full.stages if run.name == "layout_from_lines")
    assert layout.note and "scale from" in layout.note and not layout.warning
    assert not any(run.warning for run in full.stages if run.note is None)

    bare = InputFiles(photo=given.photo, K=None, detections=None)
    stages = ("objects_from_detections", "intrinsics")
    runs = reconstruct_scene(bare, name="x", image_file="img.jpg", stages=stages).scene.stages
    warnings = {run.name: run.note for run in runs if run.warning}
    assert "no detections.json" in (warnings["objects_from_detections"] or "")
    assert "no cam_K.txt" in (warnings["intrinsics"] or "")


def test_an_empty_detections_file_is_one_warning_that_says_so(t3d5: Path) -> None:
    given = read_input_folder(t3d5)
    empty = InputFiles(photo=given.photo, K=given.K, detections=[])
    scene = reconstruct_scene(empty, name="x", image_file="img.jpg").scene
    assert scene.objects == []
    warnings = {run.name: run.note for run in scene.stages if run.warning}
    assert "lists no objects" in (warnings.pop("objects_from_detector") or "")
    # The later stages have nothing to work on; none of them blames the camera or the room.
    assert "boxes_by_refiner" not in warnings
    assert not any("camera height" in (note or "") for note in warnings.values()), warnings


def test_an_object_without_a_3d_box_is_named_with_the_reason(t3d5: Path) -> None:
    """A chair a person stood on the floor whose bottom edge is high on the wall (above the
    floor's horizon): placement cannot place it, and its warning says why, where it is read."""
    given = read_input_folder(t3d5)
    assert given.detections is not None
    high = Detection(cls="chair", bbox=(300.0, 2.0, 340.0, 30.0))
    chair = f"o{len(given.detections)}"
    on_floor = SupportRelation(child=chair, parent="floor", type="below", source="manual")
    scene = reconstruct_scene(
        dataclasses.replace(given, detections=[*given.detections, high]),
        name="x",
        image_file="img.jpg",
        pinned_supports=[on_floor],
    ).scene
    placement = next(run for run in scene.stages if run.name == "placement")
    assert placement.warning
    assert f"no 3D box for {chair} (its bottom edge does not meet the floor in view)" in (
        placement.note or ""
    )

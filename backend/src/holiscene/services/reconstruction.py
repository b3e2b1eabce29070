"""One photo through the pipeline: the scene document and its GLB."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from holiscene_schema import (
    Camera,
    ImageInfo,
    Layout,
    RemovedObject,
    Scene,
    SceneObject,
    StageRun,
    SupportRelation,
)

from ..geometry.boxes import corners_of
from ..inputs import InputFiles
from ..pipeline import DEFAULT_STAGES, KEPT_LAYOUT_STAGES, SceneContext, build_pipeline
from ..pipeline.runner import ProgressCallback
from ..pipeline.stages.detections import objects_from_detections, unknown_class_note
from ..pipeline.stages.restore import has_hand_set_layout
from ..segmentation.rle import encode_mask

LAYOUT_NOT_ESTIMATED = "the room layout is not estimated by this pipeline yet"

# The stages that run the Relation Network (or its counted priors).
SUPPORT_STAGES = ("supports_from_network", "supports_from_priors")


@dataclass(frozen=True)
class Reconstruction:
    scene: Scene
    glb: bytes | None


def reconstruct_scene(
    inputs: InputFiles,
    *,
    name: str,
    image_file: str,
    pinned_supports: Sequence[SupportRelation] = (),
    pinned_objects: Sequence[SceneObject] = (),
    removed_objects: Sequence[RemovedObject] = (),
    stages: Sequence[str] = DEFAULT_STAGES,
    models_dir: Path | None = None,
    support_model_dir: Path | None = None,
    detector_model_dir: Path | None = None,
    model_names: Mapping[str, str] | None = None,
    stage_options: Mapping[str, Mapping[str, Any]] | None = None,
    progress: ProgressCallback | None = None,
) -> Reconstruction:
    """Run the stages on one photo. `models_dir` holds the user's own models
    (`<class>/*.obj|glb|ply`), offered to `shapes_fit` beside the built-in library;
    `support_model_dir` is the Relation Network to use (default: the committed model),
    `detector_model_dir` the object detector (default: the committed detector);
    `model_names` names them by stage name, as the stage runs record them (a scene says
    which model guessed its supports);
    `pinned_supports`, `pinned_objects` and `removed_objects` are people's, kept by the
    stages;
    `stage_options` adds options by stage name (e.g. the stored scene a placement job
    starts from)."""
    options: dict[str, dict[str, Any]] = {k: dict(v) for k, v in (stage_options or {}).items()}
    if models_dir and "shapes_fit" in stages:
        options["shapes_fit"] = {"models_dir": models_dir}
    for stage in SUPPORT_STAGES:
        if support_model_dir and stage in stages:
            options[stage] = {"model_dir": support_model_dir}
    if detector_model_dir and "objects_from_detector" in stages:
        options.setdefault("objects_from_detector", {})["model_dir"] = detector_model_dir
    pipeline = build_pipeline(stages, options)
    ctx = SceneContext(
        image=inputs.photo.rgb,
        given_K=inputs.K,
        detections=inputs.detections,
        depth=inputs.depth.metres if inputs.depth is not None else None,
        pinned_supports=list(pinned_supports),
        pinned_objects=list(pinned_objects),
        removed_objects=list(removed_objects),
    )
    runs = [
        run.model_copy(update={"model": model_names[run.name]})
        if model_names and run.name in model_names
        else run
        for run in pipeline.run(ctx, progress)
    ]
    if inputs.notes:  # what the import left out of the given labels stays said
        runs = [import_stage("; ".join(inputs.notes)), *runs]
    scene = Scene(
        name=name,
        image=ImageInfo(file=image_file, width=ctx.width, height=ctx.height),
        camera=ctx.camera,
        layout=ctx.layout or Layout(note=LAYOUT_NOT_ESTIMATED),
        depth=inputs.depth.ref() if inputs.depth is not None else None,
        objects=[_finished_object(ctx, obj) for obj in ctx.objects or []],
        supports=ctx.supports or [],
        removed_by_person=ctx.removed_objects,
        stages=runs,
    )
    return Reconstruction(scene=scene, glb=ctx.scene_glb)


def import_stage(note: str) -> StageRun:
    """The import's own warning among a scene's stage runs."""
    return StageRun(name="import", seconds=0.0, note=note, warning=True)


def _finished_object(ctx: SceneContext, obj: SceneObject) -> SceneObject:
    """The object with what the stages computed for it: mask, 3D box, its corners, how sure the
    box is and where its mesh came from."""
    mask = (ctx.masks or {}).get(obj.id)
    fitted = (ctx.object_meshes or {}).get(obj.id)
    box = (ctx.boxes_3d or {}).get(obj.id)
    corners = None
    if box is not None:
        corners = corners_of(box).round(4).tolist()
    return obj.model_copy(
        update={
            "mask": encode_mask(mask.pixels, mask.source) if mask is not None else None,
            "box_3d": box,
            "corners_3d": corners,
            "box_3d_confidence": ctx.box_confidences.get(obj.id) if box is not None else None,
            "mesh": fitted.ref if fitted is not None and box is not None else obj.mesh,
            "note": ctx.object_notes.get(obj.id, obj.note),
        }
    )


def given_camera(inputs: InputFiles) -> Camera | None:
    """The intrinsics given with the photo, before any run: with them the layout editor can
    start a room by hand (pitch and roll come from the pipeline or from that room)."""
    if inputs.K is None:
        return None
    return Camera(K=inputs.K.tolist(), K_source="given", pitch_deg=None, roll_deg=None)


def imported_scene(inputs: InputFiles, name: str) -> Scene:
    """Revision 1 of a scene: the photo and its boxes as given, nothing inferred yet."""
    objects = objects_from_detections(inputs.detections or [])
    image = ImageInfo(
        file=f"img{inputs.photo.suffix}", width=inputs.photo.width, height=inputs.photo.height
    )
    note = "; ".join(
        [n for n in [unknown_class_note(inputs.detections or [])] if n] + list(inputs.notes)
    )
    # The import's own note, shown with the pipeline's warnings until a run replaces them.
    stages = [import_stage(note)] if note else []
    # Supports given with the photo are people's labels (a pipeline run keeps them) or, from
    # an export, the pipeline's guesses. An exported scene's camera and layout (scene.json)
    # start revision 1 as they were; a layout set by hand is kept by the pipeline then.
    return Scene(
        name=name,
        image=image,
        camera=inputs.camera or given_camera(inputs),
        layout=inputs.layout or Layout(),
        depth=inputs.depth.ref() if inputs.depth is not None else None,
        objects=objects,
        supports=list(inputs.supports),
        stages=stages,
    )


def full_run_stages(scene: Scene) -> tuple[tuple[str, ...], dict[str, dict[str, Any]] | None]:
    """The stages of a full pipeline run on `scene`, and their options: a room layout set by
    hand (and the camera fitted to it) is kept, as people's supports are."""
    if has_hand_set_layout(scene):
        return KEPT_LAYOUT_STAGES, {"layout_from_revision": {"scene": scene}}
    return DEFAULT_STAGES, None

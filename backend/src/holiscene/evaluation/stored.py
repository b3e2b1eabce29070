"""`holiscene eval --store`: the stored scenes that came with ground truth (gt.json beside the
scene, store/files.py) scored with the thesis's metrics.

Two things can be scored against the ground truth: a scene's current revision (what people
and the pipeline have now), or the pipeline run afresh on the scene's stored photo, intrinsics
and boxes with none of people's labels (the thesis's tables: what the method does alone).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from holiscene_schema import Scene
from pydantic import ValidationError

from ..core.settings import Settings
from ..store.model_registry import active_model_dir
from ..store.scenes import SceneStore
from .metrics import Evaluation


@dataclass(frozen=True)
class Rerun:
    """What a re-run uses: the active Relation Network and detector of the store's registry
    (None: the committed ones, as for a pipeline job) and the user's own shapes."""

    support_model_dir: Path | None = None
    detector_model_dir: Path | None = None
    models_dir: Path | None = None
    # False: the single-photo path even where the scene's folder holds depth.png.
    use_depth: bool = True

    def describe(self) -> dict[str, str]:
        def name(folder: Path | None) -> str:
            return f"model {folder.name}" if folder is not None else "the committed model"

        return {
            "relation_network": name(self.support_model_dir),
            "detector": name(self.detector_model_dir),
        }


def active_rerun(settings: Settings, use_depth: bool = True) -> Rerun:
    """The models a pipeline job of this store would use now."""
    return Rerun(
        active_model_dir(settings, "relation"),
        active_model_dir(settings, "detector"),
        settings.models_dir,
        use_depth,
    )


@dataclass(frozen=True)
class StoredScene:
    scene_id: str
    name: str
    revision: int  # the revision scored, or the one whose inputs the re-run started from


@dataclass
class StoredEvaluation:
    rerun: Rerun | None
    evaluation: Evaluation = field(default_factory=Evaluation)
    scored: list[StoredScene] = field(default_factory=list)
    without_truth: list[StoredScene] = field(default_factory=list)
    # scene id -> why it could not be scored (unreadable gt.json) or why its re-run failed
    # (then scored as an empty prediction, as a crashed pipeline must not look better)
    errors: dict[str, str] = field(default_factory=dict)

    def summary(self) -> dict[str, Any]:
        def listed(items: list[StoredScene]) -> list[dict[str, Any]]:
            return [{"id": s.scene_id, "name": s.name, "revision": s.revision} for s in items]

        summary = self.evaluation.summary()
        summary["store"] = {
            "scored": "pipeline re-run" if self.rerun else "current revision",
            "models": self.rerun.describe() if self.rerun else None,
            "scenes": listed(self.scored),
            "skipped_without_ground_truth": listed(self.without_truth),
            "errors": self.errors,
        }
        return summary


def evaluate_stored(
    scenes: SceneStore,
    scene_ids: Sequence[str],
    rerun: Rerun | None = None,
    progress: Callable[[str], object] = lambda _scene_id: None,
) -> StoredEvaluation:
    """Score each scene that has gt.json; the others are listed as skipped. `progress` is
    called after each scene. An unknown id raises SceneNotFoundError before any scoring."""
    for scene_id in scene_ids:
        scenes.summary(scene_id)
    run = StoredEvaluation(rerun)
    for scene_id in scene_ids:
        _evaluate_one(scenes, scene_id, run)
        progress(scene_id)
    return run


def _evaluate_one(scenes: SceneStore, scene_id: str, run: StoredEvaluation) -> None:
    current = scenes.document(scene_id)
    item = StoredScene(scene_id, current.scene.name, current.revision)
    truth_file = scenes.files.ground_truth_path(scene_id)
    if not truth_file.is_file():
        run.without_truth.append(item)
        return
    try:
        truth = Scene.model_validate_json(truth_file.read_text())
    except (OSError, ValidationError) as exc:
        run.errors[scene_id] = f"{truth_file} is not a valid scene: {exc}"
        return
    predicted = current.scene
    if run.rerun is not None:
        try:
            predicted = _rerun(scenes, scene_id, current.scene, run.rerun)
        except Exception as exc:  # any stage's failure is this scene's, the others go on
            run.errors[scene_id] = f"the pipeline failed ({type(exc).__name__}: {exc})"
            predicted = Scene(name=truth.name, image=truth.image)
    run.evaluation.add(predicted, truth)
    run.scored.append(item)


def _rerun(scenes: SceneStore, scene_id: str, current: Scene, rerun: Rerun) -> Scene:
    """The pipeline on the scene's folder (an input folder: photo, cam_K.txt, detections.json)
    with nothing people set pinned: no supports, objects or removals of theirs."""
    from ..inputs import read_input_folder
    from ..services.reconstruction import reconstruct_scene

    result = reconstruct_scene(
        read_input_folder(scenes.files.folder(scene_id), use_depth=rerun.use_depth),
        name=current.name,
        image_file=current.image.file,
        models_dir=rerun.models_dir,
        support_model_dir=rerun.support_model_dir,
        detector_model_dir=rerun.detector_model_dir,
    )
    return result.scene


def markdown_scene_list(run: StoredEvaluation) -> str:
    """The report's part on which stored scenes were scored, skipped or failed."""
    lines = ["", "## Scenes", ""]
    if run.rerun is not None:
        models = run.rerun.describe()
        lines += [
            "The pipeline ran afresh on each scene's stored photo, intrinsics and boxes, "
            f"without people's labels (Relation Network: {models['relation_network']}; "
            f"detector: {models['detector']}).",
            "",
        ]
    lines += ["| scene | name | revision |", "| --- | --- | --- |"]
    lines += [f"| {s.scene_id} | {s.name} | {s.revision} |" for s in run.scored]
    if run.without_truth:
        skipped = ", ".join(f"{s.scene_id} ({s.name})" for s in run.without_truth)
        lines += ["", f"Skipped, no ground truth: {skipped}."]
    for scene_id, why in run.errors.items():
        lines += ["", f"Error in {scene_id}: {why}"]
    return "\n".join(lines) + "\n"

"""Each placed box filled with a model: library variants and user models, chosen by silhouette.

See `holiscene.placement.shape_choice`: four turns of the model about the box's vertical axis
and a few variants of the class (seeds of the shape library, plus the user's models from the
`models_dir` option: `<models_dir>/<class>/*.obj|glb|ply`) are compared by IoU of their
projected silhouette with the mask; the best is fitted into the box. Its MeshRef says where it
came from (builtin class + seed, or user file).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ...placement.projection import MaskTarget
from ...placement.room import pinhole, projection_matrix
from ...placement.shape_choice import UserModel, fit_model, load_user_models
from ..base import ObjectMesh, PipelineBuildError, SceneContext, Stage, required
from ..registry import register_stage


@register_stage
class ShapesFit(Stage):
    name = "shapes_fit"
    requires = frozenset({"objects", "masks", "camera", "boxes_3d"})
    provides = frozenset({"object_meshes"})

    def __init__(
        self, models_dir: str | Path | None = None, seeds: int = 3, max_side: int = 96, **rest: Any
    ) -> None:
        super().__init__(**rest)
        if seeds < 0 or max_side < 8:
            raise PipelineBuildError(f"stage {self.name!r}: seeds >= 0 and max_side >= 8")
        self.seeds = int(seeds)
        self.max_side = int(max_side)
        self.user_models: dict[str, list[UserModel]] = {}
        if models_dir is not None:
            try:
                self.user_models = load_user_models(Path(models_dir))
            except (FileNotFoundError, ValueError) as error:
                raise PipelineBuildError(f"stage {self.name!r}: {error}") from error

    def run(self, ctx: SceneContext) -> None:
        objects = required(ctx.objects, "objects")
        masks = required(ctx.masks, "masks")
        boxes = required(ctx.boxes_3d, "boxes_3d")
        camera = pinhole(required(ctx.camera, "camera"))
        ctx.object_meshes = {}
        if camera is None:
            ctx.notes[self.name] = "camera pitch and roll unknown: no models"
            return
        projection = projection_matrix(camera)
        skipped = []
        for obj in objects:
            box = boxes.get(obj.id)
            if box is None:
                continue  # the placement stage has said why
            users = self.user_models.get(obj.cls, [])
            if self.seeds == 0 and not users:
                skipped.append(obj.id)
                continue
            mask = masks.get(obj.id)
            if mask is None or not mask.pixels.any():
                skipped.append(obj.id)
                continue
            target = MaskTarget(mask.pixels, max_side=self.max_side)
            fitted = fit_model(
                obj.cls, box, target, projection, self.seeds, users, int(mask.pixels.sum())
            )
            ctx.object_meshes[obj.id] = ObjectMesh(mesh=fitted.mesh, ref=fitted.ref)
        if skipped:
            ctx.notes[self.name] = f"boxes kept for {', '.join(skipped)} (no mask or no model)"

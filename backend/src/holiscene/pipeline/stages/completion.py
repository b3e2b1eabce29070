"""Completed shapes from depth (thesis Ch. 6, SK-PCN): after `shapes_fit`, every object whose
mask holds enough depth points inside its 3D box gets the mesh the completion network makes
of them (`learning.completion`), in place of the earlier mesh (the library's or the mesh
network's); the others keep theirs.

Runs only when the photo came with depth (`Stage.needs_depth`).
"""

from __future__ import annotations

from holiscene_schema import MeshRef

from ...learning.completion.runtime import MIN_OBSERVED_POINTS, completer
from ...placement.depth_box import object_points
from ...placement.room import pinhole
from ..base import ObjectMesh, SceneContext, Stage, required
from ..registry import register_stage


@register_stage
class ShapeCompletion(Stage):
    name = "shape_completion"
    requires = frozenset({"objects", "masks", "camera", "boxes_3d", "object_meshes"})
    provides = frozenset({"object_meshes"})
    needs_depth = True

    def run(self, ctx: SceneContext) -> None:
        depth = required(ctx.depth, "depth")
        masks = required(ctx.masks, "masks")
        boxes = required(ctx.boxes_3d, "boxes_3d")
        meshes = dict(required(ctx.object_meshes, "object_meshes"))
        camera = pinhole(required(ctx.camera, "camera"))
        if camera is None:
            ctx.notes[self.name] = "camera pitch and roll unknown: no completion"
            return
        model = completer()
        done, too_few = [], []
        for obj in required(ctx.objects, "objects"):
            box, mask = boxes.get(obj.id), masks.get(obj.id)
            if box is None or mask is None:
                continue
            points = object_points(mask.pixels, depth, camera)
            result = model.complete(points, box) if points is not None else None
            if result is None:
                too_few.append(obj.id)
                continue
            ref = MeshRef(library="completion", cls=obj.cls)
            meshes[obj.id] = ObjectMesh(mesh=result.mesh, ref=ref)
            done.append(obj.id)
        ctx.object_meshes = meshes
        ctx.reports[self.name] = f"{len(done)} of {len(done) + len(too_few)} objects completed"
        if too_few:
            # Those keep the mesh an earlier stage gave them: the library's or the mesh
            # network's (the object list's badge says which).
            ctx.notes[self.name] = (
                f"not completed from depth, their earlier meshes kept: {', '.join(too_few)} "
                f"(fewer than {MIN_OBSERVED_POINTS} depth points in the box)"
            )

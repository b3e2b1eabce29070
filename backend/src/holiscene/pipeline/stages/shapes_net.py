"""Meshes from the mesh network (thesis Ch. 5, MGN; `learning.mesh_net`): after `shapes_fit`,
every object of a class the network knows gets its class template deformed to what its mask
shows, in place of the library model; the others keep theirs. With depth, `shape_completion`
runs after it and replaces the meshes of the objects it can complete.
"""

from __future__ import annotations

from holiscene_schema import MeshRef

from ...learning.mesh_net.runtime import mesh_generator
from ...placement.room import pinhole, projection_matrix
from ..base import ObjectMesh, SceneContext, Stage, required
from ..registry import register_stage


@register_stage
class ShapesByMeshNet(Stage):
    name = "shapes_by_mesh_net"
    requires = frozenset({"objects", "masks", "camera", "boxes_3d", "object_meshes"})
    provides = frozenset({"object_meshes"})

    def run(self, ctx: SceneContext) -> None:
        masks = required(ctx.masks, "masks")
        boxes = required(ctx.boxes_3d, "boxes_3d")
        meshes = dict(required(ctx.object_meshes, "object_meshes"))
        camera = pinhole(required(ctx.camera, "camera"))
        if camera is None:
            ctx.notes[self.name] = "camera pitch and roll unknown: library models kept"
            return
        projection = projection_matrix(camera)
        generator = mesh_generator()
        done = 0
        for obj in required(ctx.objects, "objects"):
            box, mask = boxes.get(obj.id), masks.get(obj.id)
            if box is None or mask is None or obj.id not in meshes:
                continue
            generated = generator.generate(obj.cls, box, mask.pixels, projection)
            if generated is None:
                continue
            meshes[obj.id] = ObjectMesh(
                mesh=generated.mesh, ref=MeshRef(library="learned", cls=obj.cls)
            )
            done += 1
        ctx.object_meshes = meshes
        ctx.reports[self.name] = f"{done} of {len(meshes)} meshes made by the mesh network"

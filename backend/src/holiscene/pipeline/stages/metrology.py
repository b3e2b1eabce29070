"""Object heights by single-view metrology along the support order (thesis Eq. 4.3).

See `holiscene.placement.metrology`: each object's height line (the longest vertical edge of
its mask, by rays from the vertical vanishing point) is carried onto the room's height line
and measured by cross ratio, from the floor up; an object supported from below starts at its
supporter's top. Estimates outside three standard deviations of the class's height prior are
replaced by the prior's mean (thesis Appendix B.2); the stage note lists those objects,
grouped by why (on a crowded photo most chairs can fail the same way: one line per reason
reads better than one per chair).
"""

from __future__ import annotations

import numpy as np
from holiscene_schema import SupportRelation

from ...placement.metrology import (
    OUTSIDE_PRIOR,
    HeightEstimate,
    HeightMeter,
    height_prior,
    room_reference,
)
from ...placement.room import pinhole, projection_matrix, room_of
from ...placement.support_order import supporters_first
from ..base import SceneContext, Stage, required
from ..registry import register_stage


@register_stage
class HeightsByMetrology(Stage):
    name = "heights_by_metrology"
    requires = frozenset({"objects", "masks", "camera", "layout", "vanishing_points", "supports"})
    provides = frozenset({"heights"})

    def run(self, ctx: SceneContext) -> None:
        objects = required(ctx.objects, "objects")
        if not objects:
            ctx.heights = {}
            return
        masks = required(ctx.masks, "masks")
        camera = pinhole(required(ctx.camera, "camera"))
        room = room_of(required(ctx.layout, "layout"))
        vps = np.asarray(required(ctx.vanishing_points, "vanishing_points"), dtype=float)
        support_of: dict[str, SupportRelation] = {
            s.child: s for s in required(ctx.supports, "supports")
        }
        ctx.heights = {}
        reference = None
        projection = None
        if camera is not None and room is not None and vps.shape == (3, 3):
            projection = projection_matrix(camera)
            reference = room_reference(projection, room, vps, (ctx.width, ctx.height))
        if reference is None or room is None or projection is None or not masks:
            for obj in objects:
                ctx.heights[obj.id] = height_prior(obj.cls)[0]
            ctx.notes[self.name] = (
                "no object has a mask: every height is its class's prior mean"
                if not masks
                else "no room height line (camera, layout or vanishing points missing): "
                "every height is its class's prior mean"
            )
            return
        meter = HeightMeter(
            reference,
            room,
            projection,
            {obj_id: m.pixels for obj_id, m in masks.items()},
            {o.id: o.cls for o in objects},
            support_of,
            vps[1:],
        )
        estimates: dict[str, HeightEstimate] = {}
        for obj in supporters_first(objects, support_of):
            estimates[obj.id] = meter.measure(obj.id)
            ctx.heights[obj.id] = round(estimates[obj.id].height, 4)
        note = fallback_note(estimates, [o.id for o in objects])
        if note:
            ctx.notes[self.name] = note


def fallback_note(estimates: dict[str, HeightEstimate], order: list[str]) -> str | None:
    """The objects not measured, grouped by reason, in the scene's order ("2 of 9 objects given
    their class's typical height instead (measured outside its class's range: o1 0.11 m;
    bottom hidden: o6)"), then those whose top is hidden; None when every object was measured.
    """
    by_reason: dict[str, list[str]] = {}
    for obj_id in order:
        estimate = estimates.get(obj_id)
        if estimate is None or estimate.source != "prior":
            continue
        shown = obj_id
        if estimate.reason == OUTSIDE_PRIOR and estimate.measured is not None:
            shown = f"{obj_id} {estimate.measured:.2f} m"
        by_reason.setdefault(estimate.reason or "not measured", []).append(shown)
    bounds = [i for i in order if i in estimates and estimates[i].source == "lower_bound"]
    parts = []
    if by_reason:
        fallen = sum(len(ids) for ids in by_reason.values())
        groups = "; ".join(f"{reason}: {', '.join(ids)}" for reason, ids in by_reason.items())
        parts.append(
            f"{fallen} of {len(order)} objects given their class's typical height instead "
            f"({groups})"
        )
    if bounds:
        parts.append("top hidden, so at least their class's typical height: " + ", ".join(bounds))
    return "; ".join(parts) or None

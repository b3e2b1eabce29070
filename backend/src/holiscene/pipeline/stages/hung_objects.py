"""The room's walls moved to the things hung on them (pictures, windows, doors, televisions
on a wall): out behind them, or in to them, after the box refiner.

The refiner often puts a thing on a wall farther than the estimated wall, and it is more
often right than the wall: moving those things back onto the wall finds fewer true boxes
(docs/benchmarks.md, "Learned box refinement"). A picture behind its wall is also hidden in
the 3D view. So the wall follows the thing: each wall moves out along its normal until every
box hung on a wall is inside the room. And the other way: a wall something hangs on (the
wall nearest the hung box) moves in until the nearest box touches it, so that a picture
does not float in front of its wall (every box stays inside; layout IoU 71.6 -> 72.2 on the
40 held-out rooms of seed 950000). The walls' distances out of view are priors anyway
(docs/benchmarks.md, "Where the layout IoU goes"), and what hangs on a wall is evidence of
where that wall is.

A layout set by a person or taken from the ground truth is kept as it is. The stage is not
in a placement job (`PLACEMENT_STAGES`): there the walls it moved are the stored layout, and
moving them again after each placement would let the room grow job by job.
"""

from __future__ import annotations

import numpy as np

from ...geometry.boxes import corners_of
from ...placement.room import narrowed_to_hung, pinhole, widened_to_hold
from ..base import SceneContext, Stage, required
from ..registry import register_stage
from .layout import image_corners

# The layout is rewritten only when a wall moves at least this far: a box touching its wall
# within rounding is no reason to.
MIN_MOVE_M = 0.005
# A wall moved in to what hangs on it stays at least this far from the camera (which is in
# the room).
CAMERA_GAP_M = 0.3


@register_stage
class LayoutHoldsHungObjects(Stage):
    name = "layout_holds_hung_objects"
    requires = frozenset({"camera", "layout", "supports", "boxes_3d"})
    provides = frozenset({"layout"})
    single_photo_only = True  # with depth, the walls it sees are measured

    def run(self, ctx: SceneContext) -> None:
        layout = required(ctx.layout, "layout")
        camera = pinhole(required(ctx.camera, "camera"))
        if layout.corners_3d is None or camera is None:
            ctx.reports[self.name] = "no room or no camera pitch and roll: no wall to move"
            return
        if layout.source != "estimated":
            source = layout.source or "no source"
            ctx.reports[self.name] = f"the layout is not an estimate ({source}): kept as it is"
            return
        boxes = required(ctx.boxes_3d, "boxes_3d")
        hung = [
            corners_of(box)
            for s in required(ctx.supports, "supports")
            if s.parent == "wall" and (box := boxes.get(s.child)) is not None
        ]
        placed = [corners_of(box) for box in boxes.values() if box is not None]
        corners, outs = widened_to_hold(np.array(layout.corners_3d, dtype=float), hung)
        corners, ins = narrowed_to_hung(corners, hung, placed, CAMERA_GAP_M)
        moved_out = [m for m in outs if m >= MIN_MOVE_M]
        moved_in = [m for m in ins if m >= MIN_MOVE_M]
        if not moved_out and not moved_in:
            ctx.reports[self.name] = (
                f"every box hung on a wall ({len(hung)}) is inside the room, on its wall"
                if hung
                else "no box hung on a wall"
            )
            return
        said = "; ".join(
            [
                *(
                    [f"{len(moved_out)} wall(s) moved out by up to {max(moved_out):.2f} m"]
                    if moved_out
                    else []
                ),
                *(
                    [f"{len(moved_in)} wall(s) moved in by up to {max(moved_in):.2f} m"]
                    if moved_in
                    else []
                ),
            ]
        )
        said += " to meet what hangs on them"
        stored = corners.round(4)
        ctx.layout = layout.model_copy(
            update={
                "corners_3d": stored.tolist(),
                "corners_2d": image_corners(camera, stored),
                "note": f"{layout.note}; {said}" if layout.note else said,
            }
        )
        ctx.reports[self.name] = said

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

Last, each wall moves out until the middle half of every box standing on the floor is inside
the room: no floor-standing thing lies mostly beyond a wall (layout IoU +0.35, +0.11 and
+0.02 points on 40, 80 and 40 rooms of seeds 950000, 980000 and 1, where holding the whole
boxes lost 0.5 points on the 80, the boxes' own errors moving walls out).

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


def middle_half(corners: np.ndarray) -> np.ndarray:
    """A box's corners pulled halfway to its centre: the part of a standing object the walls
    must hold. An estimated box may reach through its wall by a little (its distance is a few
    percent off); more than a quarter of its size says the wall is wrong."""
    result: np.ndarray = (corners + corners.mean(axis=0, keepdims=True)) / 2
    return result


def _moved(moves: list[float], how: str) -> str:
    """'2 wall(s) moved out by up to 0.45 m ...' for the moves that count; '' for none."""
    counted = [m for m in moves if m >= MIN_MOVE_M]
    return f"{len(counted)} wall(s) {how.format(max(counted))}" if counted else ""


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
        standing = [
            middle_half(corners_of(box))
            for s in required(ctx.supports, "supports")
            if s.parent == "floor" and (box := boxes.get(s.child)) is not None
        ]
        corners, outs = widened_to_hold(np.array(layout.corners_3d, dtype=float), hung)
        corners, ins = narrowed_to_hung(corners, hung, placed, CAMERA_GAP_M)
        corners, outs_standing = widened_to_hold(corners, standing)
        said = "; ".join(
            described
            for moves, how in (
                (outs, "moved out by up to {:.2f} m to meet what hangs on them"),
                (ins, "moved in by up to {:.2f} m to meet what hangs on them"),
                (outs_standing, "moved out by up to {:.2f} m to hold what stands on the floor"),
            )
            if (described := _moved(moves, how))
        )
        if not said:
            ctx.reports[self.name] = (
                f"every box hung on a wall ({len(hung)}) is inside the room, on its wall"
                if hung
                else "no box hung on a wall"
            )
            return
        stored = corners.round(4)
        ctx.layout = layout.model_copy(
            update={
                "corners_3d": stored.tolist(),
                "corners_2d": image_corners(camera, stored),
                "note": f"{layout.note}; {said}" if layout.note else said,
            }
        )
        ctx.reports[self.name] = said

"""What the geometry rules out before support scores are decoded, shared by the pipeline's
support stages (backend `pipeline/stages/supports.py`, `geometry/metric_scale.py`) and the
browser's live suggestions (frontend `inference/supportGeometry.ts`), so both rule out the
same supporters on the same photo.

- The floor holds up from below nothing whose bottom edge is above its horizon (the ray
  through the middle of the edge drops less than FLOOR_RAY_MIN_DROP_DEG), unless another box
  starts within HIDING_GAP of the photo's height below that edge (or above it) and reaches
  lower across HIDING_OVERLAP of its width: it may hide a lower bottom.
- Nor anything that, standing where its bottom edge meets the floor, would span more floor or
  rise higher (camera heights) than TOO_LARGE_LIMITS allows its class, unless other objects'
  pixels fill the strip HIDING_GAP below its bottom edge across PIXELS_HIDING_SHARE of its
  width, or the photo's bottom edge cuts that strip. A limit is 1.5 times the class's largest
  size (footprint diagonal, height) over the lowest believable camera height (0.87 m); the
  backend's tests hold the table to the furniture library's sizes.
- Such an object is held up by a wall, the ceiling, or an object spanning SUPPORTER_OVERLAP of
  its width.
- No wall holds up from behind an object seen against the floor: the ray through the middle
  of its bottom edge meets the room's floor FLOOR_BEFORE_WALL times nearer than the wall it
  leaves the room through (the camera inside the room).
"""

from __future__ import annotations

from typing import Any

FLOOR_RAY_MIN_DROP_DEG = 1.0
HIDING_GAP = 0.03
HIDING_OVERLAP = 0.3
PIXELS_HIDING_SHARE = 0.6
SUPPORTER_OVERLAP = 0.3
FLOOR_BEFORE_WALL = 1.6

# Class -> (floor span, rise), in camera heights; classes of any size (otherprop,
# otherfurniture, otherstructure) and those without sizes are never judged.
TOO_LARGE_LIMITS: dict[str, tuple[float, float]] = {
    "bag": (1.057, 0.866),
    "bathtub": (3.447, 1.125),
    "bed": (5.148, 2.078),
    "blinds": (3.466, 3.117),
    "books": (1.125, 0.519),
    "bookshelf": (2.19, 3.809),
    "box": (1.469, 0.866),
    "cabinet": (2.323, 3.463),
    "chair": (1.532, 1.905),
    "clothes": (1.489, 1.385),
    "counter": (5.334, 1.645),
    "curtain": (4.343, 4.502),
    "desk": (3.411, 1.351),
    "door": (1.766, 3.809),
    "dresser": (2.959, 2.251),
    "floor_mat": (6.243, 0.035),
    "lamp": (1.224, 2.944),
    "mirror": (1.734, 2.77),
    "night_stand": (1.352, 1.212),
    "paper": (0.735, 0.052),
    "person": (1.178, 3.29),
    "picture": (2.08, 1.732),
    "pillow": (1.561, 0.346),
    "refrigerator": (2.15, 3.376),
    "shelves": (2.219, 3.117),
    "shower_curtain": (3.128, 3.463),
    "sink": (1.732, 1.645),
    "sofa": (4.823, 1.645),
    "table": (3.565, 1.351),
    "television": (2.462, 1.558),
    "toilet": (1.514, 1.472),
    "towel": (1.224, 1.385),
    "whiteboard": (4.157, 2.078),
    "window": (3.502, 2.77),
}


def support_geometry_contract() -> dict[str, Any]:
    """The figures above, for the TypeScript twin (vocabulary.json)."""
    return {
        "floor_ray_min_drop_deg": FLOOR_RAY_MIN_DROP_DEG,
        "hiding_gap": HIDING_GAP,
        "hiding_overlap": HIDING_OVERLAP,
        "pixels_hiding_share": PIXELS_HIDING_SHARE,
        "supporter_overlap": SUPPORTER_OVERLAP,
        "floor_before_wall": FLOOR_BEFORE_WALL,
        "too_large_limits": {cls: list(limits) for cls, limits in TOO_LARGE_LIMITS.items()},
    }

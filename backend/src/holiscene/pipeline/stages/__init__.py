"""Built-in stages; importing this package registers them."""

from . import boxes, camera, detections, layout, masks, mesh, supports

__all__ = ["boxes", "camera", "detections", "layout", "masks", "mesh", "supports"]

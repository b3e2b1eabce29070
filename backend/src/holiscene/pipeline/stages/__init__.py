"""Built-in stages; importing this package registers them."""

from . import boxes, camera, detections, detector, layout, masks, mesh, supports
from .box_refiner import BoxesByRefiner  # noqa: F401
from .completion import ShapeCompletion  # noqa: F401
from .depth_boxes import BoxesFromDepth  # noqa: F401
from .depth_layout import LayoutFromDepth  # noqa: F401
from .grabcut import MasksGrabCut  # noqa: F401
from .hung_objects import LayoutHoldsHungObjects  # noqa: F401
from .metrology import HeightsByMetrology  # noqa: F401
from .placement import PlacementStage  # noqa: F401
from .restore import SceneFromRevision  # noqa: F401
from .scene_net import BoxesByNetwork, LayoutByNetwork  # noqa: F401
from .shapes_fit import ShapesFit  # noqa: F401
from .shapes_net import ShapesByMeshNet  # noqa: F401

__all__ = [
    "boxes",
    "camera",
    "detections",
    "detector",
    "layout",
    "masks",
    "mesh",
    "supports",
]

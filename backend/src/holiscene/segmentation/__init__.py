"""Image segmentation helpers that know nothing of the pipeline."""

from .grabcut import BoxCut, grabcut_in_box

__all__ = ["BoxCut", "grabcut_in_box"]

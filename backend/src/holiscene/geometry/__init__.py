"""Camera and box geometry shared by the pipeline stages.

The world frame and the camera's pitch and roll: docs/architecture.md, "Conventions".
"""

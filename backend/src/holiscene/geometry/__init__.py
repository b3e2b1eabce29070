"""Camera and box geometry shared by the pipeline stages (world frame: see DESIGN.md)."""

"""Files the pipeline writes for other tools: GLB scenes."""

"""The reviewer's viser viewer: a scene's room, meshes, camera with photo and support arrows.

- `sources`: load a scene (a scene.json path or a stored scene id) with its photo and GLB.
- `geometry`, `meshes`: what to draw, as numbers (no viser).
- `scene_viewer`: the viser nodes and the review panel.
- `server`: a viewer on 127.0.0.1 for `holiscene view`, a pool of them for the web app.
"""

from .scene_viewer import SceneViewer
from .server import HOST, ViewerPool, start_viewer, viewer_url
from .sources import (
    ViewerInput,
    ViewerInputError,
    load_scene_path,
    load_stored_scene,
    open_store,
)

__all__ = [
    "HOST",
    "SceneViewer",
    "ViewerInput",
    "ViewerInputError",
    "ViewerPool",
    "load_scene_path",
    "load_stored_scene",
    "open_store",
    "start_viewer",
    "viewer_url",
]

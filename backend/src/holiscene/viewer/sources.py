"""Where a viewed scene comes from: a scene.json on disk, or a scene stored by the workbench.

Either way the viewer gets the same `ViewerInput`: the scene, its photo (RGB, or None with a
note), its GLB bytes (or None) and its depth in metres (or None). Nothing here knows about
viser.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from holiscene_schema import Scene
from numpy.typing import NDArray
from pydantic import ValidationError

from ..core.settings import Settings
from ..inputs import InputError, load_photo
from ..learning.completion.scene_points import stored_depth
from ..store.scenes import SceneNotFoundError, SceneStore

SCENE_FILE_NAMES = ("scene.json", "gt.json")  # what `infer` and `synth` write


class ViewerInputError(Exception):
    """A scene that cannot be shown; the message is for the user."""


@dataclass(frozen=True)
class ViewerInput:
    scene: Scene
    photo: NDArray[np.uint8] | None  # (H, W, 3) RGB
    glb: bytes | None
    origin: str  # what is shown, for the panel: a path, or "scene <id>, revision <n>"
    models_dir: Path | None = None  # for MeshRefs to user models
    notes: list[str] = field(default_factory=list)
    depth: NDArray[np.float32] | None = None  # metres (H, W), the photo's; None without


def _read_photo(path: Path) -> NDArray[np.uint8]:
    photo = load_photo(path.read_bytes())
    rgb: NDArray[np.uint8] = np.ascontiguousarray(photo.rgb, dtype=np.uint8)
    return rgb


def _photo_or_note(path: Path | None, notes: list[str]) -> NDArray[np.uint8] | None:
    if path is None or not path.is_file():
        notes.append(f"photo not found ({path}); the camera is drawn without it")
        return None
    try:
        return _read_photo(path)
    except (InputError, OSError) as exc:
        notes.append(f"photo {path} unreadable ({exc}); the camera is drawn without it")
        return None


def _depth_or_note(scene: Scene, folder: Path, notes: list[str]) -> NDArray[np.float32] | None:
    """The scene's depth (its DepthRef's file in `folder`), or None with a note why not."""
    if scene.depth is None:
        return None
    path = folder / scene.depth.file
    try:
        return stored_depth(scene, path.read_bytes())
    except (InputError, OSError) as exc:
        notes.append(f"depth {path} unreadable ({exc}); no depth points")
        return None


def resolve_scene_file(path: Path) -> Path:
    """A scene file, or a folder holding scene.json (from infer) or gt.json (from synth)."""
    if path.is_dir():
        for name in SCENE_FILE_NAMES:
            if (path / name).is_file():
                return path / name
        raise ViewerInputError(f"{path} holds no {' or '.join(SCENE_FILE_NAMES)}")
    if not path.is_file():
        raise ViewerInputError(f"no such file: {path}")
    return path


def load_scene_path(
    path: Path, photo: Path | None = None, models_dir: Path | None = None
) -> ViewerInput:
    """A scene JSON (a Scene, or a SceneDocument as the API serves it) with the photo and
    `scene.glb` beside it, as `holiscene infer -o DIR` and `holiscene synth` write them."""
    scene_file = resolve_scene_file(path)
    try:
        data = json.loads(scene_file.read_text())
        if isinstance(data, dict) and "scene_id" in data and "scene" in data:
            data = data["scene"]  # a saved API document
        scene = Scene.model_validate(data)
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ViewerInputError(f"{scene_file}: not a readable JSON file ({exc})") from exc
    except ValidationError as exc:
        first = exc.errors()[0]
        where = ".".join(str(p) for p in first["loc"])
        raise ViewerInputError(
            f"{scene_file}: not a HoliScene scene ({where}: {first['msg']})"
        ) from exc
    notes: list[str] = []
    folder = scene_file.parent
    rgb = _photo_or_note(photo if photo is not None else folder / scene.image.file, notes)
    glb_path = folder / "scene.glb"
    glb = glb_path.read_bytes() if glb_path.is_file() else None
    depth = _depth_or_note(scene, folder, notes)
    return ViewerInput(scene, rgb, glb, str(scene_file), models_dir, notes, depth)


def load_stored_scene(
    store: SceneStore, scene_id: str, models_dir: Path | None = None
) -> ViewerInput:
    """The current revision of a stored scene, its photo and its newest GLB."""
    try:
        document = store.document(scene_id)
        image = store.image_path(scene_id)
        glb_path = store.glb_path(scene_id)
    except SceneNotFoundError as exc:
        raise ViewerInputError(str(exc.args[0]) if exc.args else str(exc)) from exc
    notes: list[str] = []
    rgb = _photo_or_note(image, notes)
    glb = glb_path.read_bytes() if glb_path is not None and glb_path.is_file() else None
    if glb is None:
        notes.append("no 3D scene file yet (run the pipeline); boxes shown where known")
    origin = f"scene {scene_id}, revision {document.revision}"
    depth = _depth_or_note(document.scene, store.files.folder(scene_id), notes)
    return ViewerInput(document.scene, rgb, glb, origin, models_dir, notes, depth)


def open_store(settings: Settings) -> SceneStore:
    """The workbench's scene store, for reading; refuses to create an empty database."""
    from ..core.db import make_engine, migrate
    from ..store.files import SceneFiles

    url = settings.resolved_database_url
    if url.startswith("sqlite:///"):
        db_file = Path(url.removeprefix("sqlite:///"))
        if not db_file.is_file():
            raise ViewerInputError(f"there is no scene store at {db_file}")
    engine = make_engine(url)
    migrate(engine)
    return SceneStore(engine, SceneFiles(settings.data_dir))


def load_scene_argument(arg: str, settings: Settings, photo: Path | None = None) -> ViewerInput:
    """`holiscene view SCENE`: an existing path (a scene JSON or its folder; `photo` replaces
    the one beside it), else a scene id in the store of `settings`. Something that looks like
    a path but is missing is an error about the file, not an unknown id."""
    path = Path(arg)
    if path.exists():
        return load_scene_path(path, photo, settings.models_dir)
    if path.suffix == ".json" or "/" in arg or "\\" in arg:
        raise ViewerInputError(f"no such file: {path}")
    hint = "give a scene id of the workbench's store or a scene.json path"
    try:
        store = open_store(settings)
    except ViewerInputError as exc:
        raise ViewerInputError(f"no scene {arg!r}: {exc}; {hint}") from exc
    try:
        return load_stored_scene(store, arg, settings.models_dir)
    except ViewerInputError as exc:
        raise ViewerInputError(f"{exc} in {settings.data_dir}; {hint}") from exc
    finally:
        store.engine.dispose()

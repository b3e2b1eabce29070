"""The reviewer's viser viewer of a scene, started on demand on a free port of 127.0.0.1.

One viewer per scene, reused while the app runs (rebuilt when the scene has a newer
revision), at most `MAX_VIEWERS` at a time; all stop with the app. Viewers bind loopback
only, whatever address the app serves on.
"""

from __future__ import annotations

from collections.abc import AsyncIterator
from contextlib import asynccontextmanager

from fastapi import APIRouter, FastAPI, Request
from fastapi.concurrency import run_in_threadpool
from holiscene_schema import ErrorMessage, ViewerInfo

from ...store.scenes import SceneNotFoundError
from ...viewer import ViewerInputError, ViewerPool, load_stored_scene
from ..deps import WorkbenchDep

MAX_VIEWERS = 4


@asynccontextmanager
async def _viewers(app: FastAPI) -> AsyncIterator[None]:
    pool = ViewerPool(MAX_VIEWERS)
    app.state.viewers = pool
    try:
        yield
    finally:
        await run_in_threadpool(pool.close)


router = APIRouter(prefix="/api/scenes", tags=["viewer"], lifespan=_viewers)


@router.post(
    "/{scene_id}/viewer", response_model=ViewerInfo, responses={404: {"model": ErrorMessage}}
)
def open_viewer(scene_id: str, workbench: WorkbenchDep, request: Request) -> ViewerInfo:
    """Start (or reuse) the viser viewer of the scene's current revision."""
    pool: ViewerPool = request.app.state.viewers
    revision = workbench.scenes.summary(scene_id).revision  # 404 for an unknown scene
    models_dir = workbench.settings.models_dir
    try:
        url = pool.open(
            scene_id, revision, lambda: load_stored_scene(workbench.scenes, scene_id, models_dir)
        )
    except ViewerInputError as exc:
        raise SceneNotFoundError(str(exc)) from exc
    return ViewerInfo(
        scene_id=scene_id,
        revision=revision,
        url=url,
        command=f"holiscene view {scene_id} --data-dir {workbench.settings.data_dir}",
    )

"""Files to download: a scene's scene.json and COCO JSON, and several scenes as one zip (a
folder per scene, or an export format)."""

from __future__ import annotations

from fastapi import APIRouter, Response
from holiscene_schema import ErrorMessage, SceneArchiveRequest

from ...export.archive import (
    ArchivedScene,
    archived_scene,
    coco_description,
    coco_json,
    file_stem,
    scene_json,
    scenes_zip,
)
from ...export.folders import exported_zip
from ...services.workbench import Workbench
from ...store.scenes import SceneNotFoundError
from ..deps import WorkbenchDep

router = APIRouter(prefix="/api/scenes", tags=["downloads"])

_ERRORS: dict[int | str, dict[str, object]] = {
    404: {"model": ErrorMessage},
    422: {"model": ErrorMessage},
}


def attachment(name: str) -> dict[str, str]:
    return {"Content-Disposition": f'attachment; filename="{name}"'}


def _archived(workbench: Workbench, scene_id: str) -> ArchivedScene:
    return archived_scene(workbench.scenes, scene_id)


@router.get("/{scene_id}/scene.json", responses=_ERRORS)
def download_scene_json(scene_id: str, workbench: WorkbenchDep) -> Response:
    """The current revision's scene, as `holiscene infer` writes scene.json."""
    scene = workbench.scenes.document(scene_id).scene
    return Response(
        scene_json(scene),
        media_type="application/json",
        headers=attachment(f"{file_stem(scene.name, scene_id)}.scene.json"),
    )


@router.get("/{scene_id}/coco.json", responses=_ERRORS)
def download_coco_json(scene_id: str, workbench: WorkbenchDep) -> Response:
    """The current revision's objects as a COCO instances file of the photo."""
    doc = workbench.scenes.document(scene_id)
    return Response(
        coco_json(doc.scene, coco_description(scene_id, doc.revision, doc.scene)),
        media_type="application/json",
        headers=attachment(f"{file_stem(doc.scene.name, scene_id)}.coco.json"),
    )


@router.post(
    "/archive",
    responses={200: {"content": {"application/zip": {}}}, **_ERRORS},
    response_class=Response,
)
def download_archive(request: SceneArchiveRequest, workbench: WorkbenchDep) -> Response:
    """The scenes as one zip (see export/archive.py), or as `format` writes them
    (export/folders.py); 404 naming every unknown id, and nothing is made then."""
    scene_ids = list(dict.fromkeys(request.scene_ids))  # the same scene once
    known = {s.id for s in workbench.scenes.list_summaries(archived=None)}
    unknown = [i for i in scene_ids if i not in known]
    if unknown:
        raise SceneNotFoundError(f"no scene with the id {', '.join(unknown)}: nothing archived")
    chosen = [_archived(workbench, i) for i in scene_ids]
    if request.format is None:
        data = scenes_zip(chosen)
        name = f"holiscene-{len(scene_ids)}-scenes.zip"
    else:  # refused with 422 (ExportRefusedError) when the format has nothing to write
        data = exported_zip(chosen, request.format)
        name = f"holiscene-{len(scene_ids)}-scenes-{request.format}.zip"
    return Response(data, media_type="application/zip", headers=attachment(name))

"""Scenes: import, read, edit, history, files."""

from __future__ import annotations

from pathlib import Path as FilePath
from typing import Annotated, Literal

import numpy as np
from fastapi import APIRouter, File, Form, Path, Query, UploadFile
from fastapi.responses import FileResponse, Response
from holiscene_schema import (
    MAX_REVISION,
    Conflict,
    DepthKey,
    DepthPoints,
    EditRequest,
    ErrorMessage,
    ImportResult,
    Job,
    ObjectDepthPoints,
    RevisionInfo,
    Scene,
    SceneDocument,
    SceneState,
    SceneSummary,
)

from ...core.recent_values import RecentValues
from ...export.archive import file_stem
from ...export.depth_preview import depth_preview_key, depth_preview_png
from ...inputs import (
    InputError,
    InputFiles,
    Photo,
    load_photo,
    parse_class_map,
    parse_detections,
    parse_intrinsics,
)
from ...inputs.depth import (
    DEPTH_FILE,
    METRES_PER_UNIT,
    DepthMap,
    DepthUnits,
    read_depth_file,
)
from ...learning.completion.scene_points import MAX_POINTS, scene_depth_points, stored_depth
from ...store.scenes import SceneNotFoundError
from ...store.tables import SCENE_NAME_LENGTH
from ..deps import AnnotatorDep, UserDep, WorkbenchDep, author_of
from ..permissions import with_edit_permission

router = APIRouter(prefix="/api/scenes", tags=["scenes"])


_ERRORS: dict[int | str, dict[str, object]] = {
    404: {"model": ErrorMessage},
    422: {"model": ErrorMessage},
}


async def _read_limited(upload: UploadFile, what: str, limit: int) -> bytes:
    data = await upload.read(limit + 1)
    if len(data) > limit:
        raise InputError(f"{what} is larger than {limit // (1024 * 1024)} MB", 413)
    return data


# Which scenes a list holds: those in use (the default), the archived ones, or both.
ArchivedScope = Literal["exclude", "only", "include"]
_ARCHIVED: dict[ArchivedScope, bool | None] = {"exclude": False, "only": True, "include": None}


@router.get("", response_model=list[SceneSummary])
def list_scenes(
    workbench: WorkbenchDep, state: SceneState | None = None, archived: ArchivedScope = "exclude"
) -> list[SceneSummary]:
    """The scenes, newest first; `state` keeps the scenes in that workflow state, `archived`
    says whether archived scenes are left out (the default), the only ones, or included."""
    latest = workbench.jobs.latest_for_scenes()
    summaries = workbench.scenes.list_summaries(state, _ARCHIVED[archived])
    return [s.model_copy(update={"latest_job": latest.get(s.id)}) for s in summaries]


@router.post(
    "",
    status_code=201,
    response_model=ImportResult,
    responses={413: {"model": ErrorMessage}, 415: {"model": ErrorMessage}, **_ERRORS},
)
async def import_scene(
    workbench: WorkbenchDep,
    user: AnnotatorDep,
    image: Annotated[UploadFile, File(description="The photo, JPEG or PNG")],
    cam_k: Annotated[UploadFile | None, File(description="cam_K.txt: 3x3 intrinsics")] = None,
    detections: Annotated[
        UploadFile | None, File(description="detections.json: 2D boxes and classes")
    ] = None,
    class_map: Annotated[
        UploadFile | None,
        File(description='class_map.json: {"dataset name": "NYU-40 class"}, for the boxes'),
    ] = None,
    depth: Annotated[
        UploadFile | None,
        File(description="Depth registered to the photo: 16-bit PNG or .npy of float metres"),
    ] = None,
    depth_units: Annotated[
        DepthUnits | None,
        Form(description='"mm" (PNG, the default), "sunrgbd" (PNG, SUN RGB-D\'s bits), "m" (.npy)'),
    ] = None,
    name: Annotated[str | None, Form(max_length=SCENE_NAME_LENGTH)] = None,
    author: Annotated[str, Form(min_length=1, max_length=64)] = "import",
    run_pipeline: Annotated[bool, Form()] = True,
) -> ImportResult:
    limit = workbench.settings.max_upload_mb * 1024 * 1024
    photo = load_photo(await _read_limited(image, "the photo", limit))
    depth_map = await _uploaded_depth(depth, depth_units, photo, limit)
    K = None
    if cam_k is not None:
        raw_k = await _read_limited(cam_k, "cam_K.txt", 64 * 1024)
        try:
            K = parse_intrinsics(raw_k.decode())
        except UnicodeDecodeError as exc:
            raise InputError("cam_K.txt is not text") from exc
    boxes = None
    if detections is not None:
        raw = await _read_limited(detections, "detections.json", 8 * 1024 * 1024)
        names = None
        if class_map is not None:
            names = parse_class_map(await _read_limited(class_map, "class_map.json", 1024 * 1024))
        boxes = parse_detections(raw, photo.width, photo.height, names)
    inputs = InputFiles(photo=photo, K=K, detections=boxes, depth=depth_map)
    # A name from the file name is cut to fit (only a typed name is the user's to shorten).
    from_file = (image.filename or "photo").rsplit(".", 1)[0].strip()[:SCENE_NAME_LENGTH]
    typed = (name or "").strip()
    scene_name = typed or from_file or "photo"  # numbered by the store when taken
    return workbench.import_scene(inputs, scene_name, author_of(user, author), run_pipeline)


async def _uploaded_depth(
    upload: UploadFile | None, units: DepthUnits | None, photo: Photo, limit: int
) -> DepthMap | None:
    if upload is None:
        if units is not None:
            raise InputError("depth_units was given without a depth file")
        return None
    data = await _read_limited(upload, "the depth file", limit)
    return read_depth_file(data, photo.width, photo.height, units, what="the depth file")


@router.get("/{scene_id}", response_model=SceneDocument, responses=_ERRORS)
def get_scene(scene_id: str, workbench: WorkbenchDep, user: UserDep) -> SceneDocument:
    """The latest revision; `editable` says whether the user asking may edit it now."""
    return with_edit_permission(workbench.scenes.document(scene_id), workbench, user)


@router.get("/{scene_id}/image", responses=_ERRORS)
def get_image(scene_id: str, workbench: WorkbenchDep) -> FileResponse:
    return FileResponse(workbench.scenes.image_path(scene_id))


def _depth_path(workbench: WorkbenchDep, scene_id: str, scene: Scene | None = None) -> FilePath:
    """The scene's depth file (SceneNotFoundError without one); `scene`: a revision of it
    already read, else the latest is."""
    scene = scene or workbench.scenes.document(scene_id).scene
    path = workbench.scenes.files.folder(scene_id) / DEPTH_FILE
    if scene.depth is None or not path.is_file():
        raise SceneNotFoundError(f"scene {scene_id} has no depth: it was imported without")
    return path


def _depth_file(workbench: WorkbenchDep, scene_id: str) -> bytes:
    return _depth_path(workbench, scene_id).read_bytes()


@router.get("/{scene_id}/depth.png", responses=_ERRORS)
def get_depth(scene_id: str, workbench: WorkbenchDep) -> Response:
    """The depth given with the photo, as stored: a 16-bit PNG of millimetres (0: none)."""
    return Response(_depth_file(workbench, scene_id), media_type="image/png")


@router.get("/{scene_id}/depth-preview.png", responses=_ERRORS)
def get_depth_preview(scene_id: str, workbench: WorkbenchDep) -> Response:
    """The depth as a colour picture to lay over the photo: near warm, far cool, and
    transparent where there is no depth."""
    return Response(depth_preview_png(_depth_file(workbench, scene_id)), media_type="image/png")


@router.get("/{scene_id}/depth-key", response_model=DepthKey, responses=_ERRORS)
def get_depth_key(scene_id: str, workbench: WorkbenchDep) -> DepthKey:
    """The depth overlay's key: the near and far depths its colours span, and the colours."""
    ref = workbench.scenes.document(scene_id).scene.depth
    unit = ref.metres_per_unit if ref is not None else METRES_PER_UNIT
    near, far, colours = depth_preview_key(_depth_file(workbench, scene_id), unit)
    return DepthKey(near_m=round(near, 3), far_m=round(far, 3), colours=colours)


def _to_tenth_mm(points: np.ndarray) -> list[list[float]]:
    rounded: list[list[float]] = np.round(points, 4).tolist()
    return rounded


@router.get(
    "/{scene_id}/depth-points",
    response_model=DepthPoints,
    responses={409: {"model": ErrorMessage}, **_ERRORS},
)
def get_depth_points(
    scene_id: str,
    workbench: WorkbenchDep,
    revision: Annotated[int | None, Query(ge=1, le=MAX_REVISION)] = None,
) -> DepthPoints:
    """Each object's partial points (its mask with depth, back-projected) and the shape
    completion network's points, world frame, at most MAX_POINTS each; of the latest revision
    or `revision`. 404 for a scene without depth, 409 before the pipeline placed its camera."""
    document = workbench.scenes.document(scene_id, revision)
    depth_path = _depth_path(workbench, scene_id, document.scene)
    key = (str(depth_path), depth_path.stat().st_mtime_ns, document.revision)
    kept = _recent_depth_points.get(key)
    if kept is not None:
        return kept
    depth = stored_depth(document.scene, depth_path.read_bytes())
    objects = scene_depth_points(document.scene, depth)
    answer = DepthPoints(
        scene_id=scene_id,
        revision=document.revision,
        objects=[
            ObjectDepthPoints(
                id=o.id,
                partial=_to_tenth_mm(o.partial),
                completed=None if o.completed is None else _to_tenth_mm(o.completed),
            )
            for o in objects
        ],
        max_points=MAX_POINTS,
    )
    _recent_depth_points.put(key, answer)
    return answer


# A revision's points never change (a revision is never rewritten and its depth file came
# with the import), while each request would run the completion network on every object: the
# last few answers are kept, by depth file (and its time, should it be replaced) and revision.
_recent_depth_points: RecentValues[tuple[str, int, int], DepthPoints] = RecentValues(8)


# The revision whose run made the GLB, on every scene.glb answer.
GLB_REVISION_HEADER = "X-Glb-Revision"


@router.get("/{scene_id}/scene.glb", responses=_ERRORS)
def get_glb(scene_id: str, workbench: WorkbenchDep) -> FileResponse:
    """The scene's 3D scene as the last pipeline or placement run made it; its header
    `X-Glb-Revision` names that revision (edits since are not in the file)."""
    made = workbench.scenes.glb_file(scene_id)
    if made is None or not made[1].is_file():
        raise SceneNotFoundError(f"scene {scene_id} has no 3D scene yet: run the pipeline")
    revision, path = made
    name = file_stem(workbench.scenes.summary(scene_id).name, scene_id)
    return FileResponse(
        path,
        media_type="model/gltf-binary",
        filename=f"{name}.glb",
        headers={GLB_REVISION_HEADER: str(revision)},
    )


_JOB_ERRORS: dict[int | str, dict[str, object]] = {
    409: {"model": ErrorMessage},
    503: {"model": ErrorMessage},
    **_ERRORS,
}


@router.post(
    "/{scene_id}/pipeline-jobs", status_code=202, response_model=Job, responses=_JOB_ERRORS
)
def run_pipeline_job(scene_id: str, workbench: WorkbenchDep, user: AnnotatorDep) -> Job:
    """Run the pipeline again on the latest revision. 409 while the scene is submitted or
    accepted, while another annotator holds it (admins may), or while it has a job queued or
    running; 503 when the server's job queue is full."""
    workbench.workflow.check_job_allowed(scene_id, user)
    return workbench.start_pipeline(scene_id, user.name)


@router.post(
    "/{scene_id}/placement-jobs", status_code=202, response_model=Job, responses=_JOB_ERRORS
)
def run_placement_job(scene_id: str, workbench: WorkbenchDep, user: AnnotatorDep) -> Job:
    """Place the objects again (heights, 3D boxes, shapes, scene.glb) on the current revision's
    camera and room layout, after a person changed them; the result is a new revision, stored
    only if nobody saved the scene meanwhile (else the job fails and nothing is overwritten).
    Refused as a pipeline run is (409, 503)."""
    workbench.workflow.check_job_allowed(scene_id, user)
    return workbench.start_placement(scene_id, user.name)


@router.post(
    "/{scene_id}/edits",
    response_model=SceneDocument,
    responses={409: {"model": Conflict}, **_ERRORS},
)
def edit_scene(
    scene_id: str, request: EditRequest, workbench: WorkbenchDep, user: AnnotatorDep
) -> Response:
    """A new revision; the first edit takes the scene for annotation (409 when someone
    else is annotating it, or it is submitted or accepted)."""
    request = request.model_copy(update={"author": author_of(user, request.author)})
    saved = workbench.workflow.edit(scene_id, request, user)
    # The rules let this user make the revision just saved (checked again with the write), so
    # it is theirs to edit on: the answer needs no second read of the scene's workflow state.
    answer = saved.model_copy(update={"editable": True, "editable_reason": None})
    # Written to JSON here, in the worker thread: a returned model would cost one more hand-over
    # to a worker (FastAPI checks it there) and its JSON would be made on the event loop.
    return Response(answer.model_dump_json(by_alias=True), media_type="application/json")


@router.get("/{scene_id}/revisions", response_model=list[RevisionInfo], responses=_ERRORS)
def list_revisions(scene_id: str, workbench: WorkbenchDep) -> list[RevisionInfo]:
    return workbench.scenes.revisions(scene_id)


@router.get("/{scene_id}/revisions/{number}", response_model=SceneDocument, responses=_ERRORS)
def get_revision(
    scene_id: str,
    number: Annotated[int, Path(ge=1, le=MAX_REVISION)],
    workbench: WorkbenchDep,
    user: UserDep,
) -> SceneDocument:
    """A revision as stored; only the latest can be `editable`."""
    return with_edit_permission(
        workbench.scenes.document(scene_id, number), workbench, user, by_number=True
    )

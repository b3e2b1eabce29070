"""The annotation workflow: take the next scene, submit it, accept or reject it, ask for a
second annotation; a scene's state and history; the dashboard."""

from __future__ import annotations

from fastapi import APIRouter
from holiscene_schema import (
    Dashboard,
    ErrorMessage,
    RejectRequest,
    ReleaseRequest,
    ReviewRequest,
    SceneSummary,
    SceneWorkflow,
    SecondAnnotationRequest,
    SubmitRequest,
)

from ..deps import AdminDep, AnnotatorDep, ReviewerDep, UserDep, WorkbenchDep
from ..permissions import with_edit_permission

router = APIRouter(prefix="/api", tags=["workflow"])

_ERRORS: dict[int | str, dict[str, object]] = {
    404: {"model": ErrorMessage},
    409: {
        "model": ErrorMessage,
        "description": "The workflow does not allow it now; or, with a Conflict body, the "
        "revision named is not the latest",
    },
    422: {"model": ErrorMessage},
}


@router.post("/scenes/next", response_model=SceneSummary, responses=_ERRORS)
def next_scene(user: AnnotatorDep, workbench: WorkbenchDep) -> SceneSummary:
    """Assign the caller their next scene: one of theirs a reviewer rejected, else the
    predicted scene the pipeline is least sure of (highest uncertainty). 404 when none."""
    return workbench.workflow.next_scene(user)


@router.get("/scenes/next-review", response_model=SceneSummary, responses=_ERRORS)
def next_to_review(
    user: ReviewerDep, workbench: WorkbenchDep, after: str | None = None
) -> SceneSummary:
    """The submitted scene waiting longest that the caller did not annotate; nothing is
    assigned (404 when none waits). `after`: the scene open now; the next one in the queue
    after it comes back (round to the oldest), never itself."""
    return workbench.workflow.next_to_review(user, after)


@router.get("/scenes/{scene_id}/workflow", response_model=SceneWorkflow, responses=_ERRORS)
def scene_workflow(scene_id: str, user: UserDep, workbench: WorkbenchDep) -> SceneWorkflow:
    """State, assignee, the reviewer's comment when rejected, every state change, and whether
    the user asking may edit the scene now (`editable`, `editable_reason`)."""
    return with_edit_permission(workbench.workflow.scene_workflow(scene_id), workbench, user)


@router.post("/scenes/{scene_id}/take", response_model=SceneSummary, responses=_ERRORS)
def take_scene(scene_id: str, user: AnnotatorDep, workbench: WorkbenchDep) -> SceneSummary:
    """Start annotating this scene (editing it does the same). 409 when someone else is
    annotating it, or it is submitted or accepted."""
    return workbench.workflow.take(scene_id, user)


@router.post("/scenes/{scene_id}/release", response_model=SceneWorkflow, responses=_ERRORS)
def release_scene(
    scene_id: str, body: ReleaseRequest, user: AnnotatorDep, workbench: WorkbenchDep
) -> SceneWorkflow:
    """Give back a scene taken by mistake (its annotator, or an admin): it waits for "Next
    scene" again, with every revision kept. 409 unless it is in annotation, or when a reviewer
    sent it back to be fixed (admins may); `revision` must be the latest."""
    flow = workbench.workflow.release(scene_id, body.revision, user)
    return with_edit_permission(flow, workbench, user)


@router.post("/scenes/{scene_id}/submit", response_model=SceneWorkflow, responses=_ERRORS)
def submit_scene(
    scene_id: str, body: SubmitRequest, user: AnnotatorDep, workbench: WorkbenchDep
) -> SceneWorkflow:
    """Hand the scene to the reviewers (only its annotator; `revision` must be the latest)."""
    flow = workbench.workflow.submit(scene_id, body.revision, user)
    return with_edit_permission(flow, workbench, user)


@router.post("/scenes/{scene_id}/withdraw", response_model=SceneWorkflow, responses=_ERRORS)
def withdraw_scene(
    scene_id: str, body: SubmitRequest, user: AnnotatorDep, workbench: WorkbenchDep
) -> SceneWorkflow:
    """Take a submission back before a reviewer decides (only the annotator who submitted it;
    `revision` must be the latest): it is in annotation again, theirs."""
    flow = workbench.workflow.withdraw(scene_id, body.revision, user)
    return with_edit_permission(flow, workbench, user)


@router.post("/scenes/{scene_id}/accept", response_model=SceneWorkflow, responses=_ERRORS)
def accept_scene(
    scene_id: str, body: ReviewRequest, user: ReviewerDep, workbench: WorkbenchDep
) -> SceneWorkflow:
    flow = workbench.workflow.accept(scene_id, body.revision, user, body.comment)
    return with_edit_permission(flow, workbench, user)


@router.post("/scenes/{scene_id}/reject", response_model=SceneWorkflow, responses=_ERRORS)
def reject_scene(
    scene_id: str, body: RejectRequest, user: ReviewerDep, workbench: WorkbenchDep
) -> SceneWorkflow:
    """Send the scene back to its annotator with a comment saying what went wrong."""
    flow = workbench.workflow.reject(scene_id, body.revision, user, body.comment)
    return with_edit_permission(flow, workbench, user)


@router.post(
    "/scenes/{scene_id}/second-annotation", response_model=SceneWorkflow, responses=_ERRORS
)
def second_annotation(
    scene_id: str, body: SecondAnnotationRequest, user: ReviewerDep, workbench: WorkbenchDep
) -> SceneWorkflow:
    """Have a submitted or accepted scene annotated again, independently: its supports go
    back to the pipeline's guesses and someone who did not label it takes it next. The
    dashboard then shows how far the two annotations agree."""
    flow = workbench.workflow.second_annotation(scene_id, body.revision, user, body.comment)
    return with_edit_permission(flow, workbench, user)


@router.post("/scenes/{scene_id}/archive", response_model=SceneSummary, responses=_ERRORS)
def archive_scene(scene_id: str, user: AdminDep, workbench: WorkbenchDep) -> SceneSummary:
    """Archive a scene nobody should work on (a junk photo, a duplicate): it leaves the scene
    list, "Next scene", reviews, retraining and batch runs and is read only; every revision
    is kept, and `unarchive` brings it back (admin)."""
    return workbench.scenes.set_archived(scene_id, True, user.name)


@router.post("/scenes/{scene_id}/unarchive", response_model=SceneSummary, responses=_ERRORS)
def unarchive_scene(scene_id: str, user: AdminDep, workbench: WorkbenchDep) -> SceneSummary:
    """Bring an archived scene back, as it was (admin)."""
    return workbench.scenes.set_archived(scene_id, False, user.name)


@router.get("/dashboard", response_model=Dashboard)
def dashboard(_: UserDep, workbench: WorkbenchDep) -> Dashboard:
    """Scenes per state, what each person did, and agreement on scenes labelled twice."""
    return workbench.workflow.dashboard(workbench.users.roles())

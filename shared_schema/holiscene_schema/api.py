"""What the app and the server exchange: edits, scene documents, revisions and jobs."""

from __future__ import annotations

from datetime import datetime
from typing import Annotated, Any, Literal

from pydantic import Field

from .scene import Box2D, Mask, Point2, Point3, Scene, SchemaModel, SupportType

# Revisions are stored as 32-bit integers (PostgreSQL's INTEGER; SQLite's are 64-bit): a
# number beyond that can name no revision, and the database would fail on it, not answer.
MAX_REVISION = 2**31 - 1
RevisionNumber = Annotated[int, Field(ge=1, le=MAX_REVISION)]


class SetSupport(SchemaModel):
    """Make `parent` the supporter of `child` (replacing any supporter it had)."""

    kind: Literal["set_support"] = "set_support"
    child: str
    parent: str
    type: SupportType


class RemoveSupport(SchemaModel):
    """Leave `child` without a supporter (it is then flagged for labelling)."""

    kind: Literal["remove_support"] = "remove_support"
    child: str


class RestoreSupport(SchemaModel):
    """Put `child`'s supporter back exactly as it was in revision `from_revision` (source,
    confidence, author and time included), or remove it if it had none then. Undo and revert
    use it, so taking back a correction gives the pipeline's guess back as a guess, not as a
    person's label."""

    kind: Literal["restore_support"] = "restore_support"
    child: str
    from_revision: RevisionNumber


class SetLayout(SchemaModel):
    """Set the room layout from its 8 corners in the image (dragged by an annotator).

    The server fits the room box and the camera's pitch and roll to the known corners (the
    room fit, `holiscene.geometry.room_fit`, with the camera's height as the scale) and stores
    the fitted box's corners and their projections. A `camera_height_m` sets the scale by hand.
    The objects' 3D boxes are not moved: a placement job does that.
    """

    kind: Literal["set_layout"] = "set_layout"
    corners_2d: Annotated[list[Point2 | None], Field(min_length=8, max_length=8)] = Field(
        description="Pixels in the order of Layout.corners_3d; null for a corner not used "
        "(behind the camera, or out of view and left to the fit)"
    )
    unseen_wall_distance: float | None = Field(
        default=None,
        gt=0.0,
        description="Metres from the camera to a wall without known corners (the fit needs "
        "it when only two adjacent vertical room edges are known)",
    )
    camera_height_m: float | None = Field(
        default=None,
        ge=0.1,
        le=20.0,
        description="The camera's height above the floor in metres, when the annotator knows "
        "it (the scale of the whole room; no photo tells it). Null keeps the scene's.",
    )


class AddObject(SchemaModel):
    """Add an object to the scene (a person's box, or an object detector's suggestion the
    annotator accepted). It starts without a supporter. Without a `mask` the server cuts one
    with GrabCut in the box (Mask.source "grabcut", or "box" when the cut fails) and stores
    it in the new revision."""

    kind: Literal["add_object"] = "add_object"
    id: str = Field(
        pattern=r"^[A-Za-z0-9_-]{1,64}$",
        description="Chosen by the client, unique in the scene, so later edits of the same "
        "request can name the object",
    )
    cls: str = Field(
        alias="class",
        min_length=1,
        max_length=64,
        description="An NYU-40 class or a known alias of one (stored as the NYU-40 class, the "
        "name given as the object's source_class when it differs)",
    )
    bbox: Box2D = Field(description="[x1, y1, x2, y2] in pixels, inside the photo")
    mask: Mask | None = Field(default=None, description="Null: the server cuts one in the box")
    score: float | None = Field(default=None, ge=0.0, le=1.0, description="Detection confidence")
    source: Literal["detector", "manual"] = Field(
        default="manual", description="An accepted detector suggestion, or drawn by a person"
    )


class RemoveObject(SchemaModel):
    """Remove an object: its supporter goes with it, and the objects it supported are left
    without one (flagged for labelling)."""

    kind: Literal["remove_object"] = "remove_object"
    id: str = Field(min_length=1)


class SetClass(SchemaModel):
    """Give an object another class (an NYU-40 class or a known alias, stored as for
    AddObject). A pipeline re-run keeps it."""

    kind: Literal["set_class"] = "set_class"
    id: str = Field(min_length=1)
    cls: str = Field(alias="class", min_length=1, max_length=64)


class SetBbox(SchemaModel):
    """Move or resize an object's box (inside the photo). A mask made from the box (GrabCut's
    or the box's own) is cut again in the new box; a mask a person drew is clipped to it. A
    pipeline re-run keeps the box."""

    kind: Literal["set_bbox"] = "set_bbox"
    id: str = Field(min_length=1)
    bbox: Box2D = Field(description="[x1, y1, x2, y2] in pixels, inside the photo")


class SetMask(SchemaModel):
    """Replace an object's mask with one a person drew (brush, eraser, polygon or refined
    strokes). It is stored with source "manual" and the object's box becomes the mask's
    extent. A pipeline re-run keeps it."""

    kind: Literal["set_mask"] = "set_mask"
    id: str = Field(min_length=1)
    mask: Mask


class RestoreObject(SchemaModel):
    """Put an object back exactly as it was in revision `from_revision` (class, box, mask and
    all), with every support it took part in there whose objects still exist: undo of a
    removal, a class, a box or a mask change. An object that revision did not have is removed
    (undo of an addition)."""

    kind: Literal["restore_object"] = "restore_object"
    id: str = Field(min_length=1)
    from_revision: RevisionNumber


ObjectEdit = AddObject | RemoveObject | SetClass | SetBbox | SetMask | RestoreObject


class RestoreScene(SchemaModel):
    """Put the whole scene back as revision `from_revision` had it: its objects (classes, boxes,
    masks, 3D boxes, shapes), supports, room layout and camera, the objects people had removed,
    and the pipeline stages behind them. The photo, its depth and the scene's name stay. The
    history's "Revert to this"; undo is a restore_scene of the revision before it."""

    kind: Literal["restore_scene"] = "restore_scene"
    from_revision: RevisionNumber


Edit = Annotated[
    SetSupport | RemoveSupport | RestoreSupport | SetLayout | ObjectEdit | RestoreScene,
    Field(discriminator="kind"),
]


class Stroke(SchemaModel):
    """A brush stroke: a polyline of pixel points painted with a round brush."""

    points: list[Point2] = Field(min_length=1, max_length=5000)
    radius: float = Field(gt=0.0, le=500.0, description="Brush radius in pixels")


class MaskRefineRequest(SchemaModel):
    """GrabCut in a box, steered by strokes a person painted: pixels under `foreground`
    strokes are the object, under `background` strokes they are not. Nothing is stored."""

    bbox: Box2D = Field(description="[x1, y1, x2, y2] in pixels, inside the photo")
    foreground: list[Stroke] = Field(default_factory=list, max_length=200)
    background: list[Stroke] = Field(default_factory=list, max_length=200)


class MaskRefineResult(SchemaModel):
    mask: Mask = Field(description="Source 'manual': made by a person's strokes")
    milliseconds: float = Field(description="Time the cut took on the server")


# The formats `holiscene export --format` writes, which a browser download can ask for too.
ExportFormatName = Literal[
    "coco", "scene", "total3d", "total3d-training", "relation-training", "nyu-supports"
]


class SceneArchiveRequest(SchemaModel):
    """Scenes to download as one zip: per scene its scene.json, coco.json, photo and
    scene.glb (when it has one); or, with `format`, what `holiscene export --format` writes."""

    scene_ids: list[Annotated[str, Field(min_length=1, max_length=64)]] = Field(
        min_length=1, max_length=500
    )
    format: ExportFormatName | None = Field(
        default=None,
        description="None: a folder per scene (HoliScene's own archive, which Import a "
        "dataset takes back); else the export format of `holiscene export`",
    )


class EditRequest(SchemaModel):
    base_revision: RevisionNumber = Field(description="The revision the edits were made on")
    author: str = Field(min_length=1, max_length=64)
    edits: list[Edit] = Field(min_length=1, max_length=500)


class EditPermission(SchemaModel):
    """Whether the user asking may edit the scene now, so the app can disable its editors.
    The server checks every edit itself (409 with the same reason) whatever this says."""

    editable: bool = Field(
        default=False,
        description="The user asking may change this scene's supports and room layout now",
    )
    editable_reason: str | None = Field(
        default=None,
        description="Why not, when editable is false (e.g. the scene is submitted for review, "
        "someone else is annotating it, or this is not the latest revision)",
    )


class SceneDocument(EditPermission):
    scene_id: str
    revision: int
    updated_at: datetime
    scene: Scene


# reset: the supports were put back to the pipeline's guesses for a second, independent
# annotation of the scene (a reviewer's request).
RevisionKind = Literal["import", "pipeline", "edit", "reset"]


class RevisionInfo(SchemaModel):
    number: int
    created_at: datetime
    author: str
    kind: RevisionKind
    summary: str
    edits: list[Edit] | None = None


# cancelled: stopped on an admin's request (retrain jobs); its message ("cancelled by adam; ...")
# says by whom.
JobStatus = Literal["queued", "running", "succeeded", "failed", "cancelled"]
FINISHED_JOB_STATUSES: tuple[JobStatus, ...] = ("succeeded", "failed", "cancelled")
# placement: the placement stages only, on a scene's stored camera, layout, masks and supports;
# retrain: retraining the Relation Network; detector_retrain: retraining the object detector.
JobKind = Literal["pipeline", "placement", "retrain", "detector_retrain"]


class Job(SchemaModel):
    """A background job: a pipeline run on one scene (all stages, or placement only), or
    retraining a model of the registry (the Relation Network or the object detector)."""

    id: str
    kind: JobKind
    scene_id: str | None = Field(
        default=None, description="The scene of a pipeline or placement job"
    )
    status: JobStatus
    progress: float = Field(ge=0.0, le=1.0)
    stage: str | None = None
    message: str | None = None
    error: str | None = None
    log: str = Field(default="", description="What the job did so far, one line per step")
    base_revision: int | None = Field(default=None, description="Pipeline jobs: the input")
    result_revision: int | None = None
    result_model_id: str | None = Field(
        default=None, description="Retrain jobs: the model they registered"
    )
    started_by: str | None = Field(
        default=None,
        description="Who asked for the job: an account's name, or 'import' (unknown for jobs "
        "from before this was recorded)",
    )
    created_at: datetime
    finished_at: datetime | None = None


# new: imported, no prediction yet; predicted: the pipeline ran; in_annotation: an annotator
# took it; submitted: waiting for a reviewer; accepted; rejected: back to the annotator with
# the reviewer's comment.
SceneState = Literal["new", "predicted", "in_annotation", "submitted", "accepted", "rejected"]
Role = Literal["annotator", "reviewer", "admin"]


class SceneSummary(SchemaModel):
    id: str
    name: str
    revision: int
    created_at: datetime
    updated_at: datetime = Field(description="When its latest revision was stored")
    last_activity_at: datetime | None = Field(
        default=None,
        description="The later of its latest revision and its latest workflow step (taken, "
        "submitted, accepted...): what the scene list shows as Updated",
    )
    width: int
    height: int
    object_count: int
    state: SceneState
    assignee: str | None = Field(default=None, description="The annotator working on it")
    annotation_round: int = Field(
        ge=1, description="1, or 2 once a reviewer asked for a second, independent annotation"
    )
    uncertainty: float | None = Field(
        default=None,
        ge=0.0,
        le=1.0,
        description="Mean over the objects of 1 - confidence of their supporter (1 without "
        "one, 0 when a person set it); 1 for a scene without objects; 'Next scene' picks the "
        "highest",
    )
    archived_at: datetime | None = Field(
        default=None,
        description="When an admin archived it: out of the list, 'Next scene', reviews, "
        "retraining and batch runs, and read only, until restored",
    )
    archived_by: str | None = None
    latest_job: Job | None = None


class ImportResult(SchemaModel):
    scene: SceneSummary
    job: Job | None
    same_photo: SceneSummary | None = Field(
        default=None,
        description="A scene stored before with this very photo file (the first), if any: the "
        "import went ahead, as a second scene of the photo, and the page says so",
    )


class ImportedPhoto(SchemaModel):
    name: str = Field(description="The photo's name in the upload (a file or folder)")
    scene_id: str = Field(description="Its scene: made now, or imported before (skipped)")
    scene_name: str | None = Field(
        default=None,
        description="That scene's name (a scene stored before may be named otherwise than the "
        "photo in this upload)",
    )
    notes: list[str] = Field(
        default_factory=list,
        description="What was left out of the labels given with it (e.g. a support row of an "
        "unknown type), while the photo and the rest were imported; or that the same photo "
        "was stored before as another scene",
    )


class PhotoError(SchemaModel):
    name: str = Field(description="The photo's or file's name in the upload")
    message: str = Field(description="Why it was left out; nothing of it was stored")


class ImportJob(SchemaModel):
    """A dataset uploaded as a .zip (POST /api/imports), imported in the background: each
    photo becomes a scene, is skipped as imported before, or is left out with its error."""

    id: str
    status: JobStatus
    archive: str = Field(description="The uploaded file's name")
    format: str | None = Field(
        default=None, description="What the zip holds: COCO, LabelMe, SUN RGB-D, input folders"
    )
    total: int = Field(ge=0, description="Photos (and unreadable files) found in the zip")
    done: int = Field(ge=0, description="Of them, read so far")
    run_pipeline: bool = Field(description="Whether each new scene's pipeline is queued")
    imported: list[ImportedPhoto] = Field(default_factory=list, description="New scenes")
    skipped: list[ImportedPhoto] = Field(
        default_factory=list, description="Photos with the same files imported before"
    )
    errors: list[PhotoError] = Field(default_factory=list)
    error: str | None = Field(default=None, description="Why the whole import stopped")
    started_by: str | None = None
    created_at: datetime
    finished_at: datetime | None = None


class ConflictDetail(SchemaModel):
    message: str
    current_revision: int


class ErrorMessage(SchemaModel):
    detail: str


class Conflict(SchemaModel):
    detail: ConflictDetail


# -- the model registry (admin): the Relation Network and the object detector ---------------

# Each kind has its own versions, active model, history and retraining.
ModelKind = Literal["relation", "detector"]
# default: the committed model the registry started with; accepted: trained here and at least
# as good as the active model on the held-out scenes (so it was promoted); candidate: as good,
# but the active model changed while it trained, so it was not promoted by itself; rejected:
# worse on the held-out scenes. Any of them can still be made active by hand.
ModelStatus = Literal["default", "accepted", "candidate", "rejected"]
ModelAction = Literal["seed", "promote", "rollback"]


class HeldoutFigure(SchemaModel):
    """Another registered model's figures on a retrain's held-out scenes (a shipped detector
    that is neither the new model nor its parent gets figures no other way)."""

    model_id: str
    accuracy: float = Field(description="As ModelInfo.heldout_accuracy")
    recall: float | None = Field(default=None, description="As ModelInfo.heldout_recall")


class ModelInfo(SchemaModel):
    id: str
    kind: ModelKind = Field(
        description="relation: a Relation Network (supports); detector: an object detector"
    )
    version: int = Field(ge=1, description="Counted per kind")
    name: str | None = Field(
        default=None,
        description="What the model is, from its metadata.json (detectors: which network, "
        "trained on what); None when it does not say",
    )
    created_at: datetime
    status: ModelStatus
    active: bool
    parent_id: str | None = Field(
        default=None, description="The model that was active when this one was trained"
    )
    parent_version: int | None = None
    job_id: str | None = Field(default=None, description="The retrain job that made it")
    heldout_accuracy: float | None = Field(
        default=None,
        description="On the held-out labelled scenes: support accuracy (relation), or mAP@0.5 "
        "of the confirmed boxes (detector); promotion compares this figure",
    )
    parent_heldout_accuracy: float | None = Field(
        default=None, description="The parent's figure on the same held-out scenes"
    )
    heldout_recall: float | None = Field(
        default=None,
        description="Detector: share of the held-out confirmed boxes found with the right class "
        "(IoU 0.5)",
    )
    parent_heldout_recall: float | None = Field(
        default=None, description="Detector: the parent's recall on the same held-out scenes"
    )
    validation_accuracy: float | None = Field(
        default=None,
        description="On the training run's own validation split: accuracy (relation), or "
        "mAP@0.5 on synthetic rooms (detector)",
    )
    training_scenes: int = Field(ge=0, description="Labelled scenes it was trained on")
    heldout_scenes: int = Field(ge=0, description="Labelled scenes it was evaluated on")
    heldout_items: int | None = Field(
        default=None,
        ge=0,
        description="What those scenes held to score: labelled objects (relation) or "
        "confirmed boxes (detector); a handful decides little",
    )
    heldout_others: list[HeldoutFigure] = Field(
        default_factory=list,
        description="The other registered models of its kind, measured on the same held-out "
        "scenes as this one when it was trained (detectors)",
    )
    has_curve: bool
    note: str | None = None
    metrics: dict[str, Any] = Field(default_factory=dict, description="The model's metrics.json")


# A held-out figure on fewer labelled items than this decides little (one item can be a whole
# share): a retrain better on so few is kept as a candidate, not made active by itself, and
# the models page warns before anyone makes such a model active by hand.
FEW_HELDOUT_ITEMS = 20


class ModelEvent(SchemaModel):
    """One change of the active model: who made which model active, when."""

    id: int
    at: datetime
    action: ModelAction
    actor: str
    model_id: str
    model_version: int
    previous_model_id: str | None = None
    previous_version: int | None = None
    note: str | None = None


class DetectorInfo(SchemaModel):
    """The active object detector (GET /api/detector/active): where its files are and what it
    detects; the browser runs it with onnxruntime-web."""

    id: str = Field(description="Changes with the model file; its files are under this id")
    name: str
    label_space: str = Field(description="coco80 (mapped to NYU-40) or nyu40")
    classes: list[str] = Field(description="The model's own classes, by class index")
    model_sha256: str
    model_bytes: int
    model_url: str
    metadata_url: str


class RetrainRequest(SchemaModel):
    author: str = Field(default="admin", min_length=1, max_length=64)
    max_epochs: int | None = Field(
        default=None, ge=1, le=500, description="Null: the kind's default (detector: epochs)"
    )
    synthetic_scenes: int | None = Field(
        default=None,
        ge=0,
        le=20_000,
        description="Synthetic rooms trained on beside the stored scenes; null: the default",
    )


class RetrainReadiness(SchemaModel):
    """Whether a kind of model can be retrained now: how many stored scenes it could learn
    from, how many of them it would hold out to judge the new model, and how many it needs."""

    labelled_scenes: int = Field(ge=0, description="Stored scenes the retraining would use")
    heldout_scenes: int = Field(
        ge=0, description="Of those, the scenes held out to judge the new model, never trained on"
    )
    needed: int = Field(ge=1, description="Labelled scenes needed before it can start")
    what: str = Field(description="What counts as a labelled scene for this kind")
    other_retrain: str | None = Field(
        default=None,
        description="A retrain of another kind of model, queued or running: one runs at a time, "
        "so this kind's waits for it ('a retrain of the Relation Network started by adam (40%)')",
    )


class PromoteRequest(SchemaModel):
    author: str = Field(default="admin", min_length=1, max_length=64)
    note: str | None = Field(default=None, max_length=500)


# -- users, sessions and the annotation workflow --------------------------------------------

UserName = Annotated[
    str,
    Field(
        min_length=1,
        max_length=64,
        pattern=r"^[a-z0-9][a-z0-9_.-]*$",
        description="Lower-case letters, digits, '.', '_' and '-'",
    ),
]
Password = Annotated[str, Field(min_length=1, max_length=256)]


class UserInfo(SchemaModel):
    name: str
    role: Role
    created_at: datetime
    disabled: bool = Field(
        default=False,
        description="An admin disabled the account: it cannot log in and its sessions ended",
    )
    disabled_at: datetime | None = Field(default=None, description="Since when, if disabled")


class CurrentUser(SchemaModel):
    """Who is asking. In local single-user mode (loopback, no accounts yet) everyone is the
    local admin and `local_mode` is true."""

    name: str
    role: Role
    local_mode: bool


class LoginRequest(SchemaModel):
    name: str = Field(min_length=1, max_length=64)
    password: Password
    token: bool = Field(
        default=False,
        description="Return the session token in the answer (scripts: send it as "
        "'Authorization: Bearer'); the browser uses the HttpOnly cookie instead",
    )


class LoginResult(SchemaModel):
    user: CurrentUser
    token: str | None = None
    expires_at: datetime


class NewUser(SchemaModel):
    name: UserName
    role: Role
    password: Password


class RoleChange(SchemaModel):
    role: Role


class PasswordReset(SchemaModel):
    password: Password


class PasswordChange(SchemaModel):
    current_password: Password
    new_password: Password


WorkflowAction = Literal[
    "import",
    "predict",
    "claim",
    "release",
    "reopen",
    "submit",
    "withdraw",
    "accept",
    "reject",
    "second_annotation",
    "archive",
    "unarchive",
]


class WorkflowEvent(SchemaModel):
    """One change of a scene's state (or assignee): who, when, on which revision, why."""

    id: int
    at: datetime
    actor: str
    action: WorkflowAction
    from_state: SceneState | None
    to_state: SceneState
    assignee: str | None = Field(default=None, description="The annotator concerned")
    revision: int
    annotation_round: int
    comment: str | None = None


class SceneWorkflow(EditPermission):
    scene_id: str
    state: SceneState
    assignee: str | None
    annotation_round: int
    revision: int
    review_comment: str | None = Field(
        default=None,
        description="The reviewer's comment from the last rejection, until the scene is "
        "submitted again",
    )
    events: list[WorkflowEvent] = Field(description="Oldest first")
    archived_by: str | None = Field(
        default=None,
        description="The admin who archived the scene: no workflow step until restored",
    )


class ReleaseRequest(SchemaModel):
    revision: RevisionNumber = Field(
        description="The revision the annotator gives back (the latest)"
    )


class SubmitRequest(SchemaModel):
    revision: RevisionNumber = Field(description="The revision the annotator submits (the latest)")


class ReviewRequest(SchemaModel):
    revision: RevisionNumber = Field(description="The revision the reviewer looked at (the latest)")
    comment: str | None = Field(default=None, max_length=2000)


class RejectRequest(SchemaModel):
    revision: RevisionNumber = Field(description="The revision the reviewer looked at (the latest)")
    comment: str = Field(min_length=1, max_length=2000, description="What went wrong")


class SecondAnnotationRequest(SchemaModel):
    revision: RevisionNumber = Field(description="The revision the reviewer looked at (the latest)")
    comment: str | None = Field(default=None, max_length=2000)


class PersonStats(SchemaModel):
    name: str
    role: Role | None = Field(default=None, description="null for a name without an account")
    in_annotation: int = Field(ge=0, description="Scenes they are annotating now")
    submitted: int = Field(ge=0, description="Submissions (a resubmission counts again)")
    accepted: int = Field(ge=0, description="Their submissions a reviewer accepted")
    rejected: int = Field(ge=0, description="Their submissions a reviewer rejected")
    reviewed: int = Field(ge=0, description="Submissions they accepted or rejected")


class SceneAgreement(SchemaModel):
    """Two independent annotations of one scene: the last submission of round 1 and of
    round 2, by different annotators."""

    scene_id: str
    name: str
    annotators: Annotated[list[str], Field(min_length=2, max_length=2)]
    revisions: Annotated[list[int], Field(min_length=2, max_length=2)]
    objects: int = Field(ge=1, description="Objects compared (those that need a supporter)")
    matching: int = Field(ge=0, description="Objects with the same supporter and type")
    agreement: float = Field(ge=0.0, le=1.0)


class Dashboard(SchemaModel):
    states: dict[SceneState, int] = Field(description="Scenes per state (every state listed)")
    people: list[PersonStats]
    agreement: list[SceneAgreement]
    mean_agreement: float | None = Field(
        default=None, description="Mean of the scenes' agreement; null without any"
    )


# -- the reviewer's viser viewer ------------------------------------------------------------


class ViewerInfo(SchemaModel):
    """The answer of POST /api/scenes/{id}/viewer: the scene's viser viewer, started on demand."""

    scene_id: str
    revision: int = Field(description="The revision the viewer shows")
    url: str = Field(description="The viewer's page, on 127.0.0.1")
    command: str = Field(description="The same viewer from a shell")


# -- depth points -----------------------------------------------------------------------------


class ObjectDepthPoints(SchemaModel):
    """One object's points from the depth, world frame (metres, as its 3D box)."""

    id: str
    partial: list[Point3] = Field(
        description="The object's mask pixels with depth, back-projected (depth outliers "
        "dropped), subsampled"
    )
    completed: list[Point3] | None = Field(
        description="The shape completion network's output points, before meshing; null when "
        "the object has no 3D box or too few partial points lie in it"
    )


class DepthPoints(SchemaModel):
    """The answer of GET /api/scenes/{id}/depth-points: what the depth saw of each object and
    what shape completion made of it."""

    scene_id: str
    revision: int
    objects: list[ObjectDepthPoints] = Field(description="Objects with a mask, in scene order")
    max_points: int = Field(description="At most this many points per list (subsampled)")


class DepthKey(SchemaModel):
    """The answer of GET /api/scenes/{id}/depth-key: the depths the depth overlay's colours
    span (2nd to 98th percentile of the depth present; nearer is drawn as near, further as
    far) and its colours from near to far."""

    near_m: float
    far_m: float
    colours: list[str] = Field(description="CSS hex colours from near to far, evenly spaced")

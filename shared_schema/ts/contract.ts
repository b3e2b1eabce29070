// Generated from shared_schema/jsonschema/contract.schema.json by ts/generate.mjs.
// Do not edit: change the pydantic models and run `make schema`.

export interface HoliSceneContract {
AddObject?: AddObject
Box3D?: Box3D
Camera?: Camera
Conflict?: Conflict
ConflictDetail?: ConflictDetail
CurrentUser?: CurrentUser
Dashboard?: Dashboard
DepthKey?: DepthKey
DepthPoints?: DepthPoints
DepthRef?: DepthRef
DetectorInfo?: DetectorInfo
EditRequest?: EditRequest
ErrorMessage?: ErrorMessage
HeldoutFigure?: HeldoutFigure
ImageInfo?: ImageInfo
ImportJob?: ImportJob
ImportResult?: ImportResult
ImportedPhoto?: ImportedPhoto
Job?: Job
Layout?: Layout
LoginRequest?: LoginRequest
LoginResult?: LoginResult
Mask?: Mask
MaskRefineRequest?: MaskRefineRequest
MaskRefineResult?: MaskRefineResult
MeshRef?: MeshRef
ModelEvent?: ModelEvent
ModelInfo?: ModelInfo
NewUser?: NewUser
ObjectDepthPoints?: ObjectDepthPoints
PasswordChange?: PasswordChange
PasswordReset?: PasswordReset
PersonStats?: PersonStats
PhotoError?: PhotoError
PromoteRequest?: PromoteRequest
RejectRequest?: RejectRequest
RemoveObject?: RemoveObject
RemoveSupport?: RemoveSupport
RemovedObject?: RemovedObject
RestoreObject?: RestoreObject
RestoreScene?: RestoreScene
RestoreSupport?: RestoreSupport
RetrainReadiness?: RetrainReadiness
RetrainRequest?: RetrainRequest
ReviewRequest?: ReviewRequest
RevisionInfo?: RevisionInfo
RoleChange?: RoleChange
Scene?: Scene
SceneAgreement?: SceneAgreement
SceneArchiveRequest?: SceneArchiveRequest
SceneDocument?: SceneDocument
SceneObject?: SceneObject
SceneSummary?: SceneSummary
SceneWorkflow?: SceneWorkflow
SecondAnnotationRequest?: SecondAnnotationRequest
SetBbox?: SetBbox
SetClass?: SetClass
SetLayout?: SetLayout
SetMask?: SetMask
SetSupport?: SetSupport
StageRun?: StageRun
Stroke?: Stroke
SubmitRequest?: SubmitRequest
SupportRelation?: SupportRelation
UserInfo?: UserInfo
ViewerInfo?: ViewerInfo
WorkflowEvent?: WorkflowEvent
}
/**
 * Add an object to the scene (a person's box, or an object detector's suggestion the
 * annotator accepted). It starts without a supporter. Without a `mask` the server cuts one
 * with GrabCut in the box (Mask.source "grabcut", or "box" when the cut fails) and stores
 * it in the new revision.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "AddObject".
 */
export interface AddObject {
/**
 * [x1, y1, x2, y2] in pixels, inside the photo
 * 
 * @minItems 4
 * @maxItems 4
 */
bbox: [number, number, number, number]
/**
 * An NYU-40 class or a known alias of one (stored as the NYU-40 class, the name given as the object's source_class when it differs)
 */
class: string
/**
 * Chosen by the client, unique in the scene, so later edits of the same request can name the object
 */
id: string
kind: "add_object"
/**
 * Null: the server cuts one in the box
 */
mask: (Mask | null)
/**
 * Detection confidence
 */
score: (number | null)
/**
 * An accepted detector suggestion, or drawn by a person
 */
source: ("detector" | "manual")
}
/**
 * A binary mask inside a window of the image, run-length encoded row by row.
 * 
 * `rle` alternates runs of 0 and 1 pixels, starting with a (possibly empty) run of 0.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "Mask".
 */
export interface Mask {
/**
 * [x, y] of the window's top-left pixel
 * 
 * @minItems 2
 * @maxItems 2
 */
origin: [number, number]
rle: number[]
/**
 * [width, height] of the window
 * 
 * @minItems 2
 * @maxItems 2
 */
size: [number, number]
source: ("given" | "box" | "grabcut" | "model" | "ground_truth" | "manual")
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "Box3D".
 */
export interface Box3D {
/**
 * @minItems 3
 * @maxItems 3
 */
center: [number, number, number]
/**
 * Extent along the box's own x (front), y (up), z axes
 * 
 * @minItems 3
 * @maxItems 3
 */
size: [number, number, number]
yaw_deg: number
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "Camera".
 */
export interface Camera {
/**
 * 3x3 intrinsics, pixels
 * 
 * @minItems 3
 * @maxItems 3
 */
K: [[number, number, number], [number, number, number], [number, number, number]]
K_source: ("given" | "assumed" | "estimated")
/**
 * Camera centre above the floor
 */
height_m: (number | null)
/**
 * Where height_m came from: a prior, estimated from the photo, set by hand, the dataset's ground truth, or measured from the depth's floor plane
 */
height_source: (("prior" | "estimated" | "manual" | "ground_truth" | "depth") | null)
note: (string | null)
/**
 * Angle of the optical axis below the horizon (positive looking down)
 */
pitch_deg: (number | null)
/**
 * Rotation about the optical axis (positive: camera turned clockwise as seen from behind it, so the scene appears turned counter-clockwise)
 */
roll_deg: (number | null)
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "Conflict".
 */
export interface Conflict {
detail: ConflictDetail
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "ConflictDetail".
 */
export interface ConflictDetail {
current_revision: number
message: string
}
/**
 * Who is asking. In local single-user mode (loopback, no accounts yet) everyone is the
 * local admin and `local_mode` is true.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "CurrentUser".
 */
export interface CurrentUser {
local_mode: boolean
name: string
role: ("annotator" | "reviewer" | "admin")
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "Dashboard".
 */
export interface Dashboard {
agreement: SceneAgreement[]
/**
 * Mean of the scenes' agreement; null without any
 */
mean_agreement: (number | null)
people: PersonStats[]
/**
 * Scenes per state (every state listed)
 */
states: {
[k: string]: number
}
}
/**
 * Two independent annotations of one scene: the last submission of round 1 and of
 * round 2, by different annotators.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "SceneAgreement".
 */
export interface SceneAgreement {
agreement: number
/**
 * @minItems 2
 * @maxItems 2
 */
annotators: [string, string]
/**
 * Objects with the same supporter and type
 */
matching: number
name: string
/**
 * Objects compared (those that need a supporter)
 */
objects: number
/**
 * @minItems 2
 * @maxItems 2
 */
revisions: [number, number]
scene_id: string
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "PersonStats".
 */
export interface PersonStats {
/**
 * Their submissions a reviewer accepted
 */
accepted: number
/**
 * Scenes they are annotating now
 */
in_annotation: number
name: string
/**
 * Their submissions a reviewer rejected
 */
rejected: number
/**
 * Submissions they accepted or rejected
 */
reviewed: number
/**
 * null for a name without an account
 */
role: (("annotator" | "reviewer" | "admin") | null)
/**
 * Submissions (a resubmission counts again)
 */
submitted: number
}
/**
 * The answer of GET /api/scenes/{id}/depth-key: the depths the depth overlay's colours
 * span (2nd to 98th percentile of the depth present; nearer is drawn as near, further as
 * far) and its colours from near to far.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "DepthKey".
 */
export interface DepthKey {
/**
 * CSS hex colours from near to far, evenly spaced
 */
colours: string[]
far_m: number
near_m: number
}
/**
 * The answer of GET /api/scenes/{id}/depth-points: what the depth saw of each object and
 * what shape completion made of it.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "DepthPoints".
 */
export interface DepthPoints {
/**
 * At most this many points per list (subsampled)
 */
max_points: number
/**
 * Objects with a mask, in scene order
 */
objects: ObjectDepthPoints[]
revision: number
scene_id: string
}
/**
 * One object's points from the depth, world frame (metres, as its 3D box).
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "ObjectDepthPoints".
 */
export interface ObjectDepthPoints {
/**
 * The shape completion network's output points, before meshing; null when the object has no 3D box or too few partial points lie in it
 */
completed: ([number, number, number][] | null)
id: string
/**
 * The object's mask pixels with depth, back-projected (depth outliers dropped), subsampled
 */
partial: [number, number, number][]
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "DepthRef".
 */
export interface DepthRef {
/**
 * 16-bit PNG beside the scene file; 0 = no depth
 */
file: string
metres_per_unit: number
}
/**
 * The active object detector (GET /api/detector/active): where its files are and what it
 * detects; the browser runs it with onnxruntime-web.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "DetectorInfo".
 */
export interface DetectorInfo {
/**
 * The model's own classes, by class index
 */
classes: string[]
/**
 * Changes with the model file; its files are under this id
 */
id: string
/**
 * coco80 (mapped to NYU-40) or nyu40
 */
label_space: string
metadata_url: string
model_bytes: number
model_sha256: string
model_url: string
name: string
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "EditRequest".
 */
export interface EditRequest {
author: string
/**
 * The revision the edits were made on
 */
base_revision: number
/**
 * @minItems 1
 * @maxItems 500
 */
edits: [(SetSupport | RemoveSupport | RestoreSupport | SetLayout | AddObject | RemoveObject | SetClass | SetBbox | SetMask | RestoreObject | RestoreScene), ...((SetSupport | RemoveSupport | RestoreSupport | SetLayout | AddObject | RemoveObject | SetClass | SetBbox | SetMask | RestoreObject | RestoreScene))[]]
}
/**
 * Make `parent` the supporter of `child` (replacing any supporter it had).
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "SetSupport".
 */
export interface SetSupport {
child: string
kind: "set_support"
parent: string
type: ("below" | "behind")
}
/**
 * Leave `child` without a supporter (it is then flagged for labelling).
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "RemoveSupport".
 */
export interface RemoveSupport {
child: string
kind: "remove_support"
}
/**
 * Put `child`'s supporter back exactly as it was in revision `from_revision` (source,
 * confidence, author and time included), or remove it if it had none then. Undo and revert
 * use it, so taking back a correction gives the pipeline's guess back as a guess, not as a
 * person's label.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "RestoreSupport".
 */
export interface RestoreSupport {
child: string
from_revision: number
kind: "restore_support"
}
/**
 * Set the room layout from its 8 corners in the image (dragged by an annotator).
 * 
 * The server fits the room box and the camera's pitch and roll to the known corners (the
 * room fit, `holiscene.geometry.room_fit`, with the camera's height as the scale) and stores
 * the fitted box's corners and their projections. A `camera_height_m` sets the scale by hand.
 * The objects' 3D boxes are not moved: a placement job does that.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "SetLayout".
 */
export interface SetLayout {
/**
 * The camera's height above the floor in metres, when the annotator knows it (the scale of the whole room; no photo tells it). Null keeps the scene's.
 */
camera_height_m: (number | null)
/**
 * Pixels in the order of Layout.corners_3d; null for a corner not used (behind the camera, or out of view and left to the fit)
 * 
 * @minItems 8
 * @maxItems 8
 */
corners_2d: [([number, number] | null), ([number, number] | null), ([number, number] | null), ([number, number] | null), ([number, number] | null), ([number, number] | null), ([number, number] | null), ([number, number] | null)]
kind: "set_layout"
/**
 * Metres from the camera to a wall without known corners (the fit needs it when only two adjacent vertical room edges are known)
 */
unseen_wall_distance: (number | null)
}
/**
 * Remove an object: its supporter goes with it, and the objects it supported are left
 * without one (flagged for labelling).
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "RemoveObject".
 */
export interface RemoveObject {
id: string
kind: "remove_object"
}
/**
 * Give an object another class (an NYU-40 class or a known alias, stored as for
 * AddObject). A pipeline re-run keeps it.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "SetClass".
 */
export interface SetClass {
class: string
id: string
kind: "set_class"
}
/**
 * Move or resize an object's box (inside the photo). A mask made from the box (GrabCut's
 * or the box's own) is cut again in the new box; a mask a person drew is clipped to it. A
 * pipeline re-run keeps the box.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "SetBbox".
 */
export interface SetBbox {
/**
 * [x1, y1, x2, y2] in pixels, inside the photo
 * 
 * @minItems 4
 * @maxItems 4
 */
bbox: [number, number, number, number]
id: string
kind: "set_bbox"
}
/**
 * Replace an object's mask with one a person drew (brush, eraser, polygon or refined
 * strokes). It is stored with source "manual" and the object's box becomes the mask's
 * extent. A pipeline re-run keeps it.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "SetMask".
 */
export interface SetMask {
id: string
kind: "set_mask"
mask: Mask
}
/**
 * Put an object back exactly as it was in revision `from_revision` (class, box, mask and
 * all), with every support it took part in there whose objects still exist: undo of a
 * removal, a class, a box or a mask change. An object that revision did not have is removed
 * (undo of an addition).
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "RestoreObject".
 */
export interface RestoreObject {
from_revision: number
id: string
kind: "restore_object"
}
/**
 * Put the whole scene back as revision `from_revision` had it: its objects (classes, boxes,
 * masks, 3D boxes, shapes), supports, room layout and camera, the objects people had removed,
 * and the pipeline stages behind them. The photo, its depth and the scene's name stay. The
 * history's "Revert to this"; undo is a restore_scene of the revision before it.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "RestoreScene".
 */
export interface RestoreScene {
from_revision: number
kind: "restore_scene"
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "ErrorMessage".
 */
export interface ErrorMessage {
detail: string
}
/**
 * Another registered model's figures on a retrain's held-out scenes (a shipped detector
 * that is neither the new model nor its parent gets figures no other way).
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "HeldoutFigure".
 */
export interface HeldoutFigure {
/**
 * As ModelInfo.heldout_accuracy
 */
accuracy: number
model_id: string
/**
 * As ModelInfo.heldout_recall
 */
recall: (number | null)
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "ImageInfo".
 */
export interface ImageInfo {
/**
 * File name of the photo, relative to the scene's folder
 */
file: string
height: number
width: number
}
/**
 * A dataset uploaded as a .zip (POST /api/imports), imported in the background: each
 * photo becomes a scene, is skipped as imported before, or is left out with its error.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "ImportJob".
 */
export interface ImportJob {
/**
 * The uploaded file's name
 */
archive: string
created_at: string
/**
 * Of them, read so far
 */
done: number
/**
 * Why the whole import stopped
 */
error: (string | null)
errors: PhotoError[]
finished_at: (string | null)
/**
 * What the zip holds: COCO, LabelMe, SUN RGB-D, input folders
 */
format: (string | null)
id: string
/**
 * New scenes
 */
imported: ImportedPhoto[]
/**
 * Whether each new scene's pipeline is queued
 */
run_pipeline: boolean
/**
 * Photos with the same files imported before
 */
skipped: ImportedPhoto[]
started_by: (string | null)
status: ("queued" | "running" | "succeeded" | "failed" | "cancelled")
/**
 * Photos (and unreadable files) found in the zip
 */
total: number
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "PhotoError".
 */
export interface PhotoError {
/**
 * Why it was left out; nothing of it was stored
 */
message: string
/**
 * The photo's or file's name in the upload
 */
name: string
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "ImportedPhoto".
 */
export interface ImportedPhoto {
/**
 * The photo's name in the upload (a file or folder)
 */
name: string
/**
 * What was left out of the labels given with it (e.g. a support row of an unknown type), while the photo and the rest were imported; or that the same photo was stored before as another scene
 */
notes: string[]
/**
 * Its scene: made now, or imported before (skipped)
 */
scene_id: string
/**
 * That scene's name (a scene stored before may be named otherwise than the photo in this upload)
 */
scene_name: (string | null)
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "ImportResult".
 */
export interface ImportResult {
job: (Job | null)
/**
 * A scene stored before with this very photo file (the first), if any: the import went ahead, as a second scene of the photo, and the page says so
 */
same_photo: (SceneSummary | null)
scene: SceneSummary
}
/**
 * A background job: a pipeline run on one scene (all stages, or placement only), or
 * retraining a model of the registry (the Relation Network or the object detector).
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "Job".
 */
export interface Job {
/**
 * Pipeline jobs: the input
 */
base_revision: (number | null)
created_at: string
error: (string | null)
finished_at: (string | null)
id: string
kind: ("pipeline" | "placement" | "retrain" | "detector_retrain")
/**
 * What the job did so far, one line per step
 */
log: string
message: (string | null)
progress: number
/**
 * Retrain jobs: the model they registered
 */
result_model_id: (string | null)
result_revision: (number | null)
/**
 * The scene of a pipeline or placement job
 */
scene_id: (string | null)
stage: (string | null)
/**
 * Who asked for the job: an account's name, or 'import' (unknown for jobs from before this was recorded)
 */
started_by: (string | null)
status: ("queued" | "running" | "succeeded" | "failed" | "cancelled")
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "SceneSummary".
 */
export interface SceneSummary {
/**
 * 1, or 2 once a reviewer asked for a second, independent annotation
 */
annotation_round: number
/**
 * When an admin archived it: out of the list, 'Next scene', reviews, retraining and batch runs, and read only, until restored
 */
archived_at: (string | null)
archived_by: (string | null)
/**
 * The annotator working on it
 */
assignee: (string | null)
created_at: string
height: number
id: string
/**
 * The later of its latest revision and its latest workflow step (taken, submitted, accepted...): what the scene list shows as Updated
 */
last_activity_at: (string | null)
latest_job: (Job | null)
name: string
object_count: number
revision: number
state: ("new" | "predicted" | "in_annotation" | "submitted" | "accepted" | "rejected")
/**
 * Mean over the objects of 1 - confidence of their supporter (1 without one, 0 when a person set it); 1 for a scene without objects; 'Next scene' picks the highest
 */
uncertainty: (number | null)
/**
 * When its latest revision was stored
 */
updated_at: string
width: number
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "Layout".
 */
export interface Layout {
/**
 * Room cuboid corners in the image, order of corners_3d; null for a corner behind the camera (it has no image point)
 */
corners_2d: ([([number, number] | null), ([number, number] | null), ([number, number] | null), ([number, number] | null), ([number, number] | null), ([number, number] | null), ([number, number] | null), ([number, number] | null)] | null)
corners_3d: ([[number, number, number], [number, number, number], [number, number, number], [number, number, number], [number, number, number], [number, number, number], [number, number, number], [number, number, number]] | null)
note: (string | null)
source: (("estimated" | "manual" | "ground_truth") | null)
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "LoginRequest".
 */
export interface LoginRequest {
name: string
password: string
/**
 * Return the session token in the answer (scripts: send it as 'Authorization: Bearer'); the browser uses the HttpOnly cookie instead
 */
token: boolean
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "LoginResult".
 */
export interface LoginResult {
expires_at: string
token: (string | null)
user: CurrentUser
}
/**
 * GrabCut in a box, steered by strokes a person painted: pixels under `foreground`
 * strokes are the object, under `background` strokes they are not. Nothing is stored.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "MaskRefineRequest".
 */
export interface MaskRefineRequest {
/**
 * @maxItems 200
 */
background: Stroke[]
/**
 * [x1, y1, x2, y2] in pixels, inside the photo
 * 
 * @minItems 4
 * @maxItems 4
 */
bbox: [number, number, number, number]
/**
 * @maxItems 200
 */
foreground: Stroke[]
}
/**
 * A brush stroke: a polyline of pixel points painted with a round brush.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "Stroke".
 */
export interface Stroke {
/**
 * @minItems 1
 * @maxItems 5000
 */
points: [[number, number], ...([number, number])[]]
/**
 * Brush radius in pixels
 */
radius: number
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "MaskRefineResult".
 */
export interface MaskRefineResult {
mask: Mask1
/**
 * Time the cut took on the server
 */
milliseconds: number
}
/**
 * A binary mask inside a window of the image, run-length encoded row by row.
 * 
 * `rle` alternates runs of 0 and 1 pixels, starting with a (possibly empty) run of 0.
 */
export interface Mask1 {
/**
 * [x, y] of the window's top-left pixel
 * 
 * @minItems 2
 * @maxItems 2
 */
origin: [number, number]
rle: number[]
/**
 * [width, height] of the window
 * 
 * @minItems 2
 * @maxItems 2
 */
size: [number, number]
source: ("given" | "box" | "grabcut" | "model" | "ground_truth" | "manual")
}
/**
 * Where an object's mesh comes from: the built-in library (class + seed), a file,
 * `completion`: completed from the object's depth points, or `learned`: the class template
 * deformed by the mesh network (those two meshes are only in the GLB).
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "MeshRef".
 */
export interface MeshRef {
class: string
file: (string | null)
library: ("builtin" | "user" | "completion" | "learned")
seed: (number | null)
}
/**
 * One change of the active model: who made which model active, when.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "ModelEvent".
 */
export interface ModelEvent {
action: ("seed" | "promote" | "rollback")
actor: string
at: string
id: number
model_id: string
model_version: number
note: (string | null)
previous_model_id: (string | null)
previous_version: (number | null)
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "ModelInfo".
 */
export interface ModelInfo {
active: boolean
created_at: string
has_curve: boolean
/**
 * On the held-out labelled scenes: support accuracy (relation), or mAP@0.5 of the confirmed boxes (detector); promotion compares this figure
 */
heldout_accuracy: (number | null)
/**
 * What those scenes held to score: labelled objects (relation) or confirmed boxes (detector); a handful decides little
 */
heldout_items: (number | null)
/**
 * The other registered models of its kind, measured on the same held-out scenes as this one when it was trained (detectors)
 */
heldout_others: HeldoutFigure[]
/**
 * Detector: share of the held-out confirmed boxes found with the right class (IoU 0.5)
 */
heldout_recall: (number | null)
/**
 * Labelled scenes it was evaluated on
 */
heldout_scenes: number
id: string
/**
 * The retrain job that made it
 */
job_id: (string | null)
/**
 * relation: a Relation Network (supports); detector: an object detector
 */
kind: ("relation" | "detector")
/**
 * The model's metrics.json
 */
metrics: {
[k: string]: unknown
}
/**
 * What the model is, from its metadata.json (detectors: which network, trained on what); None when it does not say
 */
name: (string | null)
note: (string | null)
/**
 * The parent's figure on the same held-out scenes
 */
parent_heldout_accuracy: (number | null)
/**
 * Detector: the parent's recall on the same held-out scenes
 */
parent_heldout_recall: (number | null)
/**
 * The model that was active when this one was trained
 */
parent_id: (string | null)
parent_version: (number | null)
status: ("default" | "accepted" | "candidate" | "rejected")
/**
 * Labelled scenes it was trained on
 */
training_scenes: number
/**
 * On the training run's own validation split: accuracy (relation), or mAP@0.5 on synthetic rooms (detector)
 */
validation_accuracy: (number | null)
/**
 * Counted per kind
 */
version: number
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "NewUser".
 */
export interface NewUser {
/**
 * Lower-case letters, digits, '.', '_' and '-'
 */
name: string
password: string
role: ("annotator" | "reviewer" | "admin")
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "PasswordChange".
 */
export interface PasswordChange {
current_password: string
new_password: string
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "PasswordReset".
 */
export interface PasswordReset {
password: string
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "PromoteRequest".
 */
export interface PromoteRequest {
author: string
note: (string | null)
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "RejectRequest".
 */
export interface RejectRequest {
/**
 * What went wrong
 */
comment: string
/**
 * The revision the reviewer looked at (the latest)
 */
revision: number
}
/**
 * An object a person removed: a pipeline re-run does not bring it back (an object it
 * finds overlapping this box is taken as the same one).
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "RemovedObject".
 */
export interface RemovedObject {
/**
 * [x1, y1, x2, y2]
 * 
 * @minItems 4
 * @maxItems 4
 */
bbox: [number, number, number, number]
class: ("wall" | "floor" | "cabinet" | "bed" | "chair" | "sofa" | "table" | "door" | "window" | "bookshelf" | "picture" | "counter" | "blinds" | "desk" | "shelves" | "curtain" | "dresser" | "pillow" | "mirror" | "floor_mat" | "clothes" | "ceiling" | "books" | "refrigerator" | "television" | "paper" | "towel" | "shower_curtain" | "box" | "whiteboard" | "person" | "night_stand" | "toilet" | "sink" | "lamp" | "bathtub" | "bag" | "otherstructure" | "otherfurniture" | "otherprop")
id: string
}
/**
 * Whether a kind of model can be retrained now: how many stored scenes it could learn
 * from, how many of them it would hold out to judge the new model, and how many it needs.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "RetrainReadiness".
 */
export interface RetrainReadiness {
/**
 * Of those, the scenes held out to judge the new model, never trained on
 */
heldout_scenes: number
/**
 * Stored scenes the retraining would use
 */
labelled_scenes: number
/**
 * Labelled scenes needed before it can start
 */
needed: number
/**
 * A retrain of another kind of model, queued or running: one runs at a time, so this kind's waits for it ('a retrain of the Relation Network started by adam (40%)')
 */
other_retrain: (string | null)
/**
 * What counts as a labelled scene for this kind
 */
what: string
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "RetrainRequest".
 */
export interface RetrainRequest {
author: string
/**
 * Null: the kind's default (detector: epochs)
 */
max_epochs: (number | null)
/**
 * Synthetic rooms trained on beside the stored scenes; null: the default
 */
synthetic_scenes: (number | null)
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "ReviewRequest".
 */
export interface ReviewRequest {
comment: (string | null)
/**
 * The revision the reviewer looked at (the latest)
 */
revision: number
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "RevisionInfo".
 */
export interface RevisionInfo {
author: string
created_at: string
edits: ((SetSupport | RemoveSupport | RestoreSupport | SetLayout | AddObject | RemoveObject | SetClass | SetBbox | SetMask | RestoreObject | RestoreScene)[] | null)
kind: ("import" | "pipeline" | "edit" | "reset")
number: number
summary: string
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "RoleChange".
 */
export interface RoleChange {
role: ("annotator" | "reviewer" | "admin")
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "Scene".
 */
export interface Scene {
camera: (Camera | null)
/**
 * Depth along the optical axis
 */
depth: (DepthRef | null)
image: ImageInfo
layout: Layout
name: string
objects: SceneObject[]
/**
 * Objects people removed; a re-run leaves them out
 */
removed_by_person: RemovedObject[]
schema_version: 1
/**
 * Pipeline stages that produced this scene
 */
stages: StageRun[]
supports: SupportRelation[]
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "SceneObject".
 */
export interface SceneObject {
/**
 * [x1, y1, x2, y2]
 * 
 * @minItems 4
 * @maxItems 4
 */
bbox: [number, number, number, number]
box_3d: (Box3D | null)
/**
 * How likely the 3D box is right: the box refiner's estimate of the chance that it overlaps the true box at 3D IoU 0.15 or more; null where no model judged it
 */
box_3d_confidence: (number | null)
class: ("wall" | "floor" | "cabinet" | "bed" | "chair" | "sofa" | "table" | "door" | "window" | "bookshelf" | "picture" | "counter" | "blinds" | "desk" | "shelves" | "curtain" | "dresser" | "pillow" | "mirror" | "floor_mat" | "clothes" | "ceiling" | "books" | "refrigerator" | "television" | "paper" | "towel" | "shower_curtain" | "box" | "whiteboard" | "person" | "night_stand" | "toilet" | "sink" | "lamp" | "bathtub" | "bag" | "otherstructure" | "otherfurniture" | "otherprop")
corners_3d: ([[number, number, number], [number, number, number], [number, number, number], [number, number, number], [number, number, number], [number, number, number], [number, number, number], [number, number, number]] | null)
id: string
mask: (Mask | null)
mesh: (MeshRef | null)
note: (string | null)
/**
 * Detection confidence
 */
score: (number | null)
/**
 * What people set: 'object' when a person added it (drawn, or a detector suggestion accepted), and its class, box or mask when a person changed them. A pipeline re-run keeps all of these.
 */
set_by_person: ("object" | "class" | "bbox" | "mask")[]
/**
 * Where the object came from: boxes given with the photo, the object detector, or a person; null in scenes stored before sources were recorded
 */
source: (("given" | "detector" | "manual") | null)
/**
 * The class name as imported, before mapping to NYU-40
 */
source_class: (string | null)
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "StageRun".
 */
export interface StageRun {
/**
 * The learned model the stage ran, as the server's model registry names it (e.g. 'Relation Network v2'); None for stages without one, or runs outside a server
 */
model: (string | null)
name: string
note: (string | null)
seconds: number
/**
 * The note tells what the stage could not do (shown as a warning), not just what it found
 */
warning: boolean
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "SupportRelation".
 */
export interface SupportRelation {
author: (string | null)
child: string
confidence: (number | null)
/**
 * An object id, or 'floor', 'wall' or 'ceiling'
 */
parent: string
source: ("auto" | "manual")
time: (string | null)
type: ("below" | "behind")
}
/**
 * Scenes to download as one zip: per scene its scene.json, coco.json, photo and
 * scene.glb (when it has one); or, with `format`, what `holiscene export --format` writes.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "SceneArchiveRequest".
 */
export interface SceneArchiveRequest {
/**
 * None: a folder per scene (HoliScene's own archive, which Import a dataset takes back); else the export format of `holiscene export`
 */
format: (("coco" | "scene" | "total3d" | "total3d-training" | "relation-training" | "nyu-supports") | null)
/**
 * @minItems 1
 * @maxItems 500
 */
scene_ids: [string, ...(string)[]]
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "SceneDocument".
 */
export interface SceneDocument {
/**
 * The user asking may change this scene's supports and room layout now
 */
editable: boolean
/**
 * Why not, when editable is false (e.g. the scene is submitted for review, someone else is annotating it, or this is not the latest revision)
 */
editable_reason: (string | null)
revision: number
scene: Scene
scene_id: string
updated_at: string
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "SceneWorkflow".
 */
export interface SceneWorkflow {
annotation_round: number
/**
 * The admin who archived the scene: no workflow step until restored
 */
archived_by: (string | null)
assignee: (string | null)
/**
 * The user asking may change this scene's supports and room layout now
 */
editable: boolean
/**
 * Why not, when editable is false (e.g. the scene is submitted for review, someone else is annotating it, or this is not the latest revision)
 */
editable_reason: (string | null)
/**
 * Oldest first
 */
events: WorkflowEvent[]
/**
 * The reviewer's comment from the last rejection, until the scene is submitted again
 */
review_comment: (string | null)
revision: number
scene_id: string
state: ("new" | "predicted" | "in_annotation" | "submitted" | "accepted" | "rejected")
}
/**
 * One change of a scene's state (or assignee): who, when, on which revision, why.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "WorkflowEvent".
 */
export interface WorkflowEvent {
action: ("import" | "predict" | "claim" | "release" | "reopen" | "submit" | "withdraw" | "accept" | "reject" | "second_annotation" | "archive" | "unarchive")
actor: string
annotation_round: number
/**
 * The annotator concerned
 */
assignee: (string | null)
at: string
comment: (string | null)
from_state: (("new" | "predicted" | "in_annotation" | "submitted" | "accepted" | "rejected") | null)
id: number
revision: number
to_state: ("new" | "predicted" | "in_annotation" | "submitted" | "accepted" | "rejected")
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "SecondAnnotationRequest".
 */
export interface SecondAnnotationRequest {
comment: (string | null)
/**
 * The revision the reviewer looked at (the latest)
 */
revision: number
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "SubmitRequest".
 */
export interface SubmitRequest {
/**
 * The revision the annotator submits (the latest)
 */
revision: number
}
/**
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "UserInfo".
 */
export interface UserInfo {
created_at: string
/**
 * An admin disabled the account: it cannot log in and its sessions ended
 */
disabled: boolean
/**
 * Since when, if disabled
 */
disabled_at: (string | null)
name: string
role: ("annotator" | "reviewer" | "admin")
}
/**
 * The answer of POST /api/scenes/{id}/viewer: the scene's viser viewer, started on demand.
 * 
 * This interface was referenced by `HoliSceneContract`'s JSON-Schema
 * via the `definition` "ViewerInfo".
 */
export interface ViewerInfo {
/**
 * The same viewer from a shell
 */
command: string
/**
 * The revision the viewer shows
 */
revision: number
scene_id: string
/**
 * The viewer's page, on 127.0.0.1
 */
url: string
}

"""A scene as viser nodes and a review panel, on a running `viser.ViserServer`.

Scene tree (names are stable, tests and reviewers can rely on them):
  /room/floor, /room/walls, /room/edges   the layout's cuboid: floor, translucent walls and
                                          ceiling facing inwards, and its 12 edges
  /objects/<id>                           each placed object's mesh, coloured as its mask
  /labels/<id>                            "<id> <class>" above each placed object
  /supports/<child id>                    one arrow per support, supporter -> supported
  /camera/photo                           the camera frustum with the photo on it
  /depth/partial/<id>, /depth/completed/<id>
                                          with depth: what the depth saw of each object and
                                          what shape completion made of it (hidden at first)
  /highlight                              the selected object's box edges
The panel has the scene's summary, toggles, an object dropdown with the selected object's
details (class, supporter, type, confidence, source), and a table of every object. Picking an
object in the dropdown or clicking its mesh highlights it and dims the others.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable
from dataclasses import dataclass

import cv2
import numpy as np
import viser
import viser.transforms as vtf
from holiscene_schema import STRUCTURAL_SUPPORTERS, SceneObject, SupportRelation
from numpy.typing import NDArray

from ..export.glb import room_meshes
from ..geometry.camera import FloatArray, PinholeCamera
from ..learning.completion.scene_points import DepthPointsError, scene_depth_points
from .colours import object_colours
from .geometry import (
    box_edge_segments,
    object_corners,
    room_corners,
    scene_centre,
    support_arrows,
)
from .meshes import MeshSource, object_meshes
from .sources import ViewerInput

BELOW_RGB = (220, 38, 38)  # thesis figures: red = supported from below
BEHIND_RGB = (37, 99, 235)  # blue = supported from behind
HIGHLIGHT_RGB = (255, 196, 0)
FLOOR_RGB = (200, 200, 200)
WALL_RGB = (222, 218, 210)
EDGE_RGB = (90, 90, 90)
WALL_OPACITY = 0.25
DIMMED_OPACITY = 0.25
SEE_THROUGH_OPACITY = 0.4  # every object while the depth points (on their surfaces) are shown
# The depth points, as the workbench's 3D view draws them: seen by the depth camera, and
# completed by the shape completion network.
PARTIAL_RGB = (249, 115, 22)
COMPLETED_RGB = (13, 148, 136)
POINT_SIZE_M = 0.012
FRUSTUM_SCALE = 0.45  # metres: the photo stays small beside a room of a few metres
PHOTO_MAX_SIDE = 640  # pixels sent to the browser for the frustum's image
NO_SELECTION = "(none)"
VIEW_FROM_CAMERA = (-2.0, 2.0, -1.6)  # start of the review view, from the photo's camera
VIEW_TARGET_FRACTION = 0.35  # of the way from the camera to the room's centre


@dataclass
class _ObjectNode:
    obj: SceneObject
    mesh: viser.MeshHandle
    source: MeshSource
    corners: FloatArray


def _photo_for_frustum(photo: NDArray[np.uint8]) -> NDArray[np.uint8]:
    height, width = photo.shape[:2]
    factor = PHOTO_MAX_SIDE / max(height, width)
    if factor >= 1.0:
        return photo
    size = (max(1, round(width * factor)), max(1, round(height * factor)))
    small: NDArray[np.uint8] = np.asarray(
        cv2.resize(photo, size, interpolation=cv2.INTER_AREA), dtype=np.uint8
    )
    return small


# What made a mesh the viewer shows from scene.glb (MeshRef.library), for the object's details:
# the web page's badge word ("mesh: learned"), then what it means.
MESH_MAKERS = {
    "builtin": "library (the furniture library's fit)",
    "user": "file (a user's model)",
    "completion": "from depth (shape completion)",
    "learned": "learned (the mesh network's template)",
}


def _mesh_text(obj: SceneObject, source: MeshSource) -> str:
    """Where the shown mesh comes from: the stage that made it when it is the GLB's."""
    if source != "scene.glb" or obj.mesh is None:
        return source
    return f"{MESH_MAKERS[obj.mesh.library]} (from scene.glb)"


def _fmt(value: float | None, digits: int = 2) -> str:
    return "-" if value is None else f"{value:.{digits}f}"


def _percent(share: float | None) -> str:
    """A score or confidence as the web page writes it: whole percent, rounded down (so 99.6%
    never reads as a sure 100%)."""
    return "-" if share is None else f"{math.floor(100 * share + 1e-9)}%"


class SceneViewer:
    """Builds the nodes and panel of one scene on `server`; `rebuild` swaps in another."""

    def __init__(self, server: viser.ViserServer, data: ViewerInput) -> None:
        self.server = server
        self._lock = threading.RLock()
        self.objects: dict[str, _ObjectNode] = {}
        self.arrows: dict[str, viser.ArrowsHandle] = {}
        self.labels: dict[str, viser.LabelHandle] = {}
        self.depth_points: dict[str, viser.PointCloudHandle] = {}  # by node name
        self.room: dict[str, viser.SceneNodeHandle] = {}
        self.frustum: viser.CameraFrustumHandle | None = None
        self.highlight: viser.LineSegmentsHandle | None = None
        self.selected: str | None = None
        self.notes: list[str] = []
        self._build(data)

    # -- building ------------------------------------------------------------------------

    def rebuild(self, data: ViewerInput) -> None:
        with self._lock:
            self.server.scene.reset()
            self.server.gui.reset()
            self.objects.clear()
            self.arrows.clear()
            self.labels.clear()
            self.depth_points.clear()
            self.room.clear()
            self.frustum = self.highlight = None
            self.selected = None
            self._build(data)

    def _build(self, data: ViewerInput) -> None:
        self.data = data
        self.scene = data.scene
        self.notes = list(data.notes)
        self.server.scene.set_up_direction("+y")
        self._add_room()
        self._add_objects()
        self._add_arrows()
        self._add_camera()
        self._add_depth_points()
        self._place_view()
        self._add_panel()

    def _add_room(self) -> None:
        corners = room_corners(self.scene)
        if corners is None:
            self.notes.append("no room layout: the room is not drawn")
            return
        quads = room_meshes(corners)
        floor_mesh, _ = quads.pop("floor")
        self.room["floor"] = self.server.scene.add_mesh_simple(
            "/room/floor",
            np.asarray(floor_mesh.vertices, dtype=np.float32),
            np.asarray(floor_mesh.faces, dtype=np.int32),
            color=FLOOR_RGB,
            side="double",
        )
        # Walls and ceiling face inwards and are single-sided: seen from outside the room
        # (the usual review position) the near ones vanish and the far ones stay.
        vertices: list[FloatArray] = []
        faces: list[NDArray[np.int64]] = []
        offset = 0
        for quad, _colour in quads.values():
            faces.append(np.asarray(quad.faces, dtype=np.int64) + offset)
            vertices.append(np.asarray(quad.vertices, dtype=float))
            offset += len(quad.vertices)
        self.room["walls"] = self.server.scene.add_mesh_simple(
            "/room/walls",
            np.vstack(vertices).astype(np.float32),
            np.vstack(faces).astype(np.int32),
            color=WALL_RGB,
            opacity=WALL_OPACITY,
            side="front",
            cast_shadow=False,
            receive_shadow=False,
        )
        self.room["edges"] = self.server.scene.add_line_segments(
            "/room/edges",
            box_edge_segments(corners),
            EDGE_RGB,
            thickness=1.5,
            thickness_units="screen",  # thin however close the review camera comes
        )

    def _add_objects(self) -> None:
        plan = object_meshes(self.scene, self.data.glb, self.data.models_dir)
        self.notes.extend(plan.notes)
        # As the scene page colours each object's mask: one object, one colour in both views.
        colours = object_colours([o.id for o in self.scene.objects])
        for obj in self.scene.objects:
            mesh = plan.meshes.get(obj.id)
            corners = object_corners(obj)
            if mesh is None or corners is None:
                continue
            handle = self.server.scene.add_mesh_simple(
                f"/objects/{obj.id}",
                mesh.vertices,
                mesh.faces,
                color=colours[obj.id],
                side="double",
                flat_shading=True,
            )
            handle.on_click(self._on_click(obj.id))
            self.objects[obj.id] = _ObjectNode(obj, handle, mesh.source, corners)
            top = corners.mean(axis=0) + np.array([0.0, (np.ptp(corners[:, 1])) / 2 + 0.05, 0.0])
            self.labels[obj.id] = self.server.scene.add_label(
                f"/labels/{obj.id}",
                f"{obj.id} {obj.cls}",
                position=top,
                font_screen_scale=0.7,
                anchor="bottom-center",
            )

    def _on_click(
        self, obj_id: str
    ) -> Callable[[viser.SceneNodePointerEvent[viser.MeshHandle]], None]:
        def clicked(_event: viser.SceneNodePointerEvent[viser.MeshHandle]) -> None:
            self.select(obj_id)

        return clicked

    def _add_arrows(self) -> None:
        plan = support_arrows(self.scene)
        self._arrow_skipped = plan.skipped
        for arrow in plan.arrows:
            self.arrows[arrow.child] = self.server.scene.add_arrows(
                f"/supports/{arrow.child}",
                np.stack([arrow.start, arrow.end])[None].astype(np.float32),
                BELOW_RGB if arrow.type == "below" else BEHIND_RGB,
                shaft_radius=0.015,
                head_radius=0.05,
                head_length=0.12,
            )

    def _add_camera(self) -> None:
        camera = self.scene.camera
        if camera is None:
            self.notes.append("no camera: the photo's frustum is not drawn")
            return
        K = np.asarray(camera.K, dtype=float)
        if camera.pitch_deg is None or camera.roll_deg is None:
            self.notes.append("camera pitch/roll unknown: the frustum is drawn level")
        pinhole = PinholeCamera(K, camera.pitch_deg or 0.0, camera.roll_deg or 0.0)
        width, height = self.scene.image.width, self.scene.image.height
        # viser frustums follow OpenCV axes, as `world_from_cv` does.
        wxyz = vtf.SO3.from_matrix(pinhole.world_from_cv).wxyz
        photo = self.data.photo
        self.frustum = self.server.scene.add_camera_frustum(
            "/camera/photo",
            fov=2.0 * math.atan2(height / 2.0, float(K[1, 1])),
            aspect=width / height,
            scale=FRUSTUM_SCALE,
            color=(30, 30, 30),
            thickness=0.006,
            image=_photo_for_frustum(photo) if photo is not None else None,
            format="jpeg",
            wxyz=wxyz,
            position=(0.0, 0.0, 0.0),
        )

    def _add_depth_points(self) -> None:
        if self.data.depth is None:
            return
        try:
            found = scene_depth_points(self.scene, self.data.depth)
        except DepthPointsError as exc:
            self.notes.append(f"no depth points: {exc}")
            return
        for entry in found:
            for kind, points, colour in (
                ("partial", entry.partial, PARTIAL_RGB),
                ("completed", entry.completed, COMPLETED_RGB),
            ):
                if points is None or len(points) == 0:
                    continue
                name = f"/depth/{kind}/{entry.id}"
                self.depth_points[name] = self.server.scene.add_point_cloud(
                    name,
                    np.asarray(points, dtype=np.float32),
                    colour,
                    point_size=POINT_SIZE_M,
                    point_shape="circle",
                    visible=False,
                )

    def _place_view(self) -> None:
        """Start above and behind the photo's camera, to its left, looking a third of the way
        into the room: the frustum with the photo sits in the foreground with the room
        beyond it, the near walls and the ceiling (single-sided, facing in) out of the way."""
        target = scene_centre(self.scene) * VIEW_TARGET_FRACTION + np.array([0.0, -0.3, 0.0])
        self.server.initial_camera.position = VIEW_FROM_CAMERA
        self.server.initial_camera.look_at = target
        self.server.initial_camera.up = (0.0, 1.0, 0.0)

    # -- the panel -----------------------------------------------------------------------

    def _supports_by_child(self) -> dict[str, SupportRelation]:
        return {s.child: s for s in self.scene.supports}

    def _supporter_text(self, parent: str) -> str:
        if parent in STRUCTURAL_SUPPORTERS:
            return parent
        cls = next((o.cls for o in self.scene.objects if o.id == parent), "?")
        return f"{parent} ({cls})"

    def _add_panel(self) -> None:
        gui = self.server.gui
        gui.configure_theme(control_width="large", show_share_button=False, dark_mode=False)
        gui.set_panel_label(f"HoliScene · {self.scene.name}")
        gui.add_markdown(self._summary_markdown())

        with gui.add_folder("Show"):
            self._add_toggle("Room", list(self.room.values()))
            self._add_toggle("Support arrows", list(self.arrows.values()))
            self._add_toggle("Labels", list(self.labels.values()))
            self._add_toggle("Photo frustum", [self.frustum] if self.frustum else [])
            self.depth_toggle = self._add_toggle(
                "Depth points", list(self.depth_points.values()), initial=False
            )

        @self.depth_toggle.on_update
        def _(_event: viser.GuiEvent[viser.GuiCheckboxHandle]) -> None:
            self._set_opacities()

        self._choices = {NO_SELECTION: None} | {
            f"{o.id} · {o.cls}": o.id for o in self.scene.objects
        }
        self._label_of = {obj_id: label for label, obj_id in self._choices.items()}
        with gui.add_folder("Object"):
            self.dropdown = gui.add_dropdown(
                "Object", tuple(self._choices), initial_value=NO_SELECTION
            )
            self.details = gui.add_markdown(self._details_markdown(None))

        @self.dropdown.on_update
        def _(_event: viser.GuiEvent[viser.GuiDropdownHandle[str]]) -> None:
            self._show(self._choices.get(self.dropdown.value))

        with gui.add_folder("Objects and supports"):
            self.table = gui.add_markdown(self._table_markdown())

    def _add_toggle(
        self, label: str, handles: list[viser.SceneNodeHandle], initial: bool = True
    ) -> viser.GuiCheckboxHandle:
        box = self.server.gui.add_checkbox(label, initial, disabled=not handles)

        @box.on_update
        def _(_event: viser.GuiEvent[viser.GuiCheckboxHandle]) -> None:
            for handle in handles:
                handle.visible = box.value

        return box

    def _summary_markdown(self) -> str:
        scene = self.scene
        facts = [
            f"{len(scene.objects)} objects ({len(self.objects)} in 3D), "
            f"{len(scene.supports)} supports, {len(self.arrows)} arrows: "
            "red = from below, blue = from behind."
        ]
        camera = scene.camera
        if camera is not None:
            facts.append(
                f"Camera: pitch {_fmt(camera.pitch_deg, 1)}°, roll {_fmt(camera.roll_deg, 1)}°, "
                f"height {_fmt(camera.height_m)} m ({camera.height_source or '-'})."
            )
        sources: dict[str, int] = {}
        for node in self.objects.values():
            sources[node.source] = sources.get(node.source, 0) + 1
        if sources:
            facts.append(
                "Meshes: " + ", ".join(f"{n} from {s}" for s, n in sorted(sources.items())) + "."
            )
        if self.depth_points:
            facts.append(
                "Depth points (Show, Depth points): orange = seen by the depth camera, "
                "teal = completed by shape completion."
            )
        text = f"**{scene.name}** — {self.data.origin}\n\n" + "  \n".join(facts)
        if self.notes:
            text += "\n\n" + "\n".join(f"- {note}" for note in self.notes)
        return text

    def _details_markdown(self, obj_id: str | None) -> str:
        if obj_id is None:
            return "Pick an object here or click it in the scene."
        obj = next(o for o in self.scene.objects if o.id == obj_id)
        support = self._supports_by_child().get(obj_id)
        rows: list[tuple[str, str]] = [("class", obj.cls)]
        if obj.source_class and obj.source_class != obj.cls:
            rows.append(("class as imported", obj.source_class))
        if support is None:
            rows.append(("supporter", "none (needs a label)"))
        else:
            rows += [
                ("supporter", self._supporter_text(support.parent)),
                ("type", support.type),
                ("confidence", _percent(support.confidence)),
                ("source", support.source + (f" ({support.author})" if support.author else "")),
            ]
        rows.append(("detection score", _percent(obj.score)))
        node = self.objects.get(obj_id)
        if node is None:
            rows.append(("3D", "no 3D box"))
        else:
            rows.append(("mesh", _mesh_text(obj, node.source)))
            if obj.box_3d is not None:
                size = " × ".join(f"{s:.2f}" for s in obj.box_3d.size)
                rows.append(("box size (d × h × w)", f"{size} m"))
                rows.append(("3D box confidence", _percent(obj.box_3d_confidence)))
        if obj_id in self._arrow_skipped:
            rows.append(("arrow", f"not drawn: {self._arrow_skipped[obj_id]}"))
        if obj.note:
            rows.append(("note", obj.note))
        body = "\n".join(f"| {key} | {value} |" for key, value in rows)
        return f"**{obj_id}**\n\n| | |\n|---|---|\n{body}"

    def _table_markdown(self) -> str:
        supports = self._supports_by_child()
        rows = []
        for obj in self.scene.objects:
            support = supports.get(obj.id)
            if support is None:
                rows.append(f"| {obj.id} | {obj.cls} | - | - | - |")
            else:
                rows.append(
                    f"| {obj.id} | {obj.cls} | {support.parent} | {support.type} | "
                    f"{_percent(support.confidence)} |"
                )
        header = "| object | class | supporter | type | conf. |\n|---|---|---|---|---|"
        return header + "\n" + "\n".join(rows) if rows else "No objects."

    # -- selection -----------------------------------------------------------------------

    def select(self, obj_id: str | None) -> None:
        """Highlight one object (None: none), in the scene and in the panel."""
        if obj_id is not None and obj_id not in self._label_of:
            raise KeyError(f"no object {obj_id!r}")
        with self._lock:
            self._show(obj_id)
            # viser's setter is real (it runs the callbacks); its typing hides it from mypy.
            self.dropdown.value = self._label_of[obj_id]  # type: ignore[misc]

    def _set_opacities(self) -> None:
        """Objects other than the selected one dimmed; all see-through while the depth points
        are shown."""
        see_through = self.depth_toggle.value
        for obj_id, node in self.objects.items():
            if self.selected not in (None, obj_id):
                node.mesh.opacity = DIMMED_OPACITY
            else:
                node.mesh.opacity = SEE_THROUGH_OPACITY if see_through else None

    def _show(self, obj_id: str | None) -> None:
        with self._lock:
            if obj_id == self.selected:
                return
            self.selected = obj_id
            self._set_opacities()
            if self.highlight is not None:
                self.highlight.remove()
                self.highlight = None
            chosen = self.objects.get(obj_id) if obj_id is not None else None
            if chosen is not None:
                self.highlight = self.server.scene.add_line_segments(
                    "/highlight", box_edge_segments(chosen.corners), HIGHLIGHT_RGB, thickness=0.02
                )
            self.details.content = self._details_markdown(obj_id)

"""One synthetic scene from a seed: plan, render, and the ground truth in the scene schema.

Output folder (an input folder for `holiscene infer`, plus the truth):
  img.png          the rendered photo
  cam_K.txt        exact intrinsics
  detections.json  the visible objects' 2D boxes and classes (objects[i] of gt.json)
  gt.json          the scene schema with every ground-truth field filled
  depth.png        16-bit depth along the optical axis, millimetres
"""

from __future__ import annotations

import json
import math
import os
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path

import cv2
import numpy as np
from holiscene_schema import (
    Box3D,
    Camera,
    DepthRef,
    ImageInfo,
    Layout,
    MeshRef,
    Scene,
    SceneObject,
    SupportRelation,
)

from ..geometry.boxes import box_corners
from ..geometry.camera import PinholeCamera, default_intrinsics, rot_y
from ..segmentation.rle import encode_mask
from . import ranges
from .materials import Material, Pattern, object_material, random_material
from .plan import DEFAULT_STYLE, PlannedObject, RoomPlan, RoomStyle, plan_room
from .render import ROOM_INSTANCE, Frame, Lighting, RenderItem, render

FLOOR_PATTERNS: tuple[Pattern, ...] = ("wood", "tiles", "fabric")


@dataclass(frozen=True)
class SyntheticScene:
    name: str
    truth: Scene
    frame: Frame
    K: np.ndarray


def _camera(plan: RoomPlan) -> PinholeCamera:
    width, height = ranges.IMAGE_SIZE
    return PinholeCamera(
        default_intrinsics(width, height, plan.hfov_deg), plan.pitch_deg, plan.roll_deg
    )


def _render_plan(plan: RoomPlan, keep: set[int], rng: np.random.Generator) -> Frame:
    world = plan.world_transform()
    floor, ceiling, walls = plan.room_mesh()
    items = [
        RenderItem(
            floor.copy().apply_transform(world),
            ROOM_INSTANCE,
            random_material(rng, FLOOR_PATTERNS[int(rng.integers(3))], (0.3, 0.8)),
        ),
        RenderItem(
            ceiling.copy().apply_transform(world),
            ROOM_INSTANCE,
            random_material(rng, "paint", (1.0, 2.0)),
        ),
        RenderItem(
            walls.copy().apply_transform(world),
            ROOM_INSTANCE,
            random_material(rng, "paint", (1.0, 3.0)),
        ),
    ]
    materials: dict[int, Material] = {}
    for obj in plan.objects:
        if obj.key in keep:
            mesh = obj.shape.mesh.copy().apply_transform(world @ obj.room_transform())
            material = object_material(rng, obj.cls)  # drawn always: the next draws stay put
            shared = None if obj.looks_like is None else materials.get(obj.looks_like)
            materials[obj.key] = shared or material
            items.append(RenderItem(mesh, obj.key, materials[obj.key]))
    light_room = np.array(
        [
            rng.uniform(-0.3, 0.3) * plan.depth,
            plan.height - 0.15,
            rng.uniform(-0.3, 0.3) * plan.width,
        ]
    )
    lighting = Lighting(
        position=plan.to_world(light_room[None, :])[0],
        intensity=float(rng.uniform(*ranges.LIGHT_INTENSITY)),
        ambient=float(rng.uniform(0.15, 0.3)),
    )
    return render(
        items,
        _camera(plan),
        ranges.IMAGE_SIZE,
        lighting,
        float(rng.uniform(*ranges.SENSOR_NOISE_SIGMA)),
        rng,
        texture_from_world=rot_y(math.radians(plan.yaw_deg)).T,
    )


def _descendants(plan: RoomPlan, roots: set[int]) -> set[int]:
    out = set(roots)
    grew = True
    while grew:
        grew = False
        for obj in plan.objects:
            if isinstance(obj.parent, int) and obj.parent in out and obj.key not in out:
                out.add(obj.key)
                grew = True
    return out


def _visible_keys(frame: Frame) -> dict[int, int]:
    ids, counts = np.unique(frame.instance[frame.instance >= 0], return_counts=True)
    return {int(i): int(c) for i, c in zip(ids, counts, strict=True)}


def synthesize(seed: int, style: RoomStyle = DEFAULT_STYLE) -> SyntheticScene:
    """Deterministic per seed. Objects too little visible to label are dropped with everything
    they hold up (so every labelled object's supporter is labelled too), then rendered again."""
    rng = np.random.default_rng(seed)
    plan = plan_room(rng, style)
    render_seed = int(rng.integers(2**31))
    keep = {o.key for o in plan.objects}
    for _ in range(4):
        frame = _render_plan(plan, keep, np.random.default_rng(render_seed))
        visible = _visible_keys(frame)
        hidden = {k for k in keep if visible.get(k, 0) < ranges.MIN_VISIBLE_PIXELS}
        dropped = _descendants(plan, hidden)
        if not (dropped - hidden) & set(visible):
            keep -= dropped
            break
        keep -= dropped  # something visible stood on a hidden object: render without it
    K = _camera(plan).K
    name = f"synth-{seed}{style.folder_suffix}"
    return SyntheticScene(name, _truth(plan, keep, frame, K, seed, name), frame, K)


def _truth(
    plan: RoomPlan, keep: set[int], frame: Frame, K: np.ndarray, seed: int, name: str
) -> Scene:
    height, width = frame.instance.shape
    kept = [o for o in plan.objects if o.key in keep]
    order = np.random.default_rng(seed + 1).permutation(len(kept))  # ids carry no placement order
    kept = [kept[i] for i in order]
    ids = {o.key: f"o{i}" for i, o in enumerate(kept)}
    objects = [_truth_object(plan, o, ids[o.key], frame) for o in kept]
    supports = [
        SupportRelation(
            child=ids[o.key],
            parent=ids[o.parent] if isinstance(o.parent, int) else o.parent,
            type=o.support_type,
            source="manual",
            confidence=1.0,
            author="synthetic",
        )
        for o in kept
    ]
    camera = _camera(plan)
    layout_corners = plan.to_world(
        box_corners(
            np.array([0.0, plan.height / 2, 0.0]),
            np.array([plan.depth, plan.height, plan.width]),
            0.0,
        )
    )
    layout_2d = [
        None if np.isnan(p).any() else [round(float(p[0]), 2), round(float(p[1]), 2)]
        for p in camera.project(layout_corners)
    ]
    return Scene(
        name=name,
        image=ImageInfo(file="img.png", width=width, height=height),
        camera=Camera(
            K=K.tolist(),
            K_source="given",
            pitch_deg=round(plan.pitch_deg, 4),
            roll_deg=round(plan.roll_deg, 4),
            height_m=round(float(plan.camera_position[1]), 4),
            height_source="ground_truth",
        ),
        layout=Layout(
            corners_2d=layout_2d,
            corners_3d=layout_corners.round(4).tolist(),
            source="ground_truth",
            note=f"{plan.theme} room {plan.depth:.2f} x {plan.width:.2f} x {plan.height:.2f} m",
        ),
        depth=DepthRef(file="depth.png", metres_per_unit=0.001),
        objects=objects,
        supports=supports,
    )


def _truth_object(plan: RoomPlan, obj: PlannedObject, obj_id: str, frame: Frame) -> SceneObject:
    pixels = frame.instance == obj.key
    rows, cols = np.flatnonzero(pixels.any(axis=1)), np.flatnonzero(pixels.any(axis=0))
    bbox = [float(cols[0]), float(rows[0]), float(cols[-1] + 1), float(rows[-1] + 1)]
    center = plan.to_world(obj.center[None, :])[0]
    yaw = (obj.yaw_deg + plan.yaw_deg + 180.0) % 360.0 - 180.0
    box = Box3D(
        center=center.round(4).tolist(), size=obj.size.round(4).tolist(), yaw_deg=round(yaw, 4)
    )
    return SceneObject(
        id=obj_id,
        cls=obj.cls,
        source_class=obj.cls,
        bbox=bbox,
        mask=encode_mask(pixels, "ground_truth"),
        box_3d=box,
        corners_3d=box_corners(center, obj.size, yaw).round(4).tolist(),
        mesh=MeshRef(library="builtin", cls=obj.cls, seed=obj.seed),
    )


def write_scene(scene: SyntheticScene, out_dir: Path) -> Path:
    """Write the scene folder atomically (a temporary folder renamed into place)."""
    out_dir.mkdir(parents=True, exist_ok=True)
    target = out_dir / scene.name
    staging = Path(tempfile.mkdtemp(prefix=f".{scene.name}-", dir=out_dir))
    try:
        cv2.imwrite(str(staging / "img.png"), cv2.cvtColor(scene.frame.rgb, cv2.COLOR_RGB2BGR))
        depth_mm = np.clip(np.round(scene.frame.depth * 1000.0), 0, 65535).astype(np.uint16)
        cv2.imwrite(str(staging / "depth.png"), depth_mm)
        (staging / "cam_K.txt").write_text(
            "\n".join(" ".join(f"{v:.6f}" for v in row) for row in scene.K) + "\n"
        )
        detections = [{"bbox": o.bbox, "class": o.cls} for o in scene.truth.objects]
        (staging / "detections.json").write_text(json.dumps(detections, indent=1))
        (staging / "gt.json").write_text(scene.truth.model_dump_json(indent=1))
        if target.exists():
            shutil.rmtree(target)
        os.replace(staging, target)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return target


def synthesize_to(seed: int, out_dir: Path, style: RoomStyle = DEFAULT_STYLE) -> Path:
    """Generate and write one scene (a top-level function, so worker processes can run it)."""
    return write_scene(synthesize(seed, style), out_dir)

"""One PNG per real photo: the photo with masks and the room layout, the Surface Network's
labels, and the reconstructed 3D scene rendered from the photo's camera and from above. For
looking, not for committing (the photos' terms forbid copying them into the repository):

    .venv/bin/python scripts/real_photo_sheets.py [OUT_DIR]   # default /tmp/holiscene-real
"""

from __future__ import annotations

import sys
from pathlib import Path

import cv2
import numpy as np
import trimesh
from holiscene.core.settings import REPO_ROOT
from holiscene.export.glb import class_colour
from holiscene.geometry.camera import PinholeCamera
from holiscene.geometry.surface_map import load_surface_model
from holiscene.inputs import read_input_folder
from holiscene.segmentation.rle import decode_mask
from holiscene.services.reconstruction import reconstruct_scene
from holiscene.synth.materials import Material
from holiscene.synth.render import Lighting, RenderItem, render

PHOTOS = REPO_ROOT.parent / "shared" / "data" / "real"
LAYOUT_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
                (0, 4), (1, 5), (2, 6), (3, 7)]  # fmt: skip


def _overlay(rgb: np.ndarray, scene) -> np.ndarray:  # type: ignore[no-untyped-def]
    image = cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR)
    tinted = image.copy()
    h, w = image.shape[:2]
    for obj in scene.objects:
        if obj.mask is not None:
            r, g, b, _ = class_colour(obj.cls)
            tinted[decode_mask(obj.mask, w, h)] = (b, g, r)
    out = cv2.addWeighted(image, 0.5, tinted, 0.5, 0)
    corners = scene.layout.corners_2d or []
    for a, b in LAYOUT_EDGES:
        if corners and corners[a] is not None and corners[b] is not None:
            pa = tuple(int(v) for v in np.clip(corners[a], -9999, 9999))
            pb = tuple(int(v) for v in np.clip(corners[b], -9999, 9999))
            cv2.line(out, pa, pb, (255, 0, 255), 2, cv2.LINE_AA)
    return out


SURFACE_COLOURS = np.array(  # BGR: floor green, ceiling yellow, front wall red, side wall blue
    [[60, 160, 60], [60, 200, 220], [60, 60, 220], [220, 90, 60]], dtype=np.uint8
)


def _surface_panel(rgb: np.ndarray) -> np.ndarray:
    """What the Surface Network sees: its most probable label per cell over the photo."""
    labels = load_surface_model().label_map(rgb)
    h, w = rgb.shape[:2]
    colours = cv2.resize(SURFACE_COLOURS[labels], (w, h), interpolation=cv2.INTER_NEAREST)
    return cv2.addWeighted(cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR), 0.5, colours, 0.5, 0)


def _load_glb(glb: bytes) -> trimesh.Scene:
    return trimesh.load_scene(trimesh.util.wrap_as_stream(glb), file_type="glb")


def _render_scene(
    loaded: trimesh.Scene, camera: PinholeCamera, size: tuple[int, int], walls: bool = True
) -> np.ndarray:
    items: list[RenderItem] = []
    for name, geometry in loaded.geometry.items():
        if not walls and (name == "ceiling" or name.startswith("wall_")):
            continue  # seen from above, the room is a floor
        mesh = geometry.copy()
        mesh.apply_transform(loaded.graph.get(name)[0] if name in loaded.graph.nodes else np.eye(4))
        colour = getattr(mesh.visual, "material", None)
        rgba = getattr(colour, "baseColorFactor", None)
        rgb = (np.array(rgba[:3]) / 255.0) if rgba is not None else np.array([0.8, 0.8, 0.8])
        material = Material("paint", (float(rgb[0]), float(rgb[1]), float(rgb[2])), 1.0, 0.0)
        items.append(RenderItem(mesh, len(items), material))
    light = Lighting(position=np.array([2.0, 1.0, 0.0]), intensity=1.0, ambient=0.35)
    frame = render(items, camera, size, light, 0.0, np.random.default_rng(0))
    return cv2.cvtColor(frame.rgb, cv2.COLOR_RGB2BGR)


def main() -> int:
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("/tmp/holiscene-real")
    out.mkdir(parents=True, exist_ok=True)
    for folder in sorted(p for p in PHOTOS.iterdir() if p.is_dir()):
        inputs = read_input_folder(folder)
        result = reconstruct_scene(inputs, name=folder.name, image_file="img.jpg")
        scene, cam = result.scene, result.scene.camera
        panels = [_overlay(inputs.photo.rgb, scene), _surface_panel(inputs.photo.rgb)]
        if result.glb is not None and cam is not None and cam.pitch_deg is not None:
            size = (inputs.photo.width, inputs.photo.height)
            K = np.array(cam.K)
            panels.append(
                _render_scene(
                    _load_glb(result.glb),
                    PinholeCamera(K, cam.pitch_deg, cam.roll_deg or 0.0),
                    size,
                )
            )
            # From above and behind the camera, looking down at the room.
            above = PinholeCamera(K, 50.0, 0.0)
            lifted = _load_glb(result.glb)
            lifted.apply_translation([2.5, -3.5, 0.0])
            panels.append(_render_scene(lifted, above, size, walls=False))
        cv2.imwrite(str(out / f"{folder.name}.png"), np.hstack(panels))
        print(out / f"{folder.name}.png")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

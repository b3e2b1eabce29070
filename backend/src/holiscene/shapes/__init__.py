"""Parametric furniture: a mesh per NYU-40 class that fills a given 3D box exactly.

Used by the synthetic scene generator (meshes to ray cast, with support surfaces to put
things on) and as the default model library of reconstruction (each object's box replaced
by a fitted mesh).

Conventions
-----------
- Canonical frame: metres, right-handed, y up, the object's front facing +x, z to its
  right; the same local frame as a contract 3D box (centre, size, yaw about +y).
- size = (d, h, w) = (depth along x, height along y, width along z). A shape of that size
  has axis-aligned bounds exactly [-d/2, d/2] x [-h/2, h/2] x [-w/2, w/2]: it touches all
  six faces of its box, so placing it with the box's centre and yaw reproduces the box.
- "Front": where a user faces the object. A chair's or sofa's back and a bed's headboard
  are at -x; drawers, doors, screens and pictures face +x; wall items have their back at
  -x, against the wall.
- Watertight where sensible: a shape is a union of parts, each a closed, consistently
  outward-oriented triangle mesh (boxes, cylinders, solids of revolution, extruded
  sheets). Parts may touch or overlap; they are not boolean-merged, and no vertex is
  shared between parts, so trimesh reports the whole mesh watertight too, but it is not
  one 2-manifold surface. Thin things (pictures, curtains, screens) are thin closed solids.
- Modest triangle counts: round parts use 12-16 sections; every class stays under about
  2.5k faces (a chair under 2k), so a room of 30 objects ray casts quickly.
- Support surfaces: horizontal rectangles in the canonical frame (a height y, an x range
  and a z range) on which other objects can stand, with the free height above them.
- Randomness: every parameter comes from the `numpy.random.Generator` passed in, so a
  shape is a function of (class, size, rng state).

API
---
`generate_shape(cls, size, rng) -> Shape`, `typical_size(cls, rng) -> (d, h, w)`,
`SUPPORTED_CLASSES` (parametric; any other NYU-40 class gets a plain box),
`fit_to_box(mesh, size)`, and `load_model_folder(folder)` / `shape_from_mesh(mesh, size)`
for user models.
"""

from .fitting import fit_to_box
from .library import GENERIC_CLASSES, SIZE_RANGES, SUPPORTED_CLASSES, generate_shape, typical_size
from .shape import Shape, SupportSurface
from .user_models import MODEL_SUFFIXES, load_model_folder, shape_from_mesh

__all__ = [
    "GENERIC_CLASSES",
    "MODEL_SUFFIXES",
    "SIZE_RANGES",
    "SUPPORTED_CLASSES",
    "Shape",
    "SupportSurface",
    "fit_to_box",
    "generate_shape",
    "load_model_folder",
    "shape_from_mesh",
    "typical_size",
]

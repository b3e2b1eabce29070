"""Metrology, placement and model fitting of objects in the room (thesis Section 4.4).

- `room`: the room cuboid of the layout as a frame with floor, ceiling and wall planes.
- `metrology`: object heights from masks, vanishing points and the room height line by cross
  ratio (thesis Eq. 4.3), along the support order, checked against class priors (3-sigma rule).
- `projection`: fast IoU between projected boxes or meshes and masks (reduced resolution).
- `optimise`: DIRECT global search then BOBYQA local refinement (nlopt).
- `solver`: 3D boxes maximising IoU(projection, mask) under the support constraints
  (thesis Eq. 4.4-4.6), from the floor up.
- `shape_choice`: the shape library's variants and user models fitted into boxes, chosen by
  silhouette IoU.
- `support_order`: objects ordered along the support graph, every supporter before what it
  holds up (the order boxes are measured and placed in).
- `oracle`: a scene context filled from a synthetic scene's ground truth, for tests and
  benchmarks of these stages in isolation.
"""

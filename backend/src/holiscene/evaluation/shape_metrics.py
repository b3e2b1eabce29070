"""Shape metrics against a true mesh (thesis Ch. 6): Chamfer distance, an Earth Mover's distance
approximation, and normal consistency.

Protocol: both shapes are compared as point sets of equal size sampled on their surfaces
(for a point set, the points themselves), in the frame the caller chooses (the true box's
normalised frame in `holiscene eval`, so objects of every size weigh the same).

- Chamfer distance: the mean distance from each point to the nearest point of the other set,
  averaged over both directions (L1 Chamfer, as PCN and SK-PCN report it).
- EMD (approximation): the mean distance of a one-to-one matching of 512-point subsamples,
  found by an entropy-regularised optimal transport (Sinkhorn) and rounded greedily to a
  permutation. It is an upper bound of the exact EMD on those subsamples.
- Normal consistency: the mean |cos| between the normal at each point and the normal of the
  nearest point of the other shape, both directions (needs normals on both sides).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

Points = NDArray[np.floating]

EMD_POINTS = 512
_SINKHORN_ROUNDS = 60
_BLOCK = 2048


def _nearest(a: Points, b: Points) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Index and distance of each point of a's nearest point in b (blockwise, bounded memory)."""
    index = np.empty(len(a), dtype=np.int64)
    distance = np.empty(len(a))
    b = np.asarray(b, dtype=np.float64)
    b_norm = (b**2).sum(axis=1)
    for start in range(0, len(a), _BLOCK):
        block = np.asarray(a[start : start + _BLOCK], dtype=np.float64)
        squared = (block**2).sum(axis=1)[:, None] + b_norm[None, :] - 2.0 * block @ b.T
        nearest = squared.argmin(axis=1)
        index[start : start + len(block)] = nearest
        distance[start : start + len(block)] = np.sqrt(
            np.maximum(squared[np.arange(len(block)), nearest], 0.0)
        )
    return index, distance


def chamfer_distance(a: Points, b: Points) -> float:
    """Mean nearest-neighbour distance, averaged over both directions."""
    return 0.5 * float(_nearest(a, b)[1].mean() + _nearest(b, a)[1].mean())


def emd_approximation(a: Points, b: Points, rng: np.random.Generator | None = None) -> float:
    """Sinkhorn-then-greedy one-to-one matching cost on EMD_POINTS-point subsamples of each set."""
    rng = rng or np.random.default_rng(0)
    a = np.asarray(a, dtype=np.float64)[rng.choice(len(a), EMD_POINTS, replace=len(a) < EMD_POINTS)]
    b = np.asarray(b, dtype=np.float64)[rng.choice(len(b), EMD_POINTS, replace=len(b) < EMD_POINTS)]
    cost = np.linalg.norm(a[:, None, :] - b[None, :, :], axis=2)
    epsilon = 0.02 * float(cost.mean()) + 1e-12
    kernel = np.exp(-(cost - cost.min()) / epsilon)
    u = np.ones(EMD_POINTS)
    v = np.ones(EMD_POINTS)
    for _ in range(_SINKHORN_ROUNDS):
        u = 1.0 / np.maximum(kernel @ v, 1e-300)
        v = 1.0 / np.maximum(kernel.T @ u, 1e-300)
    plan = u[:, None] * kernel * v[None, :]
    # Round the transport plan to a permutation: strongest entries first, each row and column once.
    order = np.argsort(-plan, axis=None)
    used_a = np.zeros(EMD_POINTS, dtype=bool)
    used_b = np.zeros(EMD_POINTS, dtype=bool)
    total, matched = 0.0, 0
    for flat in order:
        i, j = divmod(int(flat), EMD_POINTS)
        if used_a[i] or used_b[j]:
            continue
        used_a[i] = used_b[j] = True
        total += cost[i, j]
        matched += 1
        if matched == EMD_POINTS:
            break
    return total / EMD_POINTS


def normal_consistency(a: Points, a_normals: Points, b: Points, b_normals: Points) -> float:
    """Mean |cos| between matched normals (nearest points), both directions."""
    to_b = np.abs((a_normals * b_normals[_nearest(a, b)[0]]).sum(axis=1))
    to_a = np.abs((b_normals * a_normals[_nearest(b, a)[0]]).sum(axis=1))
    return 0.5 * float(to_b.mean() + to_a.mean())

"""Bound-constrained maximisation: DIRECT (global, nlopt's DIRECT-L) then BOBYQA (local).

The thesis searches a grid of discrete choices and refines sizes and positions with BOBYQA
(Powell 2009); DIRECT first finds the right basin within the bounds, so a poor initial guess
(an occluded mask, a wrong contact edge) does not trap the local search.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable
from dataclasses import dataclass

import nlopt
import numpy as np

from ..geometry.camera import FloatArray

Objective = Callable[[FloatArray], float]


@dataclass(frozen=True)
class Optimum:
    x: FloatArray
    value: float
    initial_value: float
    evaluations: int


class _Tracked:
    """The objective with the best point seen so far (nlopt may stop on round-off)."""

    def __init__(self, f: Objective) -> None:
        self.f = f
        self.best_x: FloatArray | None = None
        self.best_value = -np.inf
        self.count = 0

    def __call__(self, x: FloatArray, grad: FloatArray) -> float:
        value = float(self.f(np.asarray(x, dtype=float)))
        if not np.isfinite(value):
            value = -1e6
        self.count += 1
        if value > self.best_value:
            self.best_value, self.best_x = value, np.array(x, dtype=float)
        return value


def _run(algorithm: int, tracked: _Tracked, x0: FloatArray, lo: FloatArray, hi: FloatArray,
         evals: int, step: FloatArray | None = None) -> None:  # fmt: skip
    opt = nlopt.opt(algorithm, len(x0))
    opt.set_lower_bounds(lo.tolist())
    opt.set_upper_bounds(hi.tolist())
    opt.set_max_objective(tracked)
    opt.set_maxeval(int(evals))
    if step is not None:
        opt.set_initial_step(step.tolist())
        opt.set_xtol_rel(1e-4)
    with contextlib.suppress(nlopt.RoundoffLimited, ValueError, RuntimeError):
        opt.optimize(np.clip(x0, lo, hi).tolist())  # on failure, the best point seen stays


def maximise(
    f: Objective,
    x0: FloatArray,
    lo: FloatArray,
    hi: FloatArray,
    global_evals: int = 150,
    local_evals: int = 80,
) -> Optimum:
    """Maximise f over the box [lo, hi], starting from x0 (always evaluated)."""
    lo = np.asarray(lo, dtype=float)
    hi = np.maximum(np.asarray(hi, dtype=float), lo + 1e-6)
    x0 = np.clip(np.asarray(x0, dtype=float), lo, hi)
    tracked = _Tracked(f)
    initial = tracked(x0, np.zeros(0))
    if global_evals > 0:
        _run(nlopt.GN_DIRECT_L, tracked, x0, lo, hi, global_evals)
    if local_evals > 0:
        start = tracked.best_x if tracked.best_x is not None else x0
        _run(nlopt.LN_BOBYQA, tracked, start, lo, hi, local_evals, step=0.1 * (hi - lo))
    assert tracked.best_x is not None
    return Optimum(tracked.best_x, tracked.best_value, initial, tracked.count)

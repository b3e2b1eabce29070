"""What the networks trained for a wall-clock budget share (shape completion, the mesh network):
collecting random samples until there are enough, the training loop with its learning rate
annealed over the budget and a validation check at regular intervals, the curve's picture, and
a one-thread onnxruntime session for run time.

PyTorch and matplotlib are imported inside the functions that need them, so the run-time
helpers stay importable without the training extra.
"""

from __future__ import annotations

import json
import math
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

if TYPE_CHECKING:
    import onnxruntime as ort
    import torch

Sample = TypeVar("Sample")


def collect_samples(
    count: int,
    make: Callable[[np.random.Generator], Sample | None],
    seed: int,
    unit: str,
    progress: bool = True,
) -> list[Sample]:
    """`count` samples from `make` (which returns None for a draw it cannot use), with a
    progress bar."""
    from tqdm import tqdm

    rng = np.random.default_rng(seed)
    rows: list[Sample] = []
    with tqdm(total=count, desc=f"{unit}s", unit=unit, disable=not progress) as bar:
        while len(rows) < count:
            sample = make(rng)
            if sample is not None:
                rows.append(sample)
                bar.update(1)
    return rows


def stack_fields(rows: list[Any], names: Any) -> dict[str, np.ndarray]:
    """Dataclass rows stacked into one array per field name."""
    return {name: np.stack([np.asarray(getattr(r, name)) for r in rows]) for name in names}


def train_for_budget(
    optimiser: torch.optim.Optimizer,
    step_loss: Callable[[], torch.Tensor],
    validate: Callable[[], dict[str, float]],
    budget_s: float,
    curve: list[dict[str, float]],
    base_rate: float = 1e-3,
    floor: float = 0.05,
    checks: int = 12,
) -> None:
    """Steps until `budget_s` seconds have passed, the learning rate annealed from `base_rate`
    down to `floor` times it (cosine over the budget); about `checks` times the validation
    scores join `curve` with the mean training loss since the last check (and go to stderr)."""
    start = time.monotonic()
    step, last_check, losses = 0, start, []
    while (elapsed := time.monotonic() - start) < budget_s:
        for group in optimiser.param_groups:
            cosine = 0.5 * (1 + math.cos(math.pi * elapsed / budget_s))
            group["lr"] = base_rate * (floor + (1 - floor) * cosine)
        loss = step_loss()
        optimiser.zero_grad()
        loss.backward()  # type: ignore[no-untyped-call]
        optimiser.step()
        losses.append(loss.item())
        step += 1
        if time.monotonic() - last_check > budget_s / checks:
            last_check = time.monotonic()
            point = {
                "seconds": round(elapsed, 1),
                "step": step,
                "train_loss": float(np.mean(losses)),
            }
            curve.append({**point, **validate()})
            losses = []
            print(json.dumps(curve[-1]), file=sys.stderr, flush=True)


def plot_curve(
    curve: list[dict[str, float]], path: Path, lines: dict[str, str], ylabel: str
) -> None:
    """The validation curve as a PNG: one line per curve key (label by key); the first solid,
    the others dashed."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axis = plt.subplots(figsize=(6, 3.5))
    steps = [c["step"] for c in curve]
    for i, (key, label) in enumerate(lines.items()):
        axis.plot(steps, [c[key] for c in curve], label=label, linestyle="-" if i == 0 else "--")
    axis.set_xlabel("step")
    axis.set_ylabel(ylabel)
    axis.legend()
    figure.tight_layout()
    figure.savefig(path, dpi=90)
    plt.close(figure)


def single_thread_session(model_file: Path) -> ort.InferenceSession:
    """An onnxruntime session on one thread: pipeline stages run one at a time, and the other
    core stays with the web server."""
    import onnxruntime as ort

    options = ort.SessionOptions()
    options.intra_op_num_threads = 1
    return ort.InferenceSession(str(model_file), options, providers=["CPUExecutionProvider"])

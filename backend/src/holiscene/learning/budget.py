"""What the networks trained for a wall-clock budget share (shape completion, the mesh network):
collecting random samples until there are enough, random batches of them, the training loop
with its learning rate annealed over the budget and a validation check at regular intervals,
the ONNX export checked against PyTorch, the run's files (metrics, metadata, the curve's
picture), and a one-thread onnxruntime session for run time.

PyTorch and matplotlib are imported inside the functions that need them, so the run-time
helpers stay importable without the training extra.
"""

from __future__ import annotations

import json
import math
import sys
import time
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol, TypeVar

import numpy as np

if TYPE_CHECKING:
    import onnxruntime as ort
    import torch

Sample = TypeVar("Sample")

ONNX_TOLERANCE = 1e-3  # largest difference from PyTorch an exported model may show


class BudgetRun(Protocol):
    """The settings every network trained for a budget has, and its validation curve."""

    out: Path
    seed: int
    time_budget: float
    batch: int
    curve: list[dict[str, float]]


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


def as_tensors(arrays: Mapping[str, np.ndarray]) -> dict[str, torch.Tensor]:
    """The arrays as tensors sharing their memory."""
    import torch

    return {name: torch.from_numpy(value) for name, value in arrays.items()}


def random_batch(data: dict[str, torch.Tensor], size: int) -> dict[str, torch.Tensor]:
    """`size` samples drawn with replacement: the same rows of every tensor in `data`."""
    import torch

    count = next(iter(data.values())).shape[0]
    index = torch.randint(count, (size,))
    return {name: value[index] for name, value in data.items()}


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


def export_checked_onnx(
    net: torch.nn.Module,
    example: tuple[torch.Tensor, ...],
    path: Path,
    input_names: list[str],
    output_names: list[str],
    dynamic_axes: dict[str, dict[int, str]],
    checked: list[str] | None = None,
) -> float:
    """Writes `net` to `path` as ONNX and runs it in onnxruntime on `example`; returns the
    largest difference from PyTorch over the `checked` outputs (all when None), and raises
    when it is above ONNX_TOLERANCE."""
    import onnxruntime as ort
    import torch

    net.eval()
    torch.onnx.export(
        net,
        example,
        str(path),
        input_names=input_names,
        output_names=output_names,
        dynamic_axes=dynamic_axes,
        opset_version=17,
        dynamo=False,
    )
    with torch.no_grad():
        outputs = net(*example)
    if isinstance(outputs, torch.Tensor):
        outputs = (outputs,)
    expected = dict(zip(output_names, outputs, strict=True))
    checked = output_names if checked is None else checked
    session = ort.InferenceSession(str(path), providers=["CPUExecutionProvider"])
    feeds = {name: value.numpy() for name, value in zip(input_names, example, strict=True)}
    got = session.run(checked, feeds)
    difference = max(
        float(np.abs(value - expected[name].numpy()).max())
        for name, value in zip(checked, got, strict=True)
    )
    if difference > ONNX_TOLERANCE:
        raise RuntimeError(f"the ONNX model differs from PyTorch by {difference}")
    return difference


def write_run_files(
    run: BudgetRun,
    metrics: dict[str, Any],
    metadata: dict[str, Any],
    lines: dict[str, str],
    ylabel: str,
) -> None:
    """metrics.json, metadata.json (`metadata` followed by the run's seed, budget, batch and
    curve) and curve.png (see plot_curve for `lines` and `ylabel`) in `run.out`."""
    settings = {
        "seed": run.seed,
        "time_budget_s": run.time_budget,
        "batch": run.batch,
        "curve": run.curve,
    }
    (run.out / "metrics.json").write_text(json.dumps(metrics, indent=1) + "\n")
    (run.out / "metadata.json").write_text(json.dumps({**metadata, **settings}, indent=1) + "\n")
    plot_curve(run.curve, run.out / "curve.png", lines, ylabel)


def single_thread_session(model_file: Path) -> ort.InferenceSession:
    """An onnxruntime session on one thread: pipeline stages run one at a time, and the other
    core stays with the web server."""
    import onnxruntime as ort

    options = ort.SessionOptions()
    options.intra_op_num_threads = 1
    return ort.InferenceSession(str(model_file), options, providers=["CPUExecutionProvider"])

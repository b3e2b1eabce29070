"""The thesis's Relation Network for support inference (Sec. 4.3, Appendix B.1.3), as specified:
the reference row next to the default SupportNet.

Network (`ThesisRelationNet`):
- Vision: input 300x300x4 (RGB in [0, 1] + the mask channel), five 3x3x64 convolutions with
  stride 2 and padding 1, each followed by ReLU then BatchNorm (the thesis's order):
  300 -> 150 -> 75 -> 38 -> 19 -> 10, so 10x10 cells of 64-d features.
- Each cell's feature gets its 2-d cell-centre coordinates in [-1, 1] (66-d). All 100x100
  ordered pairs (a, b), a == b included, are concatenated with the 106-d question vector:
  66 + 66 + 106 = 238-d.
- g-MLP: four fully connected layers of 512, each with ReLU, on every pair; the 10,000 outputs
  are summed element-wise.
- f-MLP: 512 -> 512 (ReLU) -> 512 (ReLU) -> 104, the answer logits.
The first g layer is one Linear(238, 512) whose weight is applied to the three parts of the
input separately and summed (W [a; b; q] = W_a a + W_b b + W_q q); same function and same
parameters, without materialising 10,000 x 238 inputs per question.

The question vector, the 104-way answer table, the mask channel (the instance-label map) and
Eq. 4.1 decoding are documented in `thesis_rn_data`. In short, per object: four non-relational
questions (category, instance number, left half?, upper half?) and four relational ones
(supporting instance, supporter category, support type, is the supporter structural?); answers
0-59 instance number, 60-99 NYU-40 category, 100/101 below/behind, 102/103 yes/no.

ONNX contract of the exported model (the project's OPSET, batch axis dynamic):
  inputs  `image` float32 [B, 4, 300, 300], `question` float32 [B, 106]
  output  `answer_logits` float32 [B, 104]

Training (`train_thesis_rn`): Adam, lr 1e-3, batches of 8 questions drawn from all training
questions in a shuffled order, cross-entropy over the 104 answers. The thesis's "weight decay
rate at 0.5 in every 10 steps ... 60 epochs" is read as a learning-rate schedule by epochs:
lr x 0.5 after every 10 epochs (an epoch = one pass over every training question), at most 60
epochs. A literal 10 optimiser steps would halve the rate ~1,600 times per NYU epoch, and a
weight decay (L2) of 0.5 would pin every weight to zero, so neither can be what was meant.
Training stops before the first batch that would end past the time budget; under the budgets
used here (minutes) the network sees a small part of one epoch, so the rate stays 1e-3.
"""

from __future__ import annotations

import json
import time
import warnings
from collections import defaultdict
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import torch
from holiscene_schema.relation_model import OPSET, SUPPORT_TYPE_ORDER
from torch import nn

from ..learning.priors import SupportPriors, count_priors
from ..learning.training_api import (
    METRICS_FILE,
    MODEL_FILE,
    PRIORS_FILE,
    TrainProgress,
    TrainResult,
)
from .thesis_rn_data import (
    ANSWER_CATEGORY,
    ANSWER_TYPE,
    INPUT_SIZE,
    N_ANSWERS,
    N_CATEGORIES,
    NON_RELATIONAL,
    Q_STRUCTURAL,
    Q_SUPPORTER,
    Q_SUPPORTER_CATEGORY,
    Q_TYPE,
    QUESTION_DIM,
    RELATIONAL,
    Candidate,
    MaskMode,
    RNScene,
    Supporter,
    category_answer,
    eq41_decode,
    prior_only_decode,
    seeds_digest,
    synthetic_rn_scenes,
    yes_no,
)

FEATURES = 64
GRID = 10  # 300 -> 150 -> 75 -> 38 -> 19 -> 10
HIDDEN = 512
CELL_DIM = FEATURES + 2
INPUT_NAMES = ("image", "question")
OUTPUT_NAME = "answer_logits"
BATCH_QUESTIONS = 8
LEARNING_RATE = 1e-3
LR_STEP_EPOCHS = 10
LR_GAMMA = 0.5
MAX_EPOCHS = 60
ONNX_TOLERANCE = 1e-5

# answer(images (B, 4, 300, 300), questions (B, 106)) -> logits (B, 104), all float32
AnswerFn = Callable[[np.ndarray, np.ndarray], np.ndarray]


class ThesisRelationNet(nn.Module):
    def __init__(self) -> None:
        super().__init__()
        layers: list[nn.Module] = []
        channels = 4
        for _ in range(5):
            layers += [
                nn.Conv2d(channels, FEATURES, 3, stride=2, padding=1),
                nn.ReLU(),
                nn.BatchNorm2d(FEATURES),
            ]
            channels = FEATURES
        self.vision = nn.Sequential(*layers)
        self.g_in = nn.Linear(2 * CELL_DIM + QUESTION_DIM, HIDDEN)
        self.g_rest = nn.Sequential(
            nn.ReLU(),
            nn.Linear(HIDDEN, HIDDEN),
            nn.ReLU(),
            nn.Linear(HIDDEN, HIDDEN),
            nn.ReLU(),
            nn.Linear(HIDDEN, HIDDEN),
            nn.ReLU(),
        )
        self.f = nn.Sequential(
            nn.Linear(HIDDEN, HIDDEN),
            nn.ReLU(),
            nn.Linear(HIDDEN, HIDDEN),
            nn.ReLU(),
            nn.Linear(HIDDEN, N_ANSWERS),
        )
        centre = (torch.arange(GRID, dtype=torch.float32) + 0.5) / GRID * 2.0 - 1.0
        rows, cols = torch.meshgrid(centre, centre, indexing="ij")
        self.register_buffer("coords", torch.stack([cols, rows], dim=-1).reshape(GRID * GRID, 2))

    def cells(self, image: torch.Tensor) -> torch.Tensor:
        """(B, 100, 66): each cell's 64-d feature and its (x, y) coordinates."""
        features = self.vision(image)  # (B, 64, 10, 10)
        flat = features.flatten(2).transpose(1, 2)  # (B, 100, 64), row-major cells
        coords = self.coords.expand(flat.shape[0], -1, -1)  # type: ignore[operator]
        return torch.cat([flat, coords], dim=2)

    def answer(self, cells: torch.Tensor, question: torch.Tensor) -> torch.Tensor:
        w, b = self.g_in.weight, self.g_in.bias
        first = cells @ w[:, :CELL_DIM].T  # (B, 100, 512): the pair's first cell
        second = cells @ w[:, CELL_DIM : 2 * CELL_DIM].T  # the pair's second cell
        q = question @ w[:, 2 * CELL_DIM :].T + b  # (B, 512)
        pairs = first[:, :, None, :] + second[:, None, :, :] + q[:, None, None, :]
        summed = self.g_rest(pairs).sum(dim=(1, 2))  # (B, 512)
        out: torch.Tensor = self.f(summed)
        return out

    def forward(self, image: torch.Tensor, question: torch.Tensor) -> torch.Tensor:
        return self.answer(self.cells(image), question)


def reference_forward(
    model: ThesisRelationNet, image: torch.Tensor, q: torch.Tensor
) -> torch.Tensor:
    """The same network with the 100x100 x 238 pair inputs built literally (tests only)."""
    cells = model.cells(image)
    n = cells.shape[1]
    a = cells[:, :, None, :].expand(-1, -1, n, -1)
    b = cells[:, None, :, :].expand(-1, n, -1, -1)
    qq = q[:, None, None, :].expand(-1, n, n, -1)
    g = model.g_rest(model.g_in(torch.cat([a, b, qq], dim=3)))
    out: torch.Tensor = model.f(g.sum(dim=(1, 2)))
    return out


# ---- questions as training items -----------------------------------------------------------


@dataclass(frozen=True)
class Item:
    scene: int
    obj: int
    group: int
    index: int
    answer: int


def scene_items(scenes: Sequence[RNScene], groups: Sequence[int] = (0, 1)) -> list[Item]:
    items = []
    for s, scene in enumerate(scenes):
        for i in range(len(scene.classes)):
            for (group, index), answer in scene.answers(i).items():
                if group in groups:
                    items.append(Item(s, i, group, index, answer))
    return items


def batch_arrays(
    scenes: Sequence[RNScene], items: Sequence[Item], mode: MaskMode
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    images = np.stack([scenes[it.scene].network_input(it.obj, mode) for it in items])
    questions = np.stack([scenes[it.scene].question(it.obj, it.group, it.index) for it in items])
    answers = np.array([it.answer for it in items], dtype=np.int64)
    return images, questions, answers


def train_step(
    model: ThesisRelationNet,
    optimizer: torch.optim.Optimizer,
    images: np.ndarray,
    questions: np.ndarray,
    answers: np.ndarray,
) -> float:
    """One Adam step on a batch; returns the batch's loss before the step."""
    model.train()
    logits = model(torch.from_numpy(images), torch.from_numpy(questions))
    loss = nn.functional.cross_entropy(logits, torch.from_numpy(answers))
    optimizer.zero_grad()
    loss.backward()  # type: ignore[no-untyped-call]
    optimizer.step()
    return float(loss.item())


def torch_answer_fn(model: ThesisRelationNet) -> AnswerFn:
    def answer(images: np.ndarray, questions: np.ndarray) -> np.ndarray:
        model.eval()
        with torch.no_grad():
            out = model(torch.from_numpy(images), torch.from_numpy(questions))
        result: np.ndarray = out.numpy()
        return result

    return answer


def onnx_answer_fn(path: Path, threads: int = 1) -> AnswerFn:
    import onnxruntime as ort

    options = ort.SessionOptions()
    options.intra_op_num_threads = threads
    options.inter_op_num_threads = 1
    session = ort.InferenceSession(str(path), options, providers=["CPUExecutionProvider"])

    def answer(images: np.ndarray, questions: np.ndarray) -> np.ndarray:
        out = session.run([OUTPUT_NAME], {"image": images, "question": questions})[0]
        return np.asarray(out, dtype=np.float32)

    return answer


def export_onnx(model: ThesisRelationNet, path: Path) -> None:
    model.eval()
    example = (
        torch.zeros(1, 4, INPUT_SIZE, INPUT_SIZE),
        torch.zeros(1, QUESTION_DIM),
    )
    # The TorchScript exporter: exports this static graph in well under a second (the
    # torch.export-based one takes seconds) and writes the contract's opset directly. It warns
    # that it is deprecated; the warning says nothing about this model.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        torch.onnx.export(
            model,
            example,
            str(path),
            input_names=list(INPUT_NAMES),
            output_names=[OUTPUT_NAME],
            dynamic_axes={
                "image": {0: "batch"},
                "question": {0: "batch"},
                OUTPUT_NAME: {0: "batch"},
            },
            opset_version=OPSET,
            dynamo=False,
        )


def onnx_difference(
    model: ThesisRelationNet, path: Path, images: np.ndarray, questions: np.ndarray
) -> tuple[float, float]:
    """(largest absolute difference of onnxruntime's logits from PyTorch's, the same relative
    to the logits' scale max(1, max |logit|)).

    The relative figure is the one checked against ONNX_TOLERANCE. The logits come from a sum
    over 10,000 pairs (g outputs summing to several hundred) and reach tens; at that size
    PyTorch's own float32 result is about 1e-5 away from a float64 evaluation of the same
    weights, and onnxruntime's (another summation order) a few 1e-5, so an absolute 1e-5
    cannot be met by any float32 runtime, while the relative difference stays near 1e-6."""
    expected = torch_answer_fn(model)(images, questions).astype(np.float64)
    got = onnx_answer_fn(path)(images, questions).astype(np.float64)
    largest = float(np.abs(expected - got).max())
    return largest, largest / max(1.0, float(np.abs(expected).max()))


# ---- evaluation ----------------------------------------------------------------------------


@dataclass
class ThesisEvaluation:
    objects: int = 0  # objects with a labelled supporter
    eq41_correct: int = 0  # supporter instance and type both right after Eq. 4.1
    prior_only_correct: int = 0  # the same neighbours, network unused
    relational: int = 0  # relational questions asked
    relational_correct: int = 0  # argmax answer right, before Eq. 4.1
    relational_eq41_correct: int = 0  # answers implied by the Eq. 4.1 supporter and type
    non_relational: int = 0
    non_relational_correct: int = 0
    per_question: dict[str, list[int]] = field(default_factory=dict)  # "g,k" -> [right, asked]

    def summary(self) -> dict[str, Any]:
        def rate(a: int, b: int) -> float | None:
            return round(a / b, 4) if b else None

        return {
            "objects": self.objects,
            "support_accuracy_eq41": rate(self.eq41_correct, self.objects),
            "support_accuracy_prior_only": rate(self.prior_only_correct, self.objects),
            "relational_accuracy": rate(self.relational_correct, self.relational),
            "relational_accuracy_eq41": rate(self.relational_eq41_correct, self.relational),
            "non_relational_accuracy": rate(self.non_relational_correct, self.non_relational),
            "per_question_accuracy": {k: rate(*v) for k, v in sorted(self.per_question.items())},
        }


def _eq41_answers(scene: RNScene, supporter: Supporter, kind: str) -> dict[int, int]:
    return {
        Q_SUPPORTER: scene.supporter_answer(supporter),
        Q_SUPPORTER_CATEGORY: category_answer(scene.class_of(supporter)),
        Q_TYPE: ANSWER_TYPE + SUPPORT_TYPE_ORDER.index(kind),
        Q_STRUCTURAL: yes_no(isinstance(supporter, str)),
    }


def evaluate_thesis_rn(
    answer: AnswerFn,
    scenes: Sequence[RNScene],
    priors: SupportPriors,
    mode: MaskMode = "labels",
    non_relational: bool = True,
    batch_size: int = BATCH_QUESTIONS,
    progress: Callable[[int, int], None] | None = None,
) -> ThesisEvaluation:
    """Ask every question of every object, decode supports by Eq. 4.1 and count."""
    result = ThesisEvaluation()
    groups = (NON_RELATIONAL, RELATIONAL) if non_relational else (RELATIONAL,)
    items = scene_items(scenes, groups)
    logits: dict[tuple[int, int, int, int], np.ndarray] = {}
    for start in range(0, len(items), batch_size):
        chunk = items[start : start + batch_size]
        images, questions, _ = batch_arrays(scenes, chunk, mode)
        for it, row in zip(chunk, answer(images, questions), strict=True):
            logits[(it.scene, it.obj, it.group, it.index)] = row
        if progress:
            progress(min(start + batch_size, len(items)), len(items))
    per_question: dict[str, list[int]] = defaultdict(lambda: [0, 0])
    for it in items:
        right = int(np.argmax(logits[(it.scene, it.obj, it.group, it.index)]) == it.answer)
        per_question[f"{it.group},{it.index}"][0] += right
        per_question[f"{it.group},{it.index}"][1] += 1
        if it.group == RELATIONAL:
            result.relational += 1
            result.relational_correct += right
        else:
            result.non_relational += 1
            result.non_relational_correct += right
    result.per_question = dict(per_question)
    for s, scene in enumerate(scenes):
        for i, (parent, kind) in enumerate(zip(scene.parents, scene.types, strict=True)):
            if parent is None or kind is None:
                continue
            instance_row = logits[(s, i, RELATIONAL, Q_SUPPORTER)]
            neighbours = [
                Candidate(n, scene.class_of(n), float(instance_row[scene.supporter_answer(n)]))
                for n in scene.neighbours(i)
            ]
            category_row = logits[(s, i, RELATIONAL, Q_SUPPORTER_CATEGORY)]
            type_row = logits[(s, i, RELATIONAL, Q_TYPE)]
            chosen, chosen_kind = eq41_decode(
                scene.classes[i],
                category_row[ANSWER_CATEGORY : ANSWER_CATEGORY + N_CATEGORIES],
                type_row[ANSWER_TYPE : ANSWER_TYPE + 2],
                neighbours,
                priors.conditional,
            )
            result.objects += 1
            result.eq41_correct += int(chosen == parent and chosen_kind == kind)
            truth = scene.answers(i)
            for k, a in _eq41_answers(scene, chosen, chosen_kind).items():
                result.relational_eq41_correct += int(truth[(RELATIONAL, k)] == a)
            base, base_kind = prior_only_decode(scene.classes[i], neighbours, priors.joint)
            result.prior_only_correct += int(base == parent and base_kind == kind)
    return result


# ---- training ------------------------------------------------------------------------------


@dataclass
class _BudgetRun:
    """What the optimiser steps left: losses and times per batch, and where they stopped."""

    losses: list[float] = field(default_factory=list)
    batch_seconds: list[float] = field(default_factory=list)
    epoch: int = 0  # epochs completed
    position: int = 0  # questions into the epoch that was under way
    seconds: float = 0.0
    final_learning_rate: float = LEARNING_RATE


def _train_within_budget(
    model: ThesisRelationNet,
    train: Sequence[RNScene],
    items: Sequence[Item],
    mode: MaskMode,
    batch_size: int,
    budget_s: float,
    rng: np.random.Generator,
    report: TrainProgress,
) -> _BudgetRun:
    """Optimise until the next batch would end past `budget_s` or MAX_EPOCHS are done."""
    optimizer = torch.optim.Adam(model.parameters(), lr=LEARNING_RATE)
    schedule = torch.optim.lr_scheduler.StepLR(optimizer, LR_STEP_EPOCHS, gamma=LR_GAMMA)
    run = _BudgetRun()
    order = rng.permutation(len(items))
    start = time.perf_counter()
    while run.epoch < MAX_EPOCHS:
        elapsed = time.perf_counter() - start
        expected = float(np.mean(run.batch_seconds)) if run.batch_seconds else 0.0
        if elapsed + expected > budget_s:
            break
        t0 = time.perf_counter()
        chosen = [items[k] for k in order[run.position : run.position + batch_size]]
        run.losses.append(train_step(model, optimizer, *batch_arrays(train, chosen, mode)))
        run.batch_seconds.append(time.perf_counter() - t0)
        run.position += batch_size
        if run.position >= len(items):  # an epoch ends: reshuffle, and the schedule steps
            run.epoch, run.position = run.epoch + 1, 0
            order = rng.permutation(len(items))
            schedule.step()
        report(
            (time.perf_counter() - start) / budget_s,
            f"batch {len(run.losses)} loss {run.losses[-1]:.3f} ({run.batch_seconds[-1]:.1f} s)",
        )
    run.seconds = time.perf_counter() - start
    run.final_learning_rate = optimizer.param_groups[0]["lr"]
    return run


def train_thesis_rn(
    budget_s: float,
    train_seeds: Sequence[int],
    val_seeds: Sequence[int],
    out_dir: Path,
    progress: TrainProgress | None = None,
    *,
    mode: MaskMode = "labels",
    batch_size: int = BATCH_QUESTIONS,
    seed: int = 0,
    priors: SupportPriors | None = None,
    cache_dir: Path | None = None,
    workers: int = 2,
) -> TrainResult:
    """Train within `budget_s` seconds (data preparation and validation not counted), export
    ONNX, check it against PyTorch, validate with Eq. 4.1 and write metrics.json.

    `priors` defaults to the counts of the training scenes' labels."""

    def report(fraction: float, line: str) -> None:
        if progress:
            progress(min(1.0, max(0.0, fraction)), line)

    out_dir.mkdir(parents=True, exist_ok=True)
    torch.manual_seed(seed)
    rng = np.random.default_rng(seed)
    train = synthetic_rn_scenes(
        train_seeds, cache_dir, lambda d, n: report(0.0, f"train scenes {d}/{n}"), workers
    )
    val = synthetic_rn_scenes(
        val_seeds, cache_dir, lambda d, n: report(0.0, f"validation scenes {d}/{n}"), workers
    )
    if not train:
        raise ValueError("no training scene has a labelled object")
    if priors is None:
        priors = count_priors(s.support_sample() for s in train)
    items = scene_items(train)

    model = ThesisRelationNet()
    run = _train_within_budget(model, train, items, mode, batch_size, budget_s, rng, report)

    model_path = out_dir / MODEL_FILE
    export_onnx(model, model_path)
    probe = items[: min(4, len(items))]
    images, questions, _ = batch_arrays(train, probe, mode)
    onnx_abs, onnx_rel = onnx_difference(model, model_path, images, questions)

    report(1.0, f"validating on {len(val)} scenes")
    evaluation = evaluate_thesis_rn(torch_answer_fn(model), val, priors, mode)
    summary = evaluation.summary()
    metrics: dict[str, Any] = {
        "architecture": "thesis_rn",
        "mask_mode": mode,
        "budget_s": budget_s,
        "train_seconds": round(run.seconds, 2),
        "batches": len(run.losses),
        "batch_questions": batch_size,
        "seconds_per_batch": (
            round(float(np.mean(run.batch_seconds)), 3) if run.batch_seconds else None
        ),
        "epochs_completed": run.epoch,
        "epoch_fraction": round((run.epoch * len(items) + run.position) / len(items), 4),
        "final_learning_rate": run.final_learning_rate,
        "train_questions": len(items),
        "train_scenes": len(train),
        "train_seeds_digest": seeds_digest(train_seeds),
        "validation_scenes": len(val),
        "validation_seeds_digest": seeds_digest(val_seeds),
        "losses": [round(x, 4) for x in run.losses],
        "onnx_max_abs_diff": onnx_abs,
        "onnx_max_rel_diff": onnx_rel,
        "onnx_matches": onnx_rel <= ONNX_TOLERANCE,
        "torch_threads": torch.get_num_threads(),
        "validation": summary,
    }
    (out_dir / PRIORS_FILE).write_text(priors.to_json())
    (out_dir / METRICS_FILE).write_text(json.dumps(metrics, indent=1) + "\n")
    if onnx_rel > ONNX_TOLERANCE:
        raise RuntimeError(f"ONNX export differs from PyTorch by {onnx_rel:.2e} (relative)")
    accuracy = summary["support_accuracy_eq41"]
    return TrainResult(out_dir, float(accuracy or 0.0), metrics)

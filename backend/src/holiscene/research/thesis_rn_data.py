"""Questions, answers, inputs and Eq. 4.1 decoding for the thesis's Relation Network.

Numpy only (no PyTorch), so the question table and the decoding can run beside onnxruntime;
the network, its training and evaluation are in `thesis_rn`.

Question vector, 106-d, four one-hot groups (thesis Sec. 4.3.2, "for the i-th object which
belongs to the j-th category, we encode the k-th question from the m-th group"):
  [0, 60)    i: the object's instance number = its index in the sample order (the scene's
             objects without floor/wall/ceiling, at most 60; the synthetic generator shuffles
             them, like the random numbering of a segmentation the thesis mentions)
  [60, 100)  j: the object's NYU-40 category (NYU40_CLASSES order)
  [100, 104) k: the question's index in its group
  [104, 106) m: the group, 0 = non-relational, 1 = relational

Answer table, 104-way:
  [0, 60)    instance number 0..59
  [60, 100)  NYU-40 category (floor, wall and ceiling are categories 1, 0 and 21)
  100, 101   support type: below, behind
  102, 103   yes, no

Questions of object i (group, index: question -> answer):
  0,0 What is the category of object i?                        -> its category
  0,1 What is the instance number of object i?                 -> i
  0,2 Is object i's mask centre in the left half of the image? -> yes / no
  0,3 Is object i's mask centre in the upper half of the image?-> yes / no
  1,0 Which instance supports object i?   -> the supporter's instance number; a structural
                                             supporter (no instance) -> its category
  1,1 What is the category of object i's supporter?            -> category (incl. structural)
  1,2 How is object i supported?                               -> below / behind
  1,3 Is object i's supporter floor, wall or ceiling?          -> yes / no
The non-relational questions are the thesis's regularisers that make the network find the
queried object; the rough image position is asked as two yes/no questions (left/upper half)
rather than as "is it layout-supported", which would repeat relational question 1,3.
Objects without a labelled supporter get only the non-relational questions.

Mask channel (the 4th input channel): the instance-label map, (i + 1) / 60 on object i's
pixels and 0 elsewhere (the thesis: "appended with its mask (instance labels, 1-channel)").
One map per image is what makes the question's 60 instance slots meaningful: the network has
to match the queried number to a label in the map. (`MaskMode` "object", the queried object's
own mask, is kept as an option for comparison; it makes those slots redundant.) Each 300x300
cell takes the label covering most of it (background included), not an area average, so a
boundary never gets the label of a third object.

Eq. 4.1: the supporter of O_i is the neighbour O_j (objects whose mask, dilated by
NEIGHBOUR_RADIUS_FRACTION of the image diagonal, touches O_i's; floor, wall and ceiling
neighbour every object) whose category is among the top-5 answers to question 1,1 and that
maximises the counted prior P(C(O_j) | C(O_i), T_k), T_k being the answer to question 1,2.
"""

from __future__ import annotations

import hashlib
import itertools
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from multiprocessing import get_context
from pathlib import Path
from typing import Literal

import cv2
import numpy as np
from holiscene_schema import NYU40_CLASSES, STRUCTURAL_CLASSES, Scene
from holiscene_schema.relation_model import STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER

from ..learning.preprocess import area_resize, class_index
from ..learning.samples import NO_LABEL, SupportSample, answer_index, object_masks

INPUT_SIZE = 300
MAX_INSTANCES = 60
N_CATEGORIES = len(NYU40_CLASSES)  # 40
N_QUESTIONS = 4
N_GROUPS = 2
QUESTION_DIM = MAX_INSTANCES + N_CATEGORIES + N_QUESTIONS + N_GROUPS  # 106
CATEGORY_OFFSET = MAX_INSTANCES
QUESTION_OFFSET = CATEGORY_OFFSET + N_CATEGORIES
GROUP_OFFSET = QUESTION_OFFSET + N_QUESTIONS

# Answer table offsets.
ANSWER_CATEGORY = MAX_INSTANCES  # 60..99
ANSWER_TYPE = ANSWER_CATEGORY + N_CATEGORIES  # 100 below, 101 behind
ANSWER_YES = ANSWER_TYPE + len(SUPPORT_TYPE_ORDER)  # 102
ANSWER_NO = ANSWER_YES + 1  # 103
N_ANSWERS = ANSWER_NO + 1  # 104

NON_RELATIONAL, RELATIONAL = 0, 1
Q_CATEGORY, Q_INSTANCE, Q_LEFT, Q_UPPER = 0, 1, 2, 3
Q_SUPPORTER, Q_SUPPORTER_CATEGORY, Q_TYPE, Q_STRUCTURAL = 0, 1, 2, 3
QUESTION_TEXT: dict[tuple[int, int], str] = {
    (NON_RELATIONAL, Q_CATEGORY): "What is the category of object {i}?",
    (NON_RELATIONAL, Q_INSTANCE): "What is the instance number of object {i}?",
    (NON_RELATIONAL, Q_LEFT): "Is object {i} in the left half of the image?",
    (NON_RELATIONAL, Q_UPPER): "Is object {i} in the upper half of the image?",
    (RELATIONAL, Q_SUPPORTER): "Which instance supports object {i}?",
    (RELATIONAL, Q_SUPPORTER_CATEGORY): "What is the category of object {i}'s supporter?",
    (RELATIONAL, Q_TYPE): "How is object {i} supported?",
    (RELATIONAL, Q_STRUCTURAL): "Is object {i}'s supporter floor, wall or ceiling?",
}

MaskMode = Literal["labels", "object"]
# Dilation radius for "touching" masks, as a share of the image diagonal (8 px at 640x480).
NEIGHBOUR_RADIUS_FRACTION = 0.01
TOP_CATEGORIES = 5  # |SC(O_i)| in Eq. 4.1, as in the thesis
CACHE_VERSION = f"thesis-rn-v1-{INPUT_SIZE}-{NEIGHBOUR_RADIUS_FRACTION}"

# prior(supporter class, child class, support type) -> P(supporter class | child class, type)
Prior = Callable[[str, str, str], float]
# A supporter: an object index, or "floor" / "wall" / "ceiling".
Supporter = int | str


@dataclass(frozen=True)
class Question:
    instance: int
    category: int
    index: int
    group: int


def encode_question(q: Question) -> np.ndarray:
    if not (
        0 <= q.instance < MAX_INSTANCES
        and 0 <= q.category < N_CATEGORIES
        and 0 <= q.index < N_QUESTIONS
        and 0 <= q.group < N_GROUPS
    ):
        raise ValueError(f"question out of range: {q}")
    v = np.zeros(QUESTION_DIM, dtype=np.float32)
    v[q.instance] = 1.0
    v[CATEGORY_OFFSET + q.category] = 1.0
    v[QUESTION_OFFSET + q.index] = 1.0
    v[GROUP_OFFSET + q.group] = 1.0
    return v


def decode_question(v: np.ndarray) -> Question:
    """The question of a 106-d vector; raises unless each group is exactly one-hot."""
    if v.shape != (QUESTION_DIM,) or not np.isin(v, (0.0, 1.0)).all():
        raise ValueError("a question vector is 106 zeros and ones")
    bounds = (0, CATEGORY_OFFSET, QUESTION_OFFSET, GROUP_OFFSET, QUESTION_DIM)
    hot = []
    for start, end in itertools.pairwise(bounds):
        ones = np.flatnonzero(v[start:end])
        if len(ones) != 1:
            raise ValueError(f"slots {start}..{end - 1} must hold exactly one 1")
        hot.append(int(ones[0]))
    return Question(*hot)


def category_answer(cls: str) -> int:
    return ANSWER_CATEGORY + class_index(cls)


def yes_no(flag: bool) -> int:
    return ANSWER_YES if flag else ANSWER_NO


@dataclass(frozen=True)
class RNScene:
    """One labelled image as the thesis network sees it; objects in sample order."""

    name: str
    rgb: np.ndarray  # float32 (300, 300, 3) in [0, 1], area-resized
    labels: np.ndarray  # uint8 (300, 300): 0 background, i + 1 on object i
    classes: tuple[str, ...]
    parents: tuple[Supporter | None, ...]  # None: no labelled supporter
    types: tuple[str | None, ...]
    centres: np.ndarray  # float32 (N, 2): mask centre (x / W, y / H)
    adjacency: np.ndarray  # bool (N, N): dilated masks touch (symmetric, False diagonal)

    def neighbours(self, i: int) -> list[Supporter]:
        """N(O_i): touching objects, then floor, wall and ceiling (neighbours of all)."""
        objects: list[Supporter] = [int(j) for j in np.flatnonzero(self.adjacency[i])]
        return objects + list(STRUCTURAL_COLUMNS)

    def class_of(self, supporter: Supporter) -> str:
        return self.classes[supporter] if isinstance(supporter, int) else supporter

    def supporter_answer(self, supporter: Supporter) -> int:
        """Answer to "which instance supports ...": instance number, or structural category."""
        if isinstance(supporter, int):
            return supporter
        return category_answer(supporter)

    def answers(self, i: int) -> dict[tuple[int, int], int]:
        """(group, question index) -> answer index for object i's questions."""
        out = {
            (NON_RELATIONAL, Q_CATEGORY): category_answer(self.classes[i]),
            (NON_RELATIONAL, Q_INSTANCE): i,
            (NON_RELATIONAL, Q_LEFT): yes_no(bool(self.centres[i, 0] < 0.5)),
            (NON_RELATIONAL, Q_UPPER): yes_no(bool(self.centres[i, 1] < 0.5)),
        }
        parent, kind = self.parents[i], self.types[i]
        if parent is not None and kind is not None:
            out[(RELATIONAL, Q_SUPPORTER)] = self.supporter_answer(parent)
            out[(RELATIONAL, Q_SUPPORTER_CATEGORY)] = category_answer(self.class_of(parent))
            out[(RELATIONAL, Q_TYPE)] = ANSWER_TYPE + SUPPORT_TYPE_ORDER.index(kind)
            out[(RELATIONAL, Q_STRUCTURAL)] = yes_no(isinstance(parent, str))
        return out

    def question(self, i: int, group: int, index: int) -> np.ndarray:
        return encode_question(Question(i, class_index(self.classes[i]), index, group))

    def mask_channel(self, i: int, mode: MaskMode) -> np.ndarray:
        channel: np.ndarray
        if mode == "labels":
            channel = self.labels.astype(np.float32) / np.float32(MAX_INSTANCES)
        else:
            channel = (self.labels == i + 1).astype(np.float32)
        return channel

    def network_input(self, i: int, mode: MaskMode) -> np.ndarray:
        """float32 (4, 300, 300): RGB then the mask channel."""
        channels = [self.rgb.transpose(2, 0, 1), self.mask_channel(i, mode)[None]]
        return np.ascontiguousarray(np.concatenate(channels), dtype=np.float32)

    def support_sample(self) -> SupportSample:
        """The labels as a SupportSample without inputs, for `priors.count_priors`."""
        n = len(self.classes)
        targets = np.full(n, NO_LABEL, dtype=np.int64)
        for i, (parent, kind) in enumerate(zip(self.parents, self.types, strict=True)):
            if parent is None or kind is None:
                continue
            column = parent if isinstance(parent, int) else n + STRUCTURAL_COLUMNS.index(parent)
            targets[i] = answer_index(column, kind)
        ids = tuple(f"o{i}" for i in range(n))
        return SupportSample(self.name, {}, ids, self.classes, targets)


def _label_map(masks: Sequence[np.ndarray], size: int) -> np.ndarray:
    """Majority label per cell: 0 where background covers the cell most, else i + 1."""
    coverage = np.stack([area_resize(m, size) for m in masks])
    background = 1.0 - coverage.sum(axis=0)
    best = coverage.argmax(axis=0)
    labels = np.where(coverage.max(axis=0) > background, best + 1, 0)
    return labels.astype(np.uint8)


def _adjacency(masks: Sequence[np.ndarray], radius: int) -> np.ndarray:
    height, width = masks[0].shape
    index = np.zeros((height, width), dtype=np.int16)  # 0 background, i + 1 object i
    for i, m in enumerate(masks):
        index[m] = i + 1
    kernel = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (2 * radius + 1, 2 * radius + 1))
    n = len(masks)
    adjacency = np.zeros((n, n), dtype=bool)
    for i, m in enumerate(masks):
        grown = cv2.dilate(m.astype(np.uint8), kernel).astype(bool)
        touched = np.unique(index[grown])
        adjacency[i, touched[touched > 0] - 1] = True
    adjacency |= adjacency.T  # occlusion can hide one side's contact; touching is mutual
    np.fill_diagonal(adjacency, False)
    return adjacency


def rn_scene(scene: Scene, image: np.ndarray) -> RNScene | None:
    """The network's view of a labelled scene (RGB uint8 photo); None without objects."""
    kept = [o for o in scene.objects if o.cls not in STRUCTURAL_CLASSES][:MAX_INSTANCES]
    if not kept:
        return None
    scene = scene.model_copy(update={"objects": kept})
    ids = [o.id for o in kept]
    masks = object_masks(scene)
    parents: list[Supporter | None] = [None] * len(kept)
    types: list[str | None] = [None] * len(kept)
    for support in scene.supports:
        if support.child not in ids:
            continue
        i = ids.index(support.child)
        if support.parent in STRUCTURAL_COLUMNS:
            parents[i], types[i] = support.parent, support.type
        elif support.parent in ids and support.parent != support.child:
            parents[i], types[i] = ids.index(support.parent), support.type
    height, width = image.shape[:2]
    centres = np.zeros((len(kept), 2), dtype=np.float32)
    for i, m in enumerate(masks):
        rows, cols = np.nonzero(m)
        if len(rows):
            centres[i] = (cols.mean() + 0.5) / width, (rows.mean() + 0.5) / height
    radius = max(1, round(NEIGHBOUR_RADIUS_FRACTION * float(np.hypot(width, height))))
    return RNScene(
        name=scene.name,
        rgb=area_resize(image.astype(np.float64) / 255.0, INPUT_SIZE),
        labels=_label_map(masks, INPUT_SIZE),
        classes=tuple(o.cls for o in kept),
        parents=tuple(parents),
        types=tuple(types),
        centres=centres,
        adjacency=_adjacency(masks, radius),
    )


# ---- cache of synthetic scenes ------------------------------------------------------------


def default_cache_dir() -> Path:
    return Path.home() / ".cache" / "holiscene" / "thesis-rn" / CACHE_VERSION


def _synthesize(seed: int) -> RNScene | None:
    from ..synth.generate import synthesize  # heavy renderer: import in the worker

    scene = synthesize(seed)
    return rn_scene(scene.truth, scene.frame.rgb)


def _parent_code(parent: Supporter | None) -> int:
    # >= 0 object index; -1 - structural index; -100 none
    if parent is None:
        return -100
    return parent if isinstance(parent, int) else -1 - STRUCTURAL_COLUMNS.index(parent)


def _parent_from_code(code: int) -> Supporter | None:
    if code == -100:
        return None
    return code if code >= 0 else STRUCTURAL_COLUMNS[-1 - code]


def save_scene(scene: RNScene, path: Path) -> None:
    tmp = path.with_suffix(".tmp.npz")
    np.savez_compressed(
        tmp,
        name=np.array(scene.name),
        rgb=scene.rgb,
        labels=scene.labels,
        classes=np.array(scene.classes),
        parents=np.array([_parent_code(p) for p in scene.parents], dtype=np.int64),
        types=np.array([t or "" for t in scene.types]),
        centres=scene.centres,
        adjacency=scene.adjacency,
    )
    tmp.replace(path)  # whole files only


def load_scene(path: Path) -> RNScene:
    with np.load(path) as data:
        return RNScene(
            name=str(data["name"]),
            rgb=data["rgb"],
            labels=data["labels"],
            classes=tuple(str(c) for c in data["classes"]),
            parents=tuple(_parent_from_code(int(c)) for c in data["parents"]),
            types=tuple(str(t) or None for t in data["types"]),
            centres=data["centres"],
            adjacency=data["adjacency"],
        )


def synthetic_rn_scenes(
    seeds: Sequence[int],
    cache_dir: Path | None = None,
    progress: Callable[[int, int], None] | None = None,
    workers: int = 2,
) -> list[RNScene]:
    """One scene per seed (seeds without objects skipped), rendering only uncached seeds."""
    cache = cache_dir or default_cache_dir()
    cache.mkdir(parents=True, exist_ok=True)
    missing = [s for s in seeds if not (cache / f"{s}.npz").exists()]
    done = len(seeds) - len(missing)
    if progress:
        progress(done, len(seeds))
    if missing:
        with get_context("spawn").Pool(max(1, workers)) as pool:
            for seed, scene in zip(
                missing, pool.imap(_synthesize, missing, chunksize=2), strict=True
            ):
                if scene is not None:
                    save_scene(scene, cache / f"{seed}.npz")
                done += 1
                if progress:
                    progress(done, len(seeds))
    return [load_scene(cache / f"{s}.npz") for s in seeds if (cache / f"{s}.npz").exists()]


def seeds_digest(seeds: Sequence[int]) -> str:
    return hashlib.sha256(",".join(map(str, seeds)).encode()).hexdigest()[:16]


# ---- Eq. 4.1 --------------------------------------------------------------------------------


@dataclass(frozen=True)
class Candidate:
    supporter: Supporter
    cls: str
    instance_score: float = 0.0  # the network's score for it on "which instance supports ..."


def eq41_decode(
    child_cls: str,
    category_scores: np.ndarray,
    type_scores: np.ndarray,
    neighbours: Sequence[Candidate],
    prior: Prior,
    top_k: int = TOP_CATEGORIES,
) -> tuple[Supporter, str]:
    """(supporter, type) of one object by Eq. 4.1.

    `category_scores` (40,) are the network's scores on the category slots for "what is the
    category of the supporter", `type_scores` (2,) on the type slots for "how is it supported".
    The neighbour whose category is in the top-k and has the highest prior wins; ties (two
    tables beside a cup) go to the higher category score, then the higher instance score.
    When no neighbour has a top-k category, every neighbour is a candidate (the thesis does
    not say; floor/wall/ceiling are always neighbours, so this only happens when none of them
    is in the top-k either)."""
    if not neighbours:
        raise ValueError("every object has the layout instances as neighbours")
    kind = SUPPORT_TYPE_ORDER[int(np.argmax(type_scores))]
    order = np.argsort(-category_scores, kind="stable")[:top_k]
    top = {NYU40_CLASSES[c] for c in order}
    candidates = [n for n in neighbours if n.cls in top] or list(neighbours)
    best = max(
        candidates,
        key=lambda n: (
            prior(n.cls, child_cls, kind),
            float(category_scores[class_index(n.cls)]),
            n.instance_score,
        ),
    )
    return best.supporter, kind


def prior_only_decode(
    child_cls: str,
    neighbours: Sequence[Candidate],
    joint: Callable[[str, str, str], float],
) -> tuple[Supporter, str]:
    """Baseline without the network: the neighbour and type maximising the counted
    P(supporter class, type | child class); equal priors go to the earlier neighbour."""
    best = max(
        ((n, t) for n in neighbours for t in SUPPORT_TYPE_ORDER),
        key=lambda nt: joint(nt[0].cls, child_cls, nt[1]),
    )
    return best[0].supporter, best[1]

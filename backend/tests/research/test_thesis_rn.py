"""The thesis's Relation Network: shapes, question encoding, Eq. 4.1, training, ONNX export."""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import numpy as np
import pytest
import torch
from holiscene.learning.priors import count_priors
from holiscene.research.thesis_rn import (
    ONNX_TOLERANCE,
    Item,
    ThesisRelationNet,
    batch_arrays,
    evaluate_thesis_rn,
    export_onnx,
    onnx_difference,
    reference_forward,
    scene_items,
    train_step,
)
from holiscene.research.thesis_rn_data import (
    ANSWER_CATEGORY,
    ANSWER_NO,
    ANSWER_TYPE,
    ANSWER_YES,
    N_ANSWERS,
    QUESTION_DIM,
    RELATIONAL,
    Candidate,
    Question,
    RNScene,
    decode_question,
    encode_question,
    eq41_decode,
    load_scene,
    rn_scene,
    save_scene,
)
from holiscene.synth.generate import synthesize
from holiscene_schema import NYU40_CLASSES
from holiscene_schema.relation_model import OPSET

# Two small synthetic scenes: 34 has objects on the floor and on the wall, 36 on other objects.
TINY_SEEDS = (34, 36)


@cache
def tiny_scenes() -> tuple[RNScene, ...]:
    out = []
    for seed in TINY_SEEDS:
        synthetic = synthesize(seed)
        scene = rn_scene(synthetic.truth, synthetic.frame.rgb)
        assert scene is not None
        out.append(scene)
    return tuple(out)


def test_shapes_300x300x4_to_10x10x64_to_104() -> None:
    torch.manual_seed(0)
    model = ThesisRelationNet().eval()
    image = torch.rand(1, 4, 300, 300)
    sizes = []
    x = image
    for layer in model.vision:
        x = layer(x)
        if isinstance(layer, torch.nn.Conv2d):
            sizes.append((x.shape[1], x.shape[2], x.shape[3]))
    assert sizes == [(64, 150, 150), (64, 75, 75), (64, 38, 38), (64, 19, 19), (64, 10, 10)]
    cells = model.cells(image)
    assert cells.shape == (1, 100, 66)
    question = torch.from_numpy(encode_question(Question(3, 5, 2, 1)))[None]
    with torch.no_grad():
        out = model(image, question)
        literal = reference_forward(model, image, question)
    assert out.shape == (1, N_ANSWERS) == (1, 104)
    # The split first g layer is the same function as building all 100x100 x 238 inputs.
    scale = max(1.0, float(literal.abs().max()))
    assert float((out - literal).abs().max()) <= 1e-5 * scale
    assert model.g_in.in_features == 64 * 2 + 2 * 2 + 106


def test_question_encoding_is_106_one_hot_groups_and_round_trips() -> None:
    assert QUESTION_DIM == 106 == 60 + 40 + 4 + 2
    for instance, category, index, group in itertools.product(
        (0, 17, 59), range(40), range(4), range(2)
    ):
        q = Question(instance, category, index, group)
        v = encode_question(q)
        assert v.shape == (106,) and v.dtype == np.float32
        assert [v[a:b].sum() for a, b in ((0, 60), (60, 100), (100, 104), (104, 106))] == [1] * 4
        assert decode_question(v) == q
    two_hot = encode_question(Question(1, 2, 3, 0))
    two_hot[5] = 1.0
    with pytest.raises(ValueError):
        decode_question(two_hot)
    with pytest.raises(ValueError):
        encode_question(Question(60, 0, 0, 0))


def test_scene_answers_follow_the_table() -> None:
    for scene in tiny_scenes():
        n = len(scene.classes)
        # Every object keeps at least one cell of its own in the 300x300 label map.
        assert set(np.unique(scene.labels)) == set(range(n + 1))
        for i in range(n):
            answers = scene.answers(i)
            assert len(answers) == 8 and all(0 <= a < 104 for a in answers.values())
            parent, kind = scene.parents[i], scene.types[i]
            assert parent is not None and kind is not None
            assert answers[(0, 0)] == ANSWER_CATEGORY + NYU40_CLASSES.index(scene.classes[i])
            assert answers[(0, 1)] == i
            assert answers[(1, 2)] == ANSWER_TYPE + ("below", "behind").index(kind)
            if isinstance(parent, str):  # structural: category answers, "yes"
                assert (
                    answers[(1, 0)]
                    == answers[(1, 1)]
                    == ANSWER_CATEGORY + (NYU40_CLASSES.index(parent))
                )
                assert answers[(1, 3)] == ANSWER_YES
            else:
                assert answers[(1, 0)] == parent and answers[(1, 3)] == ANSWER_NO
                assert parent in scene.neighbours(i)
            assert scene.neighbours(i)[-3:] == ["ceiling", "floor", "wall"]
    kinds = {p if isinstance(p, str) else "object" for s in tiny_scenes() for p in s.parents}
    assert kinds >= {"floor", "wall", "object"}


def test_cache_round_trip(tmp_path: Path) -> None:
    scene = tiny_scenes()[1]
    save_scene(scene, tmp_path / "36.npz")
    back = load_scene(tmp_path / "36.npz")
    assert (back.name, back.classes, back.parents, back.types) == (
        scene.name,
        scene.classes,
        scene.parents,
        scene.types,
    )
    assert np.array_equal(back.rgb, scene.rgb) and np.array_equal(back.labels, scene.labels)
    assert np.array_equal(back.adjacency, scene.adjacency)


def _scores(*classes: str) -> np.ndarray:
    """Category scores ranking `classes` first, in that order."""
    scores = np.zeros(40, dtype=np.float32)
    for rank, cls in enumerate(classes):
        scores[NYU40_CLASSES.index(cls)] = 10.0 - rank
    return scores


PRIOR = {
    ("night_stand", "below"): 0.4,
    ("table", "below"): 0.3,
    ("bed", "below"): 0.9,  # the most probable class, but the network does not rank it
    ("floor", "below"): 0.1,
    ("wall", "behind"): 0.8,
}


def prior(supporter: str, child: str, kind: str) -> float:
    assert child == "lamp"
    return PRIOR.get((supporter, kind), 0.0)


LAYOUT = [Candidate("ceiling", "ceiling"), Candidate("floor", "floor"), Candidate("wall", "wall")]


def test_eq41_picks_the_most_probable_neighbour_among_the_top_5_categories() -> None:
    neighbours = [
        Candidate(0, "table"),
        Candidate(1, "night_stand"),
        Candidate(2, "bed"),
        *LAYOUT,
    ]
    categories = _scores("table", "floor", "desk", "night_stand", "wall", "bed")
    below = np.array([2.0, -1.0])
    assert eq41_decode("lamp", categories, below, neighbours, prior) == (1, "below")
    # The type comes from the network: from behind, the wall's prior wins.
    assert eq41_decode("lamp", categories, below[::-1], neighbours, prior) == ("wall", "behind")
    # A night stand that does not touch the lamp is not a candidate.
    assert eq41_decode("lamp", categories, below, [neighbours[0], *LAYOUT], prior) == (
        0,
        "below",
    )
    # Two tables touching: the network's instance score breaks the tie.
    tables = [Candidate(4, "table", 0.2), Candidate(7, "table", 1.5), *LAYOUT]
    assert eq41_decode("lamp", categories, below, tables, prior) == (7, "below")
    # Top-1 instead of top-5: only tables are candidates.
    assert eq41_decode("lamp", categories, below, neighbours, prior, top_k=1) == (0, "below")


@dataclass
class Oracle:
    """Answers every question right, from the scenes it knows (found by their image)."""

    scenes: tuple[RNScene, ...]

    def __call__(self, images: np.ndarray, questions: np.ndarray) -> np.ndarray:
        by_rgb = {s.rgb.tobytes(): s for s in self.scenes}
        out = np.zeros((len(images), N_ANSWERS), dtype=np.float32)
        for row, (image, vector) in enumerate(zip(images, questions, strict=True)):
            scene = by_rgb[np.ascontiguousarray(image[:3].transpose(1, 2, 0)).tobytes()]
            q = decode_question(vector)
            out[row, scene.answers(q.instance)[(q.group, q.index)]] = 1.0
        return out


def test_evaluation_with_right_answers_scores_every_question_right() -> None:
    scenes = tiny_scenes()
    priors = count_priors(s.support_sample() for s in scenes)
    result = evaluate_thesis_rn(Oracle(scenes), scenes, priors)
    objects = sum(len(s.classes) for s in scenes)
    assert result.objects == objects and result.relational == 4 * objects
    summary = result.summary()
    assert summary["relational_accuracy"] == summary["non_relational_accuracy"] == 1.0
    # Every supporter touches its object and is in the top-5 categories, but so is the floor
    # (the oracle's other 39 category scores tie, and the first ones are wall, floor, cabinet,
    # bed); Eq. 4.1 then trusts the prior, so the lamp on scene 36's table goes to the floor,
    # P(floor | lamp, below) being the larger. Every other object is found.
    assert (result.eq41_correct, result.prior_only_correct) == (objects - 1, objects - 1)
    lamp = tiny_scenes()[1].classes.index("lamp")
    assert tiny_scenes()[1].parents[lamp] == tiny_scenes()[1].classes.index("table")
    assert priors.conditional("floor", "lamp", "below") > priors.conditional(
        "table", "lamp", "below"
    )


@cache
def trained() -> tuple[ThesisRelationNet, list[float], tuple[np.ndarray, ...]]:
    torch.manual_seed(0)
    scenes = tiny_scenes()
    relational = [it for it in scene_items(scenes) if it.group == RELATIONAL]
    batch: list[Item] = [relational[0], relational[-1]]  # one question from each scene
    arrays = batch_arrays(scenes, batch, "labels")
    assert arrays[0].shape == (2, 4, 300, 300) and arrays[1].shape == (2, 106)
    model = ThesisRelationNet()
    # lr 1e-4 rather than the thesis's 1e-3: on one batch of two the larger rate overshoots
    # within three steps (the sum over 10,000 pairs makes the logits large).
    optimizer = torch.optim.Adam(model.parameters(), lr=1e-4)
    losses = [train_step(model, optimizer, *arrays) for _ in range(3)]
    return model, losses, arrays


def test_a_few_training_steps_reduce_the_loss() -> None:
    _, losses, _ = trained()
    assert losses[-1] < 0.5 * losses[0], losses


def test_onnx_export_matches_pytorch(tmp_path: Path) -> None:
    model, _, (images, questions, _) = trained()
    path = tmp_path / "thesis_rn.onnx"
    export_onnx(model, path)
    import onnx

    exported = onnx.load(str(path))
    assert exported.opset_import[0].version == OPSET
    graph = exported.graph
    assert [i.name for i in graph.input] == ["image", "question"]
    assert [o.name for o in graph.output] == ["answer_logits"]
    absolute, relative = onnx_difference(model, path, images, questions)
    assert relative <= ONNX_TOLERANCE, (absolute, relative)
    # A batch of one goes through the same file (the batch axis is dynamic).
    assert onnx_difference(model, path, images[:1], questions[:1])[1] <= ONNX_TOLERANCE

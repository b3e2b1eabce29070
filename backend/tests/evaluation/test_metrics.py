"""Support accuracy, camera errors, AP and mask IoU on small hand-made scenes."""

from __future__ import annotations

import numpy as np
import pytest
from holiscene.evaluation.metrics import Evaluation, score_3d
from holiscene.geometry.boxes import box_corners
from holiscene.segmentation.rle import encode_mask
from holiscene_schema import Camera, ImageInfo, Layout, Scene, SceneObject, SupportRelation

IMAGE = ImageInfo(file="img.png", width=20, height=10)


def obj(
    obj_id: str, cls: str, bbox: list[float], center: tuple[float, float, float] | None = None
) -> SceneObject:
    mask = np.zeros((10, 20), dtype=bool)
    x1, y1, x2, y2 = (int(v) for v in bbox)
    mask[y1:y2, x1:x2] = True
    corners = None
    if center is not None:
        corners = box_corners(np.array(center), np.ones(3), 0.0).tolist()
    return SceneObject(
        id=obj_id, cls=cls, bbox=bbox, mask=encode_mask(mask, "given"), corners_3d=corners
    )  # type: ignore[arg-type]


def support(child: str, parent: str, kind: str = "below") -> SupportRelation:
    return SupportRelation(child=child, parent=parent, type=kind, source="auto")  # type: ignore[arg-type]


def camera(pitch: float | None, roll: float | None) -> Camera:
    return Camera(K=np.eye(3).tolist(), K_source="given", pitch_deg=pitch, roll_deg=roll)


@pytest.fixture()
def truth() -> Scene:
    return Scene(
        name="t",
        image=IMAGE,
        camera=camera(10.0, 2.0),
        objects=[
            obj("t0", "table", [0, 4, 10, 10], (3, 0, 0)),
            obj("t1", "lamp", [2, 0, 5, 4], (3, 1, 0)),
            obj("t2", "picture", [12, 1, 18, 5], (5, 1, 2)),
        ],
        supports=[support("t0", "floor"), support("t1", "t0"), support("t2", "wall", "behind")],
    )


def test_perfect_prediction_scores_perfectly(truth: Scene) -> None:
    evaluation = Evaluation()
    evaluation.add(truth, truth)
    summary = evaluation.summary()
    assert summary["support"]["accuracy"] == 1.0
    assert summary["camera"]["pitch_mae_deg"] == 0.0
    assert summary["detection_3d"]["map"] == pytest.approx(1.0)
    assert summary["detection_3d"]["recall"] == 1.0
    assert summary["mask"]["mean_iou"] == 1.0


def test_supports_matched_by_boxes_not_ids(truth: Scene) -> None:
    # Same boxes under other ids and in another order; the lamp's supporter is wrong in type.
    predicted = Scene(
        name="p",
        image=IMAGE,
        camera=camera(13.0, -1.0),
        objects=[
            truth.objects[2].model_copy(update={"id": "a"}),
            truth.objects[0].model_copy(update={"id": "b"}),
            truth.objects[1].model_copy(update={"id": "c"}),
        ],
        supports=[
            support("a", "wall", "behind"),
            support("b", "floor"),
            support("c", "b", "behind"),
        ],
    )
    evaluation = Evaluation()
    evaluation.add(predicted, truth)
    s = evaluation.summary()
    assert s["support"]["accuracy"] == pytest.approx(2 / 3)
    assert s["support"]["supporter_accuracy"] == 1.0
    assert s["support"]["type_accuracy"] == pytest.approx(2 / 3)
    assert s["support"]["type_confusion"]["below"]["behind"] == 1
    assert s["camera"]["pitch_mae_deg"] == pytest.approx(3.0)
    assert s["camera"]["roll_mae_deg"] == pytest.approx(3.0)


def test_missing_values_score_as_wrong(truth: Scene) -> None:
    empty = Scene(name="p", image=IMAGE, camera=camera(None, None))
    evaluation = Evaluation()
    evaluation.add(empty, truth)
    s = evaluation.summary()
    assert s["support"]["accuracy"] == 0.0
    assert s["support"]["type_confusion"]["below"]["none"] == 2
    assert s["camera"]["scenes_without_estimate"] == 1
    assert s["mask"]["mean_iou"] == 0.0
    assert s["detection_3d"]["map"] == 0.0
    assert s["detection_3d"]["recall"] == 0.0


def test_average_precision_with_a_false_positive_ranked_first() -> None:
    evaluation = Evaluation()
    evaluation.gt_boxes["chair"] = 2
    # Ranked: false positive, then two hits -> precision 0, 1/2, 2/3 at recall 0, 1/2, 1.
    evaluation.detections["chair"] = [(0.9, False), (0.8, True), (0.7, True)]
    assert evaluation.average_precision()["chair"] == pytest.approx(2 / 3)


def test_3d_boxes_rank_by_detection_score_times_box_confidence(truth: Scene) -> None:
    """Two lamps, one placed wrong: ranked by the box confidence the wrong one comes second
    (precision 1 at recall 1/2: AP 1/2); with the higher confidence it would come first
    (precision 1/2: AP 1/4)."""
    lamps = [obj(f"l{i}", "lamp", [i, 0, i + 1, 2], (3 * i, 5, 0)) for i in range(2)]
    truth = truth.model_copy(update={"objects": lamps, "supports": []})
    wrong = lamps[0].model_copy(update={"corners_3d": (np.array(lamps[0].corners_3d) + 5).tolist()})

    def lamp_ap(confidences: tuple[float, float]) -> float:
        judged = [
            o.model_copy(update={"score": 0.8, "box_3d_confidence": c})
            for o, c in zip((wrong, lamps[1]), confidences, strict=True)
        ]
        evaluation = Evaluation()
        evaluation.add(truth.model_copy(update={"objects": judged}), truth)
        return evaluation.average_precision()["lamp"]

    assert lamp_ap((0.2, 0.9)) == pytest.approx(0.5)
    assert lamp_ap((0.9, 0.2)) == pytest.approx(0.25)
    assert score_3d(lamps[0]) == 1.0  # neither a score nor a confidence
    assert score_3d(lamps[0].model_copy(update={"score": 0.5, "box_3d_confidence": 0.4})) == 0.2


def test_box_recall_counts_every_box_the_same(truth: Scene) -> None:
    """Three lamps found and a table missed: recall 3/4, while mAP (lamp 1, table 0) is 1/2."""
    lamps = [obj(f"l{i}", "lamp", [i, 0, i + 1, 2], (3 * i, 5, 0)) for i in range(3)]
    table = obj("t", "table", [0, 4, 10, 10], (3, 0, 0))
    truth = truth.model_copy(update={"objects": [*lamps, table], "supports": []})
    moved = table.model_copy(update={"corners_3d": (np.array(table.corners_3d) + 5).tolist()})
    predicted = truth.model_copy(update={"objects": [*lamps, moved]})
    evaluation = Evaluation()
    evaluation.add(predicted, truth)
    detection = evaluation.summary()["detection_3d"]
    assert detection["recall"] == pytest.approx(3 / 4)
    assert detection["map"] == pytest.approx(1 / 2)


def test_layout_in_view_leaves_out_the_room_behind_the_camera() -> None:
    view = Camera(
        K=[[10.0, 0, 10], [0, 10, 5], [0, 0, 1]], K_source="given", pitch_deg=10.0, roll_deg=0.0
    )
    room = box_corners(np.array([2.0, 0.0, 0.0]), np.array([6.0, 3.0, 4.0]), 0.0)
    behind_moved = box_corners(np.array([1.0, 0.0, 0.0]), np.array([8.0, 3.0, 4.0]), 0.0)
    truth = Scene(name="t", image=IMAGE, camera=view, layout=Layout(corners_3d=room.tolist()))
    guess = truth.model_copy(update={"layout": Layout(corners_3d=behind_moved.tolist())})
    evaluation = Evaluation()
    evaluation.add(guess, truth)
    layout = evaluation.summary()["layout"]
    assert layout["iou_3d"] == pytest.approx(0.75)
    assert layout["iou_3d_in_view"] == pytest.approx(1.0)


def test_a_missed_layout_counts_in_view_only_where_the_truth_has_a_camera() -> None:
    room = box_corners(np.array([2.0, 0.0, 0.0]), np.array([6.0, 3.0, 4.0]), 0.0).tolist()
    view = Camera(
        K=[[10.0, 0, 10], [0, 10, 5], [0, 0, 1]], K_source="given", pitch_deg=10.0, roll_deg=0.0
    )
    with_camera = Scene(name="a", image=IMAGE, camera=view, layout=Layout(corners_3d=room))
    without_camera = with_camera.model_copy(update={"name": "b", "camera": camera(None, None)})
    evaluation = Evaluation()
    evaluation.add(with_camera, with_camera)  # in view 1.0
    evaluation.add(Scene(name="b", image=IMAGE), without_camera)  # missed: no in-view figure
    layout = evaluation.summary()["layout"]
    assert layout["iou_3d"] == pytest.approx(0.5)
    assert layout["iou_3d_in_view"] == pytest.approx(1.0)

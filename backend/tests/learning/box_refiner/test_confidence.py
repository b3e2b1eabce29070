"""The box refiner's confidence: a logistic regression fitted on boxes found or not."""

from __future__ import annotations

import numpy as np
import pytest
from holiscene.learning.box_refiner.confidence import (
    CONFIDENCE_FEATURES,
    ConfidenceModel,
    confidence_features,
    fit_confidence,
)
from holiscene_schema import Box3D


def test_the_fit_learns_that_larger_expected_errors_mean_wrong_boxes() -> None:
    rng = np.random.default_rng(0)
    features = rng.normal(size=(400, len(CONFIDENCE_FEATURES)))
    # Found when the expected distance error (feature 0) is small, with some noise.
    found = features[:, 0] + 0.5 * rng.normal(size=400) < 0.0
    model = fit_confidence(features, found)
    chances = model.chance(features)
    assert np.all((chances > 0) & (chances < 1))
    assert chances[found].mean() > 0.7 > 0.3 > chances[~found].mean()
    assert model.weights[1] < 0  # the distance's expected error lowers the chance
    # Its mean chance matches the share found (a logistic fit's intercept does that).
    assert chances.mean() == pytest.approx(found.mean(), abs=0.02)
    again = ConfidenceModel.from_json(model.to_json())
    assert np.allclose(again.chance(features), chances, atol=1e-4)


def test_the_fit_stays_finite_when_one_feature_separates_the_boxes() -> None:
    features = np.zeros((20, len(CONFIDENCE_FEATURES)))
    features[:, 1] = np.arange(20)
    model = fit_confidence(features, features[:, 1] >= 10)
    assert np.isfinite(model.weights).all()


def test_a_model_made_for_other_features_is_refused() -> None:
    data = fit_confidence(np.ones((3, len(CONFIDENCE_FEATURES))), np.array([1, 0, 1], bool))
    stale = {**data.to_json(), "features": ["log distance"]}
    with pytest.raises(ValueError, match="other features"):
        ConfidenceModel.from_json(stale)


def test_features_read_the_box_against_its_distance() -> None:
    box = Box3D(center=[0.0, 0.0, -4.0], size=[0.2, 1.0, 2.0], yaw_deg=0.0)
    row = confidence_features(box, np.full(4, -2.0, np.float32), np.zeros(4, np.float32))
    assert row.shape == (len(CONFIDENCE_FEATURES),)
    assert np.isfinite(row).all()  # a spread of 0 (one member) too
    assert row[-3] == pytest.approx(np.log(0.2 / 4.0))
    assert row[-2] == pytest.approx(np.log(2.0 / 4.0))
    assert row[-1] == pytest.approx(np.log(4.0))

"""Every refusal of the domain is a DomainError, and one handler answers it with its status,
its headers and `{"detail": ...}`; anything else stays a 500 without details."""

from __future__ import annotations

import pytest
from fastapi import FastAPI
from fastapi.testclient import TestClient
from holiscene.api.errors import install_error_handlers
from holiscene.core.errors import DomainError
from holiscene.core.passwords import WeakPasswordError
from holiscene.editing.edits import InvalidEditError
from holiscene.editing.workflow_rules import WorkflowError
from holiscene.inputs import InputError
from holiscene.pipeline import PipelineBuildError
from holiscene.segmentation.refine import RefineInputError
from holiscene.services.relation_retraining import NotEnoughLabelsError
from holiscene.services.workbench import PlacementNotPossibleError
from holiscene.store.jobs import (
    JobNotFoundError,
    JobQueueFullError,
    RetrainRunningError,
    SceneJobRunningError,
)
from holiscene.store.model_registry import ModelNotFoundError, NoActiveModelError
from holiscene.store.scenes import RevisionConflictError, SceneChangedError, SceneNotFoundError
from holiscene.store.users import UserError, UserNotFoundError
from holiscene.store.workflow import NoSceneWaitingError, WorkflowCommentError

CONFLICT_MESSAGE = (
    "this scene changed since you loaded it (someone else saved first); "
    "reload to see their changes, then apply yours again"
)

ANSWERS: list[tuple[Exception, int, object]] = [
    (InputError("the photo is empty", 400), 400, "the photo is empty"),
    (InputError("cam_K.txt is not text"), 422, "cam_K.txt is not text"),
    (InvalidEditError("no object o9"), 422, "invalid edit: no object o9"),
    (RefineInputError("the box is empty"), 422, "cannot refine the mask: the box is empty"),
    (SceneNotFoundError("no scene s1"), 404, "no scene s1"),
    (JobNotFoundError(), 404, "not found"),
    (ModelNotFoundError("no model m"), 404, "no model m"),
    (NoActiveModelError(), 404, "no Relation Network model is registered"),
    (UserNotFoundError("no user u"), 404, "no user u"),
    (NoSceneWaitingError("nothing to annotate"), 404, "nothing to annotate"),
    (RevisionConflictError(7), 409, {"message": CONFLICT_MESSAGE, "current_revision": 7}),
    (SceneChangedError(3, 8), 409, {"message": CONFLICT_MESSAGE, "current_revision": 8}),
    (
        RetrainRunningError("j1"),
        409,
        "a retrain job is already running (job j1); wait for it to finish",
    ),
    (SceneJobRunningError("j2"), 409, str(SceneJobRunningError("j2"))),
    (WorkflowError("cannot submit"), 409, "cannot submit"),
    (UserError("the name is taken", 409), 409, "the name is taken"),
    (UserError("bad name"), 422, "bad name"),
    (NotEnoughLabelsError("need 3"), 422, "need 3"),
    (PlacementNotPossibleError("no layout"), 422, "no layout"),
    (PipelineBuildError("unknown stage x"), 422, "unknown stage x"),
    (WorkflowCommentError("say why"), 422, "say why"),
    (WeakPasswordError("too short"), 422, "too short"),
]


@pytest.fixture(scope="module")
def raising() -> tuple[TestClient, list[Exception]]:
    to_raise: list[Exception] = []
    app = FastAPI()
    install_error_handlers(app)

    @app.get("/raise")
    def raise_last() -> None:
        raise to_raise[-1]

    return TestClient(app, raise_server_exceptions=False), to_raise


@pytest.mark.parametrize(("error", "status", "detail"), ANSWERS, ids=lambda v: type(v).__name__)
def test_a_domain_error_answers_with_its_status_and_detail(
    raising: tuple[TestClient, list[Exception]], error: Exception, status: int, detail: object
) -> None:
    client, to_raise = raising
    assert isinstance(error, DomainError)
    to_raise.append(error)
    answer = client.get("/raise")
    assert (answer.status_code, answer.json()) == (status, {"detail": detail})
    assert "retry-after" not in answer.headers


def test_a_full_queue_says_when_to_try_again(raising: tuple[TestClient, list[Exception]]) -> None:
    client, to_raise = raising
    to_raise.append(JobQueueFullError(12))
    answer = client.get("/raise")
    assert answer.status_code == 503
    assert answer.headers["retry-after"] == "60"
    assert answer.json()["detail"].startswith("12 pipeline jobs are queued or running")


def test_other_errors_stay_internal(raising: tuple[TestClient, list[Exception]]) -> None:
    client, to_raise = raising
    to_raise.append(ValueError("/srv/holiscene/secret"))
    answer = client.get("/raise")
    assert answer.status_code == 500
    assert "secret" not in answer.text

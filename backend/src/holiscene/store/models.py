"""The Relation Network model registry: versioned model directories plus who made which active.

A model is a directory (model.onnx, metrics.json, priors.json, data.json, curve.png) copied
into `<data_dir>/models/<id>/` under a temporary name and renamed into place; its database row
is inserted only after that, so a row always names complete files and a failed copy leaves no
row. Models never change once registered. The active model is the one named by the newest row
of `model_events`, so promoting and rolling back are one insert each and keep the history.
"""

from __future__ import annotations

import functools
import json
import os
import shutil
import tempfile
import threading
import uuid
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from holiscene_schema import ModelAction, ModelEvent, ModelInfo, ModelStatus
from sqlalchemy import Engine, create_engine, func, make_url, select
from sqlalchemy.exc import OperationalError, ProgrammingError
from sqlalchemy.orm import Session
from sqlalchemy.pool import NullPool

from ..core.settings import Settings
from ..learning.training_api import (
    CURVE_FILE,
    DATA_FILE,
    METRICS_FILE,
    MODEL_FILE,
    PRIORS_FILE,
)
from .clock import as_utc, utcnow
from .tables import ModelEventRow, ModelRow

# The model committed with the code; an empty registry starts from it (version 1, active).
DEFAULT_MODEL_DIR = Path(__file__).resolve().parents[1] / "learning" / "default_model"
NO_MODEL_MESSAGE = "no Relation Network model is registered"

# The files a model directory may hold, and how they are served.
MODEL_FILES: Mapping[str, str] = {
    MODEL_FILE: "application/octet-stream",
    METRICS_FILE: "application/json",
    PRIORS_FILE: "application/json",
    DATA_FILE: "application/json",
    CURVE_FILE: "image/png",
}
_STAGING_PREFIX = ".staging-"


class ModelNotFoundError(LookupError):
    pass


class NoActiveModelError(ModelNotFoundError):
    def __init__(self) -> None:
        super().__init__(NO_MODEL_MESSAGE)


class InvalidModelDirError(ValueError):
    pass


@dataclass(frozen=True)
class Registration:
    """What is known about a model besides its files."""

    status: ModelStatus
    parent_id: str | None = None
    job_id: str | None = None
    heldout_accuracy: float | None = None
    parent_heldout_accuracy: float | None = None
    validation_accuracy: float | None = None
    data: dict[str, Any] = field(default_factory=dict)  # scenes it saw, its config
    note: str | None = None


class ModelStore:
    def __init__(self, engine: Engine, root: Path, default_dir: Path | None) -> None:
        """`default_dir`: the model an empty registry starts from (DEFAULT_MODEL_DIR), or None."""
        self.engine = engine
        self.root = root
        self.default_dir = default_dir
        self.root.mkdir(parents=True, exist_ok=True)
        # Version numbers and compare-and-set promotion read then write; in one server process
        # this lock makes them atomic (the unique version column catches anything else).
        self._lock = threading.Lock()

    # -- reading -------------------------------------------------------------------------

    def folder(self, model_id: str) -> Path:
        return self.root / model_id

    def list_models(self) -> list[ModelInfo]:
        """Every model, newest first."""
        with Session(self.engine) as session:
            rows = session.scalars(select(ModelRow).order_by(ModelRow.version.desc())).all()
            active = _active_id(session)
            versions = {r.id: r.version for r in rows}
            return [self._info(r, active, versions) for r in rows]

    def get(self, model_id: str) -> ModelInfo:
        with Session(self.engine) as session:
            row = self._row(session, model_id)
            return self._info(row, _active_id(session), self._versions(session))

    def by_job(self, job_id: str) -> ModelInfo | None:
        with Session(self.engine) as session:
            row = session.scalar(select(ModelRow).where(ModelRow.job_id == job_id))
            if row is None:
                return None
            return self._info(row, _active_id(session), self._versions(session))

    def active(self) -> ModelInfo:
        """The active model; NoActiveModelError when the registry is empty."""
        with Session(self.engine) as session:
            active = _active_id(session)
            if active is None:
                raise NoActiveModelError()
            return self._info(self._row(session, active), active, self._versions(session))

    def active_or_none(self) -> ModelInfo | None:
        try:
            return self.active()
        except NoActiveModelError:
            return None

    def active_dir(self) -> Path | None:
        with Session(self.engine) as session:
            active = _active_id(session)
        return self.folder(active) if active is not None else None

    def file(self, model_id: str, name: str) -> Path:
        """One of a registered model's files; ModelNotFoundError when it has no such file."""
        self.get(model_id)  # the id must be registered before it becomes a path
        path = self.folder(model_id) / name
        if name not in MODEL_FILES or not path.is_file():
            raise ModelNotFoundError(f"model {model_id} has no file {name!r}")
        return path

    def events(self) -> list[ModelEvent]:
        """Every change of the active model, newest first."""
        with Session(self.engine) as session:
            versions = self._versions(session)
            rows = session.scalars(select(ModelEventRow).order_by(ModelEventRow.id.desc())).all()
            return [
                ModelEvent(
                    id=r.id,
                    at=as_utc(r.at),
                    action=r.action,
                    actor=r.actor,
                    model_id=r.model_id,
                    model_version=versions[r.model_id],
                    previous_model_id=r.previous_model_id,
                    previous_version=versions.get(r.previous_model_id or ""),
                    note=r.note,
                )
                for r in rows
            ]

    # -- writing -------------------------------------------------------------------------

    def seed_if_empty(self) -> ModelInfo | None:
        """On first start, register the committed default model as version 1 and make it
        active. Without a default model directory the registry stays empty."""
        if self.default_dir is None or not (self.default_dir / MODEL_FILE).is_file():
            return None
        with Session(self.engine) as session:
            if session.scalar(select(func.count()).select_from(ModelRow)):
                return None
        metrics = _read_json(self.default_dir / METRICS_FILE)
        accuracy = metrics.get("validation_accuracy")
        return self.register(
            self.default_dir,
            Registration(
                status="default",
                validation_accuracy=float(accuracy) if isinstance(accuracy, int | float) else None,
                data={"source": "committed default model"},
                note="the model committed with the code",
            ),
            promote=True,
            actor="system",
            action="seed",
        )

    def register(
        self,
        source: Path,
        registration: Registration,
        *,
        promote: bool = False,
        expected_active: str | None = None,
        actor: str = "system",
        action: ModelAction = "promote",
    ) -> ModelInfo:
        """Copy a finished model directory into the registry and record it.

        With `promote`, the new model becomes active in the same transaction, but only if the
        active model is still `expected_active` (the one it was compared with); otherwise an
        'accepted' model is kept as a 'candidate' and the active model stays."""
        if not (source / MODEL_FILE).is_file() or (source / MODEL_FILE).stat().st_size == 0:
            raise InvalidModelDirError(f"{source} holds no {MODEL_FILE}")
        metrics = _read_json(source / METRICS_FILE)
        model_id = uuid.uuid4().hex[:12]
        self._copy_in(source, model_id)
        try:
            with self._lock, Session(self.engine) as session:
                active = _active_id(session)
                status = registration.status
                note = registration.note
                promoted = promote and (action == "seed" or active == expected_active)
                if promote and not promoted and status == "accepted":
                    status = "candidate"
                    note = _join(note, "the active model changed while this one trained")
                version = (session.scalar(select(func.max(ModelRow.version))) or 0) + 1
                session.add(
                    ModelRow(
                        id=model_id,
                        version=version,
                        created_at=utcnow(),
                        status=status,
                        parent_id=registration.parent_id,
                        job_id=registration.job_id,
                        heldout_accuracy=registration.heldout_accuracy,
                        parent_heldout_accuracy=registration.parent_heldout_accuracy,
                        validation_accuracy=registration.validation_accuracy,
                        metrics=metrics,
                        data=registration.data,
                        note=note,
                    )
                )
                session.flush()
                if promoted:
                    self._add_event(session, model_id, active, actor, action, None)
                session.commit()
        except BaseException:
            shutil.rmtree(self.folder(model_id), ignore_errors=True)
            raise
        return self.get(model_id)

    def promote(self, model_id: str, actor: str, note: str | None = None) -> ModelInfo:
        """Make any registered model active: a rollback when it is older than the active one.
        Promoting the active model changes nothing."""
        with self._lock, Session(self.engine) as session:
            target = self._row(session, model_id)
            active = _active_id(session)
            if active != model_id:
                current = session.get(ModelRow, active) if active else None
                action: ModelAction = (
                    "rollback" if current and target.version < current.version else "promote"
                )
                self._add_event(session, model_id, active, actor, action, note)
                session.commit()
        return self.get(model_id)

    def remove_leftovers(self) -> list[Path]:
        """Delete staging folders and folders without a row (a crash between the rename and the
        insert); call only when nothing is registering, e.g. at start-up."""
        with Session(self.engine) as session:
            known = set(session.scalars(select(ModelRow.id)))
        removed = []
        for path in self.root.iterdir():
            if path.is_dir() and path.name not in known:
                shutil.rmtree(path, ignore_errors=True)
                removed.append(path)
        return removed

    # -- helpers -------------------------------------------------------------------------

    def _copy_in(self, source: Path, model_id: str) -> None:
        staging = Path(tempfile.mkdtemp(prefix=_STAGING_PREFIX, dir=self.root))
        try:
            for name in MODEL_FILES:
                if (source / name).is_file():
                    _copy_durably(source / name, staging / name)
            _fsync_dir(staging)
            os.replace(staging, self.folder(model_id))
            _fsync_dir(self.root)
        except BaseException:
            shutil.rmtree(staging, ignore_errors=True)
            raise

    @staticmethod
    def _add_event(
        session: Session,
        model_id: str,
        previous: str | None,
        actor: str,
        action: ModelAction,
        note: str | None,
    ) -> None:
        session.add(
            ModelEventRow(
                at=utcnow(),
                action=action,
                actor=actor,
                model_id=model_id,
                previous_model_id=previous,
                note=note,
            )
        )

    @staticmethod
    def _row(session: Session, model_id: str) -> ModelRow:
        row = session.get(ModelRow, model_id)
        if row is None:
            raise ModelNotFoundError(f"no model {model_id!r}")
        return row

    @staticmethod
    def _versions(session: Session) -> dict[str, int]:
        return {mid: v for mid, v in session.execute(select(ModelRow.id, ModelRow.version))}

    def _info(self, row: ModelRow, active: str | None, versions: dict[str, int]) -> ModelInfo:
        data = row.data or {}
        return ModelInfo(
            id=row.id,
            version=row.version,
            created_at=as_utc(row.created_at),
            status=row.status,
            active=row.id == active,
            parent_id=row.parent_id,
            parent_version=versions.get(row.parent_id) if row.parent_id else None,
            job_id=row.job_id,
            heldout_accuracy=row.heldout_accuracy,
            parent_heldout_accuracy=row.parent_heldout_accuracy,
            validation_accuracy=row.validation_accuracy,
            training_scenes=len(data.get("training_scenes", [])),
            heldout_scenes=len(data.get("heldout_scenes", [])),
            has_curve=(self.folder(row.id) / CURVE_FILE).is_file(),
            note=row.note,
            metrics=row.metrics or {},
        )


def _active_id(session: Session) -> str | None:
    return session.scalar(select(ModelEventRow.model_id).order_by(ModelEventRow.id.desc()).limit(1))


def _read_json(path: Path) -> dict[str, Any]:
    if not path.is_file():
        return {}
    try:
        value = json.loads(path.read_text())
    except (OSError, ValueError) as exc:
        raise InvalidModelDirError(f"{path} is not valid JSON: {exc}") from exc
    return value if isinstance(value, dict) else {"value": value}


def _join(first: str | None, second: str) -> str:
    return f"{first}; {second}" if first else second


def _copy_durably(source: Path, target: Path) -> None:
    shutil.copyfile(source, target)
    with target.open("rb") as handle:
        os.fsync(handle.fileno())
    if target.stat().st_size != source.stat().st_size:
        raise OSError(f"copying {source} to {target} was incomplete")


def _fsync_dir(path: Path) -> None:
    # On Linux a directory's entries are durable only after fsync on the directory itself.
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


# -- for the pipeline: the promoted model, without a Workbench -----------------------------


@functools.lru_cache(maxsize=8)
def _lookup_engine(url: str) -> Engine:
    # No pool: a lookup per pipeline run must not keep files open (tests delete their dirs).
    connect_args = {"timeout": 30} if url.startswith("sqlite") else {}
    return create_engine(url, poolclass=NullPool, connect_args=connect_args)


def active_model_dir(settings: Settings) -> Path | None:
    """The directory of the promoted Relation Network (model.onnx, priors.json, ...), or None
    when no model is registered or there is no database yet.

    The pipeline's support stage calls this to use whatever an admin promoted. It only reads:
    it never creates or migrates a database (`holiscene infer` may run without one)."""
    url = settings.resolved_database_url
    parsed = make_url(url)
    if parsed.get_backend_name() == "sqlite":
        database = parsed.database
        if not database or database == ":memory:" or not Path(database).is_file():
            return None
    try:
        with Session(_lookup_engine(url)) as session:
            model_id = _active_id(session)
    except (OperationalError, ProgrammingError):
        return None  # a database from before the registry existed (not migrated yet)
    if model_id is None:
        return None
    folder = settings.data_dir / "models" / model_id
    return folder if (folder / MODEL_FILE).is_file() else None


def require_active_model_dir(settings: Settings) -> Path:
    """Like active_model_dir, but NoActiveModelError (a clear message) instead of None."""
    folder = active_model_dir(settings)
    if folder is None:
        raise NoActiveModelError()
    return folder

"""The model registry: versioned model directories plus who made which active, per kind.

Two kinds of model are registered, each with its own versions, active model and history: the
Relation Network ("relation": model.onnx, metrics.json, priors.json, data.json, curve.png in
`<data_dir>/models/<id>/`) and the object detector ("detector": model.onnx, metadata.json,
metrics.json, curve.png in `<data_dir>/detectors/<id>/`). A `ModelStore` serves one kind.

A model directory is copied in under a temporary name and renamed into place; its database row
is inserted only after that, so a row always names complete files and a failed copy leaves no
row. Models never change once registered. A kind's active model is the one named by the newest
row of `model_events` among its models, so promoting and rolling back are one insert each and
keep the history.
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
from typing import Any, TypeVarTuple

from holiscene_schema import (
    HeldoutFigure,
    ModelAction,
    ModelEvent,
    ModelInfo,
    ModelKind,
    ModelStatus,
)
from sqlalchemy import Engine, Select, create_engine, func, make_url, select
from sqlalchemy.exc import OperationalError, ProgrammingError
from sqlalchemy.orm import Session
from sqlalchemy.pool import NullPool

from ..core.errors import NotFoundError
from ..core.settings import Settings
from ..learning.detector import runtime as detector_runtime
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
# The detectors an empty detector registry starts from: the first with a model file.
DEFAULT_DETECTOR_DIRS: tuple[Path, ...] = (detector_runtime.DEFAULT_DETECTOR_DIR,)
# Detectors shipped beside the default and registered with it, not active, for an admin to
# choose: the NYU-40 head is better on synthetic rooms and worse on real photos; the COCO
# CenterNet was the default before PicoDet.
OFFERED_DETECTOR_DIRS: tuple[Path, ...] = (
    detector_runtime.NYU_DETECTOR_DIR,
    detector_runtime.COCO_DETECTOR_DIR,
)
NO_MODEL_MESSAGE = "no Relation Network model is registered"
NO_MODEL_MESSAGES: Mapping[ModelKind, str] = {
    "relation": NO_MODEL_MESSAGE,
    "detector": "no object detector model is registered",
}
# Where each kind's model folders live, under the data directory.
KIND_FOLDERS: Mapping[ModelKind, str] = {"relation": "models", "detector": "detectors"}
# The metrics.json entry a seeded model's validation figure comes from.
_VALIDATION_KEYS: Mapping[ModelKind, str] = {
    "relation": "validation_accuracy",
    "detector": "validation_map_at_0_5",
}

# The files a model directory may hold, and how they are served.
MODEL_FILES: Mapping[str, str] = {
    MODEL_FILE: "application/octet-stream",
    METRICS_FILE: "application/json",
    PRIORS_FILE: "application/json",
    DATA_FILE: "application/json",
    CURVE_FILE: "image/png",
}
DETECTOR_FILES: Mapping[str, str] = {
    detector_runtime.MODEL_FILE: "application/octet-stream",
    detector_runtime.METADATA_FILE: "application/json",
    METRICS_FILE: "application/json",
    CURVE_FILE: "image/png",
    "LICENSE": "text/plain; charset=utf-8",
}
FILES_BY_KIND: Mapping[ModelKind, Mapping[str, str]] = {
    "relation": MODEL_FILES,
    "detector": DETECTOR_FILES,
}
_STAGING_PREFIX = ".staging-"
_Columns = TypeVarTuple("_Columns")


def default_detector_dir() -> Path | None:
    """The detector an empty detector registry starts from (the committed default), or None."""
    for folder in DEFAULT_DETECTOR_DIRS:
        if (folder / detector_runtime.MODEL_FILE).is_file():
            return folder
    return None


class ModelNotFoundError(NotFoundError):
    pass


class NoActiveModelError(ModelNotFoundError):
    def __init__(self, kind: ModelKind = "relation") -> None:
        super().__init__(NO_MODEL_MESSAGES[kind])


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
    heldout_recall: float | None = None  # detectors: kept in `data`
    parent_heldout_recall: float | None = None


class ModelStore:
    def __init__(
        self,
        engine: Engine,
        root: Path,
        default_dir: Path | None,
        kind: ModelKind = "relation",
    ) -> None:
        """The registry of one kind of model, its folders under `root`. `default_dir`: the
        model an empty registry starts from (DEFAULT_MODEL_DIR, default_detector_dir()), or
        None."""
        self.engine = engine
        self.root = root
        self.default_dir = default_dir
        self.kind: ModelKind = kind
        self.files = FILES_BY_KIND[kind]
        self.root.mkdir(parents=True, exist_ok=True)
        # Version numbers and compare-and-set promotion read then write; in one server process
        # this lock makes them atomic (the unique version column catches anything else).
        self._lock = threading.Lock()

    # -- reading -------------------------------------------------------------------------

    def folder(self, model_id: str) -> Path:
        return self.root / model_id

    def list_models(self) -> list[ModelInfo]:
        """Every model of this kind, newest first."""
        with Session(self.engine) as session:
            query = self._of_kind(select(ModelRow)).order_by(ModelRow.version.desc())
            rows = session.scalars(query).all()
            active = _active_id(session, self.kind)
            versions = {r.id: r.version for r in rows}
            return [self._info(r, active, versions) for r in rows]

    def get(self, model_id: str) -> ModelInfo:
        with Session(self.engine) as session:
            row = self._row(session, model_id)
            return self._info(row, _active_id(session, self.kind), self._versions(session))

    def by_job(self, job_id: str) -> ModelInfo | None:
        with Session(self.engine) as session:
            row = session.scalar(self._of_kind(select(ModelRow)).where(ModelRow.job_id == job_id))
            if row is None:
                return None
            return self._info(row, _active_id(session, self.kind), self._versions(session))

    def active(self) -> ModelInfo:
        """The active model; NoActiveModelError when the registry is empty."""
        with Session(self.engine) as session:
            active = _active_id(session, self.kind)
            if active is None:
                raise NoActiveModelError(self.kind)
            return self._info(self._row(session, active), active, self._versions(session))

    def active_or_none(self) -> ModelInfo | None:
        try:
            return self.active()
        except NoActiveModelError:
            return None

    def active_dir(self) -> Path | None:
        with Session(self.engine) as session:
            active = _active_id(session, self.kind)
        return self.folder(active) if active is not None else None

    def file(self, model_id: str, name: str) -> Path:
        """One of a registered model's files; ModelNotFoundError when it has no such file."""
        self.get(model_id)  # the id must be registered before it becomes a path
        path = self.folder(model_id) / name
        if name not in self.files or not path.is_file():
            raise ModelNotFoundError(f"model {model_id} has no file {name!r}")
        return path

    def events(self) -> list[ModelEvent]:
        """Every change of this kind's active model, newest first."""
        with Session(self.engine) as session:
            versions = self._versions(session)
            query = _events_of_kind(select(ModelEventRow), self.kind)
            rows = session.scalars(query.order_by(ModelEventRow.id.desc())).all()
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
            if session.scalar(self._of_kind(select(func.count()).select_from(ModelRow))):
                return None
        metrics = _read_json(self.default_dir / METRICS_FILE)
        accuracy = metrics.get(_VALIDATION_KEYS[self.kind])
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
                active = _active_id(session, self.kind)
                status = registration.status
                note = registration.note
                promoted = promote and (action == "seed" or active == expected_active)
                if promote and not promoted and status == "accepted":
                    status = "candidate"
                    note = _join(note, "the active model changed while this one trained")
                newest = session.scalar(self._of_kind(select(func.max(ModelRow.version))))
                session.add(
                    ModelRow(
                        id=model_id,
                        kind=self.kind,
                        version=(newest or 0) + 1,
                        created_at=utcnow(),
                        status=status,
                        parent_id=registration.parent_id,
                        job_id=registration.job_id,
                        heldout_accuracy=registration.heldout_accuracy,
                        parent_heldout_accuracy=registration.parent_heldout_accuracy,
                        validation_accuracy=registration.validation_accuracy,
                        metrics=metrics,
                        data=_registration_data(registration),
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
            active = _active_id(session, self.kind)
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
            known = set(session.scalars(select(ModelRow.id)))  # of any kind: never a model's
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
            for name in self.files:
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

    def _of_kind(self, query: Select[*_Columns]) -> Select[*_Columns]:
        return query.where(ModelRow.kind == self.kind)

    def _row(self, session: Session, model_id: str) -> ModelRow:
        row = session.get(ModelRow, model_id)
        if row is None or row.kind != self.kind:
            raise ModelNotFoundError(f"no {self.kind} model {model_id!r}")
        return row

    def _versions(self, session: Session) -> dict[str, int]:
        query = self._of_kind(select(ModelRow.id, ModelRow.version))
        return {mid: v for mid, v in session.execute(query)}

    def _name(self, model_id: str) -> str | None:
        """A detector's name from its metadata.json."""
        if self.kind != "detector":
            return None
        return _detector_name(self.folder(model_id) / detector_runtime.METADATA_FILE)

    def _info(self, row: ModelRow, active: str | None, versions: dict[str, int]) -> ModelInfo:
        data = row.data or {}
        return ModelInfo(
            id=row.id,
            kind=self.kind,
            version=row.version,
            name=self._name(row.id),
            created_at=as_utc(row.created_at),
            status=row.status,
            active=row.id == active,
            parent_id=row.parent_id,
            parent_version=versions.get(row.parent_id) if row.parent_id else None,
            job_id=row.job_id,
            heldout_accuracy=row.heldout_accuracy,
            parent_heldout_accuracy=row.parent_heldout_accuracy,
            heldout_recall=_figure(data.get("heldout_recall")),
            parent_heldout_recall=_figure(data.get("parent_heldout_recall")),
            validation_accuracy=row.validation_accuracy,
            training_scenes=len(data.get("training_scenes", [])),
            heldout_scenes=len(data.get("heldout_scenes", [])),
            heldout_items=_count(data.get("heldout_items")),
            heldout_others=_heldout_others(data.get("heldout_others")),
            has_curve=(self.folder(row.id) / CURVE_FILE).is_file(),
            note=row.note,
            metrics=row.metrics or {},
        )


@functools.lru_cache(maxsize=256)
def _detector_name(metadata_file: Path) -> str | None:
    """Read once per registered detector: its files never change once registered, and every
    listing of the models page names them all."""
    try:
        metadata = _read_json(metadata_file)
    except InvalidModelDirError:
        return None  # the list still shows; loading that detector says what is wrong
    name = metadata.get("name")
    return name if isinstance(name, str) else None


def _count(value: Any) -> int | None:
    return value if isinstance(value, int) and not isinstance(value, bool) else None


def _events_of_kind(query: Select[*_Columns], kind: ModelKind) -> Select[*_Columns]:
    return query.join(ModelRow, ModelRow.id == ModelEventRow.model_id).where(ModelRow.kind == kind)


def _active_id(session: Session, kind: ModelKind) -> str | None:
    query = _events_of_kind(select(ModelEventRow.model_id), kind)
    return session.scalar(query.order_by(ModelEventRow.id.desc()).limit(1))


def _registration_data(registration: Registration) -> dict[str, Any]:
    data = dict(registration.data)
    for key in ("heldout_recall", "parent_heldout_recall"):
        value = getattr(registration, key)
        if value is not None:
            data[key] = value
    return data


def _figure(value: object) -> float | None:
    return float(value) if isinstance(value, int | float) else None


def _heldout_others(value: object) -> list[HeldoutFigure]:
    """The other models' figures a retrain stored in its model's data (none before they were
    recorded; an entry that does not read as one is left out)."""
    figures = []
    for entry in value if isinstance(value, list) else []:
        accuracy = _figure(entry.get("accuracy")) if isinstance(entry, dict) else None
        if accuracy is not None and isinstance(entry.get("model_id"), str):
            figures.append(
                HeldoutFigure(
                    model_id=entry["model_id"],
                    accuracy=accuracy,
                    recall=_figure(entry.get("recall")),
                )
            )
    return figures


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


def model_label(info: ModelInfo) -> str:
    """How a stored scene names the model that made its guesses: "Relation Network v2",
    "object detector v3 (COCO PicoDet-S 416 ...)"."""
    if info.kind == "relation":
        return f"Relation Network v{info.version}"
    return f"object detector v{info.version}" + (f" ({info.name})" if info.name else "")


def active_model_dir(settings: Settings, kind: ModelKind = "relation") -> Path | None:
    """The directory of the promoted model of a kind (the Relation Network's model.onnx,
    priors.json, ...; the detector's model.onnx, metadata.json), or None when no model of the
    kind is registered or there is no database yet.

    For running the pipeline with whatever an admin promoted. It only reads: it never creates
    or migrates a database (`holiscene infer` may run without one)."""
    url = settings.resolved_database_url
    parsed = make_url(url)
    if parsed.get_backend_name() == "sqlite":
        database = parsed.database
        if not database or database == ":memory:" or not Path(database).is_file():
            return None
    try:
        with Session(_lookup_engine(url)) as session:
            model_id = _active_id(session, kind)
    except (OperationalError, ProgrammingError):
        return None  # a database from before the registry (or its kinds) existed
    if model_id is None:
        return None
    folder = settings.data_dir / KIND_FOLDERS[kind] / model_id
    return folder if (folder / MODEL_FILE).is_file() else None


def require_active_model_dir(settings: Settings, kind: ModelKind = "relation") -> Path:
    """Like active_model_dir, but NoActiveModelError (a clear message) instead of None."""
    folder = active_model_dir(settings, kind)
    if folder is None:
        raise NoActiveModelError(kind)
    return folder

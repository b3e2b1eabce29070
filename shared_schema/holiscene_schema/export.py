"""Write the contract's JSON Schema files: `python -m holiscene_schema.export [--check]`.

The TypeScript types are generated from these files by `npm run -w shared_schema generate`.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from pydantic import BaseModel, TypeAdapter
from pydantic.json_schema import models_json_schema

from .api import (
    FEW_HELDOUT_ITEMS,
    Conflict,
    CurrentUser,
    Dashboard,
    DepthKey,
    DepthPoints,
    DetectorInfo,
    EditRequest,
    ErrorMessage,
    ImportJob,
    ImportResult,
    Job,
    LoginRequest,
    LoginResult,
    MaskRefineRequest,
    MaskRefineResult,
    ModelEvent,
    ModelInfo,
    NewUser,
    PasswordChange,
    PasswordReset,
    PromoteRequest,
    RejectRequest,
    RetrainReadiness,
    RetrainRequest,
    ReviewRequest,
    RevisionInfo,
    RoleChange,
    SceneArchiveRequest,
    SceneDocument,
    SceneSummary,
    SceneWorkflow,
    SecondAnnotationRequest,
    SubmitRequest,
    UserInfo,
    ViewerInfo,
)
from .class_words import (
    GENERIC_HEADS,
    IRREGULAR_PLURALS,
    LONGEST_TYPO,
    PREPOSITIONS,
    SHORTEST_TYPO,
)
from .classes import CLASS_ALIASES, NYU40_CLASSES
from .detector_model import detector_contract
from .relation_model import relation_model_contract
from .scene import Scene
from .support_geometry import support_geometry_contract
from .support_graph import STRUCTURAL_SUPPORT_TYPES, STRUCTURAL_SUPPORTERS

SCHEMA_DIR = Path(__file__).resolve().parent.parent / "jsonschema"

# One file per top-level message; each is self-contained (its own $defs).
TOP_LEVEL: dict[str, type[BaseModel]] = {
    "scene": Scene,
    "edit_request": EditRequest,
    "scene_document": SceneDocument,
    "scene_summary": SceneSummary,
    "import_result": ImportResult,
    "import_job": ImportJob,
    "revision_info": RevisionInfo,
    "job": Job,
    "error_message": ErrorMessage,
    "conflict": Conflict,
    "model_info": ModelInfo,
    "model_event": ModelEvent,
    "retrain_request": RetrainRequest,
    "retrain_readiness": RetrainReadiness,
    "promote_request": PromoteRequest,
    "current_user": CurrentUser,
    "login_request": LoginRequest,
    "login_result": LoginResult,
    "user_info": UserInfo,
    "new_user": NewUser,
    "role_change": RoleChange,
    "password_reset": PasswordReset,
    "password_change": PasswordChange,
    "scene_workflow": SceneWorkflow,
    "submit_request": SubmitRequest,
    "review_request": ReviewRequest,
    "reject_request": RejectRequest,
    "second_annotation_request": SecondAnnotationRequest,
    "dashboard": Dashboard,
    "mask_refine_request": MaskRefineRequest,
    "mask_refine_result": MaskRefineResult,
    "scene_archive_request": SceneArchiveRequest,
    "detector_info": DetectorInfo,
    "viewer_info": ViewerInfo,
    "depth_points": DepthPoints,
    "depth_key": DepthKey,
}


def render_schemas() -> dict[str, str]:
    """File name -> JSON text of every schema, as committed."""
    out: dict[str, str] = {}
    for name, model in TOP_LEVEL.items():
        schema = TypeAdapter(model).json_schema(by_alias=True, mode="serialization")
        out[f"{name}.schema.json"] = _dump(schema)
    # Every model in one file, for the TypeScript generator (one declaration per type).
    _, bundle = models_json_schema(
        [(model, "serialization") for model in TOP_LEVEL.values()],
        title="HoliScene contract",
        ref_template="#/$defs/{model}",
    )
    out["contract.schema.json"] = _dump(bundle)
    out["vocabulary.json"] = _dump(
        {
            "nyu40_classes": list(NYU40_CLASSES),
            "class_aliases": CLASS_ALIASES,
            "class_words": {  # class_words.py's word lists, for its TypeScript twin
                "generic_heads": list(GENERIC_HEADS),
                "prepositions": list(PREPOSITIONS),
                "irregular_plurals": IRREGULAR_PLURALS,
                "shortest_typo": SHORTEST_TYPO,
                "longest_typo": LONGEST_TYPO,
            },
            "structural_supporters": sorted(STRUCTURAL_SUPPORTERS),
            "structural_support_types": STRUCTURAL_SUPPORT_TYPES,
            "support_types": ["below", "behind"],
            "relation_model": relation_model_contract(),
            "support_geometry": support_geometry_contract(),
            "detector_model": detector_contract(),
            "retraining": {"few_heldout_items": FEW_HELDOUT_ITEMS},
        }
    )
    return out


def _dump(schema: dict[str, object]) -> str:
    return json.dumps(schema, indent=2, sort_keys=True) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--check", action="store_true", help="fail if committed files differ")
    args = parser.parse_args(argv)
    rendered = render_schemas()
    stale = [n for n, text in rendered.items() if _read(SCHEMA_DIR / n) != text]
    extra = sorted({p.name for p in SCHEMA_DIR.glob("*.json")} - set(rendered))
    if args.check:
        if stale or extra:
            print(f"stale JSON Schema files: {stale + extra}; run `make schema`", file=sys.stderr)
            return 1
        return 0
    SCHEMA_DIR.mkdir(parents=True, exist_ok=True)
    for name in stale:
        (SCHEMA_DIR / name).write_text(rendered[name])
    for name in extra:
        (SCHEMA_DIR / name).unlink()
    return 0


def _read(path: Path) -> str | None:
    return path.read_text() if path.exists() else None


if __name__ == "__main__":
    raise SystemExit(main())

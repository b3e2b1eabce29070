"""Convert the COCO PicoDet that the PyPI package `paddlelabel-ml` ships to ONNX, and check it.

    .venv/bin/python scripts/convert_picodet_detector.py [--photos DIR] [--out DIR]

Build time only, never at run time. In a scratch folder: pip downloads the package (its
PicoDet-S 416 LCNet inference model, trained on COCO, Apache-2.0) and installs PaddlePaddle and
paddle2onnx into a scratch venv; paddle2onnx converts the model; the converted graph is put
behind the detector contract (holiscene.learning.detector.picodet_contract). Paddle Inference
then runs the original model on the photos in --photos, fed exactly the tensor the ONNX model
resizes and normalises internally, and every detection at or above --min-score must match a row
of the ONNX model (same class, score and box within --tolerance, boxes as a fraction of the
input's size), and the other way round. Only then are model.onnx, metadata.json (classes,
provenance, the check's figures) and the package's licence written to --out.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

import numpy as np
import onnx
import onnxruntime as ort
from holiscene.learning.detector.picodet_contract import (
    PICODET_INPUT,
    PICODET_SIZE,
    input_model,
    wrap_picodet,
)
from holiscene.learning.detector.row_matching import row_difference
from holiscene.learning.detector.runtime import PICODET_DETECTOR_DIR
from holiscene_schema.detector_model import COCO_CLASSES, INPUT_NAME, INPUT_SIZE, OPSET, OUTPUT_NAME
from model_conversion import (
    contract_inputs,
    conversion_parser,
    photo_paths,
    sha256,
    write_detector_dir,
)

PACKAGE = "paddlelabel-ml"
PACKAGE_VERSION = "1.0.0"
MODEL_IN_PACKAGE = "paddlelabel_ml/model/PicoDet/ckpt"
LICENCE_IN_PACKAGE = f"paddlelabel_ml-{PACKAGE_VERSION}.dist-info/LICENSE"
REFERENCE_PACKAGES = ("paddlepaddle==3.3.1", "paddle2onnx==1.3.1")
REPO = Path(__file__).resolve().parent.parent
REFERENCE_SCRIPT = REPO / "scripts" / "paddle_reference.py"


def fetch_package(scratch: Path) -> tuple[Path, Path]:
    """The package's PicoDet folder and licence, unpacked from its wheel into scratch."""
    subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "download",
            "--quiet",
            "--no-deps",
            "--dest",
            str(scratch),
            f"{PACKAGE}=={PACKAGE_VERSION}",
        ],
        check=True,
    )
    wheel = next(scratch.glob("paddlelabel_ml-*.whl"))
    unpacked = scratch / "package"
    with zipfile.ZipFile(wheel) as archive:
        members = [
            n
            for n in archive.namelist()
            if n.startswith(MODEL_IN_PACKAGE) or n == LICENCE_IN_PACKAGE
        ]
        archive.extractall(unpacked, members)
    return unpacked / MODEL_IN_PACKAGE, unpacked / LICENCE_IN_PACKAGE


def reference_python(scratch: Path) -> Path:
    """A scratch venv with PaddlePaddle and paddle2onnx; its python."""
    venv = scratch / "paddle-venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    python = venv / "bin" / "python"
    subprocess.run(
        [
            str(python),
            "-m",
            "pip",
            "install",
            "--quiet",
            "--disable-pip-version-check",
            *REFERENCE_PACKAGES,
        ],
        check=True,
    )
    return python


def matched(
    ours: np.ndarray, theirs: np.ndarray, min_score: float, tolerance: float
) -> tuple[int, int, float, float]:
    """Rows of either side at or above min_score without a partner on the other (same class,
    score and box within tolerance, by row_matching.row_difference), and the largest score and
    box differences of partners. ours: x1, y1, x2, y2, score, class; theirs: class, score, x1,
    y1, x2, y2 (Paddle's order, in any order of rows)."""
    theirs = theirs[:, [2, 3, 4, 5, 1, 0]]
    unmatched = 0
    worst_score = worst_box = 0.0
    for first, second in ((ours, theirs), (theirs, ours)):
        # Rows just below the bar on one side may sit just above it on the other.
        for row in first[first[:, 4] >= min_score + tolerance]:
            differences = [row_difference(row, other) for other in second]
            best = int(np.argmin(differences)) if differences else -1
            if best < 0 or differences[best] > tolerance:
                unmatched += 1
                continue
            partner = second[best]
            worst_score = max(worst_score, float(abs(partner[4] - row[4])))
            worst_box = max(worst_box, float(np.abs(partner[:4] - row[:4]).max() / INPUT_SIZE))
    return unmatched, len(ours[ours[:, 4] >= min_score]), worst_score, worst_box


def check_against_paddle(
    model: onnx.ModelProto,
    python: Path,
    paddle_dir: Path,
    photos: list[Path],
    work: Path,
    min_score: float,
    tolerance: float,
) -> dict[str, float]:
    """The ONNX model's detections against Paddle Inference's on the same input."""
    work.mkdir()
    inner = ort.InferenceSession(
        input_model().SerializeToString(), providers=["CPUExecutionProvider"]
    )
    session = ort.InferenceSession(model.SerializeToString(), providers=["CPUExecutionProvider"])
    ours: dict[str, np.ndarray] = {}
    for name, tensor in contract_inputs(photos, "onnx"):
        np.save(work / f"{name}.input.npy", inner.run([PICODET_INPUT], {INPUT_NAME: tensor})[0])
        ours[name] = np.asarray(session.run([OUTPUT_NAME], {INPUT_NAME: tensor})[0]).reshape(-1, 6)
    print("running Paddle Inference for the reference detections ...")
    subprocess.run(
        [
            str(python),
            str(REFERENCE_SCRIPT),
            "run",
            str(paddle_dir),
            str(work),
            str(PICODET_SIZE / INPUT_SIZE),
        ],
        check=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    worst = {"unmatched": 0.0, "compared": 0.0, "score": 0.0, "box_of_input_size": 0.0}
    for name, rows in ours.items():
        theirs = np.load(work / f"{name}.paddle.npy").reshape(-1, 6)
        unmatched, compared, score, box = matched(rows, theirs, min_score, tolerance)
        worst["unmatched"] += unmatched
        worst["compared"] += compared
        worst["score"] = max(worst["score"], score)
        worst["box_of_input_size"] = max(worst["box_of_input_size"], box)
    return worst


def main(argv: list[str] | None = None) -> int:
    parser = conversion_parser(__doc__.split("\n\n")[0], PICODET_DETECTOR_DIR)
    parser.add_argument("--min-score", type=float, default=0.1, help="detections compared")
    args = parser.parse_args(argv)
    photos = photo_paths(args.photos)
    with tempfile.TemporaryDirectory(prefix="holiscene-picodet-") as scratch_name:
        scratch = Path(scratch_name)
        print(
            f"fetching {PACKAGE}=={PACKAGE_VERSION}, "
            f"installing {' and '.join(REFERENCE_PACKAGES)} ..."
        )
        paddle_dir, licence = fetch_package(scratch)
        python = reference_python(scratch)
        converted_file = scratch / "converted.onnx"
        subprocess.run(
            [
                str(python),
                str(REFERENCE_SCRIPT),
                "export",
                str(paddle_dir),
                str(converted_file),
                str(OPSET),
            ],
            check=True,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        model = wrap_picodet(
            onnx.load(converted_file),
            doc_string=(
                f"COCO PicoDet-S 416 (LCNet) from PyPI {PACKAGE}=={PACKAGE_VERSION} "
                f"{MODEL_IN_PACKAGE}, Apache-2.0; converted by scripts/convert_picodet_detector.py"
            ),
        )
        worst = check_against_paddle(
            model, python, paddle_dir, photos, scratch / "check", args.min_score, args.tolerance
        )
        print(
            f"{int(worst['compared'])} detections at score >= {args.min_score} "
            f"on {len(photos)} photos; without a partner within {args.tolerance}: "
            f"{int(worst['unmatched'])}; largest differences: score {worst['score']:.2e}, "
            f"box {worst['box_of_input_size']:.2e} of the input"
        )
        if worst["unmatched"] or not worst["compared"]:
            print("the ONNX model does not match Paddle Inference")
            return 1
        model_file = scratch / "model.onnx"
        onnx.save(model, model_file)
        metadata = {
            "name": "COCO PicoDet-S 416 (LCNet), converted",
            "label_space": "coco80",
            "classes": list(COCO_CLASSES),
            "provenance": {
                "package": f"PyPI {PACKAGE}=={PACKAGE_VERSION}",
                "files": {
                    f"{MODEL_IN_PACKAGE}/{name}": sha256(paddle_dir / name)
                    for name in ("model.pdmodel", "model.pdiparams", "infer_cfg.yml")
                },
                "licence": "Apache-2.0 (LICENSE beside this file, from the package)",
                "converter": "scripts/convert_picodet_detector.py",
                "conversion_tools": list(REFERENCE_PACKAGES),
            },
            "check": {
                "reference": f"Paddle Inference ({REFERENCE_PACKAGES[0]}), IR optimisation off",
                "photos": len(photos),
                "detections_compared": int(worst["compared"]),
                "min_score": args.min_score,
                "unmatched": int(worst["unmatched"]),
                "max_score_difference": worst["score"],
                "max_box_difference_of_input_size": worst["box_of_input_size"],
                "tolerance": args.tolerance,
            },
        }
        write_detector_dir(args.out, model_file, licence, metadata)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""Convert the COCO detector that `@vladmandic/human` ships to ONNX, and check it.

    .venv/bin/python scripts/convert_coco_detector.py [--photos DIR] [--out DIR]

Build time only, never at run time: npm fetches the package (and TensorFlow.js, for the
reference outputs) into a scratch folder; the graph model `models/centernet.json` (a
MobileNetV3 CenterNet trained on COCO) is converted by holiscene.learning.detector.tfjs_convert;
both models run on the photos in --photos, preprocessed as holiscene_schema.detector_model
says, and every score and box (as a fraction of the input's size) of the ONNX model must be within
--tolerance of TensorFlow.js's.
Only then are model.onnx, metadata.json (classes, provenance, the check's figures) and the
package's licence written to --out.
"""

from __future__ import annotations

import subprocess
import tarfile
import tempfile
from pathlib import Path

import numpy as np
import onnx
import onnxruntime as ort
from holiscene.learning.detector.runtime import COCO_DETECTOR_DIR
from holiscene.learning.detector.tfjs_convert import convert
from holiscene.learning.detector.tfjs_graph import load_graph_model
from holiscene_schema.detector_model import COCO_CLASSES, INPUT_NAME, INPUT_SIZE, OUTPUT_NAME
from model_conversion import (
    contract_inputs,
    conversion_parser,
    photo_paths,
    sha256,
    write_detector_dir,
)
from tqdm import tqdm

PACKAGE = "@vladmandic/human"
PACKAGE_VERSION = "3.3.6"
TFJS_VERSION = "4.22.0"
GRAPH_FILE = "models/centernet.json"
TF_OUTPUT = "tower_0/detections"
HEAD_OUTPUTS = ("tower_0/keypoints", "tower_0/wh")  # where the graph's NCHW part ends
REPO = Path(__file__).resolve().parent.parent
REFERENCE_SCRIPT = REPO / "scripts" / "tfjs_reference.mjs"


def fetch_package(scratch: Path) -> Path:
    """The npm package unpacked into scratch/package; TensorFlow.js installed beside it."""
    subprocess.run(
        ["npm", "pack", f"{PACKAGE}@{PACKAGE_VERSION}", "--silent"],
        cwd=scratch,
        check=True,
        stdout=subprocess.DEVNULL,
    )
    tarball = next(scratch.glob("*.tgz"))
    with tarfile.open(tarball) as archive:
        archive.extractall(scratch, filter="data")
    (scratch / "package.json").write_text('{"private": true}\n')
    subprocess.run(
        ["npm", "install", "--no-audit", "--no-fund", f"@tensorflow/tfjs@{TFJS_VERSION}"],
        cwd=scratch,
        check=True,
        stdout=subprocess.DEVNULL,
    )
    return scratch / "package"


def check_against_tfjs(
    model_file: Path, graph_file: Path, photos: list[Path], work: Path
) -> dict[str, float]:
    """Largest differences of scores and box coordinates between ONNX and TensorFlow.js."""
    work.mkdir()
    inputs: dict[str, np.ndarray] = {}
    for name, tensor in contract_inputs(photos, "preprocess"):
        inputs[name] = tensor
        (work / f"{name}.input.f32").write_bytes(tensor.astype("<f4").tobytes())
    print("running TensorFlow.js (CPU backend) for the reference outputs ...")
    subprocess.run(
        ["node", str(REFERENCE_SCRIPT), str(graph_file), str(work), TF_OUTPUT],
        check=True,
        stdout=subprocess.DEVNULL,
    )
    session = ort.InferenceSession(str(model_file), providers=["CPUExecutionProvider"])
    worst = {"score": 0.0, "box_px": 0.0, "class_mismatches": 0.0}
    for name, tensor in tqdm(inputs.items(), desc="compare", unit="photo"):
        ours = np.asarray(session.run([OUTPUT_NAME], {INPUT_NAME: tensor})[0]).reshape(-1, 6)
        reference_file = work / f"{name}.{TF_OUTPUT.replace('/', '_')}.f32"
        reference = np.frombuffer(reference_file.read_bytes(), "<f4").reshape(-1, 6)
        worst["score"] = max(worst["score"], float(np.abs(ours[:, 4] - reference[:, 4]).max()))
        worst["box_px"] = max(worst["box_px"], float(np.abs(ours[:, :4] - reference[:, :4]).max()))
        worst["class_mismatches"] += float((ours[:, 5] != reference[:, 5]).sum())
    return worst


def main(argv: list[str] | None = None) -> int:
    parser = conversion_parser(__doc__.split("\n\n")[0], COCO_DETECTOR_DIR)
    args = parser.parse_args(argv)
    photos = photo_paths(args.photos)
    with tempfile.TemporaryDirectory(prefix="holiscene-detector-") as scratch_name:
        scratch = Path(scratch_name)
        print(f"fetching {PACKAGE}@{PACKAGE_VERSION} and TensorFlow.js {TFJS_VERSION} ...")
        package = fetch_package(scratch)
        graph_file = package / GRAPH_FILE
        model_json, weights = load_graph_model(graph_file)
        model = convert(
            model_json,
            weights,
            {TF_OUTPUT: OUTPUT_NAME},
            nhwc_outputs=HEAD_OUTPUTS,
            input_name=INPUT_NAME,
        )
        model.doc_string = (
            f"COCO CenterNet (MobileNetV3) from npm {PACKAGE}@{PACKAGE_VERSION} {GRAPH_FILE}, "
            "MIT licence; converted by scripts/convert_coco_detector.py"
        )
        model_file = scratch / "model.onnx"
        onnx.save(model, model_file)
        worst = check_against_tfjs(model_file, graph_file, photos, scratch / "check")
        print(
            f"largest difference over {len(photos)} photos: score {worst['score']:.2e}, "
            f"box {worst['box_px']:.2e} px ({worst['box_px'] / INPUT_SIZE:.2e} of the input), "
            f"classes differing {int(worst['class_mismatches'])}"
        )
        # Boxes are compared as a fraction of the input's size, as scores are in [0, 1].
        box_fraction = worst["box_px"] / INPUT_SIZE
        if max(worst["score"], box_fraction) > args.tolerance or worst["class_mismatches"]:
            print(f"the ONNX model differs from TensorFlow.js by more than {args.tolerance}")
            return 1
        weights_file = graph_file.with_suffix(".bin")
        metadata = {
            "name": "COCO CenterNet (MobileNetV3), converted",
            "label_space": "coco80",
            "classes": list(COCO_CLASSES),
            "provenance": {
                "package": f"npm {PACKAGE}@{PACKAGE_VERSION}",
                "files": {
                    GRAPH_FILE: sha256(graph_file),
                    f"models/{weights_file.name}": sha256(weights_file),
                },
                "generated_by": model_json.get("generatedBy"),
                "converted_by": model_json.get("convertedBy"),
                "licence": "MIT (LICENSE beside this file, from the package)",
                "converter": "scripts/convert_coco_detector.py",
            },
            "check": {
                "reference": f"TensorFlow.js {TFJS_VERSION}, CPU backend",
                "photos": len(photos),
                "max_score_difference": worst["score"],
                "max_box_difference_px": worst["box_px"],
                "max_box_difference_of_input_size": worst["box_px"] / INPUT_SIZE,
                "tolerance": args.tolerance,
            },
        }
        write_detector_dir(args.out, model_file, package / "LICENSE", metadata)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

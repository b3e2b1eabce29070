"""The Paddle side of scripts/convert_picodet_detector.py, run in its scratch venv (paddlepaddle,
paddle2onnx), never by the product.

    python paddle_reference.py export MODEL_DIR OUT.onnx OPSET
    python paddle_reference.py run MODEL_DIR WORK_DIR SCALE

`export`: paddle2onnx converts the inference model (model.pdmodel + model.pdiparams).
`run`: Paddle Inference runs the same model on every WORK_DIR/*.input.npy (the normalised
[1, 3, 416, 416] input) with scale_factor SCALE, and writes its detections beside each,
*.paddle.npy: rows of class, score, x1, y1, x2, y2.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np


def export(model_dir: Path, out: Path, opset: int) -> None:
    import paddle2onnx

    paddle2onnx.export(
        str(model_dir / "model.pdmodel"),
        str(model_dir / "model.pdiparams"),
        save_file=str(out),
        opset_version=opset,
        auto_upgrade_opset=False,
        verbose=False,
    )


def run(model_dir: Path, work: Path, scale: float) -> None:
    import paddle.inference as paddle_inference

    config = paddle_inference.Config(
        str(model_dir / "model.pdmodel"), str(model_dir / "model.pdiparams")
    )
    config.disable_gpu()
    config.switch_ir_optim(False)  # the reference: the graph as it is, not a fused one
    config.disable_glog_info()
    predictor = paddle_inference.create_predictor(config)
    for path in sorted(work.glob("*.input.npy")):
        predictor.get_input_handle("image").copy_from_cpu(np.load(path))
        predictor.get_input_handle("scale_factor").copy_from_cpu(np.full((1, 2), scale, np.float32))
        predictor.run()
        detections = predictor.get_output_handle(predictor.get_output_names()[0]).copy_to_cpu()
        np.save(path.with_name(path.name.replace(".input.npy", ".paddle.npy")), detections)


def main(argv: list[str]) -> int:
    if len(argv) == 4 and argv[0] == "export":
        export(Path(argv[1]), Path(argv[2]), int(argv[3]))
    elif len(argv) == 4 and argv[0] == "run":
        run(Path(argv[1]), Path(argv[2]), float(argv[3]))
    else:
        print(__doc__, file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))

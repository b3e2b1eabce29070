"""`holiscene train-detector` refuses settings it cannot train with before rendering or
writing anything."""

from __future__ import annotations

from pathlib import Path

import pytest
from holiscene.cli import main


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--retexture", "1.5"], "--retexture must be between 0 and 1"),
        (["--retexture", "-0.1"], "--retexture must be between 0 and 1"),
        (["--coco-weight", "2"], "--coco-weight must be between 0 and 1"),
        (["--views", "0"], "must be at least 1"),
        # PicoDet's class head has none of the CenterNet head's options.
        (["--on-picodet"], "--on-picodet trains PicoDet's class head; drop --tune-deep-blocks"),
        (
            ["--on-picodet", "--cushion-rows"],
            "drop --tune-deep-blocks, --cushion-rows",
        ),
        (["--branch-learning-rate", "0.5"], "--branch-learning-rate is for --on-picodet"),
        (["--unnamed", "books"], "--unnamed is for --on-picodet"),
    ],
)
def test_bad_settings_are_refused_and_nothing_is_written(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], extra: list[str], message: str
) -> None:
    out, cache = tmp_path / "model", tmp_path / "rooms"
    argv = ["train-detector", "-o", str(out), "--cache", str(cache), "--tune-deep-blocks", *extra]
    status = main(argv)
    assert status != 0
    assert message in capsys.readouterr().err
    assert not out.exists() and not cache.exists()


def test_a_model_is_named_after_its_recipe() -> None:
    """The models page and the benchmark tell models apart by this name."""
    from holiscene.learning.detector.train import DetectorTrainConfig, model_name

    plain = model_name(DetectorTrainConfig())
    assert plain == "NYU-40 detector (COCO backbone, head fine-tuned on synthetic rooms)"
    full = model_name(DetectorTrainConfig(tune_deep_blocks=True, cushion_rows=True, retexture=0.5))
    assert "a copy of its stride-32 blocks" in full
    assert full.endswith("synthetic rooms with rows of cushions and repainted surfaces)")
    assert model_name(DetectorTrainConfig(retexture=0.5)).endswith("with repainted surfaces)")


def test_an_unknown_unnamed_class_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out, cache = tmp_path / "model", tmp_path / "rooms"
    argv = ["train-detector", "-o", str(out), "--cache", str(cache), "--on-picodet"]
    assert main([*argv, "--unnamed", "books", "--unnamed", "bookz"]) != 0
    assert "--unnamed: not NYU-40 classes: bookz" in capsys.readouterr().err
    assert not out.exists() and not cache.exists()

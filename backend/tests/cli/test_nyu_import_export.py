"""`holiscene import` of NYU Depth v2's labelled .mat with its support labels, and `holiscene
export --format nyu-supports`: what goes out comes back in (classes, boxes within 1 px, masks,
supports), and a bad image is refused alone with nothing of it stored."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from holiscene.cli import main
from holiscene.cli.export import scene_store
from holiscene.core.settings import Settings
from holiscene.segmentation.rle import decode_mask
from holiscene_schema import Scene

from ..inputs.datasets.files import labelme_file, shape
from ..inputs.datasets.nyu_files import bedroom, nyu_folder


def _stored(data_dir: Path) -> list[Scene]:
    with scene_store(Settings(data_dir=data_dir)) as scenes:
        return sorted(
            (scenes.document(s.id).scene for s in scenes.list_summaries()), key=lambda s: s.name
        )


def _labelled_supports(scene: Scene) -> set[tuple[str, tuple[float, ...], str, str]]:
    """Each support as (child's class, child's box, parent, type), the parent an object's
    class and box or a structural name: comparable across imports, whose ids may differ."""
    by_id = {o.id: o for o in scene.objects}

    def named(object_id: str) -> str:
        obj = by_id.get(object_id)
        return object_id if obj is None else f"{obj.cls} {[round(v) for v in obj.bbox]}"

    return {
        (by_id[s.child].cls, tuple(round(v) for v in by_id[s.child].bbox), named(s.parent), s.type)
        for s in scene.supports
    }


def _import(path: Path, data_dir: Path) -> int:
    return main(["import", str(path), "--data-dir", str(data_dir)])


def test_nyu_scenes_round_trip_through_nyu_supports(tmp_path: Path) -> None:
    nyu_folder(tmp_path / "nyu", [bedroom(0), bedroom(1)])
    assert _import(tmp_path / "nyu", tmp_path / "a") == 0
    first = _stored(tmp_path / "a")
    assert [s.name for s in first] == ["0001_bedroom_0000", "0002_bedroom_0001"]
    labelled = [(s.child, s.parent, s.type) for s in first[0].supports if s.source == "manual"]
    assert labelled == [
        ("o0", "floor", "below"),
        ("o1", "wall", "behind"),
        ("o2", "o0", "below"),
        ("o3", "o0", "below"),
        ("o4", "floor", "below"),
    ]  # the pipeline kept the labels and gave the rest (the picture) a supporter

    out = tmp_path / "export"
    code = main(
        ["export", "--format", "nyu-supports", "-o", str(out), "--data-dir", str(tmp_path / "a")]
    )
    assert code == 0
    assert sorted(p.name for p in out.iterdir()) == [
        "nyu_depth_v2_labeled.mat",
        "support_labels.mat",
    ]
    assert _import(out, tmp_path / "b") == 0
    # Exported newest first; each comes back under its NYU scene name.
    second = sorted(_stored(tmp_path / "b"), key=lambda s: s.name[5:])
    assert [s.name[5:] for s in second] == ["bedroom_0000", "bedroom_0001"]
    for before, after in zip(first, second, strict=True):
        assert [o.cls for o in after.objects] == [o.cls for o in before.objects]
        assert [o.source_class for o in after.objects] == [o.source_class for o in before.objects]
        width, height = before.image.width, before.image.height
        for a, b in zip(after.objects, before.objects, strict=True):
            assert np.allclose(a.bbox, b.bbox, atol=1.0)
            assert a.mask is not None and b.mask is not None
            assert np.array_equal(
                decode_mask(a.mask, width, height), decode_mask(b.mask, width, height)
            )
        # The picture has 9 pixels: the toolbox gives it no number, so its support stays out.
        expected = {s for s in _labelled_supports(before) if s[0] != "picture"}
        assert {s for s in _labelled_supports(after) if s[0] != "picture"} == expected
        assert {s.source for s in after.supports if s.child != "o5"} == {"manual"}


def test_a_bad_image_is_reported_and_the_others_imported(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    bad = bedroom(1)
    bad.supports = [(9, 0, 1)]
    labelled = nyu_folder(tmp_path / "nyu", [bedroom(0), bad, bedroom(2)])
    assert _import(labelled, tmp_path / "data") == 1
    out, err = capsys.readouterr()
    assert f"error: {labelled}/0002_bedroom_0001: support row 1 names object 9" in err
    assert "0001_bedroom_0000: scene" in out and "0003_bedroom_0002: scene" in out
    assert [s.name for s in _stored(tmp_path / "data")] == [
        "0001_bedroom_0000",
        "0003_bedroom_0002",
    ]
    assert len(list((tmp_path / "data").rglob("img.png"))) == 2  # nothing of the bad one
    # Imported again, nothing is added: the rest of an interrupted import would be.
    assert _import(labelled, tmp_path / "data") == 1
    assert len(_stored(tmp_path / "data")) == 2


def test_scenes_of_two_sizes_are_refused_before_anything_is_written(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    data = tmp_path / "data"
    assert _import(nyu_folder(tmp_path / "nyu", [bedroom()]), data) == 0
    room = labelme_file(tmp_path / "room.json", [shape("bed", [[5, 5], [40, 5], [40, 40]])])
    assert _import(room, data) == 0
    out = tmp_path / "export"
    code = main(["export", "--format", "nyu-supports", "-o", str(out), "--data-dir", str(data)])
    assert code == 2
    assert "the scenes must share one size; they have 64x48, 96x64" in capsys.readouterr().err
    assert not any(out.iterdir())


def test_import_prints_the_support_rows_it_left_out_and_every_run_says_so(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    image = bedroom()
    image.supports = [(5, 3, 3), *image.supports]
    nyu_folder(tmp_path / "nyu", [image])
    assert main(["import", str(tmp_path / "nyu"), "--data-dir", str(tmp_path / "a")]) == 0
    lines = capsys.readouterr().out.splitlines()
    imported = next(i for i, line in enumerate(lines) if line.endswith("pipeline succeeded"))
    note = "support row 1 left out: type 3 is neither 1 (below) nor 2 (behind)"
    assert lines[imported + 1] == f"    note: {note}"
    (scene,) = _stored(tmp_path / "a")  # the pipeline's revision
    assert ("o2", "o0", "below") in {(s.child, s.parent, s.type) for s in scene.supports}
    (stage,) = [s for s in scene.stages if s.name == "import"]
    assert stage.warning and stage.note == note

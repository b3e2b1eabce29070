"""NYU Depth v2's labelled .mat and support labels: objects per (label, instance) with their
masks and classes, the room's regions as structure, supports over the toolbox's region
numbers, the camera, and bad files or rows refused item by item."""

from __future__ import annotations

from pathlib import Path

import h5py
import numpy as np
import pytest
from holiscene.export.matfile import MatCell, MatValue, mat_file
from holiscene.inputs.datasets import DatasetItem, dataset_items, is_dataset
from holiscene.inputs.datasets.matlab import read_cell_of_matrices
from holiscene.inputs.datasets.nyu import NYU_FX, nyu_files, nyu_regions
from holiscene.segmentation.rle import decode_mask
from holiscene.services.reconstruction import imported_scene

from .nyu_files import (
    HEIGHT,
    NAMES,
    WIDTH,
    bedroom,
    nyu_folder,
    write_labelled,
    write_support_labels,
)


def _read(path: Path) -> list[DatasetItem]:
    return list(dataset_items(path))


def test_objects_masks_classes_and_supports(tmp_path: Path) -> None:
    image = bedroom()
    labelled = nyu_folder(tmp_path, [image])
    assert is_dataset(labelled) and is_dataset(tmp_path)
    (item,) = _read(tmp_path)
    assert item.error is None and item.inputs is not None
    assert item.name.endswith("/0001_bedroom_0000")
    inputs = item.inputs
    detections = inputs.detections or []
    # Wall and floor are the room, not objects; the teapot is no known name.
    assert [d.cls for d in detections] == [
        "bed",
        "lamp",
        "pillow",
        "pillow",
        "otherprop",
        "picture",
    ]
    assert detections[4].source_class == "teapot" and not detections[4].class_known
    assert detections[0].bbox == (5.0, 20.0, 41.0, 36.0)
    pillow = decode_mask(detections[2].mask, WIDTH, HEIGHT) if detections[2].mask else None
    assert pillow is not None and pillow.sum() == 6 * 9
    assert np.array_equal(pillow, (image.labels == 5) & (image.instances == 1))
    bed = decode_mask(detections[0].mask, WIDTH, HEIGHT) if detections[0].mask else None
    assert bed is not None and not bed[22:28, 8:17].any()  # the pillows' pixels are theirs
    relations = [(s.child, s.parent, s.type) for s in inputs.supports]
    assert relations == [
        ("o0", "floor", "below"),
        ("o1", "wall", "behind"),
        ("o2", "o0", "below"),
        ("o3", "o0", "below"),
        ("o4", "floor", "below"),
    ]  # the wall's own row (region 1 on the floor) is no object's
    assert {(s.source, s.author) for s in inputs.supports} == {("manual", "NYU Depth v2")}
    assert inputs.K is not None and inputs.K[0, 0] == pytest.approx(NYU_FX * WIDTH / 640)
    truth = inputs.ground_truth
    assert truth is not None and truth.camera is not None
    assert inputs.K.tolist() == truth.camera.K and truth.camera.K_source == "given"
    assert list(truth.supports) == list(inputs.supports)
    assert [o.id for o in truth.objects] == [f"o{i}" for i in range(6)]


def test_regions_are_numbered_as_the_toolbox_numbers_them() -> None:
    image = bedroom()
    regions = nyu_regions(image.labels, image.instances)
    assert [(r.label, r.instance, r.number) for r in regions] == [
        (1, 1, 1), (2, 1, 2), (3, 1, 3), (4, 1, 4), (5, 1, 5), (5, 2, 6), (6, 1, 7),
        (7, 1, None),  # 9 pixels: under the toolbox's 10, it gets no number
    ]  # fmt: skip
    # A small region before the others shifts nothing: numbers count only the kept ones.
    labels = image.labels.copy()
    labels[0, 0] = 8  # one pixel of label 8 (sorted last) and one of a new pillow
    labels[47, 63], instances = 5, image.instances.copy()
    instances[47, 63] = 3
    numbers = [r.number for r in nyu_regions(labels, instances)]
    assert numbers == [1, 2, 3, 4, 5, 6, None, 7, None, None]


def test_without_a_support_file_the_photos_import_without_supports(tmp_path: Path) -> None:
    labelled = write_labelled(tmp_path / "labelled.mat", [bedroom(0), bedroom(1)])
    items = _read(labelled)
    assert [i.name.rsplit("/", 1)[1] for i in items] == ["0001_bedroom_0000", "0002_bedroom_0001"]
    for item in items:
        assert item.inputs is not None and item.inputs.supports == ()
        assert item.inputs.ground_truth is not None


def test_a_support_row_naming_a_missing_object_refuses_that_image_only(tmp_path: Path) -> None:
    good, bad = bedroom(0), bedroom(1)
    bad.supports = [*bad.supports, (42, 0, 1)]
    nyu_folder(tmp_path, [good, bad])
    items = _read(tmp_path)
    assert items[0].inputs is not None and items[0].error is None
    assert items[0].inputs.notes == ()
    assert items[1].inputs is None
    assert items[1].error == (
        "support row 7 names object 42, which is not there (the image has 7 numbered regions)"
    )


def test_rows_of_another_type_and_second_supporters_are_left_out_with_a_note(
    tmp_path: Path,
) -> None:
    image = bedroom()
    # Row 1: a pillow "hanging" (the labelling tool's third type). Rows 2-4: the other pillow
    # behind the lamp and (twice) on the bed. Rows 5-6: the bed on the floor, then on the
    # floor's own region: the same support.
    image.supports = [(5, 3, 3), (6, 4, 2), (6, 3, 1), (6, 3, 1), (3, 0, 1), (3, 2, 1)]
    nyu_folder(tmp_path, [image])
    (item,) = _read(tmp_path)
    assert item.inputs is not None and item.error is None
    relations = [(s.child, s.parent, s.type) for s in item.inputs.supports]
    assert relations == [("o3", "o0", "below"), ("o0", "floor", "below")]
    assert item.inputs.notes == (
        "support row 1 left out: type 3 is neither 1 (below) nor 2 (behind)",
        "object o3 has more than one supporter: row 3 kept, row(s) 2 left out",
    )
    # Revision 1 shows them with the pipeline's warnings.
    scene = imported_scene(item.inputs, "bedroom")
    (stage,) = scene.stages
    assert stage.name == "import" and stage.warning and stage.note is not None
    assert all(note in stage.note for note in item.inputs.notes)
    assert "teapot" in stage.note  # beside the unknown class name's note


def test_a_support_cycle_refuses_that_image(tmp_path: Path) -> None:
    image = bedroom()
    image.supports = [(3, 5, 1), (5, 3, 1)]  # the bed on a pillow on the bed
    nyu_folder(tmp_path, [image])
    (item,) = _read(tmp_path)
    assert item.error is not None and "support cycle" in item.error


def test_a_truncated_file_is_one_error(tmp_path: Path) -> None:
    labelled = nyu_folder(tmp_path, [bedroom()])
    data = labelled.read_bytes()
    labelled.write_bytes(data[: len(data) // 2])
    (item,) = _read(labelled)
    assert item.inputs is None and item.error is not None
    assert "nyu_depth_v2_labeled.mat is not a readable MATLAB v7.3 (HDF5) file" in item.error


def test_an_image_whose_data_is_damaged_is_refused_alone(tmp_path: Path) -> None:
    labelled = write_labelled(
        tmp_path / "nyu.mat", [bedroom(0), bedroom(1), bedroom(2)], chunked=True
    )
    with h5py.File(labelled, "r") as file:
        chunk = file["labels"].id.get_chunk_info(1)  # image 2's labels, compressed
    with labelled.open("r+b") as raw:
        raw.seek(chunk.byte_offset)
        raw.write(b"\0" * chunk.size)
    items = _read(labelled)
    assert [item.inputs is not None for item in items] == [True, False, True]
    assert (items[1].error or "").startswith(
        "image 2's arrays cannot be read (corrupt or truncated)"
    )


def test_a_names_reference_that_points_nowhere_is_the_files_error(tmp_path: Path) -> None:
    labelled = nyu_folder(tmp_path, [bedroom()])
    with h5py.File(labelled, "r+") as file:
        file["names"][0, 3] = h5py.Reference()  # "lamp" missing: a null reference
    (item,) = _read(labelled)
    assert item.inputs is None
    assert item.error == "names entry 4: a reference points nowhere (a null reference)"


def test_a_support_file_for_other_images_is_refused(tmp_path: Path) -> None:
    nyu_folder(tmp_path, [bedroom()])
    write_support_labels(tmp_path / "support_labels.mat", [[], []])
    (item,) = _read(tmp_path)
    assert item.error == "support_labels.mat has support labels of 2 images, not 1"
    (tmp_path / "support_labels.mat").write_bytes(b"MATLAB 5.0 MAT-file" + b"\0" * 20)
    (item,) = _read(tmp_path)
    assert item.error == "support_labels.mat is not a MATLAB .mat file (level 5 or v7.3)"


def test_level_5_cells_the_export_writes_read_back(tmp_path: Path) -> None:
    rows = [np.array([[3.0, 0, 1], [4, 1, 2]]), np.zeros((0, 3)), np.array([[1.0, -1, 1]])]
    path = tmp_path / "support_labels.mat"
    path.write_bytes(mat_file({"other": np.ones((2, 2)), "supportLabels": MatCell(rows, True)}))
    read = read_cell_of_matrices(path, "supportLabels")
    assert [r.shape for r in read] == [(2, 3), (0, 3), (1, 3)]
    assert all(np.array_equal(a, b) for a, b in zip(read, rows, strict=True))


def test_level_5_files_beside_the_labelled_file_are_not_images(tmp_path: Path) -> None:
    nyu_folder(tmp_path, [bedroom()])
    write_support_labels(tmp_path / "splits.mat", [[(1, 2, 3)]])  # NYU's splits.mat is level 5
    (item,) = _read(tmp_path)
    assert item.inputs is not None and len(item.inputs.supports) == 5


def test_support_labels_saved_as_v7_3_read_too(tmp_path: Path) -> None:
    image = bedroom()
    labelled = write_labelled(tmp_path / "nyu_depth_v2_labeled.mat", [image])
    with h5py.File(tmp_path / "support_labels.mat", "w") as file:
        rows = file.create_dataset("#refs#/a", data=np.array(image.supports, dtype=float).T)
        cell = file.create_dataset("supportLabels", (1, 1), dtype=h5py.ref_dtype)
        cell[0, 0] = rows.ref
    (item,) = _read(labelled)
    assert item.inputs is not None
    assert [(s.child, s.parent) for s in item.inputs.supports][:2] == [
        ("o0", "floor"),
        ("o1", "wall"),
    ]


def test_the_depths_come_in_metres_registered_to_the_photo(tmp_path: Path) -> None:
    image = bedroom()
    (item,) = _read(nyu_folder(tmp_path, [image]))
    assert item.inputs is not None and item.inputs.depth is not None
    assert image.depth is not None
    assert np.array_equal(item.inputs.depth.metres, image.depth)


def test_a_file_without_depths_imports_without_depth(tmp_path: Path) -> None:
    labelled = nyu_folder(tmp_path, [bedroom()])
    with h5py.File(labelled, "r+") as file:
        del file["depths"]
    (item,) = _read(labelled)
    assert item.inputs is not None and item.inputs.depth is None


def test_an_image_without_usable_depth_is_refused_alone(tmp_path: Path) -> None:
    images = [bedroom(0), bedroom(1), bedroom(2)]
    images[1].depth = np.full((HEIGHT, WIDTH), np.nan, np.float32)
    holes = images[2].depth
    assert holes is not None
    holes[:10] = np.nan  # NaN pixels are pixels without depth
    items = _read(write_labelled(tmp_path / "nyu.mat", images))
    assert [item.inputs is not None for item in items] == [True, False, True]
    assert items[1].error == (
        "image 2's depth map holds no depth (every pixel is 0, NaN or out of range)"
    )
    depth = items[2].inputs.depth if items[2].inputs else None
    assert depth is not None and (depth.metres[:10] == 0).all() and depth.metres[10:].all()


def test_depths_of_another_size_are_the_files_error(tmp_path: Path) -> None:
    labelled = nyu_folder(tmp_path, [bedroom()])
    with h5py.File(labelled, "r+") as file:
        del file["depths"]
        file.create_dataset("depths", data=np.ones((1, WIDTH // 2, HEIGHT), np.float32))
    (item,) = _read(labelled)
    assert item.inputs is None and item.error is not None
    assert item.error.startswith("depths is (1, 32, 48), images (1, 3, 64, 48): they differ")


def _class_mapping(folder: Path, numbers: list[int], names: tuple[str, ...] | None = None) -> None:
    # NAMES: wall, floor, bed, lamp, pillow, teapot, picture. NYU's own file also holds the
    # names it maps (allClassName, a cell of text) and the 40 classes (className), before
    # mapClass.
    mapping: dict[str, MatValue] = {}
    if names is not None:
        mapping["allClassName"] = MatCell(list(names))
        mapping["className"] = MatCell(["wall", "floor", "cabinet"])
    mapping["mapClass"] = np.array([numbers], dtype=np.float64)
    (folder / "classMapping40.mat").write_bytes(mat_file(mapping))


def test_nyus_own_class_mapping_beside_the_file_decides_the_classes(tmp_path: Path) -> None:
    labelled = nyu_folder(tmp_path, [bedroom()])
    # The lamp mapped to otherfurniture (39) shows the file, not the vocabulary, decided.
    _class_mapping(tmp_path, [1, 2, 4, 39, 18, 40, 11])
    assert [p.name for p in nyu_files(tmp_path)] == [labelled.name]  # not an image file
    (item,) = _read(labelled)
    detections = item.inputs.detections or [] if item.inputs else []
    assert [d.cls for d in detections] == [
        "bed",
        "otherfurniture",
        "pillow",
        "pillow",
        "otherprop",
        "picture",
    ]
    teapot = detections[4]
    assert teapot.source_class == "teapot" and teapot.class_known  # mapped, no warning

    (tmp_path / "class_map.json").write_text('{"lamp": "lamp"}')  # the user's map wins
    (item,) = _read(labelled)
    assert item.inputs is not None and (item.inputs.detections or [])[1].cls == "lamp"


def test_a_class_mapping_that_names_its_classes_is_read_and_checked_against_the_names(
    tmp_path: Path,
) -> None:
    labelled = nyu_folder(tmp_path, [bedroom()])
    _class_mapping(tmp_path, [1, 2, 4, 39, 18, 40, 11], names=NAMES)
    (item,) = _read(labelled)
    assert item.inputs is not None, item.error
    assert [d.cls for d in item.inputs.detections or []][1] == "otherfurniture"
    other = ("wall", "floor", "bed", "lamp", "cushion", "teapot", "picture")
    _class_mapping(tmp_path, [1, 2, 4, 39, 18, 40, 11], names=other)
    (item,) = _read(labelled)
    assert item.inputs is None and item.error is not None
    assert "is for other names: its name 5 is 'cushion', the labelled file's 'pillow'" in item.error


@pytest.mark.parametrize(
    ("numbers", "message"),
    [([1, 2, 4], "maps 3 names, the labelled file has 7"), ([1, 2, 4, 35, 18, 41, 11], "1-40")],
)
def test_a_class_mapping_that_does_not_fit_is_the_imports_error(
    tmp_path: Path, numbers: list[int], message: str
) -> None:
    labelled = nyu_folder(tmp_path, [bedroom()])
    _class_mapping(tmp_path, numbers)
    (item,) = _read(labelled)
    assert item.inputs is None and item.error is not None and message in item.error

"""How the class vocabulary agrees with the datasets' own NYU-40 mappings of their names.

    python benchmarks/bench_class_mappings.py [--nyu-mapping classMapping40.mat]
        [--scannet-labels scannetv2-labels.combined.tsv]

--nyu-mapping: NYU Depth v2's classMapping40.mat (Gupta et al.: `allClassName`, the 894
names, and `mapClass`, the NYU-40 number of each). --scannet-labels: ScanNet's label table
(`raw_category`, `nyu40id`, `count` columns). Neither ships with HoliScene: give the files
you have. Each name is mapped as an import maps it (holiscene_schema.map_class_name, no class
map); "agree" counts the names given the dataset's class, "unknown" those that fall back to
otherprop as unknown (the import warns), split by whether the dataset says otherprop too.
"""

from __future__ import annotations

import argparse
import csv
from collections import Counter
from collections.abc import Iterable
from pathlib import Path

from holiscene.inputs.datasets.matlab import read_numeric_matrix, read_strings
from holiscene_schema import NYU40_CLASSES, map_class_name


def outcome(name: str, theirs: str) -> str:
    mapped = map_class_name(name)
    if not mapped.known:
        return "unknown, they say otherprop" if theirs == "otherprop" else "unknown, they differ"
    return "agree" if mapped.cls == theirs else "differ"


def report(title: str, rows: Iterable[tuple[str, str, int]]) -> None:
    """rows: (name, the dataset's class, instances of the name)."""
    names: Counter[str] = Counter()
    instances: Counter[str] = Counter()
    for name, theirs, count in rows:
        kind = outcome(name, theirs)
        names[kind] += 1
        instances[kind] += count
    total, weight = sum(names.values()), sum(instances.values())
    print(f"{title}: {total} names, {weight} instances")
    for kind in ("agree", "unknown, they say otherprop", "differ", "unknown, they differ"):
        print(
            f"  {kind:28s} {names[kind]:5d} names ({names[kind] / total:6.1%})"
            f"  {instances[kind]:7d} instances ({instances[kind] / weight:6.1%})"
        )


def nyu_rows(path: Path) -> list[tuple[str, str, int]]:
    names = read_strings(path, "allClassName")
    numbers = read_numeric_matrix(path, "mapClass").ravel(order="F")
    return [(n, NYU40_CLASSES[int(k) - 1], 1) for n, k in zip(names, numbers, strict=True)]


def scannet_rows(path: Path) -> list[tuple[str, str, int]]:
    with path.open(newline="") as file:
        return [
            (row["raw_category"], NYU40_CLASSES[int(row["nyu40id"]) - 1], int(row["count"]))
            for row in csv.DictReader(file, delimiter="\t")
            if row["nyu40id"]
        ]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--nyu-mapping", type=Path)
    parser.add_argument("--scannet-labels", type=Path)
    args = parser.parse_args()
    if args.nyu_mapping is None and args.scannet_labels is None:
        parser.error("give --nyu-mapping, --scannet-labels or both")
    if args.nyu_mapping is not None:
        report("NYU Depth v2 (each name once)", nyu_rows(args.nyu_mapping))
    if args.scannet_labels is not None:
        report("ScanNet", scannet_rows(args.scannet_labels))


if __name__ == "__main__":
    main()

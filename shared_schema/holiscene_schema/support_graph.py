"""Checks of a support graph: every edge points at something real, and no object holds itself up."""

from __future__ import annotations

from collections.abc import Iterable, Sequence

STRUCTURAL_SUPPORTERS = frozenset({"floor", "wall", "ceiling"})
# How each part of the room can hold an object up: the floor from below; a wall, and the
# ceiling an object hangs from, from behind (the type the workbench gives them). The other
# type names nothing physical ("floor, behind"): edits refuse it.
STRUCTURAL_SUPPORT_TYPES = {"floor": "below", "wall": "behind", "ceiling": "behind"}


def support_graph_problems(
    object_ids: Sequence[str], edges: Iterable[tuple[str, str]]
) -> list[str]:
    """Return readable problems of a (child, parent) edge list; empty when it is a forest.

    Allowed: at most one supporter per object, parents that are objects of the scene or
    structural, no self support and no cycles. Objects without a supporter are allowed here
    (a scene being annotated may have them); completeness is checked where it is required.
    """
    known = set(object_ids)
    parent_of: dict[str, str] = {}
    problems: list[str] = []
    for child, parent in edges:
        if child not in known:
            problems.append(f"support names unknown object {child!r}")
            continue
        if parent not in known and parent not in STRUCTURAL_SUPPORTERS:
            problems.append(
                f"supporter {parent!r} of {child!r} is neither an object nor structural"
            )
            continue
        if parent == child:
            problems.append(f"object {child!r} cannot support itself")
            continue
        if child in parent_of:
            problems.append(f"object {child!r} has more than one supporter")
            continue
        parent_of[child] = parent
    problems.extend(_cycle_problems(parent_of))
    return problems


def _cycle_problems(parent_of: dict[str, str]) -> list[str]:
    problems: list[str] = []
    settled: set[str] = set()
    for start in parent_of:
        path: list[str] = []
        on_path: set[str] = set()
        node = start
        while node in parent_of and node not in settled:
            if node in on_path:
                cycle = [*path[path.index(node) :], node]
                problems.append("support cycle: " + " -> ".join(cycle))
                break
            path.append(node)
            on_path.add(node)
            node = parent_of[node]
        settled.update(path)
    return problems

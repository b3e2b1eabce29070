"""The backend's code stays in functions a reader can hold in view: none over 100 lines.

A function counts from its `def` line to its last line (docstring, comments and blank lines
included); nested functions count inside their parent and on their own.
"""

from __future__ import annotations

import ast
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
CHECKED = ("backend/src", "benchmarks", "scripts")
MAX_FUNCTION_LINES = 100


def long_functions(source: str, limit: int = MAX_FUNCTION_LINES) -> list[tuple[str, int, int]]:
    """(name, first line, length) of every function in `source` longer than `limit` lines."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            assert node.end_lineno is not None
            length = node.end_lineno - node.lineno + 1
            if length > limit:
                found.append((node.name, node.lineno, length))
    return found


def test_no_backend_function_is_over_100_lines() -> None:
    offenders = [
        f"{path.relative_to(REPO)}:{line} {name} ({length} lines)"
        for folder in CHECKED
        for path in sorted((REPO / folder).rglob("*.py"))
        for name, line, length in long_functions(path.read_text(encoding="utf-8"))
    ]
    assert offenders == [], "split these into helpers of one idea each:\n" + "\n".join(offenders)


def test_the_check_sees_a_long_function_and_spares_a_short_one() -> None:
    assert long_functions("def f():\n" + "    pass\n" * 99) == []  # 100 lines
    assert long_functions("def f():\n" + "    pass\n" * 100) == [("f", 1, 101)]
    nested = "def outer():\n    def inner():\n" + "        pass\n" * 100
    assert [name for name, _, _ in long_functions(nested)] == ["outer", "inner"]
    method = "class C:\n    async def m(self):\n" + "        pass\n" * 100
    assert long_functions(method) == [("m", 2, 101)]

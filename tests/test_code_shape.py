"""Code shape (the developers' guide): outside Numba kernels no function of the package is longer than 60 lines.
Cyclomatic complexity (at most 15) is ruff's C901, configured in pyproject.toml."""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "facegear_tehl"
MAX_LINES = 60
# Decorators that make a function a Numba kernel: its loops are written out inline for speed.
KERNEL_DECORATORS = frozenset({"njit", "jit", "vectorize", "guvectorize", "stencil"})


def _decorator_name(node: ast.expr) -> str:
    """`njit` for @njit, @njit(cache=True), @numba.njit and @numba.njit(...)."""
    if isinstance(node, ast.Call):
        node = node.func
    return node.attr if isinstance(node, ast.Attribute) else getattr(node, "id", "")


def long_functions(source: str, limit: int = MAX_LINES) -> list[tuple[str, int]]:
    """(name, lines from `def` to the last line) of every function or method longer than `limit` lines that is not
    decorated as a Numba kernel."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            lines = node.end_lineno - node.lineno + 1
            kernel = any(_decorator_name(d) in KERNEL_DECORATORS for d in node.decorator_list)
            if lines > limit and not kernel:
                found.append((node.name, lines))
    return found


def test_the_walk_measures_functions_and_skips_kernels():
    body = "".join(f"    x{i} = {i}\n" for i in range(60))
    source = (f"def long():\n{body}\n@njit(cache=True)\ndef kernel():\n{body}\n"
              "class A:\n    def short(self):\n        pass\n")
    assert long_functions(source) == [("long", 61)]
    assert long_functions(source, limit=61) == []


def test_no_long_function_outside_numba_kernels():
    found = [(path.relative_to(PACKAGE).as_posix(), name, lines) for path in sorted(PACKAGE.rglob("*.py"))
             for name, lines in long_functions(path.read_text(encoding="utf-8"))]
    assert found == []

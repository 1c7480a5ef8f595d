"""The package's imports flow one way: no module imports, directly or through others, a module that imports it
(imports inside function bodies included), so that no import has to hide in a function to dodge a circle. The
layers themselves (command line -> workflows -> files -> case -> physics -> leaves; plots read files only) are
import-linter contracts in pyproject.toml, checked by `lint-imports` in .ci/run and here."""

from __future__ import annotations

from pathlib import Path
import subprocess
import sys

import grimp

PACKAGE = "facegear_tehl"
ROOT = Path(__file__).resolve().parents[1]


def _imports() -> dict[str, set[str]]:
    """Module -> the package modules it imports (at the top, under TYPE_CHECKING or in a function body)."""
    graph = grimp.build_graph(PACKAGE, cache_dir=None)
    return {m: set(graph.find_modules_directly_imported_by(m)) for m in graph.modules}


def _circle(imports: dict[str, set[str]]) -> list[str]:
    """One import circle (its modules, the first repeated at the end), or [] if there is none: depth-first search
    for an import back to a module on the current path."""
    state: dict[str, int] = {}  # 1: on the path, 2: done
    path: list[str] = []

    def visit(module: str) -> list[str]:
        state[module] = 1
        path.append(module)
        for imported in sorted(imports.get(module, ())):
            if state.get(imported) == 1:
                return path[path.index(imported):] + [imported]
            if imported not in state and (found := visit(imported)):
                return found
        state[module] = 2
        path.pop()
        return []

    for module in sorted(imports):
        if module not in state and (found := visit(module)):
            return found
    return []


def test_the_search_finds_a_circle():
    assert _circle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == ["a", "b", "c", "a"]
    assert _circle({"a": {"b", "c"}, "b": {"c"}, "c": set()}) == []


def test_no_import_circle_in_the_package():
    assert _circle(_imports()) == []


def test_the_import_contracts_hold():
    """pyproject.toml's contracts, as `lint-imports` checks them (a new top-level module must be placed in a layer
    there)."""
    command = [sys.executable, "-c", "from importlinter.cli import lint_imports_command; lint_imports_command()"]
    process = subprocess.run([*command, "--no-cache", "--no-logo"], cwd=ROOT, capture_output=True, text=True,
                             timeout=120)
    assert process.returncode == 0, process.stdout[-3000:] + process.stderr[-2000:]

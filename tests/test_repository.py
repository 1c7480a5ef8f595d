"""The repository stands alone and its documentation holds together: no tracked file sends the reader to notes
outside the repository, README's first screen has the two commands, every relative link in README and
docs/*.md (file and heading anchor) resolves, and the docs describe the present: benchmarks.md stays a page of
results, no commit hash dates a statement, and method.md's code map names every module of the package."""

from __future__ import annotations

from pathlib import Path
import re
import subprocess
import unicodedata

import pytest

ROOT = Path(__file__).resolve().parents[1]
# Design notes and shared folders that live outside the repository: cite the paper or docs/ instead.
OUTSIDE_REFERENCES = ("PHYSICS.md", "FACEGEAR.md", "BENCHMARKS.md", "STYLE.md", "ARCHITECTURE.md", "shared/design",
                      "../shared")
FIRST_SCREEN = 60  # lines of README a reader sees before scrolling
README_COMMANDS = ("tehl run cases/facegear_110.yaml", "python -m pytest")  # the commands .ci/run runs
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
FENCE = re.compile(r"^```.*?^```", re.MULTILINE | re.DOTALL)
HEADING = re.compile(r"^#{1,6}\s+(.*?)\s*#*\s*$", re.MULTILINE)
BENCHMARKS_LINES = 400  # docs/benchmarks.md holds today's results, not the run history (git keeps that)
# A commit hash: 7-40 hex digits with a letter and a digit, not part of a word, path or file name ...
HEX_HASH = re.compile(r"(?<![\w/.-])(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}(?![\w/-]|\.\w)")
# ... or digits alone after a word that dates a statement ("at 3294722")
DIGIT_HASH = re.compile(r"\b(?:at|before|after|since|until|commit|commits|against|from|with|in)\s+`?<?\d{7,40}\b",
                        re.IGNORECASE)
PACKAGE = ROOT / "facegear_tehl"
CODE_MAP = "## 7. Code layout"  # the section of docs/method.md that maps the package


def tracked_files() -> list[Path]:
    try:
        listing = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        pytest.skip("not a git checkout")
    return [ROOT / name for name in listing.splitlines() if (ROOT / name).is_file()]


def outside_references(text: str) -> list[tuple[int, str]]:
    """(line number, word) of every mention of a note outside the repository."""
    return [(number, word) for number, line in enumerate(text.splitlines(), start=1)
            for word in OUTSIDE_REFERENCES if word in line]


def markdown_files() -> list[Path]:
    return [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def github_anchor(heading: str) -> str:
    """GitHub's heading anchor: lower case, markup and punctuation dropped (letters, digits, '_', '-' and
    spaces kept), spaces to hyphens."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading).lower()
    kept = "".join(c for c in text if c in " -_" or unicodedata.category(c)[0] in "LMN")
    return kept.replace(" ", "-")


def anchors(path: Path) -> set[str]:
    text = FENCE.sub("", path.read_text(encoding="utf-8"))
    return {github_anchor(h) for h in HEADING.findall(text)}


def test_no_reference_outside_the_repository():
    this_file = Path(__file__).resolve()
    hits = []
    for path in tracked_files():
        if path.resolve() == this_file:
            continue
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError:  # images and other binary files
            continue
        hits += [f"{path.relative_to(ROOT)}:{number}: {word}" for number, word in outside_references(text)]
    assert not hits, "references outside the repository:\n" + "\n".join(hits)


def test_outside_reference_scan_finds_planted_references():
    text = "# heat partition (Blok 1937)\n# see PHYSICS.md §5.2\nlink: ../shared/design/notes\n"
    assert outside_references(text) == [(2, "PHYSICS.md"), (3, "shared/design"), (3, "../shared")]


def test_readme_first_screen_has_the_two_commands():
    head = "\n".join((ROOT / "README.md").read_text(encoding="utf-8").splitlines()[:FIRST_SCREEN])
    missing = [command for command in README_COMMANDS if command not in head]
    assert not missing, f"README's first {FIRST_SCREEN} lines lack {missing}"


def test_readme_commands_are_the_ones_ci_runs():
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert "pip install -e '.[test]' && tehl run cases/facegear_110.yaml" in ci
    assert "python -m pytest" in ci
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "pip install -e '.[test]' && tehl run cases/facegear_110.yaml" in readme


@pytest.mark.parametrize("path", markdown_files(), ids=lambda p: str(p.relative_to(ROOT)))
def test_relative_links_resolve(path):
    text = FENCE.sub("", path.read_text(encoding="utf-8"))
    broken = []
    for target in LINK.findall(text):
        if re.match(r"[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
            continue
        name, _, anchor = target.partition("#")
        linked = (path.parent / name).resolve() if name else path
        if not linked.is_file():
            broken.append(f"{target}: no file {linked.relative_to(ROOT) if linked.is_relative_to(ROOT) else linked}")
        elif anchor and linked.suffix == ".md" and anchor not in anchors(linked):
            broken.append(f"{target}: no heading '#{anchor}' in {linked.relative_to(ROOT)}")
    assert not broken, f"{path.relative_to(ROOT)}: broken links:\n" + "\n".join(broken)


def test_github_anchor_rules():
    assert github_anchor("1.6 Load, contact ratio and the meshing points S1..S5") == (
        "16-load-contact-ratio-and-the-meshing-points-s1s5")
    assert github_anchor("Parallel runs (`--jobs`)") == "parallel-runs---jobs"
    assert github_anchor("Face gear pairs: the `gear:` block") == "face-gear-pairs-the-gear-block"


def commit_hashes(text: str) -> list[tuple[int, str]]:
    """(line number, match) of every commit hash in a text."""
    return [(number, match.group(0)) for number, line in enumerate(text.splitlines(), start=1)
            for pattern in (HEX_HASH, DIGIT_HASH) for match in pattern.finditer(line)]


def test_commit_hash_scan_finds_planted_hashes():
    text = ("S1 at 3294722 took 9 s\nbefore 60a2e8d, and `--before <db0f5c7>`.\nh_c 1.2046 um, 2049 x 65, "
            "DIR/3f1c0e2a9b7d4c51.h5, 1e-3, ab30_ph2.5_u0.5_iso\n")
    assert [number for number, _ in commit_hashes(text)] == [1, 2, 2]


def test_benchmarks_is_a_page_of_results():
    lines = len((ROOT / "docs" / "benchmarks.md").read_text(encoding="utf-8").splitlines())
    assert lines <= BENCHMARKS_LINES, f"docs/benchmarks.md has {lines} lines (at most {BENCHMARKS_LINES})"


def test_docs_name_no_commit():
    paths = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    hits = [f"{path.relative_to(ROOT)}:{number}: {word}" for path in paths
            for number, word in commit_hashes(path.read_text(encoding="utf-8"))]
    assert not hits, "commit hashes in the docs (git keeps the history):\n" + "\n".join(hits)


def code_map() -> str:
    """The code-map section of docs/method.md."""
    text = (ROOT / "docs" / "method.md").read_text(encoding="utf-8")
    start = text.index(CODE_MAP)
    end = text.find("\n## ", start + len(CODE_MAP))
    return text[start:end if end >= 0 else len(text)]


def test_code_map_names_every_module():
    section = code_map()
    modules = sorted(path.relative_to(PACKAGE).as_posix() for path in PACKAGE.rglob("*.py"))
    missing = [name for name in modules
               if not re.search(rf"(?<![\w/.]){re.escape(name)}(?!\w)", section)]
    assert not missing, f"docs/method.md ({CODE_MAP}) does not name: {', '.join(missing)}"


def test_every_solver_constant_has_its_reason_in_the_tuning_ledger():
    """Every field of ehl.tuning.Tuning and of the pressure cycles' ehl.relaxation.Relaxation is named in
    docs/tuning.md (the one place its rationale is found), and the ledger names no field they do not have."""
    from dataclasses import fields
    import re

    from facegear_tehl.ehl.relaxation import Relaxation
    from facegear_tehl.ehl.tuning import Tuning

    ledger = (ROOT / "docs" / "tuning.md").read_text(encoding="utf-8")
    names = {f.name for f in (*fields(Tuning), *fields(Relaxation))}
    assert sorted(name for name in names if f"`{name}`" not in ledger) == []
    entries = set(re.findall(r"\*\*`([a-z_0-9]+)`", ledger)) | set(re.findall(r", `([a-z_0-9]+)` =", ledger))
    assert sorted(entries - names) == []

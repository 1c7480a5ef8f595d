"""A YAML alias bomb in a study file is refused at once (yaml_bounds.py, docs/guarantees.md), as in a case file;
the expansion count is exact on documents counted by hand and finite on one that contains itself."""

from __future__ import annotations

import subprocess
import sys
import time

import pytest
import yaml

from facegear_tehl.yaml_bounds import MAX_VALUES, expanded_size

import synthetic

# Nine lists of nine aliases of the list before: 9^9 = 387 million scalars from a few hundred bytes.
CHAIN = ", ".join(["&a0 [x, x, x, x, x, x, x, x, x]",
                   *(f"&a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]" for i in range(1, 9))])
BOMB = f"[{CHAIN}]"


@pytest.mark.parametrize(("text", "count"), [
    ("7", 1),
    ("[1, [2, 3], {a: 1}]", 1 + 1 + (1 + 2) + (1 + 2)),  # the list, 1, the inner list and its two, the mapping
    ("a: &x [1, 2]\nb: *x\nc: *x", 1 + 3 * (1 + (1 + 2))),  # a mapping of three keys, each naming the 3-value list
])
def test_the_expanded_size_counts_every_place_a_shared_value_is_named(text, count):
    assert expanded_size(yaml.safe_load(text)) == count


def test_a_bomb_and_a_document_containing_itself_are_too_large_at_once():
    started = time.monotonic()
    assert expanded_size(yaml.safe_load(BOMB)) > MAX_VALUES
    assert expanded_size(yaml.safe_load("&a [1, *a]")) > MAX_VALUES
    assert time.monotonic() - started < 1.0


def test_a_study_with_an_alias_bomb_exits_2_at_once(tmp_path):
    study = tmp_path / "study.yaml"
    study.write_text(f"base: {synthetic.BALL_ON_DISC}\nvary:\n  contact.load: [4.0]\nset:\n  name: {BOMB}\n",
                     encoding="utf-8")  # the anchors inside a value (keys of their own would be refused); before,
    # the name was turned into text in full: minutes of CPU in one C call, deaf to SIGTERM
    started = time.monotonic()
    process = subprocess.run(  # a subprocess: before the bound it spun for minutes
        [sys.executable, "-m", "facegear_tehl", "study", str(study), "-o", str(tmp_path / "out")],
        capture_output=True, text=True, timeout=60, check=False)
    assert time.monotonic() - started < 30.0
    assert process.returncode == 2, process.stderr
    assert process.stderr.startswith("error: (file): got 'over 1000000 values'; expected a document of at most"), \
        process.stderr
    assert not (tmp_path / "out").exists()

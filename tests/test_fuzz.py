"""Input robustness: hypothesis mutates valid case files (the plain ball-on-disc contact and the face gear pair)
- wrong types, missing and unknown keys, extreme and non-finite numbers, broken YAML, empty files, binary
garbage - and `tehl validate` answers every one with exit 0 and one `ok:` line (after one-line warnings for
unusual values), or with exit 2 and one line `error: <key path>: got ...; expected ...` per problem, naming the
offending key ('(file)' for the file itself): never a traceback, never exit 1. In-process (click's CliRunner)
for speed; a few inputs also through a subprocess.
Inputs that once crashed or gave an unnamed or multi-line message are kept as regular tests at the bottom."""

from __future__ import annotations

import math
from pathlib import Path
import re
import subprocess
import sys
from typing import Any

from click.testing import CliRunner
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
import pytest
import yaml

from facegear_tehl.case import _Loader
from facegear_tehl.cli import tehl

import synthetic

BASES = {
    "contact": synthetic.BALL_ON_DISC.read_text() + "output: {file: results/ball.h5}\n",
    "gear": (synthetic.CASES / "facegear_110.yaml").read_text(),
}
TOP_LEVEL = ("name", "description", "contact", "gear", "materials", "lubricant", "solver", "output")
# Every key the case readers know (an added key with one of these names would not be unknown).
KNOWN_KEYS = set(TOP_LEVEL) | {
    "radius_x", "radius_y", "load", "entrainment_speed", "slide_roll_ratio", "entrainment_angle", "body_1",
    "body_2", "elastic_modulus", "poisson_ratio", "density", "thermal_conductivity", "specific_heat", "roughness",
    "viscosity", "inlet_temperature", "viscosity_model", "pressure_viscosity", "roelands_z", "density_model",
    "rheology", "eyring_stress", "temperature_viscosity", "thermal_expansion", "conductivity_pressure_coefficient",
    "conductivity_pressure_saturation", "grid", "grid_y", "domain", "x", "y",
    "thermal", "thermal_layers", "max_thermal_iterations", "thermal_tolerance", "eyring_tolerance",
    "outlet_refinement", "outlet_patches",
    "coarsest_grid",
    "cycles_per_level",
    "max_cycles", "tolerance", "load_tolerance", "file", "pinion_teeth", "shaper_teeth", "face_gear_teeth",
    "module", "pressure_angle", "shaft_angle", "pinion_addendum", "face_gear_addendum", "inner_radius",
    "outer_radius", "pinion_speed", "pinion_torque", "load_sharing", "points", "shaft_angle_error", "offset",
    "pinion_axial_shift", "face_gear_axial_shift", "transition_side", "oil_type", "pinion_bulk_temperature",
    "face_gear_bulk_temperature",
}
ERROR_LINE = re.compile(r"error: (?P<key>.+?): got (?P<value>.*); expected (?P<expected>.+)")
WARNING_LINE = re.compile(r"warning: \S+: .+")
FUZZ = settings(deadline=None, database=None, suppress_health_check=[HealthCheck.too_slow])


class _Dumper(yaml.SafeDumper):
    """Writes YAML that the case reader reads back as written: it knows the reader's extra float rule, so a
    string such as '1e3' is quoted instead of turning into a number."""


_Dumper.yaml_implicit_resolvers = _Loader.yaml_implicit_resolvers


def _load(text: str) -> dict:
    return yaml.load(text, Loader=_Loader)


def _dump(data: Any) -> str:
    return yaml.dump(data, Dumper=_Dumper, sort_keys=False, allow_unicode=True)


def _paths(node: Any, prefix: tuple = ()) -> list[tuple]:
    """Paths (keys and list indices) to every entry of a parsed case, blocks and leaves."""
    children = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    found = []
    for key, value in children:
        found.append(prefix + (key,))
        found += _paths(value, prefix + (key,))
    return found


def _key_path(path: tuple) -> str:
    """The key path an error names for `path`: its keys up to the first list index."""
    keys = []
    for part in path:
        if isinstance(part, int):
            break
        keys.append(part)
    return ".".join(keys)


def _display(key: str) -> str:
    """A key path as the one-line message shows it: a part that is not printable quoted."""
    return ".".join(part if part.isprintable() else repr(part) for part in key.split("."))


def _entry(data: Any, path: tuple) -> Any:
    for part in path:
        data = data[part]
    return data


def _within(named: str, key: str) -> bool:
    """The key path `named` (as a message shows it) is `key` or a key inside it."""
    inside = (key + ".", "'" + key + ".", '"' + key + ".")  # shown as repr() when not printable
    return named == key or named.startswith(inside)


def _parent(data: dict, path: tuple) -> Any:
    return _entry(data, path[:-1])


PATHS = {kind: _paths(_load(text)) for kind, text in BASES.items()}

_runner = CliRunner()


def _validate(folder: Path, content: str | bytes) -> tuple[int, str, str]:
    """`tehl validate` in this process on a file holding `content`: (exit code, stdout, stderr)."""
    path = folder / "case.yaml"
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content, encoding="utf-8")
    result = _runner.invoke(tehl, ["validate", str(path)])
    assert result.exception is None or isinstance(result.exception, SystemExit), repr(result.exception)
    return result.exit_code, result.stdout, result.stderr


def _check_answer(code: int, stdout: str, stderr: str) -> list[str]:
    """Exit 0 with one ok line (after any one-line warnings), or exit 2 with one error line per problem; returns
    the key paths named (none for ok)."""
    assert "Traceback" not in stdout + stderr
    assert code in (0, 2), (code, stdout, stderr)
    lines = stderr.splitlines()
    assert stderr == "" or stderr.endswith("\n"), stderr
    if code == 0:
        assert all(WARNING_LINE.fullmatch(line) for line in lines), stderr
        assert len(stdout.splitlines()) == 1 and stdout.startswith("ok: "), stdout
        numbers = stdout[max(stdout.rfind("plain contact ("), stdout.rfind("face gear pair (")):]  # after the name
        assert not re.search(r"\b(nan|inf)\b", numbers), stdout
        return []
    assert stdout == "" and lines, stderr
    matches = [ERROR_LINE.fullmatch(line) for line in lines]
    assert all(matches), stderr
    assert len(set(lines)) == len(lines), stderr  # each problem named once
    return [match["key"] for match in matches]


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("fuzz")


# ------------------------------------------------------------------------------------------- values

NON_FINITE_AND_EXTREME = st.sampled_from(
    [math.nan, math.inf, -math.inf, 1e308, -1e308, 5e-324, -5e-324, -0.0, 0, 0.0, -1, 10**400, -(10**400),
     2**63, 2**64 + 1, 10**20, 1e-300]
)
NUMBERS = st.one_of(NON_FINITE_AND_EXTREME, st.floats(), st.integers())
WRONG_TYPES = st.one_of(
    st.text(max_size=20),
    st.sampled_from(["1e3", "six", "0x1F", "1,5", "2.0 GPa", "nan", "inf", "", "S9", "yes", "null"]),
    st.booleans(),
    st.none(),
    st.binary(max_size=8),
    st.lists(st.one_of(st.integers(), st.text(max_size=5)), max_size=3),
    st.dictionaries(st.text(max_size=5), st.integers(), max_size=2),
)


@settings(FUZZ, max_examples=300)
@given(kind=st.sampled_from(sorted(BASES)), data=st.data(), numeric=st.booleans())
def test_a_replaced_value_is_accepted_or_named(folder, kind, data, numeric):
    path = data.draw(st.sampled_from(PATHS[kind]), label="path")
    value = data.draw(NUMBERS if numeric else WRONG_TYPES, label="value")
    case = _load(BASES[kind])
    _parent(case, path)[path[-1]] = value
    for key in _check_answer(*_validate(folder, _dump(case))):
        if numeric:  # a number may break a cross-key check: the error names a key of the same block
            assert key.split(".")[0] == path[0] or key == "contact/gear", (path, value, key)
        else:  # a value of the wrong type is named where it is (or, for a block, one of its keys)
            assert _within(key, _key_path(path)) or key == "contact/gear", (path, value, key)


def test_every_deleted_key_is_accepted_or_named(folder):
    """Exhaustive: each key (and list entry) of both cases removed in turn; a required one is named."""
    count = 0
    for kind, text in BASES.items():
        for path in PATHS[kind]:
            case = _load(text)
            del _parent(case, path)[path[-1]]
            keys = _check_answer(*_validate(folder, _dump(case)))
            assert keys in ([], [_key_path(path)], ["contact/gear"]), (path, keys)
            count += 1
    assert count > 90


OPTIONAL_KEYS = {  # keys a block may have that the two cases leave out
    ("lubricant",): ["roelands_z", "eyring_stress", "temperature_viscosity", "thermal_expansion",
                     "thermal_conductivity", "conductivity_pressure_coefficient", "conductivity_pressure_saturation",
                     "specific_heat", "oil_type"],
    ("materials", "body_1"): ["roughness", "density", "thermal_conductivity", "specific_heat"],
    ("solver",): ["domain", "grid_y", "coarsest_grid", "cycles_per_level", "max_cycles", "tolerance", "load_tolerance",
                  "thermal_layers", "max_thermal_iterations", "thermal_tolerance", "eyring_tolerance",
                  "outlet_refinement", "outlet_patches"],
    ("gear",): ["shaft_angle_error", "offset", "pinion_axial_shift", "face_gear_axial_shift", "pinion_bulk_temperature",
                "face_gear_bulk_temperature"],
    ("output",): ["file"],
}
PLAUSIBLE = st.one_of(st.floats(-1e3, 1e3), st.floats(-1e-2, 1e-2), st.integers(-100, 5000),
                      st.lists(st.floats(-10, 10), min_size=2, max_size=2),
                      st.fixed_dictionaries({"x": st.lists(st.floats(-10, 10), min_size=2, max_size=2),
                                             "y": st.lists(st.floats(-10, 10), min_size=2, max_size=2)}))


@settings(FUZZ, max_examples=150)
@given(kind=st.sampled_from(sorted(BASES)), data=st.data(), value=st.one_of(PLAUSIBLE, NUMBERS, WRONG_TYPES))
def test_an_optional_key_is_accepted_or_named(folder, kind, data, value):
    case = _load(BASES[kind])
    absent = {b: [k for k in keys if k not in _entry(case, b)] for b, keys in OPTIONAL_KEYS.items() if b[0] in case}
    block = data.draw(st.sampled_from([b for b, keys in absent.items() if keys]), label="block")
    key = data.draw(st.sampled_from(absent[block]), label="key")
    _entry(case, block)[key] = value
    named = _check_answer(*_validate(folder, _dump(case)))
    assert all(key.split(".")[0] == block[0] for key in named), (block, key, value, named)


UNKNOWN_KEYS = st.one_of(
    st.text(min_size=1, max_size=12).filter(lambda k: k not in KNOWN_KEYS),
    st.sampled_from(sorted(KNOWN_KEYS)).map(lambda k: k + "_"),  # a near miss: "did you mean"
    st.sampled_from(["a\nb", "tab\there", "\u2028", " ", "é", "<<", "=", "~"]),
    st.integers(), st.booleans(), st.floats(allow_nan=False),
)


@settings(FUZZ, max_examples=100)
@given(kind=st.sampled_from(sorted(BASES)), data=st.data(), key=UNKNOWN_KEYS, value=st.one_of(NUMBERS, WRONG_TYPES))
def test_an_unknown_key_is_named(folder, kind, data, key, value):
    case = _load(BASES[kind])
    blocks = [()] + [p for p in PATHS[kind] if isinstance(_entry(case, p), dict)]
    where = data.draw(st.sampled_from(blocks), label="block")
    _entry(case, where)[key] = value
    text = _dump(case)
    # the key as the reader sees it (YAML folds a line break such as U+0085 in a quoted key into a space)
    added = [k for k in _entry(_load(text), where) if k not in _entry(_load(BASES[kind]), where)]
    assume(len(added) == 1)
    named = _check_answer(*_validate(folder, text))
    assert named == [_display(".".join([*where, str(added[0])]))], (where, key, named)


# --------------------------------------------------------------------------------------- broken YAML

@settings(FUZZ, max_examples=120)
@given(kind=st.sampled_from(sorted(BASES)), data=st.data(),
       damage=st.sampled_from(["truncate", "tab", "bracket", "blank"]))
def test_broken_yaml_is_answered_in_one_line(folder, kind, data, damage):
    text = BASES[kind]
    lines = text.splitlines(keepends=True)
    if damage == "truncate":
        text = text[: data.draw(st.integers(0, len(text) - 1), label="length")]
    elif damage == "tab":  # YAML forbids tabs in indentation
        indented = [i for i, line in enumerate(lines) if line.startswith("  ") and line.strip()]
        i = data.draw(st.sampled_from(indented), label="line")
        lines[i] = "\t" + lines[i].lstrip(" ")
        text = "".join(lines)
    elif damage == "bracket":
        at = data.draw(st.integers(0, len(text)), label="at")
        text = text[:at] + data.draw(st.sampled_from(list("[]{}\"'")), label="bracket") + text[at:]
    else:
        text = data.draw(st.sampled_from(["", "\n", "   \n", "# only a comment\n", "---\n", "...\n"]), label="text")
    keys = _check_answer(*_validate(folder, text))
    if damage in ("tab", "blank"):
        assert keys == ["(file)"], keys
    elif damage == "truncate":  # (a bracket may make a new, unknown key: any key)
        assert all(key.split(".")[0] in (*TOP_LEVEL, "(file)", "contact/gear") for key in keys), keys


@settings(FUZZ, max_examples=60)
@given(content=st.one_of(st.binary(max_size=200), st.text(max_size=200)))
def test_garbage_is_answered_in_one_line(folder, content):
    _check_answer(*_validate(folder, content))


# ------------------------------------------------------------------------------------ in a subprocess

SUBPROCESS_INPUTS = {
    "binary": b"\x89HDF\r\n\x1a\n\x00\x00\xff\xfe",
    "empty": b"",
    "tab": BASES["contact"].replace("  load:", "\tload:").encode(),
    "nan load": BASES["contact"].replace("load: 6.272", "load: .nan").encode(),
    "huge integer": BASES["gear"].replace("face_gear_teeth: 160", "face_gear_teeth: 1" + "0" * 400).encode(),
    "key with a newline": (BASES["gear"] + '"a\\nb": 1\n').encode(),
}


@pytest.mark.parametrize("name", SUBPROCESS_INPUTS)
def test_bad_input_in_a_subprocess(tmp_path, name):
    path = tmp_path / "case.yaml"
    path.write_bytes(SUBPROCESS_INPUTS[name])
    process = subprocess.run([sys.executable, "-m", "facegear_tehl", "validate", str(path)], capture_output=True,
                             text=True, timeout=60)
    assert process.returncode == 2, process.stderr
    assert _check_answer(process.returncode, process.stdout, process.stderr) != []


# ------------------------------------------------------------------- inputs that once crashed (regressions)

def _replace(kind: str, old: str, new: str) -> str:
    assert old in BASES[kind]
    return BASES[kind].replace(old, new, 1)


REGRESSIONS = {
    # exit 1 (OverflowError: int too large to convert to float)
    "integer beyond 1e308": (_replace("contact", "load: 6.272", "load: 1" + "0" * 400), "contact.load"),
    "face gear teeth beyond 1e308": (_replace("gear", "face_gear_teeth: 160", "face_gear_teeth: 1" + "0" * 400),
                                     "gear.face_gear_teeth"),
    # exit 1 (ValueError: exceeds the limit of 4300 digits for integer string conversion, inside YAML)
    "integer of 5000 digits": (_replace("contact", "load: 6.272", "load: 1" + "0" * 5000), "(file)"),
    # exit 1 (RecursionError inside YAML)
    "deep nesting": ("a: " + "[" * 3000 + "]" * 3000 + "\n", "(file)"),
    # exit 1 (ValueError: month must be in 1..12, a YAML timestamp)
    "impossible date": (_replace("contact", "load: 6.272", "load: 2024-13-45"), "(file)"),
    # exit 1 (OverflowError in the Hertz contact)
    "load 1e308": (_replace("contact", "load: 6.272", "load: 1.0e308"), "contact.load"),
    # exit 1 (ZeroDivisionError: the speed underflows to 0 rad/s)
    "pinion speed 5e-324": (_replace("gear", "pinion_speed: 3000.0", "pinion_speed: 5.0e-324"), "gear.pinion_speed"),
    "pinion torque 5e-324": (_replace("gear", "pinion_torque: 500.0", "pinion_torque: 5.0e-324"),
                             "gear.pinion_torque"),
    # exit 2 with an empty key (': got None; ...')
    "empty file": ("", "(file)"),
    "a list, not a mapping": ("- a\n- b\n", "(file)"),
    # exit 2 with the key '.1'
    "integer key": (BASES["contact"] + "1: 2\n", "1"),
    # exit 2 on two lines (a newline in the key)
    "key with a newline": (BASES["contact"] + '"a\\nb": 2\n', repr("a\nb")),
    # exit 0 with nonsense ('p_hertz nan..nan MPa', 'a inf µm', a grid of 2^60 + 1 nodes), or a name that makes
    # the ok line two lines long
    "torque 1e308": (_replace("gear", "pinion_torque: 500.0", "pinion_torque: 1.0e308"), "gear.pinion_torque"),
    "radii 1e305": (_replace("contact", "radius_x: 0.0127", "radius_x: 1.0e305"), "contact.radius_x"),
    "grid 2^60 + 1": (_replace("contact", "grid: 257", f"grid: {2**60 + 1}"), "solver.grid"),
    "name with a newline": (_replace("contact", "name: ball_on_disc", 'name: "a\\nb"'), "name"),
    "name with a slash": (_replace("contact", "name: ball_on_disc", "name: ../b"), "name"),
    "output file with NUL": (_replace("contact", "file: results/ball.h5", 'file: "a\\0b"'), "output.file"),
    # exit 2 after a numpy overflow warning on stderr (two lines in a subprocess)
    "shaft angle 1e-300": (_replace("gear", "shaft_angle: 110.0", "shaft_angle: 1.0e-300"), "gear.shaft_angle"),
    # exit 1 (ZeroDivisionError: the angle underflows to 0 rad)
    "shaft angle 5e-324": (_replace("gear", "shaft_angle: 110.0", "shaft_angle: 5.0e-324"), "gear.shaft_angle"),
}


@pytest.mark.parametrize("name", REGRESSIONS)
def test_inputs_that_once_crashed(folder, name):
    text, key = REGRESSIONS[name]
    assert _check_answer(*_validate(folder, text)) == [key]


def test_a_value_shown_in_a_message_stays_short(folder):
    """A YAML alias nesting lists 9 deep and 9 wide is a billion entries: the message shows a bounded part."""
    lines = ["a0: &a0 [x, x, x, x, x, x, x, x, x]"]
    lines += [f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]" for i in range(1, 9)]
    text = "\n".join(lines) + "\n" + _replace("contact", "name: ball_on_disc", "name: *a8")
    code, stdout, stderr = _validate(folder, text)
    assert _check_answer(code, stdout, stderr) == ["name", *(f"a{i}" for i in range(9))]  # a0..a8: unknown keys
    assert all(len(line) < 300 for line in stderr.splitlines())


def test_a_key_that_is_not_printable_is_named_under_its_block(folder):
    """Found by the fuzz test above: an unassigned code point as a key under solver.domain was named as one quoted
    path ('solver.domain.\\U00018cd6'), which hid the block it belongs to; only the part is quoted now."""
    case = _load(BASES["gear"])
    case["solver"]["domain"] = {"\U00018cd6": 0}
    named = _check_answer(*_validate(folder, _dump(case)))
    assert named and all(key.startswith("solver.domain") for key in named), named

"""Numbers in case and study files follow YAML 1.2 (yaml_numbers.py, docs/case-reference.md): `040` is 40 (YAML 1.1:
octal 32), `1:30` and `0b101` are not numbers (YAML 1.1: 90 and 5) and are refused naming the key; the YAML 1.2
floats (`1e-3`) stay numbers."""

from __future__ import annotations

import math

from click.testing import CliRunner
import pytest
import yaml

from facegear_tehl.case import parse_case
from facegear_tehl.cli import tehl
from facegear_tehl.schema import CaseError
from facegear_tehl.study_file import load_study
from facegear_tehl.yaml_numbers import Yaml12Loader

import synthetic

CASE_TEXT = synthetic.BALL_ON_DISC.read_text()


def _with(old: str, new: str) -> str:
    assert old in CASE_TEXT
    return CASE_TEXT.replace(old, new, 1)


@pytest.mark.parametrize(("text", "value"), [
    ("040", 40), ("010", 10), ("-007", -7), ("+12", 12), ("0o17", 15), ("0x1A", 26),  # YAML 1.2 core integers
    ("1e-3", 1e-3), ("2.0e11", 2.0e11), (".5", 0.5), ("5.", 5.0), ("-1.5E+2", -150.0), ("-.inf", -math.inf),
])
def test_numbers_read_as_yaml_1_2_core_schema(text, value):
    loaded = yaml.load(f"v: {text}", Loader=Yaml12Loader)["v"]
    assert loaded == value and type(loaded) is type(value)


@pytest.mark.parametrize("text", ["1:30", "0b101", "1_000", "0o8", "0x", "1e", "1.2.3"])
def test_yaml_1_1_only_forms_are_strings(text):
    assert yaml.load(f"v: {text}", Loader=Yaml12Loader)["v"] == text


def test_a_leading_zero_is_decimal_in_a_case():
    case = parse_case(_with("  inlet_temperature: 40.0", "  inlet_temperature: 040").replace("  load: 6.272",
                                                                                              "  load: 010"))
    assert case.lubricant.inlet_temperature == pytest.approx(273.15 + 40.0)  # K; YAML 1.1 read 32 degC
    assert case.contact.load == 10.0  # N; YAML 1.1 read 8 N


@pytest.mark.parametrize("text", ["1:30", "0b1010"])
def test_sexagesimal_and_binary_are_refused_naming_the_key(text):
    with pytest.raises(CaseError) as error:
        parse_case(_with("  load: 6.272", f"  load: {text}"))
    assert error.value.key == "contact.load" and error.value.value == text


def test_validate_exits_2_on_a_sexagesimal_load(tmp_path):
    case = tmp_path / "c.yaml"
    case.write_text(_with("  load: 6.272", "  load: 1:30"), encoding="utf-8")
    result = CliRunner().invoke(tehl, ["validate", str(case)])
    assert result.exit_code == 2
    assert result.stderr.strip() == "error: contact.load: got '1:30'; expected a finite number in N", result.stderr


def test_a_study_reads_its_values_as_yaml_1_2(tmp_path):
    study = tmp_path / "study.yaml"
    study.write_text(f"base: {synthetic.BALL_ON_DISC}\nvary:\n  contact.load: [040, 050]\n", encoding="utf-8")
    assert [v.case.contact.load for v in load_study(study).variants] == [40.0, 50.0]
    study.write_text(f"base: {synthetic.BALL_ON_DISC}\nvary:\n  contact.load: [040, 1:30]\n", encoding="utf-8")
    with pytest.raises(CaseError) as error:
        load_study(study)
    assert error.value.key == "vary.contact.load" and error.value.value == "1:30"

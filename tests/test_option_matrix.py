"""Every documented option combination runs end to end through `tehl run` (issue 14, item 4).

The matrix: solver.thermal off / reduced / full / auto x lubricant.rheology newtonian / ree_eyring x
lubricant.viscosity_model roelands / barus x lubricant.density_model dowson_higginson / incompressible, on
(a) a plain contact, cases/ball_on_disc_sliding.yaml, and (b) the face gear, cases/facegear_110.yaml at
S1 and S3; both on `--grid 33` (the gear keeps its aspect: 33 x 17). The case texts are the shipped YAML
with those four keys changed (eyring_stress dropped for newtonian: it is only required by ree_eyring),
written to tmp_path.

Each run is `tehl run CASE -o FILE --grid 33 [--points S1,S3] --jobs 1` through click's CliRunner (in this
process: the Numba kernels compile once; --jobs 1 keeps it on one of the two shared cores). The contract:
exit 0 (converged) or 3 (not converged, every such point named with its reason on stderr), never 1 or 2,
never a traceback; the file is written every time, read back by results.read_result, finite everywhere,
h_min > 0 at every converged point, and the models it records match the options; `tehl info FILE --json`
exits 0 and prints strict JSON.

Fast part (default): a pairwise-covering subset of 8 of the 32 combinations per contact (every pair of
values of any two options appears at least once; 8 = 4 x 2 is the least possible). Built from the
orthogonal array over thermal index i = 0..3 and rheology r = 0/1: viscosity = r xor (i & 1),
density = r xor (i >> 1); the gear uses the same array with the rheology flipped, so the two contacts run
16 distinct combinations between them and each contact alone covers every pair. Slow part
(`-m slow`): the remaining 24 combinations per contact, and `reduced` against `full` on 129^2 (below 129^2
`reduced` is `full` by design, docs/method.md "Thermal models", so the 33^2 matrix cannot tell them apart).

Measured (2 shared cores): a plain-contact run takes 0.1-1.8 s, a gear run (S1, S3) 1.2-6.4 s; the fast
part (18 tests) ~34 s, the slow part (49 tests) ~97 s.
"""

from __future__ import annotations

from dataclasses import dataclass
import itertools
import json
from pathlib import Path

from click.testing import CliRunner
import numpy as np
import pytest
import yaml

from facegear_tehl.cli import tehl
from facegear_tehl.lubricant import DENSITY_MODELS, RHEOLOGY_MODELS, VISCOSITY_MODELS
from facegear_tehl.results import non_finite_entries, read_result
from facegear_tehl.settings import THERMAL_MODELS

CASES = Path(__file__).resolve().parents[1] / "cases"
GRID = 33  # nodes along x: the smallest grid the docs list, ~1 s per plain run

# The documented values (docs/case-reference.md, docs/method.md "Thermal models");
# test_matrix_spans_the_documented_options fails if the package gains or drops one without this matrix following.
THERMAL = ("off", "reduced", "full", "auto")
RHEOLOGY = ("newtonian", "ree_eyring")
VISCOSITY = ("roelands", "barus")
DENSITY = ("dowson_higginson", "incompressible")
OPTIONS = (THERMAL, RHEOLOGY, VISCOSITY, DENSITY)

EXIT_OK, EXIT_NOT_CONVERGED = 0, 3  # cli.py: 1 unexpected error / failed point, 2 bad input


@dataclass(frozen=True)
class Contact:
    name: str
    case_file: str
    args: tuple[str, ...]  # extra `tehl run` options (besides -o, --grid, --jobs)
    points: tuple[str, ...]  # the points the file must hold, in order


PLAIN = Contact("plain", "ball_on_disc_sliding.yaml", (), ("contact",))
GEAR = Contact("gear", "facegear_110.yaml", ("--points", "S1,S3"), ("S1", "S3"))

Combo = tuple[str, str, str, str]  # thermal, rheology, viscosity, density


def pairwise_subset(flip_rheology: bool = False) -> list[Combo]:
    """8 combinations covering every pair of option values (orthogonal array, see the module docstring)."""
    combos = []
    for i, thermal in enumerate(THERMAL):
        for r in (0, 1):
            rheology = RHEOLOGY[r ^ int(flip_rheology)]
            combos.append((thermal, rheology, VISCOSITY[r ^ (i & 1)], DENSITY[r ^ (i >> 1)]))
    return combos


def uncovered_pairs(combos: list[Combo]) -> set[tuple[int, str, int, str]]:
    """(option index, value, option index, value) pairs that no combination in `combos` holds."""
    missing = set()
    for (a, values_a), (b, values_b) in itertools.combinations(enumerate(OPTIONS), 2):
        seen = {(c[a], c[b]) for c in combos}
        missing |= {(a, x, b, y) for x in values_a for y in values_b if (x, y) not in seen}
    return missing


ALL = list(itertools.product(*OPTIONS))
FAST = {PLAIN: pairwise_subset(), GEAR: pairwise_subset(flip_rheology=True)}

# Combinations expected to fail, each marked xfail(strict): (contact name, combo) -> reason. Empty: every
# combination exits 0 or 3 with a file (the thermal off + ree_eyring ones included: ehl/report.py reports
# dissipated_power for every film-state solve, which the heat budget reads).
KNOWN_FAILURES: dict[tuple[str, Combo], str] = {}


def _params(contact: Contact, combos: list[Combo], *marks: pytest.MarkDecorator) -> list:
    params = []
    for combo in combos:
        combo_marks = list(marks)
        reason = KNOWN_FAILURES.get((contact.name, combo))
        if reason is not None:
            combo_marks.append(pytest.mark.xfail(strict=True, reason=reason))
        params.append(pytest.param(contact, combo, marks=combo_marks, id=f"{contact.name}-{'-'.join(combo)}"))
    return params


FAST_PARAMS = [p for contact, combos in FAST.items() for p in _params(contact, combos)]
SLOW_PARAMS = [p for contact, combos in FAST.items()
               for p in _params(contact, [c for c in ALL if c not in combos], pytest.mark.slow)]


# ------------------------------------------------------------------------------------------------ helpers


def write_case(folder: Path, contact: Contact, combo: Combo) -> Path:
    """The shipped case with the four options set, written to `folder` (the shipped file is not touched)."""
    thermal, rheology, viscosity, density = combo
    case = yaml.safe_load((CASES / contact.case_file).read_text())
    case["solver"]["thermal"] = thermal
    lubricant = case["lubricant"]
    lubricant.update(rheology=rheology, viscosity_model=viscosity, density_model=density)
    if rheology == "ree_eyring":
        lubricant.setdefault("eyring_stress", 1.0e7)  # Pa; both shipped cases give 1e7 already
    else:
        lubricant.pop("eyring_stress", None)  # optional for newtonian: the case must run without it
    path = folder / f"{contact.name}_{'_'.join(combo)}.yaml"
    path.write_text(yaml.safe_dump(case, sort_keys=False))
    return path


def _invoke(*args: str):
    return CliRunner().invoke(tehl, [str(a) for a in args])


def _strict_json(text: str):
    """json.loads refusing NaN / Infinity (Python's json accepts them; JSON does not)."""

    def refuse(constant: str):
        raise ValueError(f"non-standard JSON constant {constant}")

    return json.loads(text, parse_constant=refuse)


def run_and_check(folder: Path, contact: Contact, combo: Combo, grid: int = GRID):
    """`tehl run` one combination and check the whole contract; returns the result read back."""
    thermal, rheology, viscosity, density = combo
    case = write_case(folder, contact, combo)
    target = folder / f"{case.stem}.h5"
    run = _invoke("run", case, "-o", target, "--grid", grid, "--jobs", "1", *contact.args)
    log = f"exit {run.exit_code}\nstdout:\n{run.stdout}\nstderr:\n{run.stderr}"

    # exit code: 0 or 3 only; no traceback (CliRunner keeps an escaped exception in run.exception)
    assert run.exit_code in (EXIT_OK, EXIT_NOT_CONVERGED), log
    assert run.exception is None or isinstance(run.exception, SystemExit), log
    assert "Traceback" not in run.output, log

    # the file: written, readable, finite
    assert target.is_file(), log
    result = read_result(target)
    assert non_finite_entries(target) == [], log
    assert result.status == ("ok" if run.exit_code == EXIT_OK else "not_converged"), log
    assert tuple(result.points) == contact.points, log
    assert result.overrides.get("grid") == grid, log

    # the models the case asked for (file level) and those each point's solver used
    assert result.models == {"viscosity": viscosity, "density": density, "rheology": rheology, "thermal": thermal}
    for name, point in result.points.items():
        where = f"{name}: {point.models}\n{log}"
        # each entry is '<option>' or '<option> (<source>)'
        assert point.models["viscosity"].split()[0] == viscosity, where
        assert point.models["density"].split()[0] == density, where
        assert point.models["rheology"].split()[0] == rheology, where
        if thermal == "auto":
            assert point.models["thermal"] in ("off", "reduced", "full"), where
            assert point.models["thermal_reason"].startswith("auto:"), where
        elif thermal == "reduced" and point.scalars["grid"] < 129:  # no coarse stage to freeze: solved and named full
            assert point.models["thermal"] == "full" and "solved full" in point.models["thermal_reason"], where
        else:
            assert point.models["thermal"] == thermal, where

        for group in (point.scalars, point.fields, point.axes, point.history):
            for key, value in group.items():
                values = np.asarray(getattr(value, "values", value))
                if values.dtype.kind in "biuf":
                    assert np.all(np.isfinite(values)), f"{name}.{key} not finite\n{log}"
        # a film that closed (h_min <= 0), and the last iterate of a failed solve that does not carry the load, are
        # written without fields or film scalars (ehl/report.py), never as a film; any film that is written is open
        if not point.fields:
            unloaded = point.outcome in ("diverged", "not converged") and "does not carry the load" in point.message
            assert (point.outcome == "film closed" or unloaded) and "h_min" not in point.scalars, where
        else:
            assert point.scalars["h_min"] > 0.0, where
            assert point.fields["film_thickness"].values.min() > 0.0, where
            # cavitation: the solver keeps p >= 0 exactly (no tolerance)
            assert point.fields["pressure"].values.min() >= 0.0, where
        if point.converged:
            assert point.outcome == "converged", where
            assert point.fields and point.scalars["h_min"] > 0.0, where
            assert point.scalars["h_c"] >= point.scalars["h_min"], where
        else:
            # the reason, named with its point, on stderr
            assert point.message, where
            assert f"{name}: {point.message.splitlines()[0]}" in run.stderr, where
            # issue 14: an isothermal (thermal off) Ree-Eyring point reported 'thermal loop not converged ...
            # temperature change 0.00e+00 K'; with the thermal model off there is no thermal loop to name
            if thermal == "off":
                assert "thermal loop" not in point.message, where
        # a temperature rise is a thermal model's: an isothermal film, Newtonian or Ree-Eyring, reports none (its
        # layers hold the inlet temperature; a rise of 0 K would read as a solved one)
        if point.models["thermal"] == "off":
            assert not [key for key in point.scalars if key.startswith(("dT_", "error_estimate_dT"))], where
    if run.exit_code == EXIT_NOT_CONVERGED:
        assert "not converged" in run.stderr, log

    # the heat budget: run for every converged point whose film state was computed (thermal, or an isothermal
    # Ree-Eyring film: the case where it crashed), one row per such point (another's figures are its last iterate's)
    with_film = [name for name, point in result.points.items() if point.fields and point.converged]
    if (thermal != "off" or rheology == "ree_eyring") and with_film:
        assert "point" in result.heat, log
    if result.heat:
        assert [str(p) for p in result.heat["point"].values] == with_film, log

    # `tehl info FILE --json`
    info = _invoke("info", target, "--json")
    assert info.exit_code == 0, f"exit {info.exit_code}\n{info.output}"
    document = _strict_json(info.stdout)
    assert document["status"] == result.status
    assert list(document["points"]) == list(contact.points)
    assert [document["points"][n]["converged"] for n in contact.points] == [
        result.points[n].converged for n in contact.points]
    return result


# -------------------------------------------------------------------------------------------------- tests


def test_matrix_spans_the_documented_options():
    """The matrix holds every value the case schema accepts, so a new option cannot skip it."""
    assert set(THERMAL) == set(THERMAL_MODELS)
    assert set(RHEOLOGY) == set(RHEOLOGY_MODELS)
    assert set(VISCOSITY) == set(VISCOSITY_MODELS)
    assert set(DENSITY) == set(DENSITY_MODELS)
    assert len(ALL) == 32


def test_fast_subsets_cover_every_pair():
    for combos in FAST.values():
        assert len(combos) == len(set(combos)) == 8
        assert uncovered_pairs(combos) == set()
    # the two contacts run different combinations
    assert not set(FAST[PLAIN]) & set(FAST[GEAR])
    # the check itself can fail: dropping a row leaves pairs uncovered
    assert uncovered_pairs(FAST[PLAIN][1:])


@pytest.mark.parametrize(("contact", "combo"), FAST_PARAMS)
def test_option_combination_runs(tmp_path, contact, combo):
    run_and_check(tmp_path, contact, combo)


@pytest.mark.parametrize(("contact", "combo"), SLOW_PARAMS)
def test_option_combination_runs_full_product(tmp_path, contact, combo):
    run_and_check(tmp_path, contact, combo)


@pytest.mark.slow
def test_reduced_takes_its_own_fine_stage_on_129(tmp_path):
    """On 129^2 `reduced` solves the thermal problem on 65^2 and freezes it (docs/method.md "Thermal models"); the
    33^2 matrix runs `reduced` as `full`. Both run end to end here and give different films, i.e. the
    `reduced` branch ran (any difference: the two are bit-identical when it does not; ~10 s each)."""
    combo = ("reduced", "ree_eyring", "roelands", "dowson_higginson")  # the shipped sliding case's models
    reduced = run_and_check(tmp_path, PLAIN, combo, grid=129)
    full = run_and_check(tmp_path, PLAIN, ("full", *combo[1:]), grid=129)
    assert reduced.points["contact"].scalars["h_c"] != full.points["contact"].scalars["h_c"]

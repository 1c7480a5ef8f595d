"""`tehl compare`: differences judged against the combined grid-error estimates, checked by hand on files whose
values are set here."""

from __future__ import annotations

import json
import math
import re

from click.testing import CliRunner
import h5py
import pytest

from facegear_tehl.cli import tehl
from facegear_tehl.compare import Significance, comparison_figure, differences
from facegear_tehl.results import read_result, write_result

import synthetic

FACE_GEAR = "cases/facegear_110.yaml"


@pytest.fixture(scope="module")
def design(tmp_path_factory):
    """`tehl run` of the shipped face gear at S1 and S3 on a 33-node grid (every figure unresolved there), with
    error bounds written in: h_c 1 %, h_min 2 %, μ 1 % (p_max stays unresolved)."""
    path = tmp_path_factory.mktemp("compare") / "a.h5"
    run = CliRunner().invoke(tehl, ["run", FACE_GEAR, "--grid", "33", "--points", "S1,S3", "--jobs", "1", "-o",
                                    str(path)])
    assert run.exit_code == 0, run.output
    with h5py.File(path, "r+") as h5:
        for name in h5["points"]:
            attrs = h5[f"points/{name}"].attrs
            bounds = {"error_bound_h_c": 0.01, "error_bound_h_min": 0.02, "error_bound_mu": 0.01,
                      "unresolved_h_c": 0.0, "unresolved_h_min": 0.0, "unresolved_mu": 0.0}
            for key, value in bounds.items():
                attrs[key] = value
            attrs["units"] = json.dumps({**json.loads(attrs["units"]), **dict.fromkeys(bounds, "1")})
    return path


def _variant(source, target, factors):
    """A copy of `source` with S1's scalars multiplied by `factors` (a design B known by construction)."""
    target.write_bytes(source.read_bytes())
    with h5py.File(target, "r+") as h5:
        attrs = h5["points/S1"].attrs
        for key, factor in factors.items():
            attrs[key] = attrs[key] * factor
    return target


def test_a_difference_is_significant_only_beyond_the_combined_estimates(design, tmp_path):
    """h_min moved by 3 of its bounds: beyond sqrt(e_a^2 + e_b^2) = 1.4 of them; h_c by 0.5: within; μ by 2 %
    against 1 % bounds (combined 1.43 %): beyond; p_max is unresolved: no estimate."""
    a = read_result(design)
    s1 = a.points["S1"].scalars
    e_h, e_c = s1["error_bound_h_min"], s1["error_bound_h_c"]
    b_path = _variant(design, tmp_path / "b.h5", {"h_min": 1 + 3 * e_h, "h_c": 1 + 0.5 * e_c, "mu": 1.02})
    found = {(d.point, d.quantity): d for d in differences(a, read_result(b_path))}
    h_min = found["S1", "h_min"]
    assert h_min.estimate == pytest.approx(math.hypot(e_h * s1["h_min"], e_h * s1["h_min"] * (1 + 3 * e_h)))
    assert h_min.significance is Significance.SIGNIFICANT
    assert found["S1", "h_c"].significance is Significance.NOT_SIGNIFICANT
    mu = found["S1", "mu"]
    assert mu.estimate == pytest.approx(0.01 * s1["mu"] * math.hypot(1.0, 1.02))
    assert mu.significance is Significance.SIGNIFICANT
    assert found["S1", "p_max"].significance is Significance.UNKNOWN
    assert found["S3", "h_min"].difference == 0.0
    assert found["S3", "h_min"].significance is Significance.NOT_SIGNIFICANT
    flagged = _variant(design, tmp_path / "c.h5", {"h_min": 1 + 3 * e_h})
    with h5py.File(flagged, "r+") as h5:
        h5["points/S1"].attrs["unresolved_h_min"] = 1.0  # B's h_min unresolved: no combined estimate
    unresolved = {(d.point, d.quantity): d for d in differences(a, read_result(flagged))}["S1", "h_min"]
    assert unresolved.significance is Significance.UNKNOWN


def test_the_command_prints_the_table_and_draws_the_path(design, tmp_path):
    b_path = _variant(design, tmp_path / "b.h5", {"h_min": 1.5})
    result = CliRunner().invoke(tehl, ["compare", str(design), str(b_path), "-o", str(tmp_path / "cmp.png")])
    assert result.exit_code == 0, result.output
    row = next(line for line in result.output.splitlines() if re.match(r"S1\s+h_min\s", line))
    assert row.split()[-1] == "yes" and (tmp_path / "cmp.png").stat().st_size > 10_000
    same = next(line for line in result.output.splitlines() if re.match(r"S3\s+h_min\s", line))
    assert same.endswith("no (within the estimates)")


@pytest.mark.parametrize(("args", "message"), [
    ((), "expected two or more result files"),
    (("-o", "x.bmp"), "expected a figure file ending in .png"),
])
def test_bad_use_exits_2_with_one_line(design, tmp_path, args, message):
    files = [str(design)] if not args else [str(design), str(design)]
    result = CliRunner().invoke(tehl, ["compare", *files, *args])
    assert result.exit_code == 2 and message in result.output and result.output.count("\n") == 1


def test_plain_contacts_are_compared_file_by_file(tmp_path):
    """A plain contact has no contact path: each quantity is drawn over the files (the path figure was left with
    empty panels), the point's values where the files hold them."""
    paths = [write_result(synthetic.run_result(), tmp_path / f"{name}.h5") for name in ("a", "b")]
    results = [read_result(path, fields=False) for path in paths]
    figure = comparison_figure(results, ["a", "b"])
    figure.canvas.draw()
    h_min = figure.axes[0]
    assert [tick.get_text() for tick in figure.axes[-1].get_xticklabels()] == ["a", "b"]  # the axes share x
    (line,) = [line for line in h_min.get_lines() if line.get_marker() == "o" and line.get_linestyle() == "-"]
    assert list(line.get_ydata()) == pytest.approx([0.6 * synthetic.H_C * 1e6] * 2)  # µm


def test_a_point_that_did_not_converge_is_not_compared(design, tmp_path):
    """A diverged point's scalars are its last iterate's (μ of 1e13 were seen): no difference, no verdict, not drawn."""
    b_path = _variant(design, tmp_path / "b.h5", {"mu": 1e15})
    with h5py.File(b_path, "r+") as h5:
        h5["points/S1"].attrs["converged"] = False
        h5["points/S1"].attrs["outcome"] = "diverged"
    found = {(d.point, d.quantity): d for d in differences(read_result(design), read_result(b_path))}
    mu = found["S1", "mu"]
    assert mu.significance is Significance.NOT_CONVERGED and math.isnan(mu.b) and math.isnan(mu.difference)
    assert found["S3", "mu"].significance is Significance.NOT_SIGNIFICANT  # the other point as before
    result = CliRunner().invoke(tehl, ["compare", str(design), str(b_path), "-o", str(tmp_path / "cmp.png")])
    assert result.exit_code == 0, result.output
    row = next(line for line in result.output.splitlines() if re.match(r"S1\s+mu\s", line))
    assert "not converged" in row and "e+1" not in row

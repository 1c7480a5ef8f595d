"""A thermal film state whose energy balance misses is never reported converged (solve.PointSolve.report,
ehl/energy_balance.py): at a solution of the discrete energy equation the balance closes to round-off."""

from __future__ import annotations

from click.testing import CliRunner

from facegear_tehl.cli import tehl
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.results import read_result

import synthetic

# The sliding ball-on-disc case with a Newtonian oil and the disc turning slowly backwards (SRR 2.01) on a 65-node
# grid: its loop stopped with the film's energy balance off by about 300 % (mu 144, p_max 6 p_h) and was reported
# converged, with exit 0.
UNBALANCED = (synthetic.CASES / "ball_on_disc_sliding.yaml").read_text().replace(
    "rheology: ree_eyring", "rheology: newtonian").replace("slide_roll_ratio: 1.0", "slide_roll_ratio: 2.01").replace(
    "grid: 129", "grid: 65")


def test_a_film_state_off_its_energy_balance_is_not_reported_converged(tmp_path):
    case = tmp_path / "unbalanced.yaml"
    case.write_text(UNBALANCED)
    out = tmp_path / "unbalanced.h5"
    result = CliRunner().invoke(tehl, ["run", str(case), "--jobs", "1", "-o", str(out)])
    point = read_result(out).points["contact"]
    imbalance = abs(point.scalars.get("energy_balance_error", 0.0))
    assert point.converged == (imbalance <= TUNING.max_energy_imbalance)
    assert not point.converged, point.message  # this film ends off its balance on every attempt
    assert result.exit_code == 3 and read_result(out).status == "not_converged"
    assert "energy balance is off by" in point.message

"""A coupled loop whose change stops falling finds which iteration stalls (coupled.CoupledLoop._relieve_stall): its
pressure cycled to the tolerance on the frozen film state. V-cycles that do not converge there are damped; a pressure
that converges leaves a limit cycle of the film state, whose relaxation is halved.

The contact is w36 of the wide envelope (a/b 46, 1.25 GPa, 0.5 m/s, SRR 1.6, thermal Ree-Eyring, 257 x 65). Its loop
ended after 40 outer iterations with the temperature change at 0.19 K against a tolerance of 0.13 K and the pressure
changing by 1.8e-2 per cycle: on its last frozen film state 260 V-cycles at the Gauss-Seidel / Jacobi under-relaxation
0.3 / 0.15 left the pressure change at 1.3e-3 - 5e-3 per cycle, while the film state on a frozen pressure contracted
by 0.68 per update and 0.15 / 0.1 converged that pressure by 0.3 per cycle (docs/tuning.md, cycle_damping)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from facegear_tehl.ehl import coupled
from facegear_tehl.ehl.anderson import Anderson
from facegear_tehl.ehl.convergence import History
from facegear_tehl.ehl.film_state import FilmState
from facegear_tehl.ehl.relaxation import Relaxation
from facegear_tehl.ehl.staged import solve_point
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import CONVERGED, Outcome, Status
from facegear_tehl.suites.envelope import ENERGY_BALANCE_LIMIT
from facegear_tehl.suites.wide_envelope import wide_cases


class _Pressure:
    """A pressure iteration whose cycles on a frozen film state end with `status`."""

    settings = SolverSettings()

    def __init__(self, status: Status, relaxation: Relaxation = Relaxation()):
        self.status, self.solver, self.cycled = status, SimpleNamespace(relaxation=relaxation), 0

    def cycle(self, index: int, max_cycles: int) -> Status:
        self.cycled = max_cycles
        return self.status


def _relieved(pressure: _Pressure) -> tuple[float, Status]:
    target = SimpleNamespace(index=0, model=SimpleNamespace(solve_energy=True))
    return coupled.CoupledLoop(target, pressure, History(cycles=2), 10, 313.15)._relieve_stall(0.5)


def test_v_cycles_that_do_not_converge_on_the_frozen_state_are_damped_not_the_film_state():
    pressure = _Pressure(Status(Outcome.NOT_CONVERGED, "not converged"))
    relaxation, status = _relieved(pressure)
    assert pressure.cycled == pressure.settings.max_cycles and status.outcome is Outcome.NOT_CONVERGED
    assert relaxation == 0.5  # the film state's step stays
    cycles = pressure.solver.relaxation
    assert cycles.under_gs == pytest.approx(TUNING.cycle_damping * Relaxation().under_gs)
    assert cycles.under_jd == pytest.approx(TUNING.cycle_damping * Relaxation().under_jd)
    assert cycles.xi_switch == Relaxation().xi_switch  # the switch between the two relaxations stays


@pytest.mark.parametrize(("status", "under_gs"), [
    (CONVERGED, Relaxation().under_gs),  # the pressure converges: a limit cycle of the film state
    (Status(Outcome.NOT_CONVERGED, "not converged"), TUNING.min_under_gs),  # V-cycles damped as far as they go
])
def test_otherwise_the_film_states_relaxation_is_halved(status, under_gs):
    pressure = _Pressure(status, Relaxation(under_gs=under_gs))
    relaxation, _ = _relieved(pressure)
    assert relaxation == 0.25 and pressure.solver.relaxation.under_gs == under_gs


@pytest.mark.slow
def test_a_thermal_loop_whose_v_cycles_stalled_reaches_its_tolerance():
    """w36 converges on 257 x 65 with its load balanced to 1e-3 and its energy conserved to 1 % (the heat its film
    carries out and conducts into the solids against the work of shear and compression, energy.py): a film state
    that the iteration has not reached does not balance its energy."""
    case = next(c for c in wide_cases() if c.name.startswith("w36_"))
    solution = solve_point(case.point(), case.lubricant(), case.settings(257, 65))
    assert solution.outcome is Outcome.CONVERGED, solution.message
    assert abs(solution.scalar("load_error")) <= 1e-3
    assert abs(solution.scalar("energy_balance_error")) <= ENERGY_BALANCE_LIMIT
    assert solution.scalar("thermal_iterations") < 40  # within one loop's cap, not at it


@pytest.mark.parametrize("energy", [True, False])
def test_the_change_a_halved_relaxation_is_judged_by_is_the_full_steps(energy):
    """The loop judges its tolerance and estimates its iteration error from the change of the plain step at the full
    relaxation, whatever a stall halved it to: the step over the relaxation scale is the same residual. (Judged on
    the halved step, a loop relaxed to 1/4 met a tolerance four times looser: the 90 degree face gear's S1 on 257 x 65
    then "converged" with h_min 203 nm, against 245 nm at the full relaxation and 247 nm on 513 x 129.)"""
    shape, t_in = (3, 4, 5), 313.0
    temperature, factor = np.full(shape, t_in + 10.0), np.ones(shape)
    ones = np.ones(shape)
    update = FilmState(temperature=temperature + 2.0 if energy else temperature, viscosity_factor=1.5 * ones,
                       dissipation=ones, velocity_x=None, velocity_y=None, stress_1=ones[:2], stress_2=ones[:2],
                       heat_flux_1=None, heat_flux_2=None, compression=None, change=2.0)
    rise = 10.0 if energy else None
    changes = {scale: coupled.next_film_state(Anderson(3), temperature, factor, update, scale, rise)[2:]
               for scale in (1.0, 0.5, 0.25)}
    thermal, viscous = changes[1.0]
    assert thermal == pytest.approx(TUNING.thermal_relaxation * 2.0 if energy else 0.0)
    assert viscous == pytest.approx(TUNING.viscosity_relaxation * np.log(1.5))
    for scale in (0.5, 0.25):
        assert changes[scale] == pytest.approx(changes[1.0])

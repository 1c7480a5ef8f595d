"""Damped Newton-Raphson solve of the coupled Reynolds + elasticity + load balance of a line contact.

The unknowns are all nodal pressures and H_0, solved together with the exact dense Jacobian
(`reynolds.ReynoldsSystem.jacobian`), as in the full-system Newton methods of Okamura (1982) and
Houpert & Hamrock (1986), with the Fischer-Burmeister complementarity form of the cavitation condition.
The step is damped (halved, at most `MAX_HALVINGS` times) until the merit function ||F||^2 decreases
(Armijo test with the constant ARMIJO) and the film stays positive. The balances are row-scaled once per solve
(`ReynoldsSystem.set_row_scale`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy import linalg

from facegear_tehl.line.reynolds import FilmCoefficients, ReynoldsSystem

MAX_HALVINGS = 12  # smallest damping 2^-12: a step that small that still fails means the start is too far
ARMIJO = 1e-4  # sufficient-decrease constant of the damped step (the usual textbook value)


@dataclass
class NewtonResult:
    u: np.ndarray
    residual: float  # largest |F| at the end
    iterations: int
    converged: bool
    history: list[float]


def newton(system: ReynoldsSystem, coefficients: Callable[[np.ndarray], FilmCoefficients], u0: np.ndarray,
           tolerance: float = 1e-10, max_iterations: int = 200) -> NewtonResult:
    """Solve F(u) = 0 from u0. `coefficients(P)` gives the film laws at nodal pressures P (all n nodes).

    Converged when max |F| < tolerance (F is dimensionless: a pressure over p_h, a scaled flux balance, a load
    fraction)."""
    u = u0.copy()
    system.set_row_scale(u, coefficients(system.pressure(u)))
    history: list[float] = []
    for iteration in range(max_iterations + 1):
        coef = coefficients(system.pressure(u))
        f, r, h = system.residual(u, coef)
        norm = float(np.max(np.abs(f)))
        history.append(norm)
        if not np.isfinite(norm):
            return NewtonResult(u, norm, iteration, False, history)
        if norm < tolerance:
            return NewtonResult(u, norm, iteration, True, history)
        if iteration == max_iterations:
            break
        merit = float(f @ f)
        jac = system.jacobian(u, coef, r, h)
        try:
            step = linalg.solve(jac, -f, check_finite=False)
        except linalg.LinAlgError:
            return NewtonResult(u, norm, iteration, False, history)
        damping = 1.0
        accepted = False
        for _ in range(MAX_HALVINGS + 1):
            trial = u + damping * step
            p_trial = system.pressure(trial)
            h_trial = system.film(p_trial, trial[-1])
            if np.all(h_trial > 0.0):
                f_trial, _, _ = system.residual(trial, coefficients(p_trial))
                trial_merit = float(f_trial @ f_trial)
                if np.isfinite(trial_merit) and trial_merit <= (1.0 - 2.0 * ARMIJO * damping) * merit:
                    accepted = True
                    break
            damping *= 0.5
        # no decrease along the Newton direction: take the smallest positive-film step (non-monotone escape
        # from a kink of the complementarity function) unless even that closes the film
        if not accepted and not np.all(h_trial > 0.0):
            return NewtonResult(u, norm, iteration, False, history)
        u = trial
    return NewtonResult(u, history[-1], max_iterations, False, history)

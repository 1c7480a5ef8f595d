r"""`solve_line`: steady EHL of a line contact (SI in, SI out), isothermal or thermal.

Problem (Hertzian units of `elastic.py`: X = x/b, P = p/p_h, H = h R/b^2):
    Reynolds, complementarity form (`reynolds.py`):  P >= 0, dQ/dX >= 0, P dQ/dX = 0,  Q = -e H^3 dP/dX + r H
    film (`elastic.py`):                              H = H_0 + X^2/2 - (1/pi) int P ln|X - S| dS
    load:                                             int P dX = pi/2
solved together by a damped Newton-Raphson iteration on all nodal pressures and H_0 (`newton.py`), with grid
sequencing: the problem is first solved on a coarse grid from a Hertz-like pressure and the larger of the
Ertel-Grubin and Martin films (`_hertz_start`, used only as a start; piezoviscous continuation if Newton fails),
then interpolated to finer grids. Thermal and Ree-Eyring films iterate on the finest grid (`_FilmIteration`).

Conventions: body 1 at z = 0 moves at u_1 = u_e (1 + SRR/2), body 2 at z = h at u_2 = u_e (1 - SRR/2), both
along +x (entrainment u_e = (u_1 + u_2)/2 > 0, inlet at x < 0). Load per unit length w' in N/m.
"""

from __future__ import annotations

from dataclasses import dataclass, field
import math

import numpy as np
from threadpoolctl import threadpool_limits

from facegear_tehl.line.elastic import hertz_line, influence_matrix, load_weights
from facegear_tehl.line.film import GeneralizedFilm, IsothermalNewtonian
from facegear_tehl.line.newton import NewtonResult, newton
from facegear_tehl.line.reynolds import ReynoldsSystem
from facegear_tehl.line.thermal import eyring_columns, film_flow, solve_energy
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.materials import Solid, reduced_modulus

RATE_RELAXATION = 0.5  # geometric under-relaxation of the Ree-Eyring shear rates (halves a rate jump in log)
MIN_RELAXATION = 0.05  # smallest under-relaxation of the temperature and rate updates (20 iterations per e-fold)
MAX_BACKOFFS = 4  # consecutive halvings of a film-state update after which a failing pressure solve stops the run
STRESS_TOLERANCE = 1e-3  # relative change of the Ree-Eyring shear stress per outer iteration, to stop
# largest temperature change applied per outer iteration, K: the viscosity changes by exp(beta 25) ~ 2-10 per
# step, which the pressure Newton follows; an isothermal Newtonian start with sliding heats by 1e4-1e5 K.
MAX_TEMPERATURE_STEP = 25.0
DEFAULT_DOMAIN = (-4.0, 1.5)  # x/b: inlet and outlet ends (Venner & Lubrecht 2000 use -4 .. 1.5 for line contacts)
COARSEST_NODES = 101  # first grid of the sequence: cheap (ms per Newton step) yet resolves the Hertz zone by 40
# Piezoviscous continuation (eta_bar^s, s from 0 to 1) if Newton fails from the Hertz start on the coarsest grid:
FIRST_EXPONENT_STEP = 0.125  # 8 steps: each changes ln(eta) by at most alpha p_h/8 ~ 2-4, within Newton's reach
MIN_EXPONENT_STEP = 1.0 / 256.0  # give up below this increment (64 halvings of the path would be needed)


@dataclass
class LineSolution:
    """Steady line-contact EHL solution, SI units (m, Pa, K, N/m)."""

    x: np.ndarray  # node positions, m
    p: np.ndarray  # pressure, Pa
    h: np.ndarray  # film thickness, m
    h_c: float  # film at x = 0 (the Hertz centre), m
    h_min: float  # smallest film over the nodes, m
    p_max: float  # largest pressure, Pa
    b: float  # Hertz half-width, m
    p_h: float  # Hertz maximum pressure, Pa
    load_per_length: float  # w', N/m
    converged: bool
    iterations: int  # Newton iterations on the finest grid (summed over outer thermal iterations)
    residual: float  # largest complementarity / load residual at the end
    friction: float  # traction coefficient mu = int tau_mid dx / w' (tau_mid: mean of the two wall stresses)
    thermal: bool = False
    dT_max: float = 0.0  # largest film temperature rise over the inlet temperature, K
    temperature: np.ndarray | None = None  # film temperature (n, layers), K (thermal only)
    z: np.ndarray | None = None  # cross-film layer centres as fractions of h (thermal only)
    surface_temperature_1: np.ndarray | None = None  # K
    surface_temperature_2: np.ndarray | None = None  # K
    heat_balance: dict[str, float] = field(default_factory=dict)  # W/m: generated, into solids, convected
    outer_iterations: int = 0
    message: str = ""


def hamrock_groups(radius: float, load_per_length: float, entrainment_speed: float, lubricant: Lubricant,
                   e_prime: float) -> tuple[float, float, float]:
    """(U, G, W') of Hamrock: U = eta_0 u_e/(E' R), G = alpha E', W' = w'/(E' R) (Hamrock, Schmid & Jacobson
    2004, Fundamentals of Fluid Film Lubrication, eqs. 17.38 and 18.72-18.74; alpha: the low-pressure
    pressure-viscosity coefficient of the chosen viscosity law)."""
    u = lubricant.viscosity * entrainment_speed / (e_prime * radius)
    g = lubricant.effective_alpha * e_prime
    w = load_per_length / (e_prime * radius)
    return u, g, w


def uniform_nodes(count: int, domain: tuple[float, float]) -> np.ndarray:
    """`count` equally spaced nodes over `domain` (in units of b)."""
    return np.linspace(domain[0], domain[1], count)


class _Level:
    """One grid of the sequence: nodes, influence matrix, system."""

    def __init__(self, nodes: np.ndarray, second_order: bool):
        self.x = nodes
        self.system = ReynoldsSystem(nodes, influence_matrix(nodes), load_weights(nodes), second_order)

    def start_from(self, x_prev: np.ndarray, p_prev: np.ndarray, h0: float) -> np.ndarray:
        p = np.interp(self.x, x_prev, p_prev)
        return np.concatenate([p[1:-1], [h0]])


def _grid_sequence(nodes: int) -> list[int]:
    counts = [nodes]
    while (counts[-1] - 1) // 2 + 1 >= COARSEST_NODES:
        counts.append((counts[-1] - 1) // 2 + 1)
    return counts[::-1]


def _hertz_start(level: _Level, radius: float, b: float, u: float, g: float, w: float) -> np.ndarray:
    """Hertz-like pressure and a film estimate: the larger of Ertel-Grubin's elastic-piezoviscous
    h_c = 1.95 R (U G)^{8/11} W'^{-1/11} (Grubin 1949) and Martin's rigid-isoviscous h = 4.9 R U/W' (Martin
    1916), at least positive everywhere. Only a start: the converged solution does not depend on it."""
    x = level.x
    grubin = 1.95 * (u * g) ** (8.0 / 11.0) * w ** (-1.0 / 11.0)
    martin = 4.9 * u / w
    h_c = max(grubin, martin) * radius * radius / b**2
    # a light load spreads the pressure over the hydrodynamic length sqrt(2 R h) = b sqrt(2 H) > b: a
    # semi-ellipse of that half-width c and of the same load (height 1/c)
    c = max(1.0, math.sqrt(2.0 * h_c))
    p = np.sqrt(np.clip(1.0 - (x / c) ** 2, 0.0, None)) / c
    h_hertz = level.system.film(p, 0.0)
    h0 = h_c - float(np.interp(0.0, x, h_hertz))
    h0 = max(h0, 0.5 * h_c - float(h_hertz.min()))
    return np.concatenate([p[1:-1], [h0]])


def _continuation(level: _Level, coefficients, u_start: np.ndarray, tolerance: float,
                  max_iterations: int) -> NewtonResult:
    """Piezoviscous continuation: solve with eta_bar^s for s = 1/8, 2/8, ... 1, each from the previous
    solution, halving the increment of s (down to MIN_EXPONENT_STEP) where Newton fails. At s -> 0 the film is
    isoviscous and Newton converges from the Hertz start; the final s = 1 solution is the physical one."""
    s, step = 0.0, FIRST_EXPONENT_STEP
    u = u_start
    result = NewtonResult(u_start, math.inf, 0, False, [])
    while s < 1.0:
        target = min(1.0, s + step)
        trial = newton(level.system, coefficients.with_exponent(target), u, tolerance, max_iterations)
        if trial.converged:
            s, u, result = target, trial.u, trial
            step = min(2.0 * step, FIRST_EXPONENT_STEP)
        else:
            step *= 0.5
            if step < MIN_EXPONENT_STEP:
                return trial
    return result


def _solve_sequence(levels: list[_Level], coefficients, start, tolerance: float,
                    max_iterations: int) -> tuple[_Level, NewtonResult, str]:
    """Newton on each grid of the sequence, each started from the previous solution. Until one grid has
    converged, each grid is started from `start(level)` (the Hertz-like start), with piezoviscous continuation
    if that fails (`_continuation`): a grid too coarse for a thin, heavily loaded film hands over to the next."""
    note = ""
    result: NewtonResult | None = None
    prev: _Level | None = None
    for level in levels:
        if result is not None and result.converged:
            u0 = level.start_from(prev.x, prev.system.pressure(result.u), float(result.u[-1]))
            result = newton(level.system, coefficients, u0, tolerance, max_iterations)
        else:
            u0 = start(level)
            result = newton(level.system, coefficients, u0, tolerance, max_iterations)
            if not result.converged:
                result = _continuation(level, coefficients, u0, tolerance, max_iterations)
                note = f"piezoviscous continuation on the {level.x.size}-node grid; "
        prev = level
    return prev, result, note


def solve_line(
    radius: float,
    load_per_length: float,
    entrainment_speed: float,
    slide_roll_ratio: float,
    lubricant: Lubricant,
    body_1: Solid,
    body_2: Solid,
    *,
    nodes: int = 801,
    domain: tuple[float, float] = DEFAULT_DOMAIN,
    thermal: bool = False,
    layers: int = 12,
    second_order: bool = True,
    tolerance: float = 1e-10,
    max_iterations: int = 150,
    thermal_tolerance: float = 1e-3,
    max_outer_iterations: int = 60,
    relaxation: float = 0.7,
) -> LineSolution:
    """Steady EHL of a line contact (reduced radius `radius`, m; load `load_per_length`, N/m; entrainment
    speed u_e, m/s; slide-to-roll ratio (u_1 - u_2)/u_e). `nodes` equally spaced nodes over `domain` (x/b).

    thermal=False: isothermal at the inlet temperature, Newtonian (lubricant.rheology 'newtonian') or
    Ree-Eyring (generalized Reynolds, `film.py`). thermal=True: energy equation across the film with `layers`
    cells, heat into the solids by the Jaeger moving-source integral (`thermal.py`); the film temperature is
    iterated (under-relaxed by `relaxation`) until it changes by less than thermal_tolerance x max(rise, 1 K).
    The isothermal Newtonian solution (grid sequence) is the start of the thermal or non-Newtonian iteration,
    which then runs on the finest grid only.
    """
    if entrainment_speed <= 0.0:
        raise ValueError(f"entrainment speed must be positive, got {entrainment_speed}")
    e_prime = reduced_modulus(body_1, body_2)
    b, p_h = hertz_line(load_per_length, radius, e_prime)
    lam = 12.0 * lubricant.viscosity * entrainment_speed * radius**2 / (b**3 * p_h)
    u_grp, g_grp, w_grp = hamrock_groups(radius, load_per_length, entrainment_speed, lubricant, e_prime)
    with threadpool_limits(limits=1):
        levels = [_Level(uniform_nodes(n, domain), second_order) for n in _grid_sequence(nodes)]
        def start(level: _Level) -> np.ndarray:
            return _hertz_start(level, radius, b, u_grp, g_grp, w_grp)
        coefficients = IsothermalNewtonian(lubricant, p_h, lam)
        level, result, note = _solve_sequence(levels, coefficients, start, tolerance, max_iterations)
        if (not thermal and lubricant.rheology == "newtonian") or not result.converged:
            return _isothermal_solution(level, result, note, radius, b, p_h, load_per_length, lubricant,
                                        entrainment_speed, slide_roll_ratio)
        outer = _FilmIteration(level, result, note, radius, b, p_h, load_per_length, lubricant, body_1, body_2,
                               entrainment_speed, slide_roll_ratio, layers, thermal)
        return outer.run(tolerance, max_iterations, thermal_tolerance, max_outer_iterations, relaxation)


def _isothermal_solution(level: _Level, result: NewtonResult, note: str, radius: float, b: float, p_h: float,
                         load_per_length: float, lubricant: Lubricant, u_e: float, srr: float) -> LineSolution:
    system = level.system
    p_bar = system.pressure(result.u)
    h_bar = system.film(p_bar, float(result.u[-1]))
    x = level.x * b
    p = p_bar * p_h
    h = h_bar * b * b / radius
    # Newtonian traction: the mean of the two wall stresses is eta (u_2 - u_1)/h (the Poiseuille parts cancel)
    eta = lubricant.viscosity_at(p)
    sliding = srr * u_e
    tau = eta * sliding / h
    friction = float(np.trapezoid(tau, x) / load_per_length)
    message = note + ("converged" if result.converged else
                      f"not converged: residual {result.residual:.2e} after {result.iterations} Newton steps")
    return LineSolution(
        x=x, p=p, h=h,
        h_c=float(np.interp(0.0, x, h)), h_min=float(h.min()), p_max=float(p.max()),
        b=b, p_h=p_h, load_per_length=load_per_length,
        converged=result.converged, iterations=result.iterations, residual=result.residual,
        friction=friction, message=message,
    )


class _FilmIteration:
    """Outer iteration of the film state (temperature field, Ree-Eyring ratio eta*/eta) and the pressure on the
    finest grid: pressure (Newton, generalized Reynolds at the frozen state) -> Ree-Eyring columns -> energy
    equation -> under-relaxed temperature, until the temperature settles."""

    def __init__(self, level: _Level, result: NewtonResult, note: str, radius: float, b: float, p_h: float,
                 load: float, lubricant: Lubricant, body_1: Solid, body_2: Solid, u_e: float, srr: float,
                 layers: int, thermal: bool):
        if thermal and not abs(srr) < 2.0:
            raise ValueError(f"slide-to-roll ratio {srr}: the thermal model needs both surfaces moving (|SRR| < 2)")
        self.level, self.system = level, level.system
        self.u = result.u
        self.iterations = result.iterations
        self.note = note
        self.radius, self.b, self.p_h, self.load = radius, b, p_h, load
        self.lubricant, self.body_1, self.body_2 = lubricant, body_1, body_2
        self.u_1 = u_e * (1.0 + 0.5 * srr)
        self.u_2 = u_e * (1.0 - 0.5 * srr)
        self.thermal = thermal
        n = level.x.size
        self.temperature = np.full((n, layers), lubricant.inlet_temperature)
        self.eyring = lubricant.eyring_stress if lubricant.rheology == "ree_eyring" else math.inf
        self.rate = None if not math.isfinite(self.eyring) else np.zeros((n, layers))
        self.x = level.x * b

    def _state(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        p_bar = self.system.pressure(self.u)
        h_bar = self.system.film(p_bar, float(self.u[-1]))
        return p_bar, h_bar, p_bar * self.p_h, h_bar * self.b * self.b / self.radius

    def _update_rate(self, p: np.ndarray, h: np.ndarray) -> np.ndarray | None:
        """Shear rate of every layer (Ree-Eyring) at the current pressure, film and temperature."""
        if self.rate is None:
            return None
        eta = self.lubricant.viscosity_at(np.broadcast_to(p[:, None], self.temperature.shape), self.temperature)
        rate, _ = eyring_columns(eta, h, np.gradient(p, self.x), self.u_2 - self.u_1, self.eyring)
        return rate

    def _advance_rate(self, p_bar: np.ndarray, p: np.ndarray, h: np.ndarray, weight: float) -> float:
        """Move the Ree-Eyring shear rates towards those of the current pressure, film and temperature
        (geometric under-relaxation by `weight`); return the largest change of the film's shear stress eta* rate
        relative to its largest value (0 for a Newtonian film)."""
        new = self._update_rate(p, h)
        if new is None:
            return 0.0
        old = self.rate
        floor = 1e-300  # keeps log() finite where a layer does not shear
        self.rate = np.exp((1.0 - weight) * np.log(np.maximum(old, floor)) + weight * np.log(np.maximum(new, floor)))
        tau_new = self._film().layer_laws(p_bar)[1] * self.rate
        tau_old = self._film(old).layer_laws(p_bar)[1] * old
        return float(np.abs(tau_new - tau_old).max() / np.abs(tau_new).max())

    def _film(self, rate: np.ndarray | None = None) -> GeneralizedFilm:
        return GeneralizedFilm(self.lubricant, self.p_h, self.b, self.radius, self.u_1, self.u_2,
                               self.temperature, self.rate if rate is None else rate, self.eyring)

    def run(self, tolerance: float, max_iterations: int, thermal_tolerance: float, max_outer: int,
            relaxation: float) -> LineSolution:
        energy = None
        converged = False
        change = previous = math.inf
        omega, rate_weight = relaxation, RATE_RELAXATION
        result = None
        backoffs = 0
        _, _, p, h = self._state()
        self.rate = self._update_rate(p, h)
        saved = (self.temperature, self.rate)
        outer = 0
        while outer < max_outer:
            outer += 1
            film = self._film()
            result = newton(self.system, film, self.u, tolerance, max_iterations)
            self.iterations += result.iterations
            if not result.converged:
                # the last film-state update was too large for the pressure: take half of it, damp harder
                if backoffs >= MAX_BACKOFFS:
                    break
                backoffs += 1
                self._back_off(*saved)
                omega, rate_weight = max(MIN_RELAXATION, 0.5 * omega), max(MIN_RELAXATION, 0.5 * rate_weight)
                continue
            backoffs = 0
            self.u = result.u
            p_bar, h_bar, p, h = self._state()
            saved = (self.temperature, self.rate)
            stress_change = self._advance_rate(p_bar, p, h, rate_weight)
            film = self._film()
            if not self.thermal:
                change = stress_change
                if change < thermal_tolerance:
                    converged = True
                    break
                continue
            cells = film.integrals(p_bar)
            flow = film_flow(cells, self.x, h, p, self.system.upwind, self._cavitated(film, p_bar, h_bar))
            energy = solve_energy(self.x, h, p, cells, flow, self.temperature, self.lubricant, self.body_1,
                                  self.body_2, self.u_1, self.u_2)
            delta = energy.temperature - self.temperature
            change = float(np.abs(delta).max())
            rise = float(energy.temperature.max() - self.lubricant.inlet_temperature)
            if change > previous:  # the iteration overshoots: damp it harder (adaptive under-relaxation)
                omega = max(MIN_RELAXATION, 0.5 * omega)
            else:
                omega = min(relaxation, 1.25 * omega)
            previous = change
            self.temperature = self.temperature + omega * np.clip(delta, -MAX_TEMPERATURE_STEP,
                                                                  MAX_TEMPERATURE_STEP)
            if change < thermal_tolerance * max(rise, 1.0) and stress_change < STRESS_TOLERANCE:
                converged = True
                break
        return self._solution(result, energy, converged and result.converged, outer, change)

    def _back_off(self, temperature: np.ndarray, rate: np.ndarray | None) -> None:
        """Half of the last film-state update, back towards the `temperature` (K) and Ree-Eyring `rate` it started
        from: the temperatures arithmetically, the rates geometrically."""
        self.temperature = 0.5 * (temperature + self.temperature)
        if self.rate is not None and rate is self.rate:
            # no film state has been solved yet (the first pressure solve, at the rates of the Newtonian
            # start): nothing to fall back to, so halve the Ree-Eyring rates themselves, a step back
            # towards the Newtonian film the grid sequence converged (801 nodes at 10 m/s need it)
            self.rate = 0.5 * self.rate
        elif self.rate is not None:
            self.rate = np.sqrt(np.maximum(rate, 1e-300) * np.maximum(self.rate, 1e-300))

    def _cavitated(self, film: GeneralizedFilm, p_bar: np.ndarray, h_bar: np.ndarray) -> np.ndarray:
        """Nodes past the pressure peak with P = 0 and an excess of outflow (film rupture)."""
        balance = np.zeros(p_bar.size)
        balance[1:-1] = self.system.flux_residual(p_bar, h_bar, film(p_bar))
        scale = float(np.abs(balance).max()) or 1.0
        past_peak = np.arange(p_bar.size) > int(np.argmax(p_bar))
        return past_peak & (p_bar <= 1e-9) & (balance > 1e-9 * scale)

    def _solution(self, result: NewtonResult | None, energy, converged: bool, outer: int,
                  change: float) -> LineSolution:
        p_bar, h_bar, p, h = self._state()
        film = self._film()
        cells = film.integrals(p_bar)
        p_x = np.gradient(p, self.x)
        tau_mid = cells.wall_stress(h, p_x) + 0.5 * p_x * h
        friction = float(-np.trapezoid(tau_mid, self.x) / self.load)
        kind = "thermal" if self.thermal else "isothermal Ree-Eyring"
        if converged:
            message = self.note + f"{kind}: converged in {outer} outer iterations"
        elif result is not None and not result.converged:
            message = self.note + f"{kind}: pressure not converged at outer iteration {outer}"
        else:
            message = self.note + f"{kind}: not converged after {outer} outer iterations (change {change:.2e})"
        solution = LineSolution(
            x=self.x, p=p, h=h,
            h_c=float(np.interp(0.0, self.x, h)), h_min=float(h.min()), p_max=float(p.max()),
            b=self.b, p_h=self.p_h, load_per_length=self.load,
            converged=converged, iterations=self.iterations,
            residual=result.residual if result is not None else math.inf,
            friction=friction, thermal=self.thermal, outer_iterations=outer, message=message,
        )
        if energy is not None:
            t0 = self.lubricant.inlet_temperature
            solution.temperature = self.temperature
            solution.z = (np.arange(self.temperature.shape[1]) + 0.5) / self.temperature.shape[1]
            solution.surface_temperature_1 = energy.surface_1
            solution.surface_temperature_2 = energy.surface_2
            solution.dT_max = float(self.temperature.max() - t0)
            solution.heat_balance = {
                "generated": energy.generated, "to_solid_1": energy.to_solid_1, "to_solid_2": energy.to_solid_2,
                "convected": energy.convected,
            }
        return solution

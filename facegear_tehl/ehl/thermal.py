"""Thermal and non-Newtonian state of the film on the finest grid (SI units).

One `update` maps the current pressure and film to the across-film state that the generalised Reynolds
equation needs (temperature and eta*/eta per layer, flow.py):
1. Newtonian viscosity per layer, eta(p, T_k) (lubricant.py);
2. shear stress, shear rate, velocity and dissipation across the film (rheology.py), once per update;
3. (thermal models) the energy equation in the film with the convection across the layers that continuity
   requires (energy.py; conductivity k(p) of lubricant.py, one value per column), coupled to the two solids by
   the high-Péclet moving heat source (jaeger.py) through the wall heat fluxes of the film's discrete balance:
   T_i = T_0 + (1/(sqrt(pi) B_i)) \\int q_i (x - s)^(-1/2) ds, B_i = sqrt(k_i rho_i c_i |u_ix|), applied along
   x with the x component of each surface's velocity (face gear surfaces move within 2 deg of x). A surface
   nearly at rest (Pe < 1) is given the effusivity of Pe = 1, where the high-Péclet kernel would otherwise
   diverge: a bounded, conservative estimate.
The surfaces (under-relaxed) and then the film's interior layers are iterated TUNING.inner_iterations times, so that
the state returned solves the film's discrete energy equation for its own surfaces (its energy budget closes,
energy.energy_budget).

`thermal_choice` picks the thermal model of `solver.thermal: auto` from a correlation fitted to the project's own
solutions (the heating number `heating_number`: the inlet's thermal loading and the Hertz zone's sliding heat), and
says why.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
import math

from numba import njit
import numpy as np

from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl import energy, jaeger, rheology
from facegear_tehl.ehl.film_state import FilmState
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.heat import blok_flash_temperature
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.lubricant_constants import ROELANDS
from facegear_tehl.lubricant_laws import (
    density_ratio_at,
    roelands_pressure_factor_at,
    roelands_ratio,
    roelands_temperature_coefficient,
    roelands_temperature_factor_at,
    viscosity_ratio_at,
    viscosity_temperature_coefficient_at,
)
from facegear_tehl.materials import Solid


@njit(cache=True)
def layer_viscosity(pressure, temperature, law, coefficient, temperature_factor):
    """(eta/eta_0, beta = -d ln(eta)/dT in 1/K) at every layer node (nz, ny, nx) of the temperatures (K) over the
    pressures (ny, nx), Pa: the numbers of lubricant_laws.viscosity_ratio_at and viscosity_temperature_coefficient_at
    (bit-identical), with the Roelands pressure factor once per column and the temperature factor once per node for
    both; a node at the temperature of the one below it (an isothermal film) takes its ratio, one at the temperature
    factored last (every column of an isothermal film) its factor. `coefficient` False: beta is not evaluated (an
    empty array). `temperature_factor`: the Roelands temperature factors of these temperatures when known
    (flow.temperature_factors of the film state the pressure was cycled on: the same numbers), else an empty array.
    21 -> 10 ms for both on 513 x 65 x 9 against the node-by-node laws; 6.7 -> 3.6 ms with the factors given."""
    nz, ny, nx = temperature.shape
    ratio = np.empty((nz, ny, nx))
    beta = np.empty((nz, ny, nx) if coefficient else (0, 0, 0))
    roelands = law[0] == ROELANDS
    known = temperature_factor.size > 0
    last_t, factor = math.nan, 1.0  # the last temperature factored and its factor
    for j in range(ny):
        for i in range(nx):
            p = pressure[j, i]
            pressure_factor = roelands_pressure_factor_at(p, law)
            for k in range(nz):
                t = temperature[k, j, i]
                if k > 0 and t == temperature[k - 1, j, i]:
                    ratio[k, j, i] = ratio[k - 1, j, i]
                    if coefficient:
                        beta[k, j, i] = beta[k - 1, j, i]
                elif roelands:
                    if known:
                        factor = temperature_factor[k, j, i]
                    elif t != last_t:
                        last_t, factor = t, roelands_temperature_factor_at(t, law)
                    ratio[k, j, i] = roelands_ratio(pressure_factor, factor, law)
                    if coefficient:
                        beta[k, j, i] = roelands_temperature_coefficient(pressure_factor, factor, t, law)
                else:
                    ratio[k, j, i] = viscosity_ratio_at(p, t, law)
                    if coefficient:
                        beta[k, j, i] = viscosity_temperature_coefficient_at(p, t, law)
    return ratio, beta


@njit(cache=True)
def heat_coefficients(pressure, temperature, velocity_x, velocity_y, grad_x, grad_y, dissipation, beta, thinning, law,
                      expansion, t_inlet, density, specific_heat):
    """The energy equation's coefficients at every layer node (nz, ny, nx) of the temperatures (K) over the pressures
    and their gradients (ny, nx; Pa, Pa/m), in one pass:
    - the compression coefficient beta_T (u . grad p), W/(m^3 K), with the expansivity beta_T = eps_T/(1 - eps_T (T -
      T_in)) of the density's linear temperature factor (`expansion` eps_T, 1/K; u the layer velocity, m/s);
    - rho c (J/(m^3 K)) with rho = `density` rho_0 times lubricant_laws.density_ratio_at and c = `specific_heat`;
    - the sensitivity -d(dissipation)/dT at fixed shear rate, dissipation beta thinning (W/(m^3 K); beta =
      -d ln(eta)/dT, thinning = d ln(dissipation)/d ln(eta), rheology.shear_state).
    The same operations as their NumPy expressions (bit-identical), one pass instead of ~15 (7 -> 2 ms on 513 x 65 x 9).
    """
    nz, ny, nx = temperature.shape
    compression = np.empty((nz, ny, nx))
    rho_c = np.empty((nz, ny, nx))
    sensitivity = np.empty((nz, ny, nx))
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                t = temperature[k, j, i]
                expansivity = expansion / (1.0 - expansion * (t - t_inlet))
                compression[k, j, i] = expansivity * (velocity_x[k, j, i] * grad_x[j, i]
                                                      + velocity_y[k, j, i] * grad_y[j, i])
                rho_c[k, j, i] = density * density_ratio_at(pressure[j, i], t, law) * specific_heat
                sensitivity[k, j, i] = dissipation[k, j, i] * beta[k, j, i] * thinning[k, j, i]
    return compression, rho_c, sensitivity


@njit(cache=True)
def relaxed_steps(temperature, updated, thermal_weight, viscosity_weight, x, f):
    """The outer loop's iterate and plain step (solve._next_film_state) in one pass, flat (2 n,) arrays x and f in
    place: x = (T, ln(eta*/eta)), f = (thermal_weight (T_u - T), viscosity_weight (ln(eta*/eta)_u - ln(eta*/eta))),
    with the temperatures (K, n entries) and their update `updated` given, and the logarithms of eta*/eta and of its
    update already in x[n:] and f[n:] (NumPy's, in place). Returns the largest |step| of each half (NaN if one of
    its steps is): the numbers of the NumPy expressions in one pass instead of about twelve."""
    size = temperature.size
    t, u = temperature.ravel(), updated.ravel()
    largest_t = largest_f = 0.0
    for n in range(size):
        x[n] = t[n]
        step = thermal_weight * (u[n] - t[n])
        f[n] = step
        if not abs(step) <= largest_t and largest_t == largest_t:  # a NaN step stays NaN, as NumPy's max
            largest_t = abs(step)
    for n in range(size, 2 * size):
        step = viscosity_weight * (f[n] - x[n])
        f[n] = step
        if not abs(step) <= largest_f and largest_f == largest_f:
            largest_f = abs(step)
    return largest_t, largest_f


@dataclass(frozen=True)
class _Shear:
    """The shear state of one update (rheology.shear_state's outputs; layer fields (nz, ny, nx), empty where not
    evaluated) and beta = -d ln(eta)/dT (1/K) of the Newtonian viscosity per layer node."""

    viscosity_factor: np.ndarray  # eta*/eta
    dissipation: np.ndarray  # W/m^3
    velocity_x: np.ndarray  # m/s
    velocity_y: np.ndarray  # m/s
    stress_1: np.ndarray  # (2, ny, nx), Pa
    stress_2: np.ndarray  # (2, ny, nx), Pa
    thinning: np.ndarray  # d ln(dissipation)/d ln(eta)
    beta: np.ndarray  # 1/K


class FilmThermalModel:
    """Across-film state on a uniform (ny, nx) grid with node coordinates x, y (m)."""

    first_column = 0  # the energy equation is solved from this column on (outlet.py: a patch's inflow columns)

    def __init__(self, x: np.ndarray, y: np.ndarray, layers: int, lubricant: Lubricant, point: ContactPoint,
                 solve_energy: bool, newtonian_below: float = 0.0):
        """`layers`: odd number of layer nodes across the film; `point` gives the solids, their surface velocities
        and the Hertz half-width; `solve_energy`: False for an isothermal (Ree-Eyring) film; `newtonian_below`: the
        columns whose Newtonian wall stresses stay below this multiple of tau_0 are taken as Newtonian
        (rheology.shear_state; 0: none)."""
        if layers < 3 or layers % 2 == 0:
            raise ValueError(f"layers across the film must be odd and >= 3, got {layers}")
        self.x, self.y = x, y
        self.dx, self.dy = float(x[1] - x[0]), float(y[1] - y[0])
        self.layers = layers
        self.lubricant = lubricant
        self.velocity_1 = np.asarray(point.velocity_1, dtype=float)
        self.velocity_2 = np.asarray(point.velocity_2, dtype=float)
        self.solve_energy = solve_energy
        self.law = lubricant.law_parameters()
        self.t_inlet = lubricant.inlet_temperature
        self.tau0 = lubricant.eyring_stress if lubricant.rheology == "ree_eyring" else math.inf
        self.newtonian_below = newtonian_below
        self.matrix = jaeger.influence_matrix(x.size, self.dx)
        self._stress = None  # surface-1 shear stress of the last update: the warm start of the next
        # the inputs of the wall heat fluxes of the last deferred_updates updates made without them (`completed`):
        # (the update's dissipation, its temperatures, the energy kernels' arguments; without the energy equation
        # the film and the conductivity)
        self._deferred: list[tuple[np.ndarray, np.ndarray, tuple]] = []
        half_width = point.hertz.b
        self.effusivity = tuple(self._effusivity(body, float(v[0]), half_width)
                                for body, v in ((point.body_1, self.velocity_1), (point.body_2, self.velocity_2)))

    @staticmethod
    def _effusivity(body: Solid, speed: float, half_width: float) -> float:
        """B = sqrt(k rho c |u|), with |u| at least the speed of Pe = u b/(2 kappa) = 1."""
        slowest = 2.0 * body.thermal_diffusivity / half_width
        return body.thermal_effusivity_speed(max(abs(speed), slowest))

    def initial_temperature(self) -> np.ndarray:
        return np.full((self.layers, self.y.size, self.x.size), self.t_inlet)

    def _surface(self, flux: np.ndarray, index: int, speed: float) -> np.ndarray:
        return self.t_inlet + jaeger.surface_temperature_rise(flux, self.dx, self.effusivity[index],
                                                              matrix=self.matrix, reverse=speed < 0.0)

    def update(self, pressure: np.ndarray, film: np.ndarray, temperature: np.ndarray,
               sweep_tolerance: float = TUNING.energy_sweep_tolerance, wall_fluxes: bool = True,
               temperature_factor: np.ndarray | None = None) -> FilmState:
        """The film state for pressure (Pa) and film (m) starting from the layer temperatures (K).

        The temperature moves by at most TUNING.max_temperature_step per update (a continuation in temperature:
        a Newtonian film under heavy sliding would otherwise overshoot by thousands of kelvin before the
        viscosity has dropped). `sweep_tolerance` (K): the energy equation's sweeps stop once one changes the
        temperatures by less (at least TUNING.energy_min_sweeps, at most TUNING.energy_sweeps, never below
        energy_sweep_tolerance). `wall_fluxes` False: the wall heat fluxes of the result are left out (None) until
        `completed` asks for them: an outer loop needs them only for the state it ends on, and they cost a sweep
        (on the 513 x 65 finest grid of S3 of the default face gear case 1.9 of its 8.2 s). `temperature_factor`:
        the Roelands temperature factors of `temperature` if known (`layer_viscosity`), of its shape."""
        start = temperature
        p = np.ascontiguousarray(np.maximum(pressure, 0.0))
        grad_y, grad_x = np.gradient(p, self.dy, self.dx)
        temperature = temperature.copy()
        shear = self._shear(p, film, grad_x, grad_y, temperature, temperature_factor)
        conductivity = self.lubricant.conductivity_at(p)  # (ny, nx): one k per column (p is constant across the film)
        change, rho_c, compression = 0.0, None, None
        if self.solve_energy:
            heat = heat_coefficients(p, temperature, shear.velocity_x, shear.velocity_y, grad_x, grad_y,
                                     shear.dissipation, shear.beta, shear.thinning, self.law,
                                     self.lubricant.thermal_expansion, self.t_inlet, self.lubricant.density,
                                     self.lubricant.specific_heat)
            compression_coefficient, rho_c, sensitivity = heat
            kernel_args = self._energy_arguments(shear, rho_c, sensitivity, compression_coefficient, temperature,
                                                 conductivity, film)
            change = self._film_passes(temperature, start, kernel_args, sweep_tolerance)
            q1, q2 = self._wall_fluxes(wall_fluxes, shear.dissipation, temperature, kernel_args)
            compression = compression_coefficient * temperature
        else:  # no energy equation: the flux of the temperatures as they are
            q1, q2 = self._wall_fluxes(wall_fluxes, shear.dissipation, temperature, (film, conductivity))
        self._stress = shear.stress_1
        return FilmState(
            temperature=temperature,
            viscosity_factor=shear.viscosity_factor,
            dissipation=shear.dissipation,
            velocity_x=shear.velocity_x if self.solve_energy else None,
            velocity_y=shear.velocity_y if self.solve_energy else None,
            stress_1=shear.stress_1,
            stress_2=shear.stress_2,
            heat_flux_1=q1,
            heat_flux_2=q2,
            compression=compression,
            change=change,
            heat_capacity=rho_c,
        )

    def _shear(self, p: np.ndarray, film: np.ndarray, grad_x: np.ndarray, grad_y: np.ndarray,
               temperature: np.ndarray, temperature_factor: np.ndarray | None) -> _Shear:
        """The shear state once per update, from the entry temperatures: the outer loop iterates it with the
        pressure (re-evaluating it between the energy passes couples the temperature of the inlet's stagnation
        layers to the velocity across the layers without the outer loop's relaxation: a period-2 flicker of 1-1.5 K
        on the 257 x 65 face gear points S2-S4). Velocities and thinning factors only for the energy equation
        (rheology.shear_state: empty, not evaluated)."""
        shape = temperature.shape
        layers = shape if self.solve_energy else (0, 0, 0)
        warm = self._stress is not None
        shear = _Shear(viscosity_factor=np.empty(shape), dissipation=np.empty(shape), velocity_x=np.empty(layers),
                       velocity_y=np.empty(layers), stress_1=self._stress.copy() if warm else np.zeros((2,) + p.shape),
                       stress_2=np.empty((2,) + p.shape), thinning=np.empty(layers), beta=np.empty(0))
        known = temperature_factor is not None and temperature_factor.shape == shape
        ratio, beta = layer_viscosity(p, temperature, self.law, self.solve_energy,
                                      temperature_factor if known else np.empty((0, 0, 0)))
        eta = self.lubricant.viscosity * ratio
        rheology.shear_state(p, film, np.ascontiguousarray(grad_x), np.ascontiguousarray(grad_y), eta,
                             self.velocity_1, self.velocity_2, self.tau0, warm, shear.viscosity_factor,
                             shear.dissipation, shear.velocity_x, shear.velocity_y, shear.stress_1, shear.stress_2,
                             shear.thinning, self.newtonian_below)
        return replace(shear, beta=beta)

    def _energy_arguments(self, shear: _Shear, rho_c: np.ndarray, sensitivity: np.ndarray,
                          compression_coefficient: np.ndarray, temperature: np.ndarray, conductivity: np.ndarray,
                          film: np.ndarray) -> tuple:
        """The arguments of the energy kernels (energy.wall_fluxes, energy.sweep_columns) after the temperatures:
        the transport fluxes and the parts of the balance fixed during the update."""
        fluxes = energy.transport_fluxes(shear.velocity_x, shear.velocity_y, rho_c, film, self.dx, self.dy)[:3]
        fixed = energy.fixed_parts(fluxes[2], shear.dissipation, sensitivity, temperature.copy(),
                                   compression_coefficient, conductivity, film)
        return (*fluxes, *fixed, conductivity, film, self.dx, self.dy, self.t_inlet)

    def _film_passes(self, temperature: np.ndarray, start: np.ndarray, kernel_args: tuple,
                     sweep_tolerance: float) -> float:
        """inner_iterations passes (in place on `temperature`, K): the surfaces from the heat fluxes of the film as
        it stands, then the film's interior for them, so that the state returned solves the film's discrete energy
        equation for its own surfaces; within TUNING.max_temperature_step of `start`. Returns the last pass's largest
        change (K)."""
        q1, q2 = np.empty(temperature.shape[1:]), np.empty(temperature.shape[1:])
        w = TUNING.surface_relaxation
        change = 0.0
        for _ in range(TUNING.inner_iterations):
            before = temperature.copy()
            energy.wall_fluxes(temperature, *kernel_args, q1, q2)
            temperature[0] += w * (self._surface(q1, 0, float(self.velocity_1[0])) - temperature[0])
            temperature[-1] += w * (self._surface(q2, 1, float(self.velocity_2[0])) - temperature[-1])
            energy.sweep_columns(temperature, *kernel_args, TUNING.energy_sweeps,
                                 max(sweep_tolerance, TUNING.energy_sweep_tolerance), TUNING.energy_min_sweeps,
                                 self.first_column)
            step = TUNING.max_temperature_step
            np.clip(temperature, start - step, start + step, out=temperature)
            change = float(np.abs(temperature - before).max())
        return change

    def _wall_fluxes(self, now: bool, dissipation: np.ndarray, temperature: np.ndarray,
                     kernel_args: tuple) -> tuple[np.ndarray | None, np.ndarray | None]:
        """The wall heat fluxes (W/m^2) of the update's temperatures if `now`, else (None, None) with their inputs
        kept for `completed` (`kernel_args`: the energy kernels' arguments, or (film, conductivity) without the
        energy equation)."""
        if not now:
            self._deferred = self._deferred[1 - TUNING.deferred_updates:] + [(dissipation, temperature, kernel_args)]
            return None, None
        return self._fluxes(temperature, kernel_args)

    def _fluxes(self, temperature: np.ndarray, kernel_args: tuple) -> tuple[np.ndarray, np.ndarray]:
        """The wall heat fluxes of `temperature` (K) from the arguments `_wall_fluxes` describes."""
        if not self.solve_energy:
            return energy.wall_heat_flux(temperature, *kernel_args)
        q1, q2 = np.empty(temperature.shape[1:]), np.empty(temperature.shape[1:])
        energy.wall_fluxes(temperature, *kernel_args, q1, q2)
        return q1, q2

    def completed(self, state: FilmState | None) -> FilmState | None:
        """`state` (or a state replaced from it) with the wall heat fluxes of the update it came from, for an update
        made with `wall_fluxes=False` (one of the last TUNING.deferred_updates); as it is when it has them."""
        if state is None or state.heat_flux_1 is not None:
            return state
        for dissipation, temperature, kernel_args in self._deferred:
            if dissipation is state.dissipation:
                q1, q2 = self._fluxes(temperature, kernel_args)
                return replace(state, heat_flux_1=q1, heat_flux_2=q2)
        raise ValueError("the update of this film state is not among the last ones with deferred wall fluxes")


def thermal_loading(point: ContactPoint, lubricant: Lubricant) -> float:
    """Thermal loading number L_th = beta eta_0 u_e^2/k_f (Gupta et al. 1992), with k_f = k_0 at p = 0."""
    beta_eta = lubricant.temperature_viscosity * lubricant.viscosity
    return beta_eta * point.entrainment_speed**2 / lubricant.thermal_conductivity


def gupta_reduction(point: ContactPoint, lubricant: Lubricant) -> float:
    """Thermal reduction factor of the central film (Gupta, Cheng, Zhu, Forster & Schrand 1992, Tribol. Trans.
    35:269-274), phi_T = [1 - 13.2 (p_h/E') L_th^0.42] / [1 + 0.213 (1 + 2.23 SRR^0.83) L_th^0.64], with p_h the
    Hertz pressure, E' the reduced modulus (Hamrock's 2/[(1 - nu1^2)/E1 + (1 - nu2^2)/E2]) and SRR the slide-to-roll
    ratio; as quoted by Arana et al. (2019, Proc. IMechE J 233:303, eq. 24). A published reference the tests and
    scripts/bench_thermal.py compare with; `auto` does not read it (our solutions find less reduction)."""
    srr, loading = abs(point.slide_roll_ratio), thermal_loading(point, lubricant)
    numerator = 1.0 - 13.2 * point.hertz.p_max / point.reduced_modulus * loading**0.42
    return numerator / (1.0 + 0.213 * (1.0 + 2.23 * srr**0.83) * loading**0.64)


def sliding_heating(point: ContactPoint, lubricant: Lubricant) -> float:
    """Theta_s = beta dT_f/mu: the relative drop of the viscosity per unit friction coefficient by the sliding heat's
    flash temperature dT_f of Blok (1937) on the centre line (heat.blok_flash_temperature, semi-elliptical flux,
    B_i = sqrt(k_i rho_i c_i |u_i|) of each surface), dimensionless."""
    u1, u2 = (float(np.hypot(*v)) for v in (point.velocity_1, point.velocity_2))
    flash = blok_flash_temperature(1.0, point.load, point.sliding_speed, point.hertz.b, point.hertz.a,
                                   point.body_1.thermal_effusivity_speed(u1),
                                   point.body_2.thermal_effusivity_speed(u2))
    return lubricant.temperature_viscosity * flash


def heating_number(point: ContactPoint, lubricant: Lubricant) -> float:
    """G = L_th + w Theta_s (w = TUNING.auto_sliding_weight): the inlet's shear heating and the sliding heat in the
    Hertz zone, the number `auto`'s correlation reads (docs/accuracy.md, thermal model choice)."""
    return thermal_loading(point, lubricant) + TUNING.auto_sliding_weight * sliding_heating(point, lubricant)


# `auto`: the largest relative error of each cheaper model against `full` in h_c, h_min and mu is at most C G^n,
# the upper envelope of the errors measured on the contacts of suites/thermal_auto.py (scripts/thermal_auto_fit.py)
AUTO_ENVELOPES = {"off": (TUNING.auto_off_coefficient, TUNING.auto_off_exponent),
                  "reduced": (TUNING.auto_reduced_coefficient, TUNING.auto_reduced_exponent)}
AUTO_FIGURES = ("h_c", "h_min", "mu")  # the figures `auto` keeps within TUNING.auto_tolerance of `full`


def predicted_error(model: str, number: float) -> float:
    """The correlation's bound on the largest relative error of `model` (off, reduced) against `full` in
    AUTO_FIGURES at the heating number G (`heating_number`)."""
    coefficient, exponent = AUTO_ENVELOPES[model]
    return coefficient * number**exponent


def thermal_choice(mode: str, point: ContactPoint, lubricant: Lubricant) -> tuple[str, str]:
    """The thermal model to run and why (for `auto`: the cheapest one the correlation puts within
    TUNING.auto_tolerance of `full` in h_c, h_min and mu)."""
    if mode != "auto":
        return mode, f"solver.thermal: {mode}"
    number = heating_number(point, lubricant)
    predicted = {model: predicted_error(model, number) for model in AUTO_ENVELOPES}
    chosen = next((model for model in AUTO_ENVELOPES if predicted[model] < TUNING.auto_tolerance), "full")
    return chosen, (f"auto: heating number G = {number:.3g} (L_th = {thermal_loading(point, lubricant):.3g}, "
                    f"Theta_s = {sliding_heating(point, lubricant):.3g}); the fitted envelope bounds the error in "
                    f"h_c, h_min, mu of off by {100 * predicted['off']:.3g} %, of reduced by "
                    f"{100 * predicted['reduced']:.3g} % (tolerance {100 * TUNING.auto_tolerance:g} %): {chosen}")

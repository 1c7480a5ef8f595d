"""Flow coefficients of the generalised Reynolds equation (Yang & Wen 1990 form), dimensionless.

Across the film (zeta = z/h from surface 1 at 0 to surface 2 at 1) the viscosity eta*(zeta) (Newtonian, or the
Ree-Eyring effective viscosity, with temperature) and the density rho(zeta) vary. With the layer integrals

    F0 = \\int d zeta/eta*,  F1 = \\int zeta d zeta/eta*,
    f0(zeta) = \\int_0^zeta d zeta'/eta*,  f1(zeta) = \\int_0^zeta zeta' d zeta'/eta*
    R0 = \\int rho d zeta,   R1 = \\int rho f1 d zeta,      R2 = \\int rho f0 d zeta

the mass flux per unit width is m = -h^3 (F1 R2/F0 - R1) grad p + h [u_1 R0 + (u_2 - u_1) R2/F0]: the first term
is the Poiseuille flow, the second the Couette flow (for constant properties rho h^3/(12 eta) and rho h u_e).
In the solver's variables (scaling.py; rho, eta as ratios to rho_0, eta_0; velocities divided by |u_e|):

    eps = 12 (F1 R2/F0 - R1) H^3/lambda
    f_x = s_x [u_1x R0 + (u_2x - u_1x) R2/F0],   f_y = s_y kappa [u_1y R0 + (u_2y - u_1y) R2/F0]

(s_x, s_y: signs of the entrainment components, which orient the upwind differences in reynolds.py).
The layer count is odd (Simpson's rule across the film; layers.py). Between two film-state updates only the pressure
moves: a layered state is frozen with its columns' shapes and their derivatives in the pressure (`frozen_shapes`,
evaluated by `frozen_layered_coefficients` at every relaxation sweep), a state of one temperature per column with the
shapes of its Eyring profile (`column_integrals`, `isothermal_layered_coefficients`).
"""

from __future__ import annotations

import math

from numba import njit
import numpy as np

from facegear_tehl.ehl.layers import cumulative_stencil, simpson_weight
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.lubricant_constants import ROELANDS
from facegear_tehl.lubricant_laws import (
    density_pressure_factor_at,
    density_ratio_at,
    density_thermal_factor_at,
    roelands_pressure_factor_at,
    roelands_ratio,
    roelands_temperature_factor_at,
    viscosity_ratio_at,
)


@njit(cache=True, error_model="numpy")
def isothermal_coefficients(pressure_pa, film, law, temperature, lam, cx, cy, eps, fx, fy):
    """Newtonian film at one temperature: eps = rho H^3/(eta lambda), f = s rho c (in place)."""
    ny, nx = film.shape
    for j in range(ny):
        for i in range(nx):
            rho = density_ratio_at(pressure_pa[j, i], temperature, law)
            eta = viscosity_ratio_at(pressure_pa[j, i], temperature, law)
            h = max(film[j, i], 0.0)
            eps[j, i] = rho * h * h * h / (eta * lam)
            fx[j, i] = rho * abs(cx)
            fy[j, i] = rho * abs(cy)


@njit(cache=True, error_model="numpy")
def layer_integrals(eta, rho):
    """(F0, F1, R0, R1, R2) for viscosity and density ratios on an odd number of equally spaced layer nodes.

    The running integrals f0, f1 by the fourth-order cumulative rule, R0, R1, R2 by Simpson's rule (layers.py).
    Exact for constant properties (F0 = 1/eta, F1 = 1/(2 eta), R1 = rho/(6 eta), R2 = rho/(2 eta)).
    """
    fluidity = np.empty(eta.size)
    for k in range(eta.size):
        fluidity[k] = 1.0 / eta[k]
    return fluidity_integrals(fluidity, rho)


@njit(cache=True, error_model="numpy", inline="always")
def fluidity_integrals(fluidity, rho):
    """`layer_integrals` from the fluidity 1/eta per layer node (one division per node, not one per stencil
    weight: a frozen column is integrated again whenever its pressure moved far, `frozen_layered_coefficients`)."""
    nz = fluidity.size
    dz = 1.0 / (nz - 1)
    f0 = 0.0
    f1 = 0.0
    r0 = 0.0
    r1 = 0.0
    r2 = 0.0
    for k in range(nz):
        if k > 0:
            first, w0, w1, w2, w3 = cumulative_stencil(k, nz)
            g0 = w0 * fluidity[first]
            g1 = w1 * fluidity[first + 1]
            g2 = w2 * fluidity[first + 2]
            g3 = w3 * fluidity[first + 3] if w3 != 0.0 else 0.0
            f0 += dz * (g0 + g1 + g2 + g3)
            f1 += dz * dz * (first * g0 + (first + 1) * g1 + (first + 2) * g2 + (first + 3) * g3)
        w = simpson_weight(k, nz) * rho[k]
        r0 += w
        r1 += w * f1
        r2 += w * f0
    return f0, f1, r0, r1, r2


@njit(cache=True, error_model="numpy")
def column_integrals(viscosity_factor):
    """Per column of an isothermal film, the two shapes of its Eyring profile the flow coefficients need, from
    `fluidity_integrals` of the fluidity phi = eta/eta* (nz, ny, nx) at unit density: (a1 b2/a0 - b1, b2/a0), with
    a0 = \\int phi, a1 = \\int zeta phi, b1 = \\int\\int_0^zeta zeta' phi, b2 = \\int\\int_0^zeta phi. With the
    temperature (hence rho and eta) the same in every layer, F0 = a0/eta, F1 = a1/eta, R0 = rho, R1 = rho b1/eta,
    R2 = rho b2/eta, so that (flow module) 12 (F1 R2/F0 - R1) = 12 (rho/eta)(a1 b2/a0 - b1) and R2/F0 = rho b2/a0:
    both shapes stay fixed while the pressure cycles on a frozen state (`isothermal_layered_coefficients`). For a
    Newtonian column (phi = 1): 1/12 and 1/2 (Poiseuille h^3/(12 eta), Couette u_e h), evaluated once by the same rule
    for every column with phi = 1 in all layers (most of the inlet of an isothermal Ree-Eyring film, rheology.py)."""
    nz, ny, nx = viscosity_factor.shape
    out = np.empty((2, ny, nx))
    fluidity = np.empty(nz)
    ones = np.ones(nz)
    a0, a1, _, b1, b2 = fluidity_integrals(ones, ones)
    newtonian = (a1 * b2 / a0 - b1, b2 / a0)
    for j in range(ny):
        for i in range(nx):
            uniform = True
            for k in range(nz):
                fluidity[k] = 1.0 / viscosity_factor[k, j, i]
                uniform = uniform and viscosity_factor[k, j, i] == 1.0
            if uniform:
                out[0, j, i], out[1, j, i] = newtonian
                continue
            a0, a1, _, b1, b2 = fluidity_integrals(fluidity, ones)
            out[0, j, i] = a1 * b2 / a0 - b1
            out[1, j, i] = b2 / a0
    return out


@njit(cache=True, error_model="numpy")
def isothermal_layered_coefficients(pressure_pa, film, temperature, temperature_factor, shapes, law, lam, kappa, sx,
                                    sy, u1, u2, eps, fx, fy):
    """eps, f_x, f_y (in place) of a film whose layers share one temperature per column, from the layer integrals of
    its Eyring profile: temperature (K) and its `temperature_factors` of one layer (ny, nx), `shapes` from
    `column_integrals`. One viscosity ratio and one density per column; R0 = rho (Simpson's weights sum to 1). On
    513 x 65 x 9 (S1 of the face gear case, isothermal Ree-Eyring) 3.6 -> 1.0 ms per call against the layer-by-layer
    integrals at every sweep; the same numbers to rounding (tests/test_flow.py)."""
    ny, nx = film.shape
    roelands = law[0] == ROELANDS
    for j in range(ny):
        for i in range(nx):
            p = pressure_pa[j, i]
            t = temperature[j, i]
            if roelands:
                ratio = roelands_ratio(roelands_pressure_factor_at(p, law), temperature_factor[j, i], law)
            else:
                ratio = viscosity_ratio_at(p, t, law)
            rho = density_pressure_factor_at(p, law) * density_thermal_factor_at(t, law)
            h = max(film[j, i], 0.0)
            fluidity = 1.0 / ratio
            if fluidity > 0.0:
                eps[j, i] = 12.0 * rho * fluidity * shapes[0, j, i] * h * h * h / lam
                couette = rho * shapes[1, j, i]
            else:  # infinitely viscous film (overflowing viscosity of a running-away iterate): no Poiseuille flow
                eps[j, i] = 0.0
                couette = 0.5 * rho
            fx[j, i] = sx * (u1[0] * rho + (u2[0] - u1[0]) * couette)
            fy[j, i] = sy * kappa * (u1[1] * rho + (u2[1] - u1[1]) * couette)


@njit(cache=True)
def temperature_factors(temperature, law):
    """The Roelands temperature factor of every layer node (lubricant.roelands_temperature_factor_at): it
    stays fixed while the pressure cycles run on a frozen film state, so it is computed once per state. A node at
    the temperature of the one before it (an isothermal film) takes its factor. `out` is C-ordered whatever the
    layout of `temperature` (the ravel of a non-contiguous array is a copy: its factors would never reach `out`)."""
    out = np.empty(temperature.shape)
    flat_t, flat_out = temperature.ravel(), out.ravel()
    for n in range(flat_t.size):
        if n > 0 and flat_t[n] == flat_t[n - 1]:
            flat_out[n] = flat_out[n - 1]
        else:
            flat_out[n] = roelands_temperature_factor_at(flat_t[n], law)
    return out


# The rows of `frozen_shapes`: per column, at the pressure the film state is frozen at, the Poiseuille and Couette
# shapes 12 (F1 R2/F0 - R1) and R2/F0, R0, the slopes of their logarithms against the law's pressure variable
# (`_pressure_variable`), that variable, the density's pressure factor and the spread of the layers' slopes of ln(eta).
POISEUILLE, COUETTE, MEAN_DENSITY, POISEUILLE_SLOPE, COUETTE_SLOPE, VARIABLE, COMPRESSION, SPREAD = range(8)
FROZEN_ROWS = 8
REFREEZE_SPREAD = TUNING.refreeze_spread  # a module global: Numba kernels read globals when they compile


@njit(cache=True, error_model="numpy", inline="always")
def _pressure_variable(p, law):
    """The variable the layer viscosities of a column move with as the pressure p (Pa) changes: ln(eta) of every
    layer is linear in the Roelands pressure factor (1 + p/p_r)^z (slope ln-term times the layer's temperature
    factor) and, for Barus, in p itself (slope alpha, the same in every layer)."""
    if law[0] == ROELANDS:
        return roelands_pressure_factor_at(p, law)
    return max(p, 0.0)


@njit(cache=True, error_model="numpy", inline="always")
def _freeze_column(out, j, i, p, temperature, temperature_factor, viscosity_factor, law, fluidity, change, rho):
    """Column (j, i) of `frozen_shapes` at the pressure p (Pa), into out[:, j, i]; fluidity, change, rho: (nz,)
    work arrays."""
    nz = temperature.shape[0]
    roelands = law[0] == ROELANDS
    variable = _pressure_variable(p, law)  # for Roelands its pressure factor
    compression = density_pressure_factor_at(p, law)
    lowest = highest = first_ratio = 0.0
    for k in range(nz):
        t = temperature[k, j, i]
        if roelands:
            factor = temperature_factor[k, j, i]
            if k > 0 and factor == temperature_factor[0, j, i]:
                ratio = first_ratio
            else:
                ratio = roelands_ratio(variable, factor, law)
            if k == 0:
                first_ratio = ratio
            rate = law[3] * factor  # -d ln(phi_k)/dv
        else:
            ratio = viscosity_ratio_at(p, t, law)
            rate = law[1]
        fluidity[k] = 1.0 / max(ratio * viscosity_factor[k, j, i], 1e-300)
        change[k] = -rate * fluidity[k]
        rho[k] = compression * density_thermal_factor_at(t, law)
        lowest = rate if k == 0 else min(lowest, rate)
        highest = rate if k == 0 else max(highest, rate)
    f0, f1, r0, r1, r2 = fluidity_integrals(fluidity, rho)
    d0, d1, _, e1, e2 = fluidity_integrals(change, rho)
    poiseuille_slope = couette_slope = 0.0
    if f0 > 0.0:
        poiseuille = 12.0 * (f1 * r2 / f0 - r1)
        couette = r2 / f0
        derivative = 12.0 * ((d1 * r2 + f1 * e2) / f0 - f1 * r2 * d0 / (f0 * f0) - e1)
        if poiseuille > 0.0:
            poiseuille_slope = -derivative / poiseuille
        if couette > 0.0:
            couette_slope = -(e2 / f0 - r2 * d0 / (f0 * f0)) / couette
    else:  # infinitely viscous film (overflowing viscosity of a running-away iterate): no Poiseuille flow
        poiseuille = 0.0
        couette = 0.5 * r0
    out[POISEUILLE, j, i] = poiseuille
    out[COUETTE, j, i] = couette
    out[MEAN_DENSITY, j, i] = r0
    out[POISEUILLE_SLOPE, j, i] = poiseuille_slope
    out[COUETTE_SLOPE, j, i] = couette_slope
    out[VARIABLE, j, i] = variable
    out[COMPRESSION, j, i] = compression
    out[SPREAD, j, i] = highest - lowest


@njit(cache=True, error_model="numpy")
def frozen_shapes(pressure_pa, temperature, temperature_factor, viscosity_factor, law):
    """Per column of a film state frozen at the pressures pressure_pa (Pa, (ny, nx)) with layer temperatures (K),
    their `temperature_factors` and viscosity factors eta*/eta (nz, ny, nx): the rows POISEUILLE .. SPREAD,
    (FROZEN_ROWS, ny, nx), that `frozen_layered_coefficients` evaluates at the pressures of the V-cycles.

    The layer integrals (`fluidity_integrals`) at the freezing pressure, and the derivatives of the logarithms of the
    two shapes against the law's pressure variable v (`_pressure_variable`): every layer's fluidity phi_k moves
    by d phi_k/dv = -c_k phi_k (Roelands c_k = ln-term S_k with S_k the layer's temperature factor, Barus alpha) and
    F0, F1, R1, R2 are linear in the fluidities, so their derivatives are the same integrals of -c_k phi_k.
    A layer whose temperature factor equals the first layer's (an isothermal film) reuses its viscosity ratio."""
    nz, ny, nx = temperature.shape
    out = np.empty((FROZEN_ROWS, ny, nx))
    fluidity, change, rho = np.empty(nz), np.empty(nz), np.empty(nz)
    for j in range(ny):
        for i in range(nx):
            _freeze_column(out, j, i, pressure_pa[j, i], temperature, temperature_factor, viscosity_factor, law,
                           fluidity, change, rho)
    return out


@njit(cache=True, error_model="numpy")
def frozen_layered_coefficients(pressure_pa, film, shapes, temperature, temperature_factor, viscosity_factor, law, lam,
                                kappa, sx, sy, u1, u2, eps, fx, fy):
    """eps, f_x, f_y (in place) of a layered film state frozen with `frozen_shapes` (the state's arrays as given
    there), at the pressures pressure_pa (Pa) and film H (dimensionless); u1, u2: surface velocities divided by |u_e|,
    in the (x, y) frame. Returns the number of columns frozen again.

    The shapes move with the law's pressure variable v (`_pressure_variable`) as exp(-slope (v - v_0)), v_0 its value
    at the freeze, and R0 and both shapes with the density's pressure factor (one for every layer):
    eps = POISEUILLE x those x H^3/lambda, R2/F0 = COUETTE x those. Exact at the freezing pressure, for Barus at any,
    and for a column of one temperature (every layer then has the same slope: an isothermal film); otherwise to
    second order in the change of v since the freeze, and a column whose layers moved apart by more than
    REFREEZE_SPREAD is frozen again at its pressure first (the pressure moves by a V-cycle's change between two
    film-state updates, and at the outer loop's fixed point, where it no longer moves, the film is the layer
    integrals' own). One pressure factor and two exponentials per column instead of an exponential per layer node and
    the integrals: 3.0 -> 0.7 ms on 513 x 65 x 9 (S1 of the face gear case)."""
    nz = temperature.shape[0]
    ny, nx = film.shape
    fluidity, change_k, rho = np.empty(nz), np.empty(nz), np.empty(nz)
    refrozen = 0
    for j in range(ny):
        for i in range(nx):
            p = pressure_pa[j, i]
            change = _pressure_variable(p, law) - shapes[VARIABLE, j, i]
            if abs(change) * shapes[SPREAD, j, i] > REFREEZE_SPREAD:
                _freeze_column(shapes, j, i, p, temperature, temperature_factor, viscosity_factor, law, fluidity,
                               change_k, rho)
                change = 0.0
                refrozen += 1
            density = density_pressure_factor_at(p, law) / shapes[COMPRESSION, j, i]
            h = max(film[j, i], 0.0)
            eps[j, i] = (shapes[POISEUILLE, j, i] * density * math.exp(-shapes[POISEUILLE_SLOPE, j, i] * change)
                         * h * h * h / lam)
            r0 = shapes[MEAN_DENSITY, j, i] * density
            couette = shapes[COUETTE, j, i] * density * math.exp(-shapes[COUETTE_SLOPE, j, i] * change)
            fx[j, i] = sx * (u1[0] * r0 + (u2[0] - u1[0]) * couette)
            fy[j, i] = sy * kappa * (u1[1] * r0 + (u2[1] - u1[1]) * couette)
    return refrozen

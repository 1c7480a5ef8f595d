"""Shear stress, shear rate and velocity across the film for a Newtonian or Ree-Eyring lubricant (SI units).

Across the film (z from surface 1 at 0 to surface 2 at h) the momentum balance of thin-film flow gives a
linear shear stress, tau(z) = tau_s + z grad p (a vector in the (x, y) plane), and the velocity follows
from the constitutive law:

    Newtonian:   gamma_dot = tau/eta
    Ree-Eyring:  gamma_dot = (tau_0/eta) sinh(|tau|/tau_0) tau/|tau|       (Ree & Eyring 1955; Johnson &
                 Tevaarwerk 1977), i.e. an effective viscosity eta* = eta (|tau|/tau_0)/sinh(|tau|/tau_0).

The surface stress tau_s is fixed by the velocities of the surfaces, \\int_0^h gamma_dot dz = u_2 - u_1,
solved by Newton's method with backtracking (Newtonian: in closed form). Integrals across the film use
Simpson's rule on an odd number of equally spaced layer nodes; the velocity profile u(z) = u_1 + \\int_0^z
gamma_dot dz' the fourth-order cumulative rule (layers.py). Dissipation per unit volume: tau . gamma_dot (W/m^3).

The kernels here, in flow.py and energy.py are compiled with NumPy's floating-point error model: an iterate
running away (infinite viscosity) gives inf/NaN, which the solver detects and reports, not an exception.
"""

from __future__ import annotations

import math

from numba import njit
import numpy as np

from facegear_tehl.ehl.layers import cumulative_step, simpson_weight

MAX_STRESS_RATIO = 600.0  # |tau|/tau_0 cap inside sinh (overflow guard, far beyond physical values ~10)
MIN_VISCOSITY_FACTOR = 1e-12  # floor of eta*/eta (r/sinh r underflows to 0 near the cap)


@njit(cache=True, error_model="numpy", inline="always")
def _sinh_cosh(r):
    """(sinh r, cosh r) for r >= 0 from one expm1 (the two functions cost one exponential each): with
    e - 1 = expm1(r), sinh r = (e - 1)(1 + 1/e)/2 without cancellation at small r, cosh r = (e + 1/e)/2."""
    em1 = math.expm1(r)
    inverse = 1.0 / (em1 + 1.0)
    return 0.5 * em1 * (1.0 + inverse), 0.5 * (em1 + 1.0 + inverse)


@njit(cache=True, error_model="numpy")
def _shear_rate(tx, ty, eta, inverse_eta, tau0, inverse_tau0):
    """(gamma_dot_x, gamma_dot_y, d gamma/d tau as (a, b, c) of the symmetric 2x2 Jacobian)."""
    te = math.sqrt(tx * tx + ty * ty)
    if not math.isfinite(tau0) or te == 0.0:
        return tx / eta, ty / eta, 1.0 / eta, 0.0, 1.0 / eta
    inverse_te = 1.0 / te
    r = min(te * inverse_tau0, MAX_STRESS_RATIO)
    sinh, cosh = _sinh_cosh(r)
    amp = tau0 * inverse_eta * sinh  # |gamma_dot|
    ratio = amp * inverse_te  # |gamma_dot|/|tau|
    gx, gy = ratio * tx, ratio * ty
    d_amp = cosh * inverse_eta  # d|gamma_dot|/d|tau|
    nx, ny = tx * inverse_te, ty * inverse_te
    a = d_amp * nx * nx + ratio * (1.0 - nx * nx)
    c = d_amp * ny * ny + ratio * (1.0 - ny * ny)
    return gx, gy, a, (d_amp - ratio) * nx * ny, c


@njit(cache=True, error_model="numpy", inline="always")
def surface_stress(eta, h, gpx, gpy, dux, duy, tau0, weights, guess_x, guess_y, warm, speed, rate_x, rate_y, trace,
                   inverse_eta, inverse_tau0, newtonian_below=0.0):
    """Stress (tau_x, tau_y) at surface 1 such that \\int gamma_dot dz = (dux, duy); eta per layer (Pa s); returns
    (tau_x, tau_y, rated, newtonian): `rated` True when rate_x, rate_y (per layer, in place) hold the shear rate at the
    stress returned (the residual evaluation that ended Newton's method) and `trace` the trace of its Jacobian
    d gamma_dot/d tau, else they are to be evaluated; `newtonian` True when the column is taken as Newtonian (below).

    Ree-Eyring: Newton's method from (guess_x, guess_y) if `warm`, else from the Couette estimate, to a velocity
    residual of 1e-10 `speed` (m/s, the scale of the surface speeds). A column whose Newtonian wall stresses are both
    below `newtonian_below` tau_0 keeps the Newtonian solution (0: never): its Eyring stresses are the Newtonian ones
    to a relative O(r^2), and eta*/eta = r/sinh r departs from 1 by at most r^2/6 in the log (sinh r/r =
    prod_k (1 + r^2/(k pi)^2) <= exp(r^2/6); tests/test_layers.py, tests/test_eyring_loop.py)."""
    nz = eta.size
    # Newtonian solution: tau_s G0 + grad p G1 = du, G0 = h \\int dzeta/eta, G1 = h^2 \\int zeta dzeta/eta
    g0 = 0.0
    g1 = 0.0
    for k in range(nz):
        zeta = k / (nz - 1)
        g0 += weights[k] / eta[k]
        g1 += weights[k] * zeta / eta[k]
    g0 *= h
    g1 *= h * h
    tx = (dux - gpx * g1) / g0
    ty = (duy - gpy * g1) / g0
    if not math.isfinite(tau0):
        return tx, ty, False, True
    if newtonian_below > 0.0:
        wall = max(math.sqrt(tx * tx + ty * ty), math.sqrt((tx + h * gpx) ** 2 + (ty + h * gpy) ** 2))
        if wall < newtonian_below * tau0:
            return tx, ty, False, True
    if warm:
        tx, ty = guess_x, guess_y
    else:
        # Ree-Eyring start: the Couette value tau_0 asinh(|tau_N|/tau_0) along the Newtonian direction
        tn = math.sqrt(tx * tx + ty * ty)
        if tn > 0.0:
            scale = tau0 * math.asinh(tn / tau0) / tn
            tx *= scale
            ty *= scale
    residual_norm = math.inf
    step_x = 0.0
    step_y = 0.0
    for _ in range(80):
        fx = -dux
        fy = -duy
        ja = 0.0
        jb = 0.0
        jc = 0.0
        for k in range(nz):
            z = h * k / (nz - 1)
            gx, gy, a, b, c = _shear_rate(tx + z * gpx, ty + z * gpy, eta[k], inverse_eta[k], tau0, inverse_tau0)
            rate_x[k] = gx
            rate_y[k] = gy
            trace[k] = a + c
            w = weights[k] * h
            fx += w * gx
            fy += w * gy
            ja += w * a
            jb += w * b
            jc += w * c
        norm = math.hypot(fx, fy)
        if norm <= 1e-10 * speed:
            return tx, ty, True, False
        if norm > residual_norm:
            # backtrack: the last Newton step overshot; go back half of what is left of it
            step_x *= 0.5
            step_y *= 0.5
            tx -= step_x
            ty -= step_y
            continue
        residual_norm = norm
        det = ja * jc - jb * jb
        step_x = -(jc * fx - jb * fy) / det
        step_y = -(-jb * fx + ja * fy) / det
        tx += step_x
        ty += step_y
    return tx, ty, False, False


@njit(cache=True, error_model="numpy")
def shear_state(pressure, film, grad_x, grad_y, eta_newtonian, u1, u2, tau0, warm,
                viscosity_factor, dissipation, velocity_x, velocity_y, stress_1, stress_2, thinning,
                newtonian_below=0.0):
    """Across-film shear state at every node (in place), shapes (nz, ny, nx) for layer fields.

    warm: stress_1 holds the previous solution, used as the Newton start (Ree-Eyring).
    newtonian_below: a column whose Newtonian wall stresses are below this multiple of tau_0 takes the Newtonian state
    (eta*/eta = 1, error in ln(eta*/eta) at most newtonian_below^2/6; surface_stress); 0: every column is solved.
    thinning: tanh(r)/r with r = |tau|/tau_0 (1 for a Newtonian film): d ln(dissipation)/d ln(eta) at fixed
    shear rate, for the implicit treatment of viscous heating in energy.py, formed as |gamma_dot|/|tau| over
    d|gamma_dot|/d|tau| (the trace of the shear rate's Jacobian less the former: no tanh); an empty array: not
    evaluated (a film without the energy equation, as its velocities: 35 -> 20 ms without both on 513 x 65 x 9).

    pressure (Pa), film (m), grad_x/grad_y (Pa/m), eta_newtonian (Pa s, per layer): inputs.
    Outputs: viscosity_factor eta*/eta, dissipation tau . gamma_dot (W/m^3), velocity_x/velocity_y (m/s; empty
    arrays: not evaluated, as thinning), stress_1 / stress_2: (2, ny, nx) shear stress vectors at surfaces 1 and 2 (Pa).
    """
    nz, ny, nx = eta_newtonian.shape
    weights = np.empty(nz)
    for k in range(nz):
        weights[k] = simpson_weight(k, nz)
    dux = u2[0] - u1[0]
    duy = u2[1] - u1[1]
    speed = math.hypot(u1[0], u1[1]) + math.hypot(u2[0], u2[1]) + 1e-30
    eta = np.empty(nz)
    rate_x = np.empty(nz)
    rate_y = np.empty(nz)
    trace = np.empty(nz)
    inverse_eta = np.empty(nz)
    inverse_tau0 = 1.0 / tau0
    heating = thinning.size > 0
    moving = velocity_x.size > 0
    for j in range(ny):
        for i in range(nx):
            h = max(film[j, i], 1e-12)
            for k in range(nz):
                eta[k] = eta_newtonian[k, j, i]
                inverse_eta[k] = 1.0 / eta[k]
            gpx = grad_x[j, i]
            gpy = grad_y[j, i]
            tx, ty, rated, newtonian = surface_stress(eta, h, gpx, gpy, dux, duy, tau0, weights, stress_1[0, j, i],
                                                      stress_1[1, j, i], warm, speed, rate_x, rate_y, trace,
                                                      inverse_eta, inverse_tau0, newtonian_below)
            for k in range(nz):
                z = h * k / (nz - 1)
                sx = tx + z * gpx
                sy = ty + z * gpy
                if newtonian and math.isfinite(tau0):  # a column taken as Newtonian (newtonian_below)
                    gx, gy = sx * inverse_eta[k], sy * inverse_eta[k]
                    rate_x[k] = gx
                    rate_y[k] = gy
                    viscosity_factor[k, j, i] = 1.0
                    if heating:
                        thinning[k, j, i] = 1.0
                    dissipation[k, j, i] = sx * gx + sy * gy
                    continue
                if rated:  # Newton's last residual evaluated these (the same stress, the same operations)
                    gx, gy = rate_x[k], rate_y[k]
                else:
                    gx, gy, a, _, c = _shear_rate(sx, sy, eta[k], inverse_eta[k], tau0, inverse_tau0)
                    rate_x[k] = gx
                    rate_y[k] = gy
                    trace[k] = a + c
                te = math.sqrt(sx * sx + sy * sy)
                ge = math.sqrt(gx * gx + gy * gy)
                viscosity_factor[k, j, i] = max(te / (ge * eta[k]), MIN_VISCOSITY_FACTOR) if ge > 0.0 else 1.0
                if heating:
                    # tanh(r)/r = (|gamma_dot|/|tau|)/(d|gamma_dot|/d|tau|); the Jacobian's trace is their sum
                    ratio = ge / te if te > 0.0 else 0.0
                    thinning[k, j, i] = ratio / (trace[k] - ratio) if ratio > 0.0 and math.isfinite(tau0) else 1.0
                dissipation[k, j, i] = sx * gx + sy * gy
            if moving:
                ux = u1[0]
                uy = u1[1]
                velocity_x[0, j, i] = ux
                velocity_y[0, j, i] = uy
                for k in range(1, nz):
                    ux += cumulative_step(rate_x, k, h / (nz - 1))
                    uy += cumulative_step(rate_y, k, h / (nz - 1))
                    velocity_x[k, j, i] = ux
                    velocity_y[k, j, i] = uy
            stress_1[0, j, i] = tx
            stress_1[1, j, i] = ty
            stress_2[0, j, i] = tx + h * gpx
            stress_2[1, j, i] = ty + h * gpy


@njit(cache=True, error_model="numpy")
def log_factor_change(factor, updated, log_factor, change):
    """ln(eta*/eta) of `factor` and its change ln(updated) - ln(factor) toward an update (in place; arrays of one
    shape, contiguous). An entry at 1 in both (a Newtonian column of an isothermal Ree-Eyring film, 82-87 % of its
    layer nodes on 513 x 65) takes 0 without a logarithm: one pass instead of NumPy's five (2.7 -> 0.6 ms on 513 x
    65 x 9). Returns the largest |change|."""
    flat_f, flat_u = factor.ravel(), updated.ravel()
    flat_log, flat_change = log_factor.ravel(), change.ravel()
    largest = 0.0
    for n in range(flat_f.size):
        f, u = flat_f[n], flat_u[n]
        if f == 1.0 and u == 1.0:
            flat_log[n] = 0.0
            flat_change[n] = 0.0
            continue
        log_f = math.log(f)
        d = math.log(u) - log_f
        flat_log[n] = log_f
        flat_change[n] = d
        largest = max(largest, abs(d))
    return largest

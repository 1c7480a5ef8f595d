"""Friction and heat budget formulas (docs/method.md §6) against values computed independently from the
published formulas, their closed forms and limits."""

import math

from hypothesis import given, settings
from hypothesis import strategies as st
import numpy as np
import pytest

from facegear_tehl import heat
from facegear_tehl.ehl.jaeger import surface_temperature_rise
from facegear_tehl.materials import Solid

STEEL = Solid(elastic_modulus=206e9, poisson_ratio=0.3)  # k = 46, rho = 7850, c = 470 (handbook steel)
TITANIUM = Solid(elastic_modulus=110e9, poisson_ratio=0.34, density=4500.0, thermal_conductivity=20.0,
                 specific_heat=520.0)

speeds = st.floats(min_value=0.01, max_value=50.0)


def within_quoted(value, quoted, decimals):
    """The reference is quoted to `decimals` places: agree to half a unit of its last digit."""
    assert abs(value - quoted) <= 0.5 * 10.0 ** (-decimals) * (1 + 1e-9), (value, quoted)


# --- Xu, Kahraman, Anderson & Maddock (2007), J. Mech. Des. 129:58-68 --------------------------------

XU_WORKED = [  # SR, P_h (GPa), nu_0 (mPa s), V_e (m/s), R (m), S (um), mu  [V]
    (0.3, 1.0, 10.0, 10.0, 0.01, 0.3, 0.0174667),
    (0.5, 1.5, 20.0, 5.0, 0.01, 0.2, 0.0212763),
    (0.05, 1.2, 10.0, 10.0, 0.01, 0.3, 0.0063110),
]


def xu_si(sr, p_gpa, nu_mpas, ve, radius, s_um):
    return heat.xu_friction(sr, p_gpa * 1e9, nu_mpas * 1e-3, ve, radius, s_um * 1e-6)


@pytest.mark.parametrize("sr, p_gpa, nu_mpas, ve, radius, s_um, mu", XU_WORKED)
def test_xu_worked_values(sr, p_gpa, nu_mpas, ve, radius, s_um, mu):
    # Worked values of the regression with Xu et al.'s (2007) published coefficients, evaluated by hand in
    # double precision (0.0174667, 0.0212763, 0.0063110; values quoted earlier as 0.017470 and 0.006306
    # were rounded wrongly by 2e-4 and 8e-4 relative). Seven digits: agreement to 1e-6 relative.
    value = xu_si(sr, p_gpa, nu_mpas, ve, radius, s_um)
    assert value == pytest.approx(mu, rel=1e-6, abs=0.0)


def test_xu_units_radius_in_metres():
    # Units check: R mistakenly in mm (R = 10) gives the implausible 0.00117 for case 1.
    within_quoted(xu_si(0.3, 1.0, 10.0, 10.0, 10.0, 0.3), 0.00117, 5)


def test_xu_formula_in_its_own_units():
    # The SI wrapper equals the regression written out in GPa, mPa s, m and um.
    b1, b2, b3, b4, b5, b6, b7, b8, b9 = (-8.916465, 1.03303, 1.036077, -0.354068, 2.812084, -0.100601,
                                          0.752755, -0.390958, 0.620305)
    sr, p_gpa, nu, ve, radius, s_um = 0.8, 0.9, 6.4, 7.5, 0.02, 0.4
    f = b1 + b4 * sr * p_gpa * math.log10(nu) + b5 * math.exp(-sr * p_gpa * math.log10(nu)) + b9 * math.exp(s_um)
    expected = math.exp(f) * p_gpa**b2 * sr**b3 * ve**b6 * nu**b7 * radius**b8
    assert xu_si(sr, p_gpa, nu, ve, radius, s_um) == pytest.approx(expected, rel=1e-12)
    assert xu_si(-sr, p_gpa, nu, ve, radius, s_um) == pytest.approx(expected, rel=1e-12)


def test_xu_vanishes_in_pure_rolling():
    # Xu et al. (2007): mu -> 0 as SR -> 0 (power 1.036): the V shape around the pitch point S3.
    assert heat.xu_friction(0.0, 1e9, 0.01, 10.0, 0.01, 0.3e-6) == 0.0
    small = [xu_si(sr, 1.0, 10.0, 10.0, 0.01, 0.3) for sr in (0.01, 0.02, 0.04)]
    assert small[0] < small[1] < small[2]


# --- ISO/TR 14179-2 (Schlenk 1994) -------------------------------------------------------------

def test_iso_tr_14179_in_its_own_units_and_plausible():
    # F_bt/b = 300 N/mm, v_sum = 10 m/s, rho_red = 10 mm, eta = 20 mPa s, R_a = 0.5 um, ester.
    x_l = heat.ISO_TR_14179_OIL_FACTOR["ester"]
    expected = 0.048 * (300.0 / (10.0 * 10.0)) ** 0.2 * 20.0**-0.05 * 0.5**0.25 * x_l
    value = heat.iso_tr_14179_friction(300e3, 10.0, 10e-3, 20e-3, 0.5e-6, x_l)
    assert value == pytest.approx(expected, rel=1e-12)
    # Plausibility range only (magnitude check): lubricated gear teeth run at mu ~ 0.02-0.08.
    assert 0.02 <= value <= 0.08
    mineral = heat.iso_tr_14179_friction(300e3, 10.0, 10e-3, 20e-3, 0.5e-6, heat.ISO_TR_14179_OIL_FACTOR["mineral"])
    assert 0.02 <= mineral <= 0.08


# --- Péclet number and partition (Jaeger 1942; Blok 1937) ----------------------------------------

def test_peclet_number_steel():
    within_quoted(STEEL.thermal_diffusivity * 1e5, 1.2468, 4)
    within_quoted(heat.peclet_number(10.0, 0.3e-3, STEEL), 120.3, 1)
    assert heat.peclet_number(-10.0, 0.3e-3, STEEL) == heat.peclet_number(10.0, 0.3e-3, STEEL)


@pytest.mark.parametrize("u1, u2, gamma_1", [(10.0, 6.0, 0.5635), (8.0, 2.0, 0.6667)])
def test_partition_examples(u1, u2, gamma_1):
    partition = heat.heat_partition(STEEL, STEEL, u1, u2)
    within_quoted(partition.gamma_1, gamma_1, 4)


@settings(max_examples=50, deadline=None)
@given(u1=speeds, u2=speeds)
def test_partition_same_material_and_sum(u1, u2):
    same = heat.heat_partition(STEEL, STEEL, u1, u2)
    assert same.gamma_1 == pytest.approx(1.0 / (1.0 + math.sqrt(u2 / u1)), rel=1e-12)
    mixed = heat.heat_partition(STEEL, TITANIUM, u1, u2)
    assert mixed.gamma_1 + mixed.gamma_2 == pytest.approx(1.0, abs=1e-15)
    assert mixed.effusivity_1 == STEEL.thermal_effusivity_speed(u1)


def test_partition_needs_motion():
    with pytest.raises(ValueError):
        heat.heat_partition(STEEL, STEEL, 0.0, 0.0)


# --- Blok (1937) flash temperature ---------------------------------------------------------------

def test_flash_constants():
    within_quoted(heat.FLASH_PEAK_COEFFICIENT["semi_elliptical"], 1.23462, 5)
    within_quoted(heat.FLASH_PEAK_COEFFICIENT["uniform"], 1.59577, 5)
    within_quoted(heat.BLOK_LINE_COEFFICIENT, 0.7860, 4)
    # Quoted as 0.7860 sqrt(2) = 1.1116 from the rounded 0.7860; unrounded it is 1.11155.
    assert heat.BLOK_SAME_MATERIAL_COEFFICIENT == pytest.approx(1.1116, rel=1e-4)
    assert heat.BLOK_SAME_MATERIAL_COEFFICIENT == pytest.approx(1.11, rel=2e-3)  # Blok (1937)


def test_blok_point_contact_formula():
    # dT = C q0 sqrt(b)/(B1 + B2), q0 = mu p0 |u1 - u2|, p0 = 3W/(2 pi a b) (Blok 1937 with Jaeger's kernel).
    mu, load, a, b, u1, u2 = 0.05, 1000.0, 0.87e-3, 0.30e-3, 10.0, 6.0
    partition = heat.heat_partition(STEEL, TITANIUM, u1, u2)
    effusivities = (partition.effusivity_1, partition.effusivity_2)
    q0 = mu * 3.0 * load / (2.0 * math.pi * a * b) * abs(u1 - u2)
    semi = heat.blok_flash_temperature(mu, load, u1 - u2, b, a, *effusivities)
    assert semi == pytest.approx(1.2346 * q0 * math.sqrt(b) / sum(effusivities), rel=1e-4)
    # The uniform flux of the same centre-line heat, q = (pi/4) q0, with C = 1.5958.
    uniform = heat.blok_flash_temperature(mu, load, u1 - u2, b, a, *effusivities, flux_shape="uniform")
    assert uniform == pytest.approx(1.5958 * math.pi / 4 * q0 * math.sqrt(b) / sum(effusivities), rel=1e-4)
    with pytest.raises(ValueError):
        heat.blok_flash_temperature(mu, load, u1 - u2, b, a, *effusivities, flux_shape="parabolic")


def test_blok_line_contact_and_same_material():
    mu, w, b, u1, u2 = 0.04, 3.0e5, 0.25e-3, 12.0, 3.0
    partition = heat.heat_partition(STEEL, STEEL, u1, u2)
    general = heat.blok_flash_temperature_line(mu, w, u1 - u2, b, partition.effusivity_1, partition.effusivity_2)
    sum_b = partition.effusivity_1 + partition.effusivity_2
    assert general == pytest.approx(0.7860 * mu * w * abs(u1 - u2) / (math.sqrt(b) * sum_b), rel=1e-4)
    beta = math.sqrt(46.0 * 7850.0 * 470.0)
    classical = heat.blok_flash_temperature_same_material(mu, w, u1, u2, b, STEEL)
    assert classical == pytest.approx(general, rel=1e-12)
    assert classical == pytest.approx(1.1116 * mu * w * abs(math.sqrt(u1) - math.sqrt(u2)) / (beta * math.sqrt(2 * b)),
                                      rel=1e-4)


@pytest.mark.parametrize("flux_shape", ["semi_elliptical", "uniform"])
def test_blok_equals_kernel_with_partitioned_flux(flux_shape):
    # Each surface takes gamma_i of the centre-line flux; the Jaeger kernel then gives both surfaces
    # the same maximum rise, equal to Blok's value (Blok 1937).
    mu, load, a, b, u1, u2 = 0.06, 800.0, 1.2e-3, 0.28e-3, 9.0, 4.0
    partition = heat.heat_partition(STEEL, TITANIUM, u1, u2)
    x = np.linspace(-2 * b, 2 * b, 513)
    dx = x[1] - x[0]
    q0 = mu * 3.0 * load / (2.0 * math.pi * a * b) * abs(u1 - u2)
    if flux_shape == "semi_elliptical":
        flux = q0 * np.sqrt(np.clip(1 - (x / b) ** 2, 0, None))
    else:
        flux = math.pi / 4 * q0 * (np.abs(x) <= b * (1 + 1e-12))
        flux[np.isclose(np.abs(x), b)] *= 0.5  # the band edges fall on nodes: half flux there
    rise_1 = surface_temperature_rise(partition.gamma_1 * flux, dx, partition.effusivity_1).max()
    rise_2 = surface_temperature_rise(partition.gamma_2 * flux, dx, partition.effusivity_2).max()
    assert rise_1 == pytest.approx(rise_2, rel=1e-12)
    blok = heat.blok_flash_temperature(mu, load, u1 - u2, b, a, partition.effusivity_1, partition.effusivity_2,
                                       flux_shape=flux_shape)
    assert rise_1 == pytest.approx(blok, rel=0.01)


# --- friction power and its distribution (seed paper §3.4) --------------------------------------

@settings(max_examples=30, deadline=None)
@given(seed=st.integers(min_value=0, max_value=2**32 - 1), power=st.floats(min_value=1e-3, max_value=1e4))
def test_distribute_by_pressure(seed, power):
    pressure = np.random.default_rng(seed).random((33, 17)) * 2e9
    cells = heat.distribute_by_pressure(power, pressure)
    assert cells.sum() == pytest.approx(power, rel=1e-12)
    np.testing.assert_allclose(cells / pressure, power / pressure.sum(), rtol=1e-12)


def test_distribute_by_pressure_needs_load():
    with pytest.raises(ValueError):
        heat.distribute_by_pressure(1.0, np.zeros((3, 3)))


def test_friction_power_and_shear_power():
    # Couette shear tau = eta v_s / h on an area A: the shear power is tau v_s A = mu F v_s with mu = tau A / F.
    eta, h, load = 0.02, 0.5e-6, 1000.0
    v = np.array([1.5, -2.0])  # sliding u1 - u2, m/s
    tau = eta * v / h
    nx, ny, dx, dy = 30, 40, 0.03e-3, 0.03e-3
    cells = heat.distribute_by_shear_power(np.full((ny, nx), tau[0]), np.full((ny, nx), tau[1]), v[0], v[1], dx, dy)
    mu = np.hypot(*tau) * nx * ny * dx * dy / load
    assert cells.sum() == pytest.approx(heat.friction_power(mu, load, np.hypot(*v)), rel=1e-12)
    # Shear across the sliding direction does no work.
    across = heat.distribute_by_shear_power(np.full(3, -tau[1]), np.full(3, tau[0]), v[0], v[1], dx, dy)
    np.testing.assert_allclose(across, 0.0, atol=1e-20)
    assert heat.friction_power(0.05, 1000.0, -2.0) == pytest.approx(100.0, rel=1e-15)


# --- duty ratio, oil-film heat, frictional heat (seed paper §3.4-3.5) -----------------------------

def test_duty_cycle_example():
    # n = 1500 rpm, r = 30 mm, b = 0.3 mm: v_t = 4.712 m/s, t_c = 1.273e-4 s, T = 0.04 s, t_c/T = 3.183e-3.
    duty = heat.duty_cycle(0.3e-3, 30e-3, 1500.0)
    within_quoted(duty.tangential_speed, 4.712, 3)
    within_quoted(duty.dwell * 1e4, 1.273, 3)
    assert duty.period == pytest.approx(0.04, rel=1e-15)
    within_quoted(duty.ratio * 1e3, 3.183, 3)
    assert heat.steady_state_power(100.0, 0.3e-3, 30e-3) == pytest.approx(100.0 * duty.ratio, rel=1e-12)


@settings(max_examples=50, deadline=None)
@given(b=st.floats(1e-5, 2e-3), radius=st.floats(5e-3, 0.5), rpm=st.floats(10.0, 3e4))
def test_duty_ratio_is_b_over_pi_r(b, radius, rpm):
    assert heat.duty_cycle(b, radius, rpm).ratio == pytest.approx(b / (math.pi * radius), rel=1e-12)
    assert heat.duty_ratio(b, radius) == pytest.approx(b / (math.pi * radius), rel=1e-15)


def test_duty_cycle_rejects_bad_input():
    with pytest.raises(ValueError):
        heat.duty_cycle(0.3e-3, 30e-3, 0.0)


def test_oil_film_and_frictional_heat_example():
    # rho c = 920 * 2000, h = 0.5 um, A = 1.08 mm^2, dT = 30 K -> Q_oil = 2.98e-5 J;
    # mu = 0.05, F = 1000 N, v_s = 2 m/s, t_c = 6e-5 s -> Q_f = 6.0e-3 J; ratio 0.5 %.
    nx, ny, dx, dy = 30, 40, 0.03e-3, 0.03e-3  # 0.9 mm x 1.2 mm = 1.08 mm^2
    film = np.full((ny, nx), 0.5e-6)
    rise = np.full((ny, nx), 30.0)
    q_oil = heat.oil_film_heat(920.0 * 2000.0, film, rise, dx, dy)
    within_quoted(q_oil * 1e5, 2.98, 2)
    q_f = heat.frictional_heat(heat.friction_power(0.05, 1000.0, 2.0), 6e-5)
    within_quoted(q_f * 1e3, 6.0, 1)
    within_quoted(100.0 * q_oil / q_f, 0.5, 1)
    # A field of rho c gives the same sum.
    assert heat.oil_film_heat(np.full((ny, nx), 920.0 * 2000.0), film, rise, dx, dy) == pytest.approx(q_oil, rel=1e-12)


# --- Tian & Kennedy (1994), J. Tribol. 116:167-174 ---------------------------------------------

@pytest.mark.parametrize("pe, maximum, mean", [(1, 0.7484, 0.5346), (10, 0.3361, 0.2108), (100, 0.1121, 0.0686)])
def test_tian_kennedy_table(pe, maximum, mean):
    q, a, k = 2e8, 0.2e-3, 46.0
    theta = heat.tian_kennedy_circular(q, a, k, pe)
    within_quoted(theta.maximum * k / (q * a), maximum, 4)
    within_quoted(theta.mean * k / (q * a), mean, 4)


def test_tian_kennedy_limits():
    stationary = heat.tian_kennedy_circular(1.0, 1.0, 1.0, 0.0)
    within_quoted(stationary.maximum, 1.0001, 4)
    assert stationary.maximum == pytest.approx(1.0, rel=2e-4)  # exact stationary disc: q a/k
    within_quoted(stationary.mean, 0.8489, 4)
    assert stationary.mean == pytest.approx(8.0 / (3.0 * math.pi), rel=2e-4)
    pe = 1e10
    fast = heat.tian_kennedy_circular(1.0, 1.0, 1.0, pe)
    assert fast.maximum * math.sqrt(pe) == pytest.approx(2.0 / math.sqrt(math.pi), rel=1e-9)  # 1-D trailing edge
    within_quoted(fast.mean * math.sqrt(pe), 0.688, 3)
    assert fast.mean * math.sqrt(pe) == pytest.approx(0.6886, rel=1e-3)  # disc average of the 1-D solution
    with pytest.raises(ValueError):
        heat.tian_kennedy_circular(1.0, 1.0, 1.0, -1.0)

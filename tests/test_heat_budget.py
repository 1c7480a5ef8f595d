"""Heat budget of the face gear points (issues 5 and 19): conservation, closed forms, trends, the in-ellipse
frictional and oil-film heat."""

import dataclasses
import math

import numpy as np
import pytest

from facegear_tehl.case import load_case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.ehl.domain import venner_lubrecht_domain
from facegear_tehl.ehl.scaling import scaling_for
from facegear_tehl.heat_budget import heat_budget, point_budget
from facegear_tehl.points import contact_analysis, select_points
from facegear_tehl.run import run_case
from facegear_tehl.solution import Field, Outcome, PointSolution


@pytest.fixture
def run(facegear_run):
    """The default face gear case on --grid 65, solved once per session (conftest.py)."""
    return facegear_run


def test_heat_table_has_one_row_per_point(run):
    assert list(run.heat["point"].values) == ["S1", "S2", "S3", "S4", "S5"]
    for name, column in run.heat.items():
        if name != "point":
            assert np.isfinite(column.values).all(), name


def test_partition_sums_to_one_and_power_splits(run):
    h = run.heat
    assert np.allclose(h["partition_1"].values + h["partition_2"].values, 1.0, atol=1e-12)
    assert np.allclose(h["friction_power_1"].values + h["friction_power_2"].values, h["friction_power"].values,
                       rtol=1e-12)


def test_duty_ratio_at_the_pitch_point_is_b_over_pi_r_pitch(run):
    # At S3 the contact is on the pinion pitch circle, r = m N1/2 = 6.35 mm * 25/2 (docs/method.md §1.1), and on the
    # face gear at L0 = m N2/2 = 508 mm: t_c/T = b/(pi r) (seed paper §3.4: t_c = 2b/v_t).
    s3 = next(p for p in run.points if p.name == "S3")
    b = s3.scalar("b")
    assert s3.scalar("duty_ratio_1") == pytest.approx(b / (math.pi * 0.00635 * 25 / 2), rel=1e-9)
    assert s3.scalar("duty_ratio_2") == pytest.approx(b / (math.pi * 0.00635 * 160 / 2), rel=1e-9)


def test_distributed_heat_sums_to_the_friction_power(run):
    for p in run.points:
        x, y = p.axes["x"].values, p.axes["y"].values
        cell = (x[1] - x[0]) * (y[1] - y[0])
        power = p.scalar("friction_power")
        for field in ("heat_flux_by_pressure", "heat_flux_by_shear"):
            total = p.fields[field].values.sum() * cell
            assert total == pytest.approx(power, rel=1e-9, abs=1e-9), (p.name, field)


def test_friction_heat_and_flash_temperature_are_smallest_at_the_pitch_point(run):
    h = run.heat
    names = list(h["point"].values)
    for column in ("mu", "friction_power", "flash_temperature"):
        values = list(h[column].values)
        assert names[int(np.argmin(values))] == "S3", column
    # the solved surface rise and the Blok flash temperature are both largest at the most sliding point, S1
    assert names[int(np.argmax(h["flash_temperature"].values))] == "S1"
    assert names[int(np.argmax(h["surface_rise_max"].values))] == "S1"


def test_oil_film_holds_a_few_percent_of_the_frictional_heat(run):
    # seed paper §3.5: about 1 %; here 2-6 % (docs/accuracy.md discusses the difference)
    ratio = run.heat["oil_to_friction_ratio"].values
    assert ((ratio > 0.001) & (ratio < 0.1)).all()


def _synthetic_solution(srr):
    """A solved point made by hand on a 5 x 5 grid with nodes at x = (-2, -1, 0, 1, 2) b, y = (-2, -1, 0, 1, 2) a:
    the Hertz ellipse holds five of them, (0, 0), (+-b, 0), (0, +-a), each standing for a cell of area a b.
    Uniform pressure 0.5 GPa, film 1 um and mean temperature rise 12 K; the dissipation per unit area grows with
    the node numbers, so that the ellipse's share is not a fixed fraction of the domain's."""
    case = load_case("cases/ball_on_disc_sliding.yaml")
    lub = case.lubricant
    point = ContactPoint.from_rolling_sliding("hand", 0.01, 0.02, 40.0, 3.0, srr, 0.0, case.materials.body_1,
                                              case.materials.body_2)
    a, b, mu = 2.0e-4, 1.0e-4, 0.03
    x, y = b * np.arange(-2.0, 3.0), a * np.arange(-2.0, 3.0)
    j, i = np.meshgrid(np.arange(5), np.arange(5), indexing="ij")
    column = 1.0e7 * (1.0 + i + 10.0 * j)  # W/m^2
    shape = (5, 5)
    fields = {
        "pressure": Field(np.full(shape, 0.5e9), "Pa", ""),
        "film_thickness": Field(np.full(shape, 1.0e-6), "m", ""),
        "temperature_mean": Field(np.full(shape, lub.inlet_temperature + 12.0), "K", ""),
        "dissipation_column": Field(column, "W/m^2", ""),
        **{f"shear_stress_{k}_{c}": Field(np.full(shape, 1.0e6), "Pa", "") for k in (1, 2) for c in "xy"},
    }
    scalars = {"mu": (mu, "1"), "a": (a, "m"), "b": (b, "m"), "p_hertz": (0.6e9, "Pa"),
               "dT_surface_1_max": (3.0, "K"), "dT_surface_2_max": (4.0, "K"),
               "dissipated_power": (float(column.sum() * a * b), "W")}
    solution = PointSolution(name="hand", outcome=Outcome.CONVERGED, message="", scalars=scalars, fields=fields,
                             axes={"x": Field(x, "m", ""), "y": Field(y, "m", "")})
    return point, solution, lub, column


def test_in_ellipse_heat_budget_by_hand_on_a_synthetic_point():
    """Q_f as the seed defines it (mu F |v_s| t_c), the film's dissipation and the oil's heat in the same Hertz
    ellipse, and their ratios, against a hand calculation: the five nodes in the ellipse, rho(p, T) of Dowson &
    Higginson (1966), rho/rho_0 = (0.59 + 1.34 p)/(0.59 + p) (p in GPa), times (1 - alpha_T dT)."""
    point, solution, lub, column = _synthetic_solution(srr=0.5)
    values, _ = point_budget(point, solution, lub)
    a, b, mu = 2.0e-4, 1.0e-4, 0.03
    cell = a * b
    dwell = 2.0 * b / 3.0  # t_c = 2b/U_e
    # nodes in the ellipse: (j, i) = (2, 2), (2, 1), (2, 3), (1, 2), (3, 2); column = 1e7 (1 + i + 10 j)
    inside = 1.0e7 * ((1 + 2 + 20) + (1 + 1 + 20) + (1 + 3 + 20) + (1 + 2 + 10) + (1 + 2 + 30))
    assert values["dissipated_power_ellipse"] == pytest.approx(inside * cell, rel=1e-12)
    assert values["frictional_heat_ellipse"] == pytest.approx(inside * cell * dwell, rel=1e-12)
    sliding = 0.5 * 3.0  # |v_s| = SRR U_e
    assert values["frictional_heat_seed"] == pytest.approx(mu * 40.0 * sliding * dwell, rel=1e-12)
    rho = lub.density * (0.59 + 1.34 * 0.5) / (0.59 + 0.5) * (1.0 - lub.thermal_expansion * 12.0)
    q_oil = 5 * lub.specific_heat * rho * 1.0e-6 * 12.0 * cell
    assert values["oil_film_heat"] == pytest.approx(q_oil, rel=1e-12)
    assert values["oil_to_ellipse_friction_ratio"] == pytest.approx(q_oil / (inside * cell * dwell), rel=1e-12)
    assert values["oil_to_seed_friction_ratio"] == pytest.approx(q_oil / (mu * 40.0 * sliding * dwell), rel=1e-12)
    # the whole domain: 25 nodes
    assert values["frictional_heat"] == pytest.approx(column.sum() * cell * dwell, rel=1e-12)
    assert values["oil_film_heat_domain"] == pytest.approx(5.0 * q_oil, rel=1e-12)
    # pure rolling: the seed's Q_f is zero and its ratio undefined, left out of the point and of the /heat table;
    # the film's own in-ellipse heat is unchanged
    rolling, rolling_solution, _, _ = _synthetic_solution(srr=0.0)
    rolled, _ = point_budget(rolling, rolling_solution, lub)
    assert rolled["frictional_heat_seed"] == 0.0 and "oil_to_seed_friction_ratio" not in rolled
    assert rolled["oil_to_ellipse_friction_ratio"] == pytest.approx(values["oil_to_ellipse_friction_ratio"], rel=1e-12)
    out, table = heat_budget([point, rolling], [solution, rolling_solution], lub)
    assert "oil_to_seed_friction_ratio" not in table and "oil_to_ellipse_friction_ratio" in table
    assert table["frictional_heat_seed"].units == "J" and "seed" in table["frictional_heat_seed"].description
    assert out[0].scalars["oil_to_seed_friction_ratio"][1] == "1"
    assert "oil_to_seed_friction_ratio" not in out[1].scalars


def test_the_seeds_frictional_heat_is_zero_at_the_pitch_point_and_the_films_is_not(run):
    """On the default case: Q_f,seed = mu F |v_s| t_c vanishes at S3 (pure rolling), the film's in-ellipse
    dissipation does not (rolling traction), and the in-ellipse figures are parts of the domain's."""
    h = run.heat
    names = list(h["point"].values)
    s3 = names.index("S3")
    seed, ellipse = h["frictional_heat_seed"].values, h["frictional_heat_ellipse"].values
    assert seed[s3] < 1e-12 * ellipse[s3] and ellipse[s3] > 0.0
    assert (ellipse < h["frictional_heat"].values).all()
    assert (h["oil_film_heat"].values < h["oil_film_heat_domain"].values).all()
    assert "oil_to_seed_friction_ratio" not in h  # undefined at S3
    for p in run.points:
        if p.name != "S3":
            assert p.scalar("oil_to_seed_friction_ratio") == pytest.approx(
                p.scalar("oil_film_heat") / p.scalar("frictional_heat_seed"), rel=1e-12)


def _in_ellipse_ratios(name, inlet_extension):
    """Q_oil/Q_f,ellipse and Q_oil/Q_f,seed of one default-case point, its inlet lengthened by `inlet_extension`
    minor semi-axes at the default spacing (6 b over 256 cells) and grid_y."""
    case = load_case("cases/facegear_110.yaml")
    point = select_points(list(contact_analysis(case).points), [name])[0]
    domain_x, domain_y = venner_lubrecht_domain(scaling_for(point, case.lubricant))
    cells = 256 * (6.0 + inlet_extension) / 6.0
    solver = dataclasses.replace(case.solver, grid=int(cells) + 1, grid_y=65,
                                 domain_x=(domain_x[0] - inlet_extension, domain_x[1]), domain_y=domain_y)
    solved = run_case(dataclasses.replace(case, solver=solver), points=[name], jobs=1).points[0]
    assert solved.converged
    return solved.scalar("oil_to_ellipse_friction_ratio"), solved.scalar("oil_to_seed_friction_ratio")


@pytest.mark.slow
@pytest.mark.parametrize("name", [
    "S1",
    pytest.param("S5", marks=pytest.mark.xfail(strict=True, reason=(
        "measured +8.7 % (in ellipse) and +14 % (seed): at S5 the film in the ellipse itself changes with the "
        "inlet, mu -20 %, h_c +4.3 %, dT_max -8.5 % (the default domain starves it; issue 19 item 3)"))),
])
def test_in_ellipse_heat_ratios_barely_depend_on_the_inlet_length(name):
    """Issue 19 item 5: lengthening the inlet from 4.5 b to 10.5 b (257 -> 513 nodes along x, same spacing)
    changes the in-ellipse ratios by < 5 % (S1 measured +4.0 % and +4.3 %; the whole-domain Q_oil/Q_f -8 %)."""
    short = _in_ellipse_ratios(name, 0.0)
    long = _in_ellipse_ratios(name, 6.0)
    for before, after in zip(short, long):
        assert abs(after / before - 1.0) < 0.05, (short, long)

"""`tehl plot`: every figure type renders from real result files (plain contact, face gear) and from a face
gear file carrying thermal and heat-budget data, without a matplotlib warning; the default set is the small
one (a centre-line figure per point and one overview sheet instead of a map and a surface per field); every
default figure fits its canvas; ΔT maps are centred at 0 on one scale for all points; fields that are zero
to round-off and figure types without data are skipped with one line; trends draw no line across a jump of
the tooth load; files from failed or partial runs draw what is there."""

from __future__ import annotations

from dataclasses import replace
import json
import math
from pathlib import Path
import warnings

from click.testing import CliRunner
import h5py
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
import numpy as np
from PIL import Image
import pytest

from facegear_tehl.case import Case, load_case
from facegear_tehl.cli import tehl
from facegear_tehl.plots import PlotReport, common, figure_types, plot_file
from facegear_tehl.plots.field_data import field_label, field_map, round_off_names, section, section_directions
from facegear_tehl.plots.over_points import continuous_runs
from facegear_tehl.points import contact_analysis
from facegear_tehl.results import RunResult, read_result, write_result
from facegear_tehl.run import run_case
from facegear_tehl.solution import Field, Outcome, PointSolution
from facegear_tehl.sweep import run_sweep

import synthetic

FACE_GEAR = synthetic.CASES / "facegear_110.yaml"
MAP_FIGURES = ("pressure_contour", "film_contour")
SURFACE_FIGURES = ("pressure_surface", "film_surface")
THERMAL_FIELDS = ("temperature_mean", "temperature_mid", "temperature_surface_1", "temperature_surface_2",
                  "heat_flux_1", "heat_flux_2")  # heat_flux_by_pressure, _by_shear: zero at the pitch point S3
CONTACT_FIGURES = ("contact_path", "contact_curvatures", "contact_speeds", "contact_load")
DPI = 80


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("plots")


@pytest.fixture(scope="module")
def ball_run() -> RunResult:
    return run_case(load_case(synthetic.BALL_ON_DISC), grid=33, jobs=1)


def _face_gear(thermal: str, rheology: str, eyring_stress: float) -> Case:
    """The shipped face gear case with the thermal model and rheology set here, whatever the file says."""
    case = load_case(FACE_GEAR)
    lubricant = replace(case.lubricant, rheology=rheology, eyring_stress=eyring_stress)
    return replace(case, solver=replace(case.solver, thermal=thermal), lubricant=lubricant)


@pytest.fixture(scope="module")
def gear_run() -> RunResult:
    """Isothermal Newtonian face gear run at S1, S3, S5."""
    return run_case(_face_gear("off", "newtonian", math.inf), grid=33, points=["S1", "S3", "S5"], jobs=1)


@pytest.fixture(scope="module")
def ball_file(ball_run, folder) -> Path:
    return write_result(ball_run, folder / "ball.h5")


@pytest.fixture(scope="module")
def gear_file(gear_run, folder) -> Path:
    return write_result(gear_run, folder / "gear.h5")


@pytest.fixture(scope="module")
def thermal_file(folder) -> Path:
    """A thermal Ree-Eyring face gear run (S1, S3) with its heat-budget table."""
    run = run_case(_face_gear("full", "ree_eyring", 1.0e7), grid=33, points=["S1", "S3"], jobs=1)
    assert run.heat, "tehl run writes the /heat table of a thermal run"
    return write_result(run, folder / "thermal.h5")


@pytest.fixture(scope="module")
def sweep_file(folder) -> Path:
    swept = run_sweep(load_case(synthetic.BALL_ON_DISC), (17, 33, 65), jobs=1)
    return write_result(swept.run, folder / "sweep.h5")


def _plot(path: Path, out: Path, **options) -> PlotReport:
    """Plot with every warning turned into an error."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return plot_file(path, out, dpi=DPI, **options)


def _check_images(report: PlotReport, out: Path, stems: list[str]) -> None:
    """Exactly the expected files, each a valid PNG of sensible size."""
    assert sorted(p.name for p in report.written) == sorted(f"{stem}.png" for stem in stems)
    for stem in stems:
        path = out / f"{stem}.png"
        assert path.stat().st_size > 10_000, path
        with Image.open(path) as image:
            image.verify()
        with Image.open(path) as image:
            assert image.format == "PNG" and min(image.size) > 200, (path, image.size)


def _skipped(report: PlotReport, what: str) -> list[str]:
    return [line for line in report.skipped if line.startswith(f"skipped {what}")]


def test_the_overview_title_of_a_single_contact_stays_within_its_sheet(ball_file, tmp_path, monkeypatch):
    """One point makes the narrowest sheet; its title (the case, the subject, the note on the grid's stepped outlines)
    is wrapped to the sheet's width, not cut at both edges."""
    figures = _capture(monkeypatch)
    _plot(ball_file, tmp_path, what=["overview"])
    fig = figures["overview"]
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    box, sheet = fig._suptitle.get_window_extent(canvas.get_renderer()), fig.bbox
    assert "stepped outlines" in fig._suptitle.get_text()
    assert sheet.x0 <= box.x0 and box.x1 <= sheet.x1


def test_plain_contact_draws_centre_line_overview_and_convergence_and_skips_the_rest(ball_file, tmp_path):
    report = _plot(ball_file, tmp_path)
    _check_images(report, tmp_path, ["contact_centreline", "overview", "convergence"])
    for what in ("trends", "friction", "heat", "contact", "convergence sweep", "fields temperature", "cycle"):
        assert len(_skipped(report, what)) == 1, (what, report.skipped)


def test_the_default_set_is_a_figure_per_point_and_one_per_family(gear_file, tmp_path):
    """Default: one centre-line figure per point and one overview sheet; no map or surface per field."""
    report = _plot(gear_file, tmp_path)
    centre = [f"{p}_centreline" for p in ("S1", "S3", "S5")]
    _check_images(report, tmp_path, centre + ["overview", "trends", *CONTACT_FIGURES, "convergence", "cycle"])
    assert _skipped(report, "trends ΔT") and _skipped(report, "friction") and _skipped(report, "heat")
    everything = _plot(gear_file, tmp_path / "all", what=figure_types("all"))
    per_field = [f"{p}_{f}" for p in ("S1", "S3", "S5") for f in MAP_FIGURES + SURFACE_FIGURES]
    assert sorted(p.stem for p in everything.written) == sorted(
        [p.stem for p in report.written] + per_field)


def test_thermal_face_gear_draws_temperatures_friction_and_heat_by_default(thermal_file, tmp_path):
    report = _plot(thermal_file, tmp_path, points=["S3"])
    heat = ["friction", "heat_power", "heat_oil_film"]
    _check_images(report, tmp_path,
                  ["S3_centreline", "overview", "trends", *CONTACT_FIGURES, "convergence", *heat, "cycle"])
    assert report.skipped == [
        "skipped fields S3: heat_flux_by_pressure, heat_flux_by_shear: zero to round-off (|value| below 1e-12 of "
        "the largest field in the same units)",
        "skipped convergence sweep: no /sweep table in the file (written by tehl sweep)"]


def test_maps_and_surfaces_on_request_leave_out_the_fields_zero_to_round_off(thermal_file, tmp_path):
    """At the pitch point S3 the sliding speed is zero, so the frictional heat mu F |v_s| and the two fluxes
    that spread it are zero; the conducted fluxes heat_flux_1/2 are not."""
    report = _plot(thermal_file, tmp_path, points=["S3"], what=["maps", "surfaces"])
    fields = [f"S3_{f}" for f in MAP_FIGURES + SURFACE_FIGURES]
    fields += [f"S3_{t}_{k}" for t in THERMAL_FIELDS for k in ("contour", "surface")]
    _check_images(report, tmp_path, fields)
    assert len(_skipped(report, "fields S3")) == 1


def test_round_off_is_relative_to_the_fields_in_the_same_units():
    flux = np.array([[0.0, 2.0e7], [-1.0e7, 5.0e6]])
    fields = {"q": Field(flux, "W/m^2", ""), "q_zero": Field(3e-16 * flux, "W/m^2", ""),
              "q_small": Field(1e-6 * flux, "W/m^2", ""), "p": Field(1e-9 * np.abs(flux), "Pa", "")}
    assert round_off_names(fields) == ["q_zero"]


def _capture(monkeypatch) -> dict:
    """Figures by file stem as `plot` saves them."""
    figures = {}
    save = common.Output.save

    def capture(self, figure, stem):
        figures[stem] = figure
        save(self, figure, stem)

    monkeypatch.setattr(common.Output, "save", capture)
    return figures


def test_every_default_figure_fits_its_canvas(thermal_file, tmp_path, monkeypatch):
    """No title, label, legend or tick label outside the figure (a clipped title shows as a tight bounding
    box larger than the canvas)."""
    figures = _capture(monkeypatch)
    _plot(thermal_file, tmp_path)
    assert len(figures) == 13
    for stem, figure in figures.items():
        box = figure.get_tightbbox()
        width, height = figure.get_size_inches()
        tolerance = 1.0 / DPI  # one pixel
        assert box.x0 >= -tolerance and box.y0 >= -tolerance, (stem, box)
        assert box.x1 <= width + tolerance and box.y1 <= height + tolerance, (stem, box, width, height)


def test_temperature_maps_are_rises_centred_at_zero_each_on_its_own_scale(thermal_file, tmp_path, monkeypatch):
    """ΔT = T - T_inlet with T_inlet = 40 degC (the case file); each point on [-L, L], L its own largest |ΔT| (a scale
    shared with S1's 90 K rise left S3's map blank), each with its colour bar."""
    figures = _capture(monkeypatch)
    _plot(thermal_file, tmp_path, what=["overview"])
    result = read_result(thermal_file)
    rises = [np.asarray(p.fields["temperature_mid"].values) - (40.0 + 273.15) for p in result.points.values()]
    images = [image for ax in figures["overview"].axes for image in ax.get_images()
              if image.get_cmap().name == "RdBu_r"]
    assert len(images) == 2
    for image, rise, point in zip(images, rises, result.points.values()):
        low, high = image.get_clim()
        assert low == -high
        assert high >= np.abs(rise).max()
        assert high == pytest.approx(max(point.scalars["dT_max"], -point.scalars["dT_min"]))
        assert image.colorbar is not None
    assert len({image.get_clim() for image in images}) == 2
    assert any(rise.min() < 0.0 for rise in rises), "the S3 outlet cools below the inlet (expansion)"


def test_the_place_of_dT_min_is_named_only_inside_the_domain(thermal_file, tmp_path, monkeypatch):
    """A ΔT_min of 0 is the inlet itself (no film below the inlet temperature) and a minimum on the domain edge is
    a boundary value: no location is printed for them; a location printed is more than one node inside the grid."""
    figures = _capture(monkeypatch)
    _plot(thermal_file, tmp_path, what=["centreline"])
    result = read_result(thermal_file)
    for name, point in result.points.items():
        labels = [t.get_text() for ax in figures[f"{name}_centreline"].axes if ax.get_legend()
                  for t in ax.get_legend().get_texts() if "T_{min}" in t.get_text()]
        assert len(labels) == 1
        x, y = (np.asarray(point.axes[k].values) for k in ("x", "y"))
        place = point.scalars["x_dT_min"], point.scalars["y_dT_min"]
        interior = all(axis[1] < p < axis[-2] for axis, p in zip((x, y), place))
        if point.scalars["dT_min"] < 0.0 and interior:
            assert f"= {place[0] / point.scalars['b']:.2f}" in labels[0], labels
        else:
            assert "x/b" not in labels[0], labels
            if point.scalars["dT_min"] >= 0.0:
                assert "none below the inlet" in labels[0]


def test_trends_draw_no_line_across_a_jump_of_the_tooth_load(gear_run, tmp_path, monkeypatch):
    """With a contact ratio eps between 1 and 2, one pair carries the load between s_end - p_b and
    s_start + p_b, two pairs outside; the load jumps there. Points either side of a jump are not joined."""
    result = read_result(write_result(gear_run, tmp_path / "gear.h5"))
    start, end, pitch = (result.contact_scalars[k] for k in ("path_start", "path_end", "base_pitch"))
    assert 1.0 < (end - start) / pitch < 2.0
    jumps = (end - pitch, start + pitch)
    places = {"A": start, "B": jumps[0] - 0.4e-3, "C": jumps[0] + 0.4e-3, "D": jumps[1] - 0.4e-3,
              "E": jumps[1] + 0.4e-3, "F": end}
    s1 = gear_run.points[0]
    points = tuple(replace(s1, name=name, scalars={**s1.scalars, "path_coordinate": (s, "m")})
                   for name, s in places.items())
    path = write_result(replace(gear_run, points=points), tmp_path / "moved.h5")
    moved = read_result(path)
    assert continuous_runs(moved, list(places)) == [["A", "B"], ["C", "D"], ["E", "F"]]
    figures = _capture(monkeypatch)
    _plot(path, tmp_path / "figures", what=["trends"])
    for ax in figures["trends"].axes:
        for line in ax.get_lines():
            x = np.asarray(line.get_xdata(), dtype=float)
            if len(x) > 1 and line.get_linestyle() != "None" and line.get_label() != "$p_h$ along the path":
                assert not any(x.min() < 1e3 * s < x.max() for s in jumps), (line.get_label(), x)


def test_trend_error_bars_are_the_bounds_and_an_unresolved_figure_gets_a_cross(gear_run, tmp_path, monkeypatch):
    """The h_c bar of each point spans value (1 -+ bound) (error_bound_h_c, not the smaller x-estimate); a point
    whose h_min is unresolved has no h_min bar and a cross at its value."""
    bounds = {"S1": 0.05, "S3": 0.10, "S5": 0.20}
    points = tuple(replace(p, scalars={**p.scalars, "error_estimate_h_c": (0.001, "1"),
                                       "error_bound_h_c": (bounds[p.name], "1"), "unresolved_h_c": (0.0, "1"),
                                       "unresolved_h_min": (float(p.name == "S3"), "1"),
                                       "error_bound_h_min": (0.01, "1")})
                   for p in gear_run.points)
    path = write_result(replace(gear_run, points=points), tmp_path / "bounds.h5")
    figures = _capture(monkeypatch)
    _plot(path, tmp_path / "figures", what=["trends"])
    film = next(ax for ax in figures["trends"].axes if ax.get_title() == "film thickness")
    containers = {c.get_label(): c for c in film.containers}
    h_c = {p.name: p.scalars["h_c"][0] * 1e6 for p in points}  # µm, the axis unit
    spans = sorted((seg[1][1] - seg[0][1]) for seg in containers["$h_c$ (central)"].lines[2][0].get_segments())
    assert spans == pytest.approx(sorted(2 * bounds[n] * h_c[n] for n in bounds), rel=1e-6)
    h_min_bars = [seg for seg in containers["$h_{min}$ (minimum)"].lines[2][0].get_segments() if seg[1][1] > seg[0][1]]
    assert len(h_min_bars) == 2  # S1 and S5; none at the unresolved S3
    crosses = [line for line in film.get_lines() if line.get_marker() == "x" and len(line.get_xdata())]
    assert [float(y) for line in crosses for y in line.get_ydata()] == pytest.approx(
        [points[1].scalars["h_min"][0] * 1e6])
    legend = [t.get_text() for ax in figures["trends"].axes if ax.get_legend() for t in ax.get_legend().get_texts()]
    assert "error bars: the solver's error bounds" in legend and "cross: unresolved (no bound)" in legend


def test_convergence_draws_the_tolerances_of_the_case(gear_file, tmp_path, monkeypatch):
    figures = _capture(monkeypatch)
    _plot(gear_file, tmp_path, what=["convergence"])
    case = load_case(FACE_GEAR)
    levels = {float(line.get_ydata()[0]) for ax in figures["convergence"].axes for line in ax.get_lines()
              if line.get_linestyle() == "--" and len(set(line.get_ydata())) == 1}
    assert {case.solver.tolerance, case.solver.load_tolerance} <= levels


def test_convergence_ticks_the_nodes_panel_at_the_node_counts_the_file_holds(gear_file, tmp_path, monkeypatch):
    """The nodes each cycle ran on span less than a decade (65-513): a log axis had no tick label at all."""
    figures = _capture(monkeypatch)
    _plot(gear_file, tmp_path, what=["convergence"])
    with h5py.File(gear_file, "r") as h5:
        taken = {int(v) for name in h5["points"] for v in h5["points"][name]["cycle_nodes_history"][()]}
    panel = next(ax for ax in figures["convergence"].axes if ax.get_ylabel() == "nodes along x")
    figures["convergence"].canvas.draw()
    assert panel.get_yscale() == "linear"
    assert {int(label.get_text()) for label in panel.get_yticklabels()} == taken


def test_convergence_labels_the_films_per_cycle_by_their_values_and_names(gear_file, tmp_path, monkeypatch):
    """A film that settles in its fifth digit was labelled by matplotlib's offset ("1e-5+2.262e-1") under the key's
    words ("cycle h c"): the ticks now read the film in µm and the label names it."""
    figures = _capture(monkeypatch)
    _plot(gear_file, tmp_path, what=["convergence"])
    fig = figures["convergence"]
    FigureCanvasAgg(fig).draw()
    panels = {ax.get_ylabel(): ax for ax in fig.axes}
    for label in ("$h_c$ (µm)", "$h_{min}$ (µm)"):
        assert label in panels and panels[label].yaxis.get_offset_text().get_text() == ""


def test_convergence_draws_the_settled_floor_bound_the_file_holds(gear_file, tmp_path, monkeypatch):
    """Plots read files only: the pressure's settled-floor bound is the file's band times the case's tolerance (a
    band rewritten in the file moves the line); a file without the bands (format 1.2) gets the tolerances alone."""
    tolerance = load_case(FACE_GEAR).solver.tolerance
    for name, bands, expected in (("rewritten", {"pressure_floor_band": 7.0}, {7.0 * tolerance}), ("old", None, set())):
        path = tmp_path / f"{name}.h5"
        path.write_bytes(gear_file.read_bytes())
        with h5py.File(path, "r+") as h5:
            if bands is None:
                del h5.attrs["convergence_bands"]
            else:
                h5.attrs["convergence_bands"] = json.dumps(bands)
        figures = _capture(monkeypatch)
        _plot(path, tmp_path / name, what=["convergence"])
        bounds = {float(line.get_ydata()[0]) for ax in figures["convergence"].axes for line in ax.get_lines()
                  if line.get_label().startswith("settled-floor bound") and len(line.get_ydata())}
        assert bounds == expected


def test_sweep_file_draws_error_vs_grid_and_cost(sweep_file, tmp_path, monkeypatch):
    figures = _capture(monkeypatch)
    report = _plot(sweep_file, tmp_path, what=["trends", "friction", "convergence"])
    _check_images(report, tmp_path, ["convergence", "sweep_error"])
    assert len(_skipped(report, "trends")) == 1 and len(_skipped(report, "friction")) == 1
    fig = figures["sweep_error"]
    FigureCanvasAgg(fig).draw()
    for ax in fig.axes:  # the figures named as on the other sheets, the errors as plain numbers
        assert {text.get_text() for text in ax.get_legend().get_texts()} <= {"$p_{max}$", "$h_c$", "$h_{min}$"}
        labels = [tick.get_text() for tick in ax.get_yticklabels() if tick.get_text()]
        assert labels and all(float(label) > 0.0 for label in labels)


def test_friction_from_the_heat_table_alone(gear_run, tmp_path):
    heat = {"mu_xu": Field(np.array([0.05, 0.004, 0.04]), "1", "Xu et al. (2007)")}
    path = write_result(replace(gear_run, heat=heat), tmp_path / "heat.h5")
    report = _plot(path, tmp_path / "figures", what=["friction", "heat"])
    _check_images(report, tmp_path / "figures", ["friction"])
    for what in ("friction mu:", "heat power", "heat energy"):
        assert len(_skipped(report, what)) == 1, (what, report.skipped)


def test_partial_run_draws_what_is_there_and_says_what_is_missing(gear_run, tmp_path):
    s1, s3, s5 = gear_run.points
    failed = PointSolution(name="S3", outcome=Outcome.FAILED, message="failed: RuntimeError: diverged", scalars={
        "path_coordinate": s3.scalars["path_coordinate"]}, fields={}, axes={})
    stalled = replace(s5, outcome=Outcome.NOT_CONVERGED, message="residual above tolerance after 40 cycles")
    path = write_result(replace(gear_run, points=(s1, failed, stalled), failed=("S3",)), tmp_path / "partial.h5")
    assert read_result(path).status == "failed"
    report = _plot(path, tmp_path / "figures", what=["centreline", "overview", "trends", "convergence"])
    fields = [f"{p}_centreline" for p in ("S1", "S5")]
    _check_images(report, tmp_path / "figures", fields + ["overview", "trends", "convergence"])
    assert _skipped(report, "fields S3") == [
        "skipped fields S3: no fields in the file (failed: RuntimeError: diverged)"]


def test_a_single_point_with_results_skips_trends(gear_run, tmp_path):
    s1, s3, s5 = gear_run.points
    empty = [PointSolution(name=p.name, outcome=Outcome.FAILED, message="failed: x", scalars={}, fields={}, axes={})
             for p in (s3, s5)]
    path = write_result(replace(gear_run, points=(s1, *empty), failed=("S3", "S5")), tmp_path / "one.h5")
    report = _plot(path, tmp_path / "figures", what=["trends"])
    assert report.written == [] and _skipped(report, "trends") == [
        "skipped trends: results at 1 point(s); trends need two or more"]


@pytest.mark.parametrize("fmt", ["pdf", "svg"])
def test_vector_formats(gear_file, tmp_path, fmt):
    report = _plot(gear_file, tmp_path, what=["trends"], fmt=fmt)
    assert [p.name for p in report.written] == [f"trends.{fmt}"] and report.written[0].stat().st_size > 10_000


@pytest.mark.parametrize("angle", [0.0, 30.0])
def test_profiles_follow_the_hertz_pressure_along_and_across(tmp_path, angle):
    """On the analytic Hertz field both sections are p_h sqrt(1 - t^2), t in Hertz radii, at any skew."""
    case = synthetic.ball_on_disc()
    solution = synthetic.solution(contact_analysis(case).points[0], nx=129, ny=129)
    solution = replace(solution, scalars={**solution.scalars, "entrainment_angle": (angle, "deg")})
    result = read_result(write_result(RunResult(case=case, points=(solution,)), tmp_path / "hertz.h5"))
    point = result.points["contact"]
    m = field_map(point, "pressure", field_label(result, "pressure"), None, 0.0)
    for direction in section_directions(point):
        t, values = section(m, direction)
        exact = point.scalars["p_hertz"] * 1e-6 * np.sqrt(np.clip(1.0 - t**2, 0.0, None))
        inner, outer = np.abs(t) < 0.9, np.abs(t) > 1.1  # linear interpolation is poor where sqrt is steep
        assert np.max(np.abs(values - exact)[inner]) < 0.01 * m.vmax
        assert np.all(values[outer] == 0.0)
        assert t.min() < -1.0 and t.max() > 1.0


def _invoke(*args) -> object:
    return CliRunner().invoke(tehl, ["plot", *map(str, args)])


def test_cli_lists_the_files_written(gear_file, tmp_path):
    result = _invoke(gear_file, "--what", "trends,contact", "-o", tmp_path, "--dpi", DPI)
    assert result.exit_code == 0, result.output
    written = [line.strip() for line in result.output.splitlines() if line.startswith("  ")]
    assert sorted(Path(p).name for p in written) == sorted(f"{s}.png" for s in ("trends", *CONTACT_FIGURES))
    assert all(Path(p).is_file() for p in written)


def test_cli_skips_a_figure_type_without_data_with_one_line(ball_file, tmp_path):
    result = _invoke(ball_file, "--what", "contact", "-o", tmp_path / "figures")
    assert result.exit_code == 0, result.output
    assert result.output.count("skipped contact:") == 1
    assert not (tmp_path / "figures").exists()


def test_cli_default_folder_is_next_to_the_result(gear_file, tmp_path):
    copy = tmp_path / "copy.h5"
    copy.write_bytes(gear_file.read_bytes())
    result = _invoke(copy, "--what", "trends", "--dpi", DPI)
    assert result.exit_code == 0, result.output
    assert (tmp_path / "copy_plots" / "trends.png").is_file()


@pytest.mark.parametrize(
    "args, message",
    [
        (["--what", "pressure"], "error: --what: got 'pressure'; expected figure types among: default, all"),
        (["--point", "S2"], "error: --point: got 'S2'; expected point names of the file among: S1, S3, S5"),
        (["--format", "jpg"], "error: --format: got 'jpg'; expected one of png, pdf, svg"),
    ],
)
def test_cli_bad_options_exit_2_with_one_line(gear_file, tmp_path, args, message):
    result = _invoke(gear_file, *args, "-o", tmp_path / "figures")
    assert result.exit_code == 2
    assert result.output.startswith(message) and result.output.count("\n") == 1
    assert not (tmp_path / "figures").exists()


def test_cli_missing_or_foreign_file_exits_2(tmp_path):
    for path in (tmp_path / "absent.h5", synthetic.BALL_ON_DISC):
        result = _invoke(path, "-o", tmp_path / "figures")
        assert result.exit_code == 2
        assert result.output.startswith(f"error: {path}:") and result.output.count("\n") == 1



def test_the_cycle_figure_draws_no_line_across_a_jump_of_the_tooth_load(gear_file, tmp_path, monkeypatch):
    """As the trends: the load share jumps at s_end - p_b and s_start + p_b (a contact ratio between 1 and 2), and
    S1, S3, S5 lie on either side of both jumps, so no series joins them (the meshing-point marks are vertical)."""
    result = read_result(gear_file)
    start, end, pitch = (result.contact_scalars[k] for k in ("path_start", "path_end", "base_pitch"))
    jumps_mm = (1e3 * (end - pitch), 1e3 * (start + pitch))
    figures = _capture(monkeypatch)
    _plot(gear_file, tmp_path, what=["cycle"])
    joined = 0
    for ax in figures["cycle"].axes:
        for line in ax.get_lines():
            x = np.asarray(line.get_xdata(), dtype=float)
            if "ISO/TR" in line.get_label():  # the mean coefficient: a horizontal line across the axes
                continue
            if len(x) > 1 and np.ptp(x) > 0.0 and line.get_linestyle() != "None":
                joined += 1
                assert not any(x.min() < s < x.max() for s in jumps_mm), (line.get_label(), x)
    markers = [line for ax in figures["cycle"].axes for line in ax.get_lines() if len(line.get_xdata()) == 1]
    # load share, p_h and h_min at three points (λ is a second scale of h_min, not a series)
    assert joined == 0 and len(markers) >= 3 * 3, "every series is drawn as markers, one run per point"


def _bar_heights(ax) -> dict[str, list[float]]:
    """Bar heights per legend label of one axes."""
    return {container.get_label(): [bar.get_height() for bar in container] for container in ax.containers}


def test_heat_held_over_the_domain_is_not_drawn_on_the_axis_of_the_heat_generated(thermal_file, tmp_path, monkeypatch):
    """Q_oil over the whole domain (a heat held, growing with the inlet length) has an axis of its own; every bar
    is the file's /heat value in mJ; the revolution-averaged powers are not on the axis of the instantaneous ones."""
    figures = _capture(monkeypatch)
    _plot(thermal_file, tmp_path, what=["heat"])
    heat = read_result(thermal_file).heat
    axes = [_bar_heights(ax) for ax in figures["heat_oil_film"].axes]
    holding = [bars for bars in axes if any("whole domain" in label and "held" in label for label in bars)]
    assert len(holding) == 1 and len(holding[0]) == 1
    assert holding[0].popitem()[1] == pytest.approx(1e3 * np.asarray(heat["oil_film_heat_domain"].values))
    generated = [bars for bars in axes if any(label.startswith("$Q_f") for label in bars)]
    assert len(generated) == 1 and not any("held" in label for label in generated[0])
    for bars in [_bar_heights(ax) for ax in figures["heat_power"].axes]:
        steady = [label for label in bars if "P_{ss" in label]
        assert not steady or len(steady) == len(bars)


def test_the_cycle_figure_names_the_axis_of_every_series_and_draws_the_film_once(thermal_file, tmp_path,
                                                                                 monkeypatch):
    """Where a panel has two y-axes, each legend entry says which axis it is read on; h_min and λ = h_min/σ are one
    curve with two scales (the second scale maps h_min by the file's σ), not two coinciding curves."""
    figures = _capture(monkeypatch)
    _plot(thermal_file, tmp_path, what=["cycle"])
    cycle = read_result(thermal_file).cycle
    panels = [ax for ax in figures["cycle"].axes if ax.get_legend() is not None]
    assert len(panels) == 5
    places = [ax.get_position().bounds for ax in figures["cycle"].axes]
    twins = {id(ax) for ax in panels if places.count(ax.get_position().bounds) == 2}
    assert len(twins) == 2, "load share with p_h, and μ with the sliding power"
    for ax in panels:
        labels = [text.get_text() for text in ax.get_legend().get_texts()]
        two_axes = id(ax) in twins
        assert all(label.endswith(("(left axis)", "(right axis)")) == two_axes for label in labels), labels
    film = next(ax for ax in panels if ax.get_ylabel().startswith("h_min"))
    assert {line.get_label() for line in film.get_lines() if not line.get_label().startswith("_")} == {"h_min"}
    scale = film.child_axes[0]
    sigma = np.asarray(cycle["h_min"].values) / np.asarray(cycle["film_parameter"].values)
    assert np.ptp(sigma) < 1e-9 * sigma.max(), "λ = h_min/σ with one σ along the path"
    assert f"σ {1e6 * sigma[0]:.3g} µm" in scale.get_ylabel()


def test_convergence_marks_each_stage_restart_from_the_solve_record(thermal_file, tmp_path, monkeypatch):
    """The temperature change per outer iteration jumps where the solve begins its next stage on a finer grid: the
    open squares sit exactly at the record's stage starts (the record rewritten in the file to stages beginning at
    outer iterations 0, 2 and 4 moves them there), and the changes are drawn relative to the point's rise against
    one tolerance line, not one line per point. The per-cycle panels mark the stages at their first V-cycle (a stage
not in the reported history, -1, is not marked)."""
    path = tmp_path / "staged.h5"
    path.write_bytes(thermal_file.read_bytes())
    with h5py.File(path, "r+") as h5:
        for name in h5["points"]:
            attrs = h5[f"points/{name}/solve"].attrs
            stages = json.loads(attrs["stages"])
            assert len(h5[f"points/{name}/thermal_change_history"]) > 4
            assert len(h5[f"points/{name}/pressure_change_history"]) > 3
            staged = [{**stages[-1], "first_outer": first, "first_cycle": cycle}
                      for first, cycle in ((0, 0), (2, 3), (4, -1))]
            attrs["stages"] = json.dumps(staged)
            attrs["stage_seconds"] = [0.0] * len(staged)
    figures = _capture(monkeypatch)
    _plot(path, tmp_path / "figures", what=["convergence"])
    case = load_case(FACE_GEAR)
    panel = next(ax for ax in figures["convergence"].axes if "T_{max}" in ax.get_ylabel())
    squares = [list(line.get_xdata()) for line in panel.get_lines() if line.get_marker() == "s" and
               len(line.get_xdata())]
    assert squares == [[2, 4]] * len(read_result(path).points)
    pressure = next(ax for ax in figures["convergence"].axes if "pressure" in ax.get_title())
    squares = [list(line.get_xdata()) for line in pressure.get_lines() if line.get_marker() == "s" and
               len(line.get_xdata())]
    assert squares == [[3]] * len(read_result(path).points)
    assert "restart, not divergence" in figures["convergence"].get_supxlabel()
    levels = [float(line.get_ydata()[0]) for line in panel.get_lines()
              if line.get_linestyle() in ("--", ":") and len(line.get_ydata())]
    assert case.solver.thermal_tolerance in levels and len(levels) <= 2


def test_the_true_scale_title_gives_both_axes_to_three_digits(ball_file, tmp_path, monkeypatch):
    """The ball on disc is a circle (R_x = R_y): its overview's true-scale strip names 2a = 2b (2a was rounded to one
    decimal, 0.2 mm against 2b's 0.16)."""
    titles = []
    set_title = Axes.set_title

    def recorded(ax, text, *args, **kwargs):
        titles.append(text)
        return set_title(ax, text, *args, **kwargs)

    monkeypatch.setattr(Axes, "set_title", recorded)
    _plot(ball_file, tmp_path)
    point = read_result(ball_file, fields=False).points["contact"]
    a, b = (f"{2e3 * point.scalars[key]:.3g}" for key in ("a", "b"))
    assert a == b and f"true scale: 2a = {a} mm, 2b = {b} mm" in titles

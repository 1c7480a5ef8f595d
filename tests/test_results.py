"""Result files: round trip, units on every dataset, atomic writes, NaN refusal, rejection of foreign files."""

from __future__ import annotations

from dataclasses import replace
import json
from pathlib import Path
import signal

import h5py
import numpy as np
import pytest

from facegear_tehl import results
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.results import (
    FORMAT_VERSION,
    NonFiniteError,
    ResultFileError,
    RunResult,
    read_result,
    write_result,
)
from facegear_tehl.solution import Field, Outcome

import synthetic


@pytest.fixture(scope="module")
def run() -> RunResult:
    return synthetic.run_result()


def _with_point(run: RunResult, **changes) -> RunResult:
    return replace(run, points=(replace(run.points[0], **changes),))


def _files(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir())


def test_round_trip_keeps_every_value(run, tmp_path):
    path = write_result(run, tmp_path / "r.h5")
    result = read_result(path)
    solution = run.points[0]
    assert result.format_version == FORMAT_VERSION
    assert result.case_name == "ball_on_disc"
    assert result.case_yaml == synthetic.BALL_ON_DISC.read_text()
    assert result.status == "ok" and result.message == ""
    assert result.models == {"viscosity": "roelands", "density": "dowson_higginson", "rheology": "newtonian",
                             "thermal": "off"}
    assert list(result.points) == ["contact"]
    point = result.points["contact"]
    assert point.converged and point.message == ""
    assert point.scalars == {key: value for key, (value, _) in solution.scalars.items()}
    assert point.units == {key: units for key, (_, units) in solution.scalars.items()}
    assert isinstance(point.scalars["iterations"], int)
    assert point.models == solution.models
    assert set(point.fields) == {"pressure", "film_thickness"}
    assert set(point.axes) == {"x", "y"} and set(point.history) == {"residual_history"}
    for read, written in [*zip(point.fields.values(), solution.fields.values()),
                          *zip(point.axes.values(), solution.axes.values()),
                          *zip(point.history.values(), solution.history.values())]:
        np.testing.assert_array_equal(read.values, written.values)
        assert (read.units, read.description) == (written.units, written.description)


def test_a_read_without_fields_keeps_everything_else(run, tmp_path):
    """read_result(fields=False), what the CLI's tables read back: the points' fields are left out, the rest is the
    full read's."""
    path = write_result(run, tmp_path / "r.h5")
    full, light = read_result(path), read_result(path, fields=False)
    assert full.points["contact"].fields and not light.points["contact"].fields
    assert (light.status, light.message, light.case_yaml, light.models) == (full.status, full.message,
                                                                               full.case_yaml, full.models)
    point, whole = light.points["contact"], full.points["contact"]
    assert (point.scalars, point.units, point.models, point.outcome) == (whole.scalars, whole.units, whole.models,
                                                                         whole.outcome)
    for part in ("axes", "history"):
        assert getattr(point, part).keys() == getattr(whole, part).keys()
        for name, read in getattr(point, part).items():
            np.testing.assert_array_equal(read.values, getattr(whole, part)[name].values)


def test_fields_are_stored_with_the_standard_shuffle_and_deflate_filters(run, tmp_path):
    """The chunks deflated outside the HDF5 library (results.DEFLATE_THREADS) are what its own filters make of the
    array: h5py inflates them to the exact values, a C-ordered and a Fortran-ordered array alike, and the file says
    gzip and shuffle, as a dataset compressed by the library does."""
    solution = run.points[0]
    pressure = solution.fields["pressure"].values
    fortran = Field(np.asfortranarray(pressure * 1.5), "Pa", "the pressure, Fortran-ordered")
    path = write_result(_with_point(run, fields={**solution.fields, "pressure_fortran": fortran}), tmp_path / "r.h5")
    with h5py.File(path, "r+") as h5:
        for name, expected in (("pressure", pressure), ("pressure_fortran", fortran.values)):
            dataset = h5[f"points/contact/{name}"]
            assert (dataset.compression, dataset.compression_opts, dataset.shuffle) == ("gzip", 4, True)
            assert dataset.chunks == expected.shape
            np.testing.assert_array_equal(dataset[()], expected)
        library = h5.create_dataset("by_the_library", data=pressure, chunks=pressure.shape, compression="gzip",
                                    compression_opts=4, shuffle=True)
        assert library.id.read_direct_chunk((0, 0))[1] == h5["points/contact/pressure"].id.read_direct_chunk((0, 0))[1]


def test_fields_hold_the_analytic_values(run, tmp_path):
    point = read_result(write_result(run, tmp_path / "r.h5")).points["contact"]
    x, y = point.axes["x"].values, point.axes["y"].values
    a, b, p_hertz = point.scalars["a"], point.scalars["b"], point.scalars["p_hertz"]
    pressure = point.fields["pressure"].values
    assert pressure.shape == (y.size, x.size)
    assert pressure.max() == pytest.approx(p_hertz, rel=0.02)  # the grid has a node near the centre
    iy, ix = 6, 22
    assert pressure[iy, ix] == pytest.approx(p_hertz * np.sqrt(max(0.0, 1 - (x[ix] / b) ** 2 - (y[iy] / a) ** 2)))
    contact = synthetic.ball_on_disc().contact
    assert point.fields["film_thickness"].values[iy, ix] == pytest.approx(
        synthetic.H_C + x[ix] ** 2 / (2 * contact.radius_x) + y[iy] ** 2 / (2 * contact.radius_y))
    np.testing.assert_allclose(point.history["residual_history"].values, 10.0 ** -np.arange(1, synthetic.CYCLES + 1))


def test_every_dataset_has_units_and_description(run, tmp_path):
    contact = {"s": Field(np.linspace(-1e-3, 1e-3, 5), "m", "path coordinate")}
    path = write_result(replace(run, contact=contact, heat={"mu": Field(np.array([0.05]), "1")}), tmp_path / "r.h5")
    datasets = []
    with h5py.File(path) as h5:
        h5.visititems(lambda name, obj: datasets.append(obj) if isinstance(obj, h5py.Dataset) else None)
        assert {d.name for d in datasets} >= {"/points/contact/pressure", "/points/contact/x", "/contact/s", "/heat/mu"}
        for dataset in datasets:
            assert isinstance(dataset.attrs["units"], str), dataset.name
            assert "description" in dataset.attrs, dataset.name
        root = dict(h5.attrs)
        point_attrs = h5["points/contact"].attrs
        assert json.loads(point_attrs["units"])["h_c"] == "m"
        assert point_attrs["converged"] == np.True_
    assert {"format_version", "tehl_version", "created", "case_yaml", "case_name", "status", "message",
            "models"} <= set(root)


def test_contact_and_heat_tables_round_trip(run, tmp_path):
    velocities = np.arange(10.0).reshape(5, 2)
    contact = {"s": Field(np.linspace(-1e-3, 1e-3, 5), "m", "path coordinate"),
               "u1": Field(velocities, "m/s", "surface velocity of body 1"),
               "label": Field(np.array(["S1", "", "S3", "", "S5"]), "", "meshing point")}
    heat = {"friction_power": Field(np.array([12.5]), "W")}
    scalars = {"contact_ratio": (1.56, "1"), "normal_load": (6950.4, "N")}
    run = replace(run, contact=contact, contact_scalars=scalars, heat=heat, warnings=("S2 after S3",))
    result = read_result(write_result(run, tmp_path / "r.h5"))
    assert list(result.contact) == ["s", "u1", "label"]
    assert result.contact_scalars == {"contact_ratio": 1.56, "normal_load": 6950.4}
    assert result.contact_units == {"contact_ratio": "1", "normal_load": "N"}
    assert result.warnings == ("S2 after S3",)
    np.testing.assert_array_equal(result.contact["u1"].values, velocities)
    assert result.contact["u1"].units == "m/s"
    assert list(result.contact["label"].values) == ["S1", "", "S3", "", "S5"]
    assert result.heat["friction_power"].values.tolist() == [12.5]


def test_tables_are_absent_when_not_given(run, tmp_path):
    path = write_result(run, tmp_path / "r.h5")
    with h5py.File(path) as h5:
        assert set(h5) == {"points"}
    result = read_result(path)
    assert result.contact == {} and result.heat == {} and result.contact_scalars == {} and result.warnings == ()


def test_status_and_message_flag_non_converged_and_failed_points(run, tmp_path):
    not_converged = _with_point(run, outcome=Outcome.NOT_CONVERGED, message="load error 3e-2 above 1e-4")
    result = read_result(write_result(not_converged, tmp_path / "a.h5"))
    assert result.status == "not_converged"
    assert result.message == "contact: load error 3e-2 above 1e-4"
    assert not result.points["contact"].converged and result.points["contact"].outcome == "not converged"

    failed = _with_point(run, outcome=Outcome.FAILED, message="failed: FloatingPointError: overflow", scalars={},
                         fields={}, axes={}, history={})
    result = read_result(write_result(replace(failed, failed=("contact",)), tmp_path / "b.h5"))
    assert result.status == "failed" and result.points["contact"].outcome == "failed"
    assert result.points["contact"].fields == {} and result.points["contact"].scalars == {}


@pytest.mark.parametrize("converged, outcome", [(True, "converged"), (False, "not converged")])
def test_a_format_1_0_file_without_outcomes_reads_them_from_converged(run, tmp_path, converged, outcome):
    path = write_result(run, tmp_path / "r.h5")
    with h5py.File(path, "r+") as h5:
        h5.attrs["format_version"] = "1.0"
        del h5["points/contact"].attrs["outcome"]
        h5["points/contact"].attrs["converged"] = converged
    assert read_result(path).points["contact"].outcome == outcome


def test_point_order_is_kept(run, tmp_path):
    base = run.points[0]
    names = ["S5", "S1", "S3"]
    ordered = replace(run, points=tuple(replace(base, name=name) for name in names))
    assert list(read_result(write_result(ordered, tmp_path / "r.h5")).points) == names


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
@pytest.mark.parametrize("where", ["field", "axis", "history", "scalar", "contact", "contact scalar"])
def test_non_finite_values_are_refused(run, tmp_path, where, bad):
    target = tmp_path / "r.h5"
    write_result(run, target)
    before = target.read_bytes()
    point = run.points[0]
    if where == "scalar":
        broken = _with_point(run, scalars={**point.scalars, "h_min": (bad, "m")})
    elif where == "contact":
        broken = replace(run, contact={"load": Field(np.array([1.0, bad]), "N")})
    elif where == "contact scalar":
        broken = replace(run, contact_scalars={"contact_ratio": (bad, "1")})
    else:
        attribute = {"field": "fields", "axis": "axes", "history": "history"}[where]
        entries = dict(getattr(point, attribute))
        name, column = next(iter(entries.items()))
        values = np.array(column.values, dtype=float)
        values.flat[values.size // 2] = bad
        entries[name] = replace(column, values=values)
        broken = _with_point(run, **{attribute: entries})
    with pytest.raises(NonFiniteError, match="non-finite|NaN"):
        write_result(broken, target)
    assert target.read_bytes() == before
    assert _files(tmp_path) == ["r.h5"]


@pytest.mark.parametrize(
    "changes, match",
    [
        ({"scalars": {"converged": (1.0, "1")}}, "reserved"),
        ({"scalars": {"h_c": ("thin", "m")}}, "not a real number"),
        ({"name": "S1/S2"}, "without '/'"),
        ({"axes": {}}, "axes x and y"),
    ],
)
def test_malformed_solutions_are_refused(run, tmp_path, changes, match):
    with pytest.raises(ValueError, match=match):
        write_result(_with_point(run, **changes), tmp_path / "r.h5")
    assert _files(tmp_path) == []


def test_field_shape_must_match_the_axes(run, tmp_path):
    point = run.points[0]
    fields = {**point.fields, "pressure": Field(point.fields["pressure"].values.T, "Pa")}
    with pytest.raises(ValueError, match=r"expected \(ny, nx\)"):
        write_result(_with_point(run, fields=fields), tmp_path / "r.h5")


@pytest.mark.parametrize("interruption", [RuntimeError("disk full"), KeyboardInterrupt()])
def test_failure_mid_write_keeps_the_previous_file(run, tmp_path, monkeypatch, interruption):
    target = tmp_path / "r.h5"
    write_result(run, target)
    before = target.read_bytes()
    write_point = results._write_point

    def write_then_fail(points, solution, *rest):
        write_point(points, solution, *rest)
        assert len(_files(tmp_path)) == 2  # the temporary file exists next to the target
        raise interruption

    monkeypatch.setattr(results, "_write_point", write_then_fail)
    with pytest.raises(type(interruption)):
        write_result(run, target)
    assert target.read_bytes() == before
    assert _files(tmp_path) == ["r.h5"]


def test_failure_mid_write_leaves_no_file(run, tmp_path, monkeypatch):
    monkeypatch.setattr(results, "_write_table", lambda *args: (_ for _ in ()).throw(OSError("no space")))
    with pytest.raises(OSError):
        write_result(run, tmp_path / "r.h5")
    assert _files(tmp_path) == []


def test_overwrite_replaces_the_previous_file(run, tmp_path):
    target = tmp_path / "r.h5"
    write_result(_with_point(run, outcome=Outcome.NOT_CONVERGED, message="stalled"), target)
    write_result(run, target)
    assert read_result(target).status == "ok"
    assert _files(tmp_path) == ["r.h5"]


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGKILL])
def test_interrupted_writer_process_keeps_the_previous_file(run, tmp_path, signum):
    target = tmp_path / "r.h5"
    write_result(_with_point(run, message="previous"), target)
    before = target.read_bytes()
    code = "results.write_result(synthetic.run_result(), sys.argv[1])"
    returncode, _ = synthetic.interrupt_while_writing(code, [str(target)], tmp_path, signum)
    assert returncode != 0
    assert target.read_bytes() == before
    if signum == signal.SIGINT:  # a catchable signal also removes the temporary file
        assert _files(tmp_path) == ["r.h5"]


def test_reader_rejects_foreign_files(tmp_path):
    foreign = tmp_path / "other.h5"
    with h5py.File(foreign, "w") as h5:
        h5["pressure"] = np.zeros(3)
    with pytest.raises(ResultFileError, match="not a tehl result"):
        read_result(foreign)
    text = tmp_path / "case.yaml"
    text.write_text("name: x\n")
    with pytest.raises(ResultFileError, match="cannot open"):
        read_result(text)
    with pytest.raises(ResultFileError, match="cannot open"):
        read_result(tmp_path / "missing.h5")


def test_reader_rejects_another_format_version(run, tmp_path):
    path = write_result(run, tmp_path / "r.h5")
    with h5py.File(path, "r+") as h5:
        h5.attrs["format_version"] = "2.0"
    with pytest.raises(ResultFileError, match="format 2.0"):
        read_result(path)


@pytest.mark.parametrize("damage", ["no points", "unknown status"])
def test_reader_reports_a_damaged_file(run, tmp_path, damage):
    path = write_result(run, tmp_path / "r.h5")
    with h5py.File(path, "r+") as h5:
        if damage == "no points":
            del h5["points"]
        else:
            h5.attrs["status"] = "fine"
    with pytest.raises(ResultFileError, match="damaged"):
        read_result(path)


# ------------------------------------------------------------------ format 1.2: dimensions, descriptions, counts


def test_xarray_opens_every_group_with_named_dimensions_and_coordinates(facegear_file):
    """xarray's netCDF-4 reader (engine h5netcdf, a reader independent of ours) finds the dimension scales: fields
    on (y, x) with the node coordinates, histories on their index, tables on their key column."""
    xarray = pytest.importorskip("xarray")
    pytest.importorskip("h5netcdf")
    result = read_result(facegear_file)
    for name, point in result.points.items():
        with xarray.open_dataset(facegear_file, group=f"points/{name}", engine="h5netcdf") as ds:
            assert ds["pressure"].dims == ("y", "x") and ds["temperature_mid"].dims == ("y", "x")
            np.testing.assert_array_equal(ds["x"].values, point.axes["x"].values)
            np.testing.assert_array_equal(ds["y"].values, point.axes["y"].values)
            assert ds["x"].attrs["units"] == "m" and ds["pressure"].attrs["units"] == "Pa"
            # the pressure peak sits on the centre line of the ellipse: y within one node of 0
            peak = ds["pressure"].where(ds["pressure"] == ds["pressure"].max(), drop=True)
            assert abs(float(peak["y"][0])) <= float(ds["y"].diff("y").max())
            assert ds["residual_history"].dims == ("cycle",) and ds["level_h_c"].dims == ("level",)
            assert ds["thermal_change_history"].dims == ("outer_iteration",)
            assert ds.sizes["cycle"] == point.history["residual_history"].values.size
    with xarray.open_dataset(facegear_file, group="heat", engine="h5netcdf") as heat:
        assert list(heat["point"].values) == list(result.points)
        assert heat["mu"].dims == ("point",)
        assert float(heat["mu"].sel(point="S1")) == result.points["S1"].scalars["mu"]
    with xarray.open_dataset(facegear_file, group="contact", engine="h5netcdf") as contact:
        assert contact["p_h"].dims == ("s",) and contact["u1"].dims == ("s", "xy")
        assert contact["contact_point"].dims == ("s", "xyz") and list(contact["xy"].values) == ["x", "y"]
        entrainment = 0.5 * (contact["u1"] + contact["u2"])  # U_e = (u1 + u2)/2, by component
        np.testing.assert_allclose(entrainment, contact["entrainment"], rtol=1e-12)


def test_every_dataset_of_a_real_file_has_units_and_a_description(facegear_file):
    missing = []

    def visit(name: str, item) -> None:
        if isinstance(item, h5py.Dataset):
            units, description = item.attrs.get("units", ""), item.attrs.get("description", "")
            if not (isinstance(units, str) and units.strip() and isinstance(description, str) and description.strip()):
                missing.append(f"{name}: units {units!r}, description {description!r}")

    with h5py.File(facegear_file) as h5:
        h5.visititems(visit)
        assert {"contact", "heat", "points"} <= set(h5)
    assert missing == []


def test_counts_are_stored_as_integers(facegear_file):
    """The conftest run solves on --grid 65: 65 x 17 nodes, levels 2^k + 1 up to 65, 9 thermal layers (default)."""
    with h5py.File(facegear_file) as h5:
        attrs = h5["points/S1"].attrs
        for key in ("iterations", "thermal_iterations", "grid", "grid_y", "coarsest_grid", "thermal_layers"):
            assert attrs[key].dtype.kind == "i", key
        assert (attrs["grid"], attrs["grid_y"], attrs["thermal_layers"]) == (65, 17, 9)
        levels = h5["points/S1/level_nodes"][()]
        assert levels.dtype.kind == "i" and levels[-1] == 65
        assert all((n - 1) & (n - 2) == 0 for n in levels)  # n - 1 a power of two
    point = read_result(facegear_file).points["S1"]
    assert isinstance(point.scalars["iterations"], int) and point.scalars["iterations"] >= 1


def test_tables_and_histories_without_a_shared_index_get_their_own(run, tmp_path):
    """A table without its key column runs along `row`; a history whose length differs from the shared `cycle`
    index gets an index of its own; a sweep table runs along its grids; its NaN-holding count column stays float."""
    xarray = pytest.importorskip("xarray")
    pytest.importorskip("h5netcdf")
    point = run.points[0]
    history = {**point.history, "load_error_history": Field(np.arange(3.0), "1", "relative load error per cycle")}
    sweep = {"grid": Field(np.array([33.0, 65.0, 129.0]), "1", "nodes per side"),
             "iterations": Field(np.array([12.0, np.nan, 14.0]), "1", "V-cycles on the finest grid")}
    heat = {"mu": Field(np.array([0.05, 0.06]), "1", "friction coefficient")}
    path = write_result(replace(_with_point(run, history=history), heat=heat, sweep=sweep), tmp_path / "r.h5")
    with xarray.open_dataset(path, group="points/contact", engine="h5netcdf") as ds:
        assert ds["residual_history"].dims == ("cycle",) and ds.sizes["cycle"] == synthetic.CYCLES
        assert ds["load_error_history"].dims == ("load_error_history_index",)
    with xarray.open_dataset(path, group="heat", engine="h5netcdf") as ds:
        assert ds["mu"].dims == ("row",) and list(ds["row"].values) == [0, 1]
    with xarray.open_dataset(path, group="sweep", engine="h5netcdf") as ds:
        assert ds["iterations"].dims == ("grid",) and list(ds["grid"].values) == [33, 65, 129]
        assert ds["grid"].dtype.kind == "i" and ds["iterations"].dtype.kind == "f"
    result = read_result(path)
    assert set(result.points["contact"].history) == {"residual_history", "load_error_history"}
    assert set(result.heat) == {"mu"} and set(result.sweep) == {"grid", "iterations"}


def test_table_columns_must_share_their_rows(run, tmp_path):
    heat = {"mu": Field(np.array([0.05, 0.06]), "1", "friction"), "P": Field(np.array([1.0]), "W", "power")}
    with pytest.raises(ValueError, match="different lengths"):
        write_result(replace(run, heat=heat), tmp_path / "r.h5")
    assert _files(tmp_path) == []


def test_a_format_1_1_file_is_still_read(tmp_path):
    """A file laid out as format 1.1 wrote it (no dimension scales, counts as floats), built here by hand."""
    path = tmp_path / "old.h5"
    with h5py.File(path, "w") as h5:
        h5.attrs.update({"filetype": results.FILETYPE, "format_version": "1.1", "tehl_version": "0.1.0",
                         "created": "2026-01-01T00:00:00+00:00", "case_name": "old", "case_yaml": "name: old\n",
                         "status": "ok", "message": "", "warnings": "[]", "models": "{}", "overrides": "{}"})
        point = h5.create_group("points/S1")
        point.attrs.update({"h_c": 1.2e-6, "iterations": 34.0, "units": json.dumps({"h_c": "m", "iterations": "1"}),
                            "converged": True, "outcome": "converged", "message": "", "models": "{}"})
        for name, values, units, kind in (("x", np.linspace(-1e-3, 1e-3, 5), "m", "axis"),
                                          ("y", np.linspace(-2e-3, 2e-3, 3), "m", "axis"),
                                          ("pressure", np.ones((3, 5)), "Pa", "field"),
                                          ("residual_history", np.array([1e-2, 1e-4]), "1", "history")):
            point[name] = values
            point[name].attrs.update({"units": units, "description": name, "kind": kind})
        h5["heat/mu"] = np.array([0.05])
        h5["heat/mu"].attrs.update({"units": "1", "description": "", "kind": "table"})
        h5["heat"].attrs["units"] = "{}"
    result = read_result(path)
    assert result.format_version == "1.1" and result.points["S1"].scalars == {"h_c": 1.2e-6, "iterations": 34.0}
    assert set(result.points["S1"].axes) == {"x", "y"} and result.points["S1"].fields["pressure"].values.shape == (3, 5)
    assert result.heat["mu"].values.tolist() == [0.05]


def test_the_file_states_the_solvers_settled_floor_bands(facegear_file):
    """The bands the convergence plot draws from the file are the ones the solver judges its loops by."""
    result = read_result(facegear_file)
    assert result.convergence_bands == {"pressure_floor_band": TUNING.floor_band,
                                        "thermal_floor_fraction": TUNING.thermal_floor_fraction,
                                        "min_rise": TUNING.min_rise}

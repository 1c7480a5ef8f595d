"""The result file (HDF5): the one writer and the one reader.

Layout (format 1.x; docs/cli.md describes it for readers):

    /                   attrs: filetype, format_version, tehl_version, created, case_name, case_yaml,
                        status (ok | not_converged | failed), message, warnings (JSON list),
                        models (JSON), overrides (JSON), derived (JSON list: the case's inputs derived
                        from others, '<key path> = <value>: <source>', e.g. an oil given by ISO grade)
    /points/<name>/     attrs: one per scalar (SI), units (JSON: scalar -> unit), converged, outcome (from 1.1:
                        converged | not converged | diverged | film closed | failed), message,
                        models (JSON); datasets x, y (kind 'axis'), fields (ny, nx) (kind 'field'),
                        per-cycle arrays (kind 'history')
    /points/<name>/solve  the solve record (from 1.3; record.py): attrs plan, stages, retries, notes (JSON lists:
                        the planned stages in words; per stage run: stage, nx, ny, cycles, outer, outcome;
                        per retry: reason, action, attempt, detail), attempt, relaxation, iteration,
                        stage_seconds (the wall time of each stage, s)
    /points/<name>/accuracy  the accuracy target's record (from 1.4, with solver.accuracy; accuracy_record.py):
                        attrs target, stop, nodes, case_nodes, figures, choices, steps (JSON lists: per asked
                        figure: name, bound, model_effect, verdict; per choice: what, chosen, reason; per solve:
                        grid, model, purpose, outcome, seconds)
    /contact/           gear contact analysis, written if given: one dataset per path column (kind
                        'table'); attrs: scalar geometry (SI) and its units (JSON)
    /heat/              table over points, written if given
    /cycle/             meshing cycle of a gear case (cycle.py), written if given: one dataset per column along
                        the path (kind 'table'); attrs: power_loss, mesh_efficiency, ... and their units (JSON)
    /verdict/           the case's verdict (verdict.py), written if given: attrs lambda_min, contact_temperature_max,
                        mesh_efficiency, ... (SI) and their units (JSON), labels (JSON: lambda_min_point, regime)
    /sweep/             grid-convergence table of `tehl sweep` (sweep.py), written if given: one dataset
                        per column (kind 'table'), one row per grid; its derived columns hold NaN where a
                        value is not defined (e.g. the order on the two coarsest grids), never Inf;
                        attrs: scalars and their units (JSON)

Every dataset carries `units`, `description` and `kind` attributes. From format 1.2 every dataset is attached
to HDF5 dimension scales, as netCDF-4 lays out dimensions, so that xarray (engine h5netcdf) opens any group with
named dimensions and coordinates: fields on (y, x); histories on an index (`cycle`, `outer_iteration`, `level`);
tables on their key column (`point`, `s`, `grid`) and a vector's components on `xy` or `xyz`. The index and
component datasets have kind 'scale' and are not read back (they hold nothing but 0, 1, 2, ... or x, y, z).
Counts (cycles, iterations, grid nodes, layers) are stored as integers. Files are written to a temporary
file in the target directory and renamed onto the target only when complete, so a crash or an
interruption leaves the previous file (or no file), never a partial one. NaN and Inf are refused
(except the NaN that marks an undefined entry of the sweep table).
"""

from __future__ import annotations

from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass, field
from datetime import datetime, timezone
import json
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping
import zlib

import numpy as np

from facegear_tehl import __version__
from facegear_tehl.accuracy_record import AccuracyRecord, accuracy_from_dict, accuracy_to_dict
from facegear_tehl.atomic_files import remove_stale, temporary_beside
from facegear_tehl.case import Case
from facegear_tehl.h5_guard import RECORDS, ResultFileError, check_layout
from facegear_tehl.record import SolveRecord, record_from_dict, record_to_dict
from facegear_tehl.solution import Field, PointSolution

if TYPE_CHECKING:  # h5py is imported where a file is written or read: `tehl validate` does not need it
    import h5py

FILETYPE = "facegear_tehl result"
# 1.1: /points/<name> attrs outcome; 1.2: dimension scales, integer counts; 1.3: /points/<name>/solve, root attr
# convergence_bands; 1.4: /points/<name>/accuracy
FORMAT_VERSION = "1.4"
STATUSES = ("ok", "not_converged", "failed")
# Group attributes that are not scalars.
_RESERVED_ATTRS = ("units", "converged", "outcome", "message", "models", "labels")
_RECORD_LISTS = ("plan", "stages", "retries", "notes")  # the solve record's attributes held as JSON
_ACCURACY_LISTS = ("figures", "choices", "steps")  # the accuracy record's attributes held as JSON
# The 2-D numeric datasets (the points' fields, the tables' vectors) are stored with HDF5's shuffle and deflate filters
# at this zlib level, one chunk per dataset: any HDF5 reader (h5py, xarray, HDFView) inflates them. The chunks are
# shuffled and deflated here rather than by the HDF5 library, on up to DEFLATE_THREADS threads (zlib releases the
# GIL), and written as they are (h5py's write_direct_chunk); level 4 and the threads' gain are measured in
# docs/benchmarks.md, "Result file".
DEFLATE_LEVEL = 4
# At most this many threads (fewer if fewer CPUs are available): measured with two on a 2-core machine; more would
# only take CPUs from the other writers or solves of a many-core machine for a file written in about a second.
DEFLATE_THREADS = 4
_AXES = ("x", "y")
# Scalars and columns that count something: stored as integers (a sweep column keeps floats where it holds NaN).
COUNTS = frozenset({"iterations", "thermal_iterations", "thermal_layers", "grid", "grid_y", "coarsest_grid",
                    "level_nodes", "attempts", "cycle_nodes_history"})
# The index a history runs along, by the start of its name (default: the finest-grid cycle).
_HISTORY_INDEX = (("level_", "level", "full-multigrid level, coarsest first"),
                  ("thermal_", "outer_iteration", "outer (thermal) iteration"),
                  ("viscosity_", "outer_iteration", "outer (thermal) iteration"))
_CYCLE_INDEX = ("cycle", "entry of the per-cycle histories, in the order they were recorded")
# The column each table's rows are keyed by (its coordinate in xarray).
_TABLE_KEYS = {"contact": "s", "heat": "point", "sweep": "grid"}
_COMPONENTS = {2: ("xy", ("x", "y")), 3: ("xyz", ("x", "y", "z"))}  # a vector column's components (see its description)


class NonFiniteError(ValueError):
    """A value bound for a result file is NaN or Inf (the solver must never produce them)."""


@dataclass(frozen=True)
class RunResult:
    """What one run produced, ready to be written.

    points: one solution per solved point, in order (failed points included, with no data).
    failed: names of the points whose solve raised an error.
    contact: path table (gear cases), name -> column; contact_scalars: name -> (value, units).
    heat: table over points, name -> column.
    cycle: meshing cycle along the path (gear cases), name -> column; cycle_scalars: name -> (value, units).
    sweep: grid-convergence table (one row per grid), name -> column; sweep_scalars: name -> (value, units).
    warnings: remarks on the run that are not failures (e.g. from the contact analysis).
    overrides: command-line options that changed the case (e.g. grid, points).
    verdict: the case's verdict (verdict.py), name -> (value, units); verdict_labels: its words, name -> text.
    """

    case: Case
    points: tuple[PointSolution, ...]
    failed: tuple[str, ...] = ()
    contact: Mapping[str, Field] = field(default_factory=dict)
    contact_scalars: Mapping[str, tuple[float, str]] = field(default_factory=dict)
    heat: Mapping[str, Field] = field(default_factory=dict)
    sweep: Mapping[str, Field] = field(default_factory=dict)
    sweep_scalars: Mapping[str, tuple[float, str]] = field(default_factory=dict)
    # the solver's settled-floor bands (ehl.tuning.convergence_bands), for the convergence plot; {}: none given
    convergence_bands: Mapping[str, float] = field(default_factory=dict)
    cycle: Mapping[str, Field] = field(default_factory=dict)
    cycle_scalars: Mapping[str, tuple[float, str]] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()
    overrides: Mapping[str, Any] = field(default_factory=dict)
    verdict: Mapping[str, tuple[float, str]] = field(default_factory=dict)
    verdict_labels: Mapping[str, str] = field(default_factory=dict)

    @property
    def status(self) -> str:
        if self.failed:
            return "failed"
        return "ok" if all(p.converged for p in self.points) else "not_converged"

    @property
    def message(self) -> str:
        """One line per point that failed or did not converge."""
        return "\n".join(f"{p.name}: {p.message or 'not converged'}" for p in self.points if not p.converged)

    @property
    def models(self) -> dict[str, str]:
        """The models the case asked for (each point records the ones its solver used)."""
        return {
            "viscosity": self.case.lubricant.viscosity_model,
            "density": self.case.lubricant.density_model,
            "rheology": self.case.lubricant.rheology,
            "thermal": self.case.solver.thermal,
        }


@dataclass(frozen=True)
class PointResult:
    """One /points/<name> group as read back."""

    name: str
    converged: bool
    outcome: str  # solution.Outcome's value: converged, not converged, diverged, film closed, failed
    message: str
    scalars: Mapping[str, float | int]
    units: Mapping[str, str]
    axes: Mapping[str, Field]
    fields: Mapping[str, Field]
    history: Mapping[str, Field]
    models: Mapping[str, str]
    record: SolveRecord | None = None  # the solve record (None in a file before format 1.3)
    accuracy: AccuracyRecord | None = None  # the accuracy target's record (None without solver.accuracy, before 1.4)


@dataclass(frozen=True)
class Result:
    """A result file as read back."""

    path: Path
    format_version: str
    tehl_version: str
    created: str
    case_name: str
    case_yaml: str
    status: str
    message: str
    warnings: tuple[str, ...]
    models: Mapping[str, str]
    overrides: Mapping[str, Any]
    points: Mapping[str, PointResult]
    contact: Mapping[str, Field]
    contact_scalars: Mapping[str, float | int]
    contact_units: Mapping[str, str]
    heat: Mapping[str, Field]
    sweep: Mapping[str, Field] = field(default_factory=dict)
    derived: tuple[str, ...] = ()  # the case's inputs derived from others (Case.derived)
    verdict: Mapping[str, float | int] = field(default_factory=dict)
    verdict_units: Mapping[str, str] = field(default_factory=dict)
    verdict_labels: Mapping[str, str] = field(default_factory=dict)
    sweep_scalars: Mapping[str, float | int] = field(default_factory=dict)
    sweep_units: Mapping[str, str] = field(default_factory=dict)
    cycle: Mapping[str, Field] = field(default_factory=dict)
    cycle_scalars: Mapping[str, float | int] = field(default_factory=dict)
    cycle_units: Mapping[str, str] = field(default_factory=dict)
    # the solver's settled-floor bands (ehl.tuning.convergence_bands; empty in a file of format 1.2 or older)
    convergence_bands: Mapping[str, float] = field(default_factory=dict)


# ----------------------------------------------------------------------------------------- writing


def write_result(run: RunResult, path: str | Path) -> Path:
    """Write `run` to `path` atomically; the previous file survives any failure or interruption."""
    import h5py

    target = Path(path)
    _check_run(run)
    remove_stale(target)  # a killed writer's temporary file
    temporary = temporary_beside(target)
    try:
        with (h5py.File(temporary, "w-", track_order=True) as h5,
              ThreadPoolExecutor(max_workers=_deflate_threads()) as pool):
            chunks = _Chunks(pool, [column.values for solution in run.points for column in solution.fields.values()])
            _write_root(h5, run)
            points = h5.create_group("points", track_order=True)
            for solution in run.points:
                _write_point(points, solution, chunks)
            _write_table(h5, "contact", run.contact, run.contact_scalars, chunks)
            _write_table(h5, "heat", run.heat, {}, chunks)
            _write_table(h5, "sweep", run.sweep, run.sweep_scalars, chunks)
            _write_table(h5, "cycle", run.cycle, run.cycle_scalars, chunks)
            if run.verdict or run.verdict_labels:  # words without figures where no point converged
                verdict = h5.create_group("verdict", track_order=True)
                _write_scalars(verdict, run.verdict)
                if run.verdict_labels:
                    verdict.attrs["labels"] = json.dumps(dict(run.verdict_labels))
            h5.flush()
        _fsync(temporary)
        os.replace(temporary, target)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise
    _fsync(target.parent)
    return target


def _deflate_threads() -> int:
    """Threads that deflate a file's chunks: the CPUs this process may run on, at most DEFLATE_THREADS."""
    available = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    return max(1, min(available, DEFLATE_THREADS))


def _deflated(values: np.ndarray) -> bytes:
    """One chunk holding all of `values` as HDF5's filter pipeline stores it: shuffled (the elements' bytes grouped
    by their place in the element, H5Z_FILTER_SHUFFLE) and then deflated (zlib, H5Z_FILTER_DEFLATE)."""
    data = np.ascontiguousarray(values)
    return zlib.compress(data.view(np.uint8).reshape(-1, data.itemsize).T.tobytes(), DEFLATE_LEVEL)


def _compressible(values: np.ndarray) -> bool:
    """Stored shuffled and deflated: a non-empty 2-D array of numbers."""
    return values.ndim == 2 and values.dtype.kind in "fiu" and values.size > 0


class _Chunks:
    """The deflated chunks of a file's 2-D datasets: those of `arrays` begun at once on `pool`, any other one
    deflated when it is written."""

    def __init__(self, pool: ThreadPoolExecutor, arrays: list[Any]) -> None:
        self._pending: dict[int, tuple[np.ndarray, Future[bytes]]] = {}
        for values in arrays:
            if isinstance(values, np.ndarray) and _compressible(values):
                self._pending[id(values)] = (values, pool.submit(_deflated, values))

    def chunk(self, values: np.ndarray) -> bytes:
        begun = self._pending.pop(id(values), None)
        return begun[1].result() if begun is not None and begun[0] is values else _deflated(values)


def _fsync(path: Path) -> None:
    descriptor = os.open(path, os.O_RDONLY)
    try:
        os.fsync(descriptor)
    finally:
        os.close(descriptor)


def _write_root(h5: h5py.File, run: RunResult) -> None:
    h5.attrs["filetype"] = FILETYPE
    h5.attrs["format_version"] = FORMAT_VERSION
    h5.attrs["tehl_version"] = __version__
    h5.attrs["created"] = datetime.now(timezone.utc).isoformat(timespec="seconds")
    h5.attrs["case_name"] = run.case.name
    h5.attrs["case_yaml"] = run.case.text
    h5.attrs["status"] = run.status
    h5.attrs["message"] = run.message
    h5.attrs["warnings"] = json.dumps(list(run.warnings))
    h5.attrs["models"] = json.dumps(run.models)
    h5.attrs["overrides"] = json.dumps(dict(run.overrides))
    h5.attrs["convergence_bands"] = json.dumps(dict(run.convergence_bands))
    h5.attrs["derived"] = json.dumps(list(run.case.derived))


def _write_point(points: h5py.Group, solution: PointSolution, chunks: _Chunks) -> None:
    group = points.create_group(solution.name, track_order=True)
    _write_scalars(group, solution.scalars)
    group.attrs["converged"] = bool(solution.converged)
    group.attrs["outcome"] = solution.outcome.value
    group.attrs["message"] = solution.message
    group.attrs["models"] = json.dumps(dict(solution.models))
    for kind, entries in (("axis", solution.axes), ("field", solution.fields), ("history", solution.history)):
        for name, column in entries.items():
            _write_dataset(group, name, column, kind, chunks)
    if solution.record is not None:
        _write_record(group.create_group("solve"), solution.record)
    if solution.accuracy is not None:
        accuracy = group.create_group("accuracy")
        for key, value in accuracy_to_dict(solution.accuracy).items():
            accuracy.attrs[key] = json.dumps(value) if key in _ACCURACY_LISTS else value
    for axis in solution.axes:
        group[axis].make_scale(axis)
    for name in solution.fields:
        _attach(group[name], group["y"], group["x"])
    for name, column in solution.history.items():
        index, description = next(((index, text) for start, index, text in _HISTORY_INDEX if name.startswith(start)),
                                  _CYCLE_INDEX)
        _attach(group[name], _index_scale(group, index, len(column.values), f"index: {description}", name))


def _write_record(group: h5py.Group, record: SolveRecord) -> None:
    """The solve record as attributes: lists as JSON, numbers and words as they are; the stages' wall times apart
    (stage_seconds), so that two runs of one case differ in their timings alone."""
    data = record_to_dict(record)
    group.attrs["stage_seconds"] = [stage.pop("seconds") for stage in data["stages"]]
    for key, value in data.items():
        group.attrs[key] = json.dumps(value) if isinstance(value, list) else value


def name_is_record(name: str, item: h5py.Group | h5py.Dataset) -> bool:
    """The item of a point group is its solve or accuracy record (a group, not a dataset of the point)."""
    return name in RECORDS and hasattr(item, "keys")


def _read_accuracy(group: h5py.Group) -> AccuracyRecord | None:
    """The accuracy record of a point group (None without one)."""
    if "accuracy" not in group or not name_is_record("accuracy", group["accuracy"]):
        return None
    attrs = group["accuracy"].attrs
    data = {key: json.loads(attrs[key]) if key in _ACCURACY_LISTS else attrs[key] for key in attrs}
    return accuracy_from_dict({key: value.item() if isinstance(value, np.generic) else value
                               for key, value in data.items()})


def _read_record(group: h5py.Group) -> SolveRecord | None:
    """The solve record of a point group (None in a file before format 1.3)."""
    if "solve" not in group or not name_is_record("solve", group["solve"]):
        return None
    attrs = group["solve"].attrs
    data = {key: json.loads(attrs[key]) if key in _RECORD_LISTS else attrs[key] for key in attrs}
    data = {key: value.item() if isinstance(value, np.generic) else value for key, value in data.items()}
    for stage, seconds in zip(data["stages"], np.atleast_1d(data.pop("stage_seconds")), strict=True):
        stage["seconds"] = float(seconds)
    return record_from_dict(data)


def _attach(dataset: h5py.Dataset, *scales: h5py.Dataset) -> None:
    """Attach `scales` to the dimensions of `dataset`, in order."""
    for dimension, scale in zip(dataset.dims, scales):
        dimension.attach_scale(scale)


def _index_scale(group: h5py.Group, name: str, size: int, description: str, owner: str,
                 labels: tuple[str, ...] | None = None) -> h5py.Dataset:
    """The dimension scale `name` of `size` entries (0, 1, ... or `labels`) in `group`, created on first use;
    a dataset whose length differs from the shared scale gets its own, `<owner>_index`."""
    if name in group and group[name].shape != (size,):
        name = f"{owner}_index"
    if name not in group:
        values = np.arange(size) if labels is None else np.array(labels)
        _write_dataset(group, name, Field(values, "1" if labels is None else "-", description), "scale")
        group[name].make_scale(name)
    return group[name]


def _write_scalars(group: h5py.Group, scalars: Mapping[str, tuple[float, str]]) -> None:
    for key, (value, _) in scalars.items():
        group.attrs[key] = _stored(key, value)
    group.attrs["units"] = json.dumps({key: units for key, (_, units) in scalars.items()})


def _write_table(
    h5: h5py.File, name: str, columns: Mapping[str, Field], scalars: Mapping[str, tuple[float, str]], chunks: _Chunks
) -> None:
    if columns or scalars:
        group = h5.create_group(name, track_order=True)
        _write_scalars(group, scalars)
        for column_name, column in columns.items():
            _write_dataset(group, column_name, column, "table", chunks)
        _attach_table_dimensions(group, name, columns)


def _attach_table_dimensions(group: h5py.Group, name: str, columns: Mapping[str, Field]) -> None:
    """Rows along the table's key column (an index `row` without it); a vector's components along `xy`/`xyz`."""
    key = _TABLE_KEYS.get(name)
    if key in columns and np.ndim(columns[key].values) == 1:
        rows = group[key]
        rows.make_scale(key)
    elif columns:
        rows = _index_scale(group, "row", len(next(iter(columns.values())).values), "index: row of the table", name)
    for column_name, column in columns.items():
        scales = [rows]
        if np.ndim(column.values) == 2:
            size = np.shape(column.values)[1]
            scale, labels = _COMPONENTS.get(size, (f"{column_name}_index", None))
            what = ", ".join(labels) if labels else "index"
            scales.append(_index_scale(group, scale, size, f"vector component ({what})", column_name, labels))
        if column_name != key:
            _attach(group[column_name], *scales)


def _stored(name: str, value: Any) -> Any:
    """`value` as the file stores it: counts (COUNTS) as integers when every value is a whole number."""
    if name not in COUNTS:
        return value
    array = np.asarray(value)
    if array.dtype.kind == "f" and np.all(np.isfinite(array)) and np.all(array == np.round(array)):
        array = array.astype(np.int64)
    return array if array.ndim else array.item()


def _write_dataset(group: h5py.Group, name: str, column: Field, kind: str, chunks: _Chunks | None = None) -> None:
    import h5py

    values = _stored(name, np.asarray(column.values))
    if values.dtype.kind in "US":
        dataset = group.create_dataset(name, data=values.astype(object), dtype=h5py.string_dtype())
    elif _compressible(values):
        dataset = group.create_dataset(name, shape=values.shape, dtype=values.dtype, chunks=values.shape,
                                       compression="gzip", compression_opts=DEFLATE_LEVEL, shuffle=True)
        dataset.id.write_direct_chunk((0,) * values.ndim, _deflated(values) if chunks is None else chunks.chunk(values))
    else:
        dataset = group.create_dataset(name, data=values)
    dataset.attrs["units"] = column.units
    dataset.attrs["description"] = column.description
    dataset.attrs["kind"] = kind


def _check_run(run: RunResult) -> None:
    """Reject what the file cannot hold before any byte is written."""
    names = [p.name for p in run.points]
    if len(set(names)) != len(names):
        raise ValueError(f"duplicate point names: {names}")
    for solution in run.points:
        _check_point(solution)
    _check_scalars("/contact", run.contact_scalars)
    _check_scalars("/sweep", run.sweep_scalars)
    _check_scalars("/cycle", run.cycle_scalars)
    _check_scalars("/verdict", run.verdict)
    for table_name, table in (("contact", run.contact), ("heat", run.heat), ("sweep", run.sweep),
                              ("cycle", run.cycle)):
        for name, column in table.items():
            _check_column(f"/{table_name}/{name}", name, column, allow_nan=table_name == "sweep")
        rows = {name: len(column.values) for name, column in table.items()}
        if len(set(rows.values())) > 1:
            raise ValueError(f"/{table_name}: columns of different lengths {rows}; a table's columns share its rows")


def _check_point(solution: PointSolution) -> None:
    where = f"/points/{solution.name}"
    if not solution.name or "/" in solution.name:
        raise ValueError(f"point name {solution.name!r}: expected a non-empty name without '/'")
    _check_scalars(where, solution.scalars)
    data = [*solution.axes.items(), *solution.fields.items(), *solution.history.items()]
    names = [name for name, _ in data]
    for name in set(names):
        if names.count(name) > 1:
            raise ValueError(f"{where}/{name}: the name is used twice (axes, fields and history share one group)")
    for name, column in data:
        _check_column(f"{where}/{name}", name, column)
    if solution.fields:
        missing = [axis for axis in _AXES if axis not in solution.axes]
        if missing:
            raise ValueError(f"{where}: fields need the axes x and y (missing: {', '.join(missing)})")
        shape = (np.size(solution.axes["y"].values), np.size(solution.axes["x"].values))
        for name, column in solution.fields.items():
            if np.shape(column.values) != shape:
                raise ValueError(f"{where}/{name}: shape {np.shape(column.values)}, expected (ny, nx) = {shape}")


def _check_scalars(where: str, scalars: Mapping[str, tuple[float, str]]) -> None:
    for key, (value, units) in scalars.items():
        if key in _RESERVED_ATTRS:
            raise ValueError(f"{where}: scalar name {key!r} is reserved for the group's attributes")
        if not isinstance(units, str):
            raise ValueError(f"{where}.{key}: units {units!r} is not a string")
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
            raise ValueError(f"{where}.{key}: scalar {value!r} is not a real number")
        if not np.isfinite(value):
            raise NonFiniteError(f"{where}.{key} = {value}: refusing to write a non-finite scalar")


def _check_column(where: str, name: str, column: Field, allow_nan: bool = False) -> None:
    if not name or "/" in name:
        raise ValueError(f"{where}: expected a non-empty dataset name without '/'")
    if not isinstance(column.units, str):
        raise ValueError(f"{where}: units {column.units!r} is not a string")
    values = np.asarray(column.values)
    if values.dtype.kind in "US":
        return
    if values.dtype.kind not in "biuf":
        raise ValueError(f"{where}: dtype {values.dtype} is not numeric or text")
    bad = np.isinf(values) if allow_nan else ~np.isfinite(values)
    if bad.any():
        raise NonFiniteError(
            f"{where}: refusing to write {int(np.isnan(values).sum())} NaN and {int(np.isinf(values).sum())} Inf values"
        )


# ----------------------------------------------------------------------------------------- reading


def read_result(path: str | Path, fields: bool = True) -> Result:
    """Read a result file; ResultFileError if it is not a tehl result of a supported format. `fields` False: the
    points' fields (the arrays over the grid, most of the file) are not read and each point's `fields` is empty;
    what the tables print (scalars, histories, the run's tables) is read as ever: the 41-point isothermal cycle's
    file (80 MB) in 0.34 s, against 1.08 s with its fields."""
    import h5py

    path = Path(path)
    if path.exists() and not path.is_file():  # a FIFO would block the open until someone writes to it
        raise ResultFileError(f"{path}: not a result file (a directory, device or FIFO, not a regular file)")
    try:
        h5 = h5py.File(path, "r")
    except (OSError, ValueError) as exc:
        raise ResultFileError(f"{path}: cannot open as an HDF5 file ({_reason(exc)})") from None
    with h5:
        attrs = h5.attrs
        if not isinstance(attrs.get("filetype"), str) or attrs["filetype"] != FILETYPE or "format_version" not in attrs:
            raise ResultFileError(f"{path}: not a tehl result file (no filetype '{FILETYPE}' attribute)")
        version = str(attrs["format_version"])
        if version.split(".")[0] != FORMAT_VERSION.split(".")[0]:
            raise ResultFileError(f"{path}: result format {version}; this tehl reads format {FORMAT_VERSION}")
        check_layout(h5, path)
        try:
            return _read_contents(h5, path, version, fields)
        except (KeyError, ValueError, TypeError, OSError) as exc:  # OSError: data HDF5 cannot read (a bad chunk)
            raise ResultFileError(f"{path}: damaged tehl result ({_reason(exc)}); write it again with tehl run") \
                from None


def _read_contents(h5: h5py.File, path: Path, version: str, fields: bool) -> Result:
    """The Result of an open file whose type and layout are checked (read_result)."""
    attrs = h5.attrs
    status = str(attrs["status"])
    if status not in STATUSES:
        raise ValueError(f"status {status!r}, expected one of {', '.join(STATUSES)}")
    groups = {name: h5.get(name) for name in ("contact", "sweep", "cycle", "verdict")}
    scalars = {name: _read_scalars(group) if group is not None else ({}, {}) for name, group in groups.items()}
    verdict = groups["verdict"]
    return Result(
        path=path,
        format_version=version,
        tehl_version=str(attrs["tehl_version"]),
        created=str(attrs["created"]),
        case_name=str(attrs["case_name"]),
        case_yaml=str(attrs["case_yaml"]),
        status=status,
        message=str(attrs["message"]),
        warnings=tuple(json.loads(attrs["warnings"])),
        models=json.loads(attrs["models"]),
        overrides=json.loads(attrs["overrides"]),
        derived=tuple(json.loads(attrs.get("derived", "[]"))),
        verdict=scalars["verdict"][0],
        verdict_units=scalars["verdict"][1],
        verdict_labels=json.loads(verdict.attrs.get("labels", "{}")) if verdict is not None else {},
        points={name: _read_point(name, group, fields) for name, group in h5["points"].items()},
        contact=_read_table(groups["contact"]),
        contact_scalars=scalars["contact"][0],
        contact_units=scalars["contact"][1],
        heat=_read_table(h5.get("heat")),
        sweep=_read_table(groups["sweep"]),
        sweep_scalars=scalars["sweep"][0],
        sweep_units=scalars["sweep"][1],
        cycle=_read_table(groups["cycle"]),
        cycle_scalars=scalars["cycle"][0],
        cycle_units=scalars["cycle"][1],
        convergence_bands=json.loads(attrs.get("convergence_bands", "{}")),
    )


def _reason(exc: Exception) -> str:
    return str(exc).strip("'\"") or type(exc).__name__


def _read_scalars(group: h5py.Group) -> tuple[dict[str, float | int], dict[str, str]]:
    units = json.loads(group.attrs["units"])
    return {key: group.attrs[key].item() for key in units}, units


def _read_point(name: str, group: h5py.Group, fields: bool = True) -> PointResult:
    scalars, units = _read_scalars(group)
    by_kind: dict[str, dict[str, Field]] = {"axis": {}, "field": {}, "history": {}, "scale": {}}
    for dataset_name, dataset in group.items():
        if name_is_record(dataset_name, dataset):
            continue
        kind = str(dataset.attrs["kind"])
        if fields or kind != "field":
            by_kind[kind][dataset_name] = _read_field(dataset)
    return PointResult(
        name=name,
        converged=bool(group.attrs["converged"]),
        outcome=str(group.attrs.get("outcome", "converged" if group.attrs["converged"] else "not converged")),
        message=str(group.attrs["message"]),
        scalars=scalars,
        units=units,
        axes=by_kind["axis"],
        fields=by_kind["field"],
        history=by_kind["history"],
        models=json.loads(group.attrs["models"]),
        record=_read_record(group),
        accuracy=_read_accuracy(group),
    )


def _read_table(group: h5py.Group | None) -> dict[str, Field]:
    if group is None:
        return {}
    return {name: _read_field(dataset) for name, dataset in group.items() if dataset.attrs["kind"] != "scale"}


def _read_field(dataset: h5py.Dataset) -> Field:
    import h5py

    if h5py.check_string_dtype(dataset.dtype) is not None:
        values = dataset.asstr()[()]
        values = np.asarray(values, dtype=str)
    else:
        values = dataset[()]
    return Field(values=values, units=str(dataset.attrs["units"]), description=str(dataset.attrs["description"]))


def non_finite_entries(path: str | Path) -> list[str]:
    """Every dataset and attribute of the HDF5 file at `path` holding NaN or Inf (numbers inside JSON text
    attributes included), as '<object>[.<attribute>]: n NaN, m Inf'; the NaN marking an undefined entry of
    the /sweep table is allowed. Empty for a sound file: checks a file as it is on disk, whoever wrote it."""
    import h5py

    found: list[str] = []

    def check(where: str, values: Any, allow_nan: bool = False) -> None:
        if isinstance(values, str):
            values = _json_numbers(values)
        array = np.asarray(values)
        if array.dtype.kind not in "fc":
            return
        bad = np.isinf(array) if allow_nan else ~np.isfinite(array)
        if bad.any():
            found.append(f"{where}: {int(np.isnan(array).sum())} NaN, {int(np.isinf(array).sum())} Inf")

    def visit(name: str, item: h5py.Group | h5py.Dataset) -> None:
        for key, value in item.attrs.items():
            check(f"/{name}.{key}", value)
        if isinstance(item, h5py.Dataset) and h5py.check_string_dtype(item.dtype) is None:
            check(f"/{name}", item[()], allow_nan=name.startswith("sweep/"))

    with h5py.File(path, "r") as h5:
        visit("", h5)
        h5.visititems(visit)
    return found


def _json_numbers(text: str) -> list[float]:
    """The numbers in a JSON object or list (Python's json reads NaN and Infinity); [] for other text."""
    if not text.startswith(("{", "[")):
        return []
    try:
        pending = [json.loads(text)]
    except ValueError:
        return []
    numbers = []
    while pending:
        value = pending.pop()
        if isinstance(value, dict):
            pending.extend(value.values())
        elif isinstance(value, list):
            pending.extend(value)
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            numbers.append(float(value))
    return numbers

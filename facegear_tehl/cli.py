"""Command line: `tehl run | validate | contact | info`.

Exit codes: 0 ok; 1 unexpected error (or a point whose solve failed; its result is still written);
2 bad input (case file, options, not a result file): one line `error: <key path>: ...`, no output file;
3 not converged (result written, flagged).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
import json
import os
from pathlib import Path
import signal
import traceback
from typing import Any

import click

from facegear_tehl import __version__
from facegear_tehl.case import Case, load_case
from facegear_tehl.cycle import COARSE_POINT_COUNT, QUADRATURE
from facegear_tehl.gears.analysis import analyse_gear_pair
from facegear_tehl.gears.report import contact_table
from facegear_tehl.parallel import worker_count
from facegear_tehl.points import contact_analysis, select_points
from facegear_tehl.results import PointResult, Result, ResultFileError, read_result, write_result
from facegear_tehl.schema import CaseError
from facegear_tehl.solution import PointSolution
from facegear_tehl.sweep import check_tolerance, parse_grids, report, run_sweep, with_thermal, write_csv
from facegear_tehl.tables import COST, Column, cell, format_pairs, format_table, yes_no
from facegear_tehl.units import CELSIUS, MILLIMETRE, PERCENT, display

EXIT_ERROR, EXIT_BAD_INPUT, EXIT_NOT_CONVERGED = 1, 2, 3


class _Tehl(click.Group):
    """Turns bad input into one line and exit 2, and any other error into one line and exit 1."""

    def invoke(self, ctx: click.Context) -> Any:
        try:
            return super().invoke(ctx)
        except (click.ClickException, click.exceptions.Exit, click.Abort):
            raise
        except (CaseError, ResultFileError) as exc:
            click.echo(f"error: {exc}", err=True)
            ctx.exit(EXIT_BAD_INPUT)
        except Exception as exc:  # noqa: BLE001 - any other error: one line and exit 1 (--debug: the traceback)
            if ctx.params.get("debug"):
                traceback.print_exc()
            click.echo(f"error: {type(exc).__name__}: {exc}", err=True)
            ctx.exit(EXIT_ERROR)


@click.group(cls=_Tehl, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="tehl")
@click.option("--debug", is_flag=True, help="Show the traceback of unexpected errors.")
def tehl(debug: bool) -> None:
    """Thermal EHL of face gear pairs: one YAML case in, one HDF5 result out."""


@tehl.command()
@click.argument("case_file", metavar="CASE")
@click.option("-o", "--output", help="Result file (default: output.file of the case, else <case name>.h5).")
@click.option("--grid", type=int, help="Nodes per side of the finest grid, 2^n + 1 (overrides solver.grid).")
@click.option("--points", help="Comma-separated point names to solve (e.g. S1,S3); default all.")
@click.option("--jobs", type=int, help="Worker processes solving points side by side (default: all cores).")
@click.pass_context
def run(
    ctx: click.Context, case_file: str, output: str | None, grid: int | None, points: str | None, jobs: int | None
) -> None:
    """Solve CASE and write the result file."""
    case = load_case(case_file)
    workers = worker_count(jobs)
    solver = (case if grid is None else case.with_grid(grid)).solver
    names = _point_names(points)
    analysis = contact_analysis(case)
    selected = analysis.points if names is None else select_points(analysis.points, names)
    target = _output_path(Path(case_file), case, output)
    processes = min(workers, len(selected))
    click.echo(
        f"tehl run: {case.name}: {', '.join(p.name for p in selected)} on a {solver.grid}x{solver.nodes_y} grid"
        + (f", {processes} worker processes" if processes > 1 else ""),
        err=True,
    )
    for warning in analysis.warnings:
        click.echo(f"warning: {warning}", err=True)
    # Imported once the input is checked: only this command needs the solver (Numba kernels).
    from facegear_tehl.run import run_case

    run_result = run_case(case, grid=grid, points=names, progress=_report_progress, jobs=workers)
    for warning in run_result.warnings:
        if warning not in analysis.warnings:  # what the run found (a grid the solver chose, ...)
            click.echo(f"warning: {warning}", err=True)
    target.parent.mkdir(parents=True, exist_ok=True)
    write_result(run_result, target)
    result = read_result(target)
    click.echo(summary_table(result.points.values()))
    if result.heat and "point" in result.heat:
        click.echo(heat_budget_table(result))
    if result.cycle:
        click.echo(cycle_table(result))
        click.echo(cycle_summary(result))
    click.echo(f"result: {target} (status {result.status})")
    _exit_on_status(ctx, result)


def _exit_on_status(ctx: click.Context, result: Result) -> None:
    """Exit 1 if a point failed, 3 if one did not converge (the file is written either way)."""
    if result.status == "failed":
        click.echo(f"error: {result.message}", err=True)
        ctx.exit(EXIT_ERROR)
    if result.status == "not_converged":
        click.echo(f"warning: not converged: {result.message}", err=True)
        ctx.exit(EXIT_NOT_CONVERGED)


@tehl.command()
@click.argument("case_file", metavar="CASE")
@click.option("--grids", default="33,65,129,257,513", show_default=True,
              help="Nodes per side of each grid: ascending, each refining the previous by 2, at least three.")
@click.option("--point", help="Point to solve (default: the case's first, S1 for a face gear pair).")
@click.option("--thermal", help="Thermal model, overrides solver.thermal: off | reduced | full | auto.")
@click.option("--tol", "tolerance", type=float, default=0.01, show_default=True,
              help="Relative change to the next grid below which a quantity counts as grid-independent.")
@click.option("-o", "--output",
              help="Sweep file, HDF5 (default: <case name>_sweep_<point>.h5); the CSV goes next to it.")
@click.option("--jobs", type=int, help="Worker processes solving grids side by side (default: all cores).")
@click.pass_context
def sweep(
    ctx: click.Context,
    case_file: str,
    grids: str,
    point: str | None,
    thermal: str | None,
    tolerance: float,
    output: str | None,
    jobs: int | None,
) -> None:
    """Solve one point of CASE on a sequence of grids and print its mesh-independence table (change per
    grid, observed order, Richardson extrapolation with its GCI uncertainty); writes HDF5 (/sweep) and CSV."""
    case = load_case(case_file)
    grid_list = parse_grids(grids, case)
    check_tolerance(tolerance)
    workers = worker_count(jobs)
    model = case.solver.thermal if thermal is None else with_thermal(case, thermal).solver.thermal
    points = contact_analysis(case).points
    name = points[0].name if point is None else select_points(points, [point], key="--point")[0].name
    target = _writable("--output", Path(output if output is not None else f"{case.name}_sweep_{name}.h5"))
    if target.suffix.lower() == ".csv":
        raise CaseError("--output", str(target), "an HDF5 file name (the CSV is written next to it)")
    click.echo(
        f"tehl sweep: {case.name}: {name} on grids {','.join(map(str, grid_list))}, thermal {model}"
        + (f", {min(workers, len(grid_list))} worker processes" if workers > 1 else ""),
        err=True,
    )
    swept = run_sweep(case, grid_list, point=name, thermal=thermal, tolerance=tolerance, jobs=workers,
                      progress=_report_progress)
    target.parent.mkdir(parents=True, exist_ok=True)
    write_result(swept.run, target)
    result = read_result(target)
    for warning in result.warnings:
        click.echo(f"warning: {warning}", err=True)
    csv = write_csv(result.sweep, target.with_suffix(".csv"))
    click.echo(report(result.sweep, result.sweep_scalars))
    click.echo(f"result: {target}, {csv} (status {result.status})")
    _exit_on_status(ctx, result)


@tehl.command()
@click.argument("case_file", metavar="CASE")
def validate(case_file: str) -> None:
    """Check CASE without running it."""
    case = load_case(case_file)
    points = contact_analysis(case).points
    if case.gear is None:
        point = points[0]
        length = display("m")
        kind = (f"plain contact (p_hertz {display('Pa').text(point.hertz.p_max, '.0f')}, "
                f"a {length.text(point.hertz.a, '.1f')}, b {length.text(point.hertz.b, '.1f')})")
    else:
        pressure = display("Pa")
        p_hertz = [pressure(p.hertz.p_max) for p in points]
        kind = (f"face gear pair ({len(points)} points {points[0].name}..{points[-1].name}, "
                f"p_hertz {min(p_hertz):.0f}..{max(p_hertz):.0f} {pressure.label})")
    lubricant = case.lubricant
    click.echo(
        f"ok: {case.name}: {kind}; grid {case.solver.grid}x{case.solver.nodes_y}; models: viscosity "
        f"{lubricant.viscosity_model}, density {lubricant.density_model}, rheology {lubricant.rheology}, "
        f"thermal {case.solver.thermal}"
    )


@tehl.command()
@click.argument("case_file", metavar="CASE")
def contact(case_file: str) -> None:
    """Print the face gear contact analysis of CASE at its meshing points (no lubrication)."""
    case = load_case(case_file)
    if case.gear is None:
        raise CaseError("gear", None, "a gear: block (tehl contact analyses a face gear pair)")
    click.echo(contact_table(analyse_gear_pair(case.gear, case.materials.body_1, case.materials.body_2)))


@tehl.command()
@click.argument("result_file", metavar="RESULT")
@click.option("--json", "as_json", is_flag=True, help="Print the per-point scalars (SI) as JSON.")
def info(result_file: str, as_json: bool) -> None:
    """Show the per-point scalars of a result file."""
    result = read_result(result_file)
    click.echo(json.dumps(info_json(result), indent=2) if as_json else info_text(result))


@tehl.command()
@click.argument("result_file", metavar="RESULT")
@click.option("--what", default="all", show_default=True,
              help="Figure types, comma-separated: all, fields, trends, friction, heat, contact, convergence, "
                   "cycle.")
@click.option("--point", "points", help="Points whose fields and convergence are drawn, comma-separated; default all.")
@click.option("-o", "--output", help="Folder for the figures (default: <RESULT name>_plots next to RESULT).")
@click.option("--format", "fmt", default="png", show_default=True, help="png | pdf | svg.")
@click.option("--dpi", type=int, default=150, show_default=True, help="Resolution of raster figures.")
def plot(result_file: str, what: str, points: str | None, output: str | None, fmt: str, dpi: int) -> None:
    """Draw the figures of a result file (nothing is solved); figure types without data are skipped."""
    # Imported here: only this command needs matplotlib.
    from facegear_tehl.plots import figure_types, plot_result

    result = read_result(result_file)
    source = Path(result_file)
    folder = Path(output) if output is not None else source.with_name(f"{source.stem}_plots")
    report = plot_result(result, folder, what=figure_types(what), points=_point_names(points), fmt=fmt, dpi=dpi)
    for line in report.skipped:
        click.echo(line)
    if not report.written:
        click.echo("no figures written: the file has no data for the figure types asked for")
        return
    click.echo(f"wrote {len(report.written)} figure file(s) to {folder}:")
    for path in report.written:
        click.echo(f"  {path}")


def info_json(result: Result) -> dict[str, Any]:
    """{'case', 'status', 'message', 'format_version', 'points': {name: {scalar: SI value, 'converged',
    'message'}}, 'units': {name: {scalar: unit}}}."""
    return {
        "case": result.case_name,
        "status": result.status,
        "message": result.message,
        "format_version": result.format_version,
        "points": {
            name: {**p.scalars, "converged": p.converged, "message": p.message} for name, p in result.points.items()
        },
        "units": {name: dict(p.units) for name, p in result.points.items()},
        **({"cycle": {**result.cycle_scalars, "units": dict(result.cycle_units),
                      "columns": {name: column.values.tolist() for name, column in result.cycle.items()}}}
           if result.cycle else {}),
    }


def info_text(result: Result) -> str:
    """The file's header, then every scalar of every point (SI) with its units."""
    header = [
        ("case", result.case_name),
        ("status", result.status),
        ("created", f"{result.created} (tehl {result.tehl_version}, format {result.format_version})"),
        ("models", ", ".join(f"{k} {v}" for k, v in result.models.items())),
    ]
    if result.overrides:
        header.append(("overrides", ", ".join(f"{k} {_listed(v)}" for k, v in result.overrides.items())))
    for table_name, table in (("contact path", result.contact), ("heat table", result.heat),
                              ("sweep table", result.sweep), ("cycle", result.cycle)):
        if table:
            header.append((table_name, f"{len(table)} columns: {', '.join(table)}"))
    if result.message:
        header.append(("message", result.message.replace("\n", "; ")))
    header += [("warning", warning) for warning in result.warnings]
    points = list(result.points.values())
    names = list(dict.fromkeys(key for p in points for key in p.scalars))
    rows = [["converged", "", *(yes_no(p.converged) for p in points)]]
    for key in names:
        units = next(p.units[key] for p in points if key in p.units)
        rows.append([key, units, *(cell(p.scalars.get(key), ".6g", "-") for p in points)])
    lines = [format_pairs(header), "", format_table(["scalar", "units", *(p.name for p in points)], rows)]
    if result.heat and "point" in result.heat:
        lines += ["", "heat budget:", heat_budget_table(result)]
    if result.cycle:
        lines += ["", "meshing cycle:", cycle_table(result), cycle_summary(result)]
    if result.contact_scalars:
        contact_rows = [[key, result.contact_units[key], cell(value, ".6g", "-")]
                        for key, value in result.contact_scalars.items()]
        lines += ["", format_table(["contact", "units", "value"], contact_rows)]
    return "\n".join(lines)


def _listed(value: Any) -> str:
    return ",".join(map(str, value)) if isinstance(value, list) else str(value)


# Summary columns, then the error estimates: column, the quantity it estimates the error of.
_SUMMARY = (
    Column("h_c", "h_c", "m"),
    Column("h_min", "h_min", "m"),
    Column("p_max", "p_max", "Pa", ".1f"),
    Column("p_hertz", "p_hertz", "Pa", ".1f"),
    Column("dT_max", "dT_max", "K", ".1f"),
    Column("dT_min", "dT_min", "K", ".1f"),
    Column("mu", "mu", spec=".4f"),
    Column("load error", "load_error", spec=".1e"),
    *COST,
)
_ERROR_ESTIMATES = (("err h_c %", "error_estimate_h_c", "h_c"), ("err h_min %", "error_estimate_h_min", "h_min"),
                    ("err dT_max %", "error_estimate_dT_max", "dT_max"), ("err mu %", "error_estimate_mu", "mu"))

# Heat-budget columns, keys of the /heat table.
_HEAT = (
    Column("mu", "mu", spec=".4f"),
    Column("mu Xu", "mu_xu", spec=".4f"),
    Column("P", "friction_power", "W", ".1f"),
    Column("gamma_1", "partition_1", spec=".3f"),
    Column("P_ss,1", "steady_power_1", "W", ".3g"),
    Column("P_ss,2", "steady_power_2", "W", ".3g"),
    Column("flash", "flash_temperature", "K", ".1f"),
    Column("surface dT", "surface_rise_max", "K", ".1f"),
    Column("Q_f", "frictional_heat", "J", ".3g"),
    Column("Q_oil", "oil_film_heat", "J", ".3g"),
    Column("Q_oil/Q_f", "oil_to_friction_ratio", spec=".2f", unit=PERCENT),
)


def heat_budget_table(result: Result) -> str:
    """One row per point of the /heat table: friction, heat power and its partition, steady-state power per
    gear, flash temperature, frictional and oil-film heat; '-' where a column is missing."""
    heat = result.heat
    rows = [[str(name), *(c.text(heat[c.key].values[i] if c.key in heat else None) for c in _HEAT)]
            for i, name in enumerate(heat["point"].values)]
    return format_table(["point", *(c.header for c in _HEAT)], rows)


# Meshing-cycle columns, keys of the /cycle group.
_CYCLE = (
    Column("s", "s", "m", ".2f", MILLIMETRE),
    Column("K", "load_share", spec=".3f"),
    Column("p_h", "p_h", "Pa", ".1f"),
    Column("h_min", "h_min", "m"),
    Column("lambda", "film_parameter", spec=".2f"),
    Column("dT_max", "dT_max", "K", ".1f"),
    Column("flash", "flash_temperature", "K", ".1f"),
    Column("theta_B,1", "contact_temperature_1", "K", ".1f", CELSIUS),
    Column("theta_B,2", "contact_temperature_2", "K", ".1f", CELSIUS),
    Column("mu", "mu", spec=".4f"),
    Column("mu Xu", "mu_xu", spec=".4f"),
    Column("P", "sliding_power", "W", ".1f"),
)
# Power-loss variants: attr suffix, label; [c] marks the cylindrical-gear correlations.
_LOSS_VARIANTS = (("", "film mu (solved)"), ("_xu", "Xu et al. (2007) mu along the path [c]"),
                  ("_iso", "ISO/TR 14179-2 mean mu {mu_iso:.4f} [c]"),
                  ("_dissipated", "film dissipation, whole domain"))


def cycle_table(result: Result) -> str:
    """One row per point of the /cycle group in path order; '-' where a column is missing."""
    cycle = result.cycle
    rows = [[str(name), *(c.text(cycle[c.key].values[i] if c.key in cycle else None) for c in _CYCLE)]
            for i, name in enumerate(cycle["point"].values)]
    return format_table(["point", *(c.header for c in _CYCLE)], rows)


def cycle_summary(result: Result) -> str:
    """The mesh power loss and efficiency with their variants, the quadrature, and a note on coarse samples."""
    scalars = result.cycle_scalars
    count = int(scalars["point_count"])
    if not any(f"power_loss{suffix}" in scalars for suffix, _ in _LOSS_VARIANTS):
        return f"mesh cycle: {count} points; no mesh power loss (see the warnings)"
    lines = [f"mesh cycle: {count} points, input power T1 w1 = {scalars['input_power'] / 1e3:.2f} kW; "
             f"power loss = {QUADRATURE}:"]
    for suffix, label in _LOSS_VARIANTS:
        if f"power_loss{suffix}" in scalars:
            lines.append(f"  {label.format(**scalars):<42}  power loss {scalars[f'power_loss{suffix}']:8.1f} W  "
                         f"efficiency {PERCENT(scalars[f'mesh_efficiency{suffix}']):.3f} %")
    lines.append("  [c] cylindrical-gear correlations: face gears are outside their scope")
    if count < COARSE_POINT_COUNT:
        lines.append(f"  note: {count} points are a coarse sample of the cycle (gear.points: 41 samples it "
                     "evenly; docs/cycle.md)")
    return "\n".join(lines)


def summary_table(points: Iterable[PointResult]) -> str:
    """One row per point: convergence, film, pressure, load balance and cost; '-' where a value is missing."""
    rows = [[p.name, yes_no(p.converged), *(c.text(p.scalars.get(c.key)) for c in _SUMMARY),
             *(_error_percent(p, key, of) for _, key, of in _ERROR_ESTIMATES)] for p in points]
    headers = ["point", "converged", *(c.header for c in _SUMMARY), *(h for h, *_ in _ERROR_ESTIMATES)]
    return format_table(headers, rows)


def _error_percent(point: PointResult, key: str, of: str) -> str:
    """An error estimate in % of its quantity: given in metres (absolute) or as a fraction (relative)."""
    if key not in point.scalars:
        return "-"
    value = point.scalars[key]
    if point.units.get(key) == "m":
        if not point.scalars.get(of):
            return "-"
        value = value / point.scalars[of]
    return cell(PERCENT(abs(value)), ".2f", "-")


def _report_progress(solution: PointSolution, done: int, total: int) -> None:
    if solution.converged:
        state = "converged"
    else:
        state = solution.message or "not converged"
    details = []
    if "iterations" in solution.scalars:
        details.append(f"{solution.scalar('iterations'):.0f} cycles")
    if "wall_time" in solution.scalars:
        details.append(f"{solution.scalar('wall_time'):.2f} s")
    suffix = f" ({', '.join(details)})" if details else ""
    click.echo(f"[{done}/{total}] {solution.name}: {state}{suffix}", err=True)


def _point_names(option: str | None) -> list[str] | None:
    if option is None:
        return None
    return list(dict.fromkeys(name.strip() for name in option.split(",") if name.strip()))


def _output_path(case_file: Path, case: Case, option: str | None) -> Path:
    """-o, else output.file of the case (relative to the case file), else <case name>.h5 here.

    Checked before solving (CaseError): not a directory, and its nearest existing folder is writable.
    """
    if option is not None:
        key, target = "--output", Path(option)
    elif case.output.file is not None:
        key, target = "output.file", case_file.parent / case.output.file
    else:
        key, target = "name", Path(f"{case.name}.h5")
    return _writable(key, target)


def _writable(key: str, target: Path) -> Path:
    """`target`, checked before solving (CaseError under `key`): not a directory, and its nearest existing
    folder is writable."""
    if target.is_dir():
        raise CaseError(key, str(target), "a file path, not a directory")
    folder = target.absolute().parent
    while not folder.exists():
        folder = folder.parent
    if not folder.is_dir() or not os.access(folder, os.W_OK):
        raise CaseError(key, str(target), f"a path under a writable directory ({folder} is not)")
    return target


def _terminate(signum: int, frame: object) -> None:
    """SIGTERM ends the run like Ctrl-C does: cleanups run and no partial result file is left."""
    raise SystemExit(128 + signum)


def main(argv: Sequence[str] | None = None) -> None:
    """Console entry point `tehl`."""
    signal.signal(signal.SIGTERM, _terminate)
    tehl.main(args=argv, prog_name="tehl")

"""Command line: `tehl init | validate | contact | run | info | plot | report | compare | sweep | study`
(docs/cli.md).

Exit codes: 0 ok; 1 unexpected error (or a point whose solve failed; its result is still written);
2 bad input (case file, options, not a result file): one line `error: <key path>: ...` per problem, no
output file; 3 not converged (result written, flagged), or a variant of a study that did not converge or failed
(the others written);
130 interrupted by Ctrl-C, 143 by SIGTERM (docs/guarantees.md).
Warnings (valid but unusual input) go to stderr.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import replace
import gc
import json
from pathlib import Path
import signal
import traceback
from typing import Any

import click
import numpy as np

from facegear_tehl import __version__, kernel_cache
from facegear_tehl.accuracy_record import accuracy_lines, accuracy_summary, accuracy_to_dict
from facegear_tehl.case import Case, accuracy_fraction, load_case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.cycle import COARSE_POINT_COUNT, QUADRATURE
from facegear_tehl.ehl.tuning import TUNING
from facegear_tehl.ehl.unresolved import Why
from facegear_tehl.gears.analysis import analyse_gear_pair
from facegear_tehl.gears.report import contact_table
from facegear_tehl.output_path import (
    checked_output,
    inside_case_folder,
    keeping_the_better,
    starts_with,
    writable_location,
)
from facegear_tehl.parallel import worker_count
from facegear_tehl.points import contact_analysis, select_points
from facegear_tehl.record import record_lines, record_to_dict
from facegear_tehl.resources import check_fits, estimate, machine_memory, study_estimate
from facegear_tehl.results import PointResult, Result, ResultFileError, read_result, write_result
from facegear_tehl.schema import CaseError, check
from facegear_tehl.settings import SolverSettings
from facegear_tehl.solution import PointSolution
from facegear_tehl.sweep import check_tolerance, parse_grids, report, run_sweep, with_thermal, write_csv
from facegear_tehl.tables import (
    COST,
    ROUND_OFF,
    SCALAR_GROUPS,
    UNRESOLVED,
    UNRESOLVED_REASON,
    UNRESOLVED_WORD,
    Column,
    cell,
    error_bound,
    format_pairs,
    format_table,
    group_of,
    scalar_unit,
    yes_no,
)
from facegear_tehl.templates import case_template
from facegear_tehl.units import CELSIUS, MILLIMETRE, PERCENT, Unit, display
from facegear_tehl.verdict import assess, verdict_text

EXIT_ERROR, EXIT_BAD_INPUT, EXIT_NOT_CONVERGED = 1, 2, 3
EXIT_INTERRUPTED = 128 + signal.SIGINT  # 130
UNEXPECTED = "an unexpected error: tehl --debug with the same arguments shows where; please report it with that output"
BIG_RUN_SECONDS = 600.0  # a run estimated longer than this says so before it starts
ANNOUNCED_VARIANTS = 100  # a study of this many variants says its size before validating them (2 s or more) ...
ACCURACY_HELP = ("Accuracy asked of h_c, h_min, p_max, dT_max and mu, a fraction or a percentage (1%): the solver "
                 "chooses each point's grid and cheaper models (overrides solver.accuracy).")
ACCURACY_TITLE = ("accuracy target {:g} % per point: the grid chosen (asked, solved), each figure's bound (grid and "
                  "cheaper model) against it, the solves and their wall time (tehl info: the choices and each solve):")
VALIDATION_SECONDS = 0.02  # ... at about this many seconds a variant (1000 face gear variants validated in 20 s)


class _Tehl(click.Group):
    """Turns bad input into one line and exit 2, and any other error into one line and exit 1."""

    def invoke(self, ctx: click.Context) -> Any:
        try:
            return super().invoke(ctx)
        except (click.ClickException, click.exceptions.Exit, click.Abort):
            raise
        except KeyboardInterrupt:  # Ctrl-C: the shell's convention, 128 + SIGINT; files as SIGTERM leaves them
            click.echo("interrupted", err=True)
            ctx.exit(EXIT_INTERRUPTED)
        except (CaseError, ResultFileError) as exc:
            for line in str(exc).splitlines():  # one line per problem (CaseErrors holds several)
                click.echo(f"error: {line}", err=True)
            ctx.exit(EXIT_BAD_INPUT)
        except Exception as exc:  # noqa: BLE001 - any other error: one line and exit 1 (--debug: the traceback)
            if ctx.params.get("debug"):
                traceback.print_exc()
            click.echo(f"error: {type(exc).__name__}: {exc} ({UNEXPECTED})", err=True)
            ctx.exit(EXIT_ERROR)


@click.group(cls=_Tehl, context_settings={"help_option_names": ["-h", "--help"]}, epilog="""\b
Examples:
  tehl init -o my_gear.yaml          write a commented face gear case
  tehl validate my_gear.yaml         check it (exit 2 naming every problem)
  tehl run my_gear.yaml --grid 65    solve it on a quick grid: my_gear.h5
  tehl info my_gear.h5               its results in µm, MPa, K, %
  tehl plot my_gear.h5               its figures
Each command has its own --help with examples; docs/cli.md shows them with their output.""")
@click.version_option(__version__, prog_name="tehl")
@click.option("--debug", is_flag=True, help="Show the traceback of unexpected errors.")
def tehl(debug: bool) -> None:
    """Thermal EHL of face gear pairs: one YAML case in, one HDF5 result out."""


@tehl.command(epilog="""\b
Examples:
  tehl run cases/facegear_110.yaml                      all points, the case's grid
  tehl run cases/facegear_110.yaml --grid 65 -o quick.h5
  tehl run cases/facegear_110.yaml --points S1,S3 --thermal off
  tehl run cases/ball_on_disc.yaml --jobs 1""")
@click.argument("case_file", metavar="CASE")
@click.option("-o", "--output", help="Result file (default: output.file of the case, else <case name>.h5).")
@click.option("--grid", type=int, help="Nodes per side of the finest grid, 2^n + 1 (overrides solver.grid).")
@click.option("--points", help="Comma-separated point names to solve (e.g. S1,S3); default all.")
@click.option("--thermal", help="Thermal model, overrides solver.thermal: off | reduced | full | auto.")
@click.option("--accuracy", help=ACCURACY_HELP)
@click.option("--jobs", type=int, help="Worker processes solving points side by side (default: all cores).")
@click.option("--force", is_flag=True, help="Overwrite an existing output file that tehl did not write; run even "
                                           "when the memory estimate passes this machine's memory.")
@click.pass_context
def run(
    ctx: click.Context,
    case_file: str,
    output: str | None,
    grid: int | None,
    points: str | None,
    thermal: str | None,
    accuracy: str | None,
    jobs: int | None,
    force: bool,
) -> None:
    """Solve CASE and write the result file."""
    case = _with_options(_load_case(case_file, solves=True), thermal, accuracy, grid)
    workers = worker_count(jobs)
    solver = (case if grid is None else case.with_grid(grid)).solver
    names = _point_names(points)
    analysis = contact_analysis(case)
    selected = analysis.points if names is None else select_points(analysis.points, names)
    target = _output_path(Path(case_file), case, output, force)
    processes = min(workers, len(selected))
    _guard([(p, case.lubricant, solver) for p in selected], processes, ("--grid", grid) if grid else
           ("solver.grid", case.solver.grid), force)
    click.echo(_run_banner(case, selected, solver, processes), err=True)
    for warning in analysis.warnings:
        click.echo(f"warning: {warning}", err=True)
    # Imported once the input is checked: only this command needs the solver (Numba kernels).
    from facegear_tehl.run import run_case

    run_result = assess(run_case(case, grid=grid, points=names, progress=_report_progress, jobs=workers))
    if thermal is not None:  # recorded in the file like the other options that change the case
        run_result = replace(run_result, overrides={**run_result.overrides, "thermal": thermal})
    for warning in run_result.warnings:
        if warning not in analysis.warnings:  # what the run found (a grid the solver chose, ...)
            click.echo(f"warning: {warning}", err=True)
    target, kept = keeping_the_better(target, sum(p.converged for p in run_result.points))
    if kept:
        click.echo(f"warning: {kept}", err=True)
    target.parent.mkdir(parents=True, exist_ok=True)
    write_result(run_result, target)
    result = read_result(target, fields=False)  # the tables print what the file holds
    click.echo(SUMMARY_TITLE + "\n" + summary_table(result.points.values()))
    if any(p.accuracy is not None for p in result.points.values()):
        click.echo(ACCURACY_TITLE.format(100 * case.solver.accuracy) + "\n" + "\n".join(
            accuracy_summary(p.name, p.accuracy) for p in result.points.values() if p.accuracy is not None))
    if result.heat and "point" in result.heat:
        click.echo(HEAT_TITLE + "\n" + heat_budget_table(result))
    if result.cycle:
        click.echo(CYCLE_TITLE + "\n" + cycle_table(result))
        click.echo(cycle_summary(result))
    verdict = verdict_text(result)
    if verdict:
        click.echo(verdict)
    click.echo(f"result: {target} (status {result.status})")
    _exit_on_status(ctx, result)


def _with_options(case: Case, thermal: str | None, accuracy: str | None, grid: int | None) -> Case:
    """The case with the command line's thermal model and accuracy target (CaseError for --grid with a target: the
    target chooses the grid)."""
    if thermal is not None:
        case = with_thermal(case, thermal)
    if accuracy is not None:
        case = case.with_accuracy(accuracy)
    check(grid is None or case.solver.accuracy is None, "--grid", grid,
          "no --grid with an accuracy target (solver.accuracy, --accuracy): the target chooses the grid")
    return case


def _run_banner(case: Case, selected: Sequence[ContactPoint], solver: SolverSettings, processes: int) -> str:
    """The first line of `tehl run`: the case, its points, the grid asked (or the accuracy target), the model."""
    if solver.accuracy is None:
        grid = (f"on a {solver.grid}x{solver.nodes_y} grid", " (the grid as asked; each point's line gives the grid "
                "solved on, with the lengthened inlet)")
    else:
        grid = (f"to {100 * solver.accuracy:g} % accuracy", f" (each point's grid and cheaper models chosen from "
                f"{TUNING.accuracy_start_grid} nodes along x; a line per solve, with the grid solved on, or with "
                f"worker processes a line per point as it ends)")
    workers = f", {processes} worker processes" if processes > 1 else ""
    return (f"tehl run: {case.name}: {', '.join(p.name for p in selected)} {grid[0]}, thermal {solver.thermal}"
            f"{workers}{grid[1]}")


def _load_case(case_file: str, solves: bool = False) -> Case:
    """The validated case; its warnings (valid but unusual values) and the inputs it derived (an oil given by
    grade or nu40, nu100) on stderr, and for a command that `solves` the kernel cache's (kernel_cache.py)."""
    case = load_case(case_file)
    if solves and kernel_cache.WARNING:
        click.echo(f"warning: {kernel_cache.WARNING}", err=True)
    for warning in case.warnings:
        click.echo(f"warning: {warning}", err=True)
    for line in case.derived:
        click.echo(f"derived: {line}", err=True)
    return case


def _guard(tasks: list, processes: int, setting: tuple[str, Any], force: bool) -> None:
    """The resource guard (resources.py): refuse a run above this machine's memory unless `force` (CaseError under
    the option or key that set the grid); print the estimate when it takes half the memory or ten minutes."""
    found = estimate(tasks, processes)
    check_fits(found, *setting, force)
    if found.memory > 0.5 * machine_memory() or found.seconds > BIG_RUN_SECONDS:
        click.echo(f"note: {found.text()}", err=True)


def _exit_on_status(ctx: click.Context, result: Result) -> None:
    """Exit 1 if a point failed, 3 if one did not converge (the file is written either way)."""
    if result.status == "failed":
        click.echo(f"error: {result.message}", err=True)
        ctx.exit(EXIT_ERROR)
    if result.status == "not_converged":
        click.echo(f"warning: not converged: {result.message}", err=True)
        ctx.exit(EXIT_NOT_CONVERGED)


@tehl.command(epilog="""\b
Examples:
  tehl sweep cases/facegear_110.yaml --point S3 --grids 33,65,129
  tehl sweep cases/ball_on_disc.yaml --thermal off --tol 0.005 -o ball_sweep.h5""")
@click.argument("case_file", metavar="CASE")
@click.option("--grids", default="33,65,129,257,513", show_default=True,
              help="Nodes per side of each grid: ascending, each refining the previous by 2, at least three.")
@click.option("--point", help="Point to solve (default: the case's first, S1 for a face gear pair).")
@click.option("--thermal", help="Thermal model, overrides solver.thermal: off | reduced | full | auto.")
@click.option("--tol", "tolerance", type=float, default=0.01, show_default=True,
              help="Relative change to the next grid below which a quantity counts as grid-independent.")
@click.option("--accuracy", help="Also solve the point to this accuracy (a fraction or 1%; overrides "
                                 "solver.accuracy) and compare it with the sweep's extrapolated values.")
@click.option("-o", "--output",
              help="Sweep file, HDF5 (default: <case name>_sweep_<point>.h5); the CSV goes next to it.")
@click.option("--jobs", type=int, help="Worker processes solving grids side by side (default: all cores).")
@click.option("--force", is_flag=True, help="Overwrite existing output files that tehl did not write; run even "
                                           "when the memory estimate passes this machine's memory.")
@click.pass_context
def sweep(
    ctx: click.Context,
    case_file: str,
    grids: str,
    point: str | None,
    thermal: str | None,
    tolerance: float,
    accuracy: str | None,
    output: str | None,
    jobs: int | None,
    force: bool,
) -> None:
    """Solve one point of CASE on a sequence of grids and print its mesh-independence table (change per
    grid, observed order, Richardson extrapolation with its GCI uncertainty); writes HDF5 (/sweep) and CSV."""
    case = _load_case(case_file, solves=True)
    if accuracy is not None:
        case = case.with_accuracy(accuracy)
    grid_list = parse_grids(grids, case)
    check_tolerance(tolerance)
    workers = worker_count(jobs)
    model = case.solver.thermal if thermal is None else with_thermal(case, thermal).solver.thermal
    points = contact_analysis(case).points
    name = points[0].name if point is None else select_points(points, [point], key="--point")[0].name
    target = Path(output if output is not None else f"{case.name}_sweep_{name}.h5")
    if target.suffix.lower() == ".csv":
        raise CaseError("--output", str(target), "an HDF5 file name (the CSV is written next to it)")
    checked_output("--output", target, inputs=[Path(case_file)], force=force)
    checked_output("--output", target.with_suffix(".csv"), inputs=[Path(case_file)], force=force,
                   ours=starts_with("grid ["), what="a sweep CSV")
    point_of = next(p for p in points if p.name == name)
    swept_case = case if thermal is None else with_thermal(case, thermal)
    _guard([(point_of, case.lubricant, swept_case.with_grid(g).solver) for g in grid_list], workers,
           ("--grids", grids), force)
    click.echo(
        f"tehl sweep: {case.name}: {name} on grids {','.join(map(str, grid_list))}, thermal {model}"
        + (f", {min(workers, len(grid_list))} worker processes" if workers > 1 else ""),
        err=True,
    )
    swept = run_sweep(case, grid_list, point=name, thermal=thermal, tolerance=tolerance, jobs=workers,
                      progress=_report_progress)
    target.parent.mkdir(parents=True, exist_ok=True)
    write_result(swept.run, target)
    result = read_result(target, fields=False)
    for warning in result.warnings:
        click.echo(f"warning: {warning}", err=True)
    csv = write_csv(result.sweep, target.with_suffix(".csv"))
    click.echo(report(result.sweep, result.sweep_scalars))
    click.echo(f"result: {target}, {csv} (status {result.status})")
    _exit_on_status(ctx, result)


@tehl.command(epilog="""\b
Examples:
  tehl study torque_speed.yaml -o maps --workers 2      a local Dask cluster of two worker processes
  tehl study torque_speed.yaml --scheduler tcp://host:8786   an existing Dask cluster
  tehl plot maps --what maps --z h_min""")
@click.argument("study_file", metavar="STUDY")
@click.option("-o", "--output", help="Folder of the study's result files and index.csv (default: <STUDY name>_study).")
@click.option("--workers", type=int, help="Worker processes of the local Dask cluster (default: all cores).")
@click.option("--scheduler", help="Address of an existing Dask scheduler (e.g. tcp://host:8786) instead.")
@click.option("--accuracy", help="Accuracy asked of every variant, a fraction or a percentage (1%): sets "
                                 "solver.accuracy in each (over the study's set: and base case).")
@click.option("--force", is_flag=True, help="Run even when the memory estimate of the local cluster passes this "
                                           "machine's memory.")
@click.pass_context
def study(ctx: click.Context, study_file: str, output: str | None, workers: int | None, scheduler: str | None,
          accuracy: str | None, force: bool) -> None:
    """Run every variant of STUDY (a base case and the keys it varies) on a Dask cluster: one result file per
    variant, named by its varied values (a hash suffix only where needed), and index.csv; variants already finished
    are skipped."""
    # Imported here: only this command needs Dask.
    from facegear_tehl.study import check_folder, run_study
    from facegear_tehl.study_file import load_study

    fixed = () if accuracy is None else (("solver.accuracy", accuracy_fraction(accuracy, "--accuracy")),)
    plan = load_study(study_file, announce=_announce_study, fixed=fixed)
    if kernel_cache.WARNING:
        click.echo(f"warning: {kernel_cache.WARNING}", err=True)
    if scheduler is not None and workers is not None:
        raise CaseError("--workers", workers, "no --workers with --scheduler (the cluster has its own workers)")
    count = min(worker_count(workers, "--workers"), len(plan.variants))  # a worker per variant at most, as --jobs
    folder = Path(output if output is not None else f"{Path(study_file).stem}_study")
    check_folder(folder)
    if scheduler is None:  # the local cluster's memory (a remote cluster's machines are not this one)
        found = study_estimate([v.case for v in plan.variants], count)
        check_fits(found, "--workers", count, force)
        if found.memory > 0.5 * machine_memory():
            click.echo(f"note: {found.text()}", err=True)
    where = f"the Dask cluster at {scheduler}" if scheduler else f"a local Dask cluster of {count} worker processes"
    click.echo(f"tehl study: {len(plan.variants)} variants of {plan.base.name} over {', '.join(plan.keys)} "
               f"on {where}", err=True)
    report = run_study(plan, folder, workers=count, scheduler=scheduler, progress=_study_progress,
                       notice=lambda line: click.echo(f"warning: {line}", err=True))
    skipped = len(report.outcomes) - report.computed
    not_converged = sum(o.status == "not_converged" for o in report.outcomes)
    click.echo(f"{report.computed} variants computed, {skipped} already finished, {len(report.failed)} failed, "
               f"{not_converged} not converged; index: {report.index}")
    for outcome in report.failed:
        click.echo(f"failed: variant {outcome.variant.index + 1} ({outcome.variant.label}): {outcome.message}",
                   err=True)
    if report.failed or any(o.status in ("not_converged", "failed") for o in report.outcomes):
        ctx.exit(EXIT_NOT_CONVERGED)  # as tehl run: every variant is in the index, one did not converge or failed


def _announce_study(count: int) -> None:
    """A study large enough that validating its variants takes a while says its size first."""
    if count >= ANNOUNCED_VARIANTS:
        click.echo(f"tehl study: {count} variants: validating each case (about {count * VALIDATION_SECONDS:.0f} s)",
                   err=True)


def _study_progress(outcome, done: int, total: int, eta: float) -> None:
    state = outcome.status if outcome.status != "failed" else f"failed: {outcome.message}"
    click.echo(f"[{done}/{total}] variant {outcome.variant.index + 1} ({outcome.variant.label}): {state}, "
               f"{outcome.seconds:.1f} s; ETA {_duration(eta)}", err=True)


def _duration(seconds: float) -> str:
    minutes, rest = divmod(round(seconds), 60)
    return f"{minutes // 60} h {minutes % 60:02d} min" if minutes >= 60 else f"{minutes} min {rest:02d} s"


@tehl.command(epilog="""\b
Examples:
  tehl validate cases/facegear_110.yaml
  tehl init --contact -o ball.yaml && tehl validate ball.yaml""")
@click.argument("case_file", metavar="CASE")
def validate(case_file: str) -> None:
    """Check CASE without running it."""
    case = _load_case(case_file)
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
        + ("" if case.solver.accuracy is None else f"; accuracy {100 * case.solver.accuracy:g} %")
    )


@tehl.command(epilog="""\b
Example:
  tehl contact cases/facegear_110.yaml""")
@click.argument("case_file", metavar="CASE")
def contact(case_file: str) -> None:
    """Print the face gear contact analysis of CASE at its meshing points (no lubrication)."""
    case = _load_case(case_file)
    if case.gear is None:
        raise CaseError("gear", None, "a gear: block (tehl contact analyses a face gear pair)")
    click.echo(contact_table(analyse_gear_pair(case.gear, case.materials.body_1, case.materials.body_2)))


@tehl.command(epilog="""\b
Examples:
  tehl init                            a face gear case: case.yaml
  tehl init --contact -o ball.yaml     a plain elliptical contact
  tehl init -o my_gear.yaml && tehl validate my_gear.yaml && tehl run my_gear.yaml --grid 65""")
@click.option("--gear", "kind", flag_value="gear", default=True, help="A face gear pair (the default).")
@click.option("--contact", "kind", flag_value="contact", help="A plain elliptical contact (ball on disc).")
@click.option("-o", "--output", default="case.yaml", show_default=True, help="Case file to write.")
@click.option("--force", is_flag=True, help="Overwrite OUTPUT if it exists.")
def init(kind: str, output: str, force: bool) -> None:
    """Write a commented case template (valid as written); edit it, then validate and run it."""
    target = writable_location("--output", Path(output))
    if target.exists() and not force:
        raise CaseError("--output", output, "a file that does not exist yet (--force overwrites it)")
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(case_template(kind, target.name), encoding="utf-8")
    click.echo(f"wrote {target}: a {'face gear' if kind == 'gear' else 'plain contact'} case; next: "
               f"tehl validate {target}")


@tehl.command(epilog="""\b
Examples:
  tehl info facegear_110.h5           by theme, in µm, MPa, K, %
  tehl info facegear_110.h5 --si      the same in SI units
  tehl info facegear_110.h5 --json    SI values for scripts""")
@click.argument("result_file", metavar="RESULT")
@click.option("--si", is_flag=True, help="Values in the file's SI units (m, Pa, K, fractions), not µm, MPa, K, %.")
@click.option("--json", "as_json", is_flag=True, help="Print the per-point scalars (SI) as JSON.")
def info(result_file: str, si: bool, as_json: bool) -> None:
    """Show the per-point scalars of a result file, by theme, in engineering units."""
    result = read_result(result_file, fields=False)
    click.echo(json.dumps(info_json(result), indent=2) if as_json else info_text(result, si=si))


@tehl.command(epilog="""\b
Examples:
  tehl plot facegear_110.h5
  tehl plot facegear_110.h5 --what maps --point S1,S3 --format pdf
  tehl plot facegear_110.h5 --what trends,heat -o figures""")
@click.argument("result_file", metavar="RESULT")
@click.option("--what", default="default", show_default=True,
              help="Figure types, comma-separated: default (centreline, overview, trends, friction, heat, contact, "
                   "convergence, cycle), all, or any of those and maps, surfaces (a file per point and field); for a "
                   "`tehl study` folder: maps (operating maps over its varied keys, docs/study.md).")
@click.option("--point", "points", help="Points whose fields and convergence are drawn, comma-separated; default all.")
@click.option("-o", "--output", help="Folder for the figures (default: <RESULT name>_plots next to RESULT).")
@click.option("--format", "fmt", default="png", show_default=True, help="png | pdf | svg.")
@click.option("--dpi", type=int, default=150, show_default=True, help="Resolution of raster figures.")
@click.option("--z", default="h_min", show_default=True, help="Study maps: the scalar of index.csv drawn.")
@click.option("--x", "x_key", help="Study maps: the varied key along x (default: the first).")
@click.option("--y", "y_key", help="Study maps: the varied key along y (default: the second).")
def plot(result_file: str, what: str, points: str | None, output: str | None, fmt: str, dpi: int, z: str,
         x_key: str | None, y_key: str | None) -> None:
    """Draw the figures of a result file, or the maps (--what maps) of a `tehl study` folder (nothing is solved);
    figure types without data are skipped."""
    # Imported here: only this command needs matplotlib.
    from facegear_tehl.plots import figure_types, plot_result

    source = Path(result_file)
    if output is not None:
        _check_figure_folder(Path(output), source)
    if source.is_dir():  # a study folder: maps over its varied keys
        from facegear_tehl.plots.study_maps import plot_study

        folder = Path(output) if output is not None else source / "maps"
        report = plot_study(source, folder, what=what, z=z, x=x_key, y=y_key, points=_point_names(points), fmt=fmt,
                            dpi=dpi)
    else:
        result = read_result(result_file)
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


@tehl.command("report", epilog="""\b
Examples:
  tehl report facegear_110.h5                  writes facegear_110.html beside it
  tehl report facegear_110.h5 -o review.html""")
@click.argument("result_file", metavar="RESULT")
@click.option("-o", "--output", help="The HTML file (default: <RESULT name>.html next to RESULT).")
def report_command(result_file: str, output: str | None) -> None:
    """Write one self-contained HTML page of a result file (inputs, verdict, results with their error estimates,
    key figures, solve summary, provenance) to hand on or print to PDF; nothing is solved."""
    # Imported here: only this command and plot need matplotlib.
    from facegear_tehl.report_page import write_report

    source = Path(result_file)
    target = checked_output("--output", Path(output) if output is not None else source.with_suffix(".html"),
                            inputs=[source], ours=starts_with("<!DOCTYPE html>"), what="an HTML")
    click.echo(f"report: {write_report(read_result(source), target)}")


@tehl.command("compare", epilog="""\b
Examples:
  tehl compare design_a.h5 design_b.h5                    table, and design_a_compare.png
  tehl compare a.h5 b.h5 c.h5 -o compare.pdf""")
@click.argument("result_files", metavar="RESULT RESULT [...]", nargs=-1)
@click.option("-o", "--output", help="The figure along the path (.png, .pdf, .svg; default: <first>_compare.png).")
def compare_command(result_files: tuple[str, ...], output: str | None) -> None:
    """Compare two or more result files point by point: each quantity side by side, the difference to the first
    file and whether it exceeds the combined error estimates; and a figure along the contact path."""
    # Imported here: only this command, plot and report need matplotlib.
    from facegear_tehl.compare import common_points, comparison_table, labels_of, save_figure
    from facegear_tehl.plots import FORMATS

    if len(result_files) < 2:
        raise CaseError("RESULT", " ".join(result_files), "two or more result files")
    paths = [Path(name) for name in result_files]
    target = Path(output) if output is not None else paths[0].with_name(f"{paths[0].stem}_compare.png")
    if target.suffix.lstrip(".") not in FORMATS:
        raise CaseError("--output", str(target), "a figure file ending in ." + ", .".join(FORMATS))
    checked_output("--output", target, inputs=paths, ours=lambda path: path.suffix.lstrip(".") in FORMATS,
                   what="a figure")
    results = [read_result(path, fields=False) for path in paths]
    if not common_points(results):
        raise CaseError("RESULT", " ".join(result_files), "files that share at least one point name")
    labels = labels_of(paths)
    click.echo("point by point: each file's value, its difference to the first and whether it exceeds the combined "
               "grid-error estimates sqrt(e_1^2 + e_2^2) of the two:")
    click.echo(comparison_table(results, labels))
    for path in save_figure(results, labels, target).written:
        click.echo(f"figure: {path}")


def info_json(result: Result) -> dict[str, Any]:
    """{'case', 'status', 'message', 'format_version', 'points': {name: {scalar: SI value, 'converged',
    'message'}}, 'units': {name: {scalar: unit}}, 'solve': {name: the solve record (record.record_to_dict)}}, and
    'accuracy' (accuracy_record.accuracy_to_dict), 'cycle' and 'verdict' where the file has them."""
    return {
        "case": result.case_name,
        "status": result.status,
        "message": result.message,
        "format_version": result.format_version,
        "points": {
            name: {**p.scalars, "converged": p.converged, "message": p.message} for name, p in result.points.items()
        },
        "units": {name: dict(p.units) for name, p in result.points.items()},
        "solve": {name: record_to_dict(p.record) for name, p in result.points.items() if p.record is not None},
        **({"accuracy": {name: accuracy_to_dict(p.accuracy) for name, p in result.points.items()
                         if p.accuracy is not None}} if any(p.accuracy for p in result.points.values()) else {}),
        **({"cycle": {**result.cycle_scalars, "units": dict(result.cycle_units),
                      "columns": {name: column.values.tolist() for name, column in result.cycle.items()}}}
           if result.cycle else {}),
        **({"verdict": {**result.verdict, "units": dict(result.verdict_units), "labels": dict(result.verdict_labels)}}
           if result.verdict or result.verdict_labels else {}),
    }


def info_text(result: Result, si: bool = False) -> str:
    """The file's header, then the scalars of every point in tables by theme (film, pressure, temperature,
    heat, convergence, other): in engineering units (µm, mm, MPa, K, %), a value below ROUND_OFF of the largest
    of its unit in its table shown as 0 (round-off); or the file's raw SI values with `si`."""
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
    header += [("derived", line) for line in result.derived]
    header += [("warning", warning) for warning in result.warnings]
    points = list(result.points.values())
    names = list(dict.fromkeys(key for p in points for key in p.scalars if not key.startswith(UNRESOLVED_REASON)))
    units = {key: next(p.units[key] for p in points if key in p.units) for key in names}
    lines = [format_pairs(header)]
    for group in [name for name, _ in SCALAR_GROUPS] + ["other"]:
        keys = [key for key in names if group_of(key) == group]
        if group == "convergence":
            keys = ["converged", *keys]
        elif not keys:
            continue
        rows = [["converged", "", *(yes_no(p.converged) for p in points)] if key == "converged" else
                _flag_row(key, [p.scalars.get(key) for p in points]) if key.startswith(UNRESOLVED) else
                _unresolved_cells(key, points, _scalar_row(key, units[key], [p.scalars.get(key) for p in points],
                                                           _scale(keys, units, points), si))
                for key in keys]
        lines += ["", format_table([group, "unit", *(p.name for p in points)], rows)]
    if result.heat and "point" in result.heat:
        lines += ["", HEAT_TITLE, heat_budget_table(result)]
    if result.cycle:
        lines += ["", CYCLE_TITLE, cycle_table(result), cycle_summary(result)]
    verdict = verdict_text(result)
    if verdict:
        lines += ["", verdict]
    lines += _point_sections(points)
    if result.contact_scalars:
        contact_rows = [_scalar_row(key, result.contact_units[key], [value], abs(value), si)
                        for key, value in result.contact_scalars.items()]
        lines += ["", format_table(["contact", "unit", "value"], contact_rows)]
    return "\n".join(lines)


def _point_sections(points: list[PointResult]) -> list[str]:
    """The thermal model each point ran where it is not the case's (`thermal: auto`'s choice, `reduced` solved
    `full` on a grid too coarse for its coarse stage) and why, then each point's solve record and accuracy record,
    for `tehl info`."""
    lines = []
    choices = [f"  {p.name}: {p.models['thermal']} ({p.models['thermal_reason']})" for p in points
               if p.models.get("thermal_reason", "").startswith("auto") or "solved full" in p.models.get(
                   "thermal_reason", "")]
    if choices:
        lines += ["", "thermal model each point ran, where not the case's (docs/accuracy.md):", *choices]
    reasons = [f"  {p.name} {key.removeprefix(UNRESOLVED_REASON)}: {Why(int(code)).words}" for p in points
               for key, code in p.scalars.items()
               if key.startswith(UNRESOLVED_REASON) and code in set(Why) and Why(int(code)) is not Why.NEVER]
    if reasons:
        lines += ["", "why a figure is unresolved (p_max never has a bound; docs/accuracy.md, error bounds):",
                  *reasons]
    for p in points:
        if p.record is not None:
            lines += ["", *record_lines(p.name, p.record)]
        if p.accuracy is not None:
            lines += ["", *accuracy_lines(p.name, p.accuracy)]
    return lines


def _unresolved_cells(key: str, points: list[PointResult], row: list[str]) -> list[str]:
    """An error-estimate row (`error_estimate_<figure>`, `error_estimate_y_<figure>`) with the word "unresolved" for
    each point that cannot bound the figure: its estimate is no promise there."""
    if not key.startswith("error_estimate_"):
        return row
    figure = key.removeprefix("error_estimate_").removeprefix("y_")
    return [*row[:2], *(UNRESOLVED_WORD if isinstance(error_bound(p.scalars, figure), str) else cell
                        for p, cell in zip(points, row[2:]))]


def _flag_row(key: str, values: list[float | None]) -> list[str]:
    """An unresolved_<quantity> flag per point as a word: "unresolved" (1), "bounded" (0), "-" (missing)."""
    return [key, "", *("-" if v is None else "unresolved" if v == 1.0 else "bounded" for v in values)]


def _scale(keys: list[str], units: Mapping[str, str], points: list[PointResult]) -> dict[str, float]:
    """The largest |value| of each SI unit among `keys` over all points (the reference of round-off)."""
    scale: dict[str, float] = {}
    for key in keys:
        for p in points:
            if key in p.scalars:
                scale[units[key]] = max(scale.get(units[key], 0.0), abs(p.scalars[key]))
    return scale


def _scalar_row(key: str, units: str, values: list[float | int | None], scale: Mapping[str, float] | float,
                si: bool) -> list[str]:
    """[key, unit, a cell per value]: raw SI with `si` (6 digits), else in `scalar_unit` (4 digits) with 0 for
    round-off (below ROUND_OFF of `scale`, per unit or one number); '-' for a missing value."""
    reference = scale if isinstance(scale, (int, float)) else scale.get(units, 0.0)
    unit = Unit(units) if si else scalar_unit(key, units)
    cells = []
    for value in values:
        if value is None:
            cells.append("-")
        elif not si and abs(value) < ROUND_OFF * reference:
            cells.append("0")
        else:
            cells.append(cell(unit(value), ".6g" if si else ".4g", "-"))
    return [key, unit.label, *cells]


def _listed(value: Any) -> str:
    return ",".join(map(str, value)) if isinstance(value, list) else str(value)


# The titles of the tables `tehl run` prints (and `tehl info` for the last two).
SUMMARY_TITLE = ("film, pressure and temperature rise over the inlet per point; err: the bound of the grid and "
                 "iteration error in %, or unresolved where the solve cannot bound it (docs/accuracy.md):")
HEAT_TITLE = ("heat budget: per point; Blok flash dT is the rise by Blok's (1937) formula, surface dT the solved "
              "largest surface rise:")
CYCLE_TITLE = ("meshing cycle: along the path; load share of the pair; theta_B,i solved = bulk + the solved surface "
               "rise of flank i, Blok flash dT = Blok's (1937) rise with the film's mu (theta_B by Blok = bulk + it):")

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
                    ("err p_max %", "error_estimate_p_max", "p_max"),
                    ("err dT_max %", "error_estimate_dT_max", "dT_max"),
                    ("err dT_min %", "error_estimate_dT_min", "dT_min"), ("err mu %", "error_estimate_mu", "mu"))

# Heat-budget columns, keys of the /heat table.
_HEAT = (
    Column("mu", "mu", spec=".4f"),
    Column("mu Xu", "mu_xu", spec=".4f"),
    Column("P", "friction_power", "W", ".1f"),
    Column("gamma_1", "partition_1", spec=".3f"),
    Column("P_ss,1", "steady_power_1", "W", ".3g"),
    Column("P_ss,2", "steady_power_2", "W", ".3g"),
    Column("Blok flash dT", "flash_temperature", "K", ".1f"),
    Column("surface dT", "surface_rise_max", "K", ".1f"),
    Column("Q_f", "frictional_heat", "J", ".3g"),
    Column("Q_oil", "oil_film_heat", "J", ".3g"),
    Column("Q_oil/Q_f", "oil_to_friction_ratio", spec=".2f", unit=PERCENT),
)


def heat_budget_table(result: Result) -> str:
    """One row per point of the /heat table: friction, heat power and its partition, steady-state power per
    gear, flash temperature, frictional and oil-film heat; '-' where a column is missing, 0 for a value below
    ROUND_OFF of its column's largest."""
    heat = result.heat
    columns = {c.key: np.where(np.abs(heat[c.key].values) < ROUND_OFF * np.max(np.abs(heat[c.key].values)), 0.0,
                               heat[c.key].values) for c in _HEAT if c.key in heat}  # round-off shown as 0
    rows = [[str(name), *(c.text(columns[c.key][i] if c.key in columns else None) for c in _HEAT)]
            for i, name in enumerate(heat["point"].values)]
    return format_table(["point", *(c.header for c in _HEAT)], rows)


# Meshing-cycle columns, keys of the /cycle group.
_CYCLE = (
    Column("s", "s", "m", ".2f", MILLIMETRE),
    Column("load share", "load_share", spec=".3f"),
    Column("p_h", "p_h", "Pa", ".1f"),
    Column("h_min", "h_min", "m"),
    Column("lambda", "film_parameter", spec=".2f"),
    Column("dT_max", "dT_max", "K", ".1f"),
    Column("Blok flash dT", "flash_temperature", "K", ".1f"),
    Column("theta_B,1 solved", "contact_temperature_1", "K", ".1f", CELSIUS),
    Column("theta_B,2 solved", "contact_temperature_2", "K", ".1f", CELSIUS),
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
        return f"mesh cycle: {count} point{'s' if count != 1 else ''}; no mesh power loss (see the warnings)"
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
    """The error bound of a quantity in % (ehl/error_bounds.py), "unresolved" where the solve cannot bound it; in
    a file without bounds its error estimate, given in metres (absolute) or as a fraction (relative)."""
    bound = error_bound(point.scalars, of)
    if isinstance(bound, str):
        return bound
    if bound is not None:
        return cell(PERCENT(bound), ".2f", "-")
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
    if {"x", "y"} <= solution.axes.keys():
        details.append(f"solved on {len(solution.axes['x'].values)}x{len(solution.axes['y'].values)}")
    suffix = f" ({', '.join(details)})" if details else ""
    click.echo(f"[{done}/{total}] {solution.name}: {state}{suffix}", err=True)


def _point_names(option: str | None) -> list[str] | None:
    """The names of a --points option as given (a name given twice is refused where points are solved, as in YAML)."""
    if option is None:
        return None
    return [name.strip() for name in option.split(",") if name.strip()]


def _output_path(case_file: Path, case: Case, option: str | None, force: bool) -> Path:
    """-o, else output.file of the case (inside the case file's folder), else <case name>.h5 here; checked
    before solving by the output-path policy (output_path.py): never the case file, never a file tehl did not
    write unless `force`."""
    if option is not None:
        key, target = "--output", Path(option)
    elif case.output.file is not None:
        key, target = "output.file", inside_case_folder("output.file", case_file, case.output.file)
    else:
        key, target = "name", Path(f"{case.name}.h5")
    return checked_output(key, target, inputs=[case_file], force=force)


def _check_figure_folder(folder: Path, source: Path) -> None:
    """`tehl plot -o`: a folder (existing or new) under a writable directory, not an existing file (the file
    plotted among them)."""
    if folder.exists() and not folder.is_dir():
        what = "the file plotted" if folder.resolve() == source.resolve() else "an existing file"
        raise CaseError("--output", str(folder), f"a folder for the figures, not {what}")
    writable_location("--output", folder / "figure")


def _terminate(signum: int, frame: object) -> None:
    """SIGTERM ends the run like Ctrl-C does: cleanups run and no partial result file is left."""
    raise SystemExit(128 + signum)


def main(argv: Sequence[str] | None = None) -> None:
    """Console entry point `tehl`. The process ends with it: every object it made is frozen out of the garbage
    collector (`gc.freeze`) first, as the interpreter's exit otherwise traverses them all in a full collection for each
    module it tears down (those of Numba, SciPy and h5py)."""
    signal.signal(signal.SIGTERM, _terminate)
    try:
        tehl.main(args=argv, prog_name="tehl")
    finally:
        gc.freeze()

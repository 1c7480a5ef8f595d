"""`tehl report`: one self-contained HTML page of a result file, to hand on or print to PDF.

The page holds the provenance (tehl version, case, file, dates), the inputs in engineering units (the case text
stored in the file, lengths in mm), the verdict, the scalars of every point each with the solver's error estimate,
the key figures (contact path, the meshing cycle, the overview of the maps, the centre line of the point with the
thinnest film) embedded as base64 PNG, and the solve summary of each point from its solve record (plan, stages,
retries). Nothing is solved again; no script, no external resource.
"""

from __future__ import annotations

import base64
from collections.abc import Iterable, Mapping, Sequence
from datetime import datetime, timezone
import html
import math
from pathlib import Path
import tempfile
from typing import Any

import numpy as np
import yaml

from facegear_tehl import __version__
from facegear_tehl.compare import absolute_estimate
from facegear_tehl.key_units import key_unit
from facegear_tehl.plots import plot_result
from facegear_tehl.record import SolveRecord
from facegear_tehl.results import PointResult, Result
from facegear_tehl.tables import UNRESOLVED_WORD, error_bound, scalar_unit
from facegear_tehl.units import MILLIMETRE
from facegear_tehl.verdict import verdict_text

# The per-point scalars of the results table, each with the key of its relative error estimate (None: no estimate).
SCALARS = (("h_c", "error_estimate_h_c"), ("h_min", "error_estimate_h_min"), ("film_parameter", "error_estimate_h_min"),
           ("p_max", "error_estimate_p_max"), ("p_hertz", None), ("dT_max", "error_estimate_dT_max"),
           ("dT_min", "error_estimate_dT_min"), ("mu", "error_estimate_mu"), ("load_error", None))
FIGURE_DPI = 90  # enough to read on screen and in print, a page of a few MB at most
OVERVIEW_ROWS = 6  # points on the overview sheet at most (evenly spread along the path): a 41-point cycle's sheet
# would be a 4 MB image 70 inches tall
STYLE = """
body { font-family: sans-serif; max-width: 60em; margin: 1em auto; padding: 0 1em; color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; border-bottom: 1px solid #aaa; margin-top: 1.5em; }
table { border-collapse: collapse; margin: 0.5em 0; font-size: 0.85em; }
th, td { border: 1px solid #ccc; padding: 0.15em 0.5em; text-align: left; vertical-align: top; }
td.n { text-align: right; font-variant-numeric: tabular-nums; }
figure { margin: 1em 0; page-break-inside: avoid; } figure img { max-width: 100%; height: auto; }
figcaption { font-size: 0.85em; color: #444; } .note { font-size: 0.85em; color: #444; }
@media print { body { max-width: none; } h2 { page-break-after: avoid; } }
"""


def report_page(result: Result) -> str:
    """The HTML page of `result` (read with its fields for the figures)."""
    sections = [
        ("Provenance", _provenance(result)),
        ("Inputs", _inputs(result.case_yaml)),
        ("Verdict", _verdict(result)),
        ("Results per meshing point", _results(result.points.values())),
        ("Figures", _figures(result)),
        ("Solve summary", _solve_summary(result.points.values())),
    ]
    body = "".join(f"<h2>{html.escape(title)}</h2>\n{content}\n" for title, content in sections)
    title = html.escape(f"{result.case_name}: TEHL report")
    return (f"<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{title}</title>\n"
            f"<style>{STYLE}</style>\n</head>\n<body>\n<h1>{title}</h1>\n{body}</body>\n</html>\n")


def write_report(result: Result, path: Path) -> Path:
    """Write the page of `result` to `path` (whole or not at all)."""
    partial = path.with_name(path.name + ".partial")
    partial.write_text(report_page(result), encoding="utf-8")
    partial.replace(path)
    return path


def _table(headers: Sequence[str], rows: Iterable[Sequence[str]], numeric_from: int = 1) -> str:
    """An HTML table; cells from column `numeric_from` on are right-aligned numbers."""
    head = "".join(f"<th>{html.escape(h)}</th>" for h in headers)
    lines = ["".join(f"<td class=\"n\">{html.escape(c)}</td>" if i >= numeric_from else f"<td>{html.escape(c)}</td>"
                     for i, c in enumerate(row)) for row in rows]
    return f"<table><tr>{head}</tr>\n" + "\n".join(f"<tr>{line}</tr>" for line in lines) + "</table>"


def _provenance(result: Result) -> str:
    now = datetime.now(timezone.utc).replace(microsecond=0).isoformat()
    rows = [("case", result.case_name), ("result file", str(result.path)), ("status", result.status),
            ("solved", f"{result.created} with tehl {result.tehl_version} (file format {result.format_version})"),
            ("report", f"{now} with tehl {__version__}"),
            ("models", ", ".join(f"{k} {v}" for k, v in result.models.items()))]
    rows += [("override", f"{k} {v}") for k, v in result.overrides.items()]
    rows += [("warning", w) for w in result.warnings]
    return _table(["", ""], rows, numeric_from=2)


def _inputs(case_yaml: str) -> str:
    """The case's keys and values, lengths in mm, each with its unit (from the case templates)."""
    case = yaml.safe_load(case_yaml) or {}
    rows = [(key, *_engineering(key, value)) for key, value in _flatten(case)]
    return _table(["case key", "value", "unit"], rows, numeric_from=3)


def _flatten(mapping: Mapping[str, Any], prefix: str = "") -> list[tuple[str, Any]]:
    items = []
    for key, value in mapping.items():
        dotted = f"{prefix}{key}"
        items += _flatten(value, dotted + ".") if isinstance(value, Mapping) else [(dotted, value)]
    return items


def _engineering(key: str, value: Any) -> tuple[str, str]:
    """(value, unit) of a case key: lengths in mm, the rest in the unit the case is written in."""
    unit = key_unit(key) or ""
    if unit == "m" and isinstance(value, (int, float)) and not isinstance(value, bool):
        return f"{MILLIMETRE(value):.6g}", MILLIMETRE.label
    if isinstance(value, list):
        return ", ".join(map(str, value)), unit
    return str(value), unit


def _verdict(result: Result) -> str:
    """The verdict as a table of (item, assessment), or why there is none."""
    text = verdict_text(result)
    if not text:
        return "<p class=\"note\">The file has no /verdict group (a plain contact, or a file before the verdict).</p>"
    rows = []
    for line in text.splitlines()[1:]:
        item, _, text = line.strip().partition("  ")
        rows.append((item, text.strip()))
    return _table(["item", "assessment"], rows, numeric_from=2)


def _results(points: Iterable[PointResult]) -> str:
    """Every point's scalars in engineering units, each with its error estimate (± absolute, in the same unit)."""
    points = list(points)
    keys = [(key, estimate) for key, estimate in SCALARS if any(key in p.scalars for p in points)]
    headers = ["point", "converged", "grid solved on"]
    for key, _ in keys:
        units = next(p.units[key] for p in points if key in p.scalars)
        label = scalar_unit(key, units).label
        headers.append(key if label in ("-", "") else f"{key} ({label})")
    rows = [[p.name, "yes" if p.converged else "no", _grid(p),
             *(_value_with_error(p, key, estimate) for key, estimate in keys)] for p in points]
    note = ("<p class=\"note\">± is the solver's bound of the grid and iteration error (docs/accuracy.md, error "
            "bounds); \"unresolved\": the solve cannot bound it (a feature narrower than the grid, an estimate outside "
            "the asymptotic range, the pressure spike); a value without either has no estimate.</p>")
    return _table(headers, rows, numeric_from=3) + note


def _grid(point: PointResult) -> str:
    return "x".join(str(len(point.axes[k].values)) for k in ("x", "y") if k in point.axes) or "-"


def _value_with_error(point: PointResult, key: str, estimate: str | None) -> str:
    """'1.205 ± 0.001' in the scalar's display unit; '-' for a missing value."""
    if key not in point.scalars:
        return "-"
    unit = scalar_unit(key, point.units[key])
    value = unit(point.scalars[key])
    if estimate is not None and error_bound(point.scalars, estimate.removeprefix("error_estimate_")) == UNRESOLVED_WORD:
        return f"{value:.4g} ({UNRESOLVED_WORD})"
    error = absolute_estimate(point, key, estimate)
    if math.isnan(error):
        return f"{value:.4g}"
    return f"{value:.4g} ± {abs(unit(error) - unit(0.0)):.2g}"


def _figures(result: Result) -> str:
    """The key figures drawn by `tehl plot` into a temporary folder, embedded as base64 PNG with a caption: the
    contact path, the cycle, the trends, the overview of the maps and the centre line of the thinnest film."""
    solved = [p for p in result.points.values() if "h_min" in p.scalars and p.fields]
    thinnest = min(solved, key=lambda p: p.scalars["h_min"]).name if solved else ""
    rows = overview_rows([p.name for p in solved])
    wanted = [("contact_path", "Where the contact lies on both teeth along the path."),
              ("cycle", "Film, temperatures and friction along the meshing cycle (docs/figures.md)."),
              ("trends", "p_max, h_c, h_min and the temperature rise over the points, with their error estimates."),
              ("overview", "Pressure, film and mid-film temperature rise of " + (
                  "every point." if len(rows) == len(solved) else f"{', '.join(rows)} of the {len(solved)} points.")),
              (f"{thinnest}_centreline", f"The centre line of {thinnest}, the point of the thinnest film.")]
    with tempfile.TemporaryDirectory() as folder:
        written = list(plot_result(result, folder, what=("contact", "cycle", "trends"), dpi=FIGURE_DPI).written)
        if solved:
            written += plot_result(result, folder, what=("overview",), points=rows, dpi=FIGURE_DPI).written
            written += plot_result(result, folder, what=("centreline",), points=[thinnest], dpi=FIGURE_DPI).written
        files = {path.stem: path for path in written}
        blocks = [_figure(files[stem], caption) for stem, caption in wanted if stem in files]
    return "\n".join(blocks) or "<p class=\"note\">No figure: the file holds no fields, path or cycle.</p>"


def overview_rows(names: Sequence[str]) -> list[str]:
    """At most OVERVIEW_ROWS of `names` (in path order), evenly spread, the first and the last among them."""
    if len(names) <= OVERVIEW_ROWS:
        return list(names)
    return [names[i] for i in sorted({round(k) for k in np.linspace(0, len(names) - 1, OVERVIEW_ROWS)})]


def _figure(path: Path, caption: str) -> str:
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return (f"<figure><img src=\"data:image/png;base64,{data}\" alt=\"{html.escape(path.stem)}\">"
            f"<figcaption>{html.escape(caption)}</figcaption></figure>")


def _solve_summary(points: Iterable[PointResult]) -> str:
    """Per point: the planned stages, the stages that ran (grid, V-cycles, outer iterations, outcome, time), the
    retries; a point without a record (a file before format 1.3) is named as such."""
    parts = []
    for point in points:
        record: SolveRecord | None = point.record
        if record is None:
            parts.append(f"<h3>{html.escape(point.name)}</h3><p class=\"note\">no solve record in the file</p>")
            continue
        plan = "".join(f"<li>{html.escape(step)}</li>" for step in record.plan)
        stages = _table(["stage", "grid", "V-cycles", "outer iterations", "outcome", "wall time (s)"],
                        [(s.stage.value, f"{s.nx}x{s.ny}", str(s.cycles), str(s.outer), s.outcome.value,
                          f"{s.seconds:.2f}") for s in record.stages], numeric_from=2)
        retries = "".join(f"<li>{html.escape(r.reason.value)} (attempt {r.attempt}): {html.escape(r.action.value)}"
                          f"{': ' + html.escape(r.detail) if r.detail else ''}</li>" for r in record.retries)
        parts.append(f"<h3>{html.escape(point.name)}</h3><p>Plan:</p><ol>{plan}</ol>{stages}"
                     f"<p>Retries: {'none' if not retries else ''}</p>" + (f"<ul>{retries}</ul>" if retries else ""))
    return "\n".join(parts)

"""Operating maps of a study (`tehl plot DIR --what maps`): a scalar of DIR/index.csv over two varied keys, as a
heat map with its value written in each cell and contour lines where both keys are numbers.

One figure per point of the base case and one for the worst point of each variant (the smallest film, λ or
efficiency; the largest pressure, temperature rise, friction or power loss), and, when the study varies more
than the two keys drawn, one of each per combination of the other keys' values. A variant that failed, or a
point without the scalar, leaves its cell blank (marked –); a point that did not converge is marked '*'.
"""

from __future__ import annotations

from collections.abc import Sequence
import csv
from dataclasses import dataclass
import io
import itertools
import math
from pathlib import Path
import re

import numpy as np

from facegear_tehl.plots import FORMATS
from facegear_tehl.plots.common import Output, PlotReport, figure, plain
from facegear_tehl.results import ResultFileError
from facegear_tehl.schema import CaseError
from facegear_tehl.study_file import HASH_DIGITS
from facegear_tehl.study_index import COLUMNS, INDEX
from facegear_tehl.units import display

WORST = "worst"
SMALLER_IS_WORSE = ("h_c", "h_min", "film_parameter", "mesh_efficiency")  # the others: larger is worse
MAX_ANNOTATED_CELLS = 400  # above this many cells the numbers would overlap: colours only
LABELS = {"film_parameter": "λ", "dT_max": "ΔT_max", "mu": "μ", "mesh_efficiency": "efficiency"}


@dataclass(frozen=True)
class StudyIndex:
    """DIR/index.csv as read back: the varied keys in the study's order, the rows (column -> text) and the
    units of the scalar columns."""

    keys: tuple[str, ...]
    rows: tuple[dict[str, str], ...]
    units: dict[str, str]


@dataclass(frozen=True)
class MapGrid:
    """One map: z over the values of `x` (columns) and `y` (rows; None: one row), SI units; NaN where there is no
    value; `not_converged` where the value comes from a point that did not converge; `fixed`: the values of the
    other varied keys; `point`: a point name or WORST."""

    z: str
    units: str
    x: str
    y: str | None
    x_values: tuple[str, ...]
    y_values: tuple[str, ...]
    values: np.ndarray  # (len(y_values), len(x_values))
    not_converged: np.ndarray
    point: str
    fixed: tuple[tuple[str, str], ...]


def read_index(folder: Path) -> StudyIndex:
    """The index of the study folder `folder`; ResultFileError if it has none or it is not a study index."""
    path = folder / INDEX
    try:
        text = path.read_text(encoding="utf-8")
        table = list(csv.reader(io.StringIO(text, newline="")))
    except OSError as exc:
        raise ResultFileError(f"{folder}: not a study folder ({INDEX}: {exc.strerror})") from None
    except (UnicodeDecodeError, csv.Error) as exc:
        raise ResultFileError(f"{path}: not a readable study index ({exc}); run tehl study again to rewrite it") \
            from None
    header = table[0] if table else []
    if header[:1] != ["variant"] or "point" not in header:
        raise ResultFileError(f"{path}: not a study index (no variant and point columns)")
    if not text.endswith("\n"):  # write_index ends every row, the last one included, with a newline
        raise ResultFileError(f"{path}: its last line is cut short (a truncated index); run tehl study again to "
                              "rewrite it")
    _check_rows(path, header, table[1:])
    keys = tuple(header[1:header.index("point")])
    units = {}
    for column in header:
        match = re.fullmatch(r"(\w+) \[(.*)\]", column)
        if match:
            units[match.group(1)] = match.group(2)
    names = [re.sub(r" \[.*\]$", "", column) for column in header]
    return StudyIndex(keys, tuple(dict(zip(names, row)) for row in table[1:]), units)


def _check_rows(path: Path, header: list[str], rows: list[list[str]]) -> None:
    """ResultFileError naming the line of the first row of `rows` that has not a cell per column (a truncated or
    edited index) or holds a scalar of COLUMNS that is neither empty nor a finite number."""
    numeric = [i for i, column in enumerate(header) if re.sub(r" \[.*\]$", "", column) in COLUMNS]
    for line, row in enumerate(rows, start=2):
        if len(row) != len(header):
            raise ResultFileError(f"{path}: line {line} has {len(row)} cells, the header {len(header)} (a truncated "
                                  "or damaged index); run tehl study again to rewrite it")
        for i in numeric:
            if row[i] and not _finite(row[i]):
                raise ResultFileError(f"{path}: line {line}, column {header[i]}: {row[i]!r} is not a number; run "
                                      "tehl study again to rewrite the index")


def _unlisted_files(folder: Path, index: StudyIndex) -> int:
    """Variant result files in `folder` (named by HASH_DIGITS hex digits) that no row of `index` names."""
    listed = {row.get("file") for row in index.rows}
    return sum(bool(re.fullmatch(f"[0-9a-f]{{{HASH_DIGITS}}}\\.h5", path.name)) and path.name not in listed
               for path in folder.iterdir())


def _finite(text: str) -> bool:
    try:
        return math.isfinite(float(text))
    except ValueError:
        return False


def map_grids(index: StudyIndex, z: str = "h_min", x: str | None = None, y: str | None = None,
              points: Sequence[str] | None = None) -> list[MapGrid]:
    """The maps of `z` over `x` and `y` (default: the first two varied keys; no `y` when the study varies one key:
    a single row) for each point of `points` (default
    every point, then WORST), one set per combination of the other varied keys. CaseError naming the option
    for an unknown scalar, key or point."""
    if z not in COLUMNS:
        raise CaseError("--z", z, "a scalar of the study index among: " + ", ".join(COLUMNS))
    if not index.keys:
        raise ResultFileError("the study index has no varied keys (columns between variant and point)")
    x = x if x is not None else next((key for key in index.keys if key != y), index.keys[0])
    y = y if y is not None else next((key for key in index.keys if key != x), None)
    for option, key in (("--x", x), ("--y", y)):
        if key is not None and key not in index.keys:
            raise CaseError(option, key, "a key the study varies: " + ", ".join(index.keys))
    if x == y:
        raise CaseError("--y", y, f"another varied key than --x ({x})")
    known = list(dict.fromkeys(row["point"] for row in index.rows if row["point"]))
    for name in points or ():
        if name not in known + [WORST]:
            raise CaseError("--point", name, "point names of the study among: " + ", ".join(known + [WORST]))
    chosen = list(points) if points else known + [WORST]
    others = [key for key in index.keys if key not in (x, y)]
    x_values, y_values = _values(index, x), (_values(index, y) if y is not None else ("",))
    grids = []
    for fixed in itertools.product(*(_values(index, key) for key in others)):
        pinned = tuple(zip(others, fixed))
        rows = [row for row in index.rows if all(row[key] == value for key, value in pinned)]
        for point in chosen:
            values = np.full((len(y_values), len(x_values)), math.nan)
            flagged = np.zeros(values.shape, dtype=bool)
            for (i, y_value), (j, x_value) in itertools.product(enumerate(y_values), enumerate(x_values)):
                cell = [row for row in rows if row[x] == x_value and (y is None or row[y] == y_value)]
                values[i, j], flagged[i, j] = _cell(cell, z, point)
            grids.append(MapGrid(z, index.units.get(z, "1"), x, y, x_values, y_values, values, flagged, point, pinned))
    return grids


def _values(index: StudyIndex, key: str) -> tuple[str, ...]:
    """The values of a varied key in the study's order (the order of their first row)."""
    return tuple(dict.fromkeys(row[key] for row in index.rows))


def _cell(rows: Sequence[dict[str, str]], z: str, point: str) -> tuple[float, bool]:
    """The value of one cell (NaN: none) and whether it comes from a point that did not converge: the point's,
    or for WORST the worst over the variant's points that have the scalar."""
    found = [(float(row[z]), row["converged"] != "yes") for row in rows
             if row.get(z) and (point == WORST and row["point"] or row["point"] == point)]
    if not found:
        return math.nan, False
    pick = min if z in SMALLER_IS_WORSE else max
    return pick(found, key=lambda item: item[0])


def plot_study(folder: Path, out_folder: Path, *, what: str = "maps", z: str = "h_min", x: str | None = None,
               y: str | None = None, points: Sequence[str] | None = None, fmt: str = "png",
               dpi: int = 150) -> PlotReport:
    """Draw the maps of the study folder `folder` into `out_folder` (see `map_grids`); CaseError for a figure type
    other than maps (or default, all: the same), an unknown format or a non-positive dpi."""
    for name in (part.strip() for part in what.split(",")):
        if name not in ("maps", "default", "all"):
            raise CaseError("--what", name, "maps (the figure type of a study folder)")
    if fmt not in FORMATS:
        raise CaseError("--format", fmt, "one of " + ", ".join(FORMATS))
    if dpi <= 0:
        raise CaseError("--dpi", dpi, "a positive number of dots per inch")
    index = read_index(folder)
    grids = map_grids(index, z, x, y, points)
    out = Output(out_folder, fmt, dpi, PlotReport())
    unlisted = _unlisted_files(folder, index)
    if unlisted:
        out.report.skipped.append(f"warning: {folder / INDEX} does not name {unlisted} result file(s) of the folder "
                                  "(an index cut short, or files of an earlier study): run tehl study again to "
                                  "rewrite it")
    for grid in grids:
        if np.isnan(grid.values).all():
            out.skip(f"map {_stem(grid)}", f"no {grid.z} in the index for these variants")
            continue
        draw_map(grid, out)
    return out.report


def draw_map(grid: MapGrid, out: Output) -> None:
    """One heat map: the cells coloured by value (display units), each value written in its cell, contour lines
    where both keys are numbers."""
    unit = display(grid.units)
    values = unit(grid.values)
    xs, x_numeric = _coordinates(grid.x_values)
    ys, y_numeric = _coordinates(grid.y_values) if grid.y is not None else (np.zeros(1), False)
    fig = figure(width=max(6.0, 1.0 + 0.8 * len(xs)), height=max(4.0, 1.5 + 0.5 * len(ys)))
    ax = fig.subplots()
    mesh = ax.pcolormesh(_edges(xs), _edges(ys), np.ma.masked_invalid(values), cmap="viridis", shading="flat")
    label = LABELS.get(grid.z, grid.z)
    fig.colorbar(mesh, ax=ax, label=f"{label} ({unit.label})" if unit.label != "-" else label)
    if x_numeric and y_numeric and min(values.shape) >= 2 and np.isfinite(values).all():
        lines = ax.contour(xs, ys, values, colors="white", linewidths=0.8)
        ax.clabel(lines, fontsize="x-small", fmt="%.3g")
    if values.size <= MAX_ANNOTATED_CELLS:
        for (i, j), value in np.ndenumerate(values):
            text = "–" if math.isnan(value) else f"{value:.3g}" + ("*" if grid.not_converged[i, j] else "")
            ax.text(xs[j], ys[i], text, ha="center", va="center", fontsize="x-small", color="black",
                    bbox={"facecolor": "white", "alpha": 0.6, "linewidth": 0, "pad": 1})
    ax.set_xticks(xs, [plain(v) for v in grid.x_values] if not x_numeric else None)
    ax.set_xlabel(plain(grid.x))
    if grid.y is None:
        ax.set_yticks([])
    else:
        ax.set_yticks(ys, [plain(v) for v in grid.y_values] if not y_numeric else None)
        ax.set_ylabel(plain(grid.y))
    where = "worst point" if grid.point == WORST else f"point {plain(grid.point)}"
    pinned = plain("".join(f", {key} = {value}" for key, value in grid.fixed))
    flagged = "; * not converged" if grid.not_converged.any() else ""
    ax.set_title(f"{label}, {where}{pinned}{flagged}", fontsize="medium")
    out.save(fig, _stem(grid))


def _stem(grid: MapGrid) -> str:
    """map_<z>_<point>[_<key>=<value>...], with characters other than letters, digits, '.', '=', '-' as '_'."""
    name = "_".join(["map", grid.z, grid.point, *(f"{key}={value}" for key, value in grid.fixed)])
    return re.sub(r"[^\w.=-]", "_", name)


def _coordinates(values: Sequence[str]) -> tuple[np.ndarray, bool]:
    """The values as numbers when they all are (and increase or decrease), else their positions 0, 1, ..."""
    try:
        numbers = np.array([float(v) for v in values])
    except ValueError:
        return np.arange(len(values), dtype=float), False
    steps = np.diff(numbers)
    if len(numbers) > 1 and np.isfinite(numbers).all() and ((steps > 0).all() or (steps < 0).all()):
        return numbers, True
    return np.arange(len(values), dtype=float), False


def _edges(centres: np.ndarray) -> np.ndarray:
    """Cell edges around `centres`: the midpoints between them, the end cells as wide as their neighbours (half a
    unit each side of a single centre)."""
    if len(centres) == 1:
        return np.array([centres[0] - 0.5, centres[0] + 0.5])
    middle = 0.5 * (centres[1:] + centres[:-1])
    return np.concatenate([[2 * centres[0] - middle[0]], middle, [2 * centres[-1] - middle[-1]]])

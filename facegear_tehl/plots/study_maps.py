"""Operating maps of a study (`tehl plot DIR --what maps`): a scalar of DIR/index.csv over two varied keys, its
value written at each variant. A filled map with contour lines only where it can be read as one: both keys numbers
with at least MIN_CONTOUR_VALUES values each, every variant solved on one grid and resolved; otherwise a marker per
variant (its shape the grid solved on, open where the variant is under-resolved). Axes name the key with its unit.

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

from matplotlib.axes import Axes
from matplotlib.cm import ScalarMappable
from matplotlib.colors import Normalize
import numpy as np

from facegear_tehl.key_units import key_label
from facegear_tehl.plots import FORMATS
from facegear_tehl.plots.common import Output, PlotReport, figure, plain
from facegear_tehl.results import ResultFileError
from facegear_tehl.schema import CaseError
from facegear_tehl.study_index import COLUMNS, GRID, INDEX, UNRESOLVED_CELL
from facegear_tehl.units import display

WORST = "worst"
SMALLER_IS_WORSE = ("h_c", "h_min", "film_parameter", "mesh_efficiency")  # the others: larger is worse
MAX_ANNOTATED_CELLS = 400  # above this many cells the numbers would overlap: colours only
LABELS = {"film_parameter": "λ", "dT_max": "ΔT_max", "mu": "μ", "mesh_efficiency": "efficiency"}
MIN_CONTOUR_VALUES = 4  # per key: contour lines through fewer values per axis are the interpolation, not the film
UNRESOLVED_ESTIMATE = 0.05  # relative error bound above which a value is marked under-resolved: 20-100 times the
# estimates of the shipped case (0.05-0.3 %), and as large as the trends a map is read for
GRID_MARKERS = ("o", "s", "^", "D", "v", "P")  # one marker shape per grid solved on


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
    grids: np.ndarray | None = None  # the grid each value was solved on ('' unknown), as values
    unresolved: np.ndarray | None = None  # the value's error estimate is above UNRESOLVED_ESTIMATE

    @property
    def grid_names(self) -> tuple[str, ...]:
        """The grids the values were solved on, most common first ('' where the index does not say)."""
        if self.grids is None:
            return ()
        named = [g for g, v in zip(self.grids.ravel(), self.values.ravel()) if g and not math.isnan(v)]
        return tuple(sorted(set(named), key=lambda g: -named.count(g)))

    @property
    def contourable(self) -> bool:
        """A filled map with contours reads right: enough numeric values per key, every value there, one grid, none
        under-resolved."""
        rows, columns = self.values.shape
        return (self.y is not None and min(rows, columns) >= MIN_CONTOUR_VALUES and np.isfinite(self.values).all()
                and len(self.grid_names) <= 1 and not (self.unresolved is not None and self.unresolved.any())
                and _coordinates(self.x_values)[1] and _coordinates(self.y_values)[1])


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
    """Result files in `folder` (a study writes nothing else there with the suffix .h5) that no row of `index`
    names."""
    listed = {row.get("file") for row in index.rows}
    return sum(path.suffix == ".h5" and path.name not in listed for path in folder.iterdir())


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
            shape = (len(y_values), len(x_values))
            values, flagged, solved = np.full(shape, math.nan), np.zeros(shape, dtype=bool), np.full(shape, "", object)
            unresolved = np.zeros(shape, dtype=bool)
            for (i, y_value), (j, x_value) in itertools.product(enumerate(y_values), enumerate(x_values)):
                cell = [row for row in rows if row[x] == x_value and (y is None or row[y] == y_value)]
                values[i, j], flagged[i, j], solved[i, j], unresolved[i, j] = _cell(cell, z, point)
            grids.append(MapGrid(z, index.units.get(z, "1"), x, y, x_values, y_values, values, flagged, point, pinned,
                                 solved, unresolved))
    return grids


def _values(index: StudyIndex, key: str) -> tuple[str, ...]:
    """The values of a varied key in the study's order (the order of their first row)."""
    return tuple(dict.fromkeys(row[key] for row in index.rows))


def _cell(rows: Sequence[dict[str, str]], z: str, point: str) -> tuple[float, bool, str, bool]:
    """The value of one cell (NaN: none), whether it comes from a point that did not converge, the grid it was
    solved on and whether its error estimate (if the index has one) is above UNRESOLVED_ESTIMATE: the point's, or
    for WORST the worst over the variant's points that have the scalar."""
    found = [(float(row[z]), row["converged"] != "yes", row.get(GRID, ""), _under_resolved(row, z)) for row in rows
             if row.get(z) and (point == WORST and row["point"] or row["point"] == point)]
    if not found:
        return math.nan, False, "", False
    pick = min if z in SMALLER_IS_WORSE else max
    return pick(found, key=lambda item: item[0])


def _under_resolved(row: dict[str, str], z: str) -> bool:
    """The row's error bound of `z` is "unresolved" or above UNRESOLVED_ESTIMATE (in an index written before the
    bounds: its error estimate)."""
    bound = row.get(f"error_bound_{z}")
    if bound:
        return bound == UNRESOLVED_CELL or float(bound) > UNRESOLVED_ESTIMATE
    return abs(float(row.get(f"error_estimate_{z}") or 0.0)) > UNRESOLVED_ESTIMATE


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
    """One map: a filled map with contour lines where `grid.contourable`, else a marker per variant coloured by value
    (shape: the grid solved on; open: under-resolved); each value written at its variant."""
    unit = display(grid.units)
    values = unit(grid.values)
    xs, x_numeric = _coordinates(grid.x_values)
    ys, y_numeric = _coordinates(grid.y_values) if grid.y is not None else (np.zeros(1), False)
    fig = figure(width=max(6.0, 1.0 + 0.8 * len(xs)), height=max(4.0, 1.5 + 0.5 * len(ys)))
    ax = fig.subplots()
    label = LABELS.get(grid.z, grid.z)
    resolved = np.isfinite(values) & ~(grid.unresolved if grid.unresolved is not None else False)
    finite = values[resolved] if resolved.any() else values[np.isfinite(values)]  # the colours: resolved values
    norm = Normalize(float(finite.min()), float(finite.max()))
    if grid.contourable:
        mesh = ax.pcolormesh(_edges(xs), _edges(ys), values, cmap="viridis", norm=norm, shading="flat")
        lines = ax.contour(xs, ys, values, colors="white", linewidths=0.8)
        ax.clabel(lines, fontsize="x-small", fmt="%.3g")
    else:
        mesh = _markers(ax, grid, values, xs, ys, norm)
    fig.colorbar(mesh, ax=ax, label=f"{label} ({unit.label})" if unit.label != "-" else label)
    if values.size <= MAX_ANNOTATED_CELLS:
        offset = (0, 0) if grid.contourable else (0, 13)  # points: above the marker
        for (i, j), value in np.ndenumerate(values):
            text = "–" if math.isnan(value) else f"{value:.3g}" + ("*" if grid.not_converged[i, j] else "")
            ax.annotate(text, (xs[j], ys[i]), xytext=offset, textcoords="offset points", ha="center", va="center",
                        fontsize="x-small", color="black",
                        bbox={"facecolor": "white", "alpha": 0.6, "linewidth": 0, "pad": 1})
    _axes(ax, grid, xs, ys, x_numeric, y_numeric)
    out.save(fig, _stem(grid))


def _markers(ax: Axes, grid: MapGrid, values: np.ndarray, xs: np.ndarray, ys: np.ndarray, norm: Normalize):
    """A marker per variant coloured by value, its shape the grid solved on, open where under-resolved; a legend
    naming the grids (when more than one) and the open markers."""
    names = grid.grid_names or ("",)
    mesh = None
    for k, name in enumerate(names):
        for resolved in (True, False):
            take = np.isfinite(values) & ((grid.grids == name) if grid.grids is not None else True)
            take &= ~grid.unresolved if resolved else grid.unresolved
            i, j = np.nonzero(take)
            if not len(i):
                continue
            style = {"c": values[i, j], "cmap": "viridis", "norm": norm} if resolved else {
                "facecolors": "none", "edgecolors": "black"}
            where = f"solved on {name}" if len(names) > 1 else ""
            unresolved = f"under-resolved: estimate above {UNRESOLVED_ESTIMATE:.0%}"
            text = where if resolved else (where + "; " if where else "") + unresolved
            points = ax.scatter(xs[j], ys[i], s=160, marker=GRID_MARKERS[k % len(GRID_MARKERS)], label=text or None,
                                **style)
            if resolved and mesh is None:
                mesh = points
    if mesh is None:
        mesh = ScalarMappable(norm=norm, cmap="viridis")
    if any(h.get_label() and not h.get_label().startswith("_") for h in ax.collections):
        ax.legend(fontsize="x-small", loc="upper center", bbox_to_anchor=(0.5, -0.18), ncols=2)
    ax.margins(0.25)
    return mesh


def _axes(ax: Axes, grid: MapGrid, xs: np.ndarray, ys: np.ndarray, x_numeric: bool, y_numeric: bool) -> None:
    """Ticks at the variants' values, the keys with their units, the title."""
    ax.set_xticks(xs, [plain(v) for v in grid.x_values] if not x_numeric else None)
    ax.set_xlabel(plain(key_label(grid.x)))
    if grid.y is None:
        ax.set_yticks([])
    else:
        ax.set_yticks(ys, [plain(v) for v in grid.y_values] if not y_numeric else None)
        ax.set_ylabel(plain(key_label(grid.y)))
    label = LABELS.get(grid.z, grid.z)
    where = "worst point" if grid.point == WORST else f"point {plain(grid.point)}"
    pinned = plain("".join(f", {key_label(key)} = {value}" for key, value in grid.fixed))
    flagged = "; * not converged" if grid.not_converged.any() else ""
    ax.set_title(f"{label}, {where}{pinned}{flagged}", fontsize="medium")


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

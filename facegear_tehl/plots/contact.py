"""The face gear contact path (Fig. 2, 4, 6, 8): where the contact lies on the teeth, curvatures, speeds
and load along the path coordinate s, with the meshing points of the file marked."""

from __future__ import annotations

from collections.abc import Sequence

from matplotlib.axes import Axes
from matplotlib.figure import Figure
import numpy as np

from facegear_tehl.plots.common import Output, body_names, figure, legend, title
from facegear_tehl.results import Result
from facegear_tehl.units import MILLIMETRE, Unit, display


def draw_contact(result: Result, out: Output) -> None:
    """The /contact path table (Fig. 2, 4, 6, 8), with the meshing points of the file marked."""
    if not result.contact:
        out.skip("contact", "no /contact path table in the file (plain contact case)")
        return
    table = result.contact
    if "s" not in table:
        out.skip("contact", "the /contact table has no path coordinate s")
        return
    for stem, draw in (("contact_path", _path_figure), ("contact_curvatures", _curvature_figure),
                       ("contact_speeds", _speed_figure), ("contact_load", _load_figure)):
        missing = [c for c in _CONTACT_COLUMNS[stem] if c not in table]
        if missing:
            out.skip(stem, f"/contact lacks {', '.join(missing)}")
        else:
            out.save(draw(result), stem)


_CONTACT_COLUMNS = {
    "contact_path": ("face_gear_radius", "pinion_profile_radius"),
    "contact_curvatures": ("pinion_curvature", "face_gear_curvature_1", "face_gear_curvature_2", "Rx", "Ry"),
    "contact_speeds": ("u1", "u2", "entrainment_speed", "sliding_speed", "srr", "entrainment_angle"),
    "contact_load": ("load", "p_h", "a", "b"),
}


def _path_mm(result: Result) -> np.ndarray:
    """The path coordinate s of the /contact rows, mm."""
    return MILLIMETRE(np.asarray(result.contact["s"].values))


def _column(result: Result, name: str, unit: Unit | None = None) -> np.ndarray:
    """A /contact column, SI or in `unit`."""
    values = np.asarray(result.contact[name].values, dtype=float)
    return values if unit is None else unit(values)


def _mark_points(axes: Sequence[Axes], result: Result) -> None:
    """Vertical lines at the meshing points of the file, named on the top panel."""
    marks = {n: MILLIMETRE(p.scalars["path_coordinate"]) for n, p in result.points.items()
             if "path_coordinate" in p.scalars}
    for ax in axes:
        for s in marks.values():
            ax.axvline(s, color="grey", linewidth=0.7, linestyle=":")
        ax.grid(alpha=0.3)
    top = axes[0]
    for name, s in marks.items():
        top.annotate(name, (s, 1.0), xycoords=("data", "axes fraction"), xytext=(0, 3),
                     textcoords="offset points", ha="center", va="bottom", fontsize="small")


def _path_panels(result: Result, count: int, subject: str) -> tuple[Figure, np.ndarray]:
    """`count` panels above each other sharing the path coordinate axis."""
    fig = figure(height=2.5 * count + 1.0)
    axes = fig.subplots(count, 1, sharex=True, squeeze=False)[:, 0]
    axes[-1].set_xlabel(f"path coordinate s ({MILLIMETRE.label}; − meshing in, + meshing out)")
    fig.suptitle(title(result, subject))
    return fig, axes


def _curve(ax: Axes, s: np.ndarray, values: np.ndarray, y_label: str, heading: str, colour: str) -> None:
    """One quantity along the path; the top panel's title leaves room for the point names above it."""
    ax.plot(s, values, color=colour)
    ax.set_ylabel(y_label)
    ax.set_title(heading, fontsize="medium", pad=14 if ax.get_subplotspec().is_first_row() else None)


def _finish_path(axes: Sequence[Axes], result: Result) -> None:
    """Meshing points marked, legends where there are labels."""
    _mark_points(axes, result)
    for ax in axes:
        legend(ax, fontsize="small")


def _path_figure(result: Result) -> Figure:
    """Where the contact lies on both teeth along the path (Fig. 2)."""
    s = _path_mm(result)
    fig, axes = _path_panels(result, 2, "contact path on the teeth")
    _curve(axes[0], s, _column(result, "face_gear_radius", MILLIMETRE), f"face gear radius ({MILLIMETRE.label})",
           "on the face gear: radius across the face width", "tab:blue")
    _curve(axes[1], s, _column(result, "pinion_profile_radius", MILLIMETRE), f"ρ₁ ({MILLIMETRE.label})",
           "on the pinion: involute profile radius of curvature (root → tip)", "tab:orange")
    _finish_path(axes, result)
    return fig


def _curvature_figure(result: Result) -> Figure:
    """Principal curvatures of both tooth surfaces and the reduced radii (Fig. 4)."""
    s = _path_mm(result)
    fig, axes = _path_panels(result, 3, "curvature along the contact path")
    ax = axes[0]
    ax.plot(s, _column(result, "pinion_curvature"), label="pinion, along the profile")
    ax.plot(s, np.zeros_like(s), "--", label="pinion, along the axis (0)")
    ax.plot(s, _column(result, "face_gear_curvature_1"), label="face gear, principal 1")
    ax.plot(s, _column(result, "face_gear_curvature_2"), label="face gear, principal 2")
    ax.set_ylabel("curvature (1/m)")
    ax.set_title("principal curvatures (convex +)", fontsize="medium", pad=14)
    ax.legend(fontsize="small", ncols=2)
    _curve(axes[1], s, _column(result, "Rx", MILLIMETRE), f"$R_x$ ({MILLIMETRE.label})",
           "reduced radius along the minor axis", "tab:purple")
    _curve(axes[2], s, _column(result, "Ry"), "$R_y$ (m)", "reduced radius along the major axis", "tab:brown")
    _finish_path(axes, result)
    return fig


def _speed_figure(result: Result) -> Figure:
    """Surface, rolling and sliding speeds, slide-to-roll ratio and entrainment angle (Fig. 6)."""
    s = _path_mm(result)
    body_1, body_2 = body_names(result)
    fig, axes = _path_panels(result, 3, "speeds along the contact path")
    ax = axes[0]
    ax.plot(s, np.hypot(*_column(result, "u1").T), label=f"{body_1} surface |u₁|")
    ax.plot(s, np.hypot(*_column(result, "u2").T), label=f"{body_2} surface |u₂|")
    ax.plot(s, _column(result, "entrainment_speed"), linewidth=2, label="rolling (entrainment) $|U_e|$")
    ax.plot(s, _column(result, "sliding_speed"), linewidth=2, label="sliding $|V_s|$")
    ax.set_ylabel("speed (m/s)")
    ax.set_title("speeds relative to the contact point", fontsize="medium", pad=14)
    _curve(axes[1], s, _column(result, "srr"), "SRR (–)", r"slide-to-roll ratio, signed by $V_s \cdot U_e$", "tab:red")
    axes[1].axhline(0.0, color="black", linewidth=0.6)
    _curve(axes[2], s, _column(result, "entrainment_angle"), r"$\psi$ (deg)", "entrainment angle to the minor axis x",
           "tab:green")
    _finish_path(axes, result)
    return fig


def _load_figure(result: Result) -> Figure:
    """Normal load with its share, Hertz pressure and semi-axes (Fig. 8)."""
    s = _path_mm(result)
    fig, axes = _path_panels(result, 3, "load along the contact path")
    _curve(axes[0], s, _column(result, "load"), "normal load (N)", "normal load on the tooth pair", "tab:blue")
    total = result.contact_scalars.get("normal_load")
    if total:
        share = axes[0].secondary_yaxis("right", functions=(lambda f: f / total, lambda k: k * total))
        share.set_ylabel("load share (–)")
    pressure = display("Pa")
    _curve(axes[1], s, _column(result, "p_h", pressure), f"$p_h$ ({pressure.label})", "maximum Hertz pressure",
           "tab:red")
    axes[2].plot(s, _column(result, "a", MILLIMETRE), label="$a$, major semi-axis (left)")
    axes[2].set_ylabel(f"$a$ ({MILLIMETRE.label})")
    right = axes[2].twinx()
    right.plot(s, _column(result, "b", MILLIMETRE), color="tab:orange", label="$b$, minor semi-axis (right)")
    right.set_ylabel(f"$b$ ({MILLIMETRE.label})")
    axes[2].set_title("Hertz semi-axes", fontsize="medium")
    axes[2].legend(handles=[*axes[2].get_lines(), *right.get_lines()], fontsize="small", loc="lower center")
    _mark_points(axes, result)
    return fig

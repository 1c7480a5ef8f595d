"""Plain-text table of a gear contact analysis (what `tehl contact CASE.yaml` prints)."""

from __future__ import annotations

import numpy as np

from facegear_tehl.gears.analysis import GearContactAnalysis

# (header, unit, path key, scale from SI, decimals)
_COLUMNS = (
    ("s", "mm", "s", 1e3, 3),
    ("R_x", "mm", "Rx", 1e3, 3),
    ("R_y", "mm", "Ry", 1e3, 0),
    ("a/b", "-", "ellipticity", 1.0, 1),
    ("a", "mm", "a", 1e3, 3),
    ("b", "mm", "b", 1e3, 4),
    ("p_h", "MPa", "p_h", 1e-6, 0),
    ("|U_e|", "m/s", "entrainment_speed", 1.0, 3),
    ("|V_s|", "m/s", "sliding_speed", 1.0, 3),
    ("SRR", "-", "srr", 1.0, 3),
    ("psi_e", "deg", "entrainment_angle", 1.0, 2),
    ("load", "N", "load", 1.0, 1),
)


def _cell(value: float, digits: int) -> str:
    """Fixed-point text without a negative zero."""
    return f"{round(value, digits) + 0.0:.{digits}f}"


def contact_table(analysis: GearContactAnalysis) -> str:
    """One row per meshing point; SRR is signed (negative before the pitch point), psi_e is the angle of
    the entrainment velocity to the minor axis of the Hertz ellipse."""
    values = analysis.point_values
    header = ["point"] + [name for name, *_ in _COLUMNS]
    units = [""] + [f"[{unit}]" for _, unit, *_ in _COLUMNS]
    rows = [
        [point.name] + [_cell(float(values[key][i]) * scale, digits) for _, _, key, scale, digits in _COLUMNS]
        for i, point in enumerate(analysis.points)
    ]
    table = [header, units] + rows
    widths = [max(len(row[c]) for row in table) for c in range(len(header))]
    lines = ["  ".join(cell.rjust(width) for cell, width in zip(row, widths)) for row in table]
    summary = (
        f"contact ratio {analysis.contact_ratio:.4f}, F_n = {analysis.normal_load:.1f} N, "
        f"path s = {analysis.path_start * 1e3:.3f} .. {analysis.path_end * 1e3:.3f} mm, "
        f"L1 = {analysis.undercut_limit * 1e3:.1f} mm, L2 = {analysis.pointing_limit * 1e3:.1f} mm, "
        f"face-gear radius {np.min(analysis.path['face_gear_radius']) * 1e3:.1f} .. "
        f"{np.max(analysis.path['face_gear_radius']) * 1e3:.1f} mm"
    )
    return "\n".join(lines + [summary] + [f"warning: {text}" for text in analysis.warnings])

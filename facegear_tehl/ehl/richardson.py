"""Richardson's extrapolation of a figure from two grids, the scheme's formal order it assumes by default.

Light on purpose (no kernels): `tehl sweep`'s tables import it with the command line, which `tehl validate` loads.
"""

from __future__ import annotations

ORDER = 2  # formal order of the discretisation, for the Richardson-scaled error estimate


def richardson_error(fine: float, coarse: float, order: int, ratio: int = 2) -> float:
    """Relative discretisation error of `fine` from the same figure on a grid `ratio` times coarser, Richardson-scaled
    for `order`: (f_h - f_rh)/((r^order - 1) f_h) (Richardson 1911)."""
    return (fine - coarse) / (ratio**order - 1) / fine

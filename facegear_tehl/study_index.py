"""The index of a study folder (`tehl study` writes it, `tehl plot --what maps` reads it): its file name and the
scalars of its columns."""

INDEX = "index.csv"
INDEX_HEADER = "variant,"  # how every index.csv begins (study.write_index): what marks one as ours
# Per-point scalars of the index (SI units in its header); a point without one leaves the cell empty.
POINT_COLUMNS = (("h_c", "m"), ("h_min", "m"), ("film_parameter", "1"), ("p_max", "Pa"), ("dT_max", "K"),
                 ("mu", "1"))
# Attributes of a result's /cycle group (the mesh cycle: power loss, efficiency), the same on every point's row.
CYCLE_COLUMNS = (("power_loss", "W"), ("mesh_efficiency", "1"))
# The solver's error bound of a figure (relative; ehl/error_bounds.py), per point: the word "unresolved" where the
# solve cannot bound it, empty in a file without bounds.
ESTIMATE_COLUMNS = tuple((f"error_bound_{name}", "1") for name in ("h_c", "h_min", "p_max", "dT_max", "dT_min", "mu"))
UNRESOLVED_CELL = "unresolved"  # an error-bound cell of a figure the solve cannot bound
GRID = "grid"  # the column of the nodes solved on, 'nx x ny' (the lengthened inlet included)
REFINEMENTS = "refinements"  # the column of the times the solver solved a point again on a finer grid
COLUMNS = tuple(name for name, _ in POINT_COLUMNS + CYCLE_COLUMNS)
"""The scalars of the index, in its order: what `tehl plot --what maps --z` can draw."""

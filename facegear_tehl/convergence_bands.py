"""The bands, beyond the tolerances of the case's `solver:`, by which the solver (ehl/solve.py) accepts an iteration
that has settled on its algebraic floor: written into every result file (results.py) so that the convergence plot
draws them from the file it reads (docs/method.md, the outer loop and its algebraic floor)."""

# The pressure change per cycle settled (stalled) below this multiple of `solver.tolerance` is accepted.
PRESSURE_FLOOR_BAND = 10.0
# The thermal loop's change per outer iteration settled below this fraction of the temperature rise is accepted.
THERMAL_FLOOR_FRACTION = 0.01
# K: tolerances relative to the temperature rise use at least this rise (near-isothermal films).
MIN_RISE = 1.0

BANDS = {"pressure_floor_band": PRESSURE_FLOOR_BAND, "thermal_floor_fraction": THERMAL_FLOOR_FRACTION,
         "min_rise": MIN_RISE}
"""Name -> value (pure numbers; min_rise in K) as the result file's root attribute `convergence_bands` holds them."""

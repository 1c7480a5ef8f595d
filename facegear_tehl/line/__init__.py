"""Independent 1-D EHL line-contact solver (isothermal and thermal), a reference for the long-ellipse limit of
the elliptical solver in `facegear_tehl.ehl` (it shares no code with it: only the lubricant and solid laws).

    from facegear_tehl.line import solve_line
    s = solve_line(radius, load_per_length, entrainment_speed, slide_roll_ratio, lubricant, body_1, body_2)
    s.h_c, s.h_min, s.p_max, s.x, s.p, s.h

See docs/line-contact.md for the equations, the method and the validation.
"""

from facegear_tehl.line.elastic import hertz_line
from facegear_tehl.line.solve import LineSolution, hamrock_groups, solve_line

__all__ = ["LineSolution", "hamrock_groups", "hertz_line", "solve_line"]

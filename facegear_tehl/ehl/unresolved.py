"""Why a reported figure has no error bound: the reason error_bounds.py found first, stored with the figure as
`unresolved_reason_<name>` (its code; none where the figure is bounded) and worded by `tehl info`."""

from __future__ import annotations

from enum import IntEnum


class Why(IntEnum):
    """The reasons error_bounds.bounds leaves a figure unresolved (the codes stored in result files, fixed once given;
    error_bounds.unresolved_figure gives the order it checks them in)."""

    NOT_CONVERGED = 1
    NEVER = 2
    STARVED_INLET = 3
    ENERGY_BALANCE = 4
    NO_ESTIMATE = 5
    OUTSIDE_ASYMPTOTIC_RANGE = 6
    NARROW_FEATURE = 7
    COMPRESSION_HELD = 8
    ITERATION_ERROR = 9
    THREE_GRIDS = 10
    STARVED_SIDES = 11

    @property
    def words(self) -> str:
        """The reason in a line (docs/accuracy.md, error bounds, holds each rule with its evidence)."""
        return _WORDS[self]


_WORDS = {
    Why.NOT_CONVERGED: "the solve did not converge",
    Why.NEVER: "never bounded: the outlet spike grows with every refinement",
    Why.STARVED_INLET: "the truncated inlet starves the film beyond the bounds (inlet_gap_ratio)",
    Why.STARVED_SIDES: "the domain's sides cut the film's spread along the contact line short beyond the bounds "
                       "(side_pressure_ratio)",
    Why.ENERGY_BALANCE: "the film's energy balance misses 1 %: its state does not solve the energy equation",
    Why.NO_ESTIMATE: "no grid estimate along x or y (a figure of zero, a coarsest grid, a failed check, or another "
                     "model's levels)",
    Why.OUTSIDE_ASYMPTOTIC_RANGE: "a grid estimate above 10 %: outside the asymptotic range",
    Why.NARROW_FEATURE: "its feature spans fewer than 3 nodes",
    Why.COMPRESSION_HELD: "the film's compression through the outlet spike sets it (it cools as much as it heats)",
    Why.ITERATION_ERROR: "the iteration left more than 10 % (iteration_error), or a drift no rate bounds",
    Why.THREE_GRIDS: "three grids along x outside the asymptotic range (differences change sign or fall too slowly)",
}

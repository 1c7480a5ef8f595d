"""The relaxation and cycle parameters of the multigrid solver (a leaf: the retry policy chooses among them without
loading the solver's kernels)."""

from __future__ import annotations

from dataclasses import dataclass
import math


@dataclass(frozen=True)
class Relaxation:
    """Parameters of the relaxation and the cycle (defaults: Venner & Lubrecht 2000)."""

    xi_switch: float = 0.3  # eps/h^2 above which a node is relaxed Gauss-Seidel (circular contact; see Level)
    # under-relaxation of Gauss-Seidel changes (Venner & Lubrecht: 0.4; 0.3 keeps ellipses with k > 40 stable)
    under_gs: float = 0.3
    under_jd: float = 0.15  # under-relaxation of Jacobi-distributive changes (Venner & Lubrecht: 0.2)
    pre_sweeps: int = 2
    post_sweeps: int = 1
    coarsest_sweeps: int = 40
    force_factor: float = 0.1  # c_h in H_0 += c_h g on the coarsest grid
    force_updates: int = 4  # H_0 updates per coarsest-grid solve
    force_damping: float = 1.0  # fraction of the secant step taken
    alternate_above: float = 0.25  # add Y-line sweeps when |c_y| > this * |c_x| (entrainment skewed > 14 deg)
    scale_switch: bool = True  # scale xi_switch for long ellipses (see Level); False: Venner's value as is
    # largest change of ln(eta*/eta) per update of the coupled loop's film state (coupled.next_film_state); inf: none
    film_step: float = math.inf

    def describe(self) -> str:
        """The words a solve record names this relaxation by: its switch, "damped" where its Gauss-Seidel changes
        are under-relaxed below the default, and a bounded film_step."""
        switch = "the ellipse-scaled switch" if self.scale_switch else "Venner's switch"
        bounded = ", the film state's step bounded" if math.isfinite(self.film_step) else ""
        return switch + (", damped" if self.under_gs < Relaxation.under_gs else "") + bounded

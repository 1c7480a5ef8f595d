"""Anderson acceleration of a fixed-point iteration (Anderson 1965; in the form of Walker & Ni 2011).

For an iteration x_k+1 = x_k + f_k, with f_k = f(x_k) the (relaxed) step of the plain iteration, Anderson's
method takes the combination of the last m + 1 iterates whose steps cancel best (Walker & Ni 2011, SIAM J.
Numer. Anal. 49:1715-1735, eqs. 1.2-1.3 in their difference form, mixing parameter 1):

    gamma = argmin || W (f_k - dF gamma) ||_2,   x_k+1 = x_k + f_k - (dX + dF) gamma,

with dX, dF the columns x_i+1 - x_i, f_i+1 - f_i of the last m pairs and W a diagonal weight that makes the
components comparable: one scale per block of components (the thermal loop's temperatures and ln(eta*/eta)). For a
linear map Anderson's iterates are those of GMRES on it (Walker & Ni 2011, theorem 2.2). The history restarts when a
step grows (GROWTH). The m x m least-squares problem is solved through its normal equations (m <= 5 here: the vectors
are long, the system tiny), dropping directions whose singular value is below GRAM_CUTOFF of the largest.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

# Relative cutoff of the normal equations' singular values (their squares: 1e-10 drops columns of dF that are
# parallel to the others to 1e-5, where gamma would only amplify noise).
GRAM_CUTOFF = 1e-10
# The history is dropped when the weighted step grew against the last one (the restart safeguard of restarted
# Anderson methods, e.g. Walker & Ni 2011 sec. 5): at 1.0, S3 of the face gear case (a period-2 flicker of a few
# nodes on 257 x 65) converges in 35 outer iterations; without it the accelerated loop locked into the flicker
# and ended unconverged after 40 on the finest grid.
GROWTH = 1.0


class Anderson:
    """The history of an accelerated fixed-point iteration (float arrays of one shape) and its next iterate.

    The inner products of the history's columns are kept block by block and unweighted, each formed once, when its
    column enters: a new scale of a block (the thermal loop's 1/rise moves at every update) weighs them without
    touching the vectors again, and the columns live in buffers allocated once per loop (on the 513 x 65 x 9 layer
    nodes of temperature and ln(eta*/eta) of S1 of the face gear case, 600 210 components, 25.7 -> 11 ms per step
    against weighing the whole history anew at each step)."""

    def __init__(self, depth: int):
        """`depth`: m, the number of earlier pairs (x_i, f_i) combined."""
        self.depth = depth
        self._buffers: tuple[np.ndarray, ...] | None = None  # last x, last f; the ring of columns dX + dF and dF
        self._blocks = 1  # the blocks the inner products are kept by
        self._order: list[int] = []  # ring slots of the history's columns, oldest first
        self._products: dict[tuple[int, int], np.ndarray] = {}  # per block <dF_a, dF_b> of slots a <= b
        self._has_last = False
        self._norm = 0.0

    def reset(self) -> None:
        """Forget the history (the next step is the plain one)."""
        self._has_last, self._order, self._products = False, [], {}

    def step(self, x: np.ndarray, f: np.ndarray, scales: Sequence[float] | float = 1.0) -> np.ndarray:
        """The next iterate from the current one `x` and its plain step `f` (arrays of one shape, taken flat), the least
        squares weighted by `scales`: one scale for all components, or one per block of as many equal consecutive
        blocks; the plain x + f while there is no history."""
        shape, x, f = x.shape, x.reshape(-1), f.reshape(-1)
        squares = np.atleast_1d(np.asarray(scales, dtype=float)) ** 2
        if x.size % squares.size:
            raise ValueError(f"{x.size} components do not split into {squares.size} equal blocks")
        n = x.size // squares.size
        blocks = [slice(k * n, (k + 1) * n) for k in range(squares.size)]
        if self._buffers is None or self._buffers[0].size != x.size or squares.size != self._blocks:
            self._buffers = tuple(np.empty((self.depth + 1 if k > 1 else 1, x.size)) for k in range(4))
            self._blocks = squares.size
            self.reset()
        last_x, last_f, sums, differences = self._buffers
        norm = float(np.sqrt(sum(s * np.dot(f[b], f[b]) for s, b in zip(squares, blocks))))
        if self._has_last and norm > GROWTH * self._norm:
            self.reset()
        self._norm = norm
        if self._has_last:
            slot = next(k for k in range(self.depth + 1) if k not in self._order)
            np.subtract(f, last_f[0], out=differences[slot])
            np.subtract(x, last_x[0], out=sums[slot])
            sums[slot] += differences[slot]
            self._order.append(slot)
            if len(self._order) > self.depth:
                dropped = self._order.pop(0)
                self._products = {pair: v for pair, v in self._products.items() if dropped not in pair}
            for other in self._order:
                self._products[min(other, slot), max(other, slot)] = np.array(
                    [np.dot(differences[slot, b], differences[other, b]) for b in blocks])
        last_x[0], last_f[0] = x, f
        self._has_last = True
        result = x + f
        if not self._order:
            return result.reshape(shape)
        order = self._order
        gram = np.array([[squares @ self._products[min(a, b), max(a, b)] for b in order] for a in order])
        rhs = np.array([sum(s * np.dot(differences[a, b], f[b]) for s, b in zip(squares, blocks)) for a in order])
        if not (np.isfinite(gram).all() and np.isfinite(rhs).all()):  # a runaway iterate: the plain step shows it
            self.reset()
            return result.reshape(shape)
        gamma = np.linalg.lstsq(gram, rhs, rcond=GRAM_CUTOFF)[0]
        for g, a in zip(gamma, order):
            result -= g * sums[a]
        return result.reshape(shape)

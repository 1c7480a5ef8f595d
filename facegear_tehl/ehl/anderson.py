"""Anderson acceleration of a fixed-point iteration (Anderson 1965; in the form of Walker & Ni 2011).

For an iteration x_k+1 = x_k + f_k, with f_k = f(x_k) the (relaxed) step of the plain iteration, Anderson's
method takes the combination of the last m + 1 iterates whose steps cancel best (Walker & Ni 2011, SIAM J.
Numer. Anal. 49:1715-1735, eqs. 1.2-1.3 in their difference form, mixing parameter 1):

    gamma = argmin || W (f_k - dF gamma) ||_2,   x_k+1 = x_k + f_k - (dX + dF) gamma,

with dX, dF the columns x_i+1 - x_i, f_i+1 - f_i of the last m pairs and W a diagonal weight that makes the
components comparable: one scale per block of components (the thermal loop's temperatures and ln(eta*/eta)), so that
the inner products are kept per block and unweighted, each formed once, when its column enters, however the scales
move (the thermal loop's 1/rise moves at every update). For a linear map Anderson's iterates are those of GMRES on it
(Walker & Ni 2011, theorem 2.2). The history restarts when a step grows by more than a factor (TUNING.anderson_growth
for the film-state loops). The m x m
least-squares problem is solved through its normal equations (m <= 5 here: the vectors are long, the system tiny),
dropping directions whose singular value is below TUNING.gram_cutoff of the largest.

Components that were zero in every x and f so far take no part: x + f and every column of dX and dF are zero
there, so the iterate is exact (0) and the least squares the same to the summation order of the inner products. The
history is kept on the others (the support, which only grows until the history is dropped): the Newtonian columns of
an isothermal Ree-Eyring film (eta*/eta = 1, rheology.shear_state) are 82-87 % of its layer nodes on 513 x 65.
"""

from __future__ import annotations

from collections.abc import Sequence
import math

from numba import njit
import numpy as np

from facegear_tehl.ehl.tuning import TUNING


@njit(cache=True)
def _advance(x, f, last_x, last_f, dg, df):
    """The new history column in one pass (flat arrays): df = f - last_f and dg = (x - last_x) + df, with last_x and
    last_f then overwritten by x and f (the NumPy expressions' numbers, 13 passes over the vectors in 8)."""
    for n in range(x.size):
        d = f[n] - last_f[n]
        df[n] = d
        dg[n] = (x[n] - last_x[n]) + d
        last_x[n] = x[n]
        last_f[n] = f[n]


@njit(cache=True)
def _combine(x, f, gamma, columns, count, out):
    """out = x + f - gamma_0 columns_0 - ... - gamma_(count-1) columns_(count-1) in one pass (flat arrays; `columns` a
    tuple of the history's depth whose first `count` are the history's), the terms subtracted in order as NumPy's
    `result -= g * column` rounds them. A tuple of fixed length is one specialisation to load from Numba's cache, not
    one per length the history passes through (each a load of 10-30 ms in a process's first solve)."""
    for n in range(x.size):
        value = x[n] + f[n]
        for i in range(count):
            value -= gamma[i] * columns[i][n]
        out[n] = value


class Anderson:
    """The history of an accelerated fixed-point iteration (float arrays of one shape) and its next iterate."""

    def __init__(self, depth: int, growth: float | None = None):
        """`depth`: m, the number of earlier pairs (x_i, f_i) combined; `growth`: the factor by which the weighted step
        may grow from one iterate to the next before the history is dropped (None: TUNING.anderson_growth)."""
        self.depth, self.growth = depth, growth
        self._last: tuple[np.ndarray, np.ndarray] | None = None  # (x, f) of the last step, on the support
        self._dg: list[np.ndarray] = []  # the columns of dX + dF: the step's correction is their combination
        self._df: list[np.ndarray] = []
        self._products: dict[tuple[int, int], np.ndarray] = {}  # per block <dF_a, dF_b>, by serial numbers a <= b
        self._serial = 0  # serial number of the next column
        self._blocks = 0  # the blocks the products are kept by
        self._norm = 0.0
        # the flat indices of the history's components (sorted; None: none yet, or all once `_whole`), their mask
        self._support: np.ndarray | None = None
        self._mask: np.ndarray | None = None
        self._whole = False

    @property
    def columns(self) -> int:
        """The pairs of differences the last step combined (0: it was the plain step)."""
        return len(self._df)

    def reset(self) -> None:
        """Forget the history (the next step is the plain one) and its support."""
        self._forget()
        self._support, self._mask, self._whole = None, None, False

    def _forget(self) -> None:
        """Forget the history, keeping its support (the arrays of the step under way are on it)."""
        self._last, self._dg, self._df, self._products = None, [], [], {}

    def _gather(self, x: np.ndarray, f: np.ndarray) -> None:
        """Extend the support by the components where x or f is non-zero (the history is zero at the new ones) or
        take it whole once it exceeds TUNING.support_share of them."""
        if self._whole:
            return
        active = (x.ravel() != 0.0) | (f.ravel() != 0.0)
        if self._mask is not None:
            if not (active & ~self._mask).any():
                return
            active |= self._mask
        support = np.flatnonzero(active)
        whole = support.size > TUNING.support_share * x.size
        old = self._support
        if old is not None:  # the history kept on the old support moves to the new one
            places = old if whole else np.searchsorted(support, old)

            def moved(column: np.ndarray) -> np.ndarray:
                out = np.zeros(x.size if whole else support.size)
                out[places] = column
                return out

            self._dg = [moved(column) for column in self._dg]
            self._df = [moved(column) for column in self._df]
            if self._last is not None:
                self._last = (moved(self._last[0]), moved(self._last[1]))
        self._whole = whole
        self._support, self._mask = (None, None) if whole else (support, active)

    def step(self, x: np.ndarray, f: np.ndarray, scales: Sequence[float] | float = 1.0) -> np.ndarray:
        """The next iterate from the current one `x` and its plain step `f` (arrays of one shape), the least squares
        weighted by `scales`: one scale for all components, or one per block of as many equal consecutive blocks of
        the flat components; the plain x + f while there is no history."""
        squares = np.atleast_1d(np.asarray(scales, dtype=float)) ** 2
        if x.size % squares.size:
            raise ValueError(f"{x.size} components do not split into {squares.size} equal blocks")
        if squares.size != self._blocks:
            self._forget()
            self._blocks = squares.size
        bounds = np.arange(squares.size + 1) * (x.size // squares.size)  # the blocks' bounds in the flat components
        self._gather(x, f)
        support = self._support
        if support is None:
            return self._step(x.reshape(-1), f.reshape(-1), squares, bounds).reshape(x.shape)
        result = np.zeros(x.shape)
        result.reshape(-1)[support] = self._step(x.ravel()[support], f.ravel()[support], squares,
                                                 np.searchsorted(support, bounds))
        return result

    def _step(self, x: np.ndarray, f: np.ndarray, squares: np.ndarray, bounds: np.ndarray) -> np.ndarray:
        """`step` on the support: x and f its components (flat), `squares` the blocks' squared scales, `bounds` their
        bounds in x and f."""
        blocks = [slice(start, end) for start, end in zip(bounds[:-1], bounds[1:])]

        def products(a: np.ndarray, b: np.ndarray) -> np.ndarray:
            return np.array([np.dot(a[block], b[block]) for block in blocks])

        norm = math.sqrt(float(squares @ products(f, f)))
        growth = TUNING.anderson_growth if self.growth is None else self.growth
        if self._last is not None and norm > growth * self._norm:
            self._forget()
        self._norm = norm
        if self._last is not None:
            dg, df = np.empty_like(x), np.empty_like(f)
            _advance(x, f, *self._last, dg, df)
            self._dg.append(dg)
            self._df.append(df)
            serial, self._serial = self._serial, self._serial + 1
            if len(self._df) > self.depth:
                del self._dg[0], self._df[0]
            first = serial - len(self._df) + 1  # serial number of the oldest column kept
            self._products = {pair: value for pair, value in self._products.items() if pair[0] >= first}
            for other, column in enumerate(self._df, start=first):
                self._products[other, serial] = products(column, self._df[-1])
        else:
            self._last = (x.copy(), f.copy())
        if not self._df:
            return x + f
        serials = range(self._serial - len(self._df), self._serial)
        gram = np.array([[squares @ self._products[min(a, b), max(a, b)] for b in serials] for a in serials])
        rhs = np.array([squares @ products(column, f) for column in self._df])
        if not (np.isfinite(gram).all() and np.isfinite(rhs).all()):  # a runaway iterate: the plain step shows it
            self._forget()
            return x + f
        gamma = np.linalg.lstsq(gram, rhs, rcond=TUNING.gram_cutoff)[0]
        result = np.empty_like(x)
        padded = tuple(self._dg) + (x,) * (self.depth - len(self._dg))  # the tuple's length the depth (_combine)
        _combine(x, f, gamma, padded, len(self._dg), result)
        return result

"""Anderson acceleration (ehl/anderson.py) against exact fixed points."""

from dataclasses import replace
import subprocess
import sys

import numpy as np
import pytest

from facegear_tehl.ehl import anderson
from facegear_tehl.ehl.anderson import Anderson


def _linear_map(n: int, rate: float, seed: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """A contraction x -> A x + b with spectral radius `rate`, and its fixed point by a direct solve."""
    rng = np.random.default_rng(seed)
    a = rng.random((n, n))
    a *= rate / np.abs(np.linalg.eigvals(a)).max()
    b = rng.random(n)
    return a, b


def _formed_anew(xs, fs, x, f, weight, depth):
    """Anderson's next iterate with the normal equations formed from the whole history at once (Walker & Ni 2011,
    eq. 1.3): the reference for the kept and restricted ones."""
    dx = [b - a for a, b in zip(xs, xs[1:] + [x])][-depth:]
    df = [b - a for a, b in zip(fs, fs[1:] + [f])][-depth:]
    weighted = [column * weight for column in df]
    gram = np.array([[float(np.vdot(a, b)) for b in weighted] for a in weighted])
    rhs = np.array([float(np.vdot(column, f * weight)) for column in weighted])
    gamma = np.linalg.lstsq(gram, rhs, rcond=1e-10)[0]
    result = x + f
    for g, a, b in zip(gamma, dx, df):
        result -= g * (a + b)
    return result



def test_anderson_solves_a_linear_fixed_point_where_the_plain_iteration_crawls():
    # spectral radius 0.95: the plain iteration gains a factor 0.95^60 ~ 0.05 in 60 steps; Anderson's iterates are
    # GMRES's (Walker & Ni 2011, thm 2.2), with depth 10 exact to round-off on this 30-dimensional map
    a, b = _linear_map(30, 0.95)
    exact = np.linalg.solve(np.eye(30) - a, b)
    plain, accelerated, anderson = np.zeros(30), np.zeros(30), Anderson(10)
    for _ in range(60):
        plain = plain + (a @ plain + b - plain)
        accelerated = anderson.step(accelerated, a @ accelerated + b - accelerated)
    assert np.abs(plain - exact).max() > 1e-2 * np.abs(exact).max()
    assert np.abs(accelerated - exact).max() < 1e-10 * np.abs(exact).max()


def test_anderson_without_history_takes_the_plain_step_and_reset_forgets():
    anderson = Anderson(3)
    x, f = np.array([1.0, 2.0]), np.array([0.5, -0.25])
    assert np.array_equal(anderson.step(x, f), x + f)
    anderson.reset()
    assert np.array_equal(anderson.step(x + f, 2 * f), x + 3 * f)


def test_anderson_weighted_least_squares_is_invariant_to_a_common_scale():
    # one scalar weight on every component changes nothing (gamma minimises a scaled norm)
    a, b = _linear_map(12, 0.8, seed=5)
    runs = []
    for weight in (1.0, 1e-3):
        x, anderson = np.zeros(12), Anderson(3)
        for _ in range(8):
            x = anderson.step(x, a @ x + b - x, weight)
        runs.append(x)
    assert np.allclose(runs[0], runs[1], rtol=1e-9, atol=0.0)


def test_anderson_restarts_when_the_step_grows_and_takes_the_plain_step_on_non_finite_history():
    anderson = Anderson(3)
    anderson.step(np.zeros(2), np.array([1.0, 1.0]))
    # the step grew (|f| 2 > 1): the history is dropped, so this is the plain step
    assert np.array_equal(anderson.step(np.ones(2), np.array([2.0, 2.0])), np.array([3.0, 3.0]))
    anderson.step(np.full(2, 3.0), np.array([1.0, 0.5]))
    # a non-finite step: no least squares on it, the plain (non-finite) step shows the runaway
    assert not np.isfinite(anderson.step(np.full(2, 4.0), np.array([np.inf, 0.0]))).all()


def test_anderson_keeps_the_normal_equations_of_its_history_as_formed_anew():
    # The history's inner products are kept per block of components, unweighted, each formed once; each step must
    # equal the normal equations formed from the whole history at once (Walker & Ni 2011, eq. 1.3) with the blocks'
    # scales as the diagonal weight, also as the scales move at every step (the thermal loop's 1/rise on its
    # temperatures, 1 on ln(eta*/eta)) and with one scale per component (40 blocks of one).
    a, b = _linear_map(40, 0.9, seed=7)
    rng = np.random.default_rng(8)
    for run in range(3):
        x, anderson, xs, fs = np.zeros(40), Anderson(3), [], []
        for k in range(10):
            scales = ((1.0,), (1.0 / (5.0 + 3.0 * k), 1.0), tuple(rng.uniform(0.5, 2.0, 40)))[run]
            weight = np.repeat(scales, 40 // len(scales))
            f = 0.5 * (a @ x + b - x)
            expected = x + f if not xs else _formed_anew(xs, fs, x, f, weight, 3)
            got = anderson.step(x, f, scales)
            assert np.allclose(got, expected, rtol=1e-12, atol=1e-14)
            xs, fs, x = xs + [x], fs + [f], got
    with pytest.raises(ValueError):
        Anderson(3).step(np.zeros(40), np.ones(40), (1.0, 2.0, 3.0))  # 40 components in 3 equal blocks


def test_anderson_leaves_out_components_that_stayed_zero_and_grows_its_support(monkeypatch):
    # An isothermal Ree-Eyring film's Newtonian columns keep ln(eta*/eta) = 0 and a zero step: the history is kept on
    # the other components only. The iterates must be those of the history kept whole (the normal equations formed
    # anew above), to summation order, the zero components exactly zero, also as components join (the support grows)
    # and once more than support_share of them are active (the support taken whole).
    n = 60
    a, b = _linear_map(n, 0.9, seed=11)
    order = np.random.default_rng(12).permutation(n)  # components join in this order, between the kept ones

    # no restarts: the history is kept as components join
    monkeypatch.setattr(anderson, "TUNING", replace(anderson.TUNING, anderson_growth=np.inf))

    def run(joined):
        x, restricted, whole = np.zeros((3, n // 3)), Anderson(3), Anderson(3)
        for k in range(12):
            active = order < joined[min(k // 4, 2)]
            flat = x.ravel()
            f = np.where(active, 0.5 * (a @ np.where(active, flat, 0.0) + b - flat), 0.0).reshape(x.shape)
            with monkeypatch.context() as patch:
                # every support taken whole
                patch.setattr(anderson, "TUNING", replace(anderson.TUNING, support_share=-1.0))
                expected = whole.step(x, f, (1.0, 0.5))
            got = restricted.step(x, f, (1.0, 0.5))  # two blocks: their bounds on the support
            assert np.allclose(got, expected, rtol=1e-10, atol=1e-12)  # the normal equations' round-off, amplified
            assert not got.ravel()[~active].any()
            if k in (4, 8):  # components joined with the history kept
                assert len(restricted._df) == len(whole._df) > 0
            x = got
        return restricted

    assert run((10, 20, 25))._support is not None  # 25 of 60 stay under support_share
    assert run((10, 25, 45))._support is None


def test_the_combination_kernel_is_one_specialisation_whatever_the_history_length():
    # each specialisation is one more load from Numba's cache in a process's first solve (10-30 ms each): the history
    # growing through 1, 2, 3, 4 columns is passed as a tuple of the depth's length, so one signature serves them all
    probe = ("import numpy as np\nfrom facegear_tehl.ehl import anderson\n"
             "accelerator, x, m = anderson.Anderson(4), np.zeros(8), np.full((8, 8), 0.05)\n"
             "for _ in range(10):\n    x = accelerator.step(x, m @ x + 1.0 - x)\n"
             "print(accelerator.columns, sorted(len(s[3]) for s in anderson._combine.signatures))")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    assert done.stdout.split() == ["4", "[4]"]

"""Load sharing K(s) (docs/method.md §1.6): the two pairs in mesh one base pitch apart carry F_n between them."""

from __future__ import annotations

import numpy as np
import pytest

from facegear_tehl.gears.loads import LOAD_SHARING_MODELS, TRANSITION_SIDES, TRANSITION_TOLERANCE, load_share
from facegear_tehl.gears.tca import MESHING_POINTS, ContactPath, meshing_points

from gear_examples import EXAMPLE_A, pair

GEO = pair(EXAMPLE_A)
S_MIN, S_MAX = ContactPath(GEO).limits()
P_B = GEO.base_pitch
S = meshing_points(S_MIN, S_MAX, P_B)
DOUBLE_ZONE = {"iso_linear": 2 / 3, "equal": 1 / 2}


def share(model: str, s, side: str) -> np.ndarray:
    return load_share(model, np.asarray(s, dtype=float), S_MIN, S_MAX, P_B, side)


@pytest.mark.parametrize("side", TRANSITION_SIDES)
@pytest.mark.parametrize("model", LOAD_SHARING_MODELS)
def test_pairs_one_base_pitch_apart_sum_to_one_inside_the_entry_zone(model, side):
    """While the pair at s in (S1, S2) meshes, the pair one base pitch ahead is at s + p_b in (S4, S5)."""
    s = S_MIN + np.linspace(0.01, 0.99, 9) * (S["S2"] - S_MIN)
    np.testing.assert_allclose(share(model, s, side) + share(model, s + P_B, side), 1.0, rtol=0, atol=1e-12)


@pytest.mark.parametrize("model", LOAD_SHARING_MODELS)
def test_double_side_sums_to_one_at_the_transitions(model):
    """With transition_side double the law holds over the closed entry zone: K(S1) + K(S4) = K(S2) + K(S5) = 1."""
    s = np.linspace(S_MIN, S["S2"], 9)  # from S1 = s_min to S2 inclusive
    np.testing.assert_allclose(share(model, s, "double") + share(model, s + P_B, "double"), 1.0, rtol=0, atol=1e-12)
    k = {name: float(share(model, [S[name]], "double")[0]) for name in MESHING_POINTS}
    assert k["S1"] + k["S4"] == pytest.approx(1.0, abs=1e-12)
    assert k["S2"] + k["S5"] == pytest.approx(1.0, abs=1e-12)
    assert k["S2"] == k["S4"] == DOUBLE_ZONE[model] and k["S3"] == 1.0


@pytest.mark.parametrize("model,total", [("iso_linear", 4 / 3), ("equal", 3 / 2)])
def test_single_side_overloads_the_transitions(model, total):
    """With transition_side single (the default) S2 and S4 carry the whole load while their partners at S5
    and S1 still carry their double-zone share: F_n counted 4/3 times (iso_linear), hence `double`."""
    for first, second in (("S1", "S4"), ("S2", "S5")):
        k = share(model, [S[first], S[second]], "single")
        assert k.sum() == pytest.approx(total, abs=1e-12), (first, second)
    np.testing.assert_array_equal(load_share(model, [S["S2"], S["S4"]], S_MIN, S_MAX, P_B), [1.0, 1.0])


@pytest.mark.parametrize("model", LOAD_SHARING_MODELS)
def test_double_side_changes_only_the_transition_points(model):
    """Points within 1e-9 p_b of S2 or S4 take the double-zone value; the zones of K(s) are unchanged."""
    near = 0.5 * TRANSITION_TOLERANCE * P_B
    at = [S["S2"] - near, S["S2"] + near, S["S4"] - near, S["S4"] + near]
    np.testing.assert_allclose(share(model, at, "double"), DOUBLE_ZONE[model], rtol=0, atol=1e-9)
    path = np.linspace(S_MIN, S_MAX, 101)
    path = path[(np.abs(path - S["S2"]) > 1e-6 * P_B) & (np.abs(path - S["S4"]) > 1e-6 * P_B)]
    np.testing.assert_array_equal(share(model, path, "double"), share(model, path, "single"))
    off = [S["S2"] + 1e-6 * P_B, S["S4"] - 1e-6 * P_B]  # inside the single-tooth zone
    np.testing.assert_array_equal(share(model, off, "double"), [1.0, 1.0])


def test_unknown_side_is_refused():
    with pytest.raises(ValueError, match="transition side"):
        share("iso_linear", [0.0], "both")

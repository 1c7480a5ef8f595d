"""Normal load, contact ratio and load sharing between tooth pairs (docs/method.md §1.6), SI units.

Zones along the path s in [s_min, s_max] for a contact ratio 1 <= eps < 2:
double-tooth entry [s_min, S2), single-tooth [S2, S4], double-tooth exit (S4, s_max],
with S2 = s_max - p_b and S4 = s_min + p_b. A point exactly at S2 or S4 takes the single-tooth value
(transition_side "single", the default) or the double-tooth-zone limit ("double").
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from facegear_tehl.gears.geometry import PairGeometry

LOAD_SHARING_MODELS = ("iso_linear", "equal")
TRANSITION_SIDES = ("single", "double")
DOUBLE_ZONE_LIMIT = {"iso_linear": 2.0 / 3.0, "equal": 0.5}  # K of a model at the S2 / S4 end of its double zones
TRANSITION_TOLERANCE = 1e-9  # of p_b: a point this close to S2 or S4 lies at the transition


def normal_load(geo: PairGeometry, torque: float) -> float:
    """F_n = T1 / r_b1, N: exact for a spur pinion, whose contact normal is its transverse line of action."""
    return torque / geo.r_b1


def contact_ratio(s_min: float, s_max: float, base_pitch: float) -> float:
    """eps = (s_max - s_min) / p_b."""
    return (s_max - s_min) / base_pitch


def load_share(
    model: str, s: np.ndarray, s_min: float, s_max: float, base_pitch: float, transition_side: str = "single"
) -> np.ndarray:
    """Share K(s) of the total normal load carried by the tooth pair in contact at s (m).

    iso_linear (docs/method.md §1.6; ISO 6336-style): 1/3 at S1 rising linearly to 2/3 before S2,
        1 over [S2, S4], 2/3 after S4 falling linearly to 1/3 at S5. The two pairs always sum to 1.
    equal (model 2): 1/2 in the double-tooth zones, 1 in the single-tooth zone.

    transition_side: the K of a point exactly at S2 or S4 (within TRANSITION_TOLERANCE p_b); elsewhere K
    is the same. "single": 1, the single-tooth zone. "double": the double-tooth-zone limit, 2/3 (iso_linear)
    or 1/2 (equal). Why "double": the pair at S1 is in mesh at the same instant as the pair one base pitch
    ahead, at S4, and the pair at S5 with the one at S2, so K(s) + K(s + p_b) = 1 over the entry zone
    [S1, S2] only if S4 and S2 carry the double-tooth value (1/3 + 2/3 with iso_linear); with "single" the
    sums at S1 + S4 and S2 + S5 are 4/3. Choose "double" to read S1..S5 as simultaneous load snapshots.
    """
    if transition_side not in TRANSITION_SIDES:
        raise ValueError(f"unknown transition side {transition_side!r}; expected one of {TRANSITION_SIDES}")
    s = np.asarray(s, dtype=float)
    entry_end = s_max - base_pitch  # S2
    exit_start = s_min + base_pitch  # S4
    entry = s < entry_end
    exit_ = s > exit_start
    share = np.ones_like(s)
    if model == "equal":
        share[entry | exit_] = 0.5
    elif model == "iso_linear":
        width = entry_end - s_min  # (eps - 1) p_b, the length of each double-tooth zone
        share[entry] = (1.0 + (s[entry] - s_min) / width) / 3.0
        share[exit_] = (2.0 - (s[exit_] - exit_start) / width) / 3.0
    else:
        raise ValueError(f"unknown load sharing model {model!r}; expected one of {LOAD_SHARING_MODELS}")
    if transition_side == "double":
        tolerance = TRANSITION_TOLERANCE * base_pitch
        share[(np.abs(s - entry_end) <= tolerance) | (np.abs(s - exit_start) <= tolerance)] = DOUBLE_ZONE_LIMIT[model]
    return share


def interpolated_share(s: np.ndarray, point_s: Sequence[float], coefficients: Sequence[float]) -> np.ndarray:
    """K(s) for a user table of one coefficient per meshing point: linear in s between the points
    (sorted by s), constant beyond the first and last point."""
    order = np.argsort(point_s)
    return np.interp(s, np.asarray(point_s)[order], np.asarray(coefficients, dtype=float)[order])

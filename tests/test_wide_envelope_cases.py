"""The wide envelope suite's random draw (facegear_tehl/suites/wide_envelope.py, solved by scripts/wide_envelope.py):
its size, that it is fixed by its seed, that every contact lies in the issue's ranges with M <= 3e5 and really has
the drawn ellipticity and Hertz pressure (exact Hertz theory, hertz.py), and that half of it is thermal. Nothing is
solved."""

from __future__ import annotations

import math

import pytest

from facegear_tehl.ehl.scaling import scaling_for
from facegear_tehl.suites import wide_envelope

LOG_UNIFORM = ("ellipticity", "entrainment_speed", "viscosity")


@pytest.fixture(scope="module")
def cases():
    return wide_envelope.wide_cases()


def test_at_least_forty_uniquely_named_contacts_fixed_by_the_seed(cases):
    assert len(cases) >= 40
    assert len({c.name for c in cases}) == len(cases)
    assert [c.name for c in wide_envelope.wide_cases()] == [c.name for c in cases]


@pytest.mark.parametrize(("attribute", "bounds"), [
    ("ellipticity", wide_envelope.ELLIPTICITY), ("hertz_pressure", wide_envelope.HERTZ_PRESSURE),
    ("entrainment_speed", wide_envelope.SPEED), ("viscosity", wide_envelope.VISCOSITY),
    ("slide_roll_ratio", wide_envelope.SLIDE_ROLL), ("skew", wide_envelope.SKEW),
])
def test_every_draw_lies_in_the_issue_ranges_and_they_spread_over_them(cases, attribute, bounds):
    values = sorted(getattr(c, attribute) for c in cases)
    low, high = bounds
    assert low <= values[0] and values[-1] <= high
    # spread over the range: its lowest and highest quarter are both reached (in log for the log-uniform draws)
    scale = math.log if attribute in LOG_UNIFORM else float
    quarter = 0.25 * (scale(high) - scale(low))
    assert scale(values[0]) < scale(low) + quarter and scale(values[-1]) > scale(high) - quarter


def test_contacts_have_their_drawn_ellipse_and_load_parameter(cases):
    for case in cases:
        scaling = scaling_for(case.point(), case.lubricant())
        assert scaling.ellipticity == pytest.approx(case.ellipticity, rel=1e-6)
        assert scaling.p_h == pytest.approx(case.hertz_pressure, rel=1e-9)
        assert scaling.moes_m <= wide_envelope.MAX_MOES_M
    assert max(wide_envelope.moes_m(c) for c in cases) > 1e5  # the heavy loads of the issue are in it


def test_half_thermal_ree_eyring(cases):
    thermal = [c for c in cases if c.thermal]
    assert len(thermal) == len(cases) // 2
    assert all(c.lubricant().rheology == "ree_eyring" and c.settings().thermal == "full" for c in thermal)
    assert all(c.settings().thermal == "off" for c in cases if not c.thermal)


def test_a_contact_is_chosen_by_the_prefix_of_its_name_and_only_one(cases):
    assert wide_envelope.wide_envelope_contact("w08").name == next(c.name for c in cases if c.name.startswith("w08_"))
    for prefix, found in (("w0", 9), ("w99", 0)):
        with pytest.raises(ValueError, match=f"case '{prefix}': expected one wide-envelope contact, found {found}"):
            wide_envelope.wide_envelope_contact(prefix)

"""Text tables (`tables`) and display units (`units`): layout, cells and exact conversions."""

from __future__ import annotations

import math

import numpy as np
import pytest

from facegear_tehl.tables import COST, Column, cell, format_pairs, format_table, yes_no
from facegear_tehl.units import CELSIUS, DISPLAY, MILLIMETRE, PERCENT, Unit, display


def test_a_known_table_layout():
    table = format_table(["point", "h_c µm", "ok"], [["S1", "1.25", "yes"], ["S10", "0.5", "no"]])
    assert table == ("point  h_c µm   ok\n"
                     "-----  ------  ---\n"
                     "S1       1.25  yes\n"
                     "S10       0.5   no")


def test_an_empty_last_cell_leaves_no_trailing_blanks():
    table = format_table(["grid", "order"], [["33", ""], ["65", "1.98"]])
    assert table.splitlines()[2] == "33" and table.splitlines()[3] == "65     1.98"


def test_pairs_align_their_values():
    assert format_pairs([("case", "ball"), ("status", "ok")]) == "case    ball\nstatus  ok"


def test_cells():
    assert cell(0.123456, ".4g") == "0.1235" and cell(-0.5, "+.2f") == "-0.50"
    assert cell(None, ".4g") == "" and cell(math.nan, ".4g", "-") == "-"
    assert yes_no(True) == "yes" and yes_no(False) == "no"


def test_columns_show_the_display_unit_in_the_header_and_the_cell():
    film = Column("h_c", "h_c", "m")
    assert film.header == "h_c µm" and film.text(2.5e-7) == "0.25" and film.text(None) == "-"
    assert Column("mu", "mu", spec=".4f").header == "mu"  # dimensionless: no unit
    assert Column("Q_f", "frictional_heat", "J", ".3g").text(0.00941324) == "9.41"
    ratio = Column("Q_oil/Q_f", "oil_to_friction_ratio", spec=".2f", unit=PERCENT)
    assert ratio.header == "Q_oil/Q_f %" and ratio.text(0.0398204) == "3.98"
    assert Column("P", "friction_power", "W", ".1f").header == "P W"  # W has no other display unit
    assert [c.header for c in COST] == ["cycles", "work units", "wall time s"]


@pytest.mark.parametrize("units, label, factor", [("m", "µm", 1e6), ("Pa", "MPa", 1e-6), ("K", "K", 1.0),
                                                  ("1", "-", 1.0), ("J", "mJ", 1e3), ("W/m^2", "MW/m²", 1e-6)])
def test_display_units_are_exact_products(units, label, factor):
    unit = display(units)
    values = np.array([0.0, 1.0, -3.7e-7, 6.53588e8, 123.456])
    assert unit.label == label and unit.offset == 0.0
    assert np.array_equal(unit(values), values * factor)  # bit for bit: the same product as before
    assert unit(2.0) == 2.0 * factor


def test_units_not_listed_are_shown_as_they_are():
    for units in ("W", "N", "s", "m/s", "deg"):
        assert units not in DISPLAY and display(units) == Unit(units) and display(units)(7.25) == 7.25


def test_other_display_units():
    assert MILLIMETRE(0.0151767) == 0.0151767 * 1e3 and MILLIMETRE.text(1.85746e-4, ".3g") == "0.186 mm"
    assert CELSIUS(273.15) == 0.0 and CELSIUS(np.array([373.15]))[0] == pytest.approx(100.0, abs=1e-12)
    assert PERCENT(0.015) == 0.015 * 100.0
    assert display("Pa").text(4.49579e8, ".0f") == "450 MPa"


def test_a_zero_offset_keeps_the_sign_of_zero():
    """No offset is added when there is none: -0.0 stays -0.0, so a table prints what it printed before."""
    assert math.copysign(1.0, PERCENT(-0.0)) == -1.0

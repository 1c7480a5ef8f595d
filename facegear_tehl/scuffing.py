"""Scuffing safety by the flash-temperature criterion (Blok 1937): a flank scuffs when its contact temperature
theta_B = theta_bulk + theta_fl reaches the scuffing temperature theta_S of the oil on that flank material,

  S_B = (theta_S - theta_oil) / (theta_B,max - theta_oil),

the form of the safety factor of the flash-temperature method (DIN 3990-4, ISO/TS 6336-20): the margin of the
temperature rise above the oil. Temperatures in K."""

from __future__ import annotations


def flash_safety(scuffing_temperature: float, oil_temperature: float, contact_temperature: float) -> float | None:
    """S_B = (theta_S - theta_oil)/(theta_B - theta_oil), -; None when theta_B does not rise above the oil."""
    if contact_temperature <= oil_temperature:
        return None
    return (scuffing_temperature - oil_temperature) / (contact_temperature - oil_temperature)

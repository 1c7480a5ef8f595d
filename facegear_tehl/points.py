"""The contact points of a case, in order: the `ContactPoint`s the EHL solver is given."""

from __future__ import annotations

from typing import Sequence

from facegear_tehl.case import Case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.schema import CaseError


def contact_points(case: Case) -> list[ContactPoint]:
    """A plain case has one point, named 'contact'."""
    contact = case.contact
    return [
        ContactPoint.from_rolling_sliding(
            name="contact",
            radius_x=contact.radius_x,
            radius_y=contact.radius_y,
            load=contact.load,
            entrainment_speed=contact.entrainment_speed,
            slide_roll_ratio=contact.slide_roll_ratio,
            entrainment_angle_deg=contact.entrainment_angle,
            body_1=case.materials.body_1,
            body_2=case.materials.body_2,
        )
    ]


def select_points(available: Sequence[ContactPoint], names: Sequence[str]) -> list[ContactPoint]:
    """The points named in `names`, in the case's order; CaseError (key `--points`) for an unknown name
    or an empty selection."""
    known = [p.name for p in available]
    for name in names:
        if name not in known:
            raise CaseError("--points", name, "point names among: " + ", ".join(known))
    if not names:
        raise CaseError("--points", "", "at least one point name among: " + ", ".join(known))
    return [p for p in available if p.name in names]

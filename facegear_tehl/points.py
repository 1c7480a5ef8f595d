"""Contact analysis of a case: the `ContactPoint`s the EHL solver is given, in order, and for a face
gear pair the contact path they lie on (gears/analysis.py)."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import Mapping, Sequence

from facegear_tehl.case import Case
from facegear_tehl.contact import ContactPoint
from facegear_tehl.gears.analysis import PATH_DESCRIPTIONS, analyse_gear_pair
from facegear_tehl.schema import CaseError
from facegear_tehl.solution import Field


@dataclass(frozen=True)
class ContactAnalysis:
    """points: in order; path: quantities along the contact path (gear cases), name -> column;
    scalars: scalar geometry, name -> (value, units); warnings: remarks of the analysis."""

    points: tuple[ContactPoint, ...]
    path: Mapping[str, Field] = field(default_factory=dict)
    scalars: Mapping[str, tuple[float, str]] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()


@lru_cache(maxsize=4)  # `tehl run` asks twice for its case's (to select and warn, then to solve)
def contact_analysis(case: Case) -> ContactAnalysis:
    """A face gear pair: its meshing points and path; a plain case: one point, named 'contact' (a case frozen and
    hashable, its analysis kept for the next call with an equal case)."""
    body_1, body_2 = case.materials.body_1, case.materials.body_2
    if case.gear is not None:
        gear = analyse_gear_pair(case.gear, body_1, body_2)
        path = {name: Field(values, gear.units[name], PATH_DESCRIPTIONS[name]) for name, values in gear.path.items()}
        return ContactAnalysis(points=gear.points, path=path, scalars=gear.scalars(), warnings=gear.warnings)
    contact = case.contact
    point = ContactPoint.from_rolling_sliding(
        name="contact",
        radius_x=contact.radius_x,
        radius_y=contact.radius_y,
        load=contact.load,
        entrainment_speed=contact.entrainment_speed,
        slide_roll_ratio=contact.slide_roll_ratio,
        entrainment_angle_deg=contact.entrainment_angle,
        body_1=body_1,
        body_2=body_2,
    )
    return ContactAnalysis(points=(point,))


def select_points(available: Sequence[ContactPoint], names: Sequence[str], key: str = "--points") -> list[ContactPoint]:
    """The points named in `names`, in the case's order; CaseError (under `key`) for an unknown name, a name given
    twice (as the case's gear.points) or an empty selection."""
    known = [p.name for p in available]
    for index, name in enumerate(names):
        if name not in known:
            raise CaseError(key, name, "point names among: " + ", ".join(known))
        if name in names[:index]:
            raise CaseError(key, name, "each point named once")
    if not names:
        raise CaseError(key, "", "at least one point name among: " + ", ".join(known))
    return [p for p in available if p.name in names]

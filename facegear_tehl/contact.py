"""ContactPoint: everything the EHL solver needs about one elliptical contact, in SI units.

Frame: x along the minor axis of the Hertz ellipse (radius_x, the smaller reduced radius), y along the
major axis (radius_y >= radius_x), origin at the Hertz centre. Surface velocities are the velocities of
the two surfaces relative to the contact point, tangent to the contact, in this (x, y) frame.
"""

from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from facegear_tehl.hertz import HertzContact, hertz_contact
from facegear_tehl.materials import Solid, reduced_modulus


@dataclass(frozen=True)
class ContactPoint:
    """One elliptical EHL contact.

    name: label (S1..S5, or 'contact' for a plain case).
    radius_x, radius_y: reduced radii of curvature, m (radius_x <= radius_y).
    load: normal load, N.
    velocity_1, velocity_2: surface velocities (u_x, u_y) of bodies 1 and 2 relative to the contact, m/s.
    body_1, body_2: the solids.
    path_coordinate: signed position s along the line of action, m (gear cases; NaN otherwise).
    rotation_radius_1, rotation_radius_2: distance of the contact point from the rotation axis of body 1 and
        body 2, m (gear cases: pinion and face gear; NaN otherwise), for the duty ratio of the heat budget.
    """

    name: str
    radius_x: float
    radius_y: float
    load: float
    velocity_1: tuple[float, float]
    velocity_2: tuple[float, float]
    body_1: Solid
    body_2: Solid
    path_coordinate: float = math.nan
    rotation_radius_1: float = math.nan
    rotation_radius_2: float = math.nan

    @classmethod
    def from_rolling_sliding(
        cls,
        name: str,
        radius_x: float,
        radius_y: float,
        load: float,
        entrainment_speed: float,
        slide_roll_ratio: float,
        entrainment_angle_deg: float,
        body_1: Solid,
        body_2: Solid,
    ) -> "ContactPoint":
        """Plain contact: u_e = U (cos t, sin t), u_1,2 = u_e (1 +- SRR/2) (sliding along the entrainment)."""
        t = math.radians(entrainment_angle_deg)
        ue = np.array([math.cos(t), math.sin(t)]) * entrainment_speed
        u1 = ue * (1.0 + 0.5 * slide_roll_ratio)
        u2 = ue * (1.0 - 0.5 * slide_roll_ratio)
        return cls(
            name=name,
            radius_x=radius_x,
            radius_y=radius_y,
            load=load,
            velocity_1=(float(u1[0]), float(u1[1])),
            velocity_2=(float(u2[0]), float(u2[1])),
            body_1=body_1,
            body_2=body_2,
        )

    @property
    def entrainment(self) -> np.ndarray:
        """U_e = (u_1 + u_2)/2, m/s (vector)."""
        return 0.5 * (np.asarray(self.velocity_1) + np.asarray(self.velocity_2))

    @property
    def sliding(self) -> np.ndarray:
        """V_s = u_1 - u_2, m/s (vector)."""
        return np.asarray(self.velocity_1) - np.asarray(self.velocity_2)

    @property
    def entrainment_speed(self) -> float:
        return float(np.hypot(*self.entrainment))

    @property
    def sliding_speed(self) -> float:
        return float(np.hypot(*self.sliding))

    @property
    def entrainment_angle(self) -> float:
        """Angle of U_e to the x (minor) axis, degrees."""
        ue = self.entrainment
        return math.degrees(math.atan2(ue[1], ue[0]))

    @property
    def slide_roll_ratio(self) -> float:
        """|V_s|/|U_e|, signed by V_s . U_e (equals (u1 - u2)/u_e when sliding is along the entrainment)."""
        ue = self.entrainment
        vs = self.sliding
        sign = 1.0 if float(np.dot(vs, ue)) >= 0.0 else -1.0
        return sign * self.sliding_speed / self.entrainment_speed

    @property
    def reduced_modulus(self) -> float:
        return reduced_modulus(self.body_1, self.body_2)

    @property
    def hertz(self) -> HertzContact:
        return hertz_contact(self.radius_x, self.radius_y, self.load, self.reduced_modulus)

"""Surface velocities at the pinion / face-gear contact (docs/method.md §1.4), fixed frame, m/s.

The pinion turns at W1 about -a_1 (it drives clockwise, phi_1 decreasing); the face gear turns at
W2 = W1 dphi_2/dphi_1 about +a_2 (W1 N1/N2 for an involute drive). With the contact point moving at
dQ/dt = -W1 dQ/dphi_1:

    v_1 = -W1 a_1 x (Q - c_1),  v_2 = W2 a_2 x (Q - O_2),  u_i = v_i - dQ/dt  (tangent; n.u_i = 0)
    sliding V_s = u_1 - u_2 = v_1 - v_2,  entrainment U_e = (u_1 + u_2)/2,  SRR = |V_s|/|U_e|

u_i is the velocity of surface i relative to the contact point (what the Reynolds equation needs); the
"rolling velocity" of the contact point over surface i is -u_i.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from facegear_tehl.gears.geometry import PairGeometry
from facegear_tehl.gears.tca import ContactState


@dataclass(frozen=True)
class SurfaceVelocities:
    """u_1 (pinion) and u_2 (face gear) relative to the contact point, and the contact point's own velocity."""

    pinion: np.ndarray  # u_1, m/s
    face_gear: np.ndarray  # u_2, m/s
    contact_point: np.ndarray  # dQ/dt, m/s

    @property
    def sliding(self) -> np.ndarray:
        """V_s = u_1 - u_2, m/s."""
        return self.pinion - self.face_gear

    @property
    def entrainment(self) -> np.ndarray:
        """U_e = (u_1 + u_2)/2, m/s."""
        return 0.5 * (self.pinion + self.face_gear)


def surface_velocities(geo: PairGeometry, state: ContactState, pinion_speed: float) -> SurfaceVelocities:
    """Velocities at the contact `state` for the pinion speed W1 (rad/s, driving direction)."""
    omega_1 = -pinion_speed * state.pinion_axis
    omega_2 = pinion_speed * state.ratio * geo.a2
    point_velocity = -pinion_speed * state.point_rate
    v_1 = np.cross(omega_1, state.point - state.pinion_centre)
    v_2 = np.cross(omega_2, state.point - state.face_gear_origin)
    return SurfaceVelocities(pinion=v_1 - point_velocity, face_gear=v_2 - point_velocity, contact_point=point_velocity)


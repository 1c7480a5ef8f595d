r"""Energy equation of the line-contact film (x-z), heat into the solids, and the Ree-Eyring film.

Film (steady, 2-D; Cheng 1965, Sadeghi & Sui 1990, Yang & Wen 1990; along-film conduction neglected):

    c_f (rho u dT/dx + rho w dT/dz) = d/dz(k dT/dz) + tau du/dz + T eps_T' u dp/dx,
    eps_T' = -(1/rho) d rho/dT = eps_T/(1 - eps_T (T - T_0))          (the project's density law)

Finite volumes on the grid of the Reynolds solve (node control volumes V_i) times `layers` equal cells across
the film, in the advective (non-conservative) form with conservative mass fluxes: the x-face layer fluxes m_{f,k}
are those of the generalized Reynolds equation (`film.CrossFilmIntegrals`: Couette part upwind-extrapolated as in
`reynolds.py`, Poiseuille part at the face gradient), so that they add up to the discrete Reynolds flux of the
face; the cross-film fluxes follow from the mass balance of each cell (zero through the bottom wall). Each cell
then reads (first-order upwind convection, inflow faces only)

    c_f sum_in |F| (T_P - T_nb) + sum G (T_P - T_nb) = V theta tau du/dz|_cell + compression,

which sums exactly to: heat generated = heat conducted into the solids + c_f sum_out |F| (T - T_0) (enthalpy
convected out through the inlet back-flow and the outlet), up to the mass imbalance of the Reynolds solution.
Past the film rupture the Couette flux would grow; there every flux is scaled by the film fraction theta so that
the mass flux stays that of the rupture point (the film is a set of streamers of constant flow).

Solids: each surface (body 1 at z = 0 moving at u_1, body 2 at z = h at u_2, both towards +x) follows Jaeger's
high-Peclet moving heat source (Jaeger 1942; Carslaw & Jaeger 1959, sec. 10.7), applied with the flux q_j into
the solid constant over each control volume:

    T_s(x_i) = T_0 + 1/sqrt(pi k_s rho_s c_s u_s) sum_j q_j int_{V_j, s < x_i} ds/sqrt(x_i - s),

the integrals in closed form (`jaeger_matrix`). Inflow of oil at T_0 through the inlet boundary (where it
enters); none is specified where it leaves.

Ree-Eyring (Ree & Eyring 1955; Johnson & Tevaarwerk 1977): du/dz = (tau_0/eta) sinh(tau/tau_0), the stress
tau = tau_a + p_x z across the film; `eyring_columns` solves u(h) - u(0) = u_2 - u_1 for tau_a at each node,
giving the shear rate of every layer (eta* = tau/rate, `film.GeneralizedFilm`).
"""

from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np
from scipy import linalg, sparse
from scipy.sparse import linalg as splinalg

from facegear_tehl.line.film import CrossFilmIntegrals
from facegear_tehl.lubricant import Lubricant
from facegear_tehl.materials import Solid

EYRING_ITERATIONS = 80  # safeguarded Newton-bisection steps on tau_a: each halves the bracket at worst
GMRES_TOLERANCE = 1e-12  # relative residual of the surface-temperature system: far below the thermal tolerance
GMRES_RESTART = 200  # Krylov vectors (the preconditioned operator is identity + a smooth compact part: ~10 used)
MAX_SINH_ARGUMENT = 700.0  # tau/tau_0 cap: sinh(700) ~ 1e304, just below the float overflow


def jaeger_matrix(x: np.ndarray) -> np.ndarray:
    """W with (W @ q)_i = int_{x_0}^{x_i} q(s) ds/sqrt(x_i - s) for q constant over each node's control volume
    [x_{j-1/2}, x_{j+1/2}] (clipped to the domain): W_ij = 2 (sqrt(x_i - lo_j) - sqrt(max(x_i - hi_j, 0))) for
    lo_j < x_i, else 0. Units m^0.5."""
    x = np.asarray(x, dtype=np.float64)
    mid = 0.5 * (x[1:] + x[:-1])
    lo = np.concatenate([[x[0]], mid])
    hi = np.concatenate([mid, [x[-1]]])
    a = np.clip(x[:, None] - lo[None, :], 0.0, None)
    b = np.clip(x[:, None] - hi[None, :], 0.0, None)
    return 2.0 * (np.sqrt(a) - np.sqrt(b))


def control_volumes(x: np.ndarray) -> np.ndarray:
    """Widths of the node control volumes (face midpoints; half cells at both ends), m."""
    mid = 0.5 * (x[1:] + x[:-1])
    lo = np.concatenate([[x[0]], mid])
    hi = np.concatenate([mid, [x[-1]]])
    return hi - lo


def eyring_columns(eta: np.ndarray, h: np.ndarray, p_x: np.ndarray, du: float, tau0: float
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Ree-Eyring film on each node column: solve h sum_k d (tau0/eta_k) sinh((tau_a + p_x h z_k)/tau0) = du
    for tau_a (monotone in tau_a: bracketed Newton), return (|du/dz| of each layer (n, m), tau_a (n)).

    eta: Newtonian viscosity of each layer (n, m), Pa s; h, p_x (n); du = u_2 - u_1, m/s; tau0 in Pa."""
    n, m = eta.shape
    d = 1.0 / m
    z = (np.arange(m) + 0.5) * d
    slope = (p_x * h)[:, None] * z[None, :]  # p_x z at the layer centres
    weight = h[:, None] * d * tau0 / eta  # (n, m)

    def residual(tau_a):
        arg = np.clip((tau_a[:, None] + slope) / tau0, -MAX_SINH_ARGUMENT, MAX_SINH_ARGUMENT)
        return (weight * np.sinh(arg)).sum(axis=1) - du, (weight * np.cosh(arg)).sum(axis=1) / tau0

    # bracket: at tau_a = -max|slope| - tau0*asinh(...) every layer term has the sign of the target
    reach = np.abs(slope).max(axis=1) + tau0 * np.arcsinh(abs(du) / (h * d * tau0 / eta.max(axis=1)).clip(1e-300))
    lo, hi = -reach - tau0, reach + tau0
    # Newtonian start: tau = eta_harmonic du/h
    tau_a = np.clip(du / (h * d * (1.0 / eta).sum(axis=1)), lo, hi)
    for _ in range(EYRING_ITERATIONS):
        f, df = residual(tau_a)
        lo = np.where(f < 0.0, tau_a, lo)
        hi = np.where(f > 0.0, tau_a, hi)
        step = tau_a - f / df
        bad = ~((step > lo) & (step < hi))
        tau_a = np.where(bad, 0.5 * (lo + hi), step)
        if np.all(np.abs(f) <= 1e-12 * max(abs(du), 1e-12)):
            break
    tau = tau_a[:, None] + slope
    arg = np.clip(tau / tau0, -MAX_SINH_ARGUMENT, MAX_SINH_ARGUMENT)
    return np.abs(tau0 / eta * np.sinh(arg)), tau_a


@dataclass
class EnergySolution:
    temperature: np.ndarray  # (n, m) film, K
    surface_1: np.ndarray  # (n) body 1 (z = 0), K
    surface_2: np.ndarray  # (n) body 2 (z = h), K
    generated: float  # W/m: dissipation + compression work
    to_solid_1: float  # W/m
    to_solid_2: float  # W/m
    convected: float  # W/m, enthalpy (relative to T_0) leaving through the inlet and outlet boundaries


@dataclass
class FilmFlow:
    """Mass fluxes of the film, per unit width (kg/(m s)): x-faces (n + 1, m) including both boundary faces,
    cross-film faces (n, m - 1), film fraction theta (n) (1 in the full film)."""

    x_flux: np.ndarray
    z_flux: np.ndarray
    theta: np.ndarray


def film_flow(cells: CrossFilmIntegrals, x: np.ndarray, h: np.ndarray, p: np.ndarray, upwind: np.ndarray,
              cavitated: np.ndarray) -> FilmFlow:
    """Layer mass fluxes consistent with the discrete Reynolds fluxes (see module docstring).

    x, h, p dimensional (n); upwind: the Couette extrapolation weights of `ReynoldsSystem.upwind` (n - 1);
    cavitated: boolean (n), nodes past the film rupture (P = 0 with an outflow excess)."""
    n = x.size
    couette = h[:, None] * cells.couette_shape  # (n, m)
    poiseuille = h[:, None] ** 3 * cells.poiseuille_shape  # per unit p_x
    grad = np.diff(p) / np.diff(x)
    face = couette[:-1].copy()
    face[1:] += upwind[1:, None] * (couette[1:-1] - couette[:-2])
    face += grad[:, None] * 0.5 * (poiseuille[:-1] + poiseuille[1:])
    total = face.sum(axis=1)
    scaled = total.copy()
    for f in range(1, n - 1):  # node f sits between faces f - 1 and f
        scaled[f] = scaled[f - 1] if cavitated[f] else scaled[f - 1] + (total[f] - total[f - 1])
    scale = np.where(total != 0.0, scaled / np.where(total != 0.0, total, 1.0), 1.0)
    face *= scale[:, None]
    x_flux = np.concatenate([face[:1], face, face[-1:]], axis=0)  # boundary faces copy their neighbours
    net = x_flux[1:] - x_flux[:-1]  # (n, m) outflow excess of each cell through its x-faces
    z_flux = -np.cumsum(net, axis=1)[:, :-1]  # upward flux through the top of layers 0 .. m-2
    theta = np.concatenate([[1.0], 0.5 * (scale[:-1] + scale[1:]), [scale[-1]]])
    return FilmFlow(x_flux=x_flux, z_flux=z_flux, theta=theta)


def solve_energy(x: np.ndarray, h: np.ndarray, p: np.ndarray, cells: CrossFilmIntegrals, flow: FilmFlow,
                 temperature: np.ndarray, lubricant: Lubricant, body_1: Solid, body_2: Solid, u_1: float,
                 u_2: float) -> EnergySolution:
    """Solve the energy system of the film cells and both surface temperatures with the film state frozen
    (viscosity, flow and dissipation of the current iterate, `temperature` (n, m)).

    The surface unknowns are eliminated: the fluid block (sparse LU) is solved inside a GMRES iteration on the
    2n surface temperatures, preconditioned by the lower-triangular Jaeger block (exact for a given fluid)."""
    n, m = temperature.shape
    t0 = lubricant.inlet_temperature
    c_f = lubricant.specific_heat
    volume = control_volumes(x)
    theta = flow.theta
    k_f = lubricant.conductivity_at(p)
    p_x = np.gradient(p, x)
    d = 1.0 / m
    size = n * m
    me = np.arange(size).reshape(n, m)
    system = _Assembly(size)
    fx = flow.x_flux  # (n + 1, m), positive towards +x
    _add_convection(system, fx, flow.z_flux, me, c_f, t0)
    # cross-film conduction, W/(m K) per unit width
    g_z = theta * k_f * volume / (h * d)
    g_w = 2.0 * g_z
    _add_conduction(system, g_z, g_w, me)
    # dissipation of the current film state (Picard: frozen during this solve)
    dissipation = cells.dissipation(h, p_x) * (theta * volume)[:, None]  # W/m per cell
    system.rhs += dissipation.ravel()
    # compression work T eps_T' u p_x (implicit in T)
    layer_flux = 0.5 * (fx[:-1] + fx[1:])  # (n, m) mean x mass flux of each cell
    eps_t = lubricant.thermal_expansion / (1.0 - lubricant.thermal_expansion * (temperature - t0))
    compression = eps_t * (layer_flux / cells.rho) * p_x[:, None] * volume[:, None]  # W/(m K), times T
    system.diag -= compression.ravel()
    walls_coupling = _WallCoupling(x, splinalg.splu(system.matrix()), g_w, volume, (me[:, 0], me[:, -1]),
                                   ((body_1, u_1), (body_2, u_2)))
    walls = walls_coupling.solve(system.rhs, t0)
    t_film = walls_coupling.fluid_from_walls(walls, system.rhs).reshape(n, m)
    t_1, t_2 = walls[:n], walls[n:]
    to_1 = float((g_w * (t_film[:, 0] - t_1)).sum())
    to_2 = float((g_w * (t_film[:, -1] - t_2)).sum())
    generated = float((dissipation + compression * t_film).sum())
    out_left = np.clip(-fx[0], 0.0, None)
    out_right = np.clip(fx[-1], 0.0, None)
    convected = float(c_f * ((out_left * (t_film[0] - t0)).sum() + (out_right * (t_film[-1] - t0)).sum()))
    return EnergySolution(temperature=t_film, surface_1=t_1, surface_2=t_2, generated=generated,
                          to_solid_1=to_1, to_solid_2=to_2, convected=convected)


class _Assembly:
    """The fluid block of the energy system: (row, column, value) triplets, its diagonal and its right-hand side
    (W/m per cell; `size` cells)."""

    def __init__(self, size: int):
        self.size = size
        self.rows: list[np.ndarray] = []
        self.cols: list[np.ndarray] = []
        self.vals: list[np.ndarray] = []
        self.diag = np.zeros(size)
        self.rhs = np.zeros(size)

    def add(self, r, c, v) -> None:
        self.rows.append(np.asarray(r).ravel())
        self.cols.append(np.asarray(c).ravel())
        self.vals.append(np.asarray(v, dtype=np.float64).ravel())

    def matrix(self) -> sparse.csc_matrix:
        """The matrix of the triplets added and the diagonal, added last."""
        self.add(np.arange(self.size), np.arange(self.size), self.diag)
        return sparse.csc_matrix((np.concatenate(self.vals), (np.concatenate(self.rows), np.concatenate(self.cols))),
                                 shape=(self.size, self.size))


def _add_convection(system: _Assembly, fx: np.ndarray, fz: np.ndarray, me: np.ndarray, c_f: float,
                    t0: float) -> None:
    """Upwind convection along x through the cell faces (`fx` (n + 1, m): face f between cell f - 1 and cell f,
    positive towards +x, kg/(m s)), with oil at `t0` (K) entering through either boundary, and across the layers
    (`fz` (n, m - 1): through the top of layer k, positive upwards)."""
    left_in = np.clip(fx[:-1], 0.0, None)  # inflow of cell i through its left face
    right_in = np.clip(-fx[1:], 0.0, None)  # inflow through its right face
    system.diag += c_f * (left_in + right_in).ravel()
    system.add(me[1:], me[:-1], -c_f * left_in[1:])
    system.add(me[:-1], me[1:], -c_f * right_in[:-1])
    system.rhs[me[0]] += c_f * left_in[0] * t0  # oil entering through the inlet boundary
    system.rhs[me[-1]] += c_f * right_in[-1] * t0  # and through the outlet boundary (reverse flow), if any
    up = np.clip(fz, 0.0, None)  # enters layer k + 1 from below
    down = np.clip(-fz, 0.0, None)  # enters layer k from above
    system.diag[me[:, 1:].ravel()] += c_f * up.ravel()
    system.add(me[:, 1:], me[:, :-1], -c_f * up)
    system.diag[me[:, :-1].ravel()] += c_f * down.ravel()
    system.add(me[:, :-1], me[:, 1:], -c_f * down)


def _add_conduction(system: _Assembly, g_z: np.ndarray, g_w: np.ndarray, me: np.ndarray) -> None:
    """Cross-film conduction between neighbouring layers (conductance `g_z`, W/(m K) per unit width, per column)
    and from the outer layers to the walls (`g_w`)."""
    m = me.shape[1]
    if m > 1:
        gz = np.repeat(g_z[:, None], m - 1, axis=1)
        system.diag[me[:, :-1].ravel()] += gz.ravel()
        system.diag[me[:, 1:].ravel()] += gz.ravel()
        system.add(me[:, :-1], me[:, 1:], -gz)
        system.add(me[:, 1:], me[:, :-1], -gz)
    system.diag[me[:, 0]] += g_w
    system.diag[me[:, -1]] += g_w


class _WallCoupling:
    """The fluid block's coupling to the 2n surface temperatures: T_s + Jc (g T_s) - Jc (g T_f) = T_0 for each
    surface, Jc = W/sqrt(pi k rho c u) (W the Jaeger matrix), g = g_w/V (W/(m^2 K))."""

    def __init__(self, x: np.ndarray, lu, g_w: np.ndarray, volume: np.ndarray, layer_of: tuple[np.ndarray, ...],
                 surfaces: tuple[tuple[Solid, float], ...]):
        """`lu`: the factorised fluid block; `layer_of`: the cells next to surface 1 and 2; `surfaces`: each solid
        and its surface speed (m/s)."""
        self.n = x.size
        self.lu, self.g_w, self.layer_of = lu, g_w, layer_of
        jaeger = jaeger_matrix(x)
        self.conductance = g_w / volume
        self.blocks = []
        for body, speed in surfaces:
            if speed <= 0.0:
                raise ValueError(f"surface speed {speed} m/s: the moving-source (Jaeger) model needs u > 0")
            jc = jaeger / math.sqrt(math.pi * body.thermal_conductivity * body.density * body.specific_heat * speed)
            self.blocks.append((jc, np.eye(self.n) + jc * self.conductance[None, :]))

    def fluid_from_walls(self, walls: np.ndarray, source: np.ndarray) -> np.ndarray:
        b = source.copy()
        b[self.layer_of[0]] += self.g_w * walls[:self.n]
        b[self.layer_of[1]] += self.g_w * walls[self.n:]
        return self.lu.solve(b)

    def walls_from_fluid(self, t_fluid: np.ndarray, constant: float) -> np.ndarray:
        n = self.n
        out = np.empty(2 * n)
        for side, (jc, e) in enumerate(self.blocks):
            right = constant + jc @ (self.conductance * t_fluid[self.layer_of[side]])
            out[side * n:(side + 1) * n] = linalg.solve_triangular(e, right, lower=True, check_finite=False)
        return out

    def solve(self, rhs: np.ndarray, t0: float) -> np.ndarray:
        """The surface temperatures (K, surface 1 then 2) for the fluid's right-hand side `rhs` and the solids'
        bulk temperature `t0` (K): GMRES on the Schur complement, formed and solved directly if GMRES fails."""
        zero = np.zeros(rhs.size)

        def operator(v: np.ndarray) -> np.ndarray:  # (I - E^-1 D A^-1 C) v, the preconditioned Schur complement
            return v - self.walls_from_fluid(self.fluid_from_walls(v, zero), 0.0)

        n = self.n
        start = self.walls_from_fluid(self.lu.solve(rhs), t0)
        schur = splinalg.LinearOperator((2 * n, 2 * n), matvec=operator, dtype=np.float64)
        walls, info = splinalg.gmres(schur, start, x0=start, rtol=GMRES_TOLERANCE, atol=0.0,
                                     restart=GMRES_RESTART, maxiter=GMRES_RESTART)
        if info != 0:  # stiff state (extreme temperatures early in the outer iteration): form the Schur complement
            columns = np.column_stack([operator(e) for e in np.eye(2 * n)])
            walls = linalg.solve(columns, start, check_finite=False)
        return walls

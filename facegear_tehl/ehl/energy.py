"""Energy equation in the film on layers across it (SI units; Numba kernels).

Steady energy balance of the lubricant in layer coordinates zeta = (z - z_1)/h (Yang & Wen 1990; Guo et al.
2001 for the velocity across the layers), conduction along the film neglected as usual for thin films:

    rho c (u dT/dx + v dT/dy) + c (W/h) dT/dzeta - (k/h^2) d^2T/dzeta^2 = tau . gamma_dot + beta_T T (u dp/dx + v dp/dy)

with the thermal expansivity beta_T = -(1/rho) d rho/dT = eps_T/(1 - eps_T (T - T_0)) of the density law
(lubricant.py) and W = rho (w - (dz_1/dx + zeta dh/dx) u - (dz_1/dy + zeta dh/dy) v) h the mass flux across the
layers (kg/(m^2 s)). Continuity in layer coordinates, d(h rho u)/dx + d(h rho v)/dy + dW/dzeta = 0 with W = 0 on
both surfaces, gives W without the surface shapes:

    W(zeta) = -d/dx \\int_0^zeta h rho u dzeta' - d/dy \\int_0^zeta h rho v dzeta'.

Since c is constant, rho c u . grad T = (1/h) [div(h rho c u T) + d(c W T)/dzeta - T (div(h rho c u) + d(c W)/dzeta)],
and the equation is discretised in this conservative form on cells around the nodes, so that its discrete
energy balance closes exactly (`energy_budget`):

- layer nodes zeta_k = k/(nz - 1); cell k spans the fraction w_k of the film, w = (9, 28, 23, 24, ..., 24, 23, 28,
  9)/(24 (nz - 1)) (Gregory's fourth-order end-corrected rule, exact for cubics: the weights the compact
  conduction scheme below integrates with); the surface nodes k = 0 and nz - 1 carry the solid surface
  temperatures (Dirichlet, from the moving heat source of each solid);
- along x and y the nodes are cell centres (spacing dx, dy); the heat-capacity flux of a layer per unit of
  zeta, h rho c u (W/(m K)), is averaged onto the cell faces, and the temperature on a face is the upwind one,
  second order by a limited (van Leer 1979) MUSCL reconstruction, with the inlet temperature where the oil flows
  in and the linear extrapolation where it flows out of the domain; the first-order part is implicit, the limited
  correction comes from the current iterate;
- across the film the discrete continuity gives the flux across each layer face, c W_k+1/2 = c W_k-1/2 -
  w_k (D_k - D_col) with D_k the divergence of the layer's face fluxes and D_col = sum w_k D_k that of the
  column: the column's total flux need not be divergence-free (the film ruptures in the cavitated outlet, where
  the full-film velocities are not mass conserving, and the Reynolds equation is discretised differently); the
  share it lacks is taken from every layer in proportion to its width, so that W = 0 on both surfaces, and the
  heat the created (or lost) mass carries at the local temperature is reported (`energy_budget`). The face
  temperature across the layers is upwind, corrected towards the linear interpolation (second order) by
  min(1, 2/Pe) with Pe = c |W| dz/k the cell Péclet number (central where it is monotone, Pe <= 2);
- in each column the conduction term is discretised compactly (Numerov's scheme, `_column`): fourth order
  where conduction dominates, as in the Hertz zone; the node balances F_k (convection minus sources) enter it
  as theta (F_k-1 + F_k+1)/12 + (1 - theta/6) F_k, and the heat flux into each wall follows from the same
  balances (`wall_fluxes`), so that the column's conduction equals the w-weighted integral of its balances.
  The cross-film convection, a small term where conduction dominates, is second-order accurate.

Each column is a pentadiagonal system in k (the cross-film upwind couples F_k to its neighbours); the columns
are swept Gauss-Seidel forwards and backwards in x. Compression cooling is implicit. On the face gear case
(cases/facegear_110.yaml, 129 x 33) the default nine layers are within 0.5 % of 33 layers in the largest
temperature rise, 0.2 % in the largest expansion cooling and 0.2 % in h_c, h_min and mu (S1 and S3). k = k(p) is
the film's conductivity, one value per column since the pressure is constant across the film (lubricant.py: the
constant k_0, or Larsson et al. 2000).
"""

from __future__ import annotations

from numba import njit
import numpy as np

from facegear_tehl.ehl.film_state import FilmState
from facegear_tehl.ehl.layers import simpson_weights
from facegear_tehl.ehl.tuning import TUNING

# Module globals from TUNING: Numba kernels read globals when they compile (central_peclet: the three-point
# convection-diffusion scheme stays monotone up to a cell Peclet number of 2, Patankar 1980, sec. 5.2).
CENTRAL_PECLET = TUNING.central_peclet
ACTIVE_REACH = TUNING.active_reach
ACTIVE_SHARE = TUNING.active_share


@njit(cache=True)
def layer_weight(k: int, nz: int) -> float:
    """Width of layer cell k as a fraction of the film (the sum over k is 1): Gregory's end-corrected rule
    (9, 28, 23, 24, ..., 24, 23, 28, 9)/24 on nz >= 7 nodes; on 5 nodes (9, 28, 22, 28, 9)/24, on 3 Simpson's rule."""
    w = 12.0 if k == 0 or k == nz - 1 else 24.0
    for end in (k, nz - 1 - k):
        if end == 0:
            w -= 3.0
        elif end == 1:
            w += 4.0
        elif end == 2:
            w -= 1.0
    return w / (24.0 * (nz - 1))


@njit(cache=True)
def layer_weights_array(nz):
    """All nz widths of `layer_weight` (for the kernels)."""
    out = np.empty(nz)
    for k in range(nz):
        out[k] = layer_weight(k, nz)
    return out


def layer_weights(nz: int) -> np.ndarray:
    """All nz widths of `layer_weight`."""
    return layer_weights_array(nz)


@njit(cache=True, inline="always")
def _limited_half(rise: float, upstream_rise: float) -> float:
    """0.5 psi(r) of van Leer's limiter (van Leer 1979), r = rise/upstream_rise; 0 at extrema."""
    if rise * upstream_rise <= 0.0:
        return 0.0
    return rise / (rise + upstream_rise)


@njit(cache=True, inline="always")
def _value(temperature, k, j, i, t_inlet):
    """Temperature of node (k, j, i); the inlet temperature outside the domain."""
    nz, ny, nx = temperature.shape
    if 0 <= j < ny and 0 <= i < nx:
        return temperature[k, j, i]
    return t_inlet


@njit(cache=True, inline="always")
def _face_value(temperature, k, j, i, dj, di, t_inlet):
    """Temperature on the face between node (j, i), upwind, and (j + dj, i + di) for flow from the first to the
    second (one of dj, di 0, the other +1 or -1): the MUSCL face value T_up + 0.5 psi(r) (T_up - T_up2), van Leer's
    limiter (van Leer 1979), r = (T_down - T_up)/(T_up - T_up2); the inlet temperature upstream of the domain (a
    face where the oil flows in carries it). On a boundary face where the oil flows out, T_down is outside: the
    face value is the linear extrapolation T_up + 0.5 (T_up - T_up2) (second order; a limiter against the inlet
    temperature would fall to first order there, halving the convective derivative of the boundary node)."""
    nz, ny, nx = temperature.shape
    jd, id_ = j + dj, i + di
    leaves = not (0 <= jd < ny and 0 <= id_ < nx)
    t_down = t_inlet if leaves else temperature[k, jd, id_]
    return _muscl(_value(temperature, k, j, i, t_inlet), _value(temperature, k, j - dj, i - di, t_inlet), t_down,
                  leaves)


@njit(cache=True, inline="always")
def _muscl(t_up, t_up2, t_down, leaves):
    """`_face_value` from the temperatures of the line through the face: upwind t_up, t_up2 behind it, t_down across
    the face; `leaves`: a boundary face the oil flows out by (t_down is then not read)."""
    if leaves:
        return t_up + 0.5 * (t_up - t_up2)
    return t_up + _limited_half(t_down - t_up, t_up - t_up2) * (t_up - t_up2)


@njit(cache=True)
def _to_faces(line):
    """Node values line[1:] (n nodes) to the n + 1 face values in place: the average of the two nodes between
    which a face lies; on the two boundary faces, half a spacing beyond the boundary nodes, the linear
    extrapolation 1.5 m_0 - 0.5 m_1 (the boundary node's value would make its cell's divergence half the
    derivative: an O(1) error of the velocity across the layers there)."""
    n = line.size - 1
    if n == 1:
        line[0] = line[1]
        return
    first, second, last, before_last = line[1], line[2], line[n], line[n - 1]
    for f in range(1, n):
        line[f] = 0.5 * (line[f] + line[f + 1])
    line[0] = 1.5 * first - 0.5 * second
    line[n] = 1.5 * last - 0.5 * before_last


@njit(cache=True, error_model="numpy")
def transport_fluxes(velocity_x, velocity_y, rho_c, film, dx, dy):
    """Heat-capacity fluxes of the layers for velocities (m/s) and rho c (J/(m^3 K)) per layer node, film h (m)
    per column on a (ny, nx) grid of spacings dx, dy (m):

    flux_x (nz, ny, nx + 1): h rho c u per unit of zeta on the faces along x (W/(m K)): face i between nodes
        i - 1 and i, the average of the two nodes' values; on the boundary faces 0 and nx linearly extrapolated
        (`_to_faces`);
    flux_y (nz, ny + 1, nx): the same along y;
    flux_z (nz + 1, ny, nx): c W across the layer faces (W/(m^2 K)), face k between nodes k - 1 and k, zero on the
        walls (faces 0 and nz), from the discrete continuity with the column's divergence shared out;
    divergence (ny, nx): D_col = sum_k w_k D_k, the divergence of the column's total flux (W/(m^2 K))."""
    nz, ny, nx = velocity_x.shape
    flux_x = np.empty((nz, ny, nx + 1))
    flux_y = np.empty((nz, ny + 1, nx))
    flux_z = np.zeros((nz + 1, ny, nx))
    divergence = np.empty((ny, nx))
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                flux_x[k, j, i + 1] = max(film[j, i], 0.0) * rho_c[k, j, i] * velocity_x[k, j, i]  # node values
            _to_faces(flux_x[k, j])
        for i in range(nx):
            for j in range(ny):
                flux_y[k, j + 1, i] = max(film[j, i], 0.0) * rho_c[k, j, i] * velocity_y[k, j, i]
            _to_faces(flux_y[k, :, i])
    layer_div = np.empty(nz)
    weights = np.empty(nz)
    for k in range(nz):
        weights[k] = layer_weight(k, nz)
    for j in range(ny):
        for i in range(nx):
            total = 0.0
            for k in range(nz):
                d = (flux_x[k, j, i + 1] - flux_x[k, j, i]) / dx + (flux_y[k, j + 1, i] - flux_y[k, j, i]) / dy
                layer_div[k] = d
                total += weights[k] * d
            divergence[j, i] = total
            w = 0.0
            for k in range(nz - 1):
                w -= weights[k] * (layer_div[k] - total)
                flux_z[k + 1, j, i] = w
    return flux_x, flux_y, flux_z, divergence


@njit(cache=True)
def _face_positions(nz):
    """Where each layer face lies between its two nodes, as a fraction of the node spacing (face k between
    nodes k - 1 and k, k = 1 .. nz - 1): the cell faces bound the widths `layer_weight`."""
    out = np.zeros(nz + 1)
    edge = 0.0
    for k in range(1, nz):
        edge += layer_weight(k - 1, nz)
        out[k] = edge * (nz - 1) - (k - 1)
    return out


@njit(cache=True, error_model="numpy", inline="always")
def _face_term(g, t, t_back, t_near, t_far, leaves, a, b):
    """(a, b) of `_node_form` with the convection through one face along x or y added, from the temperatures of
    the line through it (`_face_value`'s, with the inlet temperature outside the domain): the node's own t, t_back
    behind it, t_near across the face and t_far beyond; g the outward flux over h times the face's length per cell
    area (W/(m^3 K)); `leaves`: the face is on the domain's boundary (where the oil flows out, its value is the
    linear extrapolation)."""
    if g == 0.0:  # no flow through the face
        return a, b
    if g > 0.0:  # outflow: the face carries this node's value and its limited correction
        return a, b - g * (_muscl(t, t_back, t_near, leaves) - t)
    # inflow from the neighbour
    return a - g, b - g * _muscl(t_near, t_far, t, False)


@njit(cache=True, error_model="numpy", inline="always")
def _xy_form(temperature, k, j, i, flux_x, flux_y, rdxh, rdyh, t_inlet):
    """(a, b) of node (k, j, i)'s convection along x and y, face by face (outward flux, the temperatures of the
    line through the face); rdxh, rdyh: 1/(dx h), 1/(dy h). The same numbers as `_face_value` on each face, by
    reading the node's stencil once."""
    nz, ny, nx = temperature.shape
    t = temperature[k, j, i]
    # the inlet temperature outside the domain (`_value`), as a select on an index kept inside rather than a branch to
    # `_value`: bit-identical, and on S1 (513 x 65 x 9) `wall_fluxes` 31.4 -> 4.5 ms, a sweep of every column 38.9 ->
    # 11.7 ms (Numba compiled the branch into code ~7x slower than the fetch itself)
    west2 = temperature[k, j, max(i - 2, 0)] if i >= 2 else t_inlet
    west = temperature[k, j, max(i - 1, 0)] if i >= 1 else t_inlet
    east = temperature[k, j, min(i + 1, nx - 1)] if i + 1 < nx else t_inlet
    east2 = temperature[k, j, min(i + 2, nx - 1)] if i + 2 < nx else t_inlet
    south2 = temperature[k, max(j - 2, 0), i] if j >= 2 else t_inlet
    south = temperature[k, max(j - 1, 0), i] if j >= 1 else t_inlet
    north = temperature[k, min(j + 1, ny - 1), i] if j + 1 < ny else t_inlet
    north2 = temperature[k, min(j + 2, ny - 1), i] if j + 2 < ny else t_inlet
    a, b = _face_term(flux_x[k, j, i + 1] * rdxh, t, west, east, east2, i == nx - 1, 0.0, 0.0)
    a, b = _face_term(-flux_x[k, j, i] * rdxh, t, east, west, west2, i == 0, a, b)
    a, b = _face_term(flux_y[k, j + 1, i] * rdyh, t, south, north, north2, j == ny - 1, a, b)
    return _face_term(-flux_y[k, j, i] * rdyh, t, north, south, south2, j == 0, a, b)


@njit(cache=True, error_model="numpy")
def wall_convection(temperature, flux_x, flux_y, film, dx, dy, t_inlet):
    """(a, b) of `_xy_form` at the two wall nodes of every column, (2, 2, ny, nx) [wall, a or b]: the walls'
    temperatures stay fixed while the columns are swept, and so do these."""
    nz, ny, nx = temperature.shape
    out = np.empty((2, 2, ny, nx))
    for j in range(ny):
        for i in range(nx):
            h = max(film[j, i], 1e-12)
            for side in range(2):
                out[side, 0, j, i], out[side, 1, j, i] = _xy_form(temperature, side * (nz - 1), j, i, flux_x, flux_y,
                                                                  1.0 / (dx * h), 1.0 / (dy * h), t_inlet)
    return out


@njit(cache=True, error_model="numpy")
def fixed_parts(flux_z, source, sensitivity, reference, expansivity_grad, conductivity, film):
    """The parts of the node balances that stay fixed while the columns are swept (and between the sweeps and wall
    fluxes of one film-state update: computed once for all of them): (implicit, explicit, heating, blended), layer
    fields (nz, ny, nx) but blended (nz + 1, ny, nx):

    implicit = sensitivity + max(-beta_T u . grad p, 0): heating linearised about `reference`, expansion cooling;
    explicit = source + sensitivity reference (W/m^3); heating = max(beta_T u . grad p, 0), times T from the
    current iterate (compression heating, explicit); blended = c W min(1, 2/Pe): the flux across a layer face
    times the weight of its central correction (Pe = c |W| dz/k, the cell Péclet number across the film)."""
    nz, ny, nx = source.shape
    implicit = np.empty((nz, ny, nx))
    explicit = np.empty((nz, ny, nx))
    heating = np.empty((nz, ny, nx))
    blended = np.zeros((nz + 1, ny, nx))
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                sig = sensitivity[k, j, i]
                comp = expansivity_grad[k, j, i]  # beta_T (u . grad p), W/(m^3 K) per K of T
                implicit[k, j, i] = sig - min(comp, 0.0)
                explicit[k, j, i] = source[k, j, i] + sig * reference[k, j, i]
                heating[k, j, i] = max(comp, 0.0)
    for j in range(ny):
        for i in range(nx):
            conductance = conductivity[j, i] * (nz - 1) / max(film[j, i], 1e-12)  # k/dz
            for f in range(1, nz):
                z = flux_z[f, j, i]
                blended[f, j, i] = z * min(1.0, CENTRAL_PECLET * conductance / abs(z)) if z != 0.0 else 0.0
    return implicit, explicit, heating, blended


@njit(cache=True, error_model="numpy", inline="always")
def _node_form(temperature, k, j, i, flux_z, blended, implicit, explicit, heating, inverse_width, face_position, a, b,
               inverse_h):
    """Node (k, j, i)'s balance without conduction, convection minus sources (W/m^3), as the linear form
    F = a T_k + lo T_k-1 + up T_k+1 - b: (a, lo, up, b). a, lo, up: the implicit part (upwind convection, heating
    linearised about `reference`, compression cooling); b: sources and the explicit rest (upwind neighbours along
    x and y, the limited and central corrections of the face values from the current iterate). a, b: those of the
    convection along x and y (`_xy_form`); implicit, explicit, heating, blended: `fixed_parts`; inverse_width:
    1/w_k; inverse_h: 1/h of the column (1/m)."""
    nz = temperature.shape[0]
    t = temperature[k, j, i]
    lo = 0.0
    up = 0.0
    rw = inverse_width[k] * inverse_h
    if k < nz - 1:  # face above, outward flux +flux_z
        z = flux_z[k + 1, j, i]
        zb = blended[k + 1, j, i] * rw
        lam = face_position[k + 1]
        t_up = temperature[k + 1, j, i]
        if z >= 0.0:
            b -= zb * lam * (t_up - t)
        else:
            a -= z * rw
            up += z * rw
            b -= zb * (1.0 - lam) * (t - t_up)
    if k > 0:  # face below, outward flux -flux_z
        z = flux_z[k, j, i]
        zb = blended[k, j, i] * rw
        lam = face_position[k]
        t_lo = temperature[k - 1, j, i]
        if z <= 0.0:
            b += zb * (1.0 - lam) * (t_lo - t)
        else:
            a += z * rw
            lo -= z * rw
            b += zb * lam * (t - t_lo)
    a += implicit[k, j, i]
    b += explicit[k, j, i] + heating[k, j, i] * t
    return a, lo, up, b


@njit(cache=True, error_model="numpy", inline="always")
def _forms(temperature, j, i, flux_x, flux_y, flux_z, blended, implicit, explicit, heating, conductivity, film, dx, dy,
           t_inlet, face_position, inverse_width, walls, a, lo, up, b):
    """The linear forms of every node of column (j, i) (in place), the walls' convection along x and y from
    `wall_convection`, the fixed parts from `fixed_parts`; returns (k/dz^2, theta): Numerov's weight
    theta = min(1, 12 k/(dz^2 max a)) over the interior nodes keeps the off-diagonals of the column's matrix
    negative (no overshoot) where convection outweighs conduction across the film (thick inlet films); there the
    scheme tends to the second-order one."""
    nz = temperature.shape[0]
    h = max(film[j, i], 1e-12)
    dz = h / (nz - 1)
    conductance = conductivity[j, i] / dz
    largest = 0.0
    inverse_h = 1.0 / h
    rdxh = inverse_h / dx
    rdyh = inverse_h / dy
    # the convection along x and y of every node first, then the rest of its form: one loop for both was 1.4x slower
    a[0], b[0] = walls[0, 0, j, i], walls[0, 1, j, i]
    a[nz - 1], b[nz - 1] = walls[1, 0, j, i], walls[1, 1, j, i]
    for k in range(1, nz - 1):
        a[k], b[k] = _xy_form(temperature, k, j, i, flux_x, flux_y, rdxh, rdyh, t_inlet)
    for k in range(nz):
        a[k], lo[k], up[k], b[k] = _node_form(temperature, k, j, i, flux_z, blended, implicit, explicit, heating,
                                              inverse_width, face_position, a[k], b[k], inverse_h)
        if 0 < k < nz - 1:
            largest = max(largest, a[k])
    kz = conductance / dz
    theta = min(1.0, 12.0 * kz / largest) if largest > 0.0 else 1.0
    return kz, theta


@njit(cache=True, error_model="numpy", inline="always")
def _column(temperature, j, i, flux_x, flux_y, flux_z, blended, implicit, explicit, heating, conductivity, film, dx, dy,
            t_inlet, face_position, inverse_width, walls, a, lo, up, b, band, rhs):
    """Solve the interior layers of column (j, i) in place; returns the largest change (K).

    Every node k gives its balance as F_k = a_k T_k + lo_k T_k-1 + up_k T_k+1 - b_k (`_node_form`); k T'' = F is
    discretised compactly (Numerov's scheme): k (T_k-1 - 2 T_k + T_k+1)/dz^2 = theta (F_k-1 + F_k+1)/12
    + (1 - theta/6) F_k, fourth order for theta = 1. The wall nodes' F enter with the walls' temperatures fixed.
    The matrix (pentadiagonal) has non-positive off-diagonals and non-negative row sums: Gaussian elimination
    without pivoting."""
    nz = temperature.shape[0]
    n = nz - 2
    kz, theta = _forms(temperature, j, i, flux_x, flux_y, flux_z, blended, implicit, explicit, heating, conductivity,
                       film, dx, dy, t_inlet, face_position, inverse_width, walls, a, lo, up, b)
    side = theta / 12.0
    mid = 1.0 - theta / 6.0
    t_bottom = temperature[0, j, i]
    t_top = temperature[nz - 1, j, i]
    for m in range(n):
        k = m + 1
        # coefficients of T_k-2 .. T_k+2 in row k
        c0 = side * lo[k - 1]
        c1 = -kz + side * a[k - 1] + mid * lo[k]
        c2 = 2.0 * kz + side * up[k - 1] + mid * a[k] + side * lo[k + 1]
        c3 = -kz + mid * up[k] + side * a[k + 1]
        c4 = side * up[k + 1]
        r = side * b[k - 1] + mid * b[k] + side * b[k + 1]
        # the wall nodes are known
        if k - 2 == 0:
            r -= c0 * t_bottom
            c0 = 0.0
        if k - 1 == 0:
            r -= c1 * t_bottom
            c1 = 0.0
        if k + 1 == nz - 1:
            r -= c3 * t_top
            c3 = 0.0
        if k + 2 == nz - 1:
            r -= c4 * t_top
            c4 = 0.0
        band[0, m] = c0
        band[1, m] = c1
        band[2, m] = c2
        band[3, m] = c3
        band[4, m] = c4
        rhs[m] = r
    for m in range(n - 1):  # forward elimination
        f = band[1, m + 1] / band[2, m]
        band[2, m + 1] -= f * band[3, m]
        band[3, m + 1] -= f * band[4, m]
        rhs[m + 1] -= f * rhs[m]
        if m + 2 < n:
            f = band[0, m + 2] / band[2, m]
            band[1, m + 2] -= f * band[3, m]
            band[2, m + 2] -= f * band[4, m]
            rhs[m + 2] -= f * rhs[m]
    change = 0.0
    for m in range(n - 1, -1, -1):
        value = rhs[m]
        if m + 1 < n:
            value -= band[3, m] * temperature[m + 2, j, i]
        if m + 2 < n:
            value -= band[4, m] * temperature[m + 3, j, i]
        value /= band[2, m]
        change = max(change, abs(value - temperature[m + 1, j, i]))
        temperature[m + 1, j, i] = value
    return change


@njit(cache=True, error_model="numpy")
def sweep_columns(temperature, flux_x, flux_y, flux_z, implicit, explicit, heating, blended, conductivity, film, dx, dy,
                  t_inlet, sweeps, tolerance, min_sweeps=0, first_column=0, active_share=ACTIVE_SHARE):
    """Gauss-Seidel sweeps (forward, then backward in x) over the columns from `first_column` on with the fluxes of
    `transport_fluxes` and the fixed parts of `fixed_parts`: at most `sweeps`, stopping once one changes the
    temperatures by less than `tolerance` (K) after the first `min_sweeps`; returns (sweeps done, last change in K,
    columns solved).
    conductivity: k of the film per column, (ny, nx), W/(m K). The columns before `first_column` are held as they
    are (the upstream neighbours of a patch: its inflow, outlet.py). The first sweep solves every column; the next
    ones only the columns whose stencil (ACTIVE_REACH columns along x and y) holds a column that changed by more
    than `active_share` times `tolerance` since it was last solved (ACTIVE_SHARE)."""
    nz, ny, nx = temperature.shape
    face_position = _face_positions(nz)
    a = np.empty(nz)
    lo = np.empty(nz)
    up = np.empty(nz)
    b = np.empty(nz)
    band = np.zeros((5, nz - 2))
    rhs = np.empty(nz - 2)
    walls = wall_convection(temperature, flux_x, flux_y, film, dx, dy, t_inlet)
    inverse_width = 1.0 / layer_weights_array(nz)
    threshold = active_share * tolerance if np.isfinite(tolerance) else 0.0
    stale = np.ones((ny, nx), dtype=np.bool_)  # the column's neighbours moved since it was last solved
    change = 0.0
    done = 0
    solved = 0
    for s in range(sweeps):
        change = 0.0
        for j in range(ny):
            for step in range(nx - first_column):
                i = first_column + step if s % 2 == 0 else nx - 1 - step
                if not stale[j, i]:
                    continue
                stale[j, i] = False
                solved += 1
                c = _column(temperature, j, i, flux_x, flux_y, flux_z, blended, implicit, explicit, heating,
                            conductivity, film, dx, dy, t_inlet, face_position, inverse_width, walls, a, lo, up, b,
                            band, rhs)
                change = max(change, c)
                if c > threshold:
                    for jj in range(max(j - ACTIVE_REACH, 0), min(j + ACTIVE_REACH + 1, ny)):
                        for ii in range(max(i - ACTIVE_REACH, first_column), min(i + ACTIVE_REACH + 1, nx)):
                            if jj != j or ii != i:
                                stale[jj, ii] = True
        done = s + 1
        if done >= min_sweeps and change < tolerance:
            break
    return done, change, solved


@njit(cache=True, error_model="numpy")
def wall_fluxes(temperature, flux_x, flux_y, flux_z, implicit, explicit, heating, blended, conductivity, film, dx, dy,
                t_inlet, flux_1, flux_2):
    """Heat flux from the film into solid 1 (z = 0) and solid 2 (z = h), W/m^2, (ny, nx) in place, consistent with
    the compact scheme of `_column` (the fixed parts from `fixed_parts`):

        q_1 = k (T_1 - T_0)/dz - dz (alpha_0 F_0 + alpha_1 F_1 + alpha_2 F_2),
        alpha = ((9 - 2 theta)/24, (4 + 2 theta)/24, -1/24),

    and its mirror image at z = h. For theta = 1 (Numerov) q_1 is fourth-order accurate (Taylor expansion of
    k T' = k (T_1 - T_0)/dz - dz F/2 - dz^2 F'/6 - dz^3 F''/24 + O(dz^4) with k T'' = F); for any theta the rows
    of `_column` summed with these two fluxes give q_1 + q_2 = -dz sum_k (24 (nz - 1) w_k) F_k: the column's
    conduction is the w-weighted integral of its balances, which makes the discrete energy budget exact."""
    nz, ny, nx = temperature.shape
    face_position = _face_positions(nz)
    a = np.empty(nz)
    lo = np.empty(nz)
    up = np.empty(nz)
    b = np.empty(nz)
    f = np.empty(nz)
    walls = wall_convection(temperature, flux_x, flux_y, film, dx, dy, t_inlet)
    inverse_width = 1.0 / layer_weights_array(nz)
    for j in range(ny):
        for i in range(nx):
            kz, theta = _forms(temperature, j, i, flux_x, flux_y, flux_z, blended, implicit, explicit, heating,
                               conductivity, film, dx, dy, t_inlet, face_position, inverse_width, walls, a, lo, up, b)
            for k in (0, 1, 2, nz - 3, nz - 2, nz - 1):
                value = a[k] * temperature[k, j, i] - b[k]
                if k > 0:
                    value += lo[k] * temperature[k - 1, j, i]
                if k < nz - 1:
                    value += up[k] * temperature[k + 1, j, i]
                f[k] = value
            dz = max(film[j, i], 1e-12) / (nz - 1)
            c = kz * dz  # k/dz
            a0 = (9.0 - 2.0 * theta) / 24.0
            a1 = (4.0 + 2.0 * theta) / 24.0
            a2 = -1.0 / 24.0
            flux_1[j, i] = c * (temperature[1, j, i] - temperature[0, j, i]) - dz * (a0 * f[0] + a1 * f[1] + a2 * f[2])
            flux_2[j, i] = (c * (temperature[nz - 2, j, i] - temperature[nz - 1, j, i])
                            - dz * (a0 * f[nz - 1] + a1 * f[nz - 2] + a2 * f[nz - 3]))


def solve_film_temperature(temperature: np.ndarray, velocity_x: np.ndarray, velocity_y: np.ndarray,
                           source: np.ndarray, sensitivity: np.ndarray, expansivity_grad: np.ndarray,
                           rho_c: np.ndarray, conductivity: np.ndarray, film: np.ndarray, dx: float, dy: float,
                           t_inlet: float, sweeps: int, tolerance: float
                           ) -> tuple[int, float, np.ndarray, np.ndarray]:
    """The interior layer temperatures for fixed surface temperatures (in place): `sweeps` column sweeps at most,
    stopping below `tolerance` (K), heating linearised about the entry temperatures; returns (sweeps done, last
    change, q_1, q_2) with the heat fluxes into the solids of the result (`wall_fluxes`)."""
    fx, fy, fz, _ = transport_fluxes(velocity_x, velocity_y, rho_c, film, dx, dy)
    fixed = fixed_parts(fz, source, sensitivity, temperature.copy(), expansivity_grad, conductivity, film)
    done, change, _ = sweep_columns(temperature, fx, fy, fz, *fixed, conductivity, film, dx, dy, t_inlet, sweeps,
                                    tolerance)
    q1, q2 = np.empty(film.shape), np.empty(film.shape)
    wall_fluxes(temperature, fx, fy, fz, *fixed, conductivity, film, dx, dy, t_inlet, q1, q2)
    return done, change, q1, q2


def sweep_film_temperature(temperature: np.ndarray, velocity_x: np.ndarray, velocity_y: np.ndarray,
                           source: np.ndarray, sensitivity: np.ndarray, expansivity_grad: np.ndarray,
                           rho_c: np.ndarray, conductivity: np.ndarray, film: np.ndarray, dx: float, dy: float,
                           t_inlet: float, sweeps: int, tolerance: float) -> tuple[int, float]:
    """`solve_film_temperature` without the fluxes: (sweeps done, last change)."""
    done, change, _, _ = solve_film_temperature(temperature, velocity_x, velocity_y, source, sensitivity,
                                                expansivity_grad, rho_c, conductivity, film, dx, dy, t_inlet, sweeps,
                                                tolerance)
    return done, change


def wall_heat_flux(temperature: np.ndarray, film: np.ndarray,
                   conductivity: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
    """Heat flux from the film into solid 1 (at z = 0) and solid 2 (at z = h), W/m^2, from the temperatures
    alone: q_1 = k dT/dz|_0, q_2 = -k dT/dz|_h by fourth-order one-sided differences (-25, 48, -36, 16, -3)/(12 dz)
    (second order, (-3, 4, -1)/(2 dz), on three layers), with k per column ((ny, nx), or a scalar; W/(m K)).
    The thermal model uses `wall_fluxes`, consistent with its discrete balance; both are fourth order."""
    nz = temperature.shape[0]
    dz = np.maximum(film, 1e-12) / (nz - 1)
    t = temperature
    if nz >= 5:
        q1 = conductivity * (-25.0 * t[0] + 48.0 * t[1] - 36.0 * t[2] + 16.0 * t[3] - 3.0 * t[4]) / (12.0 * dz)
        q2 = conductivity * (-25.0 * t[-1] + 48.0 * t[-2] - 36.0 * t[-3] + 16.0 * t[-4] - 3.0 * t[-5]) / (12.0 * dz)
        return q1, q2
    q1 = conductivity * (-3.0 * t[0] + 4.0 * t[1] - t[2]) / (2.0 * dz)
    q2 = conductivity * (-3.0 * t[-1] + 4.0 * t[-2] - t[-3]) / (2.0 * dz)
    return q1, q2


def _depth_weights(layers: int, film: np.ndarray) -> np.ndarray:
    """Simpson weights across the film times the film thickness h (m): the integral over z of a layer field."""
    return simpson_weights(layers)[:, None, None] * film[None, :, :]


def dissipated_power(state: FilmState, film: np.ndarray, dx: float, dy: float) -> float:
    """Power dissipated by shear in the film, \\iiint tau . gamma_dot dV (W), on a (ny, nx) grid with film h (m)
    and spacings dx, dy (m); with or without the energy equation (an isothermal Ree-Eyring film too)."""
    return float((state.dissipation * _depth_weights(state.temperature.shape[0], film)).sum() * dx * dy)


@njit(cache=True, error_model="numpy")
def boundary_enthalpy_flux(temperature, flux_x, flux_y, t_inlet, dx, dy):
    """Enthalpy carried out of the domain through its four boundaries, sum_k w_k sum over the boundary faces of
    (h rho c u . n) (T_face - T_inlet) times the face length (W): T_face the scheme's upwind face value (the inlet
    temperature where the oil flows in)."""
    nz, ny, nx = temperature.shape
    total = 0.0
    for k in range(nz):
        layer = 0.0
        for j in range(ny):
            out = flux_x[k, j, nx]  # east
            if out > 0.0:
                layer += out * (_face_value(temperature, k, j, nx - 1, 0, 1, t_inlet) - t_inlet) * dy
            out = -flux_x[k, j, 0]  # west
            if out > 0.0:
                layer += out * (_face_value(temperature, k, j, 0, 0, -1, t_inlet) - t_inlet) * dy
        for i in range(nx):
            out = flux_y[k, ny, i]  # north
            if out > 0.0:
                layer += out * (_face_value(temperature, k, ny - 1, i, 1, 0, t_inlet) - t_inlet) * dx
            out = -flux_y[k, 0, i]  # south
            if out > 0.0:
                layer += out * (_face_value(temperature, k, 0, i, -1, 0, t_inlet) - t_inlet) * dx
        total += layer_weight(k, nz) * layer
    return total


def energy_budget(state: FilmState, film: np.ndarray, dx: float, dy: float, t_inlet: float) -> dict[str, float]:
    """The film's energy balance of a film state on a (ny, nx) grid with film h (m), spacings dx, dy (m) and inlet
    temperature (K), in the discrete form the energy equation is solved in (layer widths w_k, face fluxes; the
    state's rho c and heat fluxes), W:

    heat_generated: dissipation + compression, sum w_k h (tau . gamma_dot + beta_T T u . grad p) dA;
    heat_conducted: into the two solids, sum (q_1 + q_2) dA;
    heat_convected: carried out of the domain by the oil, the enthalpy flux rho c (T - T_0) u h through its
        boundary (`boundary_enthalpy_flux`);
    heat_mass_defect: carried by the mass the full-film layer velocities do not conserve, sum D_col (T_mean - T_0)
        dA with D_col the divergence of the column's heat-capacity flux and T_mean the w-weighted mean temperature
        (the cavitated outlet, where the film ruptures, and the difference between the Reynolds and the layer
        fluxes);
    energy_balance_error: (generated + mass defect - conducted - convected)/generated: zero for a converged
        solution of the discrete equations, up to round-off (what remains measures how far the film state is
        from one: sweeps, outer iterations)."""
    nz = state.temperature.shape[0]
    w = layer_weights(nz)
    temperature = state.temperature
    fx, fy, _, divergence = transport_fluxes(state.velocity_x, state.velocity_y, state.heat_capacity, film, dx, dy)
    depth = w[:, None, None] * np.maximum(film, 0.0)[None, :, :]
    generated = float(((state.dissipation + state.compression) * depth).sum() * dx * dy)
    conducted = float((state.heat_flux_1 + state.heat_flux_2).sum() * dx * dy)
    convected = float(boundary_enthalpy_flux(temperature, fx, fy, t_inlet, dx, dy))
    mean_rise = np.tensordot(w, temperature - t_inlet, axes=1)
    defect = float((divergence * mean_rise).sum() * dx * dy)
    imbalance = (generated + defect - conducted - convected) / generated if generated > 0.0 else 0.0
    return {"heat_generated": generated, "heat_conducted": conducted, "heat_convected": convected,
            "heat_mass_defect": defect, "energy_balance_error": imbalance}

"""Lumped thermal network of one catcher bearing: capacities, conductances, heat partition, steppers.

Nodes (index constants below): journal sleeve, inner ring, ball set, outer ring, housing (with the
ribbon damper and the axial support); ambient at a fixed temperature. The network equation is

    C dT/dt = Q - L T - g_amb (T - T_amb)

with C the node heat capacities [J/K], Q the heat sources [W], L the conductance Laplacian of the
node-to-node links (L_ii = sum_j g_ij, L_ij = -g_ij; symmetric, rows sum to zero, so the links
only move heat) and g_amb the conductances of each node to ambient [W/K] (convection + radiation,
and for the sleeve the path into the rotor if that is not a node). SI units; temperatures in K
(or any offset scale: only differences enter except in radiation).

Capacities (from dimensions, :func:`ring_heat_capacity`, :func:`ball_set_heat_capacity`): m c with
m = rho V; a ring as a plain annulus (groove and chamfers neglected, < 5 % of the volume).

Conductances:
- conduction through a cylindrical shell (Fourier; e.g. Incropera & DeWitt, ch. 3):
  g = 2 pi k L / ln(r_out / r_in); a ring's node sits at the log-mean radius sqrt(r_in r_out), so
  the two half-shells of a ring add up to the whole (:func:`half_ring_conductance`).
- the sleeve-ring clearance as a gas gap: the same shell law with the gas conductivity (no
  convection in a 0.1-0.5 mm gap); while landed, a contact conductance on top (parameter).
- ball-race Hertzian contact: the constriction resistance of an isothermal elliptical contact on a
  half-space, R = K(e)/(2 pi k a) per side (a the major semi-axis, K the complete elliptic integral,
  e the ellipse eccentricity). Circle: R = 1/(4 k a) (Holm; Carslaw & Jaeger), the elliptical form
  follows from the capacitance of an elliptic disk (the electrostatic analogue) and is Yovanovich's
  isothermal ellipse (Yovanovich & Marotta, Heat Transfer Handbook ch. 4, section 4.3.3: the
  section was found, its formula was not legible here; our form reduces to the circle exactly).
  A ball contact = ball side + race side in series; the loaded balls in parallel; plus a floor
  through the lubricant/cage for unloaded balls (parameter, assumed).
- convection g = h A; typical h (Cengel, heat transfer notes, checked): free convection of gases
  2-25 W/m^2K, forced 25-250 W/m^2K.
- radiation as a secant conductance g = eps sigma A (T^2 + T_a^2)(T + T_a), exact for the loss
  eps sigma A (T^4 - T_a^4) at the current T (update it as T changes).

Heat partition of a sliding contact (Blok 1937; Jaeger 1942): both bodies take the heat at the
same (flash) temperature. With the flash temperature of a uniform source of half-width a on body
i, T_i ~ q_i a / (k_i sqrt(c0 + Pe_i)), Pe_i = V_i a / (2 chi_i) (chi = k/(rho c), V_i the speed
of body i's surface relative to the contact zone), equal T_i give the fraction to body 1

    beta_1 = w_1 / (w_1 + w_2),   w_i = k_i sqrt(c0 + Pe_i),  c0 = 4/pi.

High Pe (both surfaces fast): beta_1 = sqrt(k1 rho1 c1 V1) / (sum), Blok's partition, independent
of c0. Pe -> 0: the split of two stationary half-spaces, k1/(k1 + k2). The interpolating form
sqrt(c0 + Pe) with c0 = 4/pi makes the centre temperature of a uniform circular source exact at
Pe = 0 (q a / k); it is Tian & Kennedy's (J. Tribol. 1994) form as we recall it, quoted, not
verified. Used for the sleeve-ring contact (radial slip) and the sleeve-face rub (axial).

Where each dissipating mechanism's heat goes (:func:`heat_sources`, shares are parameters):
- radial slip friction mu F_N |v_s| at the sleeve-bore contact: beta to the sleeve, 1 - beta to the
  inner ring (Blok, above);
- axial face rub (sleeve / rotor shoulder on the inner-ring face): the same rule with the face
  speeds;
- ball drag (Harris-Palmgren) and worn drag: dissipated at the ball-race contacts (rolling with
  micro-slip, lubricant shear): half to the balls, a quarter to each ring by default (equal
  surface speeds and equal steel at a rolling contact give Blok's 50/50 between ball and race;
  the inner/outer split is assumed equal);
- ribbon damper (hysteretic cross term and viscous part) and the outer-race friction on its axial
  support: half to the outer ring, half to the housing (assumed, steel on steel at low speed).

Steppers: backward Euler (first order, unconditionally stable, heat balance exact to round-off
with the loss evaluated at the new temperatures) and the exact exponential step for constant Q
over the step (modal solution of the symmetrised system; the heat lost to ambient over the step is
integrated exactly with phi functions). Both for coast-downs of minutes to hours with large steps.
The right-hand side and backward Euler use loops over arrays only (numba-compilable).
"""

from __future__ import annotations

from dataclasses import dataclass
from math import expm1, log, pi, sqrt

import numpy as np

from user_forces.contact_stress import _nonnegative, _positive, elliptic_ke  # the same argument checks

SLEEVE, INNER, BALLS, OUTER, HOUSING = 0, 1, 2, 3, 4
NODE_NAMES = ("sleeve", "inner_ring", "ball_set", "outer_ring", "housing")
STEFAN_BOLTZMANN = 5.670374419e-8     # W/(m^2 K^4), CODATA 2018 (exact from SI constants)
BLOK_C0 = 4.0 / pi


@dataclass(frozen=True)
class Material:
    density: float            # kg/m^3
    specific_heat: float      # J/(kg K)
    conductivity: float       # W/(m K)
    expansion: float          # 1/K, linear
    emissivity: float = 0.3   # -, machined steel surface (assumed: 0.2-0.4 oxidised/ground steel)

    def __post_init__(self):
        for name in ("density", "specific_heat", "conductivity"):
            v = getattr(self, name)
            if not v > 0.0:
                raise ValueError(f"{name} = {v!r}: must be > 0")
        if not 0.0 <= self.emissivity <= 1.0:
            raise ValueError(f"emissivity = {self.emissivity!r}: must be in [0, 1]")

    @property
    def diffusivity(self):
        return self.conductivity / (self.density * self.specific_heat)


# AISI 52100 (100Cr6): density 7810 kg/m^3 and expansion 11.9e-6/K (annealed, 0-100 C; 12.6e-6
# hardened) checked (stindia / compraco data sheets); conductivity 46.6 W/mK and specific heat
# 475 J/kgK quoted from MatWeb, not verified here.
STEEL_52100 = Material(density=7810.0, specific_heat=475.0, conductivity=46.6, expansion=11.9e-6)
AIR_CONDUCTIVITY = 0.026          # W/(m K) at ~300 K (textbook value, quoted)


# --- capacities -----------------------------------------------------------------------------

def ring_volume(d_in, d_out, width):
    """Annulus volume pi/4 (d_out^2 - d_in^2) width [m^3]."""
    _positive("d_in", d_in)
    _positive("width", width)
    if not d_out > d_in:
        raise ValueError(f"d_out = {d_out!r}: must be larger than d_in = {d_in!r}")
    return 0.25 * pi * (d_out * d_out - d_in * d_in) * width


def ring_heat_capacity(d_in, d_out, width, material):
    """rho c V of a ring [J/K]."""
    return material.density * material.specific_heat * ring_volume(d_in, d_out, width)


def ball_set_heat_capacity(n_balls, ball_diameter, material):
    """Z rho c pi D^3 / 6 [J/K]."""
    if not (isinstance(n_balls, int) and n_balls >= 1):
        raise ValueError(f"n_balls = {n_balls!r}: must be an integer >= 1")
    _positive("ball_diameter", ball_diameter)
    return n_balls * material.density * material.specific_heat * pi * ball_diameter ** 3 / 6.0


# --- conductances -----------------------------------------------------------------------------

def shell_conductance(r_in, r_out, length, conductivity):
    """Radial conduction through a cylindrical shell: 2 pi k L / ln(r_out/r_in) [W/K]."""
    _positive("r_in", r_in)
    _positive("length", length)
    _positive("conductivity", conductivity)
    if not r_out > r_in:
        raise ValueError(f"r_out = {r_out!r}: must be larger than r_in = {r_in!r}")
    return 2.0 * pi * conductivity * length / log(r_out / r_in)


def half_ring_conductance(r_surface, r_in, r_out, length, conductivity):
    """From a ring surface (r_in or r_out) to the ring's node at the log-mean radius [W/K]."""
    rm = sqrt(r_in * r_out)
    if r_surface == r_in:
        return shell_conductance(r_in, rm, length, conductivity)
    if r_surface == r_out:
        return shell_conductance(rm, r_out, length, conductivity)
    raise ValueError(f"r_surface = {r_surface!r}: must be r_in = {r_in!r} or r_out = {r_out!r}")


def constriction_resistance(a, b, conductivity):
    """Isothermal elliptical contact (semi-axes a >= b) on a half-space: K(e)/(2 pi k a) [K/W]."""
    _positive("a", a)
    _positive("b", b)
    _positive("conductivity", conductivity)
    if b > a:
        a, b = b, a
    k_ell = elliptic_ke(1.0 - (b / a) ** 2)[0]
    return k_ell / (2.0 * pi * conductivity * a)


def ball_contacts_conductance(contacts, k_ball, k_race, floor_per_ball=0.0, n_balls=0):
    """Conductance of a ball set to one race [W/K]: the loaded contacts (list of (a, b) semi-axes
    from user_forces.contact_stress) in parallel, each the ball side and the race side in series;
    plus ``floor_per_ball`` [W/K] for each of the ``n_balls`` balls (lubricant / cage path)."""
    _nonnegative("floor_per_ball", floor_per_ball)
    g = floor_per_ball * n_balls
    for a, b in contacts:
        if a > 0.0 and b > 0.0:
            g += 1.0 / (constriction_resistance(a, b, k_ball) + constriction_resistance(a, b, k_race))
    return g


def convection_conductance(h, area):
    """h A [W/K]."""
    _nonnegative("h", h)
    _nonnegative("area", area)
    return h * area


def radiation_conductance(emissivity, area, t_kelvin, t_amb_kelvin):
    """Secant radiation conductance eps sigma A (T^2 + T_a^2)(T + T_a) [W/K] (temperatures in K)."""
    if not 0.0 <= emissivity <= 1.0:
        raise ValueError(f"emissivity = {emissivity!r}: must be in [0, 1]")
    _nonnegative("area", area)
    _positive("t_kelvin", t_kelvin)
    _positive("t_amb_kelvin", t_amb_kelvin)
    return emissivity * STEFAN_BOLTZMANN * area * (t_kelvin ** 2 + t_amb_kelvin ** 2) * (t_kelvin + t_amb_kelvin)


# --- heat partition and sources -------------------------------------------------------------

def blok_partition(v1, v2, half_width, material1, material2):
    """Fraction of a sliding contact's friction heat that goes into body 1 (module docstring).

    v1, v2 : speeds of the two surfaces relative to the contact zone [m/s] (signs ignored)
    half_width : contact half-width a [m] (Hertz)"""
    _positive("half_width", half_width)
    return blok_partition_fast(v1, v2, half_width, material1.conductivity, material1.diffusivity,
                               material2.conductivity, material2.diffusivity)


def blok_partition_fast(v1, v2, half_width, k1, chi1, k2, chi2):
    """:func:`blok_partition` on plain floats (numba leaf): conductivities k [W/mK], diffusivities
    chi [m^2/s]."""
    w1 = k1 * sqrt(BLOK_C0 + abs(v1) * half_width / (2.0 * chi1))
    w2 = k2 * sqrt(BLOK_C0 + abs(v2) * half_width / (2.0 * chi2))
    return w1 / (w1 + w2)


def heat_sources(p_radial_slip, p_axial_rub, p_ball_drag, p_worn_drag, p_ribbon, beta_radial, beta_axial,
                 drag_ball_share=0.5, drag_inner_share=0.25, ribbon_outer_share=0.5):
    """Node heat inputs (sleeve, inner, balls, outer, housing) [W] from the dissipated powers [W].

    beta_radial / beta_axial: sleeve share of the radial-slip / face-rub heat (blok_partition);
    the drag shares: balls, inner ring (the outer ring takes the rest); ribbon: outer ring share
    (the housing the rest). The sum of the returned heats equals the sum of the powers."""
    for name, v in (("p_radial_slip", p_radial_slip), ("p_axial_rub", p_axial_rub), ("p_ball_drag", p_ball_drag),
                    ("p_worn_drag", p_worn_drag), ("p_ribbon", p_ribbon)):
        if not v >= 0.0:
            raise ValueError(f"{name} = {v!r}: a dissipated power must be >= 0")
    for name, v in (("beta_radial", beta_radial), ("beta_axial", beta_axial), ("drag_ball_share", drag_ball_share),
                    ("drag_inner_share", drag_inner_share), ("ribbon_outer_share", ribbon_outer_share)):
        if not 0.0 <= v <= 1.0:
            raise ValueError(f"{name} = {v!r}: a share must be in [0, 1]")
    if drag_ball_share + drag_inner_share > 1.0:
        raise ValueError(f"drag_inner_share = {drag_inner_share!r}: with drag_ball_share = {drag_ball_share!r} "
                         "the shares must not exceed 1")
    return heat_sources_fast(p_radial_slip, p_axial_rub, p_ball_drag, p_worn_drag, p_ribbon, beta_radial, beta_axial,
                             drag_ball_share, drag_inner_share, ribbon_outer_share)


def heat_sources_fast(p_radial_slip, p_axial_rub, p_ball_drag, p_worn_drag, p_ribbon, beta_radial, beta_axial,
                      drag_ball_share, drag_inner_share, ribbon_outer_share):
    """:func:`heat_sources` without checks (numba leaf, per step)."""
    p_drag = p_ball_drag + p_worn_drag
    q_sleeve = beta_radial * p_radial_slip + beta_axial * p_axial_rub
    q_inner = (1.0 - beta_radial) * p_radial_slip + (1.0 - beta_axial) * p_axial_rub + drag_inner_share * p_drag
    q_balls = drag_ball_share * p_drag
    q_outer = (1.0 - drag_ball_share - drag_inner_share) * p_drag + ribbon_outer_share * p_ribbon
    q_housing = (1.0 - ribbon_outer_share) * p_ribbon
    return q_sleeve, q_inner, q_balls, q_outer, q_housing


# --- the network ----------------------------------------------------------------------------

@dataclass(frozen=True)
class ThermalNetwork:
    """Capacities [J/K], links ((i, j, g [W/K]), ...), conductances to ambient [W/K], T_amb."""
    capacity: tuple
    links: tuple
    g_ambient: tuple
    t_ambient: float
    names: tuple = NODE_NAMES

    def __post_init__(self):
        n = len(self.capacity)
        for i, c in enumerate(self.capacity):
            if not c > 0.0:
                raise ValueError(f"capacity[{i}] = {c!r}: must be > 0")
        if len(self.g_ambient) != n:
            raise ValueError(f"g_ambient: {len(self.g_ambient)} values, must be {n} (one per node)")
        if len(self.names) != n:
            raise ValueError(f"names: {len(self.names)} names, must be {n} (one per node)")
        for i, g in enumerate(self.g_ambient):
            if not g >= 0.0:
                raise ValueError(f"g_ambient[{i}] = {g!r}: must be >= 0")
        for i, j, g in self.links:
            if not (0 <= i < n and 0 <= j < n and i != j):
                raise ValueError(f"link ({i}, {j}): node indices must differ and lie in 0..{n - 1}")
            if not g >= 0.0:
                raise ValueError(f"link ({i}, {j}) g = {g!r}: must be >= 0")

    @property
    def n(self):
        return len(self.capacity)

    def arrays(self):
        """(C, L, g_amb) as float arrays: capacity vector, link Laplacian, ambient conductances."""
        n = self.n
        lap = np.zeros((n, n))
        for i, j, g in self.links:
            lap[i, i] += g
            lap[j, j] += g
            lap[i, j] -= g
            lap[j, i] -= g
        return np.array(self.capacity, float), lap, np.array(self.g_ambient, float)


def network_rhs(t_nodes, q, cap, lap, g_amb, t_amb):
    """dT/dt = (Q - L T - g_amb (T - T_amb)) / C (loops only: numba-compilable)."""
    n = t_nodes.shape[0]
    out = np.empty(n)
    for i in range(n):
        s = q[i] - g_amb[i] * (t_nodes[i] - t_amb)
        for j in range(n):
            s -= lap[i, j] * t_nodes[j]
        out[i] = s / cap[i]
    return out


def step_backward_euler(t_nodes, q, cap, lap, g_amb, t_amb, dt):
    """One backward-Euler step: (C/dt + L + diag g) T1 = C/dt T0 + Q + g T_amb.

    Returns (T1, heat lost to ambient over the step = dt sum g (T1 - T_amb)) [K, J]; with it
    sum C (T1 - T0) = dt sum Q - lost holds to round-off (the links only move heat)."""
    n = t_nodes.shape[0]
    a = lap.copy()
    rhs = np.empty(n)
    for i in range(n):
        a[i, i] += cap[i] / dt + g_amb[i]
        rhs[i] = cap[i] / dt * t_nodes[i] + q[i] + g_amb[i] * t_amb
    # Gaussian elimination with partial pivoting, inline so that numba compiles this step alone
    for k in range(n):
        p = k
        for i in range(k + 1, n):
            if abs(a[i, k]) > abs(a[p, k]):
                p = i
        if p != k:
            for j in range(n):
                tmp = a[k, j]
                a[k, j] = a[p, j]
                a[p, j] = tmp
            tmp = rhs[k]
            rhs[k] = rhs[p]
            rhs[p] = tmp
        for i in range(k + 1, n):
            f = a[i, k] / a[k, k]
            for j in range(k, n):
                a[i, j] -= f * a[k, j]
            rhs[i] -= f * rhs[k]
    t1 = np.empty(n)
    for i in range(n - 1, -1, -1):
        s = rhs[i]
        for j in range(i + 1, n):
            s -= a[i, j] * t1[j]
        t1[i] = s / a[i, i]
    lost = 0.0
    for i in range(n):
        lost += dt * g_amb[i] * (t1[i] - t_amb)
    return t1, lost


def _phi1(x):
    return 1.0 if x == 0.0 else -expm1(-x) / x


def _phi2(x):
    if abs(x) < 1e-5:
        return 0.5 - x / 6.0 + x * x / 24.0
    return (x + expm1(-x)) / (x * x)


def step_exact(t_nodes, q, cap, lap, g_amb, t_amb, dt):
    """Exact step of C dT/dt = s - A T (A = L + diag g, s = Q + g T_amb) for Q constant over dt.

    Modal solution of the symmetrised system M = C^-1/2 A C^-1/2 = V diag(lam) V^T, z = V^T C^1/2 T:
    z(dt) = z0 e^(-lam dt) + f dt phi1(lam dt), int z = z0 dt phi1 + f dt^2 phi2 (f = V^T C^-1/2 s,
    phi1(x) = (1 - e^-x)/x, phi2(x) = (x - 1 + e^-x)/x^2; lam = 0 allowed: adiabatic networks).
    Returns (T1, heat lost to ambient over the step, integrated exactly) [K, J]."""
    t_nodes = np.asarray(t_nodes, float)
    cap = np.asarray(cap, float)
    g_amb = np.asarray(g_amb, float)
    sq = np.sqrt(cap)
    a = lap + np.diag(g_amb)
    m = a / np.outer(sq, sq)
    lam, v = np.linalg.eigh(0.5 * (m + m.T))
    lam = np.where(np.abs(lam) < 1e-14 * max(1.0, float(np.max(np.abs(lam)))), 0.0, lam)
    s = np.asarray(q, float) + g_amb * t_amb
    z0 = v.T @ (sq * t_nodes)
    f = v.T @ (s / sq)
    p1 = np.array([_phi1(x * dt) for x in lam])
    p2 = np.array([_phi2(x * dt) for x in lam])
    z1 = z0 * np.exp(-lam * dt) + f * dt * p1
    zint = z0 * dt * p1 + f * dt * dt * p2
    t1 = (v @ z1) / sq
    tint = (v @ zint) / sq
    lost = float(np.sum(g_amb * (tint - t_amb * dt)))
    return t1, lost


def steady_state(q, lap, g_amb, t_amb):
    """T with L T + g (T - T_amb) = Q (needs a path to ambient from every node)."""
    a = lap + np.diag(np.asarray(g_amb, float))
    return np.linalg.solve(a, np.asarray(q, float) + np.asarray(g_amb, float) * t_amb)


# --- the catcher-bearing network builder --------------------------------------------------------

@dataclass(frozen=True)
class CatcherThermalGeometry:
    """Dimensions of one catcher bearing's thermal network [m]; defaults: the rig's 7212 BE.

    Ring dimensions of a 7212 (60 x 110 x 22 mm): inner ring bore 60, shoulder ~75; outer ring
    ~95 / 110 (as rig.toml's race masses); balls as contact_stress.BEARING_7212BE_ASSUMED; sleeve
    59.6 mm OD on a 50 mm seat (assumed), 22 mm engaged. Housing: 2 kg steel share (assumed)."""
    sleeve_d_in: float = 0.050
    sleeve_d_out: float = 0.0596
    sleeve_length: float = 0.030
    inner_d_in: float = 0.060
    inner_d_out: float = 0.075
    outer_d_in: float = 0.095
    outer_d_out: float = 0.110
    width: float = 0.022
    n_balls: int = 15
    ball_diameter: float = 15.875e-3
    housing_capacity: float = 2.0 * 475.0       # J/K: 2 kg of steel (assumed)
    housing_area: float = 0.06                  # m^2 exposed to ambient (assumed)


def catcher_bearing_network(geom=CatcherThermalGeometry(), material=STEEL_52100, t_amb=293.15,
                            g_inner_balls=0.5, g_outer_balls=0.5, h_outer_housing=1000.0,
                            g_sleeve_ring_contact=0.0, g_sleeve_shaft=0.0, g_housing_frame=2.0, h_rotating=30.0,
                            h_still=10.0, k_gap=AIR_CONDUCTIVITY, radiation=True):
    """Five-node network of one catcher bearing (module docstring) with its conductances.

    g_inner_balls / g_outer_balls [W/K]: ball-set contact conductances (ball_contacts_conductance
    for the current ball loads: about 0.06 W/K per ball contact pair at 760 N, so ~0.4 W/K for the
    7 loaded balls at F_r = 2 kN; default 0.5 with a small lubricant floor, assumed). h_outer_housing
    [W/m^2K]: outer ring to housing through the ribbon (assumed; a ribbon touches on its wave
    crests). g_sleeve_ring_contact [W/K]: the landed contact on top of the gas gap.
    g_sleeve_shaft [W/K]: sleeve into the rotor, counted to ambient (the rotor as a large sink).
    g_housing_frame [W/K]: housing into the machine frame, counted to ambient (assumed).
    h_rotating / h_still: convection of the rings' exposed faces / the housing (Cengel's ranges).
    radiation: add each exposed surface's radiation linearised at ambient, 4 eps sigma T_a^3 A
    (~1.8 W/m^2K at 293 K, eps 0.3; use radiation_conductance at the current T when hot)."""
    m = material
    k = m.conductivity
    c_sleeve = ring_heat_capacity(geom.sleeve_d_in, geom.sleeve_d_out, geom.sleeve_length, m)
    c_inner = ring_heat_capacity(geom.inner_d_in, geom.inner_d_out, geom.width, m)
    c_balls = ball_set_heat_capacity(geom.n_balls, geom.ball_diameter, m)
    c_outer = ring_heat_capacity(geom.outer_d_in, geom.outer_d_out, geom.width, m)
    r_si, r_so = 0.5 * geom.sleeve_d_in, 0.5 * geom.sleeve_d_out
    r_ii, r_io = 0.5 * geom.inner_d_in, 0.5 * geom.inner_d_out
    r_oi, r_oo = 0.5 * geom.outer_d_in, 0.5 * geom.outer_d_out
    # sleeve node -> its surface, gap (+ contact), inner ring surface -> its node: in series
    g_gap = shell_conductance(r_so, r_ii, min(geom.sleeve_length, geom.width), k_gap) + g_sleeve_ring_contact
    r_sr = (1.0 / half_ring_conductance(r_so, r_si, r_so, geom.sleeve_length, k) + 1.0 / g_gap
            + 1.0 / half_ring_conductance(r_ii, r_ii, r_io, geom.width, k))
    r_ib = 1.0 / half_ring_conductance(r_io, r_ii, r_io, geom.width, k) + 1.0 / g_inner_balls
    r_bo = 1.0 / g_outer_balls + 1.0 / half_ring_conductance(r_oi, r_oi, r_oo, geom.width, k)
    g_oh_contact = h_outer_housing * pi * geom.outer_d_out * geom.width
    r_oh = 1.0 / half_ring_conductance(r_oo, r_oi, r_oo, geom.width, k) + 1.0 / g_oh_contact
    face = lambda d_in, d_out: 2.0 * 0.25 * pi * (d_out * d_out - d_in * d_in)
    areas = (face(geom.sleeve_d_in, geom.sleeve_d_out), face(geom.inner_d_in, geom.inner_d_out), 0.0,
             face(geom.outer_d_in, geom.outer_d_out), geom.housing_area)
    h_conv = (h_rotating, h_rotating, 0.0, h_still, h_still)
    h_rad = 4.0 * m.emissivity * STEFAN_BOLTZMANN * t_amb ** 3 if radiation else 0.0
    extra = (g_sleeve_shaft, 0.0, 0.0, 0.0, g_housing_frame)
    g_amb = tuple(convection_conductance(h + (h_rad if a > 0.0 else 0.0), a) + e
                  for h, a, e in zip(h_conv, areas, extra))
    links = ((SLEEVE, INNER, 1.0 / r_sr), (INNER, BALLS, 1.0 / r_ib), (BALLS, OUTER, 1.0 / r_bo),
             (OUTER, HOUSING, 1.0 / r_oh))
    return ThermalNetwork(capacity=(c_sleeve, c_inner, c_balls, c_outer, geom.housing_capacity), links=links,
                          g_ambient=g_amb, t_ambient=t_amb)

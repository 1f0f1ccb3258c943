"""Thermal growth of a catcher bearing and its feedback on clearance, preload and drag; runaway.

Growth (linear expansion of a free body at uniform temperature rise dT): any diameter grows by
alpha d dT (a free ring keeps its shape: bore, raceway and outside diameter all grow alike).

Internal (diametral) clearance of the ball bearing, measured at the groove bottoms
(d_i = d_m - D, d_o = d_m + D; Harris & Kotzalas ch. 2 define P_d = d_o - d_i - 2D):

    dP_d = alpha_o d_o dT_o - alpha_i d_i dT_i - 2 alpha_b D dT_b

so an inner ring and balls hotter than the outer ring eat the clearance (the usual case: the
landed sleeve heats the inner ring, the outer ring is cooled by the housing).

Catcher (journal-to-inner-ring) radial clearance: c = r_bore - r_sleeve,

    dc = alpha_ring r_bore dT_inner - alpha_sleeve r_sleeve dT_sleeve.

Preload once the clearance is consumed (angular-contact geometry, Harris & Kotzalas ch. 2-3):
the groove curvature centres are A0 = (f_i + f_o - 1) D apart along the free contact angle a0.
With a (signed) diametral clearance P_d the radial distance of the centres is
R = A0 cos a0 + P_d/2; with the rings pushed apart axially by s the axial one is X = A0 sin a0 + s.
Each ball is compressed by delta_n = A0 - sqrt(R^2 + X^2) (> 0 only when P_d < 0) at the contact
angle a = atan(X / R) and carries Q = K_n delta_n^1.5 (ball_stiffness_kn, Hertz). The uniform
preload is Z Q (its radial parts cancel); its axial resultant F_a = Z Q sin a pushes the rings
apart against the axial mounting of stiffness k_axial: F_a = k_axial s (rigid mounting: s = 0;
to first order delta_n = -P_d/2 cos a0). A soft axial spring lets the rings slide apart and
relieves most of the growth: the reason catcher bearings are spring-mounted axially.

Drag with preload: the preload's axial resultant adds to the axial load of the Harris-Palmgren
law (user_forces.ball_bearing.harris_palmgren_fast, called, not modified): F_a,total = F_a,ext +
F_a,preload (superposition of the axial loads; the radial load F_r unchanged). With F_beta =
0.9 F_a cot a - 0.1 F_r and f1 ~ F_s^0.33 the torque rises as F_a^1.33 ~ delta_n^2 beyond the
catalogue floors.

Runaway. At steady state the drag power P = |omega T(T_nodes)| must equal what the network
carries away; write P_out(P) = the drag power evaluated at the steady temperatures of the network
heated by the fixed heat Q_fixed plus P (split over the nodes as user_forces.thermal's
heat_sources does). A steady state is a fixed point P* = P_out(P*); it is stable when the loop
gain G = dP_out/dP < 1 there: one watt more of drag heats the rings, the growth adds preload, and
the preload adds G watts of drag. Because P_out grows like delta_n^2 while the losses grow
linearly, G grows with temperature: above a critical fixed heat (or speed) the curve P_out(P)
no longer meets the line P, the fixed points merge at G = 1 (a saddle-node) and the bearing runs
away: temperature and torque rise until seizure. ``steady_with_feedback`` finds the stable fixed
point or reports runaway; ``transient_with_feedback`` integrates the network with the feedback
and reports the runaway time (temperature above a limit).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from math import atan2, cos, degrees, inf, radians, sin, sqrt

import numpy as np

from user_forces.ball_bearing import harris_palmgren_fast
from user_forces.contact_stress import ball_stiffness_kn
from user_forces.thermal import BALLS, INNER, OUTER, heat_sources, steady_state, step_backward_euler


def _positive(name, value):
    if not value > 0.0:
        raise ValueError(f"{name} = {value!r}: must be > 0")


def linear_growth(length, alpha, delta_t):
    """alpha L dT [m] (free body, uniform temperature rise dT [K])."""
    _positive("length", length)
    if not alpha >= 0.0:
        raise ValueError(f"alpha = {alpha!r}: must be >= 0")
    return alpha * length * delta_t


def internal_clearance_change(pitch_diameter, ball_diameter, dt_inner, dt_outer, dt_ball,
                              alpha_inner, alpha_outer=None, alpha_ball=None):
    """dP_d [m] = alpha_o d_o dT_o - alpha_i d_i dT_i - 2 alpha_b D dT_b (groove bottoms)."""
    _positive("pitch_diameter", pitch_diameter)
    _positive("ball_diameter", ball_diameter)
    a_o = alpha_inner if alpha_outer is None else alpha_outer
    a_b = alpha_inner if alpha_ball is None else alpha_ball
    d_i = pitch_diameter - ball_diameter
    d_o = pitch_diameter + ball_diameter
    return a_o * d_o * dt_outer - alpha_inner * d_i * dt_inner - 2.0 * a_b * ball_diameter * dt_ball


def journal_clearance_change(r_bore, r_sleeve, dt_inner, dt_sleeve, alpha_ring, alpha_sleeve=None):
    """dc [m] = alpha_ring r_bore dT_inner - alpha_sleeve r_sleeve dT_sleeve."""
    _positive("r_bore", r_bore)
    _positive("r_sleeve", r_sleeve)
    a_s = alpha_ring if alpha_sleeve is None else alpha_sleeve
    return alpha_ring * r_bore * dt_inner - a_s * r_sleeve * dt_sleeve


def thermal_preload(clearance_diametral, geom, k_n=None, k_axial=inf):
    """Preload of a ball set whose diametral clearance is ``clearance_diametral`` [m] (negative =
    interference), rings held axially by a mounting of stiffness ``k_axial`` [N/m] (inf = rigid).

    Returns (Q per ball [N], F_a axial resultant [N], contact angle [deg], delta_n [m], s [m]).
    Checks its input, then :func:`thermal_preload_fast`."""
    if k_n is None:
        k_n = ball_stiffness_kn(geom)
    _positive("k_n", k_n)
    _positive("k_axial", k_axial)
    q, fa, alpha, delta, s = thermal_preload_fast(
        clearance_diametral, geom.n_balls, radians(geom.contact_angle_deg),
        (geom.f_inner + geom.f_outer - 1.0) * geom.ball_diameter, k_n, k_axial)
    return q, fa, degrees(alpha), delta, s


def thermal_preload_fast(clearance_diametral, n_balls, contact_angle_rad, a0, k_n, k_axial):
    """:func:`thermal_preload` without checks (numba leaf); a0 = (f_i + f_o - 1) D [m].

    Returns (Q, F_a, contact angle [rad], delta_n, s). With a spring, F_a(s) falls as the rings
    move apart while k s rises: one crossing in [0, s_free], found by bisection."""
    ca = cos(contact_angle_rad)
    sa = sin(contact_angle_rad)
    r = a0 * ca + 0.5 * clearance_diametral

    def at(s):
        x = a0 * sa + s
        delta = a0 - sqrt(r * r + x * x)
        alpha = atan2(x, r)
        if delta <= 0.0:
            return 0.0, 0.0, alpha, 0.0
        q = k_n * delta ** 1.5
        return q, n_balls * q * sin(alpha), alpha, delta

    q, fa, alpha, delta = at(0.0)
    if fa == 0.0 or k_axial == inf:
        return q, fa, alpha, delta, 0.0
    s_free = sqrt(max(a0 * a0 - r * r, 0.0)) - a0 * sa
    lo, hi = 0.0, max(s_free, 0.0)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if at(mid)[1] > k_axial * mid:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-16 + 1e-14 * hi:
            break
    s = 0.5 * (lo + hi)
    q, fa, alpha, delta = at(s)
    return q, fa, alpha, delta, s


def preloaded_drag_torque(omega_race_rel, f_radial, f_axial_ext, f_axial_preload, hp_constants):
    """Harris-Palmgren drag torque [N m] with the preload's axial resultant added to the axial load
    (user_forces.ball_bearing.harris_palmgren_fast with its constants ``hp_constants``)."""
    if not f_axial_preload >= 0.0:
        raise ValueError(f"f_axial_preload = {f_axial_preload!r}: must be >= 0")
    return harris_palmgren_fast(omega_race_rel, f_radial, abs(f_axial_ext) + f_axial_preload, hp_constants)


@dataclass(frozen=True)
class FeedbackModel:
    """A catcher bearing at constant speed and load, with its thermal network and geometry.

    clearance0: cold mounted diametral clearance [m]; t_mount: the temperature at which it holds
    [K]; alpha: linear expansion of rings and balls [1/K]; drag shares as heat_sources."""
    network: object                 # user_forces.thermal.ThermalNetwork
    geom: object                    # user_forces.contact_stress.BallBearingGeometry
    hp_constants: tuple             # user_forces.ball_bearing.harris_palmgren_constants(...)
    omega: float                    # relative race speed [rad/s]
    f_radial: float                 # N
    f_axial: float = 0.0            # N, external
    clearance0: float = 10.0e-6     # m
    t_mount: float = 293.15         # K
    alpha: float = 11.9e-6          # 1/K
    k_axial: float = inf            # N/m
    drag_ball_share: float = 0.5
    drag_inner_share: float = 0.25
    k_n: float = field(default=0.0)

    def __post_init__(self):
        if not self.f_radial >= 0.0:
            raise ValueError(f"f_radial = {self.f_radial!r}: must be >= 0")
        if not self.alpha >= 0.0:
            raise ValueError(f"alpha = {self.alpha!r}: must be >= 0")
        _positive("k_axial", self.k_axial)
        _positive("t_mount", self.t_mount)
        if self.k_n == 0.0:
            object.__setattr__(self, "k_n", ball_stiffness_kn(self.geom))


def drag_state(model, t_nodes):
    """(drag power [W], torque [N m], clearance [m], preload F_a [N]) at node temperatures [K]."""
    g = model.geom
    dpd = internal_clearance_change(g.pitch_diameter, g.ball_diameter, t_nodes[INNER] - model.t_mount,
                                    t_nodes[OUTER] - model.t_mount, t_nodes[BALLS] - model.t_mount, model.alpha)
    pd = model.clearance0 + dpd
    fa_pre = thermal_preload_fast(pd, g.n_balls, radians(g.contact_angle_deg),
                                  (g.f_inner + g.f_outer - 1.0) * g.ball_diameter, model.k_n,
                                  model.k_axial)[1] if pd < 0.0 else 0.0
    torque = preloaded_drag_torque(model.omega, model.f_radial, model.f_axial, fa_pre, model.hp_constants)
    return abs(torque * model.omega), torque, pd, fa_pre


def _heat(model, q_fixed, p_drag):
    q = np.array(heat_sources(0.0, 0.0, p_drag, 0.0, 0.0, 0.0, 0.0, model.drag_ball_share, model.drag_inner_share))
    return q + np.asarray(q_fixed, float)


def steady_with_feedback(model, q_fixed, t_limit=473.15, p_cap=2.0e4, max_iter=20000):
    """Stable steady state of the network heated by ``q_fixed`` (per node) plus its own drag.

    Returns dict(status='stable' | 'runaway' | 'overheat', p_drag, t_nodes, loop_gain, clearance,
    preload). 'overheat': the fixed heat with the cold drag alone already takes a node above
    ``t_limit`` (too much heat, whatever the feedback). 'runaway': otherwise, and P_out(P) > P for
    every drag power P whose steady temperatures stay below
    ``t_limit`` [K] (default 200 C: AISI 52100 is tempered and dimensionally stabilised at
    150-200 C, beyond that it softens; the preload geometry also stops being meaningful once the
    growth exceeds the groove-centre distance). ``p_cap`` [W] bounds the drag power; the monotone
    iteration stops after ``max_iter`` steps (only right at the fold, where the gain -> 1: reported
    as runaway)."""
    cap, lap, g_amb = model.network.arrays()
    t_amb = model.network.t_ambient

    def p_out(p):
        t = steady_state(_heat(model, q_fixed, p), lap, g_amb, t_amb)
        if float(np.max(t)) > t_limit:
            return inf
        return drag_state(model, t)[0]

    p_cold = drag_state(model, np.full(model.network.n, model.t_mount))[0]
    t_open = steady_state(_heat(model, q_fixed, p_cold), lap, g_amb, t_amb)
    if float(np.max(t_open)) > t_limit:
        return dict(status="overheat", p_drag=None, t_nodes=t_open, loop_gain=None, clearance=None, preload=None)
    # p_out is nondecreasing in P as long as more drag heat eats clearance (the inner ring and the
    # balls warm more than the outer ring: true for this network, whose steady temperatures all
    # rise with any heat input, A^-1 >= 0, and whose outer ring is tied to the housing); then the
    # iteration P <- p_out(P) from P = 0 rises monotonically to the smallest fixed point -- the
    # stable one -- or leaves the temperature limit (p_out = inf) when there is none. Grid scans
    # miss it near the fold, where the stable and the unstable roots merge.
    p = 0.0
    root = None
    for _ in range(max_iter):
        p_new = p_out(p)
        if p_new == inf or p_new > p_cap:
            break
        if abs(p_new - p) <= 1e-10 * max(p_new, 1.0):
            root = p_new
            break
        p = p_new
    if root is None:
        t = steady_state(_heat(model, q_fixed, min(p, p_cap)), lap, g_amb, t_amb)
        return dict(status="runaway", p_drag=None, t_nodes=t, loop_gain=None, clearance=None, preload=None)
    t = steady_state(_heat(model, q_fixed, root), lap, g_amb, t_amb)
    h = 1e-4 * max(root, 1.0)
    gain = (p_out(root + h) - p_out(max(root - h, 0.0))) / (root + h - max(root - h, 0.0))
    _, _, pd, fa = drag_state(model, t)
    return dict(status="stable", p_drag=root, t_nodes=t, loop_gain=gain, clearance=pd, preload=fa)


def transient_with_feedback(model, q_fixed, t_end, dt, t_limit=473.15, t0=None):
    """Backward-Euler integration of the network with the drag heat evaluated at the start of
    each step (explicit coupling of a slow loop: dt must be below the network's fastest time
    constant for the feedback to be resolved). Stops when any node exceeds ``t_limit`` [K].

    Returns dict(times, temps (n_steps+1, n_nodes), p_drag, runaway_time or None)."""
    _positive("t_end", t_end)
    _positive("dt", dt)
    cap, lap, g_amb = model.network.arrays()
    t_amb = model.network.t_ambient
    t = np.full(model.network.n, t_amb) if t0 is None else np.asarray(t0, float).copy()
    times, temps, powers = [0.0], [t.copy()], []
    n = int(round(t_end / dt))
    for k in range(n):
        p = drag_state(model, t)[0]
        powers.append(p)
        t, _ = step_backward_euler(t, _heat(model, q_fixed, p), cap, lap, g_amb, t_amb, dt)
        times.append((k + 1) * dt)
        temps.append(t.copy())
        if float(np.max(t)) > t_limit:
            return dict(times=np.array(times), temps=np.array(temps), p_drag=np.array(powers),
                        runaway_time=(k + 1) * dt)
    return dict(times=np.array(times), temps=np.array(temps), p_drag=np.array(powers), runaway_time=None)


__all__ = ["linear_growth", "internal_clearance_change", "journal_clearance_change", "thermal_preload",
           "thermal_preload_fast",
           "preloaded_drag_torque", "FeedbackModel", "drag_state", "steady_with_feedback",
           "transient_with_feedback"]

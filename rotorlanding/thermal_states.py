"""Thermal states of each catcher bearing, integrated with the landing (issue 18, step 1).

The five-node network of :mod:`user_forces.thermal` (sleeve, inner ring, ball set, outer ring,
housing; ambient fixed) per catcher bearing, driven by the heat that the mechanism registry
(:mod:`rotorlanding.mechanisms`) books per bearing and dissipation entry. This module is the
``post`` hook of the registry's ``catcher_thermal`` mechanism; nothing else calls it.

Heat routing (``Mechanism.heat`` in the registry names a route for every bearing-scope
dissipation entry; the import of the registry checks that none is missing):

- ``sleeve_contact`` (radial slip friction mu F_N |v_s| and the Hunt-Crossley contact damping of
  the sleeve-bore contact): Blok's partition (Blok 1937; :func:`user_forces.thermal.blok_partition_fast`)
  with the surface speeds relative to the contact zone taken as |Omega| r_sleeve (sleeve) and
  |omega_i| r_bore (inner ring) -- the contact zone is taken as moving slowly against both
  surfaces (assumed: true for a rolling-in-place or slowly whirling journal; in a fast backward
  whirl the zone moves and the partition shifts towards 50/50) -- and the half-width of the
  aligned line contact (:func:`user_forces.contact_stress.sleeve_ring_line`, Johnson sec. 4.3,
  length = ring width) at the current normal force. The damping heat takes the same split
  (assumed: it is dissipated in the same contact zone).
- ``face_rub`` (axial rub of the rotor shoulder on the inner-ring face): Blok with the face speeds
  at the mean face radius; half-width = half the radial width of the face annulus (assumed).
  The share into the rotor goes to the sleeve node.
- ``ball_contacts`` (Harris-Palmgren drag, worn drag, ball-set damping, air/grease drag of the
  race): 1/2 ball set, 1/4 inner ring, 1/4 outer ring (``user_forces.thermal.heat_sources``'s
  defaults: Blok's 50/50 between ball and race at equal surface speeds and equal steel; the
  inner/outer split is assumed equal).
- ``outer_support`` (ribbon damper, its cross-coupled friction, the outer race's Coulomb friction
  on its axial support, the races' damping to the housing): 1/2 outer ring, 1/2 housing (assumed).

Rotor-scope entries (windage, rotor damping, axial contact damping) heat the rotor and the air, not
a catcher bearing: they are not routed (``ROTOR_HEAT`` lists them).

Integration: the registry's post-processing already evaluates every power on the stored samples
t_0 < t_1 < ... (every ``solver.output_period``; decimated samples in a coast-down); the energy
ledger integrates them with the trapezoid rule. Here each node's heat power is integrated the same
way, and the network is advanced over each interval [t_k, t_k+1] by the exact solution of
C dT/dt = Q_k - A T + g T_amb with Q_k the interval's mean (trapezoid energy / dt) held constant
(the modal form of ``user_forces.thermal.step_exact``, eigen-decomposed once per bearing). So:

- heat in = the ledger's routed dissipated energy, to round-off (same trapezoid);
- heat in = heat stored sum C (T - T_0) + heat lost to ambient (integrated exactly), to round-off;
- the operator split (mechanics solved, then the one-way thermal update per output interval) holds
  the interval's heat constant: its only error is the timing of the heat within one interval, of
  relative size dt / tau_min on the temperature increment of that interval, with tau_min = 1 /
  lambda_max of C^-1 A the network's fastest time constant (21.8 s on the rig's default network,
  against dt = 1e-4 s landing, <= 0.1 s decimated coast-down rows). ``split_ratio`` = max dt / tau_min
  is reported in the summary; above ``SPLIT_WARN`` the summary warns.

The temperatures are carried states (``Output.carried``): a coast-down chunk starts from the last
stored row of every carried series, the value a resume reads from results.h5 (bit for bit), so a
resumed coast-down continues the same thermal history. The cumulative heat in and heat lost are
carried with them.

Units: temperatures in K inside and in results.h5 (series ``<bearing>_temperature_<node>_k``);
the summary gives them in degC where the key says so.
"""

from __future__ import annotations


import math

import numba
import numpy as np

from user_forces.contact_stress import STEEL_E_STAR, conformal_radius
from user_forces.thermal import (NODE_NAMES, STEEL_52100, CatcherThermalGeometry,
                                 catcher_bearing_network)

SPLIT_WARN = 0.05      # max interval / fastest time constant above which the summary warns
KELVIN_0C = 273.15
ROUTES = ("sleeve_contact", "face_rub", "ball_contacts", "outer_support")
# shares of the routes without a Blok split: (sleeve, inner, balls, outer, housing)
FIXED_SHARES = {"ball_contacts": (0.0, 0.25, 0.5, 0.25, 0.0), "outer_support": (0.0, 0.0, 0.0, 0.5, 0.5)}
NODE_SERIES = tuple(f"temperature_{n}_k" for n in NODE_NAMES)
HEAT_SERIES = ("heat_in_j", "heat_lost_j")
ROUTE_SERIES = tuple(f"heat_{r}_j" for r in ROUTES)
FEEDBACK_SERIES = ("journal_clearance_m", "internal_clearance_m", "thermal_preload_n")


def network_for(laws):
    """The bearing's ThermalNetwork from its resolved laws (``laws.extra`` holds the catcher_thermal
    parameters) and the geometry it shares with the contact laws (sleeve radius, bore radius); the
    rest of the geometry is the rig's 7212 (``CatcherThermalGeometry`` defaults)."""
    x = laws.extra
    geom = CatcherThermalGeometry(sleeve_d_out=2.0 * laws.sleeve_radius, inner_d_in=2.0 * laws.race_radius,
                                  width=x["thermal_width_m"], housing_capacity=x["thermal_housing_capacity_j_k"])
    return catcher_bearing_network(geom, t_amb=x["thermal_ambient_k"], g_inner_balls=x["thermal_g_ball_set_w_k"],
                                   g_outer_balls=x["thermal_g_ball_set_w_k"],
                                   h_outer_housing=x["thermal_h_outer_housing_w_m2k"],
                                   g_housing_frame=x["thermal_g_housing_frame_w_k"])


class ModalStepper:
    """Exact steps of C dT/dt = Q - A T + g T_amb (A = L + diag g) for Q constant over each step:
    the modal solution of ``user_forces.thermal.step_exact`` with the eigen-decomposition done once."""

    def __init__(self, net):
        cap, lap, g = net.arrays()
        self.cap, self.g, self.t_amb = cap, g, float(net.t_ambient)
        self.sq = np.sqrt(cap)
        m = (lap + np.diag(g)) / np.outer(self.sq, self.sq)
        lam, self.vec = np.linalg.eigh(0.5 * (m + m.T))
        self.lam = np.where(np.abs(lam) < 1e-14 * max(1.0, float(np.max(np.abs(lam)))), 0.0, lam)

    @property
    def fastest_time_constant_s(self) -> float:
        return 1.0 / float(np.max(self.lam))

    def run(self, dt: np.ndarray, heat: np.ndarray, t0: np.ndarray):
        """Temperatures after each interval (len(dt) x n) and the heat lost to ambient in each [J];
        ``heat`` (len(dt) x n): the energy into each node over each interval [J]."""
        vec, sq = np.ascontiguousarray(self.vec), self.sq
        n = len(sq)
        dt = np.ascontiguousarray(dt, dtype=float)
        heat = np.ascontiguousarray(heat, dtype=float)
        t0 = np.asarray(t0, float)
        # the compiled loop does not check its indices: a wrong shape must fail here, not read past an array
        if dt.ndim != 1 or heat.shape != (len(dt), n) or t0.shape != (n,):
            raise ValueError(f"ModalStepper.run: dt must be 1-D, heat (len(dt), {n}) and t0 ({n},); got "
                             f"{dt.shape}, {heat.shape}, {t0.shape}")
        if len(dt) and not float(np.min(dt)) > 0.0:
            raise ValueError(f"ModalStepper.run: every interval must be > 0 s (found {float(np.min(dt))!r})")
        s_amb = vec.T @ (self.g * self.t_amb / sq)
        z0 = vec.T @ (sq * t0)
        # one compiled loop: a landing has ~2e4 intervals, and the per-interval numpy calls of a
        # Python loop cost ~0.2 s per bearing (a quarter of a validate member's time)
        return _modal_run(vec, sq, self.lam, self.g, self.t_amb, s_amb, z0, dt, heat)


@numba.njit(cache=True)
def _modal_run(vec, sq, lam, g, t_amb, s_amb, z, dt, heat):
    """The loop of :meth:`ModalStepper.run`: per interval h, each mode j advances by the exact
    solution with the interval's heat held constant, z_j <- z_j e^(-x) + f_j h p1(x), x = lam_j h,
    p1 = (1 - e^(-x)) / x, and its time integral (for the heat lost) uses p2 = (x - 1 + e^(-x)) / x^2;
    both by their series below x = 1e-5 (no cancellation)."""
    n = len(lam)
    nt = len(dt)
    temps = np.empty((nt, n))
    lost = np.empty(nt)
    z = z.copy()
    zint = np.empty(n)
    f = np.empty(n)
    u = np.empty(n)
    for k in range(nt):
        h = dt[k]
        for i in range(n):
            u[i] = heat[k, i] / (h * sq[i])
        for j in range(n):
            acc = 0.0
            for i in range(n):
                acc += vec[i, j] * u[i]
            f[j] = s_amb[j] + acc
        for j in range(n):
            x = lam[j] * h
            if x < 1e-5:
                p1 = 1.0 - x / 2 + x * x / 6
                p2 = 0.5 - x / 6 + x * x / 24
            else:
                em = math.expm1(-x)
                p1 = -em / x
                p2 = (x + em) / (x * x)
            zint[j] = z[j] * h * p1 + f[j] * h * h * p2
            z[j] = z[j] * math.exp(-x) + f[j] * h * p1
        total = 0.0
        for i in range(n):
            ti = 0.0
            ii = 0.0
            for j in range(n):
                ti += vec[i, j] * z[j]
                ii += vec[i, j] * zint[j]
            temps[k, i] = ti / sq[i]
            total += g[i] * (ii / sq[i] - t_amb * h)
        lost[k] = total
    return temps, lost


def blok_sleeve_share(fn, omega, omega_i, laws, width, material=STEEL_52100):
    """Share of the sleeve-bore contact heat that goes into the sleeve, per sample (module docstring)."""
    from .bearing_kernel import blok_sleeve_series

    out = np.empty(len(fn))
    # the half-width of the aligned line contact (sleeve_ring_line) and Blok's partition, compiled;
    # 0.5 where there is no contact (no heat: the value does not matter)
    blok_sleeve_series(np.asarray(fn, dtype=float), np.asarray(omega, dtype=float), np.asarray(omega_i, dtype=float),
                       float(laws.sleeve_radius), float(laws.race_radius),
                       conformal_radius(laws.sleeve_radius, laws.race_radius), float(width), STEEL_E_STAR,
                       material.conductivity, material.diffusivity, out)
    return out


def node_heat_power(ev, laws) -> np.ndarray:
    """Heat power into each node (n_samples x 5) [W] from the current bearing's booked powers."""
    from .bearing_kernel import blok_face_series
    from .mechanisms import heat_routes

    k = ev.kin
    pre = ev.bearing.name + "_"
    nt = len(ev.t)
    q = np.zeros((nt, len(NODE_NAMES)))
    routes = heat_routes()
    width = laws.extra["thermal_width_m"]
    beta_r = beta_a = None
    for entry, p in ev.bpower.items():
        route = routes[entry]
        if not np.any(p):
            continue
        if route == "sleeve_contact":
            if beta_r is None:
                beta_r = blok_sleeve_share(ev.series[pre + "normal_force_n"], np.abs(k["omega"]), np.abs(k["wi"]),
                                           laws, width)
            q[:, 0] += beta_r * p
            q[:, 1] += (1.0 - beta_r) * p
        elif route == "face_rub":
            if beta_a is None:
                r_m = 0.5 * (laws.face_inner_radius + laws.face_outer_radius)
                half = 0.5 * (laws.face_outer_radius - laws.face_inner_radius)
                m = STEEL_52100
                beta_a = np.empty(nt)
                blok_face_series(np.asarray(k["omega"], dtype=float), np.asarray(k["wi"], dtype=float), r_m, half,
                                 m.conductivity, m.diffusivity, beta_a)
            q[:, 0] += beta_a * p
            q[:, 1] += (1.0 - beta_a) * p
        else:
            q += np.outer(p, FIXED_SHARES[route])
    return q


def post_thermal(ev, laws) -> None:
    """The ``catcher_thermal`` mechanism's hook: integrate the bearing's network over the samples."""
    from .mechanisms import heat_routes

    from dataclasses import replace

    pre = ev.bearing.name + "_"
    # the network of the cold geometry: with thermal feedback the solver's laws carry the grown
    # sleeve and bore, but the rings' masses, hence their heat capacities, do not change (the
    # grown radii made heat in = stored + lost miss by 2.9e-4 in a 200 degC run)
    cold = replace(laws, sleeve_radius=ev.bearing.params.sleeve_radius, race_radius=ev.bearing.params.race_radius)
    net = network_for(cold)
    stepper = ModalStepper(net)
    carry = ev.carry or {}
    if pre + NODE_SERIES[0] in carry:
        t0 = np.array([carry[pre + s] for s in NODE_SERIES])
        in0, lost0 = carry[pre + "heat_in_j"], carry[pre + "heat_lost_j"]
    else:
        t0 = np.full(net.n, net.t_ambient)
        in0 = lost0 = 0.0
    qn = node_heat_power(ev, laws)
    dt = np.diff(ev.t)
    heat = 0.5 * (qn[1:] + qn[:-1]) * dt[:, None]   # trapezoid: the ledger's rule
    if len(dt) and float(np.min(dt)) <= 0.0:
        raise ValueError(f"time_s: samples must increase (found a step of {float(np.min(dt))!r} s)")
    temps, lost = stepper.run(dt, heat, t0) if len(dt) else (np.empty((0, net.n)), np.empty(0))
    temps = np.vstack([t0, temps])
    for j, s in enumerate(NODE_SERIES):
        ev.out(s, temps[:, j])
    ev.out("heat_in_j", in0 + np.concatenate([[0.0], np.cumsum(heat.sum(axis=1))]))
    ev.out("heat_lost_j", lost0 + np.concatenate([[0.0], np.cumsum(lost)]))
    # the heat per route (which mechanisms heat the bearing), trapezoid like the ledger
    routes = heat_routes()
    for r, name in zip(ROUTES, ROUTE_SERIES):
        p = sum((ev.bpower[e] for e in ev.bpower if routes[e] == r), np.zeros(len(ev.t)))
        e0 = carry.get(pre + name, 0.0) if pre + NODE_SERIES[0] in carry else 0.0
        ev.out(name, e0 + np.concatenate([[0.0], np.cumsum(0.5 * (p[1:] + p[:-1]) * dt)]))


def bearing_summary(spec, b, t, series: dict) -> dict:
    """The summary's ``thermal`` entry of one bearing (units in the keys): peak and final node
    temperatures [degC], heat in / stored / lost over the samples [J], the balance error, the
    network's fastest time constant and the operator split's ratio."""
    pre = b.name + "_"
    net = network_for(b.laws)
    cap = np.array(net.capacity)
    temps = np.column_stack([series[pre + s] for s in NODE_SERIES])
    heat_in = float(series[pre + "heat_in_j"][-1] - series[pre + "heat_in_j"][0])
    lost = float(series[pre + "heat_lost_j"][-1] - series[pre + "heat_lost_j"][0])
    stored = float(np.sum(cap * (temps[-1] - temps[0])))
    tau = ModalStepper(net).fastest_time_constant_s
    dt_max = float(np.max(np.diff(t))) if len(t) > 1 else 0.0
    peak = np.max(temps, axis=0)
    i_peak = int(np.argmax(peak))
    heat_by_route = {r: float(series[pre + n][-1] - series[pre + n][0]) for r, n in zip(ROUTES, ROUTE_SERIES)
                     if pre + n in series}
    return {
        "heat_by_route_j": heat_by_route,
        "max_temperature_degc": {n: float(v - KELVIN_0C) for n, v in zip(NODE_NAMES, peak)},
        "final_temperature_degc": {n: float(v - KELVIN_0C) for n, v in zip(NODE_NAMES, temps[-1])},
        "hottest_node": NODE_NAMES[i_peak],
        "t_hottest_s": float(t[int(np.argmax(temps[:, i_peak]))]),
        "ambient_degc": float(net.t_ambient - KELVIN_0C),
        "heat_in_j": heat_in, "heat_stored_j": stored, "heat_lost_j": lost,
        "balance_error_relative": abs(heat_in - stored - lost) / heat_in if heat_in > 0 else 0.0,
        "fastest_time_constant_s": tau, "max_interval_s": dt_max, "split_ratio": dt_max / tau,
        **_feedback(spec, b, t, series),
    }


def _feedback(spec, b, t, series) -> dict:
    from .mechanisms import thermal_feedback_active
    from .thermal_feedback import summary as feedback_summary

    if not thermal_feedback_active(spec, b.laws):
        return {}
    return {"feedback": feedback_summary(t, series, b.name, b.laws)}


def summary(spec, t, series: dict) -> dict | None:
    """Per-bearing thermal summaries of the bearings whose network is active (None: none is)."""
    from .mechanisms import thermal_active

    out = {b.name: bearing_summary(spec, b, t, series) for b in spec.bearings if thermal_active(spec, b.laws)}
    return out or None


def split_warnings(thermal: dict | None) -> list[str]:
    out = []
    for name, th in (thermal or {}).items():
        if th["split_ratio"] > SPLIT_WARN:
            out.append(f"{name}: thermal output interval {th['max_interval_s']:.3g} s is {th['split_ratio']:.2f} of the "
                       f"network's fastest time constant ({th['fastest_time_constant_s']:.3g} s): temperatures are "
                       f"lagged by up to one interval (limit {SPLIT_WARN})")
    return out


__all__ = ["ModalStepper", "network_for", "node_heat_power", "post_thermal", "bearing_summary", "summary",
           "ROUTES", "NODE_SERIES", "HEAT_SERIES", "KELVIN_0C"]


def file_summary(h5, spec) -> dict | None:
    """:func:`summary` from an open results.h5 (a coast-down's decimated rows): reads the time and
    the carried thermal series only."""
    from .mechanisms import thermal_active

    names = [b.name + "_" + s for b in spec.bearings
             for s in NODE_SERIES + HEAT_SERIES + ROUTE_SERIES + FEEDBACK_SERIES]
    if not any(thermal_active(spec, b.laws) for b in spec.bearings) or any(f"series/{n}" not in h5 for n in names):
        return None
    t = h5["time_s"][()]
    if len(t) < 2:
        return None
    series = {n: h5[f"series/{n}"][()] for n in names}
    return summary(spec, t, series)


def format_lines(thermal: dict | None) -> list[str]:
    """One line per bearing for the command line's summary."""
    out = []
    for name, th in (thermal or {}).items():
        hot = th["hottest_node"]
        out.append(f"{name} thermal: hottest {hot.replace('_', ' ')} {th['max_temperature_degc'][hot]:.2f} degC "
                   f"(ambient {th['ambient_degc']:.1f}); inner ring {th['max_temperature_degc']['inner_ring']:.2f}, "
                   f"balls {th['max_temperature_degc']['ball_set']:.2f}, outer ring "
                   f"{th['max_temperature_degc']['outer_ring']:.2f} degC; heat in {th['heat_in_j']:.1f} J = stored "
                   f"{th['heat_stored_j']:.1f} + lost {th['heat_lost_j']:.2f} J")
        fb = th.get("feedback")
        if fb:
            out.append(f"{name} thermal feedback: internal clearance down to {fb['min_internal_clearance_m'] * 1e6:.2f} um, "
                       f"journal clearance {fb['min_journal_clearance_m'] * 1e6:.1f} um, preload up to "
                       f"{fb['max_thermal_preload_n']:.1f} N; " + (f"RUNAWAY at {fb['t_runaway_s']:.3f} s "
                       f"({fb['runaway_reason']})" if fb["runaway"] else
                       f"no runaway (limit {fb['runaway_limit_degc']:.0f} degC)"))
    return out

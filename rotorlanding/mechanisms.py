"""The mechanism registry and the output schema: every physical mechanism of the landing model in
one entry, and every output series declared once, with its unit.

A :class:`Mechanism` names what acts (a law of ``user_forces``), where (the coordinates it acts
on), when (its effect switches, resolved once in :mod:`rotorlanding.params`), what it does to the
energy balance (dissipation entries, input-work entries, potential and kinetic energy), and which
output series it declares (:class:`Output`: name, unit, per bearing or not). Consumers loop over
:data:`REGISTRY` instead of naming mechanisms:

- :func:`rotorlanding.postprocess.evaluate` calls each active mechanism's ``post`` hook on the
  stored states; the energy balance (``energy_summary``) sums :func:`dissipation_entries` and
  :func:`input_entries`;
- :func:`series_units` gives every series its unit (``results.h5``, the coast-down file), so no
  unit is guessed from a name's suffix;
- :func:`rotor_force` is the force on the rotor at a bearing (the sum of the outputs declared with
  ``on_rotor``): the summary's peak contact force, the coast-down's per-chunk peak, the sweep's
  CSV and the force plots read it;
- a mechanism that is not compiled into :mod:`rotorlanding.bearing_kernel` brings its own solver
  hook (``force``/``jacobian`` over ``forces.BEARING_LOCAL``), its parameters (:class:`Param`, read
  from each ``[bearings.NAME]`` table) and its effect switch (``effect``, added to
  ``scenario.EFFECTS``): :mod:`rotorlanding.exudyn_model` adds one connector per bearing for it,
  :mod:`rotorlanding.forces` adds it to the Python closure.

"Off contributes nothing" (PyBaMM's ``NoSEI`` idea): a mechanism whose ``active(spec, laws)`` is
False is not evaluated, adds no solver object, and its declared series and energy entries are
zeros; no later code branches on the switch. The laws of the built-in mechanisms (radial contact
to outer-race Coulomb) are compiled into the kernel from the same ``user_forces`` functions the
hooks here call (tests/test_bearing_jacobian.py checks the two agree).

Order matters and is the order of this file's :data:`REGISTRY`: rotor-scope hooks run before the
bearing-scope ones (the bearings read the axial force), per bearing in registry order (the ball
drag reads the ball force), and the energy entries are listed (and summed) in registry order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Callable

import numpy as np

from user_forces.axial import axial_force
from user_forces.axial_rub import axial_rub
from user_forces.ball_bearing import ball_force, harris_palmgren_fast, worn_drag_torque, worn_friction_with_derivatives
from user_forces.radial_contact import radial_contact
from user_forces.ribbon import outer_race_friction, ribbon_force
from user_forces.amb import amb_force, unbalance_force
from user_forces.spin import drive_torque, windage_torque, windage_torque_derivative

from .params import OMEGA_REG_HP
from .timoshenko import GRAVITY


@dataclass(frozen=True)
class Output:
    """One output series. A per-bearing series is stored as ``<bearing>_<name>``. ``on_rotor``
    ('y' or 'z'): the series is that component of a force on the rotor at the bearing station.
    ``on_housing`` ('y' or 'z'): that component of a force the housing puts on the bearing's outer
    race, which is what a load cell between bearing and housing reads (:func:`housing_force`)."""

    name: str
    unit: str
    per_bearing: bool = False
    doc: str = ""
    on_rotor: str = ""
    carried: bool = False   # a state: a coast-down chunk starts from the series' last stored row
    on_housing: str = ""


@dataclass(frozen=True)
class Param:
    """A per-bearing input of a mechanism that is not part of ``scenario.Bearing`` (read from
    ``[bearings.NAME].key``, >= 0, > 0 with ``positive``, <= ``upper`` whose reason ``why`` the
    error gives: scenario._param); ``BearingLaws.extra[key]`` holds it, 0 with the effect off."""

    key: str
    unit: str
    default: float
    doc: str = ""
    positive: bool = False           # 0 is no meaningful value (a capacity, a length)
    upper: float = math.inf          # physical maximum, checked at load with ``why`` in the one-line error
    why: str = ""


def _always(spec, laws) -> bool:
    return True


@dataclass(frozen=True)
class Mechanism:
    """One physical mechanism: what acts, where, when, its energy entries and its outputs (the
    module docstring says who reads which field)."""

    name: str
    scope: str                          # "rotor" or "bearing"
    coordinates: tuple[str, ...]        # bearing: forces.BEARING_LOCAL names; rotor: landing coordinate kinds
    laws: tuple[Callable, ...]          # the user_forces functions it evaluates
    switches: tuple[str, ...] = ()      # [effects] names resolved into its parameters (params.py)
    dissipation: tuple[str, ...] = ()   # energy entries: power_<e>_w, dissipated_<e>_j (>= 0)
    inputs: tuple[str, ...] = ()        # energy entries: input_<e>_j (work put in)
    outputs: tuple[Output, ...] = ()
    post: Callable | None = None        # post(ev, laws) on the stored states (see Evaluation)
    heat: tuple = ()                    # (dissipation entry, route of rotorlanding.thermal_states), bearing scope
    retune: Callable | None = None      # retune(laws, bearing name, carry) -> laws: the laws at the carried
                                        # states a coast-down chunk starts from (retuned_spec)
    active: Callable = _always          # active(spec, laws); laws = BearingLaws or RotorLaws
    doc: str = ""
    # a mechanism outside the compiled kernel brings these (empty for the built-in ones):
    effect: str = ""                    # a new [effects] switch it adds (default: default_on)
    default_on: bool = False
    params: tuple[Param, ...] = ()
    force: Callable | None = None       # force(x, q, v) -> 9 forces on BEARING_LOCAL, x = laws.extra
    jacobian: Callable | None = None    # jacobian(x, q, v) -> (dF/dq, dF/dv), 9 x 9 lists


@dataclass
class Evaluation:
    """What a ``post`` hook reads and writes. Per-sample quantities are Python lists (the laws
    take plain floats); contributions are added (``out``, ``dissipated``, ``work``, ``ekin``,
    ``epot``) in registry order, so every element gets its terms in the order one hand-written loop
    over the bearings would add them (which keeps the series bit for bit those of that loop)."""

    spec: object
    t: np.ndarray
    q: np.ndarray
    v: np.ndarray
    series: dict = field(default_factory=dict)      # full series name -> array
    power: dict = field(default_factory=dict)       # dissipation entry -> W
    inputs: dict = field(default_factory=dict)      # input entry -> W
    ekin: np.ndarray | None = None
    epot: np.ndarray | None = None
    bearing: object = None                          # the BearingSpec being evaluated
    kin: dict = field(default_factory=dict)         # the bearing's kinematics (lists), see _kinematics
    bpower: dict = field(default_factory=dict)      # dissipation entry -> W of the current bearing alone
    carry: dict | None = None                       # carried series -> value the samples start from

    def out(self, name: str, values) -> None:
        """Add to a declared series (of the current bearing when per bearing)."""
        self.series[name if self.bearing is None else self.bearing.name + "_" + name] += values

    def dissipated(self, entry: str, values) -> None:
        self.power[entry] += values
        if self.bearing is not None:
            self.bpower[entry] = self.bpower.get(entry, 0.0) + values

    def work(self, entry: str, values) -> None:
        self.inputs[entry] += values


# --------------------------------------------------------------------------------------------
# rotor scope


def _post_windage(ev: Evaluation, rl) -> None:
    """Windage, eq 6: P = -T_wind Omega >= 0."""
    omega = ev.v[:, ev.spec.i_theta]
    tw = np.array([windage_torque(w, rl.c_w1, rl.c_w2) for w in omega])
    ev.dissipated("windage", -tw * omega)


def axial_potential(x: np.ndarray, a) -> np.ndarray:
    """Elastic potential of the piecewise axial law (eqs 4-5), V(x) with -dV/dx = F_ax(x, 0)."""
    k1 = 1.0 / (1.0 / a.k_cb + 1.0 / a.k_ws)
    k2 = 1.0 / (1.0 / a.k_cb + 1.0 / a.k_h)
    s = np.maximum(np.abs(x) - a.cl_ax, 0.0)
    s1 = np.minimum(s, a.delta_m)
    s2 = np.maximum(s - a.delta_m, 0.0)
    return 0.5 * k1 * s1**2 + k1 * a.delta_m * s2 + 0.5 * k2 * s2**2


def _post_axial(ev: Evaluation, rl) -> None:
    """Axial contact, eqs 3-5: its force (read by the bearings' face laws), potential, damping."""
    a = ev.spec.scenario.axial
    x, xd = ev.q[:, ev.spec.i_axial], ev.v[:, ev.spec.i_axial]
    f_el = np.array([axial_force(xi, 0.0, a.cl_ax, a.delta_m, a.k_cb, a.k_ws, a.k_h, a.c_ax) for xi in x])
    f = np.array([axial_force(xi, vi, a.cl_ax, a.delta_m, a.k_cb, a.k_ws, a.k_h, a.c_ax) for xi, vi in zip(x, xd)])
    ev.out("axial_force_n", f)
    ev.dissipated("axial_damping", -(f - f_el) * xd)
    ev.epot += axial_potential(x, a)


def _post_rotor(ev: Evaluation, rl) -> None:
    """The flexible rotor body (eq 1): kinetic energy (lateral, spin, axial), elastic energy and
    gravity of the lateral coordinates, structural damping."""
    spec, n_lat = ev.spec, ev.spec.n_lat
    ql, vl = ev.q[:, :n_lat], ev.v[:, :n_lat]
    omega, xd = ev.v[:, spec.i_theta], ev.v[:, spec.i_axial]
    ev.ekin += 0.5 * np.einsum("ti,ij,tj->t", vl, spec.M, vl) + 0.5 * spec.rotor_polar_inertia * omega**2 \
        + 0.5 * spec.rotor_mass * xd**2
    ev.epot += 0.5 * np.einsum("ti,ij,tj->t", ql, spec.K, ql) - ql @ spec.f_gravity
    ev.dissipated("rotor_damping", np.einsum("ti,ij,tj->t", vl, spec.C, vl))


def _post_amb(ev: Evaluation, rl) -> None:
    """AMB hold before the drop (bias, stiffness, damping; radial and axial): its work."""
    spec, t, q, v = ev.spec, ev.t, ev.q, ev.v
    sc = spec.scenario
    amb_on = (t < sc.amb.t_drop) | (not sc.amb.drop_radial)
    for iy, iz in spec.amb_rows:
        for i in (iy, iz):
            f = amb_force(q[:, i], v[:, i], -spec.f_gravity[i], sc.amb.stiffness, sc.amb.damping)
            ev.work("amb", np.where(amb_on, f * v[:, i], 0.0))
    x, xd = q[:, spec.i_axial], v[:, spec.i_axial]
    thrust = np.array([spec.thrust(ti) for ti in t])
    ax_on = (t < sc.amb.t_drop) | (not sc.amb.drop_axial)
    f = amb_force(x, xd, -thrust, sc.amb.axial_stiffness, sc.amb.axial_damping)
    ev.work("amb", np.where(ax_on, f * xd, 0.0))


def _post_thrust(ev: Evaluation, rl) -> None:
    thrust = np.array([ev.spec.thrust(ti) for ti in ev.t])
    ev.work("thrust", thrust * ev.v[:, ev.spec.i_axial])


def _post_drive(ev: Evaluation, rl) -> None:
    """Constant-speed drive: T = gain (omega0 - Omega), its work T Omega."""
    omega = ev.v[:, ev.spec.i_theta]
    ev.work("drive", drive_torque(omega, rl.drive_gain, rl.omega0) * omega)


def _post_unbalance(ev: Evaluation, rl) -> None:
    """Rotating unbalance force m e Omega^2 at its station: its work on the lateral motion."""
    spec = ev.spec
    sc = spec.scenario
    ry, rz = spec.unbalance_rows
    vl = ev.v[:, :spec.n_lat]
    omega = ev.v[:, spec.i_theta]
    ang = ev.q[:, spec.i_theta] + math.radians(sc.unbalance.phase_deg)
    f = np.array([unbalance_force(w, a, sc.unbalance.magnitude) for w, a in zip(omega.tolist(), ang.tolist())])
    ev.work("unbalance", f[:, 0] * (vl @ ry) + f[:, 1] * (vl @ rz))


# --------------------------------------------------------------------------------------------
# bearing scope: the kinematics every bearing hook reads (lists of floats, one per sample)


def _kinematics(ev: Evaluation, b) -> dict:
    q, v, spec = ev.q, ev.v, ev.spec
    s, r, o = b.i_station, b.i_race, b.i_outer
    f_ax = ev.series["axial_force_n"]
    return {
        "dy": (q[:, s] - q[:, r]).tolist(), "dz": (q[:, s + 1] - q[:, r + 1]).tolist(),
        "dvy": (v[:, s] - v[:, r]).tolist(), "dvz": (v[:, s + 1] - v[:, r + 1]).tolist(),
        "omega": v[:, spec.i_theta].tolist(), "wi": v[:, r + 2].tolist(), "phi_i": q[:, r + 2].tolist(),
        "ey": (q[:, r] - q[:, o]).tolist(), "ez": (q[:, r + 1] - q[:, o + 1]).tolist(),
        "evy": (v[:, r] - v[:, o]).tolist(), "evz": (v[:, r + 1] - v[:, o + 1]).tolist(),
        "oy": q[:, o].tolist(), "oz": q[:, o + 1].tolist(), "ovy": v[:, o].tolist(), "ovz": v[:, o + 1].tolist(),
        "x": q[:, spec.i_axial].tolist(),
        # the face's normal load: the axial contact force where this bearing takes the thrust
        "n_ax": np.abs(f_ax).tolist() if b.laws.axial_face else [0.0] * len(ev.t),
    }


def _post_radial(ev: Evaluation, L) -> None:
    """Radial contact, eqs 10-17: forces, Hertz energy, friction and Hunt-Crossley powers (the
    user_forces law over every sample, compiled: ``bearing_kernel.radial_series``)."""
    from .bearing_kernel import radial_series

    k = ev.kin
    out = np.zeros((len(ev.t), 8))
    radial_series(*(np.asarray(k[key], dtype=float) for key in ("dy", "dz", "dvy", "dvz", "omega", "wi")),
                  float(L.clearance), float(L.k_hertz), float(L.exponent), float(L.k_visc), float(L.mu_rad),
                  float(L.v_reg), float(L.sleeve_radius), float(L.race_radius), out)
    for o, c in zip(RADIAL_CONTACT.outputs, out.T[:5]):
        ev.out(o.name, np.ascontiguousarray(c))
    ev.dissipated("contact_damping", out[:, 6].copy())
    ev.epot += out[:, 7]
    ev.dissipated("radial_friction", out[:, 5].copy())


def _post_rub(ev: Evaluation, L) -> None:
    """Axial rub on the thrust face, eqs 18-21 (acts while the face carries load): the same law as
    ``user_forces.axial_rub``, compiled (``bearing_kernel.rub_series``, equal series; the plain
    loop over the 72-point quadrature took about a third of a landing's post-processing)."""
    from .bearing_kernel import rub_series

    k, b, a = ev.kin, ev.bearing, ev.spec.scenario.axial
    nt, n_lat = len(ev.t), ev.spec.n_lat
    gy, gz, p = np.zeros(nt), np.zeros(nt), np.zeros(nt)
    arr = [np.asarray(k[key], dtype=float) for key in ("dy", "dz", "dvy", "dvz", "omega", "wi")]
    rub_series(*arr, np.ascontiguousarray(ev.q, dtype=float), np.ascontiguousarray(b.tilt_alpha, dtype=float),
               np.ascontiguousarray(b.tilt_beta, dtype=float), n_lat, np.asarray(k["n_ax"], dtype=float),
               np.asarray(k["x"], dtype=float), float(a.cl_ax), float(L.mu_ax), float(L.v_reg_axial),
               float(L.face_inner_radius), float(L.face_outer_radius), gy, gz, p)
    ev.out("rub_force_y_n", gy)
    ev.out("rub_force_z_n", gz)
    ev.dissipated("axial_rub", p)


def _post_balls(ev: Evaluation, L) -> None:
    """Ball set, eq 22: force on the inner race, its elastic energy and damping (compiled:
    ``bearing_kernel.ball_series``)."""
    from .bearing_kernel import ball_series

    k = ev.kin
    out = np.zeros((len(ev.t), 3))
    ball_series(*(np.asarray(k[key], dtype=float) for key in ("ey", "ez", "evy", "evz")), float(L.k_b1),
                float(L.k_b2), float(L.c_b), out)
    ev.out("ball_force_y_n", out[:, 0].copy())
    ev.out("ball_force_z_n", out[:, 1].copy())
    ev.epot += out[:, 2]
    ev.dissipated("ball_damping", L.c_b * (np.square(k["evy"]) + np.square(k["evz"])))


def _post_ball_drag(ev: Evaluation, L) -> None:
    """Harris-Palmgren drag on the inner race, eqs 23-27 (load = ball force and face load; compiled:
    ``bearing_kernel.drag_series``)."""
    from .bearing_kernel import drag_series

    k, pre = ev.kin, ev.bearing.name + "_"
    thp = np.zeros(len(ev.t))
    drag_series(np.asarray(k["wi"], dtype=float), np.asarray(ev.series[pre + "ball_force_y_n"], dtype=float),
                np.asarray(ev.series[pre + "ball_force_z_n"], dtype=float), np.asarray(k["n_ax"], dtype=float),
                float(L.drag_axial_preload), tuple(float(x) for x in L.hp), thp)
    ev.out("drag_torque_nm", thp)
    ev.dissipated("ball_drag", -thp * np.asarray(k["wi"]))


def _post_worn_drag(ev: Evaluation, L) -> None:
    """Worn catcher bearing's drag torque (docs/paper_corrections.md), growing with race angle: the
    load-independent part and the load-proportional one (load = ball force and face load)."""
    k, pre = ev.kin, ev.bearing.name + "_"
    tw = np.array([worn_drag_torque(w, L.worn_drag_torque, OMEGA_REG_HP, phi, L.worn_drag_growth_angle)
                   for w, phi in zip(k["wi"], k["phi_i"])])
    if L.worn_drag_friction > 0:
        by, bz = ev.series[pre + "ball_force_y_n"].tolist(), ev.series[pre + "ball_force_z_n"].tolist()
        fa_pre = L.drag_axial_preload
        tw = tw + np.array([worn_friction_with_derivatives(w, math.hypot(y, z), n + fa_pre, phi, L.worn)[0]
                            for w, y, z, n, phi in zip(k["wi"], by, bz, k["n_ax"], k["phi_i"])])
    ev.out("drag_torque_nm", tw)
    ev.dissipated("worn_bearing_drag", -tw * np.asarray(k["wi"]))


def _post_ribbon(ev: Evaluation, L) -> None:
    """Ribbon damper, eqs 28-29: force on the outer race, elastic energy, viscous and
    cross-coupled (hysteretic) powers (compiled: ``bearing_kernel.ribbon_series``)."""
    from .bearing_kernel import ribbon_series

    k = ev.kin
    out = np.zeros((len(ev.t), 4))
    ribbon_series(*(np.asarray(k[key], dtype=float) for key in ("oy", "oz", "ovy", "ovz")), float(L.k_rib),
                  float(L.c_rib), float(L.eta), float(L.v_reg), out)
    ev.out("ribbon_force_y_n", out[:, 0].copy())
    ev.out("ribbon_force_z_n", out[:, 1].copy())
    ev.epot += out[:, 2]
    ev.dissipated("ribbon_damping", L.c_rib * (np.square(k["ovy"]) + np.square(k["ovz"])))
    ev.dissipated("ribbon_cross_coupling", out[:, 3].copy())


def _post_outer_coulomb(ev: Evaluation, L) -> None:
    """Coulomb friction of the axial support on the loaded outer race, eq 30."""
    k = ev.kin
    p, fy, fz = np.zeros(len(ev.t)), np.zeros(len(ev.t)), np.zeros(len(ev.t))
    for i, n_ax in enumerate(k["n_ax"]):
        if n_ax > 0:
            ovy, ovz = k["ovy"][i], k["ovz"][i]
            fy[i], fz[i] = outer_race_friction(ovy, ovz, n_ax, L.mu_d, L.v_reg)
            p[i] = -(fy[i] * ovy + fz[i] * ovz)
    ev.out("housing_friction_y_n", fy)
    ev.out("housing_friction_z_n", fz)
    ev.dissipated("outer_race_coulomb", p)


def _post_races(ev: Evaluation, L) -> None:
    """The races as bodies (eqs 7-9): kinetic energy, gravity, viscous damping to the housing."""
    q, v, b = ev.q, ev.v, ev.bearing
    r, o = b.i_race, b.i_outer
    ev.dissipated("race_damping", L.inner_race_damping * (v[:, r] ** 2 + v[:, r + 1] ** 2)
                  + L.outer_race_damping * (v[:, o] ** 2 + v[:, o + 1] ** 2))
    # C_i and C_o act to ground: the housing carries them (0 on the rig, whose races have none)
    ev.out("race_damping_force_y_n", -(L.inner_race_damping * v[:, r] + L.outer_race_damping * v[:, o]))
    ev.out("race_damping_force_z_n", -(L.inner_race_damping * v[:, r + 1] + L.outer_race_damping * v[:, o + 1]))
    ev.ekin += 0.5 * L.inner_race_mass * (v[:, r] ** 2 + v[:, r + 1] ** 2) \
        + 0.5 * L.inner_race_inertia * v[:, r + 2] ** 2 + 0.5 * L.outer_race_mass * (v[:, o] ** 2 + v[:, o + 1] ** 2)
    ev.epot += GRAVITY * (L.inner_race_mass * q[:, r + 1] + L.outer_race_mass * q[:, o + 1])


# --------------------------------------------------------------------------------------------
# the registry

RADIAL_CONTACT = Mechanism(
    "radial_contact", "bearing", ("station_y", "station_z", "theta", "race_y", "race_z", "race_phi"),
    (radial_contact,), ("radial_friction", "contact_damping"), ("radial_friction", "contact_damping"),
    outputs=(Output("contact_force_y_n", "N", True, "race contact force on the rotor, y", "y"),
             Output("contact_force_z_n", "N", True, "race contact force on the rotor, z", "z"),
             Output("normal_force_n", "N", True, "contact normal force F_N (eq 15)"),
             Output("penetration_m", "m", True, "Hertz penetration delta (eq 14)"),
             Output("slip_velocity_m_s", "m/s", True, "slip velocity of the contact point (eq 16)")),
    post=_post_radial, heat=(("radial_friction", "sleeve_contact"), ("contact_damping", "sleeve_contact")),
    doc="sleeve / inner-race contact, eqs 10-17")

REGISTRY: tuple[Mechanism, ...] = (
    # bearing scope (the dissipation entries of both scopes are listed and summed in this order)
    RADIAL_CONTACT,
    Mechanism("axial_rub", "bearing", ("station_y", "station_z", "theta", "x_axial", "race_y", "race_z", "race_phi"),
              (axial_rub,), ("axial_rub",), ("axial_rub",),
              outputs=(Output("rub_force_y_n", "N", True, "face friction force on the rotor, y", "y"),
                       Output("rub_force_z_n", "N", True, "face friction force on the rotor, z", "z")),
              post=_post_rub, active=lambda spec, L: L.axial_rub, heat=(("axial_rub", "face_rub"),),
              doc="thrust-face friction, eqs 18-21"),
    Mechanism("balls", "bearing", ("race_y", "race_z", "outer_y", "outer_z"), (ball_force,), (), ("ball_damping",),
              outputs=(Output("ball_force_y_n", "N", True, "ball-set force on the inner race, y"),
                       Output("ball_force_z_n", "N", True, "ball-set force on the inner race, z")),
              post=_post_balls, heat=(("ball_damping", "ball_contacts"),), doc="ball set, eq 22"),
    Mechanism("ball_drag", "bearing", ("race_phi", "x_axial"), (harris_palmgren_fast,), ("ball_drag",),
              ("ball_drag",), outputs=(Output("drag_torque_nm", "N m", True, "drag torque on the inner race"),),
              post=_post_ball_drag, active=lambda spec, L: L.ball_drag, heat=(("ball_drag", "ball_contacts"),),
              doc="Harris-Palmgren drag, eqs 23-27"),
    Mechanism("worn_bearing_drag", "bearing", ("race_phi", "race_y", "race_z", "outer_y", "outer_z", "x_axial"),
              (worn_drag_torque, worn_friction_with_derivatives), ("worn_bearing_drag",),
              ("worn_bearing_drag",), outputs=(Output("drag_torque_nm", "N m", True, "drag torque on the inner race"),),
              post=_post_worn_drag, active=lambda spec, L: L.worn_drag_torque > 0 or L.worn_drag_friction > 0,
              heat=(("worn_bearing_drag", "ball_contacts"),),
              doc="worn bearing's drag (docs/paper_corrections.md)"),
    Mechanism("ribbon", "bearing", ("outer_y", "outer_z"), (ribbon_force,), ("ribbon_cross_coupling",),
              ("ribbon_damping", "ribbon_cross_coupling"),
              outputs=(Output("ribbon_force_y_n", "N", True, "ribbon force on the outer race, y", on_housing="y"),
                       Output("ribbon_force_z_n", "N", True, "ribbon force on the outer race, z", on_housing="z")),
              post=_post_ribbon, heat=(("ribbon_damping", "outer_support"), ("ribbon_cross_coupling", "outer_support")),
              doc="ribbon damper, eqs 28-29"),
    Mechanism("outer_race_coulomb", "bearing", ("outer_y", "outer_z", "x_axial"), (outer_race_friction,),
              ("outer_race_coulomb",), ("outer_race_coulomb",), post=_post_outer_coulomb,
              outputs=(Output("housing_friction_y_n", "N", True, "housing face friction on the outer race, y (eq 30)",
                              on_housing="y"),
                       Output("housing_friction_z_n", "N", True, "housing face friction on the outer race, z (eq 30)",
                              on_housing="z")),
              heat=(("outer_race_coulomb", "outer_support"),),
              active=lambda spec, L: L.outer_coulomb, doc="outer race / housing friction, eq 30"),
    # rotor scope
    Mechanism("windage", "rotor", ("theta",), (windage_torque,), ("windage",), ("windage",), post=_post_windage,
              active=lambda spec, rl: rl.windage, doc="windage torque, eq 6"),
    Mechanism("axial_contact", "rotor", ("x_axial",), (axial_force,), (), ("axial_damping",),
              outputs=(Output("axial_force_n", "N", False, "axial contact force on the rotor (eqs 3-5)"),),
              post=_post_axial, doc="axial contact, eqs 2-5"),
    Mechanism("rotor", "rotor", ("lateral", "theta", "x_axial"), (), ("gyroscopic", "rotor_flexibility"),
              ("rotor_damping",), post=_post_rotor, doc="the flexible rotor body, eq 1"),
    # bearing scope, after the rotor: the races' energies come last in each bearing's sum
    Mechanism("races", "bearing", ("race_y", "race_z", "race_phi", "outer_y", "outer_z"), (), (), ("race_damping",),
              outputs=(Output("race_damping_force_y_n", "N", True, "races' viscous damping to the housing (C_i, C_o of "
                              "eqs 7, 9) on the races, y", on_housing="y"),
                       Output("race_damping_force_z_n", "N", True, "races' viscous damping to the housing on the races, z",
                              on_housing="z")),
              post=_post_races, heat=(("race_damping", "outer_support"),), doc="races as bodies, eqs 7-9"),
    # work put in (listed and summed in this order)
    Mechanism("amb_hold", "rotor", ("lateral", "x_axial"), (), (), inputs=("amb",), post=_post_amb,
              doc="AMBs before the drop"),
    Mechanism("thrust", "rotor", ("x_axial",), (), (), inputs=("thrust",), post=_post_thrust, doc="axial thrust"),
    Mechanism("drive", "rotor", ("theta",), (), (), inputs=("drive",), post=_post_drive,
              active=lambda spec, rl: rl.constant_drive, doc="constant-speed drive"),
    Mechanism("unbalance", "rotor", ("lateral", "theta"), (), ("unbalance",), inputs=("unbalance",),
              post=_post_unbalance, active=lambda spec, rl: spec.unbalance_rows is not None,
              doc="rotating unbalance"),
)

# --------------------------------------------------------------------------------------------
# mechanisms outside the compiled kernel: the whole mechanism is its entry here (recipe in
# docs/architecture.md)

def _race_windage_force(x, q, v):
    """Air and grease drag on the spinning inner race: the drag law of eq 6 (``windage_torque``)
    with the race's own coefficients, acting on race_phi (BEARING_LOCAL index 6)."""
    return (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, windage_torque(v[6], x["race_windage_c1"], x["race_windage_c2"]), 0.0, 0.0)


def _race_windage_jacobian(x, q, v):
    jq = [[0.0] * 9 for _ in range(9)]
    jv = [[0.0] * 9 for _ in range(9)]
    jv[6][6] = windage_torque_derivative(v[6], x["race_windage_c1"], x["race_windage_c2"])
    return jq, jv


def _post_race_windage(ev: Evaluation, L) -> None:
    w = ev.kin["wi"]
    tw = np.array([windage_torque(wi, L.extra["race_windage_c1"], L.extra["race_windage_c2"]) for wi in w])
    ev.out("race_windage_torque_nm", tw)
    ev.dissipated("race_windage", -tw * np.asarray(w))


REGISTRY += (
    Mechanism("race_windage", "bearing", ("race_phi",), (windage_torque,), ("race_windage",), ("race_windage",),
              outputs=(Output("race_windage_torque_nm", "N m", True, "air/grease drag torque on the inner race"),),
              post=_post_race_windage, heat=(("race_windage", "ball_contacts"),),
              active=lambda spec, L: L.extra["race_windage_c1"] > 0 or L.extra["race_windage_c2"] > 0,
              doc="drag of the air and grease on the spinning inner race, eq 6's law on the race",
              effect="race_windage", default_on=False,
              params=(Param("race_windage_c1", "N m s", 0.0, "laminar drag coefficient of the inner race"),
                      Param("race_windage_c2", "N m s^2", 0.0, "turbulent drag coefficient of the inner race")),
              force=_race_windage_force, jacobian=_race_windage_jacobian),
)


_SOLID_SHELL = ("more than a solid copper shell 1 m wide whose radii differ by 5 % (2 pi 400 W/mK x 1 m / ln 1.05 "
                "= 5e4 W/K)")

# the catcher bearing's thermal network (issue 18): a post-processing mechanism with carried states;
# its law and routing in rotorlanding/thermal_states.py (user_forces/thermal.py's network)

from .thermal_states import ROUTES as THERMAL_ROUTES  # noqa: E402 (the routes' names, no import back)


def _post_catcher_thermal(ev: Evaluation, L) -> None:
    from .thermal_states import post_thermal

    post_thermal(ev, L)


def thermal_active(spec, L) -> bool:
    return L.extra["thermal_ambient_k"] > 0


REGISTRY += (
    Mechanism("catcher_thermal", "bearing", (), (), (), (),
              outputs=tuple(Output(f"temperature_{n}_k", "K", True, f"{n.replace('_', ' ')} temperature (lumped node)",
                                   carried=True)
                            for n in ("sleeve", "inner_ring", "ball_set", "outer_ring", "housing"))
              + (Output("heat_in_j", "J", True, "heat into the bearing's thermal network (cumulative)", carried=True),
                 Output("heat_lost_j", "J", True, "heat from the network to ambient (cumulative)", carried=True))
              + tuple(Output(f"heat_{r}_j", "J", True, f"heat into the network by the {r.replace('_', ' ')} route "
                             "(cumulative)", carried=True)
                      for r in THERMAL_ROUTES),
              post=_post_catcher_thermal, active=thermal_active,
              doc="lumped thermal network of the catcher bearing, heated by the bearing's dissipation "
                  "(rotorlanding/thermal_states.py)",
              effect="catcher_thermal", default_on=True,
              params=(Param("thermal_ambient_k", "K", 293.15, "ambient (and mounting) temperature", positive=True, upper=600.0,
                            why="bearing steel is tempered at 150-350 degC; a 600 K ambient already anneals it"),
                      Param("thermal_g_ball_set_w_k", "W/K", 0.5, "ball set to each ring (assumed, docs/designer_models.md)",
                            upper=1.0e5, why=_SOLID_SHELL),
                      Param("thermal_h_outer_housing_w_m2k", "W/(m^2 K)", 1000.0, "outer ring to housing over its OD",
                            upper=1.0e6, why="the best pressed metallic joints measured conduct ~2e5 W/m^2K (contact "
                            "resistances >= ~5e-6 m^2K/W)"),
                      Param("thermal_g_housing_frame_w_k", "W/K", 2.0, "housing into the machine frame", upper=1.0e5, why=_SOLID_SHELL),
                      Param("thermal_housing_capacity_j_k", "J/K", 950.0, "housing heat capacity (2 kg steel)", positive=True,
                            upper=1.0e8, why="200 t of steel (475 J/kgK): more than any machine frame"),
                      Param("thermal_width_m", "m", 0.022, "ring width (7212: 22 mm), the sleeve contact length", positive=True,
                            upper=2.0, why="wider than the largest rolling bearings (~2 m)"))),
)


def _post_thermal_feedback(ev: Evaluation, L) -> None:
    from .thermal_feedback import post_feedback

    post_feedback(ev, L)


def _retune_thermal(laws, name, carry):
    from .thermal_feedback import retune_bearing

    return retune_bearing(laws, name, carry)


def thermal_feedback_active(spec, L) -> bool:
    return L.extra["thermal_axial_mount_stiffness_n_m"] > 0 and thermal_active(spec, L)


REGISTRY += (
    Mechanism("thermal_feedback", "bearing", ("station_y", "station_z", "race_y", "race_z", "outer_y", "outer_z",
                                              "race_phi"), (), (), (),
              outputs=(Output("journal_clearance_m", "m", True, "sleeve-bore radial clearance with thermal growth"),
                       Output("internal_clearance_m", "m", True, "ball set's diametral internal clearance (< 0: preload)"),
                       Output("thermal_preload_n", "N", True, "axial resultant of the thermal preload of the ball set")),
              post=_post_thermal_feedback, active=thermal_feedback_active, retune=_retune_thermal,
              doc="thermal growth -> journal and internal clearance, preload -> ball stiffness and drag load "
                  "(rotorlanding/thermal_feedback.py)",
              effect="thermal_feedback", default_on=False,
              params=(Param("thermal_internal_clearance_m", "m", 20.0e-6,
                            "cold mounted diametral internal clearance of the ball set (assumed 20 um)", upper=5.0e-3,
                            why="internal clearance groups stay below ~0.2 % of the bore (ISO 5753 tables); 5 mm is "
                            "more than that for any bearing up to 2 m"),
                      Param("thermal_axial_mount_stiffness_n_m", "N/m", 5.0e6,
                            "axial stiffness holding the rings against the preload (rig: the wave spring axial.k_ws)",
                            upper=1.0e16, why="1e14 N/m already stands for a rigid mount (a ball set's own axial "
                            "stiffness is ~1e8-1e9 N/m, axial.k_cb)"),
                      Param("thermal_runaway_limit_k", "K", 473.15,
                            "temperature whose crossing with the ball set preloaded is reported as runaway (200 degC)",
                            upper=900.0, why="bearing steels are tempered at 150-350 degC; above ~900 K the "
                            "growth laws and the steel's hardness have long failed"))),
)


def retuned_spec(spec, carry: dict | None):
    """``spec`` with each bearing's laws retuned by the active mechanisms' ``retune`` hooks to the
    carried states (a coast-down chunk's start); ``spec`` itself when nothing changes."""
    import copy

    if not carry:
        return spec
    bearings, changed = [], False
    for b in spec.bearings:
        laws = b.laws
        for m in REGISTRY:
            if m.retune is not None and m.active(spec, b.laws):
                laws = m.retune(laws, b.name, carry)
        if laws is not b.laws:
            b = replace(b, laws=laws)
            changed = True
        bearings.append(b)
    if not changed:
        return spec
    out = copy.copy(spec)
    out.bearings = bearings
    return out


def heat_routes() -> dict:
    """Dissipation entry -> heat route (rotorlanding.thermal_states.ROUTES) of every bearing-scope
    mechanism."""
    return {e: r for m in REGISTRY for e, r in m.heat}


def carried_series(bearing_names) -> tuple[str, ...]:
    """Series that are states: a coast-down chunk starts from their last stored row."""
    names = tuple(o.name for m in REGISTRY if m.scope == "rotor" for o in m.outputs if o.carried)
    return names + tuple(b + "_" + o.name for b in bearing_names for o in _bearing_outputs() if o.carried)


def _check_heat_routes():
    """Every bearing-scope dissipation entry has a heat route (no heat leaks out of the networks
    unnoticed), and every route is known."""
    from .thermal_states import ROUTES

    routes = heat_routes()
    for m in REGISTRY:
        if m.scope == "bearing":
            for e in m.dissipation:
                if e not in routes:
                    raise RuntimeError(f"mechanism {m.name}: dissipation entry {e!r} has no heat route (Mechanism.heat)")
    for e, r in routes.items():
        if r not in ROUTES:
            raise RuntimeError(f"heat route {r!r} of {e!r}: must be one of {ROUTES}")


#: series of the states themselves (not of a mechanism)
STATE_OUTPUTS_BEARING = (
    Output("y_m", "m", True, "journal centre, y"), Output("z_m", "m", True, "journal centre, z"),
    Output("race_y_m", "m", True, "inner race centre, y"), Output("race_z_m", "m", True, "inner race centre, z"),
    Output("race_speed_rpm", "rpm", True, "inner race speed"))
STATE_OUTPUTS_ROTOR = (
    Output("rotor_speed_rpm", "rpm", False, "rotor speed"),
    Output("axial_position_m", "m", False, "rotor axial position"),
    Output("kinetic_energy_j", "J", False, "kinetic energy"),
    Output("potential_energy_j", "J", False, "elastic and gravitational potential energy"))


def dissipation_entries() -> tuple[str, ...]:
    return tuple(e for m in REGISTRY for e in m.dissipation)


def input_entries() -> tuple[str, ...]:
    return tuple(e for m in REGISTRY for e in m.inputs)


def extra_effects() -> dict[str, bool]:
    """The [effects] switches added by mechanisms outside the built-in list, with their defaults."""
    return {m.effect: m.default_on for m in REGISTRY if m.effect}


def extra_bearing_params() -> tuple[Param, ...]:
    return tuple(p for m in REGISTRY for p in m.params)


def _bearing_outputs() -> list[Output]:
    seen, out = set(), []
    for m in REGISTRY:
        if m.scope == "bearing":
            for o in m.outputs:
                if o.name not in seen:  # a series several mechanisms add to (the drag torque)
                    seen.add(o.name)
                    out.append(o)
    return out + list(STATE_OUTPUTS_BEARING)


def series_units(bearing_names) -> dict[str, str]:
    """Every series of a run, in output order, with its unit: the output schema."""
    units = {o.name: o.unit for m in REGISTRY if m.scope == "rotor" for o in m.outputs}
    for b in bearing_names:
        units.update({b + "_" + o.name: o.unit for o in _bearing_outputs()})
    units.update({o.name: o.unit for o in STATE_OUTPUTS_ROTOR})
    for e in dissipation_entries():
        units["power_" + e + "_w"] = "W"
        units["dissipated_" + e + "_j"] = "J"
    units.update({"input_" + e + "_j": "J" for e in input_entries()})
    return units


def rotor_force(series: dict, bearing: str) -> tuple:
    """(Fy, Fz) on the rotor at a bearing: the sum of the outputs declared ``on_rotor``."""
    return _force_sum(series, bearing, "on_rotor")


def housing_force(series: dict, bearing: str) -> tuple:
    """(Fy, Fz) the housing puts on a bearing's outer race (ribbon, eqs 28-29, and the face friction
    of eq 30 when on): the sum of the outputs declared ``on_housing``. It is what a load cell between
    bearing and housing reads, with the sign of the force on the rotor (positive up). It differs from
    :func:`rotor_force` by the races' inertia and weight: in the mean by the races' weight
    (tests/test_housing_force.py), at an impact's peak by several per cent (docs/measured_data.md)."""
    return _force_sum(series, bearing, "on_housing")


def _force_sum(series: dict, bearing: str, attr: str) -> tuple:
    parts = {"y": [], "z": []}
    for o in _bearing_outputs():
        if getattr(o, attr):
            parts[getattr(o, attr)].append(series[bearing + "_" + o.name])
    fy, fz = parts["y"][0], parts["z"][0]
    for extra in parts["y"][1:]:
        fy = fy + extra
    for extra in parts["z"][1:]:
        fz = fz + extra
    return fy, fz


def evaluate(spec, t: np.ndarray, q: np.ndarray, v: np.ndarray, carry: dict | None = None,
             skip: frozenset | tuple = ()) -> dict:
    """Every series of the schema on the stored states: each active mechanism's ``post`` hook, rotor
    scope first, then per bearing in registry order; an inactive one leaves its zeros. ``carry``:
    the values the carried series (:func:`carried_series`) start from (a coast-down chunk's
    previous row); None: their initial state. ``skip``: mechanisms whose post hook is not run (their
    series stay zero), for a caller that reads none of their outputs (diagnose's features)."""
    nt = len(t)
    names = list(series_units(spec.bearing_names))
    ev = Evaluation(spec, t, q, v, series={k: np.zeros(nt) for k in names},
                    power={e: np.zeros(nt) for e in dissipation_entries()},
                    inputs={e: np.zeros(nt) for e in input_entries()}, ekin=np.zeros(nt), epot=np.zeros(nt),
                    carry=carry)
    for m in REGISTRY:
        if m.scope == "rotor" and m.post is not None and m.name not in skip and m.active(spec, spec.rotor_laws):
            m.post(ev, spec.rotor_laws)
    for b in spec.bearings:
        ev.bearing = b
        ev.bpower = {}
        ev.kin = _kinematics(ev, b)
        for m in REGISTRY:
            if m.scope == "bearing" and m.post is not None and m.name not in skip and m.active(spec, b.laws):
                m.post(ev, b.laws)
        pre = b.name + "_"
        s, r = b.i_station, b.i_race
        ev.series[pre + "y_m"], ev.series[pre + "z_m"] = q[:, s], q[:, s + 1]
        # the inner race's centre: the journal's orbit relative to it is what the clearance bounds
        ev.series[pre + "race_y_m"], ev.series[pre + "race_z_m"] = q[:, r], q[:, r + 1]
        ev.series[pre + "race_speed_rpm"] = v[:, r + 2] * 30 / math.pi
    ev.bearing, ev.kin, ev.bpower = None, {}, {}
    out = ev.series
    out["rotor_speed_rpm"] = v[:, spec.i_theta] * 30 / math.pi
    out["axial_position_m"] = q[:, spec.i_axial]
    out["kinetic_energy_j"] = ev.ekin
    out["potential_energy_j"] = ev.epot
    for e, p in ev.power.items():
        out["power_" + e + "_w"] = p
        out["dissipated_" + e + "_j"] = _trapz_cum(p, t)
    for e, p in ev.inputs.items():
        out["input_" + e + "_j"] = _trapz_cum(p, t)
    return out


def _trapz_cum(y: np.ndarray, t: np.ndarray) -> np.ndarray:
    out = np.zeros_like(y)
    out[1:] = np.cumsum(0.5 * (y[1:] + y[:-1]) * np.diff(t))
    return out


_check_heat_routes()

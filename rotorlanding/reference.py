"""Independent check of the Exudyn assembly: the landing equations as one first-order right-hand
side for scipy's LSODA, built from the same reduced matrices and the same ``user_forces`` laws,
but assembled directly in global coordinates (no Exudyn objects, nodes or markers, and none of the
closures of ``rotorlanding.forces``). ``tests/test_reference_vs_exudyn.py`` asserts that both give
the same journal motion over the first 50 ms of a drop; a sign, index or marker error in the
Exudyn model shows up there even when every law passes its unit tests.

The equations are those listed in :mod:`rotorlanding.landing`. Gyroscopics use the current
Omega (the Exudyn model updates Omega G before each step when Omega has changed by > 1e-4).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from user_forces.amb import amb_force
from user_forces.axial import axial_force
from user_forces.axial_rub import axial_rub
from user_forces.ball_bearing import ball_force, harris_palmgren_torque, worn_drag_torque, worn_friction_torque
from user_forces.radial_contact import radial_contact
from user_forces.ribbon import outer_race_friction, ribbon_force
from user_forces.spin import drive_torque, windage_torque

from .landing import LandingSpec
from .params import OMEGA_REG_HP
from .timoshenko import GRAVITY


def mass_matrix(spec: LandingSpec) -> np.ndarray:
    n = spec.n
    M = np.zeros((n, n))
    M[: spec.n_lat, : spec.n_lat] = spec.M
    M[spec.i_theta, spec.i_theta] = spec.rotor_polar_inertia
    M[spec.i_axial, spec.i_axial] = spec.rotor_mass
    for b in spec.bearings:
        p, i = b.params, b.i_race
        M[i, i] = M[i + 1, i + 1] = p.inner_race_mass
        M[i + 2, i + 2] = p.inner_race_inertia
        M[i + 3, i + 3] = M[i + 4, i + 4] = p.outer_race_mass
    return M


def generalized_forces(spec: LandingSpec, t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Right-hand side f(t, q, v) of M q'' = f, in the spec's coordinate order."""
    sc, a = spec.scenario, spec.scenario.axial
    nl = spec.n_lat
    f = np.zeros(spec.n)
    ql, vl = q[:nl], v[:nl]
    omega = v[spec.i_theta]
    f[:nl] = spec.f_gravity - spec.K @ ql - spec.C @ vl
    rl = spec.rotor_laws
    if rl.gyroscopic:
        f[:nl] -= omega * (spec.G @ vl)
    if t < sc.amb.t_drop or not sc.amb.drop_radial:
        for iy, iz in spec.amb_rows:
            for i in (iy, iz):
                f[i] += amb_force(q[i], v[i], -spec.f_gravity[i], sc.amb.stiffness, sc.amb.damping)
    if spec.unbalance_rows is not None:
        ang = q[spec.i_theta] + math.radians(sc.unbalance.phase_deg)
        fu = sc.unbalance.magnitude * omega**2
        f[:nl] += spec.unbalance_rows[0] * fu * math.cos(ang) + spec.unbalance_rows[1] * fu * math.sin(ang)
    if rl.windage:
        f[spec.i_theta] += windage_torque(omega, rl.c_w1, rl.c_w2)
    if rl.constant_drive:
        f[spec.i_theta] += drive_torque(omega, rl.drive_gain, rl.omega0)
    x, xd = q[spec.i_axial], v[spec.i_axial]
    f_ax = axial_force(x, xd, a.cl_ax, a.delta_m, a.k_cb, a.k_ws, a.k_h, a.c_ax)
    f[spec.i_axial] += spec.thrust(t) + f_ax
    if t < sc.amb.t_drop or not sc.amb.drop_axial:
        f[spec.i_axial] += amb_force(x, xd, -spec.thrust(t), sc.amb.axial_stiffness, sc.amb.axial_damping)
    for b in spec.bearings:
        L = b.laws
        s, r, o = b.i_station, b.i_race, b.i_race + 3
        d = q[s:s + 2] - q[r:r + 2]
        dv = v[s:s + 2] - v[r:r + 2]
        wr = v[r + 2]
        fy, fz, t_rot, t_race = radial_contact(
            d[0], d[1], dv[0], dv[1], omega, wr, L.clearance, L.k_hertz, L.exponent,
            L.k_visc, L.mu_rad, L.v_reg,
            L.sleeve_radius, L.race_radius)[:4]
        n_ax = abs(f_ax) if L.axial_face else 0.0
        if L.axial_rub and n_ax > 0:
            al, be = float(b.tilt_alpha @ ql), float(b.tilt_beta @ ql)
            gy, gz, gr, gi = axial_rub(d[0], d[1], dv[0], dv[1], omega, wr, al, be, abs(x) - a.cl_ax, n_ax,
                                       1.0 if x >= 0 else -1.0, L.mu_ax, L.v_reg_axial, L.face_inner_radius,
                                       L.face_outer_radius)[:4]
            fy, fz, t_rot, t_race = fy + gy, fz + gz, t_rot + gr, t_race + gi
        f[s] += fy
        f[s + 1] += fz
        f[spec.i_theta] += t_rot
        f[r] -= fy
        f[r + 1] -= fz
        f[r + 2] += t_race
        e = q[r:r + 2] - q[o:o + 2]
        ev = v[r:r + 2] - v[o:o + 2]
        by, bz = ball_force(e[0], e[1], L.k_b1, L.k_b2, ev[0], ev[1], L.c_b)
        f[r] += by
        f[r + 1] += bz
        f[o] -= by
        f[o + 1] -= bz
        if L.ball_drag:
            f[r + 2] += harris_palmgren_torque(wr, math.hypot(by, bz), n_ax + L.drag_axial_preload,
                                               contact_angle_deg=L.contact_angle_deg,
                                               C_s=L.static_load_rating, d_m=L.pitch_diameter, z_hp=L.hp_z,
                                               y_hp=L.hp_y, omega_reg=OMEGA_REG_HP)
        if L.worn_drag_torque:
            f[r + 2] += worn_drag_torque(wr, L.worn_drag_torque, OMEGA_REG_HP, q[r + 2], L.worn_drag_growth_angle)
        if L.worn_drag_friction:
            f[r + 2] += worn_friction_torque(wr, math.hypot(by, bz), n_ax + L.drag_axial_preload,
                                             friction=L.worn_drag_friction,
                                             contact_angle_deg=L.contact_angle_deg, d_m=L.pitch_diameter,
                                             omega_reg=OMEGA_REG_HP, angle=q[r + 2],
                                             growth_angle=L.worn_drag_growth_angle)
        hy, hz = ribbon_force(q[o], q[o + 1], v[o], v[o + 1], L.k_rib, L.c_rib, L.eta, L.v_reg)
        f[o] += hy
        f[o + 1] += hz
        if L.outer_coulomb and n_ax > 0:
            ky, kz = outer_race_friction(v[o], v[o + 1], n_ax, L.mu_d, L.v_reg)
            f[o] += ky
            f[o + 1] += kz
        f[r:r + 2] -= L.inner_race_damping * v[r:r + 2]
        f[o:o + 2] -= L.outer_race_damping * v[o:o + 2]
        f[r + 1] -= L.inner_race_mass * GRAVITY
        f[o + 1] -= L.outer_race_mass * GRAVITY
    return f


def reference_rhs(spec: LandingSpec):
    """f(t, y) for y = [q, v] (first-order form)."""
    minv = np.linalg.inv(mass_matrix(spec))
    n = spec.n

    def rhs(t, y):
        q, v = y[:n], y[n:]
        return np.concatenate([v, minv @ generalized_forces(spec, t, q, v)])

    return rhs


def simulate_reference(spec: LandingSpec, t_end: float, *, t_eval=None, rtol=1e-8, atol=1e-11, method="LSODA"):
    """Integrate from the spec's initial state; returns (t, q, v) and the solver result."""
    q0, v0 = spec.initial_state()
    sol = solve_ivp(reference_rhs(spec), (0.0, t_end), np.concatenate([q0, v0]), method=method, t_eval=t_eval,
                    rtol=rtol, atol=atol)
    n = spec.n
    return sol.t, sol.y[:n].T, sol.y[n:].T, sol

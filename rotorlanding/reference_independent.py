"""Second, independent scipy reference of the landing equations (check of the Exudyn assembly).

Written from the equations of :mod:`rotorlanding.landing` and the laws in ``user_forces`` only:
it does not import or mirror ``rotorlanding.forces`` / ``rotorlanding.exudyn_model`` (nor
``rotorlanding.reference``). Everything is assembled directly in the global coordinates of the
:class:`~rotorlanding.landing.LandingSpec`::

    q = [ q_lat (n_lat) | theta, x_ax | per bearing: race_y, race_z, race_phi, outer_y, outer_z ]

and integrated in first-order form y = [q, v] with ``scipy.integrate.solve_ivp``.

Equations (sc = spec.scenario, eff = sc.effects, c = sc.contact, a = sc.axial, p = b.params):

- lateral  M q_lat'' = f_g - K q_lat - C q_lat' - [gyro] Omega G q_lat' + f_amb + f_unb
                       + sum_b (radial contact + axial rub force on the rotor) at b.i_station
- spin     I_p Omega' = sum_b (T_rotor radial + T_rotor rub) + [windage] + [constant drive]
- axial    m_r x'' = F_thrust(t) + F_ax(x, x') (+ AMB: -F_thrust - k x - c x' while held)
- inner race  m_i r'' = -F_contact - F_rub + F_ball - C_i r' - m_i g e_z
              I_i phi'' = T_race radial + T_race rub + [ball drag] T_HP
- outer race  m_o r'' = -F_ball + F_ribbon + [Coulomb, face bearing] F_oh - C_o r' - m_o g e_z

Regularisation of the axial-face friction: ``contact.v_reg_axial`` (the scenario documents it as
"regularisation of the axial-face friction (eqs 19-20)"); every other slip law uses
``contact.v_reg``. Pass ``rub_v_reg="v_reg"`` to use ``contact.v_reg`` for the face as well.
Gyroscopic term with the current Omega (exact form of the equation).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.linalg import cho_factor, cho_solve

from user_forces.axial import axial_force
from user_forces.axial_rub import axial_rub
from user_forces.ball_bearing import (OMEGA_REG_DEFAULT, ball_force, harris_palmgren_torque, worn_drag_torque,
                                     worn_friction_torque)
from user_forces.radial_contact import radial_contact
from user_forces.ribbon import outer_race_friction, ribbon_force
from user_forces.spin import windage_torque

from .timoshenko import GRAVITY


def _journal_pair(f, s, r, it, res):
    """Add a journal-race law's (F_y, F_z, T_rotor, T_race) on the rotor at station s (spin row it)
    and, reacted, on the inner race r (F_y, F_z on race_y, race_z; T_race on race_phi)."""
    f[s] += res[0]
    f[s + 1] += res[1]
    f[r] -= res[0]
    f[r + 1] -= res[1]
    f[it] += res[2]
    f[r + 2] += res[3]


def reference_forces(spec, *, rub_v_reg: str = "v_reg_axial"):
    """Return ``forces(t, q, v) -> (f, parts)``: the generalized force vector of ``M q'' = f`` in
    spec order and a dict of the individual law outputs (for term-by-term comparisons)."""
    sc = spec.scenario
    eff = sc.effects
    c = sc.contact
    a = sc.axial
    amb = sc.amb
    nl = spec.n_lat
    it, ix = spec.i_theta, spec.i_axial
    M, K, C, G = (np.asarray(m, dtype=float) for m in (spec.M, spec.K, spec.C, spec.G))
    fg = np.asarray(spec.f_gravity, dtype=float)
    k_visc = c.k_visc if eff["contact_damping"] else 0.0
    mu_rad = c.mu_rad if eff["radial_friction"] else 0.0
    v_rub = getattr(c, rub_v_reg)
    unb = spec.unbalance_rows
    if unb is not None:
        unb = (np.asarray(unb[0], dtype=float), np.asarray(unb[1], dtype=float))
        U, phase = sc.unbalance.magnitude, math.radians(sc.unbalance.phase_deg)

    def forces(t, q, v):
        f = np.zeros(spec.n)
        parts = {}
        ql, vl = q[:nl], v[:nl]
        om = v[it]
        # ---- rotor lateral: linear part
        f[:nl] = fg - K @ ql - C @ vl
        if eff["gyroscopic"]:
            f[:nl] -= om * (G @ vl)
        # AMBs
        if (not amb.drop_radial) or t < amb.t_drop:
            for iy, iz in spec.amb_rows:
                f[iy] += -fg[iy] - amb.stiffness * q[iy] - amb.damping * v[iy]
                f[iz] += -fg[iz] - amb.stiffness * q[iz] - amb.damping * v[iz]
        # unbalance
        if unb is not None:
            ang = q[it] + phase
            fy, fz = U * om * om * math.cos(ang), U * om * om * math.sin(ang)
            f[:nl] += unb[0] * fy + unb[1] * fz
        # ---- spin
        if eff["windage"]:
            f[it] += windage_torque(om, sc.spin.c_w1, sc.spin.c_w2)
        if sc.spin.drive == "constant":
            f[it] += sc.spin.drive_gain * (sc.omega0 - om)
        # ---- axial
        x, xd = q[ix], v[ix]
        f_thr = spec.thrust(t)
        f_ax = axial_force(x, xd, a.cl_ax, a.delta_m, a.k_cb, a.k_ws, a.k_h, a.c_ax)
        f[ix] += f_thr + f_ax
        if (not amb.drop_axial) or t < amb.t_drop:
            f[ix] += -f_thr - amb.axial_stiffness * x - amb.axial_damping * xd
        parts["F_ax"] = f_ax
        # ---- bearings
        for b in spec.bearings:
            p = b.params
            s, r = b.i_station, b.i_race
            o = r + 3
            dy, dz = q[s] - q[r], q[s + 1] - q[r + 1]
            dvy, dvz = v[s] - v[r], v[s + 1] - v[r + 1]
            om_i = v[r + 2]
            rc = radial_contact(dy, dz, dvy, dvz, om, om_i, p.clearance, c.k_hertz, c.exponent,
                                k_visc, mu_rad, c.v_reg, p.sleeve_radius, p.race_radius)
            parts[b.name + ".radial"] = rc
            _journal_pair(f, s, r, it, rc)
            # axial face
            N = abs(f_ax) if p.axial_face else 0.0
            if p.axial_face and eff["axial_rub"] and N > 0.0:
                alpha = float(b.tilt_alpha @ ql)
                beta = float(b.tilt_beta @ ql)
                ar = axial_rub(dy, dz, dvy, dvz, om, om_i, alpha, beta, abs(x) - a.cl_ax, N,
                               1.0 if x >= 0.0 else -1.0, c.mu_ax, v_rub,
                               p.face_inner_radius, p.face_outer_radius)
                parts[b.name + ".rub"] = ar
                _journal_pair(f, s, r, it, ar)
            # balls (force on the inner race; outer gets minus)
            fb = ball_force(q[r] - q[o], q[r + 1] - q[o + 1], p.k_b1, p.k_b2,
                            v[r] - v[o], v[r + 1] - v[o + 1], p.c_b)
            parts[b.name + ".ball"] = fb
            f[r] += fb[0]
            f[r + 1] += fb[1]
            f[o] -= fb[0]
            f[o + 1] -= fb[1]
            if eff["ball_drag"]:
                thp = harris_palmgren_torque(om_i, math.hypot(fb[0], fb[1]), N,
                                             contact_angle_deg=p.contact_angle_deg, C_s=p.static_load_rating,
                                             d_m=p.pitch_diameter, z_hp=p.hp_z, y_hp=p.hp_y, omega_reg=OMEGA_REG_DEFAULT)
                parts[b.name + ".hp"] = thp
                f[r + 2] += thp
            if eff["worn_bearing_drag"]:
                f[r + 2] += worn_drag_torque(om_i, p.worn_drag_torque, OMEGA_REG_DEFAULT, q[r + 2], p.worn_drag_growth_angle)
                f[r + 2] += worn_friction_torque(om_i, math.hypot(fb[0], fb[1]), N, friction=p.worn_drag_friction,
                                                 contact_angle_deg=p.contact_angle_deg, d_m=p.pitch_diameter,
                                                 omega_reg=OMEGA_REG_DEFAULT, angle=q[r + 2],
                                                 growth_angle=p.worn_drag_growth_angle)
            # ribbon + Coulomb on the outer race
            fr = ribbon_force(q[o], q[o + 1], v[o], v[o + 1], p.k_rib, p.c_rib,
                              p.eta if eff["ribbon_cross_coupling"] else 0.0, c.v_reg)
            parts[b.name + ".ribbon"] = fr
            f[o] += fr[0]
            f[o + 1] += fr[1]
            if eff["outer_race_coulomb"] and p.axial_face and N > 0.0:
                fc = outer_race_friction(v[o], v[o + 1], N, p.mu_d, c.v_reg)
                parts[b.name + ".coulomb"] = fc
                f[o] += fc[0]
                f[o + 1] += fc[1]
            # own damping to ground and gravity
            f[r] -= p.inner_race_damping * v[r]
            f[r + 1] -= p.inner_race_damping * v[r + 1] + p.inner_race_mass * GRAVITY
            f[o] -= p.outer_race_damping * v[o]
            f[o + 1] -= p.outer_race_damping * v[o + 1] + p.outer_race_mass * GRAVITY
        return f, parts

    return forces


def reference_mass(spec):
    """Diagonal masses of the non-lateral coordinates (vector of length n; lateral entries unused)."""
    m = np.ones(spec.n)
    m[spec.i_theta] = spec.rotor_polar_inertia
    m[spec.i_axial] = spec.rotor_mass
    for b in spec.bearings:
        p, r = b.params, b.i_race
        m[r] = m[r + 1] = p.inner_race_mass
        m[r + 2] = p.inner_race_inertia
        m[r + 3] = m[r + 4] = p.outer_race_mass
    return m


def reference_accel(spec, **kw):
    """``accel(t, q, v) -> q''`` (solves the full lateral mass matrix, divides the diagonal rest)."""
    forces = reference_forces(spec, **kw)
    nl = spec.n_lat
    cho = cho_factor(np.asarray(spec.M, dtype=float))
    m = reference_mass(spec)

    def accel(t, q, v):
        f, _ = forces(t, q, v)
        acc = f / m
        acc[:nl] = cho_solve(cho, f[:nl])
        return acc

    return accel


def reference_rhs(spec, **kw):
    """First-order right-hand side ``f(t, y)``, y = [q, v] (2n), in LandingSpec order."""
    n = spec.n
    accel = reference_accel(spec, **kw)

    def rhs(t, y):
        q, v = y[:n], y[n:]
        return np.concatenate([v, accel(t, q, v)])

    return rhs


def simulate_reference(spec, t_end, *, t_eval=None, rtol=1e-8, atol=1e-11, method="LSODA", **kw):
    """Integrate from ``spec.initial_state()`` to ``t_end``; return (t, q[t, n], v[t, n]).

    Raises RuntimeError if the integrator fails."""
    q0, v0 = spec.initial_state()
    sol = solve_ivp(reference_rhs(spec, **kw), (0.0, float(t_end)), np.concatenate([q0, v0]), method=method,
                    t_eval=t_eval, rtol=rtol, atol=atol)
    if not sol.success:
        raise RuntimeError(f"reference integration failed: {sol.message}")
    n = spec.n
    return sol.t, sol.y[:n].T, sol.y[n:].T

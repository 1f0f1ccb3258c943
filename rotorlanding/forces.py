"""Force closures of the landing model: the paper's laws wired to the model's coordinates.

:func:`rotor_forces` and :func:`bearing_forces` return plain-Python closures
``f(t, q, v) -> list`` over *local* coordinate lists; the Exudyn model wraps each as a user
function of one ObjectGenericODE2 (one call per bearing per residual evaluation, which is where
the run time goes), and post-processing re-evaluates the same laws on stored states
(:mod:`rotorlanding.postprocess`). Hot-path rules: plain floats, no numpy per call, parameters
bound once as locals.

Local coordinates
-----------------
rotor loads:    [lateral (n_lat) | theta, x_ax], or only [theta, x_ax] when no load acts on the
                lateral coordinates (no AMB during the run, no unbalance, gyroscopics elsewhere):
                see :func:`rotor_loads_need_lateral`
bearing object: [lateral block | theta, x_ax | race_y, race_z, race_phi | outer_y, outer_z]
where the lateral block is only the bearing's station (y, z) unless the bearing carries the
axial face with axial rub on, in which case it is the whole lateral vector (the rotor tilt at
the face comes from the Craig-Bampton rows of alpha and beta).
"""

from __future__ import annotations

import math

import numpy as np

from user_forces.axial import axial_force
from user_forces.axial_rub import axial_rub as _axial_rub_py
from user_forces.ball_bearing import ball_force, harris_palmgren_constants, harris_palmgren_fast
from user_forces.radial_contact import radial_contact
from user_forces.ribbon import outer_race_friction, ribbon_force
from user_forces.spin import windage_torque

from .landing import G_ACC, BearingSpec, LandingSpec

OMEGA_REG_HP = 0.1  # rad/s, sign regularisation of the ball drag torque


def _compile_axial_rub():
    """The axial-rub quadrature (72 points) costs ~20-50 us per call in Python and dominates
    combined landings; numba compiles the same plain-float function to ~1 us. Without numba
    the Python law is used unchanged."""
    try:
        import numba
    except ImportError:  # pragma: no cover
        return _axial_rub_py
    return numba.njit(cache=True)(_axial_rub_py)


axial_rub = _compile_axial_rub()


def axial_law(spec: LandingSpec):
    """(x, v) -> F_ax: the axial reaction of the thrust face on the rotor (eqs 3-5)."""
    a = spec.scenario.axial
    cl, dm, kcb, kws, kh, cax = a.cl_ax, a.delta_m, a.k_cb, a.k_ws, a.k_h, a.c_ax

    def f(x, v):
        return axial_force(x, v, cl, dm, kcb, kws, kh, cax)

    return f


def rotor_loads_need_lateral(spec: LandingSpec, gyroscopic_in_user_function: bool = True) -> bool:
    sc = spec.scenario
    amb_active = sc.amb.t_drop > 0.0 or not sc.amb.drop_radial
    return amb_active or spec.unbalance_rows is not None or (gyroscopic_in_user_function and sc.effects["gyroscopic"])


def rotor_forces(spec: LandingSpec, *, gyroscopic_in_user_function: bool = True):
    """Closure for the rotor object: gyroscopics, AMB hold, unbalance, windage, drive, axial.

    With ``gyroscopic_in_user_function=False`` the caller accounts for -Omega G q' itself (the
    Exudyn model puts Omega G into the damping matrix before each step, see exudyn_model)."""
    sc = spec.scenario
    eff = sc.effects
    n_lat = spec.n_lat
    G = spec.G if (eff["gyroscopic"] and gyroscopic_in_user_function) else None
    amb = sc.amb
    t_drop = amb.t_drop
    k_amb, c_amb = amb.stiffness, amb.damping
    bias = [(-spec.f_gravity[iy], -spec.f_gravity[iz]) for iy, iz in spec.amb_rows]
    rows = spec.amb_rows
    kax_amb, cax_amb = amb.axial_stiffness, amb.axial_damping
    drop_radial, drop_axial = amb.drop_radial, amb.drop_axial
    unb = spec.unbalance_rows
    if unb is not None:
        u_mag = sc.unbalance.magnitude
        u_phase = math.radians(sc.unbalance.phase_deg)
        uy, uz = unb
    wind = eff["windage"]
    cw1, cw2 = sc.spin.c_w1, sc.spin.c_w2
    constant_drive = sc.spin.drive == "constant"
    gain, omega0 = sc.spin.drive_gain, sc.omega0
    fax = axial_law(spec)
    thrust = spec.thrust
    if not rotor_loads_need_lateral(spec, gyroscopic_in_user_function):
        n_lat = 0  # local coordinates are only [theta, x_ax]
    i_th, i_ax = n_lat, n_lat + 1

    def f(t, q, v):
        omega = v[i_th]
        if G is not None:
            out = (-omega * (G @ np.asarray(v[:n_lat]))).tolist()
        else:
            out = [0.0] * n_lat
        out += [0.0, 0.0]
        if n_lat and (t < t_drop or not drop_radial):
            for (iy, iz), (by, bz) in zip(rows, bias):
                out[iy] += by - k_amb * q[iy] - c_amb * v[iy]
                out[iz] += bz - k_amb * q[iz] - c_amb * v[iz]
        if unb is not None:
            ang = q[i_th] + u_phase
            fu = u_mag * omega * omega
            fy, fz = fu * math.cos(ang), fu * math.sin(ang)
            for k in range(n_lat):
                out[k] += uy[k] * fy + uz[k] * fz
        torque = 0.0
        if wind:
            torque += windage_torque(omega, cw1, cw2)
        if constant_drive:
            torque += gain * (omega0 - omega)
        out[i_th] = torque
        x, xd = q[i_ax], v[i_ax]
        fa = thrust(t) + fax(x, xd)
        if t < t_drop or not drop_axial:
            fa += -thrust(t) - kax_amb * x - cax_amb * xd
        out[i_ax] = fa
        return out

    return f


def bearing_layout(spec: LandingSpec, b: BearingSpec, lagged_tilt: bool = False) -> dict:
    """Local indices of a bearing object's coordinates (see module docstring)."""
    full_lateral = b.params.axial_face and spec.scenario.effects["axial_rub"] and not lagged_tilt
    n_lat_local = spec.n_lat if full_lateral else 2
    s = b.i_station if full_lateral else 0
    return {"full_lateral": full_lateral, "n_lat": n_lat_local, "sy": s, "sz": s + 1,
            "th": n_lat_local, "ax": n_lat_local + 1, "ry": n_lat_local + 2, "rz": n_lat_local + 3,
            "rp": n_lat_local + 4, "oy": n_lat_local + 5, "oz": n_lat_local + 6, "n": n_lat_local + 7}


def bearing_forces(spec: LandingSpec, b: BearingSpec, tilt: list | None = None):
    """Closure for one catcher bearing: radial contact, axial rub, balls, drag, ribbon, friction.

    ``tilt``: optional 2-list [alpha, beta] of the rotor tilt at the station, kept up to date by
    the caller once per time step (lagged tilt). The tilt only shapes the face pressure field and
    changes little within a step; taking it from the start of the step keeps the bearing object
    at 9 local coordinates instead of the whole rotor, which makes its numerical Jacobian 2.5x
    cheaper. Without it the tilt is computed from the Craig-Bampton rows inside the call."""
    sc = spec.scenario
    eff = sc.effects
    p = b.params
    c = sc.contact
    lay = bearing_layout(spec, b, tilt is not None)
    n = lay["n"]
    sy, sz, th, ax = lay["sy"], lay["sz"], lay["th"], lay["ax"]
    ry, rz, rp, oy, oz = lay["ry"], lay["rz"], lay["rp"], lay["oy"], lay["oz"]
    clearance, r_rot, r_race = p.clearance, p.sleeve_radius, p.race_radius
    kh, ex, v_reg = c.k_hertz, c.exponent, c.v_reg
    kv = c.k_visc if eff["contact_damping"] else 0.0
    mu = c.mu_rad if eff["radial_friction"] else 0.0
    kb1, kb2, cb = p.k_b1, p.k_b2, p.c_b
    drag = eff["ball_drag"]
    hp = harris_palmgren_constants(p.contact_angle_deg, p.static_load_rating, p.pitch_diameter, p.hp_z, p.hp_y,
                                   omega_reg=OMEGA_REG_HP)
    krib, crib = p.k_rib, p.c_rib
    eta = p.eta if eff["ribbon_cross_coupling"] else 0.0
    coulomb = eff["outer_race_coulomb"] and p.axial_face
    mu_d = p.mu_d
    ci, co = p.inner_race_damping, p.outer_race_damping
    wi, wo = -p.inner_race_mass * G_ACC, -p.outer_race_mass * G_ACC
    face = p.axial_face
    rub = b.params.axial_face and eff["axial_rub"]
    full = lay["full_lateral"]
    if rub:
        ta = b.tilt_alpha.tolist()
        tb = b.tilt_beta.tolist()
        nl = spec.n_lat
        mu_ax, r1, r2, v_reg_ax = c.mu_ax, p.face_inner_radius, p.face_outer_radius, c.v_reg_axial
        cl_ax = sc.axial.cl_ax
    fax = axial_law(spec)

    def f(t, q, v):
        out = [0.0] * n
        dy, dz = q[sy] - q[ry], q[sz] - q[rz]
        dvy, dvz = v[sy] - v[ry], v[sz] - v[rz]
        omega, omega_i = v[th], v[rp]
        fy, fz, t_rot, t_race = radial_contact(dy, dz, dvy, dvz, omega, omega_i, clearance, kh, ex, kv, mu,
                                               v_reg, r_rot, r_race)[:4]
        f_ax = abs(fax(q[ax], v[ax])) if face else 0.0
        if rub and f_ax > 0.0:
            x = q[ax]
            if full:
                alpha = beta = 0.0
                for k in range(nl):
                    alpha += ta[k] * q[k]
                    beta += tb[k] * q[k]
            else:
                alpha, beta = tilt
            ry_, rz_, trr, tri = axial_rub(dy, dz, dvy, dvz, omega, omega_i, alpha, beta, abs(x) - cl_ax, f_ax,
                                           1.0 if x >= 0 else -1.0, mu_ax, v_reg_ax, r1, r2)[:4]
            fy += ry_
            fz += rz_
            t_rot += trr
            t_race += tri
        out[sy] = fy
        out[sz] = fz
        out[th] = t_rot
        # balls: force on the inner race from r = inner - outer
        by, bz = ball_force(q[ry] - q[oy], q[rz] - q[oz], kb1, kb2, v[ry] - v[oy], v[rz] - v[oz], cb)
        if drag:
            f_rad = math.hypot(by, bz)
            t_race += harris_palmgren_fast(omega_i, f_rad, f_ax, hp)
        out[ry] = -fy + by - ci * v[ry]
        out[rz] = -fz + bz - ci * v[rz] + wi
        out[rp] = t_race
        gy, gz = ribbon_force(q[oy], q[oz], v[oy], v[oz], krib, crib, eta, v_reg)
        if coulomb and f_ax > 0.0:
            hy, hz = outer_race_friction(v[oy], v[oz], f_ax, mu_d, v_reg)
            gy += hy
            gz += hz
        out[oy] = -by + gy - co * v[oy]
        out[oz] = -bz + gz - co * v[oz] + wo
        return out

    return f

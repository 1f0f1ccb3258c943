"""Force closures of the landing model: the paper's laws wired to the model's coordinates.

:func:`rotor_forces` and :func:`bearing_forces` return plain-Python closures
``f(t, q, v) -> list`` over *local* coordinate lists; post-processing re-evaluates the laws with
them on stored states (:mod:`rotorlanding.postprocess`), and the Exudyn model uses them with
``analytic_jacobian=False`` (one user function per bearing, numerical Jacobians). The solver's
default path is the compiled equivalent in :mod:`rotorlanding.bearing_kernel` (same
``user_forces`` laws; tests/test_bearing_jacobian.py checks they agree). Hot-path rules: plain floats, no numpy per call, parameters
bound once as locals.

Local coordinates
-----------------
rotor loads:    [lateral (n_lat) | theta, x_ax], or only [theta, x_ax] when no load acts on the
                lateral coordinates (no AMB during the run, no unbalance, gyroscopics elsewhere):
                see :func:`rotor_loads_need_lateral`
bearing object: [station y, z | theta, x_ax | race_y, race_z, race_phi | outer_y, outer_z]
                (``BEARING_LOCAL``); the rotor tilt at an axial face comes in through a holder
                updated once per step.
"""

from __future__ import annotations

import math

import numpy as np

from user_forces.axial import axial_force
from user_forces.axial_rub import axial_rub as _axial_rub_py
from user_forces.axial_rub import axial_rub_quadrature
from user_forces.ball_bearing import ball_force, harris_palmgren_fast, worn_drag_torque, worn_friction_with_derivatives
from user_forces.radial_contact import radial_contact
from user_forces.ribbon import outer_race_friction, ribbon_force
from user_forces.amb import amb_force, unbalance_force
from user_forces.spin import drive_torque, windage_torque, windage_torque_derivative

from .landing import G_ACC, BearingSpec, LandingSpec
from .params import OMEGA_REG_HP


def _compile_axial_rub():
    """The axial-rub quadrature (72 points) costs ~20-50 us per call in Python and dominates
    combined landings; numba compiles the same plain-float function to ~1 us. Without numba
    the Python law is used unchanged."""
    try:
        import numba
    except ImportError:  # pragma: no cover
        return _axial_rub_py
    quadrature = numba.njit(cache=True)(axial_rub_quadrature)

    @numba.njit(cache=True)
    def compiled(dy, dz, dvy, dvz, om, omi, alpha, beta, delta_ax, f_ax, sign, mu_ax, v_reg, r1, r2):
        r = quadrature(dy, dz, dvy, dvz, om, omi, alpha, beta, delta_ax, f_ax, sign, mu_ax, v_reg, r1, r2, False)
        return r[0], r[1], r[2], r[3], r[4]

    return compiled


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
    return amb_active or spec.unbalance_rows is not None or (gyroscopic_in_user_function and spec.rotor_laws.gyroscopic)


def _rotor_loads(spec: LandingSpec, gyroscopic_in_user_function: bool) -> tuple:
    """The rotor loads' parameters, read once for :func:`rotor_forces` and its Jacobian (the
    closures bind them as locals: the rotor loads run in a Python user function when AMBs hold or
    an unbalance acts)."""
    sc = spec.scenario
    rl = spec.rotor_laws
    amb = sc.amb
    n_lat = spec.n_lat if rotor_loads_need_lateral(spec, gyroscopic_in_user_function) else 0
    G = spec.G if (rl.gyroscopic and gyroscopic_in_user_function) else None
    unb = spec.unbalance_rows
    u_mag = sc.unbalance.magnitude if unb is not None else 0.0
    u_phase = math.radians(sc.unbalance.phase_deg) if unb is not None else 0.0
    return (n_lat, G, amb.t_drop, amb.stiffness, amb.damping, spec.amb_rows, amb.axial_stiffness, amb.axial_damping,
            amb.drop_radial, amb.drop_axial, unb, u_mag, u_phase, rl.windage, rl.c_w1, rl.c_w2, rl.constant_drive,
            rl.drive_gain, rl.omega0, axial_law(spec))


def rotor_forces(spec: LandingSpec, *, gyroscopic_in_user_function: bool = True):
    """Closure for the rotor object: gyroscopics, AMB hold, unbalance, windage, drive, axial.

    With ``gyroscopic_in_user_function=False`` the caller accounts for -Omega G q' itself (the
    Exudyn model puts Omega G into the damping matrix before each step, see exudyn_model)."""
    (n_lat, G, t_drop, k_amb, c_amb, rows, kax_amb, cax_amb, drop_radial, drop_axial, unb, u_mag, u_phase, wind, cw1,
     cw2, constant_drive, gain, omega0, fax) = _rotor_loads(spec, gyroscopic_in_user_function)
    if unb is not None:
        uy, uz = unb
    bias = [(-spec.f_gravity[iy], -spec.f_gravity[iz]) for iy, iz in rows]
    thrust = spec.thrust
    i_th, i_ax = n_lat, n_lat + 1  # local coordinates: [lateral (n_lat) | theta, x_ax], n_lat may be 0

    def f(t, q, v):
        omega = v[i_th]
        if G is not None:
            out = (-omega * (G @ np.asarray(v[:n_lat]))).tolist()
        else:
            out = [0.0] * n_lat
        out += [0.0, 0.0]
        if n_lat and (t < t_drop or not drop_radial):
            for (iy, iz), (by, bz) in zip(rows, bias):
                out[iy] += amb_force(q[iy], v[iy], by, k_amb, c_amb)
                out[iz] += amb_force(q[iz], v[iz], bz, k_amb, c_amb)
        if unb is not None:
            fy, fz = unbalance_force(omega, q[i_th] + u_phase, u_mag)
            for k in range(n_lat):
                out[k] += uy[k] * fy + uz[k] * fz
        torque = 0.0
        if wind:
            torque += windage_torque(omega, cw1, cw2)
        if constant_drive:
            torque += drive_torque(omega, gain, omega0)
        out[i_th] = torque
        x, xd = q[i_ax], v[i_ax]
        fa = thrust(t) + fax(x, xd)
        if t < t_drop or not drop_axial:
            fa += amb_force(x, xd, -thrust(t), kax_amb, cax_amb)
        out[i_ax] = fa
        return out

    return f


def rotor_loads_jacobian(spec: LandingSpec, *, gyroscopic_in_user_function: bool = True):
    """Analytic derivatives of :func:`rotor_forces` for Exudyn's ``jacobianUserFunction``:
    ``jac(t, q, v, fq, fv)`` returns -(fq dF/dq + fv dF/dv) over the same local coordinates
    (AMB, unbalance, windage, drive, axial contact and AMB; gyroscopics only when in the user
    function)."""
    (n_lat, G, t_drop, k_amb, c_amb, rows, kax_amb, cax_amb, drop_radial, drop_axial, unb, u_mag, u_phase, wind, cw1,
     cw2, constant_drive, gain, _, fax) = _rotor_loads(spec, gyroscopic_in_user_function)
    if unb is not None:
        uy, uz = unb
    a = spec.scenario.axial
    cl_ax, dm, cax = a.cl_ax, a.delta_m, a.c_ax
    k1 = 1.0 / (1.0 / a.k_cb + 1.0 / a.k_ws)
    k2 = 1.0 / (1.0 / a.k_cb + 1.0 / a.k_h)
    n = n_lat + 2
    i_th, i_ax = n_lat, n_lat + 1

    def jac(t, q, v, fq, fv):
        Jq = np.zeros((n, n))
        Jv = np.zeros((n, n))
        omega = v[i_th]
        if G is not None:
            Jv[:n_lat, :n_lat] -= omega * G
            Jv[:n_lat, i_th] -= G @ np.asarray(v[:n_lat])
        if n_lat and (t < t_drop or not drop_radial):
            for iy, iz in rows:
                Jq[iy, iy] -= k_amb
                Jq[iz, iz] -= k_amb
                Jv[iy, iy] -= c_amb
                Jv[iz, iz] -= c_amb
        if unb is not None:
            ang = q[i_th] + u_phase
            ca, sa = math.cos(ang), math.sin(ang)
            fu = u_mag * omega * omega
            Jq[:n_lat, i_th] += fu * (-uy * sa + uz * ca)
            Jv[:n_lat, i_th] += 2.0 * u_mag * omega * (uy * ca + uz * sa)
        dt = 0.0
        if wind:
            dt += windage_torque_derivative(omega, cw1, cw2)
        if constant_drive:
            dt -= gain
        Jv[i_th, i_th] = dt
        x, xd = q[i_ax], v[i_ax]
        if fax(x, xd) != 0.0:
            Jq[i_ax, i_ax] = -(k1 if abs(x) - cl_ax <= dm else k2)
            Jv[i_ax, i_ax] = -cax
        if t < t_drop or not drop_axial:
            Jq[i_ax, i_ax] -= kax_amb
            Jv[i_ax, i_ax] -= cax_amb
        return -(fq * Jq + fv * Jv)

    return jac


BEARING_LOCAL = ("station_y", "station_z", "theta", "x_axial", "race_y", "race_z", "race_phi", "outer_y", "outer_z")


def bearing_forces(spec: LandingSpec, b: BearingSpec, tilt: list | None = None):
    """Closure for one catcher bearing: radial contact, axial rub, balls, drag, ribbon, friction.

    Local coordinates: ``BEARING_LOCAL`` (9). ``tilt`` is a 2-list [alpha, beta] of the rotor tilt
    at the station that the caller keeps up to date once per time step (needed only by the
    bearing with the axial face when axial rub is on). The tilt only shapes the face pressure
    field and changes little within a step; reading it from the start of the step keeps this
    object at 9 coordinates instead of the whole rotor, which makes its numerical Jacobian 2.5x
    cheaper."""
    L = b.laws
    a = spec.scenario.axial
    clearance, r_rot, r_race = L.clearance, L.sleeve_radius, L.race_radius
    kh, ex, v_reg, kv, mu = L.k_hertz, L.exponent, L.v_reg, L.k_visc, L.mu_rad
    kb1, kb2, cb = L.k_b1, L.k_b2, L.c_b
    drag, hp = L.ball_drag, L.hp
    worn, worn_phi = L.worn_drag_torque, L.worn_drag_growth_angle
    worn_mu, worn_k = L.worn_drag_friction, L.worn
    fa_pre = L.drag_axial_preload
    krib, crib, eta = L.k_rib, L.c_rib, L.eta
    coulomb, mu_d = L.outer_coulomb, L.mu_d
    ci, co = L.inner_race_damping, L.outer_race_damping
    wi, wo = -L.inner_race_mass * G_ACC, -L.outer_race_mass * G_ACC
    face, rub = L.axial_face, L.axial_rub
    if rub and tilt is None:
        raise ValueError(f"bearing {b.name}: axial rub needs the tilt holder")
    mu_ax, r1, r2, v_reg_ax = L.mu_ax, L.face_inner_radius, L.face_outer_radius, L.v_reg_axial
    cl_ax, dm, kcb, kws, khs, cax = a.cl_ax, a.delta_m, a.k_cb, a.k_ws, a.k_h, a.c_ax

    def f(t, q, v):
        sy, sz, _, x, ry, rz, phi_i, oy, oz = q
        vsy, vsz, omega, xd, vry, vrz, omega_i, voy, voz = v
        dy, dz = sy - ry, sz - rz
        dvy, dvz = vsy - vry, vsz - vrz
        fy, fz, t_rot, t_race, _, _, _, _ = radial_contact(dy, dz, dvy, dvz, omega, omega_i, clearance, kh, ex, kv,
                                                           mu, v_reg, r_rot, r_race)
        f_ax = abs(axial_force(x, xd, cl_ax, dm, kcb, kws, khs, cax)) if face else 0.0
        if rub and f_ax > 0.0:
            gy, gz, gr, gi, _ = axial_rub(dy, dz, dvy, dvz, omega, omega_i, tilt[0], tilt[1], abs(x) - cl_ax, f_ax,
                                          1.0 if x >= 0 else -1.0, mu_ax, v_reg_ax, r1, r2)
            fy += gy
            fz += gz
            t_rot += gr
            t_race += gi
        # balls: force on the inner race from r = inner - outer
        by, bz = ball_force(ry - oy, rz - oz, kb1, kb2, vry - voy, vrz - voz, cb)
        if drag:
            t_race += harris_palmgren_fast(omega_i, math.hypot(by, bz), f_ax + fa_pre, hp)
        if worn:
            t_race += worn_drag_torque(omega_i, worn, OMEGA_REG_HP, phi_i, worn_phi)
        if worn_mu:
            t_race += worn_friction_with_derivatives(omega_i, math.hypot(by, bz), f_ax + fa_pre, phi_i, worn_k)[0]
        hy, hz = ribbon_force(oy, oz, voy, voz, krib, crib, eta, v_reg)
        if coulomb and f_ax > 0.0:
            ky, kz = outer_race_friction(voy, voz, f_ax, mu_d, v_reg)
            hy += ky
            hz += kz
        out = [fy, fz, t_rot, 0.0, -fy + by - ci * vry, -fz + bz - ci * vrz + wi, t_race,
               -by + hy - co * voy, -bz + hz - co * voz + wo]
        for force, x in extra:
            for i, fi in enumerate(force(x, q, v)):
                out[i] += fi
        return out

    extra = [(m.force, L.extra) for m in registry_forces(spec, L)]
    return f


def registry_forces(spec: LandingSpec, laws) -> list:
    """The active mechanisms of the registry that bring their own solver hook (not compiled into
    bearing_kernel) for one bearing's resolved laws."""
    from .mechanisms import REGISTRY

    return [m for m in REGISTRY if m.force is not None and m.active(spec, laws)]


def mechanism_functions(m, laws):
    """Exudyn (force, jacobian) user functions of a registry mechanism over BEARING_LOCAL; the
    jacobian is None (Exudyn differentiates numerically) when the mechanism declares none."""
    x, force_law, jac_law = laws.extra, m.force, m.jacobian

    def force(mbs, t, item, q, q_t):
        return list(force_law(x, q, q_t))

    if jac_law is None:
        return force, None

    def jacobian(mbs, t, item, q, q_t, fq, fv):
        Jq, Jv = jac_law(x, q, q_t)
        return -(fq * np.asarray(Jq) + fv * np.asarray(Jv))

    return force, jacobian

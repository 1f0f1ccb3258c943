"""Post-processing of a landing run: forces, powers, energy balance, whirl, summary.

The laws are re-evaluated on the stored states (the same ``user_forces`` functions the solver
used), so every force and every dissipated power is available as a time series without
side effects in the solver's user functions. With states stored at every time step
(``solver.output_period = solver.step``) the energy integrals are accurate to the integrator.

Energy bookkeeping (all in J)::

    E_kin = 1/2 q_lat'^T M q_lat' + 1/2 I_p Omega^2 + 1/2 m_r x'^2 + sum_b (1/2 m_i |r_i'|^2 + 1/2 I_i phi'^2 + 1/2 m_o |r_o'|^2)
    E_pot = 1/2 q_lat^T K q_lat - f_g^T q_lat + sum_b g (m_i z_i + m_o z_o)
            + Hertz k delta^(e+1)/(e+1) + balls (k_b1 r^2/2 + k_b2 r^3/3) + ribbon k |r_o|^2/2 + V_ax(x)
    dissipated (>= 0, per mechanism): radial friction, contact damping, axial rub, ball damping,
            ball drag, ribbon damping, ribbon cross-coupling, outer-race Coulomb, windage, axial
            damping, rotor damping, race damping
    input work: AMB forces before the drop, thrust, drive torque, unbalance force
    residual = Delta(E_kin + E_pot) + sum(dissipated) - sum(input)

The residual measures numerical energy error (time integration, sampling); the energy test
asserts it is < 1 % of the dissipated energy.
"""

from __future__ import annotations

import math

import numpy as np

from user_forces.axial import axial_force
from user_forces.axial_rub import axial_rub
from user_forces.ball_bearing import ball_force, harris_palmgren_fast, worn_drag_torque, worn_friction_with_derivatives
from user_forces.radial_contact import radial_contact
from user_forces.ribbon import outer_race_friction, ribbon_force
from user_forces.spin import windage_torque

from .params import OMEGA_REG_HP
from .landing import G_ACC, LandingSpec
from .whirl import WhirlResult, landing_whirl_bearing, whirl_analysis

MECHANISMS = ("radial_friction", "contact_damping", "axial_rub", "ball_damping", "ball_drag", "worn_bearing_drag",
              "ribbon_damping", "ribbon_cross_coupling", "outer_race_coulomb", "windage", "axial_damping",
              "rotor_damping", "race_damping")
INPUTS = ("amb", "thrust", "drive", "unbalance")


def axial_potential(x: np.ndarray, a) -> np.ndarray:
    """Elastic potential of the piecewise axial law (eqs 4-5), V(x) with -dV/dx = F_ax(x, 0)."""
    k1 = 1.0 / (1.0 / a.k_cb + 1.0 / a.k_ws)
    k2 = 1.0 / (1.0 / a.k_cb + 1.0 / a.k_h)
    s = np.maximum(np.abs(x) - a.cl_ax, 0.0)
    s1 = np.minimum(s, a.delta_m)
    s2 = np.maximum(s - a.delta_m, 0.0)
    return 0.5 * k1 * s1**2 + k1 * a.delta_m * s2 + 0.5 * k2 * s2**2


def _trapz_cum(y: np.ndarray, t: np.ndarray) -> np.ndarray:
    out = np.zeros_like(y)
    out[1:] = np.cumsum(0.5 * (y[1:] + y[:-1]) * np.diff(t))
    return out


def evaluate(spec: LandingSpec, t: np.ndarray, q: np.ndarray, v: np.ndarray) -> dict:
    """Time series of forces, torques, powers and energies (SI), keyed by name."""
    sc = spec.scenario
    a = sc.axial
    nt = len(t)
    n_lat = spec.n_lat
    omega = v[:, spec.i_theta]
    x, xd = q[:, spec.i_axial], v[:, spec.i_axial]
    out: dict[str, np.ndarray] = {}
    power = {k: np.zeros(nt) for k in MECHANISMS}
    inp = {k: np.zeros(nt) for k in INPUTS}
    f_ax_el = np.array([axial_force(xi, 0.0, a.cl_ax, a.delta_m, a.k_cb, a.k_ws, a.k_h, a.c_ax) for xi in x])
    f_ax = np.array([axial_force(xi, vi, a.cl_ax, a.delta_m, a.k_cb, a.k_ws, a.k_h, a.c_ax) for xi, vi in zip(x, xd)])
    out["axial_force_n"] = f_ax
    power["axial_damping"] = -(f_ax - f_ax_el) * xd
    epot = np.zeros(nt)
    ekin = np.zeros(nt)
    # rotor
    ql, vl = q[:, :n_lat], v[:, :n_lat]
    ekin += 0.5 * np.einsum("ti,ij,tj->t", vl, spec.M, vl) + 0.5 * spec.rotor_polar_inertia * omega**2 \
        + 0.5 * spec.rotor_mass * xd**2
    epot += 0.5 * np.einsum("ti,ij,tj->t", ql, spec.K, ql) - ql @ spec.f_gravity + axial_potential(x, a)
    power["rotor_damping"] = np.einsum("ti,ij,tj->t", vl, spec.C, vl)
    rl = spec.rotor_laws
    if rl.windage:
        tw = np.array([windage_torque(w, rl.c_w1, rl.c_w2) for w in omega])
        power["windage"] = -tw * omega
    if rl.constant_drive:
        inp["drive"] = rl.drive_gain * (rl.omega0 - omega) * omega
    amb_on = (t < sc.amb.t_drop) | (not sc.amb.drop_radial)
    for iy, iz in spec.amb_rows:
        for i in (iy, iz):
            f = -spec.f_gravity[i] - sc.amb.stiffness * q[:, i] - sc.amb.damping * v[:, i]
            inp["amb"] += np.where(amb_on, f * v[:, i], 0.0)
    thrust = np.array([spec.thrust(ti) for ti in t])
    inp["thrust"] = thrust * xd
    ax_on = (t < sc.amb.t_drop) | (not sc.amb.drop_axial)
    inp["amb"] += np.where(ax_on, (-thrust - sc.amb.axial_stiffness * x - sc.amb.axial_damping * xd) * xd, 0.0)
    if spec.unbalance_rows is not None:
        ry, rz = spec.unbalance_rows
        ang = q[:, spec.i_theta] + math.radians(sc.unbalance.phase_deg)
        fu = sc.unbalance.magnitude * omega**2
        inp["unbalance"] = fu * (np.cos(ang) * (vl @ ry) + np.sin(ang) * (vl @ rz))

    for b in spec.bearings:
        pre = b.name + "_"
        s, r = b.i_station, b.i_race
        o = b.i_outer
        cols = {k: np.zeros(nt) for k in ("contact_force_y_n", "contact_force_z_n", "normal_force_n", "penetration_m",
                                          "slip_velocity_m_s", "rub_force_y_n", "rub_force_z_n", "ball_force_y_n",
                                          "ball_force_z_n", "drag_torque_nm", "ribbon_force_y_n", "ribbon_force_z_n")}
        L = b.laws
        kv, mu, eta, rub, hp = L.k_visc, L.mu_rad, L.eta, L.axial_rub, L.hp
        for k in range(nt):
            qk, vk = q[k], v[k]
            dy, dz = qk[s] - qk[r], qk[s + 1] - qk[r + 1]
            dvy, dvz = vk[s] - vk[r], vk[s + 1] - vk[r + 1]
            wi = vk[r + 2]
            fy, fz, _, _, fn, delta, vs, pf = radial_contact(dy, dz, dvy, dvz, omega[k], wi, L.clearance, L.k_hertz,
                                                             L.exponent, kv, mu, L.v_reg, L.sleeve_radius,
                                                             L.race_radius)
            cols["contact_force_y_n"][k], cols["contact_force_z_n"][k] = fy, fz
            cols["normal_force_n"][k], cols["slip_velocity_m_s"][k] = fn, vs
            if delta > 0:
                cols["penetration_m"][k] = delta
                dist = math.hypot(dy, dz)
                ddot = (dy * dvy + dz * dvz) / dist
                el = L.k_hertz * delta**L.exponent
                power["contact_damping"][k] += (fn - el) * ddot
                epot[k] += L.k_hertz * delta ** (L.exponent + 1) / (L.exponent + 1)
            power["radial_friction"][k] += pf
            n_ax = abs(f_ax[k]) if L.axial_face else 0.0
            if rub and n_ax > 0:
                al = float(b.tilt_alpha @ qk[:n_lat])
                be = float(b.tilt_beta @ qk[:n_lat])
                ry_, rz_, _, _, prub = axial_rub(dy, dz, dvy, dvz, omega[k], wi, al, be, abs(x[k]) - a.cl_ax, n_ax,
                                                 1.0 if x[k] >= 0 else -1.0, L.mu_ax, L.v_reg_axial, L.face_inner_radius,
                                                 L.face_outer_radius)
                cols["rub_force_y_n"][k], cols["rub_force_z_n"][k] = ry_, rz_
                power["axial_rub"][k] += prub
            ey, ez = qk[r] - qk[o], qk[r + 1] - qk[o + 1]
            evy, evz = vk[r] - vk[o], vk[r + 1] - vk[o + 1]
            by, bz = ball_force(ey, ez, L.k_b1, L.k_b2, evy, evz, L.c_b)
            cols["ball_force_y_n"][k], cols["ball_force_z_n"][k] = by, bz
            rr = math.hypot(ey, ez)
            epot[k] += L.k_b1 * rr * rr / 2 + L.k_b2 * rr**3 / 3
            power["ball_damping"][k] += L.c_b * (evy * evy + evz * evz)
            if L.ball_drag:
                thp = harris_palmgren_fast(wi, math.hypot(by, bz), n_ax, hp)
                cols["drag_torque_nm"][k] = thp
                power["ball_drag"][k] += -thp * wi
            if L.worn_drag_torque > 0:
                tw = worn_drag_torque(wi, L.worn_drag_torque, OMEGA_REG_HP, qk[r + 2], L.worn_drag_growth_angle)
                cols["drag_torque_nm"][k] += tw
                power["worn_bearing_drag"][k] += -tw * wi
            if L.worn_drag_friction > 0:
                tw = worn_friction_with_derivatives(wi, math.hypot(by, bz), n_ax, qk[r + 2], L.worn)[0]
                cols["drag_torque_nm"][k] += tw
                power["worn_bearing_drag"][k] += -tw * wi
            oy, oz, ovy, ovz = qk[o], qk[o + 1], vk[o], vk[o + 1]
            gy, gz = ribbon_force(oy, oz, ovy, ovz, L.k_rib, L.c_rib, eta, L.v_reg)
            cols["ribbon_force_y_n"][k], cols["ribbon_force_z_n"][k] = gy, gz
            epot[k] += 0.5 * L.k_rib * (oy * oy + oz * oz)
            power["ribbon_damping"][k] += L.c_rib * (ovy * ovy + ovz * ovz)
            ccy, ccz = gy + L.c_rib * ovy + L.k_rib * oy, gz + L.c_rib * ovz + L.k_rib * oz
            power["ribbon_cross_coupling"][k] += -(ccy * ovy + ccz * ovz)
            if L.outer_coulomb and n_ax > 0:
                hy, hz = outer_race_friction(ovy, ovz, n_ax, L.mu_d, L.v_reg)
                power["outer_race_coulomb"][k] += -(hy * ovy + hz * ovz)
        power["race_damping"] += L.inner_race_damping * (v[:, r] ** 2 + v[:, r + 1] ** 2) \
            + L.outer_race_damping * (v[:, o] ** 2 + v[:, o + 1] ** 2)
        ekin += 0.5 * L.inner_race_mass * (v[:, r] ** 2 + v[:, r + 1] ** 2) + 0.5 * L.inner_race_inertia * v[:, r + 2] ** 2 \
            + 0.5 * L.outer_race_mass * (v[:, o] ** 2 + v[:, o + 1] ** 2)
        epot += G_ACC * (L.inner_race_mass * q[:, r + 1] + L.outer_race_mass * q[:, o + 1])
        for key, val in cols.items():
            out[pre + key] = val
        out[pre + "y_m"], out[pre + "z_m"] = q[:, s], q[:, s + 1]
        # the inner race's centre: the journal's orbit relative to it is what the clearance bounds
        out[pre + "race_y_m"], out[pre + "race_z_m"] = q[:, r], q[:, r + 1]
        out[pre + "race_speed_rpm"] = v[:, r + 2] * 30 / math.pi
    out["rotor_speed_rpm"] = omega * 30 / math.pi
    out["axial_position_m"] = x
    out["kinetic_energy_j"] = ekin
    out["potential_energy_j"] = epot
    for k in MECHANISMS:
        out["power_" + k + "_w"] = power[k]
        out["dissipated_" + k + "_j"] = _trapz_cum(power[k], t)
    for k in INPUTS:
        out["input_" + k + "_j"] = _trapz_cum(inp[k], t)
    return out


def energy_summary(series: dict) -> dict:
    de = (series["kinetic_energy_j"][-1] + series["potential_energy_j"][-1]) \
        - (series["kinetic_energy_j"][0] + series["potential_energy_j"][0])
    diss = {k: float(series["dissipated_" + k + "_j"][-1]) for k in MECHANISMS}
    inputs = {k: float(series["input_" + k + "_j"][-1]) for k in INPUTS}
    total = sum(diss.values())
    residual = de + total - sum(inputs.values())
    return {"dissipated_j": diss, "dissipated_total_j": total, "input_work_j": inputs,
            "change_of_mechanical_energy_j": float(de), "balance_residual_j": float(residual),
            "balance_error_relative": float(abs(residual) / total) if total > 0 else 0.0}


def uniform(t: np.ndarray, *arrays: np.ndarray):
    """Resample to a uniform grid (Exudyn shortens steps after Newton failures, so stored sample
    times can be irregular; spectra need uniform sampling). Grid step = median sample spacing."""
    dt = float(np.median(np.diff(t)))
    tu = t[0] + dt * np.arange(int(np.floor((t[-1] - t[0]) / dt + 1e-9)) + 1)
    return (tu,) + tuple(np.interp(tu, t, a) for a in arrays)


def summarize(spec: LandingSpec, t: np.ndarray, series: dict, *, t_drop: float | None = None) -> dict:
    sc = spec.scenario
    t_drop = sc.amb.t_drop if t_drop is None else t_drop
    bearings = {}
    whirls = {}
    for b in spec.bearings:
        pre = b.name + "_"
        y, z = series[pre + "y_m"], series[pre + "z_m"]
        fy = series[pre + "contact_force_y_n"] + series[pre + "rub_force_y_n"]
        fz = series[pre + "contact_force_z_n"] + series[pre + "rub_force_z_n"]
        bearings[b.name] = {
            "station": b.station,
            "clearance_m": b.params.clearance,
            "max_contact_force_n": float(np.max(np.hypot(fy, fz))) if len(t) else 0.0,
            "vertical_force_range_n": [float(np.min(fz)), float(np.max(fz))],
            "horizontal_force_range_n": [float(np.min(fy)), float(np.max(fy))],
            "vertical_displacement_range_m": [float(np.min(z)), float(np.max(z))],
            "horizontal_displacement_range_m": [float(np.min(y)), float(np.max(y))],
            "max_penetration_m": float(np.max(series[pre + "penetration_m"])),
            "final_race_speed_rpm": float(series[pre + "race_speed_rpm"][-1]),
        }
        try:
            tu, yu, zu, spin_rpm = uniform(t, y, z, series["rotor_speed_rpm"])
            wr = whirl_analysis(tu, yu, zu, clearance=b.params.clearance, spin_hz=spin_rpm / 60.0, t_start=t_drop)
            whirls[b.name] = wr.to_dict()
        except ValueError as err:  # record too short for the analysis window
            whirls[b.name] = {**WhirlResult("none", None, None, 0.0).to_dict(), "note": str(err)}
    name = landing_whirl_bearing(whirls)
    return {
        "scenario": sc.name,
        "whirl": {**whirls[name], "bearing": name, "per_bearing": whirls},
        "bearings": bearings,
        "speeds": {"initial_rotor_rpm": sc.speed_rpm, "final_rotor_rpm": float(series["rotor_speed_rpm"][-1]),
                   "final_inner_race_rpm": {b.name: bearings[b.name]["final_race_speed_rpm"] for b in spec.bearings}},
        "axial": {"position_range_m": [float(np.min(series["axial_position_m"])),
                                       float(np.max(series["axial_position_m"]))],
                  "max_axial_force_n": float(np.max(np.abs(series["axial_force_n"])))},
        "energy": energy_summary(series),
    }

"""Post-processing of a landing run: forces, powers, energy balance, whirl, summary.

The laws are re-evaluated on the stored states by the mechanism registry
(:mod:`rotorlanding.mechanisms`: each mechanism's ``post`` hook calls the same ``user_forces``
functions the solver used), so every force and every dissipated power is available as a time
series without side effects in the solver's user functions. With states stored at every time step
(``solver.output_period = solver.step``) the energy integrals are accurate to the integrator.

Energy bookkeeping (all in J)::

    E_kin = 1/2 q_lat'^T M q_lat' + 1/2 I_p Omega^2 + 1/2 m_r x'^2 + sum_b (1/2 m_i |r_i'|^2 + 1/2 I_i phi'^2 + 1/2 m_o |r_o'|^2)
    E_pot = 1/2 q_lat^T K q_lat - f_g^T q_lat + sum_b g (m_i z_i + m_o z_o)
            + Hertz k delta^(e+1)/(e+1) + balls (k_b1 r^2/2 + k_b2 r^3/3) + ribbon k |r_o|^2/2 + V_ax(x)
    dissipated (>= 0): one entry per ``Mechanism.dissipation`` of the registry (MECHANISMS)
    input work: one entry per ``Mechanism.inputs`` (INPUTS): AMB forces before the drop, thrust,
            drive torque, unbalance force
    residual = Delta(E_kin + E_pot) + sum(dissipated) - sum(input)

The residual measures numerical energy error (time integration, sampling); the energy test
asserts it is < 1 % of the dissipated energy.
"""

from __future__ import annotations

import numpy as np

from .landing import LandingSpec
from .mechanisms import axial_potential, dissipation_entries, input_entries, rotor_force
from .mechanisms import evaluate as _evaluate
from .thermal_states import summary as thermal_summary
from .whirl import WhirlResult, landing_whirl_bearing, whirl_analysis, whirl_shape

MECHANISMS = dissipation_entries()
INPUTS = input_entries()
__all__ = ["MECHANISMS", "INPUTS", "axial_potential", "evaluate", "energy_summary", "summarize", "uniform"]


def evaluate(spec: LandingSpec, t: np.ndarray, q: np.ndarray, v: np.ndarray, carry: dict | None = None,
             skip: frozenset | tuple = ()) -> dict:
    """Time series of forces, torques, powers and energies (SI), keyed by name; the names and
    units are :func:`rotorlanding.mechanisms.series_units`; ``carry``: the carried states' start
    values (a coast-down chunk; :func:`rotorlanding.mechanisms.evaluate`); ``skip``: mechanisms
    whose post-processing is left out (their series stay zero)."""
    return _evaluate(spec, t, q, v, carry, skip)


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


def span_deflection(spec: LandingSpec, q: np.ndarray) -> dict:
    """How far the rotor runs off the bearings' common axis along its whole span, not only at the
    sleeves the catcher bearings bound: the lateral displacement at every FE node rebuilt from the
    Craig-Bampton coordinates (``cb.T @ q_lat``: constraint modes plus fixed-interface modes, as
    the reduction defines them). A landed whirl that bends the shaft can run the rotor into an AMB
    stator, a sensor or a seal while its sleeves stay inside their clearance (docs/calibration.md,
    session 35). Returns ``{"station_peak_m": {station: largest radial displacement [m]},
    "peak_m", "peak_x_m", "x_m": node positions, "node_peak_m": the largest at each node,
    "station_x_m"}`` over the
    samples of ``q`` (rows); the last two draw the envelope along the span (``plots``, span.png)."""
    q = np.atleast_2d(q)
    full = q[:, :spec.n_lat] @ spec.cb.T.T  # every full-model DOF: per node y, z and two rotations
    per = spec.cb.T.shape[0] // len(spec.fe.nodes)
    r = np.hypot(full[:, 0::per], full[:, 1::per]).max(axis=0)
    i = int(np.argmax(r))
    return {"station_peak_m": {k: float(r[n]) for k, n in spec.fe.station_nodes.items()},
            "peak_m": float(r[i]), "peak_x_m": float(spec.fe.nodes[i]),
            "x_m": [float(x) for x in spec.fe.nodes], "node_peak_m": [float(x) for x in r],
            "station_x_m": {k: float(spec.fe.nodes[n]) for k, n in spec.fe.station_nodes.items()}}


def uniform(t: np.ndarray, *arrays: np.ndarray):
    """Resample to a uniform grid (Exudyn shortens steps after Newton failures, so stored sample
    times can be irregular; spectra need uniform sampling). Grid step = median sample spacing."""
    dt = float(np.median(np.diff(t)))
    tu = t[0] + dt * np.arange(int(np.floor((t[-1] - t[0]) / dt + 1e-9)) + 1)
    return (tu,) + tuple(np.interp(tu, t, a) for a in arrays)


def _shape(orbits: dict, name: str, w: dict) -> dict:
    """``{"shape": ...}``: the landing whirl's shape against the other journal
    (:func:`rotorlanding.whirl.whirl_shape`) over its whirl phase, from the uniformly resampled
    orbits the whirl analysis used (``orbits``: bearing -> (t, y, z)), for a rotor on two catcher
    bearings that whirls; ``{}`` otherwise (one bearing, or no whirl to take a shape of)."""
    others = [b for b in orbits if b != name]
    if w["direction"] == "none" or len(others) != 1 or name not in orbits or w.get("onset_s") is None:
        return {}
    o = others[0]
    (tu, y, z), (_, yo, zo) = orbits[name], orbits[o]
    t1 = w["end_s"] if w.get("end_s") is not None else tu[-1]
    try:
        sh = whirl_shape(tu, y, z, yo, zo, frequency_hz=w["frequency_hz"], direction=w["direction"],
                         t0=w["onset_s"], t1=t1)
    except ValueError:  # a whirl phase too short to demodulate
        return {}
    return {"shape": {"against": o, **sh}}


def summarize(spec: LandingSpec, t: np.ndarray, series: dict, *, t_drop: float | None = None) -> dict:
    sc = spec.scenario
    t_drop = sc.amb.t_drop if t_drop is None else t_drop
    bearings = {}
    whirls = {}
    orbits = {}  # bearing -> the uniform (t, y, z) the whirl analysis read, for the whirl's shape
    for b in spec.bearings:
        pre = b.name + "_"
        y, z = series[pre + "y_m"], series[pre + "z_m"]
        fy, fz = rotor_force(series, b.name)
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
            orbits[b.name] = (tu, yu, zu)
            wr = whirl_analysis(tu, yu, zu, clearance=b.params.clearance, spin_hz=spin_rpm / 60.0, t_start=t_drop)
            whirls[b.name] = wr.to_dict()
        except ValueError as err:  # record too short for the analysis window
            whirls[b.name] = {**WhirlResult("none", None, None, 0.0).to_dict(), "note": str(err)}
    name = landing_whirl_bearing(whirls)
    out = {
        "scenario": sc.name,
        "whirl": {**whirls[name], "bearing": name, "per_bearing": whirls,
                  **_shape(orbits, name, whirls[name])},
        "bearings": bearings,
        "speeds": {"initial_rotor_rpm": sc.speed_rpm, "final_rotor_rpm": float(series["rotor_speed_rpm"][-1]),
                   "final_inner_race_rpm": {b.name: bearings[b.name]["final_race_speed_rpm"] for b in spec.bearings}},
        "axial": {"position_range_m": [float(np.min(series["axial_position_m"])),
                                       float(np.max(series["axial_position_m"]))],
                  "max_axial_force_n": float(np.max(np.abs(series["axial_force_n"])))},
        "energy": energy_summary(series),
    }
    thermal = thermal_summary(spec, t, series)
    if thermal:
        out["thermal"] = thermal
    return out

"""The designer's verdict of a landing or coast-down (issue 18): every criterion of ``[limits]``
with its value, limit, margin, pass/fail and what dominates it; ``verdict.json``, ``verdict.md``
and ``temperatures.png``, each written atomically.

Criteria, per catcher bearing, from the stored series of a run (``results.h5``) and the existing
laws (``user_forces``):

- **ball-race contact pressure** (ISO 76): the bearing load on the ball set F_r = |ball force| and
  its axial load F_a (the axial contact force where the bearing takes the thrust, plus the thermal
  preload when thermal feedback is on) -> the load of the most loaded ball by the discrete
  Stribeck/Harris distribution (``contact_stress.ball_loads_fast``, compiled; Z balls, the actual
  internal clearance: the feedback's series, else its cold default 20 um, assumed; once it is
  negative the rings move apart axially until the balls carry F_a, preload included) -> the Hertz
  peak pressure p0 = c Q_max^(1/3) on the inner and the outer race (Hertz point contact: p0 ~
  Q^(1/3) exactly, c from ``hertz_point_contact`` at 1 N; 7212 BE internal geometry, assumed:
  docs/designer_models.md). Time and count above the limit (``fatigue.static_exceedance``).
  Loads are rounded to 3 significant digits before the distribution is solved (p0 changes by
  < 0.2 %), so a long coast-down solves each distinct load once.
- **sleeve-bore contact pressure**: the aligned line contact of the sleeve in the bore (Johnson
  sec. 4.3, ``contact_stress.sleeve_ring_line``, length = ring width) at the contact normal force.
  Indicative above ~10 kN, where the half-width is no longer small against the radii (conformal
  contact).
- **temperature**: the hottest node of the bearing's thermal network (``catcher_thermal``).
- **thermal runaway**: the feedback's runaway detection (only with ``effects.thermal_feedback``).
- **damage per drop and allowable drops** (``fatigue``): overrolling damage sum rev_i / N(p_i)
  (ISO 281's variable-load rule as Palmgren-Miner in pressure, N = 1e6 (p_ref/p)^n revolutions,
  p_ref = the law's inner-race pressure at F_r = C) plus the rainflow damage of the inner-race
  pressure envelope (each cycle at its peak); the two added (conservative). Allowable drops =
  1 / damage; the criterion: allowable >= drops_required. Fatigue only (see below).
- **whirl**: the landed journal's whirl (direction, frequency, onset) against
  ``whirl_acceptable_below_rpm``: a whirl that starts above that rotor speed fails. Its bearing:
  the landing's whirl bearing; for a coast-down the one whirling longest over its chunks
  (:func:`whirl_bearing`).
- **whirl severity**: the time whirling and (landing runs) the orbit amplitude over the radial
  clearance (``whirl_time_s``, ``whirl_orbit_over_clearance``), and the **peak contact force** per
  bearing (``contact_force_n``): judged when their limit is > 0, else reported ('reported' rows).

- **close clearances** (``close_clearances_m``, per rotor station): the rotor's largest displacement
  off the bearings' axis at the station over the run (``summary.json`` ``rotor_deflection``) against
  the radial gap of the AMB stator, sensor or seal there. Its 'bearing' column names the station.

The allowable drops are rolling-contact fatigue only: wear, cage damage and heat are not in that
number (the reports say so next to it).

Margin: (limit - value) / limit for a maximum; allowable / required - 1 for the drops. The
verdict passes when every evaluated criterion passes.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from user_forces.contact_stress import (BEARING_7212BE_ASSUMED, STEEL_E_STAR, ball_race_contact, ball_stiffness_kn,
                                        conformal_radius)
from user_forces.fatigue import allowable_drops, overrolling_damage, rainflow_damage, static_exceedance, \
    stress_life_from_rating

from .limits import KELVIN_0C, SOURCES, Limits, limits_from_dict
from .safeio import atomic_write_text, save_figure
from .whirl import longest_whirl

_BALL_LOADS = None
DEFAULT_INTERNAL_CLEARANCE_M = 20.0e-6  # m: the thermal_feedback mechanism's cold default (assumed)


def _ball_loads():
    """``contact_stress.ball_loads_fast`` compiled once (numba), as the tests compile it."""
    global _BALL_LOADS
    if _BALL_LOADS is None:
        import numba

        from user_forces.contact_stress import ball_loads_fast

        _BALL_LOADS = numba.njit(cache=True)(ball_loads_fast)
    return _BALL_LOADS


def _round3(x: np.ndarray) -> np.ndarray:
    """x rounded to 3 significant digits (0 stays 0)."""
    x = np.asarray(x, float)
    out = np.zeros_like(x)
    nz = x > 0
    e = np.floor(np.log10(x[nz])) - 2
    out[nz] = np.round(x[nz] / 10.0 ** e) * 10.0 ** e
    return out


def ball_pressures(f_r, f_a, clearance, laws):
    """Peak Hertz pressures (inner, outer) [Pa] of the most loaded ball for load histories [N] and
    the internal (diametral) clearance history [m] (module docstring)."""
    from dataclasses import replace

    geom = replace(BEARING_7212BE_ASSUMED, pitch_diameter=laws.pitch_diameter,
                   contact_angle_deg=laws.contact_angle_deg)
    k_n = ball_stiffness_kn(geom)
    c_in = ball_race_contact(1.0, geom, "inner")[0]
    c_out = ball_race_contact(1.0, geom, "outer")[0]
    loads = _ball_loads()
    key = np.column_stack([_round3(np.abs(f_r)), _round3(np.abs(f_a)), np.round(np.asarray(clearance) * 1e9) / 1e9])
    uniq, inv = np.unique(key, axis=0, return_inverse=True)
    qmax = np.array([loads(fr, fa, geom.n_balls, math.radians(geom.contact_angle_deg), k_n, pd, 0.0)[0]
                     for fr, fa, pd in uniq])[np.ravel(inv)]
    cube = np.cbrt(qmax)
    return c_in * cube, c_out * cube, geom, k_n


def _pressure_at_rating(c_dyn, laws) -> float:
    """Inner-race peak pressure at F_r = C (zero clearance): the stress-life anchor p_ref."""
    p_in, _, _, _ = ball_pressures(np.array([c_dyn]), np.array([0.0]), np.array([0.0]), laws)
    return float(p_in[0])


def _max_criterion(name, bearing, value, limit, unit, dominant, note=""):
    return {"criterion": name, "bearing": bearing, "value": value, "limit": limit, "unit": unit,
            "margin": (limit - value) / limit, "pass": bool(value <= limit), "dominant": dominant,
            **({"note": note} if note else {})}


def bearing_criteria(spec, b, t, s, limits: Limits, summary: dict) -> tuple[list, dict]:
    """The criteria of one bearing and its damage record."""
    from .mechanisms import thermal_active, thermal_feedback_active
    from .thermal_states import NODE_SERIES, ROUTES, ROUTE_SERIES
    from user_forces.thermal import NODE_NAMES

    pre = b.name + "_"
    L = b.laws
    out = []
    # ball-race pressures
    f_r = np.hypot(s[pre + "ball_force_y_n"], s[pre + "ball_force_z_n"])
    f_a = np.abs(s["axial_force_n"]) if L.axial_face else np.zeros(len(t))
    fb = thermal_feedback_active(spec, L)
    if fb:
        f_a = f_a + s[pre + "thermal_preload_n"]
        pd = np.asarray(s[pre + "internal_clearance_m"])
    else:
        pd = np.full(len(t), DEFAULT_INTERNAL_CLEARANCE_M)
    p_in, p_out, geom, _ = ball_pressures(f_r, f_a, pd, L)
    p_ball = np.maximum(p_in, p_out)
    i = int(np.argmax(p_ball))
    above, count, peak = static_exceedance(t.tolist(), p_ball.tolist(), limits.ball_contact_pressure_pa)
    out.append(_max_criterion("ball-race contact pressure (ISO 76)", b.name, float(peak),
                              limits.ball_contact_pressure_pa, "Pa",
                              {"t_s": float(t[i]), "race": "inner" if p_in[i] >= p_out[i] else "outer",
                               "bearing_radial_load_n": float(f_r[i]), "bearing_axial_load_n": float(f_a[i]),
                               "time_above_s": above, "crossings": count}))
    # sleeve-bore line contact
    fn = np.maximum(np.asarray(s[pre + "normal_force_n"]), 0.0)
    width = L.extra.get("thermal_width_m") or 0.022
    r_star = conformal_radius(L.sleeve_radius, L.race_radius)
    p_sl = np.sqrt(fn * STEEL_E_STAR / (math.pi * width * r_star))
    j = int(np.argmax(p_sl))
    above, count, peak = static_exceedance(t.tolist(), p_sl.tolist(), limits.sleeve_contact_pressure_pa)
    out.append(_max_criterion("sleeve-bore contact pressure (line contact)", b.name, float(peak),
                              limits.sleeve_contact_pressure_pa, "Pa",
                              {"t_s": float(t[j]), "normal_force_n": float(fn[j]), "time_above_s": above,
                               "crossings": count},
                              "indicative above ~10 kN (conformal contact)" if fn[j] > 1e4 else ""))
    # temperatures
    if thermal_active(spec, L):
        temps = np.column_stack([s[pre + n] for n in NODE_SERIES])
        k = np.unravel_index(int(np.argmax(temps)), temps.shape)
        heat = {r: float(s[pre + n][-1] - s[pre + n][0]) for r, n in zip(ROUTES, ROUTE_SERIES)}
        top = max(heat, key=heat.get)
        out.append(_max_criterion("temperature", b.name, float(temps[k] - KELVIN_0C), limits.temperature_degc, "degC",
                                  {"node": NODE_NAMES[k[1]], "t_s": float(t[k[0]]), "heat_by_route_j": heat,
                                   "largest_heat_route": top}))
    fbs = ((summary.get("thermal") or {}).get(b.name) or {}).get("feedback")
    if fbs is not None:
        out.append({"criterion": "thermal runaway", "bearing": b.name, "value": fbs["t_runaway_s"],
                    "limit": None, "unit": "s", "margin": None, "pass": not fbs["runaway"],
                    "dominant": {"reason": fbs["runaway_reason"], "min_internal_clearance_m":
                                 fbs["min_internal_clearance_m"], "max_thermal_preload_n": fbs["max_thermal_preload_n"],
                                 "t_internal_clearance_consumed_s": fbs["t_internal_clearance_consumed_s"]}})
    # damage per drop
    law = stress_life_from_rating(_pressure_at_rating(limits.dynamic_load_rating_n, L), limits.stress_life_exponent)
    rpm = np.abs(np.asarray(s[pre + "race_speed_rpm"]))
    revs = 0.5 * (rpm[1:] + rpm[:-1]) / 60.0 * np.diff(t)
    p_iv = np.maximum(p_in[1:], p_in[:-1])
    d_roll = overrolling_damage(p_iv.tolist(), revs.tolist(), law)
    d_rain = rainflow_damage(p_in.tolist(), law, "peak")
    damage = d_roll + d_rain
    allow = allowable_drops(damage)
    allow = allow if math.isfinite(allow) else None  # no damage: unlimited (JSON has no infinity)
    out.append({"criterion": "allowable drops (fatigue)", "bearing": b.name, "value": allow,
                "limit": limits.drops_required, "unit": "drops",
                "margin": allow / limits.drops_required - 1.0 if allow is not None else None,
                "pass": allow is None or allow >= limits.drops_required,
                "dominant": {"damage_per_drop": damage, "overrolling_damage": d_roll, "rainflow_damage": d_rain,
                             "inner_race_revolutions": float(np.sum(revs)), "p_ref_pa": law.p_ref}})
    return out, {"damage_per_drop": damage, "allowable_drops": allow}


def whirl_severity(t, summary: dict, clearance: dict | None = None) -> dict:
    """Whirl severity of a run from its summary: ``time_whirling_s`` (coast-down: the chunks
    classified as whirling; landing: persistence x (end - onset)) and, for a landing, the orbit
    amplitude over the radial clearance of the whirling bearing (``amplitude_over_clearance``) and
    the whirl's shape (``shape``: cylindrical or conical, ``whirl.whirl_shape``) where the summary has
    it; {} when the summary has no whirl record."""
    out = {}
    if "whirl_phases" in summary:  # coast-down: per-chunk phases
        out["time_whirling_s"] = float(sum(ph["t_end_s"] - ph["t_start_s"] for ph in summary["whirl_phases"]
                                           if ph["direction"] != "none"))
    elif "whirl" in summary:
        w = summary.get("whirl") or {}
        out["time_whirling_s"] = 0.0
        if w.get("direction", "none") != "none":
            onset = w.get("onset_s") or float(t[0])
            end = w.get("end_s") if w.get("end_s") is not None else float(t[-1])
            out["time_whirling_s"] = float(w.get("persistence") or 0.0) * (end - onset)
            c = (clearance or {}).get(w.get("bearing"))
            if w.get("amplitude_m") is not None and c:
                out["amplitude_over_clearance"] = float(w["amplitude_m"]) / c
            if (w.get("shape") or {}).get("form"):  # cylindrical or conical: which way the rotor goes round
                out["shape"] = w["shape"]["form"]
    return out


def whirl_bearing(summary: dict) -> str | None:
    """The bearing a run's whirl is named by. Landing: the summary's whirl bearing. Coast-down:
    the bearing with the longest whirl time over its phases (each chunk's whirl bearing, stored
    per chunk; the first to whirl on a tie); None when no chunk whirls or the file predates the
    per-chunk bearing (its phases carry no time per bearing)."""
    if "whirl_phases" not in summary:
        return (summary.get("whirl") or {}).get("bearing")
    times: dict = {}
    for ph in summary["whirl_phases"]:
        for name, sec in (ph.get("bearing_time_s") or {}).items():
            times[name] = times.get(name, 0.0) + float(sec)
    return longest_whirl(times)


def whirl_criterion(t, s, summary: dict, limits: Limits, clearance: dict | None = None,
                    severity: dict | None = None) -> dict:
    """The landed journal's whirl against whirl_acceptable_below_rpm (landing or coast-down), with
    its severity (:func:`whirl_severity`, or the caller's when it has it) where it whirls."""
    rpm = np.abs(np.asarray(s["rotor_speed_rpm"]))
    phases = []
    if "whirl_phases" in summary:  # coast-down: per-chunk phases
        for ph in summary["whirl_phases"]:
            if ph["direction"] != "none":
                phases.append((ph["direction"], ph["t_start_s"], ph.get("frequency_hz_median")))
    else:
        w = summary.get("whirl") or {}
        if w.get("direction", "none") != "none":
            phases.append((w["direction"], w.get("onset_s") or float(t[0]), w.get("frequency_hz")))
    if severity is None:
        severity = whirl_severity(t, summary, clearance)
    worst = None
    for direction, t0, f in phases:
        speed = float(np.interp(t0, t, rpm))
        if worst is None or speed > worst[1]:
            worst = (direction, speed, t0, f)
    lim = limits.whirl_acceptable_below_rpm
    if worst is None:
        return {"criterion": "whirl", "bearing": whirl_bearing(summary), "value": "none",
                "limit": lim, "unit": "rpm", "margin": None, "pass": True, "dominant": {}}
    return {"criterion": "whirl", "bearing": whirl_bearing(summary),
            "value": f"{worst[0]} from {worst[1]:.0f} rpm", "limit": lim, "unit": "rpm", "margin": None,
            "pass": bool(worst[1] < lim),
            "dominant": {"direction": worst[0], "rotor_speed_at_onset_rpm": worst[1], "t_onset_s": worst[2],
                         "frequency_hz": worst[3], **severity}}


def close_clearance_criteria(summary: dict, limits: Limits) -> tuple[list, list]:
    """One criterion per station of ``limits.close_clearances_m``: the rotor's largest displacement
    off the bearings' axis there over the run (``summary['rotor_deflection']['station_peak_m']``, rebuilt
    from the reduced states, gravity sag and the catcher support's deflection included) against the
    radial gap of the stationary part at that station (a landing's from every output sample, a
    coast-down's from its stored ones). (criteria, not-evaluated notes): a summary without the
    deflection (a run older than session 35, a coast-down older than session 36) judges nothing and
    says so."""
    if not limits.close_clearances_m:
        return [], []
    peaks = (summary.get("rotor_deflection") or {}).get("station_peak_m")
    if not peaks:
        return [], ["close clearances: the run's summary has no rotor deflection along the span (a run from "
                    "before it was recorded: re-run it)"]
    lacking = [st for st in limits.close_clearances_m if st not in peaks]  # a --set gap at a station the run lacks
    return [_max_criterion("close clearance", station, float(peaks[station]), gap, "m",
                           {"displacement_off_axis_m": float(peaks[station]), "radial_gap_m": gap})
            for station, gap in limits.close_clearances_m.items() if station in peaks], \
        [f"close clearance at {st}: the run's rotor deflection has no such station" for st in lacking]


def _severity_criterion(name, bearing, value, limit, unit, dominant=None):
    """A whirl-severity or force figure: judged against ``limit`` when it is > 0, else reported
    (``judged`` false: it passes, and the reports say 'reported' instead of 'pass')."""
    if limit > 0:
        return dict(_max_criterion(name, bearing, value, limit, unit, dominant or {}), judged=True)
    return {"criterion": name, "bearing": bearing, "value": value, "limit": None, "unit": unit, "margin": None,
            "pass": True, "judged": False, "dominant": dominant or {}}


def evaluate(spec, t, s: dict, summary: dict, limits: Limits) -> dict:
    """The verdict record (module docstring)."""
    from .mechanisms import thermal_feedback_active

    criteria, damage, not_evaluated = [], {}, []
    for b in spec.bearings:
        c, d = bearing_criteria(spec, b, t, s, limits, summary)
        criteria += c
        damage[b.name] = d
        recorded = ((summary.get("thermal") or {}).get(b.name) or {}).get("feedback")
        if thermal_feedback_active(spec, b.laws) and not recorded:
            not_evaluated.append(f"thermal runaway ({b.name}): the run's summary has no thermal record "
                                 "(unfinished run)")
    clearance = {b.name: b.params.clearance for b in spec.bearings}
    if "whirl_phases" in summary or "whirl" in summary:
        sev = whirl_severity(t, summary, clearance)
        wc = whirl_criterion(t, s, summary, limits, clearance, sev)
        criteria.append(wc)
        criteria.append(_severity_criterion("whirl severity: time whirling", wc["bearing"], sev["time_whirling_s"],
                                            limits.whirl_time_s, "s"))
        if "amplitude_over_clearance" in sev:
            criteria.append(_severity_criterion("whirl severity: orbit amplitude / clearance", wc["bearing"],
                                                sev["amplitude_over_clearance"], limits.whirl_orbit_over_clearance,
                                                "-"))
    else:
        not_evaluated.append("whirl: the run's summary has no whirl record (an unfinished coast-down classifies its "
                             "whirl phases at the end)")
    for name, bs in (summary.get("bearings") or {}).items():
        criteria.append(_severity_criterion("peak contact force", name, bs["max_contact_force_n"],
                                            limits.contact_force_n, "N"))
    c, missing = close_clearance_criteria(summary, limits)
    criteria += c
    not_evaluated += missing
    allow = min((d["allowable_drops"] for d in damage.values() if d["allowable_drops"] is not None), default=None)
    failed = [c for c in criteria if not c["pass"]]
    return {"scenario": spec.scenario.name, "kind": summary.get("kind", "landing"),
            "complete": bool(summary.get("complete", True)), "t_reached_s": float(t[-1]),
            "verdict": "pass" if not failed else "fail",
            "failed": [f"{c['criterion']} ({c['bearing']})" for c in failed], "not_evaluated": not_evaluated,
            "allowable_drops": allow, "drops_required": limits.drops_required,
            "limits": {k: {"value": v, "source": SOURCES[k]} for k, v in limits.to_dict().items()},
            "criteria": criteria, "damage": damage,
            "units": "SI (Pa, N, s, J); temperatures in degC as named; speeds in rpm"}


def _dominant_value(x) -> str:
    """A 'dominated by' entry as a reader takes it in: 4 significant digits, tables as name value pairs."""
    if isinstance(x, dict):
        return "{" + ", ".join(f"{k} {_dominant_value(v)}" for k, v in x.items()) + "}"
    return f"{x:.4g}" if isinstance(x, float) else str(x)


def _fmt(v, unit):
    if v is None:
        return "unlimited" if unit == "drops" else "-"
    if isinstance(v, str):
        return v
    if unit == "Pa":
        return f"{v / 1e6:.0f} MPa"
    if unit == "degC":
        return f"{v:.1f} degC"
    if unit == "drops":
        return f"{v:.3g}"
    if unit == "s":
        return f"{v:.3f} s"
    if unit == "m":
        return f"{v * 1e3:.3f} mm"
    return f"{v:.4g}" if unit == "-" else f"{v:.4g} {unit}"


def _limit_text(value) -> str:
    """A limit as the reports show it: a table of gaps as ``station mm`` pairs ('none' when empty)."""
    if isinstance(value, dict):
        return ", ".join(f"{k} {x * 1e3:.3g} mm" for k, x in value.items()) or "none"
    return str(value)


def _margin(c) -> str:
    if c["margin"] is None:
        return "-"
    if c["unit"] == "drops":
        return f"x{c['margin'] + 1.0:.3g} of the required"
    return f"{100 * c['margin']:+.0f} %"


FATIGUE_ONLY = ("This number counts rolling-contact fatigue (ISO 281 stress-life, Palmgren-Miner) and nothing "
                "else: wear of the sleeve and races, cage damage and heat are not in it (the temperature and runaway "
                "rows judge the heat; wear and the cage are not modelled).")


def _result(c) -> str:
    if not c.get("judged", True):
        return "reported"
    return "pass" if c["pass"] else "FAIL"


def markdown(v: dict) -> str:
    lines = [f"# Verdict: {v['scenario']} ({v['kind']})", "",
             f"**{v['verdict'].upper()}**" + (f": fails {', '.join(v['failed'])}" if v["failed"] else
                                             ": every criterion within its limit"),
             "", f"Allowable drops, rolling-contact fatigue only (the weakest bearing): "
             f"{_fmt(v['allowable_drops'], 'drops')} (required {v['drops_required']}). {FATIGUE_ONLY}",
             "" if v["complete"] else f"\nThe run is INCOMPLETE (reached {v['t_reached_s']:.3f} s): the verdict covers "
             "only the part simulated.", *[f"\nNot evaluated: {x}" for x in v["not_evaluated"]], "",
             "| criterion | bearing (station) | value | limit | margin | result | dominated by |", "|---|---|---|---|---|---|---|"]
    for c in v["criteria"]:
        dom = ", ".join(f"{k} {_dominant_value(x)}" for k, x in c["dominant"].items() if x is not None)
        margin = _margin(c)
        lines.append(f"| {c['criterion']} | {c['bearing'] or '-'} | {_fmt(c['value'], c['unit'])} | "
                     f"{_fmt(c['limit'], c['unit']) if c['limit'] is not None else '-'} | {margin} | "
                     f"{_result(c)} | {dom} |")
    lines += ["", "Limits and their sources:", ""]
    lines += [f"- `{k}` = {_limit_text(x['value'])}: {x['source']}" for k, x in v["limits"].items()]
    lines += ["", "Laws, sources and assumptions: docs/designer_models.md; the verdict's rules: rotorlanding/verdict.py."]
    return "\n".join(lines) + "\n"


def plot_temperatures(spec, t, s, png: Path) -> Path:
    """Node temperatures [degC] and the heat per route [J] of each bearing over time."""
    from .plots import _plt
    from .thermal_states import NODE_SERIES, ROUTES, ROUTE_SERIES
    from user_forces.thermal import NODE_NAMES

    plt = _plt()
    fig, axes = plt.subplots(2, len(spec.bearings), figsize=(5 * len(spec.bearings), 7), squeeze=False, sharex=True)
    for k, b in enumerate(spec.bearings):
        for n, name in zip(NODE_SERIES, NODE_NAMES):
            axes[0, k].plot(t, np.asarray(s[b.name + "_" + n]) - KELVIN_0C, label=name.replace("_", " "))
        axes[0, k].set_title(b.name)
        axes[0, k].set_ylabel("temperature [degC]")
        for r, n in zip(ROUTES, ROUTE_SERIES):
            axes[1, k].plot(t, s[b.name + "_" + n], label=r.replace("_", " "))
        axes[1, k].set_ylabel("heat into the bearing [J]")
        axes[1, k].set_xlabel("time [s]")
        for ax in axes[:, k]:
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
    fig.tight_layout()
    try:
        save_figure(fig, png, dpi=100)
    finally:
        plt.close(fig)
    return png


def verdict_from_results(results_h5, out_dir=None, *, overrides=None, plots=True) -> dict:
    """Verdict of a finished run from its results.h5 (the stored scenario, its [limits], ``overrides``
    such as limits.temperature_degc=100); writes verdict.json and verdict.md (and temperatures.png)
    into ``out_dir`` (default: the results' folder)."""
    from .landing import build_spec
    from .mechanisms import thermal_active
    from .readers import read_results_guarded
    from .scenario import apply_overrides, scenario_from_dict

    path = Path(results_h5)
    # every part through the guarded reader: a file without time_s or series was a KeyError traceback
    stored = read_results_guarded(path, ("scenario", "time_s", "series", "summary"), field="results")
    data = stored["scenario"]
    data.pop("coastdown", None)
    data = apply_overrides(data, overrides)
    scenario = scenario_from_dict(data, source=str(path))  # first: a bad limit's line then names the file
    limits = limits_from_dict(data.get("limits"))
    spec = build_spec(scenario)
    t, s, summary = np.asarray(stored["time_s"]), stored["series"], stored["summary"]
    v = evaluate(spec, t, s, summary, limits)
    out = Path(out_dir) if out_dir is not None else path.parent
    atomic_write_text(out / "verdict.json", json.dumps(v, indent=2, default=_json_default))
    atomic_write_text(out / "verdict.md", markdown(v))
    if plots and any(thermal_active(spec, b.laws) for b in spec.bearings):
        v["figures"] = [plot_temperatures(spec, t, s, out / "temperatures.png").name]
    return v


def _json_default(x):
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    raise TypeError(f"not JSON serialisable: {type(x).__name__}")


def format_lines(v: dict) -> list[str]:
    lines = [f"verdict: {v['verdict'].upper()}" + (f" ({', '.join(v['failed'])})" if v["failed"] else "")
             + ("" if v["complete"] else f" [INCOMPLETE run: up to {v['t_reached_s']:.3f} s]"),
             *[f"not evaluated: {x}" for x in v["not_evaluated"]],
             f"allowable drops (rolling-contact fatigue only; not wear, cage or heat): "
             f"{_fmt(v['allowable_drops'], 'drops')} (required {v['drops_required']})"]
    for c in v["criteria"]:
        margin = "" if c["margin"] is None else f", margin {_margin(c)}"
        lim = "" if c["limit"] is None else f" / limit {_fmt(c['limit'], c['unit'])}"
        lines.append(f"  {_result(c)}  {c['criterion']} [{c['bearing'] or '-'}]: "
                     f"{_fmt(c['value'], c['unit'])}{lim}{margin}")
    return lines

"""Model-gap diagnosis: which missing effect explains where simulation and measurement disagree.

``diagnose(measured, scenario_path, ...)``:
  a. simulate the model as it is, extract the same features as from the measurement, gap_before;
  b. for each candidate effect the model lacks (switched off in its scenario): switch it on and
     calibrate its parameter within bounds (bounded scalar search on the gap);
  c. rank by a BIC-like score n ln(gap^2) + k ln(n) (n features, k parameters) and name the best
     only if the disagreement is above the noise level (gap_before > NOISE_GAP), the best
     candidate shrinks it by at least ``min_improvement`` (30 %) and its score beats the unchanged model
     by more than 2; otherwise report that no candidate explains the disagreement
     (named_effect = null);
  d. ``--max-effects 2`` repeats from the improved model.
"""

from __future__ import annotations

import math
from concurrent.futures import ProcessPoolExecutor

import numpy as np
from scipy.optimize import minimize_scalar

from .effects import CATALOGUE
from .features import extract_features, gap
from .measured import Measurement

#: gaps below this are treated as noise: on clean data (the model against its own resampled,
#: noisy output) the gap is 0.03-0.1, so a disagreement must exceed 3x that to be explained
NOISE_GAP = 0.3
#: a named effect must remove at least this share of the remaining gap; with two missing effects
#: the first one found can only remove its own part (e.g. 48 % for windage + ribbon cross-coupling)
MIN_STEP_IMPROVEMENT = 0.3


def _simulate_features(scenario_path, overrides, clearance, *, with_series=False):
    from .postprocess import evaluate
    from .run import simulate
    from .scenario import load_scenario

    sc = load_scenario(scenario_path, overrides)
    spec, t, q, v, info = simulate(sc, progress=False)
    series = evaluate(spec, t, q, v)
    chans = {}
    for b in spec.bearings:
        for ax in ("y", "z"):
            chans[f"{b.name}_{ax}_m"] = (t, series[f"{b.name}_{ax}_m"])
            chans[f"{b.name}_force_{ax}_n"] = (t, series[f"{b.name}_contact_force_{ax}_n"]
                                              + series[f"{b.name}_rub_force_{ax}_n"])
        chans[f"{b.name}_inner_race_speed_rpm"] = (t, series[f"{b.name}_race_speed_rpm"])
    chans["rotor_speed_rpm"] = (t, series["rotor_speed_rpm"])
    chans["axial_m"] = (t, series["axial_position_m"])
    feats = extract_features(Measurement(chans), clearance=clearance, t_drop=sc.amb.t_drop)
    return (feats, Measurement(chans)) if with_series else feats


def write_report(res: dict, out_dir, measured: Measurement | None, scenario_path, clearance: float) -> list[str]:
    """report.md and overlay.png: measured vs model before vs after, spectrum, feature table."""
    from pathlib import Path

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .whirl import full_spectrum

    out = Path(out_dir)
    _, before = _simulate_features(scenario_path, [], clearance, with_series=True)
    _, after = _simulate_features(scenario_path, res["calibrated_overrides"], clearance, with_series=True)
    fig, axes = plt.subplots(3, 1, figsize=(9, 10))
    sets = [("model before", before, "tab:blue"), ("model after", after, "tab:green")]
    if measured is not None and measured.channels:
        sets.insert(0, ("measured", measured, "0.55"))
    for label, m, c in sets:
        if m.has("DE_z_m"):
            t, z = m.series("DE_z_m")
            axes[0].plot(t, z * 1e3, color=c, lw=2.5 if label == "measured" else 0.8, label=label)
        if m.has("rotor_speed_rpm"):
            t, sp = m.series("rotor_speed_rpm")
            axes[1].plot(t, sp, color=c, lw=2.5 if label == "measured" else 0.8, label=label)
        if m.has("DE_y_m") and m.has("DE_z_m"):
            t, y = m.series("DE_y_m")
            z = np.interp(t, *m.series("DE_z_m"))
            dt = float(np.median(np.diff(t)))
            tu = np.arange(t[0], t[-1], dt)
            f, a = full_spectrum(tu, np.interp(tu, t, y), np.interp(tu, t, z))
            axes[2].plot(f, a * 1e6, color=c, lw=2.5 if label == "measured" else 0.8, label=label)
    axes[0].set_ylabel("DE vertical [mm]")
    axes[1].set_ylabel("rotor speed [rpm]")
    axes[2].set_ylabel("full spectrum DE [um]")
    axes[2].set_xlabel("frequency [Hz] (negative: backward)")
    axes[2].set_xlim(-300, 300)
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_xlabel("time after the drop [s]")
    fig.tight_layout()
    fig.savefig(out / "overlay.png", dpi=110)
    plt.close(fig)
    lines = ["# Model-gap diagnosis", "",
             f"Model: `{scenario_path}`. Gap before: **{res['gap_before']:.3f}**, after: **{res['gap_after']:.3f}**.",
             ""]
    if res["named_effect"]:
        for n in res["named_effects"]:
            lines.append(f"Named effect: **{n}**. Signature: {res['signatures'][n]}.")
        lines.append(f"Calibrated: `{' '.join(res['calibrated_overrides'])}`.")
    else:
        lines.append("No candidate effect explains the disagreement significantly (null answer).")
    lines += ["", "## Candidates", "", "| step | effect | gap | parameters | score |", "|---|---|---|---|---|"]
    for i, stp in enumerate(res["steps"], 1):
        for c in stp["candidates"]:
            lines.append(f"| {i} | {c['effect']} | {c['gap']:.3g} | {c['parameters']} | {c['score']:.3g} |")
    lines += ["", "## Features (distance = |measured - model| / scale)", "",
              "| feature | measured | before | after | scale | distance before | distance after |", "|---|---|---|---|---|---|---|"]
    after_rows = {r["feature"]: r for r in res["features_after"]}
    for r in res["features_before"]:
        a = after_rows.get(r["feature"], {})
        lines.append(f"| {r['feature']} | {r['measured']} | {r['simulated']} | {a.get('simulated', '-')} | "
                     f"{r['scale']} | {r['distance']:.3g} | {a.get('distance', float('nan')):.3g} |")
    lines += ["", "![overlay](overlay.png)", ""]
    (out / "report.md").write_text("\n".join(lines))
    return ["report.md", "overlay.png"]


def _param_overrides(param, x):
    return [f"{k}={x!r}" for k in param.keys]


def _calibrate(args):
    """Switch one effect on and fit its (first) parameter; an effect the scenario cannot take
    (e.g. unbalance without an [unbalance] table) comes back with gap = inf and the reason."""
    from .errors import InputError

    try:
        return _calibrate_one(*args)
    except InputError as err:
        return {"effect": args[0], "gap": float("inf"), "parameters": {}, "rows": [], "k": 0,
                "not_applicable": str(err)}


def _calibrate_one(name, scenario_path, base_overrides, meas, clearance, maxiter):
    eff = CATALOGUE[name]
    on = base_overrides + [f"effects.{name}=true"]
    if not eff.parameters:
        f = _simulate_features(scenario_path, on, clearance)
        g, rows = gap(meas, f)
        return {"effect": name, "gap": g, "parameters": {}, "rows": rows, "k": 0}
    p = eff.parameters[0]
    to_x = (lambda u: 10 ** u) if p.log else (lambda u: u)
    lo, hi = (math.log10(p.lower), math.log10(p.upper)) if p.log else (p.lower, p.upper)
    cache = {}

    def objective(u):
        x = float(to_x(u))
        f = _simulate_features(scenario_path, on + _param_overrides(p, x), clearance)
        g, rows = gap(meas, f)
        cache[u] = (g, rows, x)
        return g if math.isfinite(g) else 1e9

    minimize_scalar(objective, bounds=(lo, hi), method="bounded", options={"maxiter": maxiter, "xatol": 1e-3})
    u_best = min(cache, key=lambda u: cache[u][0])
    g, rows, x = cache[u_best]
    return {"effect": name, "gap": g, "parameters": {p.name: x}, "rows": rows, "k": 1}


def diagnose(measured: Measurement | dict, scenario_path, *, clearance: float, candidates=None, max_effects: int = 1,
             min_improvement: float = MIN_STEP_IMPROVEMENT, noise_gap: float = NOISE_GAP, workers: int = 2, maxiter: int = 10,
             t_drop: float = 0.0) -> dict:
    from .scenario import load_scenario

    meas = measured if isinstance(measured, dict) else extract_features(measured, clearance=clearance,
                                                                          t_drop=t_drop)
    base = load_scenario(scenario_path)
    overrides: list[str] = []
    named, steps = [], []
    f0 = _simulate_features(scenario_path, overrides, clearance)
    gap_before, rows_before = gap(meas, f0)
    current_gap, current_rows = gap_before, rows_before
    for _ in range(max_effects):
        lacking = [n for n, on in base.effects.items() if not on and n in CATALOGUE and n not in named]
        if candidates:
            lacking = [n for n in lacking if n in candidates]
        if not lacking:
            break
        jobs = [(n, scenario_path, overrides, meas, clearance, maxiter) for n in lacking]
        if workers > 1 and len(jobs) > 1:
            with ProcessPoolExecutor(min(workers, len(jobs))) as ex:
                results = list(ex.map(_calibrate, jobs))
        else:
            results = [_calibrate(j) for j in jobs]
        n = max(1, len(current_rows))
        for r in results:
            r["score"] = (n * math.log(r["gap"] ** 2 + 1e-12) + r["k"] * math.log(n)) if math.isfinite(r["gap"]) \
                else float("inf")
        results.sort(key=lambda r: r["score"])
        best = results[0]
        base_score = n * math.log(current_gap ** 2 + 1e-12)
        significant = (current_gap > noise_gap and best["gap"] <= (1 - min_improvement) * current_gap
                       and best["score"] < base_score - 2.0)
        steps.append({"gap_before": current_gap, "candidates": [{k: r[k] for k in ("effect", "gap", "parameters",
                                                                                   "score", "not_applicable")
                                                                 if k in r} for r in results],
                      "named_effect": best["effect"] if significant else None})
        if not significant:
            break
        named.append(best["effect"])
        overrides += [f"effects.{best['effect']}=true"]
        for pname, x in best["parameters"].items():
            p = next(pp for pp in CATALOGUE[best["effect"]].parameters if pp.name == pname)
            overrides += _param_overrides(p, x)
        current_gap, current_rows = best["gap"], best["rows"]
    return {"named_effect": named[0] if named else None, "named_effects": named, "gap_before": gap_before,
            "gap_after": current_gap, "features_before": rows_before, "features_after": current_rows,
            "calibrated_overrides": overrides, "steps": steps,
            "signatures": {n: CATALOGUE[n].signature for n in named}}


__all__ = ["diagnose", "np"]

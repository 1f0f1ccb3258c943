"""Model-gap diagnosis: which missing effect explains where simulation and measurement disagree.

``diagnose(measured, scenario_path, ...)``:
  a. simulate the model as it is, extract the same features as from the measurement, gap_before;
  b. for each candidate effect the model lacks (switched off in its scenario): switch it on and
     calibrate its parameter within bounds (bounded scalar search on the gap);
  c. rank by a BIC-like score n ln(gap^2) + k ln(n) (n features, k parameters) and name the best
     only if the disagreement is above the noise level (gap_before > NOISE_GAP), the best
     candidate shrinks it by at least ``min_improvement`` and its score beats the unchanged model
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


def _simulate_features(scenario_path, overrides, clearance):
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
    return extract_features(Measurement(chans), clearance=clearance, t_drop=sc.amb.t_drop)


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
             min_improvement: float = 0.5, noise_gap: float = NOISE_GAP, workers: int = 2, maxiter: int = 10,
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

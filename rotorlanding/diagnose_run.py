"""Model-gap diagnosis: which missing effect explains where simulation and measurement disagree.

The machinery behind ``rotorlanding diagnose`` and the Python API's ``rotorlanding.diagnose(...)``
(:mod:`rotorlanding.api_studies`, which returns a ``Diagnosis``); the module is named ``diagnose_run`` so
that the package attribute ``rotorlanding.diagnose`` is the function.

``diagnose(measured, scenario_path, ...)``:
  a. simulate the model as it is at every operating point (one point for a record; one per
     ``[points.NAME]`` table of a feature table, each with its scenario overrides), extract the
     same features as from the measurement, gap_before = one weighted RMS over the rows of every
     point (:func:`rotorlanding.features.gap_points`);
  b. for each candidate effect the model lacks (switched off in its scenario): switch it on and
     calibrate its parameter within bounds (bounded scalar search on the gap over all points
     jointly); candidates run in threads that share one process pool for the simulations, so
     candidates x points simulations keep every worker busy;
  c. rank by a BIC-like score n ln(gap^2) + k ln(n) (n feature rows, k parameters) and name the best
     only if the disagreement is above the noise level (gap_before > NOISE_GAP), its score beats
     the unchanged model by more than 2, and either it shrinks the gap by at least
     ``min_improvement`` (30 %) or it makes the whirl direction right at some operating point
     without making it wrong at another (a change of the whirl regime is not a noise effect);
     otherwise report that no candidate explains the disagreement (named_effect = null);
  d. ``--max-effects 2`` repeats from the improved model.
"""

from __future__ import annotations

import json
import math
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import minimize_scalar

from .effects import CATALOGUE
from .errors import InputError
from .features import extract_features, gap_points
from .measured import Measurement
from .mechanisms import rotor_force
from .runner import Pool, reduction_cache
from .safeio import atomic_write_text

#: gaps below this are treated as noise: on clean data (the model against its own resampled,
#: noisy output) the gap is 0.03-0.1, so a disagreement must exceed 3x that to be explained
NOISE_GAP = 0.3
#: a named effect must remove at least this share of the remaining gap; with two missing effects
#: the first one found can only remove its own part (e.g. 48 % for windage + ribbon cross-coupling)
MIN_STEP_IMPROVEMENT = 0.3
#: calibration of a parameter: a grid over its bounds (one parallel batch), then a bounded search
#: between the neighbours of the best grid value
GRID_POINTS = 5


@dataclass
class Point:
    """An operating point: its name, the scenario overrides that define it and the measured
    features there (name -> (value, scale))."""

    name: str
    overrides: list[str] = field(default_factory=list)
    features: dict = field(default_factory=dict)


def _simulate_features(scenario_path, overrides, clearance, *, with_series=False):
    from .postprocess import evaluate
    from .run import simulate
    from .scenario import load_scenario

    sc = load_scenario(scenario_path, overrides)
    spec, t, q, v, info = simulate(sc, progress=False, reduction=reduction_cache())
    series = evaluate(spec, t, q, v)
    chans = {}
    for b in spec.bearings:
        force = rotor_force(series, b.name)
        for ax, f in zip(("y", "z"), force):
            chans[f"{b.name}_{ax}_m"] = (t, series[f"{b.name}_{ax}_m"])
            chans[f"{b.name}_force_{ax}_n"] = (t, f)
        chans[f"{b.name}_inner_race_speed_rpm"] = (t, series[f"{b.name}_race_speed_rpm"])
    chans["rotor_speed_rpm"] = (t, series["rotor_speed_rpm"])
    chans["axial_m"] = (t, series["axial_position_m"])
    feats = extract_features(Measurement(chans), clearance=clearance, t_drop=sc.amb.t_drop)
    return (feats, Measurement(chans)) if with_series else feats


def _sim_job(args):
    """One simulation in a worker: features, or the failure (a solver that does not converge at a
    trial parameter value is a bad trial, not a crash of the diagnosis)."""
    scenario_path, overrides, clearance = args
    try:
        return _simulate_features(scenario_path, overrides, clearance)
    except Exception as exc:  # noqa: BLE001 - reported as a failed trial
        return {"__error__": f"{type(exc).__name__}: {exc}"}


class _Simulator:
    """Runs the simulations of every operating point of one model variant in a shared process
    pool. Overrides per simulation: the model's ``--set`` values, then the point's own values
    (its speed ...), then the candidate effect and its parameter."""

    def __init__(self, scenario_path, points: list[Point], clearance: float, workers: int, base: list[str]):
        self.scenario_path, self.points, self.clearance, self.base = scenario_path, points, clearance, list(base)
        self.pool = Pool(workers, blas_threads=None)  # BLAS as before (runner.worker_setup says why)
        self.count = 0

    def overrides(self, p: Point, extra: list[str]) -> list[str]:
        return self.base + list(p.overrides) + list(extra)

    def features(self, extras: list[list[str]]) -> list[list[dict]]:
        """Simulated features at every point for each model variant (all submitted at once)."""
        jobs = [(self.scenario_path, self.overrides(p, extra), self.clearance) for extra in extras for p in self.points]
        self.count += len(jobs)
        out = self.pool.map(_sim_job, jobs, failures="raise")  # _sim_job turns a failed trial into its row
        n = len(self.points)
        return [out[i * n:(i + 1) * n] for i in range(len(extras))]

    def gaps(self, extras: list[list[str]]):
        res = []
        for sims in self.features(extras):
            failed = [s["__error__"] for s in sims if "__error__" in s]
            if failed:
                res.append((float("inf"), [], sims, failed[0]))
                continue
            g, rows = gap_points([p.features for p in self.points], sims, [p.name for p in self.points])
            res.append((g, rows, sims, None))
        return res

    def gap(self, extra: list[str]):
        return self.gaps([extra])[0]

    def close(self):
        self.pool.close()


def measured_for_diagnosis(scenario_path, measured_path, sets: list[str], time_offset_s: float | None = None):
    """What ``rotorlanding diagnose`` compares the model with: (clearance of the scenario's DE
    bearing (else its first), the measurement, its features: one ``Point`` per operating point of a
    points file, a feature table, or features extracted from a record after its detected drop).
    Every bad input is one InputError naming the file."""
    from .features import features_from_table
    from .measured import detect_drop, load_measurement
    from .scenario import load_scenario

    sc = load_scenario(scenario_path, sets)
    clearance = sc.bearings["DE"].clearance if "DE" in sc.bearings else next(iter(sc.bearings.values())).clearance
    m = load_measurement(measured_path, time_offset_s=time_offset_s or 0.0)
    if m.points:
        meas = []
        for p in m.points:
            try:
                load_scenario(scenario_path, sets + p.overrides)
            except InputError as err:
                raise InputError(f"points.{p.name}.set", " ".join(p.overrides),
                                 f"not valid for {scenario_path}: {err.field} = {err.value!r}: {err.allowed}",
                                 file=measured_path) from None
            meas.append(Point(p.name, p.overrides, features_from_table(p.features, clearance,
                                                                        where=f"points.{p.name}.features",
                                                                        file=measured_path)))
    elif m.features:
        meas = features_from_table(m.features, clearance, file=measured_path)
    else:
        for name, (_, v) in m.channels.items():
            if name.endswith("_m") and name != "axial_m" and np.nanmax(np.abs(v)) > 5 * clearance:
                raise InputError(name, f"{np.nanmax(np.abs(v)):.3g} m", f"journal displacements beyond 5x the model's "
                                 f"clearance ({clearance:g} m): data from a different rotor, or not in metres?",
                                 file=measured_path)
        t_drop = detect_drop(m, clearance) if time_offset_s is None else 0.0
        m = m.shifted(t_drop or 0.0)
        span = max(float(t[-1]) for t, _ in m.channels.values())
        if span < 0.1:
            raise InputError("time_s", f"{span:.3g} s after the drop", "record too short: need >= 0.1 s after the drop",
                             file=measured_path)
        meas = extract_features(m, clearance=clearance, t_drop=0.0)
    return clearance, m, meas


def _param_overrides(param, x):
    return [f"{k}={x!r}" for k in param.keys]


def _calibrate(sim: _Simulator, name: str, current: list[str], maxiter: int) -> dict:
    """Switch one effect on and fit its (first) parameter on the gap over all points. An effect the
    scenario cannot take (e.g. unbalance without an [unbalance] table) comes back with gap = inf
    and the reason."""
    from .scenario import load_scenario

    eff = CATALOGUE[name]
    on = current + [f"effects.{name}=true"]
    # an effect whose only missing input is the parameter the fit is about to supply (the worn
    # drag torque) is applicable: probe again with it; report the first reason if both fail
    probes = [on] + ([on + _param_overrides(eff.parameters[0], eff.parameters[0].lower)] if eff.parameters else [])
    first_error = None
    for probe in probes:
        try:
            for p in sim.points:
                load_scenario(sim.scenario_path, sim.overrides(p, probe))
            break
        except InputError as err:
            first_error = first_error or err
    else:
        return {"effect": name, "gap": float("inf"), "parameters": {}, "rows": [], "k": 0,
                "not_applicable": str(first_error)}
    if not eff.parameters:
        g, rows, sims, err = sim.gap(on)
        return {"effect": name, "gap": g, "parameters": {}, "rows": rows, "k": 0, "directions": _directions(sims),
                **({"failed": err} if err else {})}
    p = eff.parameters[0]
    to_x = (lambda u: 10 ** u) if p.log else (lambda u: u)
    lo, hi = (math.log10(p.lower), math.log10(p.upper)) if p.log else (p.lower, p.upper)
    cache = {}

    def objective(u):
        x = float(to_x(u))
        g, rows, sims, err = sim.gap(on + _param_overrides(p, x))
        cache[u] = (g, rows, x, sims)
        return g if math.isfinite(g) else 1e9

    # a coarse grid first (one parallel batch): the gap over features with bounded distances can
    # be flat or have several minima over the bounds, where a bounded Brent search alone stalls
    grid = np.linspace(lo, hi, GRID_POINTS)
    for u, (g, rows, sims, err) in zip(grid, sim.gaps([on + _param_overrides(p, float(to_x(u))) for u in grid])):
        cache[float(u)] = (g, rows, float(to_x(u)), sims)
    k = int(np.argmin([cache[float(u)][0] for u in grid]))
    a, b = float(grid[max(k - 1, 0)]), float(grid[min(k + 1, GRID_POINTS - 1)])
    minimize_scalar(objective, bounds=(a, b), method="bounded", options={"maxiter": maxiter, "xatol": 1e-3})
    u_best = min(cache, key=lambda u: cache[u][0])
    g, rows, x, sims = cache[u_best]
    return {"effect": name, "gap": g, "parameters": {p.name: x}, "rows": rows, "k": 1, "directions": _directions(sims),
            "evaluations": len(cache)}


def _directions(sims: list[dict]) -> list:
    return [s.get("whirl_direction", (None,))[0] for s in sims]


def diagnose(measured, scenario_path, *, clearance: float, candidates=None, max_effects: int = 1,
             min_improvement: float = MIN_STEP_IMPROVEMENT, noise_gap: float = NOISE_GAP, workers: int = 2,
             maxiter: int = 10, t_drop: float = 0.0, base_overrides: list[str] | None = None) -> dict:
    """``measured``: a Measurement (channels), a feature dict (one point: the scenario as it is) or
    a list of :class:`Point` (one per operating point, each with its scenario overrides).
    ``base_overrides``: ``--set`` changes of the model (e.g. ``effects.axial_rub=false``)."""
    from .scenario import load_scenario

    t_start = time.perf_counter()
    base_overrides = list(base_overrides or [])
    if isinstance(measured, list):
        points = measured
    else:
        meas = measured if isinstance(measured, dict) else extract_features(measured, clearance=clearance,
                                                                              t_drop=t_drop)
        points = [Point("", [], meas)]
    base = load_scenario(scenario_path, base_overrides)
    sim = _Simulator(scenario_path, points, clearance, workers, base_overrides)
    overrides: list[str] = []
    named, steps = [], []
    try:
        gap_before, rows_before, sims0, err = sim.gap(overrides)
        if err:
            raise RuntimeError(f"the model as it is fails to simulate: {err}")
        directions_before = _directions(sims0)
        current_gap, current_rows, current_dirs = gap_before, rows_before, directions_before
        for _ in range(max_effects):
            lacking = [n for n, on in base.effects.items() if not on and n in CATALOGUE and n not in named]
            if candidates:
                lacking = [n for n in lacking if n in candidates]
            else:  # faults (a worn bearing) only on request: a healthy rig's gap is not a fault
                lacking = [n for n in lacking if not CATALOGUE[n].fault]
            if not lacking:
                break
            if sim.pool is not None and len(lacking) > 1:
                with ThreadPoolExecutor(len(lacking)) as ex:
                    results = list(ex.map(lambda n: _calibrate(sim, n, overrides, maxiter), lacking))
            else:
                results = [_calibrate(sim, n, overrides, maxiter) for n in lacking]
            n = max(1, len(current_rows))
            for r in results:
                r["score"] = (n * math.log(r["gap"] ** 2 + 1e-12) + r["k"] * math.log(n)) if math.isfinite(r["gap"]) \
                    else float("inf")
            results.sort(key=lambda r: r["score"])
            best = results[0]
            base_score = n * math.log(current_gap ** 2 + 1e-12)
            relative = best["gap"] <= (1 - min_improvement) * current_gap
            # a whirl direction made right at some point and broken at none is a qualitative gain
            # (the whirl regime), not something sensor noise or a parameter fit of noise produces
            meas_dirs = [p.features.get("whirl_direction", (None,))[0] for p in points]
            new_dirs = best.get("directions", [None] * len(points))
            fixed = [p.name or "record" for p, m, b, a in zip(points, meas_dirs, current_dirs, new_dirs)
                     if m is not None and b != m and a == m]
            broken = [p.name or "record" for p, m, b, a in zip(points, meas_dirs, current_dirs, new_dirs)
                      if m is not None and b == m and a != m]
            significant = (current_gap > noise_gap and best["score"] < base_score - 2.0
                           and (relative or (bool(fixed) and not broken)))
            keys = ("effect", "gap", "parameters", "score", "directions", "evaluations", "not_applicable", "failed", "rows")
            steps.append({"gap_before": current_gap, "base_score": base_score,
                          "candidates": [{k: r[k] for k in keys if k in r} for r in results],
                          "named_effect": best["effect"] if significant else None,
                          "relative_improvement": 1 - best["gap"] / current_gap
                          if math.isfinite(best["gap"]) and current_gap > 0 else 0.0,
                          "whirl_direction_fixed_at": fixed, "whirl_direction_broken_at": broken,
                          "significant_by": ("relative improvement" if relative else "whirl direction")
                          if significant else None})
            if not significant:
                break
            named.append(best["effect"])
            overrides += [f"effects.{best['effect']}=true"]
            for pname, x in best["parameters"].items():
                p = next(pp for pp in CATALOGUE[best["effect"]].parameters if pp.name == pname)
                overrides += _param_overrides(p, x)
            current_gap, current_rows, current_dirs = best["gap"], best["rows"], best["directions"]
    finally:
        sim.close()
    return {"named_effect": named[0] if named else None, "named_effects": named, "gap_before": gap_before,
            "gap_after": current_gap, "features_before": rows_before, "features_after": current_rows,
            "calibrated_overrides": overrides, "steps": steps,
            "signatures": {n: CATALOGUE[n].signature for n in named},
            "model_overrides": base_overrides,
            "points": [{"name": p.name, "overrides": p.overrides,
                        "whirl_measured": p.features.get("whirl_direction", (None,))[0],
                        "whirl_before": d0, "whirl_after": d1}
                       for p, d0, d1 in zip(points, directions_before, current_dirs)],
            "simulations": sim.count, "wall_s": round(time.perf_counter() - t_start, 1), "workers": workers}


_DIR_Y = {"backward": -1, "none": 0, "forward": 1}


def _feature_figure(res: dict, path) -> None:
    """Per-point features: measured vs model before vs after, one panel per feature."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = [p["name"] or "-" for p in res["points"]]
    feats = sorted({r["feature"] for r in res["features_before"]} | {r["feature"] for r in res["features_after"]},
                   key=lambda f: (f != "whirl_direction", f != "whirl_frequency_hz", f))
    fig, axes = plt.subplots(len(feats), 1, figsize=(7, 2.2 * len(feats) + 0.5), squeeze=False)
    for ax, feat in zip(axes[:, 0], feats):
        for label, rows, style in (("measured", res["features_before"], dict(color="k", marker="o", ms=9, ls="")),
                                   ("model before", res["features_before"], dict(color="tab:blue", marker="x", ms=8,
                                                                                  ls="")),
                                   ("model after", res["features_after"], dict(color="tab:green", marker="s", ms=6,
                                                                                ls="", mfc="none"))):
            xs, ys = [], []
            for r in rows:
                if r["feature"] != feat:
                    continue
                v = r["measured"] if label == "measured" else r["simulated"]
                if v is None:
                    continue
                xs.append(names.index(r.get("point") or "-"))
                ys.append(_DIR_Y.get(v, 0) if feat == "whirl_direction" else v)
            ax.plot(xs, ys, label=label, **style)
        if feat == "whirl_direction":
            ax.set_yticks([-1, 0, 1], ["backward", "none", "forward"])
            ax.set_ylim(-1.5, 1.5)
        ax.set_ylabel(feat, fontsize=8)
        ax.set_xticks(range(len(names)), names)
        ax.set_xlim(-0.5, len(names) - 0.5)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    axes[0, 0].set_title(f"gap {res['gap_before']:.3f} -> {res['gap_after']:.3f}; named: {res['named_effect']}",
                         fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def _overlay_figure(res: dict, path, measured: Measurement, scenario_path, clearance: float) -> None:
    """measured vs model before vs after (one record): DE vertical, rotor speed, full spectrum."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .whirl import full_spectrum

    _, before = _simulate_features(scenario_path, res["model_overrides"], clearance, with_series=True)
    _, after = _simulate_features(scenario_path, res["model_overrides"] + res["calibrated_overrides"], clearance,
                                  with_series=True)
    fig, axes = plt.subplots(3, 1, figsize=(9, 10))
    sets = [("measured", measured, "0.55"), ("model before", before, "tab:blue"), ("model after", after, "tab:green")]
    for label, m, c in sets:
        lw = 2.5 if label == "measured" else 0.8
        if m.has("DE_z_m"):
            t, z = m.series("DE_z_m")
            axes[0].plot(t, z * 1e3, color=c, lw=lw, label=label)
        if m.has("rotor_speed_rpm"):
            t, sp = m.series("rotor_speed_rpm")
            axes[1].plot(t, sp, color=c, lw=lw, label=label)
        if m.has("DE_y_m") and m.has("DE_z_m"):
            t, y = m.series("DE_y_m")
            dt = float(np.median(np.diff(t)))
            tu = np.arange(t[0], t[-1], dt)
            f, a = full_spectrum(tu, np.interp(tu, t, y), np.interp(tu, *m.series("DE_z_m")))
            axes[2].plot(f, a * 1e6, color=c, lw=lw, label=label)
    axes[0].set_ylabel("DE vertical [mm]")
    axes[0].set_xlabel("time after the drop [s]")
    axes[1].set_ylabel("rotor speed [rpm]")
    axes[2].set_ylabel("full spectrum DE [um]")
    axes[2].set_xlabel("frequency [Hz] (negative: backward)")
    axes[2].set_xlim(-300, 300)
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _fmt(v) -> str:
    if v is None:
        return "-"
    if isinstance(v, str):
        return v
    return f"{v:.4g}"


def write_report(res: dict, out_dir, measured: Measurement | None, scenario_path, clearance: float) -> list[str]:
    """report.md and a figure: overlay.png (a record: measured vs model before vs after, spectrum)
    or features.png (a feature table: per-point features measured vs before vs after)."""
    from pathlib import Path

    out = Path(out_dir)
    if measured is not None and measured.channels:
        fig_name = "overlay.png"
        _overlay_figure(res, out / fig_name, measured, scenario_path, clearance)
    else:
        fig_name = "features.png"
        _feature_figure(res, out / fig_name)
    multi = len(res["points"]) > 1 or any(p["overrides"] for p in res["points"])
    model = f"`{scenario_path}`" + (f" with `{' '.join(res['model_overrides'])}`" if res["model_overrides"] else "")
    shrink = (f" ({100 * (1 - res['gap_after'] / res['gap_before']):.0f} % smaller)"
              if res["gap_before"] and math.isfinite(res["gap_before"]) else "")
    lines = ["# Model-gap diagnosis", "",
             f"Model: {model}. Gap before: **{res['gap_before']:.3f}**, after: **{res['gap_after']:.3f}**{shrink}.", ""]
    if multi:
        lines.append(f"Operating points: {', '.join(p['name'] + ' (' + ' '.join(p['overrides']) + ')' for p in res['points'])}; "
                     f"{res['simulations']} simulations, {res['wall_s']:.0f} s wall on {res['workers']} workers.")
        lines.append("")
    if res["named_effect"]:
        for n in res["named_effects"]:
            lines.append(f"Named effect: **{n}**. Signature: {res['signatures'][n]}.")
        lines.append(f"Calibrated: `{' '.join(res['calibrated_overrides'])}`.")
        if any(p["whirl_measured"] for p in res["points"]):
            fixed = [p["name"] or "the record" for p in res["points"]
                     if p["whirl_measured"] and p["whirl_before"] != p["whirl_measured"] == p["whirl_after"]]
            still = [p["name"] or "the record" for p in res["points"]
                     if p["whirl_measured"] and p["whirl_after"] != p["whirl_measured"]]
            lines.append("")
            lines.append("In the data: whirl direction measured / before / after per point: "
                         + "; ".join(f"{p['name'] or 'record'}: {p['whirl_measured']} / {p['whirl_before']} / "
                                     f"{p['whirl_after']}" for p in res["points"]) + "."
                         + (f" The named effect makes the model whirl as measured at {', '.join(fixed)}." if fixed
                            else "")
                         + (f" Still different at {', '.join(still)}." if still else ""))
    else:
        lines.append("No candidate effect explains the disagreement significantly (null answer).")
    lines += ["", "## Candidates", "", "| step | effect | gap | parameters | score | whirl per point |",
              "|---|---|---|---|---|---|"]
    for i, stp in enumerate(res["steps"], 1):
        for c in stp["candidates"]:
            note = c.get("not_applicable") or c.get("failed") or " / ".join(map(str, c.get("directions", [])))
            lines.append(f"| {i} | {c['effect']} | {c['gap']:.3g} | {c['parameters']} | {c['score']:.3g} | {note} |")
    lines += ["", "## Features (distance = |measured - model| / scale, at most 3)", "",
              "| point | feature | measured | before | after | scale | distance before | distance after |",
              "|---|---|---|---|---|---|---|---|"]
    after_rows = {(r.get("point"), r["feature"]): r for r in res["features_after"]}
    for r in res["features_before"]:
        a = after_rows.get((r.get("point"), r["feature"]), {})
        lines.append(f"| {r.get('point') or '-'} | {r['feature']} | {_fmt(r['measured'])} | {_fmt(r['simulated'])} | "
                     f"{_fmt(a.get('simulated'))} | {_fmt(r['scale'])} | {r['distance']:.3g} | "
                     f"{a.get('distance', float('nan')):.3g} |")
    lines += ["", f"![{fig_name[:-4]}]({fig_name})", ""]
    atomic_write_text(out / "report.md", "\n".join(lines))
    return ["report.md", fig_name]


def run_diagnose(scenario_path, measured_path, out_dir, *, sets=(), t_end: float | None = None, candidates=None,
                 max_effects: int = 1, workers: int = 2, maxiter: int = 10, time_offset_s: float | None = None,
                 cli_names: bool = True) -> tuple[dict, list[str]]:
    """``rotorlanding diagnose`` without its printing: validate the options, read the measurement,
    run :func:`diagnose`, write ``out_dir``/report.json, report.md and the figure; returns (the
    report, the names of the files written besides report.json). The command line and the API's
    ``rotorlanding.diagnose`` both call it, so their reports are the same.

    ``sets``: ``KEY=VALUE`` items (``--set``); ``t_end`` [s] overrides ``operating.t_end``;
    ``candidates``: effect names or None (every effect the model lacks, faults only on request);
    ``time_offset_s`` [s]: the drop instant in the data's clock (None: detected). ``cli_names``:
    errors name the options as the command line spells them (``--max-effects``), else as the API's
    keywords (``max_effects``). Every bad input is one InputError before any simulation."""
    from pathlib import Path

    from .safeio import atomic_write_text, check_out_dir
    from .scenario import EFFECTS

    def opt(name: str) -> str:
        return "--" + name.replace("_", "-") if cli_names else name

    for name, v in (("workers", workers), ("maxiter", maxiter), ("max_effects", max_effects)):
        if isinstance(v, bool) or not isinstance(v, int) or v < 1:
            raise InputError(opt(name), v, "must be an integer >= 1")
    sets = list(sets or [])
    for item in sets:
        key = item.split("=", 1)[0].strip()
        if key.startswith("effects.") and key[8:] not in EFFECTS:
            raise InputError(f"{opt('set')} {key}", item.split("=", 1)[-1], f"unknown effect; allowed: {', '.join(EFFECTS)}")
    if t_end is not None:
        sets.append(f"operating.t_end={t_end!r}")
    try:
        clearance, m, meas = measured_for_diagnosis(scenario_path, measured_path, sets, time_offset_s)
    except InputError as err:  # the readers name the file option as the command line spells it
        if cli_names or not err.field.startswith("--"):
            raise
        raise InputError(err.field[2:].replace("-", "_"), err.value, err.allowed, file=err.file) from None
    cands = list(candidates) if candidates else None
    for c in cands or []:
        if c not in CATALOGUE:
            raise InputError(opt("candidates"), c, f"unknown effect; allowed: {', '.join(CATALOGUE)}")
    out = check_out_dir(out_dir, opt("out") if cli_names else "out_dir")
    res = diagnose(meas, scenario_path, clearance=clearance, candidates=cands, max_effects=max_effects,
                   workers=workers, maxiter=maxiter, base_overrides=sets)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    atomic_write_text(out / "report.json", json.dumps(res, indent=2, default=float))
    files = write_report(res, out, m if m.channels else None, scenario_path, clearance)
    return res, files


__all__ = ["Point", "diagnose", "run_diagnose", "write_report"]

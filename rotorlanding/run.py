"""Run a landing scenario end to end: build, solve with progress, post-process, write results.

A run that fails part-way (solver divergence) keeps what it computed: results.h5 and
summary.json hold the states up to the time reached, the summary says ``"complete": false``
with that time and the solver's message, and :func:`run_scenario` reports it so the CLI exits
non-zero.

Crash safety: the output folder is checked before the solve (an existing file, /dev/null or an
unwritable folder is bad input). Before the solve starts, summary.json is replaced (atomically)
by one saying ``"complete": false, "status": "running"`` and an earlier results.h5 is removed, so
a run killed at any moment never leaves a ``complete: true`` of an earlier run in its folder.
results.h5 and summary.json are written under temporary names and renamed when complete; a
write that fails (disk full, I/O error) raises :class:`rotorlanding.safeio.WriteError` (one line,
exit 3).
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

from .exudyn_model import SolverSettings, build_exudyn, collect, solve
from .landing import build_spec
from .mechanisms import series_units
from .postprocess import evaluate, span_deflection, summarize
from .results import write_results
from .safeio import WriteError, atomic_write_text, check_out_dir, fault, unlink_quietly
from .scenario import Scenario
from .thermal_states import format_lines as format_thermal, split_warnings
from .whirl import landing_whirl

PROGRESS_MIN_STEPS = 20000
ENERGY_WARN = 0.05  # relative energy-balance error above which the summary warns  # show a progress bar for runs of at least this many steps


class Progress:
    """Text progress bar on stderr, driven by Exudyn's pre-step user function."""

    def __init__(self, t0: float, t1: float, stream=sys.stderr, width: int = 30):
        self.t0, self.t1, self.stream, self.width = t0, t1, stream, width
        self.next = 0.0
        self.wall0 = time.perf_counter()

    def __call__(self, mbs, t) -> bool:
        frac = (t - self.t0) / (self.t1 - self.t0)
        if frac >= self.next:
            self.next += 0.02
            n = int(self.width * min(frac, 1.0))
            wall = time.perf_counter() - self.wall0
            self.stream.write(f"\r[{'#' * n}{' ' * (self.width - n)}] {100 * frac:5.1f} %  t = {t:.4f} s  "
                              f"wall {wall:6.1f} s")
            self.stream.flush()
        return True

    def close(self):
        self.stream.write("\n")
        self.stream.flush()


def simulate(scenario: Scenario, *, progress: bool | None = None, reduction=None):
    """Solve the scenario; returns (spec, t, q, v, info). ``reduction``: see ``landing.build_spec``."""
    spec = build_spec(scenario, reduction=reduction)
    model = build_exudyn(spec)
    settings = SolverSettings.from_spec(spec)
    n_steps = scenario.t_end / settings.step
    bar = None
    if progress or (progress is None and n_steps >= PROGRESS_MIN_STEPS):
        bar = Progress(0.0, scenario.t_end)
        model.pre_step.progress = bar
    ok, msg, stats = solve(model, 0.0, scenario.t_end, settings)
    if bar:
        bar.close()
    t, q, v = collect(model)
    if not ok and len(t):
        # keep only samples the solver actually reached
        keep = t <= stats["t_reached"] + 1e-12
        t, q, v = t[keep], q[keep], v[keep]
    stats.update(complete=bool(ok), message=msg, simulated_s=float(t[-1]) if len(t) else 0.0)
    return spec, t, q, v, stats


def run_scenario(scenario: Scenario, out_dir, *, progress: bool | None = None, plots: bool = True,
                 reduction=None, results: bool = True) -> dict:
    """Simulate and write results.h5, summary.json and the figures into ``out_dir``.
    ``results=False``: summary.json only (and the figures if ``plots``), for the members of an
    ensemble that nothing reads back: results.h5 is ~8 MB per 1.2 s landing and its gzip ~0.15 s."""
    out = check_out_dir(Path(out_dir))  # before the solve: a bad --out is found at once
    try:
        atomic_write_text(out / "summary.json", json.dumps(RUNNING_SUMMARY | {"scenario": scenario.name}, indent=2))
        unlink_quietly(out / "results.h5")  # an earlier run's results must not outlive this run's start
    except OSError as exc:
        raise WriteError(out / "summary.json", exc) from None
    fault("run-started")
    spec, t, q, v, stats = simulate(scenario, progress=progress, reduction=reduction)
    try:
        return _write(scenario, out, spec, t, q, v, stats, plots, results)
    except OSError as exc:
        raise WriteError(getattr(exc, "filename", None) or out, exc) from None


RUNNING_SUMMARY = {"complete": False, "status": "running",
                   "message": "written when a run starts and replaced when it ends: if no run is active, it was "
                              "interrupted"}


def _write(scenario, out, spec, t, q, v, stats, plots, results=True) -> dict:
    if len(t) < 2:
        summary = {"scenario": scenario.name, "complete": False, "t_reached_s": 0.0, "message": stats["message"],
                   "performance": {k: stats[k] for k in ("simulated_s", "wall_s", "steps")}}
        atomic_write_text(out / "summary.json", json.dumps(summary, indent=2))
        return summary
    series, summary = build_summary(scenario, spec, t, q, v, stats)
    if results:
        write_results(out / "results.h5", scenario_raw=scenario.raw, scenario_name=scenario.name, names=spec.names,
                      t=t, q=q, v=v, series=series, units=series_units(spec.bearing_names), summary=summary,
                      complete=stats["complete"],
                      t_reached=float(t[-1]), message=summary.get("message", ""))
    # the summary is final only once results.h5 is (when written): a kill in between leaves `running`
    atomic_write_text(out / "summary.json", json.dumps(summary, indent=2))
    if plots:
        plot_files = __import__("rotorlanding.plots", fromlist=["plot_all"]).plot_all(
            out, t, series, summary, {b.name: b.params.clearance for b in spec.bearings}, scenario.amb.t_drop)
        summary["figures"] = [p.name for p in plot_files]
        atomic_write_text(out / "summary.json", json.dumps(summary, indent=2))
    return summary


def build_summary(scenario, spec, t, q, v, stats) -> tuple[dict, dict]:
    """(series, summary) of a solved run (at least two samples): the derived time series (SI,
    units in ``mechanisms.series_units``) and the summary.json content. The CLI and the Python
    API (:func:`rotorlanding.simulate`) both build their summary here."""
    series = evaluate(spec, t, q, v)
    summary = summarize(spec, t, series)
    summary["rotor_deflection"] = span_deflection(spec, q)
    gaps = close_clearances(scenario)
    summary["rotor_deflection"]["close_clearances_m"] = gaps  # what it is judged against
    summary["complete"] = stats["complete"]
    summary["t_reached_s"] = float(t[-1])
    if not stats["complete"]:
        summary["message"] = f"solver stopped at t = {t[-1]:.6g} s: {stats['message']}; {stop_report(spec, series, stats)}"
    summary["performance"] = {"simulated_s": stats["simulated_s"], "wall_s": stats["wall_s"], "steps": stats["steps"],
                              "newton_iterations": stats["newton_iterations"], "jacobians": stats["jacobians"],
                              "wall_s_per_simulated_s": stats["wall_s"] / max(stats["simulated_s"], 1e-12),
                              "step_s": scenario.solver.step}
    if scenario.solver.step_control == "auto":  # step_s is then the first step; the controller's counts
        summary["performance"].update(step_control="auto", step_tolerance_m=scenario.solver.step_tolerance,
                                      max_step_s=scenario.solver.max_step,
                                      rejected_steps=stats.get("rejected_steps"))
    summary["units"] = "SI (m, N, s, J); speeds in rpm as named"
    warnings = []
    err = summary["energy"]["balance_error_relative"]
    if err > ENERGY_WARN:
        warnings.append(f"energy balance error {100 * err:.1f} % > {100 * ENERGY_WARN:.0f} %: the time step "
                        f"({scenario.solver.step:g} s) or the output period is too coarse; results are not trustworthy")
    warnings += split_warnings(summary.get("thermal"))
    warnings += clearance_warnings(gaps, summary["rotor_deflection"])
    summary["warnings"] = warnings
    return series, summary


def close_clearances(scenario) -> dict[str, float]:
    """The scenario's ``[limits] close_clearances_m`` (station -> radial gap [m]; {} when none)."""
    from .limits import limits_from_dict

    return limits_from_dict(scenario.raw.get("limits")).close_clearances_m


def clearance_warnings(gaps: dict, deflection: dict) -> list[str]:
    """A warning per close clearance (``gaps``: :func:`close_clearances`) the rotor runs past: the model has
    no contact at an AMB stator, sensor or seal, so past its gap the run no longer shows what the
    machine does (it would rub there). The verdict judges the same numbers (``verdict.close_clearance_criteria``)."""
    peaks = deflection.get("station_peak_m") or {}
    return [f"the rotor runs {peaks[st] * 1e3:.3f} mm off the bearings' axis at {st}, past its {gap * 1e3:.3g} mm gap "
            "([limits] close_clearances_m): a real rotor would touch the part there, which the model has no contact for"
            for st, gap in gaps.items() if st in peaks and peaks[st] > gap]


def stop_report(spec, series: dict, stats: dict, window: int = 20) -> str:
    """What was extreme when the solver stopped (last ``window`` output samples) and the input it
    points to, so a `SolveDynamic terminated` names a cause: a contact force far above the rotor's
    weight anywhere in the run points at the contact stiffness/damping, a race or rotor speed
    running away at the friction or drive, otherwise the step."""
    sc = spec.scenario
    weight = sc.rotor.mass * 9.80665
    parts, likely = [], []
    worst = 0.0
    for b in sc.bearings:
        f_all = np.abs(series[f"{b}_normal_force_n"])
        f = f_all[-window:]
        d = series[f"{b}_penetration_m"][-window:]
        parts.append(f"{b} contact force up to {f.max():.3g} N ({f.max() / weight:.3g} x rotor weight), "
                     f"penetration {d.max():.3g} m, race {series[f'{b}_race_speed_rpm'][-1]:.4g} rpm")
        # the run's peak, not only the last samples': where the solver gives up is a matter of which
        # step it cut last (k_hertz 1e18: 47 x the weight at 0.01 s, 19 x in the last 20 samples)
        worst = max(worst, float(f_all.max()) / weight)
    rotor = series["rotor_speed_rpm"][-window:]
    h = stats.get("step_at_stop_s", float("nan"))
    parts.append(f"rotor {rotor[-1]:.4g} rpm, step {h:.3g} s (solver.step {sc.solver.step:g} s"
                 + (f", cut {sc.solver.step / h:.3g}-fold: a force too stiff for the step)" if h < 1e-3 * sc.solver.step
                    else ")"))
    if worst > 20:  # landing impacts on the rig peak at ~5 x the rotor's weight (docs/validation.md, Table 2)
        parts.append(f"peak contact force of the run {worst:.3g} x rotor weight")
        likely.append("contact.k_hertz / contact.k_visc (impact forces far above a landing's)")
    races = max(abs(series[f"{b}_race_speed_rpm"][-1]) for b in sc.bearings)
    if races > 1.5 * max(abs(sc.speed_rpm), 1.0) or abs(rotor[-1]) > 1.5 * max(abs(sc.speed_rpm), 1.0):
        likely.append("friction (contact.mu_rad, contact.mu_ax) or spin.drive (a speed running away)")
    likely.append("solver.step (halve it)")
    return "at the stop: " + "; ".join(parts) + "; likely input: " + ", or ".join(likely)


def format_summary(summary: dict) -> str:
    """A few lines a designer reads first."""
    lines = [f"scenario: {summary['scenario']}" + ("" if summary.get("complete", True) else
                                                   f"  [INCOMPLETE: {summary.get('message', '')}]")]
    w = landing_whirl(summary["whirl"]) if summary.get("whirl") else {}
    if w:
        f = f" at {w['frequency_hz']:.1f} Hz from t = {w['onset_s']:.3f} s" if w.get("frequency_hz") else ""
        if w.get("frequency_hz") and w.get("end_s") is not None:
            f += f" to {w['end_s']:.3f} s (whirling {100 * w.get('persistence', 0.0):.0f} % of the time after onset)"
        per = w.get("per_bearing", {})
        if w["direction"] == "none":
            lines.append("whirl: none" + (f" at {', '.join(per)}" if per else ""))
        else:
            others = [f"{k}: {v['direction']}" + (f" at {v['frequency_hz']:.1f} Hz" if v.get("frequency_hz") else "")
                      for k, v in per.items() if k != w["bearing"]]
            sh = w.get("shape") or {}
            shape = "" if sh.get("phase_deg") is None else (
                f"; shape {sh['form']}: the {sh['against']} journal {sh['phase_deg']:+.0f} deg from it, "
                f"{sh['amplitude_ratio']:.2f} x its component")
            lines.append(f"whirl at the {w['bearing']} bearing: {w['direction']}{f}"
                         + (f"; {'; '.join(others)}" if others else "") + shape)
    for name, b in summary.get("bearings", {}).items():
        lines.append(f"{name}: max contact force {b['max_contact_force_n']:.0f} N, vertical range "
                     f"{b['vertical_displacement_range_m'][0] * 1e3:+.3f} / {b['vertical_displacement_range_m'][1] * 1e3:+.3f} mm, "
                     f"horizontal {b['horizontal_displacement_range_m'][0] * 1e3:+.3f} / "
                     f"{b['horizontal_displacement_range_m'][1] * 1e3:+.3f} mm, inner race {b['final_race_speed_rpm']:.0f} rpm")
    d = summary.get("rotor_deflection")
    if d:  # the span, not only the sleeves: AMB stators, sensors and seals sit elsewhere on the rotor
        lines.append(f"rotor off the bearings' axis: largest {d['peak_m'] * 1e3:.3f} mm at x = {d['peak_x_m']:.3f} m; "
                     + ", ".join(f"{k} {v * 1e3:.3f}" for k, v in d["station_peak_m"].items()) + " mm")
    s = summary.get("speeds")
    if s:
        lines.append(f"rotor speed: {s['initial_rotor_rpm']:.0f} -> {s['final_rotor_rpm']:.0f} rpm")
    e = summary.get("energy")
    if e:
        top = sorted(e["dissipated_j"].items(), key=lambda kv: -kv[1])[:3]
        lines.append(f"energy lost: {e['dissipated_total_j']:.2f} J (" +
                     ", ".join(f"{k} {v:.2f} J" for k, v in top) +
                     f"); balance error {100 * e['balance_error_relative']:.3f} %")
    lines += format_thermal(summary.get("thermal"))
    for w in summary.get("warnings", []):
        lines.append(f"WARNING: {w}")
    p = summary.get("performance")
    if p and "wall_s_per_simulated_s" in p:
        lines.append(f"performance: {p['simulated_s']:.3f} s simulated in {p['wall_s']:.1f} s wall "
                     f"({p['wall_s_per_simulated_s']:.2f} s/s), {p['steps']} steps")
    return "\n".join(lines)


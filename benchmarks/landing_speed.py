"""Benchmark: speed of the full-model landings, Exudyn vs scipy's LSODA (run on demand, not in CI).

Cases: the paper's forward-whirl landing (scenarios/paper/forward_whirl_landing.toml: full model,
both bearings, axial rub, 4 kN thrust, 1 s) and the radial landing at 7000 rpm
(scenarios/landing_7000rpm.toml, 0.5 s). Per case and variant, one fresh process per run (so peak
memory is per run), best of --repeat:

- ``exudyn h=<step>``: the model as built by rotorlanding (compiled bearing connector with analytic
  Jacobians, Newton settings of SolverSettings) at the case's benchmark step (CASES, or --step;
  output period = step);
- ``exudyn scenario step``: the same at the scenario's own [solver] step (not run, and listed as
  skipped, when that step is the benchmark step: cases 2-5 and --step equal to the scenario's);
- ``exudyn numerical jacobians`` (with --baseline): plain-Python laws, one connector per bearing,
  Exudyn's numerical Jacobians and Exudyn's default Newton strategy (the state before issue 6),
  at the scenario's step;
- ``LSODA``: scipy's LSODA (rtol 1e-6, atol 1e-9) on the same equations, with the leanest RHS
  we have (the same compiled force kernel, numpy for the linear rotor, tilt from the current
  state) and its analytic Jacobian (rotorlanding.bearing_kernel.system_forces).

Reported per run: wall s per simulated s, steps, Newton iterations (per step), Jacobian
evaluations, time share of the Python user functions (a separate instrumented run), peak memory
(ru_maxrss of the run's process), the machine load (1-min load average) at the start; the
ratio LSODA / Exudyn at the benchmark step. With --convergence: peak contact force and whirl
frequency at the benchmark step and at half of it (acceptance: < 5 % and < 1 % change).

usage: python benchmarks/landing_speed.py [--step S] [--repeat 3] [--baseline] [--convergence]
                                          [--t-end S] [--lsoda-t-end S] [--json bench.json]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# case: (scenario, benchmark step). The step is the largest power-of-two multiple of the rig's 5e-5 s
# whose half-step result changes the peak contact force by < 5 % and the whirl frequency by < 1 %
# (benchmarks/step_convergence.py, 2026-11): forward whirl 2e-4 s (0.13 % / 0.03 %; 4e-4 s: 0.98 % /
# 0.42 %, energy error 0.17 %); radial landing 1e-4 s (1.05 %; 2e-4 s: 10.6 % on the first impact).
CASES = {
    "paper forward-whirl landing (3.3, 7000 rpm, 4 kN, axial rub)": (
        ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml", 2e-4),
    "radial landing 7000 rpm (mu_rad 0.15)": (ROOT / "scenarios" / "landing_7000rpm.toml", 1e-4),
    # the other paper landings (issue 21) at the rig's step: their benchmark steps are not yet
    # established by step_convergence.py (select with --cases, e.g. --cases 2,3,4,5)
    "paper backward-whirl landing (3.2, worn bearing)": (ROOT / "scenarios" / "paper" / "backward_whirl_landing.toml",
                                                         5e-5),
    "paper no-whirl landing (3.1)": (ROOT / "scenarios" / "paper" / "no_whirl_landing.toml", 5e-5),
    "paper forward-whirl landing 3000 rpm": (ROOT / "scenarios" / "paper" / "forward_whirl_3000rpm.toml", 5e-5),
    "paper forward-whirl landing 10000 rpm": (ROOT / "scenarios" / "paper" / "forward_whirl_10000rpm.toml", 5e-5),
}
PRE_ISSUE6_NEWTON = dict(jacobian_per_step=False, newton_contractivity=0.5, newton_max_iterations=25,
                         adaptive_recovery_iterations=7, linear_solver="EXUdense")  # Exudyn's defaults


def _load(path, t_end, step, auto=None):
    from rotorlanding.scenario import load_scenario

    sets = [] if t_end is None else [f"operating.t_end={t_end}"]
    if step is not None:
        sets += [f"solver.step={step}", f"solver.output_period={step}"]
    if auto is not None:  # (tolerance, max step): the error-controlled step, rig output period
        sets += ["solver.step_control='auto'", f"solver.step_tolerance={auto[0]!r}", f"solver.max_step={auto[1]!r}"]
    return load_scenario(path, sets)


def worker(job: dict) -> dict:
    """One measurement in this (fresh) process."""
    load = os.getloadavg()[0]
    from rotorlanding.landing import build_spec

    sc = _load(job["path"], job.get("t_end"), job.get("step"), job.get("auto"))
    spec = build_spec(sc)
    t_end = sc.t_end
    out = {"load_1min": load, "simulated_s": t_end, "coordinates": spec.n}
    if job["kind"] == "lsoda":
        import numpy as np
        from scipy.integrate import solve_ivp

        from rotorlanding.bearing_kernel import system_forces
        from rotorlanding.reference import mass_matrix

        f, jac = system_forces(spec)
        n = spec.n
        minv = np.linalg.inv(mass_matrix(spec))
        calls = [0.0, 0]

        def rhs(t, y):
            t0 = time.perf_counter()
            r = np.concatenate([y[n:], minv @ f(t, y[:n], y[n:])])
            calls[0] += time.perf_counter() - t0
            calls[1] += 1
            return r

        def jfirst(t, y):
            Jq, Jv = jac(t, y[:n], y[n:])
            J = np.zeros((2 * n, 2 * n))
            J[:n, n:] = np.eye(n)
            J[n:, :n] = minv @ Jq
            J[n:, n:] = minv @ Jv
            return J

        q0, v0 = spec.initial_state()
        rhs(0.0, np.concatenate([q0, v0]))  # compile/load the kernel outside the timing
        calls[:] = [0.0, 0]
        w0 = time.perf_counter()
        sol = solve_ivp(rhs, (0.0, t_end), np.concatenate([q0, v0]), method="LSODA", rtol=1e-6, atol=1e-9,
                        jac=jfirst if job.get("jac", True) else None)
        wall = time.perf_counter() - w0
        out.update(wall_s=wall, complete=bool(sol.success), steps=len(sol.t) - 1, rhs_evaluations=int(sol.nfev),
                   jacobians=int(sol.njev), lu_decompositions=int(sol.nlu), user_function_share=calls[0] / wall)
    else:
        import exudyn as exu  # noqa: F401

        from rotorlanding.exudyn_model import SolverSettings, build_exudyn, solve

        analytic = job["kind"] == "exudyn"
        settings = SolverSettings.from_spec(spec)
        if not analytic:
            for k, v in PRE_ISSUE6_NEWTON.items():
                setattr(settings, k, v)
        acc = {} if job.get("instrument") else None
        model = build_exudyn(spec, analytic_jacobian=analytic, merge_connectors=analytic, instrument=acc)
        ok, msg, st = solve(model, 0.0, t_end, settings)
        out.update(wall_s=st["wall_s"], complete=ok, steps=st["steps"], newton_iterations=st["newton_iterations"],
                   jacobians=st["jacobians"], step_s=None if settings.step_control == "auto" else settings.step,
                   rejected_steps=st.get("rejected_steps"))
        if acc is not None:
            out["user_function_s"] = {k: v[0] for k, v in acc.items()}
            out["user_function_calls"] = {k: v[1] for k, v in acc.items()}
            out["user_function_share"] = sum(v[0] for v in acc.values()) / st["wall_s"]
    out["wall_s_per_simulated_s"] = out["wall_s"] / t_end
    out["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    return out


def same_step_row(step: float, scenario_step: float) -> str | None:
    """Why the "exudyn scenario step" row would repeat the "exudyn h=<step>" row, or None.

    The paper landings' benchmark step is the rig's 5e-5 s, which is also their [solver] step: the
    two rows then take the same steps and Newton iterations (only the sensor output period differs,
    step vs the scenario's output_period, which measured no difference in wall time beyond noise),
    so timing it twice only doubled the run time and printed a duplicate row."""
    if abs(step - scenario_step) > 1e-12 * max(step, scenario_step):
        return None
    return f"the scenario's step ({scenario_step:g} s) is the benchmark step, row 'exudyn h={step:g}'"


def run_worker(script, job: dict) -> dict:
    """Run ``script --worker JOB`` in a fresh process (one landing, its own imports and JIT caches)
    and return the JSON of its last output line; shared with benchmarks/auto_step.py."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    r = subprocess.run([sys.executable, str(script), "--worker", json.dumps(job)], capture_output=True, text=True,
                       env=env, cwd=ROOT)
    if r.returncode != 0:
        raise RuntimeError(f"worker failed: {job}\n{r.stderr[-3000:]}")
    return json.loads(r.stdout.strip().splitlines()[-1])


def run_job(job: dict) -> dict:
    return run_worker(__file__, job)


def best_of(job: dict, repeat: int) -> dict:
    runs = [run_job(job) for _ in range(repeat)]
    best = min(runs, key=lambda r: r["wall_s"])
    best["wall_s_per_simulated_s_all"] = [r["wall_s_per_simulated_s"] for r in runs]
    best["load_1min_all"] = [r["load_1min"] for r in runs]
    best["peak_rss_mb"] = max(r["peak_rss_mb"] for r in runs)
    if job["kind"] != "lsoda":
        inst = run_job(dict(job, instrument=True))
        for k in ("user_function_share", "user_function_s", "user_function_calls"):
            best[k] = inst[k]
        best["instrumented_wall_s"] = inst["wall_s"]
    return best


def convergence(path, step, t_end) -> dict:
    """Peak contact force and whirl frequency at step and step/2 (same rule as step_convergence.py)."""
    sys.path.insert(0, str(Path(__file__).parent))
    import tempfile

    import step_convergence

    if t_end is None:
        t_end = _load(path, None, None).t_end
    with tempfile.TemporaryDirectory() as d:
        out = Path(d) / "conv.json"
        args = [str(path), "--steps", f"{step},{step / 2}", "--json", str(out), "--t-end", str(t_end)]
        step_convergence.main(args)
        coarse, fine = json.loads(out.read_text())
    return {"step_s": step, "half_step_s": step / 2, "simulated_s": t_end, "peak_force_n": [coarse["peak_force_n"], fine["peak_force_n"]],
            "whirl": [coarse["whirl"], fine["whirl"]], "whirl_hz": [coarse["whirl_hz"], fine["whirl_hz"]],
            "peak_force_change": coarse["peak_force_change_on_halving"],
            "whirl_frequency_change": coarse["whirl_change_on_halving"],
            "energy_error": [coarse["energy_error"], fine["energy_error"]]}


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--worker", help=argparse.SUPPRESS)
    ap.add_argument("--step", type=float, default=None,
                    help="benchmark step [s] for all cases (default: per case, see CASES; output period = step)")
    ap.add_argument("--t-end", type=float, default=None, help="simulated seconds (default: the scenario's t_end)")
    ap.add_argument("--lsoda-t-end", type=float, default=None, help="simulated seconds for LSODA (default: --t-end)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--baseline", action="store_true", help="also the pre-issue-6 model (numerical Jacobians)")
    ap.add_argument("--no-lsoda", action="store_true")
    ap.add_argument("--convergence", action="store_true", help="also peak force / whirl at step and step/2")
    ap.add_argument("--auto", default=None, metavar="TOL:HMAX",
                    help="also the error-controlled step (solver.step_control = 'auto') with these settings")
    ap.add_argument("--cases", default="0,1", help="'all' or comma-separated indices into the case list (default 0,1: the two cases with established benchmark steps)")
    ap.add_argument("--json")
    a = ap.parse_args(argv)
    if a.worker:
        print(json.dumps(worker(json.loads(a.worker))))
        return 0
    import rotorlanding

    cases = list(CASES.items())
    if a.cases != "all":
        cases = [cases[int(i)] for i in a.cases.split(",")]
    report = {"rotorlanding": rotorlanding.__version__, "python": platform.python_version(),
              "cpus": os.cpu_count(), "repeat": a.repeat, "cases": []}
    for name, (path, step) in cases:
        step = a.step or step
        rows = {}
        base = {"path": str(path), "t_end": a.t_end}
        rows[f"exudyn h={step:g}"] = best_of(dict(base, kind="exudyn", step=step), a.repeat)
        skipped = {}
        same = same_step_row(step, _load(path, a.t_end, None).solver.step)
        if same:
            skipped["exudyn scenario step"] = same
        else:
            rows["exudyn scenario step"] = best_of(dict(base, kind="exudyn"), a.repeat)
        if a.auto:
            tol, hmax = (float(x) for x in a.auto.split(":"))
            rows[f"exudyn auto tol {tol:g} max {hmax:g}"] = best_of(dict(base, kind="exudyn", auto=[tol, hmax]),
                                                                    a.repeat)
        if a.baseline:
            rows["exudyn numerical jacobians (before)"] = best_of(dict(base, kind="numerical"), max(1, a.repeat - 1))
        if not a.no_lsoda:
            rows["LSODA rtol 1e-6"] = best_of(dict(base, kind="lsoda", t_end=a.lsoda_t_end or a.t_end),
                                              max(1, a.repeat - 1))
        case = {"case": name, "scenario": str(path.relative_to(ROOT)), "step_s": step, "runs": rows}
        if skipped:
            case["skipped"] = skipped
        ex = rows[f"exudyn h={step:g}"]
        if "LSODA rtol 1e-6" in rows:
            case["lsoda_over_exudyn"] = rows["LSODA rtol 1e-6"]["wall_s_per_simulated_s"] / ex["wall_s_per_simulated_s"]
            for name, r in rows.items():
                if name.startswith("exudyn auto"):
                    case["lsoda_over_exudyn_auto"] = rows["LSODA rtol 1e-6"]["wall_s_per_simulated_s"] / r["wall_s_per_simulated_s"]
        if a.convergence:
            case["convergence"] = convergence(path, step, a.t_end)
        report["cases"].append(case)
        _print_case(case)
    if a.json:
        Path(a.json).write_text(json.dumps(report, indent=2))
    return 0


def _print_case(case):
    print(f"\n{case['case']}  [{case['scenario']}]")
    print(f"{'variant':38s} {'s/s':>6} {'step':>8} {'steps':>6} {'it/step':>7} {'jac':>6} {'uf %':>5} {'MB':>5} "
          f"{'load':>5}")
    for name, r in case["runs"].items():
        its = r.get("newton_iterations")
        itps = f"{its / r['steps']:7.2f}" if its else f"{'-':>7}"
        step = f"{r['step_s']:8.1e}" if r.get("step_s") else f"{'adapt':>8}"
        print(f"{name:38s} {r['wall_s_per_simulated_s']:6.2f} {step} {r['steps']:6d} {itps} {r['jacobians']:6d} "
              f"{100 * r['user_function_share']:5.0f} {r['peak_rss_mb']:5.0f} {r['load_1min']:5.2f}"
              + (f"  (nfev {r['rhs_evaluations']})" if "rhs_evaluations" in r else ""))
    for name, why in case.get("skipped", {}).items():
        print(f"{name:38s} skipped: {why}")
    if "lsoda_over_exudyn" in case:
        print(f"LSODA / Exudyn (wall per simulated s): {case['lsoda_over_exudyn']:.1f}x")
    if "lsoda_over_exudyn_auto" in case:
        print(f"LSODA / Exudyn auto step (wall per simulated s): {case['lsoda_over_exudyn_auto']:.1f}x")
    c = case.get("convergence")
    if c:
        print(f"step convergence h={c['step_s']:g} -> {c['half_step_s']:g}: peak force {c['peak_force_n'][0]:.0f} -> "
              f"{c['peak_force_n'][1]:.0f} N ({100 * c['peak_force_change']:.2f} %), whirl {c['whirl'][0]} "
              f"{c['whirl_hz'][0]} -> {c['whirl'][1]} {c['whirl_hz'][1]} Hz"
              + (f" ({100 * c['whirl_frequency_change']:.2f} %)" if c['whirl_frequency_change'] is not None else ""))
    sys.stdout.flush()


if __name__ == "__main__":
    sys.exit(main())

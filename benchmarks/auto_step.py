"""Benchmark (issue 21): the error-controlled step (``solver.step_control = "auto"``) against fixed steps.

Two uses, each landing in a fresh process (one JSON line per run):

``profile``: where the time of a step goes, per variant, on one landing: wall, steps, step
attempts (pre-step calls), rejected steps, Newton iterations, Jacobians, Python user-function calls
and their time, and Exudyn's own timers (residual, Jacobian, factorisation, Python) as shares.
Variants: ``fixed:H`` (fixed step H), ``auto:TOL:HMAX`` (the StepController), ``probe:TOL:HMAX``
(session 11's probe: a PostNewton recommendation with ``discontinuous.maxIterations = 1``).
Variants alternate, best of --repeat by wall time; the load average is printed with each run.

``verify``: every paper landing of ``rotorlanding validate`` (CASES), each as validate's ensemble
(8 drops from the 5 um circle, 16 for the backward landing; or --drops), auto and the rig's fixed
step against a fixed reference step (default 1.25e-5 s, 4x finer than the rig's 5e-5 s): per case
the ensemble class, median frequency, onset and peak contact force (member medians), the
differences with the issue's rule (class equal, frequency 1 %, peak 5 %), and wall s per simulated
s (median of the members; runs one after another, so the load moves between rows).

usage: python benchmarks/auto_step.py profile SCENARIO [--t-end S] [--variants fixed:5e-5,auto:1e-7:4e-4] [--repeat 3]
       python benchmarks/auto_step.py verify [--drops N] [--cases all] [--reference 1.25e-5] [--auto 1e-7:4e-4]
                                             [--rig 5e-5] [--cache DIR] [--t-end S] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _sets(variant: str) -> list[str]:
    kind, *a = variant.split(":")
    if kind == "fixed":
        h = float(a[0])
        return [f"solver.step={h!r}", f"solver.output_period={max(h, 1e-4)!r}", "solver.step_control='fixed'"]
    if kind in ("auto", "probe"):
        tol, hmax = float(a[0]), float(a[1])
        sets = [f"solver.step_tolerance={tol!r}", f"solver.max_step={hmax!r}"]
        return sets + (["solver.step_control='auto'"] if kind == "auto" else
                       [f"solver.step={hmax!r}", f"solver.output_period={max(hmax, 1e-4)!r}"])
    raise SystemExit(f"unknown variant {variant!r}: fixed:H | auto:TOL:HMAX | probe:TOL:HMAX")


def worker(job: dict) -> dict:
    load = os.getloadavg()[0]
    import exudyn as exu

    from rotorlanding import exudyn_model as em
    from rotorlanding.landing import build_spec
    from rotorlanding.run import build_summary
    from rotorlanding.scenario import load_scenario

    variant = job["variant"]
    for k, val in (job.get("controller") or {}).items():  # trial settings of the controller
        setattr(em.StepController, k, val)
    sets = list(job.get("sets", [])) + _sets(variant)
    if job.get("t_end"):
        sets.append(f"operating.t_end={job['t_end']!r}")
    sc = load_scenario(job["path"], sets)
    spec = build_spec(sc)
    acc = {} if job.get("instrument") else None
    model = em.build_exudyn(spec, instrument=acc)
    settings = em.SolverSettings.from_spec(spec)
    timers = {}
    if acc is not None:  # Exudyn's internal timers run only when asked to show them
        apply0 = em.SolverSettings.apply

        def apply(self, exu_, t0, t1):
            ss_ = apply0(self, exu_, t0, t1)
            ss_.show.computationTime = True
            return ss_

        em.SolverSettings.apply = apply
    if variant.startswith("probe"):
        # session 11's probe, unchanged (its hook and settings from adaptive_step_probe): recommendation
        # returned, error 0, one discontinuous iteration
        from adaptive_step_probe import probe_hook, probe_settings

        asked = [0]
        post = probe_hook(model.mbs, spec, sc.solver.step_tolerance, asked)
        model.mbs.SetPostNewtonUserFunction(acc and em._timed(post, acc, "postnewton") or post)
        ss = settings.apply(exu, 0.0, sc.t_end)
        probe_settings(ss)
        ss.timeIntegration.verboseMode = 0
        exu.config.suppressWarnings = True
        w0 = time.perf_counter()
        ok = exu.SolveDynamic(model.mbs, ss) is not False
        wall = time.perf_counter() - w0
        it = model.mbs.sys["dynamicSolver"].it
        stats = {"wall_s": wall, "steps": int(it.currentStepIndex), "newton_iterations": int(it.newtonStepsCount),
                 "jacobians": int(it.newtonJacobiCount), "rejected_steps": 0, "probe_asked": asked[0],
                 "t_reached": float(it.currentTime)}
        t, q, v = em.collect(model)
        tm = model.mbs.sys["dynamicSolver"].timer
    else:
        if acc is not None and settings.step_control == "auto":
            orig = em.StepController.__call__
            wrapped = em._timed(lambda self, mbs, t: orig(self, mbs, t), acc, "postnewton")
            em.StepController.__call__ = wrapped
        ok, msg, stats = em.solve(model, 0.0, sc.t_end, settings)
        t, q, v = em.collect(model)
        tm = model.mbs.sys["dynamicSolver"].timer
    for k in ("ODE2RHS", "totalJacobian", "factorization", "newtonIncrement", "python", "postNewton",
              "writeSolution", "integrationFormula", "overhead", "massMatrix"):
        timers[k] = float(getattr(tm, k))
    stats.update(complete=bool(ok), message="", simulated_s=float(t[-1]))
    _, s = build_summary(sc, spec, t, q, v, stats)
    w = s["whirl"]
    out = {"variant": variant, "load_1min": load, "wall_s": stats["wall_s"], "simulated_s": sc.t_end,
           "s_per_s": stats["wall_s"] / sc.t_end, "complete": bool(ok), "steps": stats["steps"],
           "rejected": stats.get("rejected_steps", 0), "probe_asked": stats.get("probe_asked"),
           "newton_iterations": stats["newton_iterations"], "jacobians": stats["jacobians"],
           "whirl": w.get("direction"), "hz": w.get("frequency_hz"), "onset_s": w.get("onset_s"),
           "bearing": w.get("bearing"),
           "peak_force_n": max(b["max_contact_force_n"] for b in s["bearings"].values()),
           "energy_error": s["energy"]["balance_error_relative"], "exudyn_timers_s": timers}
    if acc is not None:
        out["user_functions"] = {k: {"s": v[0], "calls": v[1]} for k, v in acc.items()}
    from rotorlanding.ensemble import member_result

    out["member"] = member_result(s)
    return out


CACHE = None  # directory of finished runs (verify --cache): a reference is not solved twice


def run_job(job: dict) -> dict:
    if CACHE is not None:
        import hashlib

        f = Path(CACHE) / (hashlib.sha256(json.dumps(job, sort_keys=True).encode()).hexdigest()[:20] + ".json")
        if f.is_file():
            return json.loads(f.read_text())
        r = _run_job(job)
        f.write_text(json.dumps(r))
        return r
    return _run_job(job)


def _run_job(job: dict) -> dict:
    from landing_speed import run_worker

    return run_worker(__file__, job)


def profile(a):
    variants = a.variants.split(",")
    best = {}
    for rep in range(a.repeat):
        for v in variants:  # alternate the variants
            r = run_job({"path": a.scenario, "variant": v, "t_end": a.t_end})
            print(f"  run {rep + 1} {v:22s} wall {r['wall_s']:.3f} s  load {r['load_1min']:.2f}", flush=True)
            if v not in best or r["wall_s"] < best[v]["wall_s"]:
                best[v] = dict(r, loads=best.get(v, {}).get("loads", []) + [r["load_1min"]])
            else:
                best[v]["loads"].append(r["load_1min"])
    inst = {v: run_job({"path": a.scenario, "variant": v, "t_end": a.t_end, "instrument": True}) for v in variants}
    ref = best[variants[0]]["wall_s"]
    print(f"\n{a.scenario}, t_end {a.t_end or 'scenario'} s; best of {a.repeat}, alternating; "
          f"user-function numbers from one extra instrumented run")
    print(f"{'variant':22s} {'s/s':>6} {'ratio':>6} {'steps':>6} {'attempts':>8} {'rej':>5} {'Newton':>7} {'it/st':>5} "
          f"{'jac':>6} {'us/step':>7} {'uf us/step':>10} {'whirl':>8} {'Hz':>7} {'onset':>6} {'peak N':>7} load")
    for v in variants:
        r, i = best[v], inst[v]
        uf = i.get("user_functions", {})
        # step attempts = pre-step calls (the auto step runs the pre-step's work itself: not counted)
        attempts = uf["prestep"]["calls"] if "prestep" in uf else "-"
        uf_us = 1e6 * sum(x["s"] for x in uf.values()) / max(r["steps"], 1)
        print(f"{v:22s} {r['s_per_s']:6.3f} {r['wall_s'] / ref:6.3f} {r['steps']:6d} {attempts:>8} {r['rejected']:5d} "
              f"{r['newton_iterations']:7d} {r['newton_iterations'] / r['steps']:5.2f} {r['jacobians']:6d} "
              f"{1e6 * r['wall_s'] / r['steps']:7.1f} {uf_us:10.1f} {r['whirl']:>8} {r['hz'] or 0:7.2f} "
              f"{r['onset_s'] or 0:6.3f} {r['peak_force_n']:7.0f} {','.join(f'{x:.2f}' for x in r['loads'])}")
    print("\nper variant (instrumented run): Python user functions calls/step and us/call; Exudyn timers (share of wall)")
    for v in variants:
        i = inst[v]
        uf = i.get("user_functions", {})
        parts = [f"{k} {x['calls'] / i['steps']:.2f}/step {1e6 * x['s'] / max(x['calls'], 1):.2f} us" for k, x in uf.items()]
        tm = i["exudyn_timers_s"]
        tparts = [f"{k} {100 * x / i['wall_s']:.0f}%" for k, x in tm.items() if x / i["wall_s"] >= 0.005]
        print(f"  {v}: " + "; ".join(parts))
        print(f"  {' ' * len(v)}  " + ", ".join(tparts))
    if a.json:
        Path(a.json).write_text(json.dumps({"best": best, "instrumented": inst}, indent=2))


def _median(xs):
    xs = [x for x in xs if x is not None]
    return statistics.median(xs) if xs else None


def verify(a):
    sys.path.insert(0, str(ROOT))
    from rotorlanding.ensemble import drop_offsets, ensemble_stats
    from rotorlanding.validate import CASES, ENSEMBLE, paper_dir

    global CACHE
    if a.cache:
        Path(a.cache).mkdir(parents=True, exist_ok=True)
        CACHE = a.cache
    keys = list(CASES) if a.cases == "all" else a.cases.split(",")
    ref_v = f"fixed:{a.reference}"
    variants = [f"auto:{x}" for x in a.auto.split(",")] + ([f"fixed:{a.rig}"] if a.rig else [])
    ctrl = json.loads(a.controller) if a.controller else None
    report = []
    print(f"{'case':26s} {'variant':20s} {'class':>16} {'Hz':>7} {'onset s':>8} {'peak N':>8} {'s/s':>6} "
          f"{'steps':>7} {'rej':>5} {'it/st':>5} load", flush=True)
    for key in keys:
        fname, sets = CASES[key]
        rows = {}
        for v in [ref_v] + variants:
            members, runs = [], []
            n = a.drops or ENSEMBLE[key]  # default: validate's ensemble (8 drops, 16 backward)
            for extra in drop_offsets(a.drops_of or n)[:n]:
                job = {"path": str(paper_dir() / fname), "variant": v, "sets": list(sets) + extra, "t_end": a.t_end}
                if ctrl and v.startswith("auto"):
                    job["controller"] = ctrl
                r = run_job(job)
                runs.append(r)
                members.append(dict(r["member"], peak_force_n=r["peak_force_n"]))
            ens = ensemble_stats(members)
            peak = _median([m["peak_force_n"] for m in members])
            row = {"class": ens["direction"], "fraction": ens["fraction"], "frequency_hz": ens.get("frequency_hz"),
                   "onset_s": ens.get("onset_s"), "peak_force_n": peak,
                   "s_per_s": _median([r["s_per_s"] for r in runs]),
                   "steps": _median([r["steps"] for r in runs]), "rejected": _median([r["rejected"] for r in runs]),
                   "it_per_step": _median([r["newton_iterations"] / r["steps"] for r in runs]),
                   "loads": [r["load_1min"] for r in runs], "members": [
                       {k: r[k] for k in ("whirl", "hz", "onset_s", "peak_force_n", "s_per_s", "steps", "rejected",
                                          "newton_iterations", "complete", "energy_error")} for r in runs]}
            rows[v] = row
            print(f"{key:26s} {v:20s} {row['class'] + ' ' + str(round(100 * row['fraction'])) + '%':>16} "
                  f"{row['frequency_hz'] or 0:7.2f} {row['onset_s'] or 0:8.3f} {row['peak_force_n']:8.0f} "
                  f"{row['s_per_s']:6.3f} {row['steps']:7.0f} {row['rejected']:5.0f} {row['it_per_step']:5.2f} "
                  f"{min(row['loads']):.1f}-{max(row['loads']):.1f}", flush=True)
        rf = rows[ref_v]
        diffs = {}
        for v in variants:
            au = rows[v]
            d = {"class_equal": au["class"] == rf["class"],
                 "frequency": None if not (au["frequency_hz"] and rf["frequency_hz"]) else au["frequency_hz"] / rf["frequency_hz"] - 1,
                 "onset_s": None if au["onset_s"] is None or rf["onset_s"] is None else au["onset_s"] - rf["onset_s"],
                 "peak_force": au["peak_force_n"] / rf["peak_force_n"] - 1,
                 "speedup_vs_reference": rf["s_per_s"] / au["s_per_s"]}
            # the acceptance rule of issue 21: class equal, frequency within 1 %, peak force within 5 %
            ok = d["class_equal"] and (d["frequency"] is None or abs(d["frequency"]) <= 0.01) and abs(d["peak_force"]) <= 0.05
            d["pass"] = ok
            diffs[v] = d
            print(f"{'':26s} {v + ' vs ref':20s} class {'equal' if d['class_equal'] else 'DIFFERENT':>9} "
                  f"freq {'-' if d['frequency'] is None else format(100 * d['frequency'], '+.2f') + ' %'} "
                  f"onset {'-' if d['onset_s'] is None else format(d['onset_s'], '+.3f') + ' s'} "
                  f"peak {100 * d['peak_force']:+.2f} % -> {'PASS' if ok else 'FAIL'}", flush=True)
        report.append({"case": key, "rows": rows, "diff": diffs})
    if a.json:
        Path(a.json).write_text(json.dumps({"drops": a.drops, "reference": ref_v, "variants": variants, "t_end": a.t_end,
                                            "controller": ctrl, "cases": report}, indent=2))


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--worker", help=argparse.SUPPRESS)
    sub = ap.add_subparsers(dest="cmd")
    p = sub.add_parser("profile")
    p.add_argument("scenario")
    p.add_argument("--t-end", type=float, default=None)
    p.add_argument("--variants", default="fixed:5e-5,probe:1e-5:2e-4,fixed:2e-4,auto:1e-7:4e-4")
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--json")
    v = sub.add_parser("verify")
    v.add_argument("--drops", type=int, default=0,
                   help="members per case (default 0: validate's ensembles, 8 drops, 16 for the backward landing)")
    v.add_argument("--drops-of", type=int, default=None,
                   help="circle size the members are taken from (default --drops; validate uses 8, 16 backward)")
    v.add_argument("--cases", default="all")
    v.add_argument("--reference", default="1.25e-5")
    v.add_argument("--auto", default="1e-7:4e-4", help="TOL:HMAX[,TOL:HMAX...]")
    v.add_argument("--rig", default="5e-5", help="also the rig's fixed step (the noise floor of the rule); '' for none")
    v.add_argument("--controller", default=None, help="JSON of StepController class attributes (trials)")
    v.add_argument("--cache", default=None, help="directory caching finished runs")
    v.add_argument("--t-end", type=float, default=None)
    v.add_argument("--json")
    a = ap.parse_args(argv)
    if a.worker:
        print(json.dumps(worker(json.loads(a.worker))))
        return 0
    if a.cmd == "profile":
        profile(a)
    elif a.cmd == "verify":
        verify(a)
    else:
        ap.print_help()
    return 0


if __name__ == "__main__":
    sys.exit(main())

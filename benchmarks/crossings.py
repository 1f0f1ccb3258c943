"""Cost of the Python-side crossings per step, and A/B of two code trees or solver settings (issue 21).

Why: a step of the implicit solver calls Python three ways (the connector's force, its Jacobian and
the pre-step); what each costs decides what to remove. Absolute times move with the shared
machine's load, so every comparison here runs its variants alternately in fresh processes, best of
``--repeat``, and reports ratios within the same run together with the 1-min load average.

Two modes:

``--instrument``: one run with timers around every Python user function (``build_exudyn(...,
instrument=)``): calls per step, microseconds per call (inside the function: argument conversion
on the C++ side is not included) and per step, share of the solve's wall time.

A/B (default): variant A and B, each a code tree (``--a-tree`` / ``--b-tree``, put first on
PYTHONPATH: e.g. /work/main against this checkout) and ``SolverSettings`` overrides (``--a-solver
jacobian_per_step=0``). Per variant and drop: wall s per simulated s, steps, Newton iterations,
Jacobians, the whirl class / frequency / onset and peak contact force of each drop, and a hash of the
whole trajectory (q, v at the output samples): equal hashes mean bit-identical results. ``--drops
N`` runs N drops from the 5 um circle (ensemble.drop_offsets; 0: the centred drop only).

usage: python benchmarks/crossings.py SCENARIO.toml [--instrument] [--a-tree DIR] [--b-tree DIR]
           [--a-solver k=v,...] [--b-solver k=v,...] [--set key=value ...] [--t-end S] [--repeat 3]
           [--drops N] [--json out.json]
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import subprocess
import sys
import time
from pathlib import Path
from statistics import median

ROOT = Path(__file__).resolve().parents[1]


def _solver_overrides(text: str) -> dict:
    out = {}
    for kv in filter(None, (text or "").split(",")):
        k, v = kv.split("=", 1)
        out[k.strip()] = json.loads(v) if v.strip()[0] in "0123456789-[{tfn" else v.strip()
    return out


def worker(job: dict) -> dict:
    load = os.getloadavg()[0]
    import numpy as np

    from rotorlanding import exudyn_model as em
    from rotorlanding.run import build_summary, simulate
    from rotorlanding.scenario import load_scenario

    over = job.get("solver", {})
    if over:
        orig = em.SolverSettings.from_spec.__func__

        def from_spec(cls, spec):
            s = orig(cls, spec)
            for k, v in over.items():
                setattr(s, k, v)
            return s

        em.SolverSettings.from_spec = classmethod(from_spec)
    sc = load_scenario(job["scenario"], job["sets"])
    if job.get("instrument"):
        from rotorlanding.landing import build_spec

        spec = build_spec(sc)
        acc = {}
        model = em.build_exudyn(spec, instrument=acc)
        ok, msg, st = em.solve(model, 0.0, sc.t_end, em.SolverSettings.from_spec(spec))
        return {"load": load, "stats": st, "simulated_s": sc.t_end,
                "functions": {k: {"s": v[0], "calls": v[1]} for k, v in acc.items()},
                "gyro_updates": getattr(model.pre_step, "updates", None)}
    spec, t, q, v, st = simulate(sc, progress=False)
    _, summ = build_summary(sc, spec, t, q, v, st)
    h = hashlib.sha256(np.ascontiguousarray(q).tobytes() + np.ascontiguousarray(v).tobytes()).hexdigest()[:16]
    w = summ["whirl"]
    return {"load": load, "wall_s": st["wall_s"], "simulated_s": float(t[-1]), "steps": st["steps"],
            "newton_iterations": st["newton_iterations"], "jacobians": st["jacobians"], "complete": st["complete"],
            "hash": h, "whirl": w.get("direction"), "whirl_hz": w.get("frequency_hz"), "onset_s": w.get("onset_s"),
            "peak_force_n": max(b["max_contact_force_n"] for b in summ["bearings"].values())}


def run_job(job: dict, tree: str | None) -> dict:
    path = [tree] if tree else [str(ROOT)]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(path + [os.environ.get("PYTHONPATH", "")]))
    r = subprocess.run([sys.executable, __file__, "--worker", json.dumps(job)], capture_output=True, text=True,
                       env=env, cwd=tree or ROOT)
    if r.returncode != 0:
        raise RuntimeError(f"worker failed: {job}\n{r.stderr[-2000:]}")
    return json.loads(r.stdout.strip().splitlines()[-1])


def instrument(a) -> dict:
    r = run_job({"scenario": a.scenario, "sets": a.sets, "instrument": True, "solver": _solver_overrides(a.a_solver)},
                a.a_tree)
    st = r["stats"]
    print(f"{a.scenario}: {r['simulated_s']} s simulated, {st['steps']} steps, {st['newton_iterations']} Newton "
          f"iterations, {st['jacobians']} Jacobians, solve {st['wall_s']:.3f} s (load {r['load']:.2f})")
    print(f"{'function':10s} {'calls/step':>10s} {'us/call':>8s} {'us/step':>8s} {'share':>6s}")
    total = 0.0
    for k, f in r["functions"].items():
        total += f["s"]
        print(f"{k:10s} {f['calls'] / st['steps']:10.2f} {1e6 * f['s'] / f['calls']:8.2f} "
              f"{1e6 * f['s'] / st['steps']:8.2f} {100 * f['s'] / st['wall_s']:5.1f}%")
    print(f"{'all':10s} {'':10s} {'':8s} {1e6 * total / st['steps']:8.2f} {100 * total / st['wall_s']:5.1f}%   "
          f"solve {1e6 * st['wall_s'] / st['steps']:.2f} us/step; gyro updates {r['gyro_updates']}")
    return r


def ab(a) -> dict:
    from rotorlanding.ensemble import drop_offsets

    offsets = drop_offsets(a.drops) if a.drops else [[]]
    variants = {"A": (a.a_tree, _solver_overrides(a.a_solver)), "B": (a.b_tree, _solver_overrides(a.b_solver))}
    runs = {k: [[] for _ in offsets] for k in variants}
    for rep in range(a.repeat):
        for d, off in enumerate(offsets):
            if rep > 0 and d > 0:
                continue  # timing repeats on the first drop only; every drop once for the results
            for name, (tree, over) in (variants.items() if rep % 2 == 0 else reversed(variants.items())):
                runs[name][d].append(run_job({"scenario": a.scenario, "sets": a.sets + off, "solver": over}, tree))
    report = {"scenario": a.scenario, "sets": a.sets, "repeat": a.repeat, "drops": len(offsets), "variants": {}}
    for name, (tree, over) in variants.items():
        first = runs[name][0]
        best = min(first, key=lambda r: r["wall_s"])
        members = [rs[0] for rs in runs[name]]
        rep = {"tree": tree or str(ROOT), "solver": over, "best_s_per_s": best["wall_s"] / best["simulated_s"],
               "all_s_per_s": [r["wall_s"] / r["simulated_s"] for r in first], "loads": [r["load"] for r in first],
               "steps": best["steps"], "newton_iterations": best["newton_iterations"], "jacobians": best["jacobians"],
               "members": members}
        report["variants"][name] = rep
        print(f"{name} [{rep['tree']} {over or ''}]: best {rep['best_s_per_s']:.3f} s/s of "
              f"{', '.join(f'{x:.3f}' for x in rep['all_s_per_s'])}; steps {best['steps']}, Newton "
              f"{best['newton_iterations']}, Jacobians {best['jacobians']}; load {', '.join(f'{x:.1f}' for x in rep['loads'])}")
    A, B = report["variants"]["A"], report["variants"]["B"]
    report["ratio_b_over_a"] = B["best_s_per_s"] / A["best_s_per_s"]
    same = [ma["hash"] == mb["hash"] for ma, mb in zip(A["members"], B["members"])]
    report["bit_identical"] = all(same)
    print(f"ratio B / A (best wall per simulated s): {report['ratio_b_over_a']:.3f}; bit-identical drops: "
          f"{sum(same)} of {len(same)}")
    for name in "AB":
        ms = report["variants"][name]["members"]
        cls = [m["whirl"] for m in ms]
        f = [m["whirl_hz"] for m in ms if m["whirl_hz"]]
        pk = [m["peak_force_n"] for m in ms]
        on = [m["onset_s"] for m in ms if m["onset_s"] is not None]
        report["variants"][name]["medians"] = {"classes": cls, "whirl_hz": median(f) if f else None,
                                               "peak_force_n": median(pk), "onset_s": median(on) if on else None}
        print(f"  {name}: classes {cls}; median whirl {median(f) if f else None} Hz, peak force {median(pk):.1f} N, "
              f"onset {median(on) if on else None} s")
    ma, mb = A["medians"], B["medians"]
    if ma["whirl_hz"] and mb["whirl_hz"]:
        report["whirl_hz_change"] = mb["whirl_hz"] / ma["whirl_hz"] - 1
    report["peak_force_change"] = mb["peak_force_n"] / ma["peak_force_n"] - 1
    print(f"  B vs A: whirl frequency {100 * report.get('whirl_hz_change', float('nan')):+.3f} %, peak force "
          f"{100 * report['peak_force_change']:+.3f} %")
    return report


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenario", nargs="?")
    ap.add_argument("--worker", help=argparse.SUPPRESS)
    ap.add_argument("--instrument", action="store_true")
    ap.add_argument("--a-tree")
    ap.add_argument("--b-tree")
    ap.add_argument("--a-solver", default="")
    ap.add_argument("--b-solver", default="")
    ap.add_argument("--set", dest="sets", action="append", default=[])
    ap.add_argument("--t-end", type=float)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--drops", type=int, default=0)
    ap.add_argument("--json")
    a = ap.parse_args(argv)
    if a.worker:
        print(json.dumps(worker(json.loads(a.worker))))
        return 0
    if a.scenario is None:
        ap.error("give a scenario")
    a.scenario = str(Path(a.scenario).resolve())
    if a.t_end:
        a.sets.append(f"operating.t_end={a.t_end}")
    t0 = time.perf_counter()
    report = instrument(a) if a.instrument else ab(a)
    report["elapsed_s"] = time.perf_counter() - t0
    if a.json:
        from rotorlanding.safeio import atomic_write_text

        atomic_write_text(Path(a.json), json.dumps(report, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())

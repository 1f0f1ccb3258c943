"""Ensemble throughput: drops per minute of an N-drop landing ensemble, two code trees side by side.

Why (issue 21): validate, calibrate and the whirl studies run ensembles of drops (the same landing
from N points of a 5 um circle); what counts there is drops per minute of the whole ensemble on
the worker pool (solve, post-processing, results.h5 and summary.json of every member), not the
solver alone. Each run is a fresh process that imports the code of its tree (``--a-tree`` /
``--b-tree`` first on PYTHONPATH, e.g. /work/main against this checkout), then runs the ensemble
with ``rotorlanding.runner.run_all`` on ``--workers`` forked workers, each member through
``run.run_scenario`` into a temporary folder (as ``validate`` does). The two trees alternate,
best of ``--repeat``; reported per run: the 1-min load average at its start, the ensemble's wall
time (first job submitted to last result), the whole process's, drops per minute, and the
members' whirl classes, frequencies and peak forces (equal between the trees when the change is
bit-identical).

usage: python benchmarks/ensemble_throughput.py [SCENARIO.toml] [--drops 8] [--workers 2] [--repeat 3]
           [--a-tree DIR] [--b-tree DIR] [--t-end S] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DEFAULT = ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml"


def _member(job):
    import tempfile

    from rotorlanding.run import run_scenario
    from rotorlanding.runner import reduction_cache
    from rotorlanding.scenario import load_scenario

    scenario, sets = job
    sc = load_scenario(scenario, sets)
    with tempfile.TemporaryDirectory() as d:
        try:
            s = run_scenario(sc, Path(d), progress=False, plots=False, reduction=reduction_cache())
        except TypeError:  # a tree whose run_scenario has no reduction argument
            s = run_scenario(sc, Path(d), progress=False, plots=False)
    w = s["whirl"]
    return {"whirl": w.get("direction"), "whirl_hz": w.get("frequency_hz"),
            "peak_force_n": max(b["max_contact_force_n"] for b in s["bearings"].values()),
            "solve_s": s["performance"]["wall_s"]}


def child(job: dict) -> dict:
    t0 = time.perf_counter()
    load = os.getloadavg()[0]
    from rotorlanding.ensemble import drop_offsets
    from rotorlanding.runner import run_all

    sets = [f"operating.t_end={job['t_end']}"] if job.get("t_end") else []
    jobs = [(job["scenario"], sets + off) for off in drop_offsets(job["drops"])]
    t1 = time.perf_counter()
    kw = {}
    if job.get("warm"):
        import functools

        from rotorlanding.runner import warm_model

        kw["warm"] = functools.partial(warm_model, job["scenario"], sets)
    members = run_all(_member, jobs, job["workers"], failures="raise", blas_threads=None, **kw)
    t2 = time.perf_counter()
    return {"load": load, "ensemble_s": t2 - t1, "process_s": t2 - t0, "members": members}


def run_child(job: dict, tree: str | None) -> dict:
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([tree or str(ROOT), os.environ.get("PYTHONPATH", "")]))
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, __file__, "--child", json.dumps(job)], capture_output=True, text=True,
                       env=env, cwd=tree or ROOT)
    if r.returncode != 0:
        raise RuntimeError(r.stderr[-2000:])
    out = json.loads(r.stdout.strip().splitlines()[-1])
    out["process_s"] = time.perf_counter() - t0  # interpreter start and imports included
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenario", nargs="?", default=str(DEFAULT))
    ap.add_argument("--child", help=argparse.SUPPRESS)
    ap.add_argument("--drops", type=int, default=8)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--a-tree")
    ap.add_argument("--b-tree")
    ap.add_argument("--t-end", type=float)
    ap.add_argument("--b-warm", action="store_true", help="B warms the model in the parent before forking (runner.warm_model)")
    ap.add_argument("--json")
    a = ap.parse_args(argv)
    if a.child:
        print(json.dumps(child(json.loads(a.child))))
        return 0
    job = {"scenario": str(Path(a.scenario).resolve()), "drops": a.drops, "workers": a.workers, "t_end": a.t_end}
    runs = {"A": [], "B": []}
    trees = {"A": a.a_tree, "B": a.b_tree}
    for rep in range(a.repeat):
        for name in ("A", "B") if rep % 2 == 0 else ("B", "A"):
            runs[name].append(run_child(dict(job, warm=a.b_warm and name == "B"), trees[name]))
    report = {"scenario": job["scenario"], "drops": a.drops, "workers": a.workers, "repeat": a.repeat, "variants": {}}
    for name, rs in runs.items():
        best = min(rs, key=lambda r: r["ensemble_s"])
        v = {"tree": trees[name] or str(ROOT), "best_ensemble_s": best["ensemble_s"],
             "drops_per_minute": 60.0 * a.drops / best["ensemble_s"],
             "ensemble_s_all": [r["ensemble_s"] for r in rs], "process_s_all": [r["process_s"] for r in rs],
             "loads": [r["load"] for r in rs], "members": best["members"]}
        report["variants"][name] = v
        print(f"{name} [{v['tree']}]: best {v['best_ensemble_s']:.2f} s for {a.drops} drops = "
              f"{v['drops_per_minute']:.1f} drops/min (ensemble s {', '.join(f'{x:.2f}' for x in v['ensemble_s_all'])}; "
              f"process s {', '.join(f'{x:.2f}' for x in v['process_s_all'])}; load "
              f"{', '.join(f'{x:.1f}' for x in v['loads'])})")
        print(f"   classes {[m['whirl'] for m in v['members']]}, peak force "
              f"{[round(m['peak_force_n'], 1) for m in v['members']]}")
    A, B = report["variants"]["A"], report["variants"]["B"]
    report["throughput_b_over_a"] = B["drops_per_minute"] / A["drops_per_minute"]
    report["same_members"] = [(m["whirl"], m["whirl_hz"], m["peak_force_n"]) for m in A["members"]] == \
        [(m["whirl"], m["whirl_hz"], m["peak_force_n"]) for m in B["members"]]
    print(f"throughput B / A: {report['throughput_b_over_a']:.3f}; members equal: {report['same_members']}")
    if a.json:
        from rotorlanding.safeio import atomic_write_text

        atomic_write_text(Path(a.json), json.dumps(report, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())

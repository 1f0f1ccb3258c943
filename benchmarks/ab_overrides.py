"""A/B speed of one scenario under two sets of --set overrides, side by side in one run.

Why: a change of a parameter (a regularisation velocity, a stiffness) can move the solver's cost;
absolute wall times move with the machine and its load, so the two variants are run alternately
in fresh processes, best of ``--repeat``, and compared as a ratio within the same run.

usage: python benchmarks/ab_overrides.py SCENARIO.toml --a "key=v key=v" --b "key=v" [--t-end S] [--repeat 3]

Prints per variant: best wall s per simulated s, Exudyn steps, Newton iterations, and the 1-min
load average at each run; then the ratio B / A.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _worker(scenario: str, sets: list[str], t_end: float | None) -> dict:
    from rotorlanding.run import run_scenario
    from rotorlanding.scenario import load_scenario

    sc = load_scenario(scenario, sets + ([f"operating.t_end={t_end}"] if t_end else []))
    with tempfile.TemporaryDirectory() as d:
        s = run_scenario(sc, Path(d), progress=False, plots=False)
    p = s.get("performance", {})
    return {"wall_s": p.get("wall_s"), "simulated_s": sc.t_end, "steps": p.get("steps"),
            "newton_iterations": p.get("newton_iterations")}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenario")
    ap.add_argument("--a", default="", help="overrides of variant A, space separated")
    ap.add_argument("--b", default="", help="overrides of variant B, space separated")
    ap.add_argument("--t-end", type=float, default=None)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--worker", nargs=argparse.REMAINDER, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker is not None:
        print(json.dumps(_worker(args.scenario, args.worker, args.t_end)))
        return 0
    runs = {"A": [], "B": []}
    for _ in range(args.repeat):
        for name, sets in (("A", args.a.split()), ("B", args.b.split())):
            load = os.getloadavg()[0]
            cmd = [sys.executable, __file__, args.scenario] + (["--t-end", str(args.t_end)] if args.t_end else []) \
                + ["--worker", *sets]
            out = subprocess.run(cmd, capture_output=True, text=True, check=True, cwd=ROOT)
            r = json.loads(out.stdout.strip().splitlines()[-1])
            r["load"] = load
            runs[name].append(r)
    best = {}
    for name, rs in runs.items():
        b = min(rs, key=lambda r: r["wall_s"])
        best[name] = b["wall_s"] / b["simulated_s"]
        sets = args.a if name == "A" else args.b
        each = ", ".join(f"{r['wall_s'] / r['simulated_s']:.3f}" for r in rs)
        loads = ", ".join(f"{r['load']:.1f}" for r in rs)
        print(f"{name} [{sets or 'scenario as is'}]: best {best[name]:.3f} s/s of {each}; steps {b['steps']}, "
              f"Newton iterations {b['newton_iterations']}; load {loads}")
    print(f"ratio B / A: {best['B'] / best['A']:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

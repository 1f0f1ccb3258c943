"""Benchmark: wall seconds per simulated second of full-model landings (run on demand).

Runs each case for --t-end simulated seconds (default 0.5) with the scenario's own solver
settings, best of --repeat runs, and prints a table (and JSON with --json): wall s per simulated
s, steps, Newton iterations per step, Jacobian evaluations.

With --lsoda S the same equations are also integrated by scipy's LSODA (the independent
reference right-hand side, rtol 1e-6) for S simulated seconds, and the ratio of wall seconds per
simulated second is printed side by side.

usage: python benchmarks/landing_speed.py [--t-end 0.5] [--repeat 2] [--lsoda 0.05] [--json bench.json]
"""

from __future__ import annotations

import argparse
import json
import platform
import sys
from pathlib import Path

import rotorlanding
from rotorlanding.run import simulate
from rotorlanding.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[1]
CASES = {
    "radial landing 7000 rpm (mu_rad 0.15)": (ROOT / "scenarios" / "landing_7000rpm.toml", []),
    "combined landing 7000 rpm (4 kN thrust, axial rub)": (
        ROOT / "scenarios" / "landing_7000rpm.toml", ["axial.f_thrust=4000.0", "amb.drop_axial=true"]),
}


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--t-end", type=float, default=0.5)
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--json")
    ap.add_argument("--lsoda", type=float, default=0.0, help="simulated seconds for the LSODA comparison (0: skip)")
    a = ap.parse_args(argv)
    rows = []
    for name, (path, sets) in CASES.items():
        best = None
        for _ in range(a.repeat):
            sc = load_scenario(path, sets + [f"operating.t_end={a.t_end}"])
            spec, t, q, v, info = simulate(sc, progress=False)
            if best is None or info["wall_s"] < best["wall_s"]:
                best = dict(info, step_s=sc.solver.step, n_coordinates=spec.n)
        lsoda = None
        if a.lsoda > 0:
            import time

            from rotorlanding.landing import build_spec
            from rotorlanding.reference import simulate_reference

            spec_l = build_spec(load_scenario(path, sets + [f"operating.t_end={a.lsoda}"]))
            w0 = time.perf_counter()
            simulate_reference(spec_l, a.lsoda, rtol=1e-6, atol=1e-9)
            lsoda = (time.perf_counter() - w0) / a.lsoda
        rows.append({"case": name, "simulated_s": a.t_end, "wall_s": best["wall_s"],
                     "lsoda_wall_s_per_simulated_s": lsoda,
                     "wall_s_per_simulated_s": best["wall_s"] / a.t_end, "step_s": best["step_s"],
                     "steps": best["steps"], "newton_iterations_per_step": best["newton_iterations"] / best["steps"],
                     "jacobians": best["jacobians"], "coordinates": best["n_coordinates"],
                     "complete": best["complete"]})
    print(f"rotorlanding {rotorlanding.__version__}, Python {platform.python_version()}, best of {a.repeat}")
    print(f"{'case':52s} {'s/s':>6} {'step':>8} {'steps':>7} {'it/step':>7} {'jac':>6} {'LSODA s/s':>9} {'ratio':>6}")
    for r in rows:
        ls = r["lsoda_wall_s_per_simulated_s"]
        extra = f" {ls:9.1f} {ls / r['wall_s_per_simulated_s']:6.1f}" if ls else ""
        print(f"{r['case']:52s} {r['wall_s_per_simulated_s']:6.2f} {r['step_s']:8.1e} {r['steps']:7d} "
              f"{r['newton_iterations_per_step']:7.2f} {r['jacobians']:6d}{extra}")
    if a.json:
        Path(a.json).write_text(json.dumps(rows, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())

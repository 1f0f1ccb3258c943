"""Benchmark: speed-up of `rotorlanding sweep` with 2 workers over 1 (run on demand).

Runs the same grid of 16 landings (speed x radial friction, ``--t-end`` simulated seconds each)
with 1 and with 2 local workers, each in a fresh Python process (so neither run inherits the
other's imports or loaded kernels), alternating the order between repeats. For every run it
reports the 1-minute load average at its start, the wall time of ``run_sweep`` (from the call
to the written table and whirl map), the wall time of the whole process (interpreter start and
imports included), and the mean per-case wall time (``wall_s`` column of sweep.csv: the worker's
time for one case); then the ratio of the 1-worker to the 2-worker wall. Both runs must give
identical summaries (checked).

The machine has 2 cores: run it when the load average is low (the ratio is meaningless when
other processes compete for the cores; the load at the start of each run is printed with it).

Measured on the quiet 2-core machine, 16 cases (2026-11-23, after whirl.py stopped importing
scipy.signal, ~0.6 s less serial start):
  0.5 s cases (0.58 s wall each): sweep 1.84x, 1.75x, 1.75x (parallel phase 1.85-1.94x);
  1.0 s cases (1.03 s wall each): sweep 1.80x, 1.95x, 1.92x (parallel phase 1.86-2.01x,
    whole process 1.77-1.91x).
The serial part (~0.65 s: parent imports, kernel load, table and whirl map) and a case running
~5 % slower when both cores are busy keep short-case sweeps near 1.8x.

usage: python benchmarks/sweep_speedup.py [--t-end 0.5] [--repeats 1] [--json out.json]
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SPEEDS = [3000.0, 5000.0, 7000.0, 10000.0]
MU_RAD = [0.1, 0.15, 0.2, 0.3]


def child(sweep_file: str, out: str, workers: int) -> None:
    """One sweep in this (fresh) process; prints its timings as JSON on the last line."""
    t0 = time.perf_counter()
    from rotorlanding import sweep_run

    t1 = time.perf_counter()
    phase = {}
    run_local = sweep_run._run_local

    def timed_run_local(*args, **kw):  # the parallel phase: first case submitted to last result
        w = time.perf_counter()
        try:
            return run_local(*args, **kw)
        finally:
            phase["cases_s"] = time.perf_counter() - w

    sweep_run._run_local = timed_run_local
    rows = sweep_run.run_sweep(sweep_file, out, workers=workers)
    t2 = time.perf_counter()
    assert len(rows) == 16 and all(r["status"] == "ok" for r in rows), rows
    ru_self, ru_kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    print(json.dumps({"import_s": t1 - t0, "sweep_s": t2 - t1, "cases_s": phase["cases_s"], "cpu_parent_s": ru_self.ru_utime + ru_self.ru_stime,
                      "cpu_workers_s": ru_kids.ru_utime + ru_kids.ru_stime}))


def one_run(sweep_file: Path, out: Path, workers: int) -> dict:
    load = os.getloadavg()
    w0 = time.perf_counter()
    p = subprocess.run([sys.executable, __file__, "--child", str(sweep_file), str(out), str(workers)],
                       capture_output=True, text=True, env={**os.environ, "PYTHONPATH": str(ROOT)})
    wall = time.perf_counter() - w0
    if p.returncode:
        raise SystemExit(f"sweep with {workers} workers failed:\n{p.stderr}")
    res = json.loads(p.stdout.strip().splitlines()[-1])
    with open(out / "sweep.csv") as fh:
        rows = list(csv.DictReader(fh))
    case_walls = [float(r["wall_s"]) for r in rows]
    return {"workers": workers, "load_1min": load[0], "load_5min": load[1], "process_s": wall,
            "sweep_s": res["sweep_s"], "cases_s": res["cases_s"], "import_s": res["import_s"], "cpu_parent_s": res["cpu_parent_s"],
            "cpu_workers_s": res["cpu_workers_s"], "case_mean_s": sum(case_walls) / len(case_walls),
            "case_sum_s": sum(case_walls), "rows": [{k: v for k, v in r.items() if k != "wall_s"} for r in rows]}


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--t-end", type=float, default=0.5, help="simulated seconds per case (default 0.5)")
    ap.add_argument("--repeats", type=int, default=1, help="pairs of runs (order alternates)")
    ap.add_argument("--json", default=None, help="also write the results to this JSON file")
    ap.add_argument("--child", nargs=3, metavar=("SWEEP", "OUT", "WORKERS"), help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    if a.child:
        child(a.child[0], a.child[1], int(a.child[2]))
        return 0
    print(f"16 cases of {a.t_end} s simulated (speed {SPEEDS} rpm x mu_rad {MU_RAD}), {os.cpu_count()} CPUs; "
          f"load average at start {os.getloadavg()[0]:.2f}")
    pairs = []
    with tempfile.TemporaryDirectory() as tmp:
        f = Path(tmp) / "sweep.toml"
        f.write_text(f'scenario = "{ROOT / "scenarios" / "landing_7000rpm.toml"}"\nmode = "grid"\n[fixed]\n'
                     f'"operating.t_end" = {a.t_end}\n[grid]\n"operating.speed_rpm" = {SPEEDS}\n'
                     f'"contact.mu_rad" = {MU_RAD}\n')
        for rep in range(a.repeats):
            runs = {}
            for workers in ((1, 2) if rep % 2 == 0 else (2, 1)):
                runs[workers] = one_run(f, Path(tmp) / f"r{rep}w{workers}", workers)
            if runs[1].pop("rows") != runs[2].pop("rows"):
                raise SystemExit("summaries differ between 1 and 2 workers")
            pairs.append({"ratio_sweep": runs[1]["sweep_s"] / runs[2]["sweep_s"],
                          "ratio_cases": runs[1]["cases_s"] / runs[2]["cases_s"],
                          "ratio_process": runs[1]["process_s"] / runs[2]["process_s"], "runs": runs})
    print(f"{'run':>4} {'workers':>7} {'load1':>6} {'sweep s':>8} {'cases s':>8} {'process s':>9} "
          f"{'case mean s':>11} {'cpu parent s':>12} {'cpu workers s':>13} {'ratio sweep':>11} {'ratio cases':>11} "
          f"{'ratio process':>13}")
    for k, p in enumerate(pairs):
        for w in (1, 2):
            r = p["runs"][w]
            ratio = (f"{p['ratio_sweep']:11.2f} {p['ratio_cases']:11.2f} {p['ratio_process']:13.2f}" if w == 2 else "")
            print(f"{k:>4} {w:>7} {r['load_1min']:6.2f} {r['sweep_s']:8.2f} {r['cases_s']:8.2f} {r['process_s']:9.2f} "
                  f"{r['case_mean_s']:11.3f} {r['cpu_parent_s']:12.2f} {r['cpu_workers_s']:13.2f} {ratio}")
    print("sweep s: run_sweep call (after `import rotorlanding.sweep_run`); cases s: its parallel phase, first case "
          "submitted to last result (after the parent's imports and kernel warm-up); process s: the whole python "
          "process; case mean s: one case in its worker; cpu: user+sys of the parent and of its workers")
    print("identical summaries with 1 and 2 workers: yes")
    if a.json:
        Path(a.json).write_text(json.dumps({"t_end": a.t_end, "cases": 16, "pairs": pairs}, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Benchmark: speed-up of `rotorlanding sweep` with 2 workers over 1 (run on demand).

Runs the same grid of 16 short landings (speed x radial friction) with 1 and with 2 local
workers into fresh folders and prints the wall times and their ratio.

usage: python benchmarks/sweep_speedup.py [--t-end 0.15]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

from rotorlanding.sweep import run_sweep

ROOT = Path(__file__).resolve().parents[1]


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--t-end", type=float, default=0.15)
    a = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        f = Path(tmp) / "sweep.toml"
        f.write_text(f'scenario = "{ROOT / "scenarios" / "landing_7000rpm.toml"}"\nmode = "grid"\n[fixed]\n'
                     f'"operating.t_end" = {a.t_end}\n[grid]\n"operating.speed_rpm" = [3000.0, 5000.0, 7000.0, 10000.0]\n'
                     '"contact.mu_rad" = [0.1, 0.15, 0.2, 0.3]\n')
        walls = {}
        for workers in (1, 2):
            w0 = time.perf_counter()
            rows = run_sweep(f, Path(tmp) / f"w{workers}", workers=workers)
            walls[workers] = time.perf_counter() - w0
            assert len(rows) == 16 and all(r["status"] == "ok" for r in rows)
    print(f"16 cases of {a.t_end} s: 1 worker {walls[1]:.1f} s, 2 workers {walls[2]:.1f} s, "
          f"speed-up {walls[1] / walls[2]:.2f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())

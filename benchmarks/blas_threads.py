"""BLAS threads on the rotor's eigenproblems: the default thread count against one thread, side by side
in one run (alternating, best of N), with the machine's load. Why rotorlanding.blas pins one thread.

usage: python benchmarks/blas_threads.py [--repeat 5] [--rotor scenarios/rig_rotor.toml]"""
import argparse
import os
import time

import numpy as np
import scipy.linalg as sla

from rotorlanding.blas import limit_blas_threads
from rotorlanding.reduction import full_model
from rotorlanding.rotor import load_rotor
from rotorlanding.timoshenko import assemble


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--rotor", default="scenarios/rig_rotor.toml")
    a = ap.parse_args(argv)
    system = full_model(assemble(load_rotor(a.rotor))).with_supports()
    n = system.n
    omega = 7000 * np.pi / 30
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(system.M, system.K), -np.linalg.solve(system.M, system.C + omega * system.G)]])
    best = {"default": np.inf, "1": np.inf}
    for _ in range(a.repeat):
        for label in best:
            restore = limit_blas_threads(1) if label == "1" else (lambda: None)
            try:
                t = time.perf_counter()
                sla.eig(A)
                best[label] = min(best[label], time.perf_counter() - t)
            finally:
                restore()
    print(f"state-space eig {2 * n} x {2 * n}, best of {a.repeat}, load {os.getloadavg()[0]:.2f}, {os.cpu_count()} CPUs")
    print(f"  default BLAS threads: {best['default'] * 1e3:9.1f} ms")
    print(f"  one BLAS thread:      {best['1'] * 1e3:9.1f} ms   (default / one = {best['default'] / best['1']:.1f})")


if __name__ == "__main__":
    main()

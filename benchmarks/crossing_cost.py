"""Benchmark (issue 21): what one Python user-function crossing costs in Exudyn 1.13.6, on its own.

A linear ObjectGenericODE2 of n coordinates (dense, random SPD stiffness) plus a second node of m
coordinates (the size of the landing model's merged connector), solved over T at the rig's step
three ways: (1) the second node with its own linear object only; (2) plus a zero-mass connector
object on it whose forceUserFunction returns a stored zero vector (the cheapest possible law);
(3) plus a jacobianUserFunction returning a stored zero matrix. The dynamics are the same in all
three (the user force is zero), so (2) - (1) over the number of force calls is the cost of one
force crossing (C++ to Python and back, the list arguments built, the returned array converted).
Best of --repeat per variant.

usage: python benchmarks/crossing_cost.py [--n 45] [--m 19] [--repeat 3]
"""

from __future__ import annotations

import argparse
import time

import numpy as np


def build(n: int, m: int, force: bool, jacobian: bool, h: float = 5e-5, T: float = 0.2):
    import exudyn as exu
    from exudyn.itemInterface import NodeGenericODE2, ObjectGenericODE2

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    rng = np.random.default_rng(0)
    A = rng.normal(size=(n, n))
    K = 1e6 * (A @ A.T + n * np.eye(n))
    nd = mbs.AddNode(NodeGenericODE2(numberOfODE2Coordinates=n, referenceCoordinates=[0.0] * n,
                                     initialCoordinates=[1e-4] * n, initialCoordinates_t=[0.0] * n))
    mbs.AddObject(ObjectGenericODE2(nodeNumbers=[nd], massMatrix=np.eye(n), stiffnessMatrix=K, dampingMatrix=1e-4 * K))
    nd2 = mbs.AddNode(NodeGenericODE2(numberOfODE2Coordinates=m, referenceCoordinates=[0.0] * m,
                                      initialCoordinates=[0.0] * m, initialCoordinates_t=[0.0] * m))
    mbs.AddObject(ObjectGenericODE2(nodeNumbers=[nd2], massMatrix=np.eye(m), stiffnessMatrix=1e6 * np.eye(m),
                                    dampingMatrix=np.zeros((m, m))))
    calls = [0]
    if force:
        f, J = np.zeros(m), np.zeros((m, m))

        def fuf(mbs_, t, i, q, qt):
            calls[0] += 1
            return f

        extra = {}
        if jacobian:
            def juf(mbs_, t, i, q, qt, fq, fv):
                return J

            extra["jacobianUserFunction"] = juf
        z = np.zeros((m, m))
        mbs.AddObject(ObjectGenericODE2(nodeNumbers=[nd2], massMatrix=z, stiffnessMatrix=z, dampingMatrix=z,
                                        forceVector=[0.0] * m, forceUserFunction=fuf, **extra))
    mbs.Assemble()
    s = exu.SimulationSettings()
    s.timeIntegration.numberOfSteps = int(round(T / h))
    s.timeIntegration.endTime = T
    s.timeIntegration.verboseMode = 0
    s.solution.file.write = False
    s.solution.sensors.writePeriod = 1e9
    s.linearSolver.solverType = exu.LinearSolverType.EXUdense
    return mbs, s, calls


def run(n, m, force, jacobian, repeat):
    best = None
    for _ in range(repeat):
        mbs, s, calls = build(n, m, force, jacobian)
        t0 = time.perf_counter()
        mbs.SolveDynamic(s)
        wall = time.perf_counter() - t0
        it = mbs.sys["dynamicSolver"].it
        r = (wall, calls[0], it.newtonStepsCount, it.newtonJacobiCount, s.timeIntegration.numberOfSteps)
        best = r if best is None or wall < best[0] else best
    return best


def main(argv=None) -> int:
    import warnings

    warnings.simplefilter("ignore")
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=45)
    ap.add_argument("--m", type=int, default=19)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args(argv)
    rows = [("linear objects only", run(a.n, a.m, False, False, a.repeat)),
            ("+ Python force", run(a.n, a.m, True, False, a.repeat)),
            ("+ Python force + Jacobian", run(a.n, a.m, True, True, a.repeat))]
    for name, (wall, calls, it, jac, steps) in rows:
        print(f"{name:28s} wall {1e3 * wall:7.1f} ms  force calls {calls:6d}  Newton {it}  Jacobians {jac}  "
              f"steps {steps}  per step {1e6 * wall / steps:6.2f} us")
    base, wf = rows[0][1], rows[1][1]
    print(f"one force crossing: {1e6 * (wf[0] - base[0]) / wf[1]:.2f} us")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

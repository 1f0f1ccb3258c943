"""Probe (issue 21, step 3, not adopted): an error-controlled step through Exudyn's PostNewton hook.

Session 12: this probe's controller never acted. Exudyn 1.13.6 repeats a step only when the
returned error exceeds ``discontinuous.iterationTolerance`` and another discontinuous iteration is
allowed; here the error is 0, the tolerance 1e10 and ``maxIterations = 1``, so every step was
accepted as it stood and the run is the fixed ``HMAX`` step with Exudyn's halving after failed
Newton iterations ("rejects" counts the requests). Kept as the record of session 11; the working
controller is ``solver.step_control = "auto"`` (rotorlanding.exudyn_model.StepController,
benchmarks/auto_step.py, docs/performance.md 3b).

Exudyn 1.13.6's implicit solver accepts ``mbs.SetPostNewtonUserFunction(f)``: after each converged
step, ``f(mbs, t)`` returns ``[discontinuousError, recommendedStepSize]``; a recommended step > 0
(with ``timeIntegration.discontinuous.useRecommendedStepSize``) makes the solver repeat the step
at that size; the step grows back by ``adaptiveStepIncrease`` (2x) after
``adaptiveStepRecoverySteps`` easy steps, up to (t_end - t_start) / numberOfSteps. The controller
here: local error of the position ~ h^2/6 |a_end - a_start| per coordinate (the spin angle
excluded), step repeated at h * max(0.2, 0.9 e^(-1/3)) when max e / tol > 1, maximum step ``hmax``.

usage: python benchmarks/adaptive_step_probe.py SCENARIO.toml (fixedH | adaptive) T_END [TOL [HMAX [key=value ...]]]
prints one JSON line: wall s per simulated s, steps, rejected steps, Newton iterations, whirl class,
frequency and onset, peak contact force. Findings: docs/performance.md (issue 21).
"""
import json
import sys
import time

import exudyn as exu
import numpy as np

from rotorlanding.scenario import load_scenario
from rotorlanding.landing import build_spec
from rotorlanding import exudyn_model as em
from rotorlanding.run import build_summary


def probe_hook(mbs, spec, tol, count):
    """Session 11's PostNewton function: local position error h^2/6 |a_end - a_start| (spin angle
    excluded) over ``tol``; above 1 it recommends h max(0.2, 0.9 e^(-1/3)) and counts the request in
    ``count[0]`` (which Exudyn ignores under :func:`probe_settings`: the module docstring)."""
    sd = mbs.systemData
    SOS = exu.ConfigurationType.StartOfStep

    def post(mbs_, t):
        h = mbs_.sys["dynamicSolver"].it.currentStepSize
        err = (h * h / 6.0) * np.abs(sd.GetODE2Coordinates_tt() - sd.GetODE2Coordinates_tt(SOS))
        err[spec.i_theta] = 0.0
        e = err.max() / tol
        if e > 1.0 and h > 2e-6:
            count[0] += 1
            return [0.0, max(h * 0.2, h * 0.9 * e ** (-1.0 / 3.0), 1e-6)]
        return [0.0, -1.0]
    return post


def probe_settings(ss):
    """The probe's discontinuous-iteration settings (one iteration: the recommendation is ignored)."""
    ti = ss.timeIntegration
    ti.discontinuous.useRecommendedStepSize = True
    ti.discontinuous.iterationTolerance = 1e10
    ti.discontinuous.maxIterations = 1
    ti.adaptiveStepRecoverySteps = 5
    ti.minimumStepSize = 1e-7


def probe(path, mode, t_end, tol=1e-7, hmax=2e-4, extra=()) -> dict:
    """One landing of ``path`` at a fixed step (mode ``fixedH``) or with the controller (``adaptive``);
    returns the line the command prints."""
    sets = [f"operating.t_end={t_end}"] + list(extra)
    sc = load_scenario(path, sets)
    spec = build_spec(sc)
    m = em.build_exudyn(spec)
    st_ = em.SolverSettings.from_spec(spec)
    rejects = [0]
    if mode.startswith("fixed"):
        st_.step = float(mode[5:])
        st_.output_period = max(st_.output_period, st_.step)
    else:
        st_.step = hmax
        m.mbs.SetPostNewtonUserFunction(probe_hook(m.mbs, spec, tol, rejects))
    ss = st_.apply(exu, 0.0, sc.t_end)
    if not mode.startswith("fixed"):
        probe_settings(ss)
    exu.config.suppressWarnings = True
    w0 = time.perf_counter()
    res = exu.SolveDynamic(m.mbs, ss)
    wall = time.perf_counter() - w0
    it = m.mbs.sys['dynamicSolver'].it
    stats = {"wall_s": wall, "steps": int(it.currentStepIndex), "newton_iterations": int(it.newtonStepsCount), "jacobians": int(it.newtonJacobiCount), "complete": bool(res is not False), "message": "", "simulated_s": sc.t_end}
    t, q, v = em.collect(m)
    _, s = build_summary(sc, spec, t, q, v, stats)
    w = s["whirl"]
    return {"mode": mode, "tol": tol, "s_per_s": wall / sc.t_end, "steps": stats["steps"], "rejects": rejects[0],
            "it": stats["newton_iterations"], "whirl": w.get("direction"), "hz": w.get("frequency_hz"),
            "onset": w.get("onset_s"), "peak": max(b["max_contact_force_n"] for b in s["bearings"].values()),
            "energy_err": s.get("energy", {}).get("balance_error")}


def main(argv=None):
    a = sys.argv[1:] if argv is None else list(argv)
    if len(a) < 3:
        sys.exit(__doc__.split("usage: ")[1].split("\n")[0])
    print(json.dumps(probe(a[0], a[1], float(a[2]), float(a[3]) if len(a) > 3 else 1e-7,
                           float(a[4]) if len(a) > 4 else 2e-4, a[5:])))


if __name__ == "__main__":
    main()

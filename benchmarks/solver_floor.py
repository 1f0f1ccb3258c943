"""Benchmark (issue 21): the floor of a landing's wall time under Python user functions.

How fast could a landing be if every law cost nothing? The landing is solved once with every Python
user function (connector forces, Jacobians, the pre-step) recording what it returns (and, for the
pre-step, when it reset the rotor's gyroscopic damping matrix). The same model is then solved again
with each user function replaced by a *replay*: call k returns the k-th recorded result, the
pre-step repeats the recorded damping updates at the same calls. Exudyn's solver is deterministic,
so the replay takes the same path step for step (checked: the final state is bit-identical), with
the same Newton iterations, Jacobians and Python crossings, but each law's body reduced to a list
lookup. Its wall time is what the C++ solver and the crossings cost by themselves: no faster way of
computing the same laws (kernels, argument handling, post-processing) can take a landing below it
(the post-processing is not even in it); only fewer steps, Newton iterations or crossings can.

The scenario's fixed step (the rig's 5e-5 s, as `rotorlanding validate` lands), and with --auto the
error-controlled step (``solver.step_control = "auto"``): its controller (Exudyn's PostNewton hook)
is recorded too, each call's return value, the next step size it set and any damping update, and
replayed the same way. Per case and step: the normal solve and the replay, alternating, best of
--repeat, with the load; wall per simulated second for both, their ratio, the counts.

usage: python benchmarks/solver_floor.py [--cases all|i,j,...] [--repeat 3] [--t-end S] [--auto TOL:HMAX]
                                         [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

CASES = {
    "forward whirl 7000 rpm": "scenarios/paper/forward_whirl_landing.toml",
    "backward whirl, worn DE": "scenarios/paper/backward_whirl_landing.toml",
    "no whirl": "scenarios/paper/no_whirl_landing.toml",
    "forward whirl 3000 rpm": "scenarios/paper/forward_whirl_3000rpm.toml",
    "forward whirl 10000 rpm": "scenarios/paper/forward_whirl_10000rpm.toml",
    "radial landing 7000 rpm": "scenarios/landing_7000rpm.toml",
}


class Tape:
    """One user function's recorded results, and its replay."""

    def __init__(self, f, key):
        self.f, self.key = f, key
        self.out: list = []
        self.updates: dict = {}  # pre-step: call index -> damping matrix set in that call

    def record(self, *args):
        if self.key == "prestep":
            n0 = self.f.updates
            r = self.f(*args)
            if self.f.updates != n0:
                self.updates[len(self.out)] = self.f.C + self.f.omega * self.f.G
            self.out.append(r)
            return r
        r = self.f(*args)
        a = np.array(r, dtype=float, copy=True)
        # a constant result (the rotor's zero Jacobian) is stored once
        if self.out and self.out[-1].shape == a.shape and np.array_equal(self.out[-1], a):
            a = self.out[-1]
        self.out.append(a)
        return r

    def replay_function(self):
        out, updates, obj = self.out, self.updates, getattr(self.f, "obj", None)
        k = [0]
        if self.key == "prestep":
            def g(mbs, t):
                i = k[0]
                k[0] = i + 1
                m = updates.get(i)
                if m is not None:
                    mbs.SetObjectParameter(obj, "dampingMatrix", m)
                return True
        else:
            def g(*args):
                i = k[0]
                k[0] = i + 1
                return out[i]
        return g


def _sets(t_end: float | None, auto: str | None) -> list[str]:
    sets = [f"operating.t_end={t_end!r}"] if t_end else []
    if auto:
        tol, hmax = (float(x) for x in auto.split(":"))
        sets += ["solver.step_control='auto'", f"solver.step_tolerance={tol!r}", f"solver.max_step={hmax!r}"]
    else:
        sets += ["solver.step_control='fixed'"]
    return sets


class ControllerTape:
    """The auto step's controller recorded (what each call returned, the step size it set, a
    damping update its pre-step work made) and its replay, as a stand-in StepController."""

    def __init__(self):
        self.log: list = []

    def recording(self):
        from rotorlanding import exudyn_model as em

        log, orig = self.log, em.StepController

        class Recording(orig):
            def __call__(self, mbs, t):
                pre = self.pre_step
                n0 = pre.updates if pre is not None else 0
                r = orig.__call__(self, mbs, t)
                upd = pre.C + pre.omega * pre.G if pre is not None and pre.updates != n0 else None
                h = self.solver.it.currentStepSize if r[1] == -1.0 else None
                log.append((list(r), h, upd))
                return r

        return Recording

    def replaying(self):
        from rotorlanding import exudyn_model as em

        log = self.log

        class Replaying:
            configure = staticmethod(em.StepController.configure)

            def __init__(self, spec, settings):
                self.k, self.accepted, self.rejected, self.pre_step, self.solver = 0, 0, 0, None, None

            def __call__(self, mbs, t):
                if self.solver is None:
                    self.solver = mbs.sys["dynamicSolver"]
                r, h, upd = log[self.k]
                self.k += 1
                if upd is not None:
                    mbs.SetObjectParameter(self.pre_step.obj, "dampingMatrix", upd)
                if h is not None:
                    self.solver.it.currentStepSize = h
                return r

        return Replaying


def _build(path: str, t_end: float | None, tapes: list | None, replay: list | None, auto: str | None = None):
    """The model, with its user functions recorded (tapes: list to fill) or replayed (replay: the
    tapes of a recorded run, in build order)."""
    from rotorlanding import exudyn_model as em
    from rotorlanding.landing import build_spec
    from rotorlanding.scenario import load_scenario

    sc = load_scenario(ROOT / path, _sets(t_end, auto))
    spec = build_spec(sc)
    original = em._timed
    order = [0]

    def hook(f, acc, key):
        if tapes is not None:
            tape = Tape(f, key)
            tapes.append(tape)
            return tape.record
        tape = replay[order[0]]
        order[0] += 1
        if tape.key != key:
            raise RuntimeError("the replay's user functions are not in the recorded order")
        return tape.replay_function()

    em._timed = hook
    try:
        model = em.build_exudyn(spec, instrument={})
    finally:
        em._timed = original
    return sc, model


def _solve(sc, model, controller=None):
    from rotorlanding import exudyn_model as em

    settings = em.SolverSettings.from_spec(model.spec)
    orig = em.StepController
    if controller is not None:
        em.StepController = controller
    try:
        ok, msg, stats = em.solve(model, 0.0, sc.t_end, settings)
    finally:
        em.StepController = orig
    if not ok:
        raise RuntimeError(msg)
    t, q, v = em.collect(model)
    return stats, q[-1].copy(), v[-1].copy()


def run_case(name: str, path: str, repeat: int, t_end: float | None, auto: str | None = None) -> dict:
    from rotorlanding import exudyn_model as em
    from rotorlanding.landing import build_spec

    tapes: list = []
    ctl = ControllerTape()
    sc, model = _build(path, t_end, tapes, None, auto)
    rec_stats, q_rec, v_rec = _solve(sc, model, ctl.recording() if auto else None)
    normal, floor, loads = [], [], []
    same = True
    for _ in range(repeat):
        # the normal model (no wrappers), then the replay, alternating
        spec = build_spec(sc)
        m = em.build_exudyn(spec)
        loads.append(os.getloadavg()[0])
        st, qn, vn = _solve(sc, m)
        normal.append(st["wall_s"])
        _, mr = _build(path, t_end, None, tapes, auto)
        loads.append(os.getloadavg()[0])
        st_r, qr, vr = _solve(sc, mr, ctl.replaying() if auto else None)
        floor.append(st_r["wall_s"])
        same &= bool(np.array_equal(qr, q_rec) and np.array_equal(vr, v_rec) and st_r["steps"] == rec_stats["steps"]
                     and st_r["newton_iterations"] == rec_stats["newton_iterations"]
                     and st_r["jacobians"] == rec_stats["jacobians"])
        same &= bool(np.array_equal(qn, q_rec))
    calls = {t.key: 0 for t in tapes}
    for t in tapes:
        calls[t.key] += len(t.out)
    T = float(sc.t_end)
    return {"case": name, "scenario": path, "step": f"auto {auto}" if auto else f"fixed {sc.solver.step:g}",
            "t_end_s": T,
            "steps": rec_stats["steps"], "newton_iterations": rec_stats["newton_iterations"],
            "jacobians": rec_stats["jacobians"], "calls": calls,
            "normal_s_per_s": min(normal) / T, "floor_s_per_s": min(floor) / T,
            "floor_share": min(floor) / min(normal), "floor_us_per_step": 1e6 * min(floor) / rec_stats["steps"],
            "bit_identical": same, "loads": loads, "normal_walls_s": normal, "floor_walls_s": floor}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="all")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--t-end", type=float, default=None)
    ap.add_argument("--auto", default=None, metavar="TOL:HMAX", help="also the auto step with these settings")
    ap.add_argument("--json")
    a = ap.parse_args(argv)
    sys.path.insert(0, str(ROOT))
    names = list(CASES)
    if a.cases != "all":
        names = [names[int(i)] for i in a.cases.split(",")]
    rows = []
    print(f"{'case':26s} {'step':>18s} {'t_end':>5s} {'steps':>6s} {'it/st':>5s} {'jac/st':>6s} {'normal s/s':>10s} "
          f"{'floor s/s':>9s} {'floor/normal':>12s} {'floor us/step':>13s} {'identical':>9s}  load", flush=True)
    for name, auto in [(n, v) for n in names for v in [None] + ([a.auto] if a.auto else [])]:
        r = run_case(name, CASES[name], a.repeat, a.t_end, auto)
        rows.append(r)
        print(f"{name:26s} {r['step']:>18s} {r['t_end_s']:5.2f} {r['steps']:6d} {r['newton_iterations'] / r['steps']:5.2f} "
              f"{r['jacobians'] / r['steps']:6.2f} {r['normal_s_per_s']:10.3f} {r['floor_s_per_s']:9.3f} "
              f"{r['floor_share']:12.2f} {r['floor_us_per_step']:13.1f} {str(r['bit_identical']):>9s}  "
              f"{min(r['loads']):.2f}-{max(r['loads']):.2f}", flush=True)
    if a.json:
        from rotorlanding.safeio import atomic_write_text

        atomic_write_text(a.json, json.dumps({"python": sys.version.split()[0], "cpus": os.cpu_count(),
                                              "cases": rows}, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

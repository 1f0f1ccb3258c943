"""Fault injection for the coast-down's checkpoints: kill a CLI run at a named point of the write
path (``ROTORLANDING_FAULT``, :func:`rotorlanding.safeio.fault`) or at a random moment (SIGKILL
from outside), resume it with ``--resume`` and compare with an uninterrupted run bit for bit.

Two modes. ``cli``: every run is ``python -m rotorlanding coastdown`` in a new process (what a
user does; used by benchmarks/fault_injection.py for many random kills and a tally). ``fork``:
the killed run is a fork of this process (no interpreter start and imports: ~1 s less per run)
and the resume runs in this process; used by tests/test_checkpoint.py to stay short. The
write path and the resume are the same code in both.
"""

from __future__ import annotations

import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SCEN = ROOT / "scenarios" / "coastdown_7000rpm.toml"
# 4 chunks of 0.01 s right after the drop (impacts, decimation at work): ~1 s of solving; the
# scenario's smooth_step (1e-3 s) exceeds chunk_s / 20 for such short chunks, and the 0.04 s never
# reach landing_s, so it is set to a step the short chunks admit (not used)
TINY = ["operating.t_end=0.04", "coastdown.chunk_s=0.01", "coastdown.decimate_every=10", "coastdown.smooth_step=2e-4"]

RANDOM_COMMIT_EVERY_S = 0.3  # s: runs killed at random commit every ~2 chunks (batches)

# every named point of the write path; the number is the chunk (0-based) whose commit is killed
# (None: the first time the point is passed)
POINTS = [
    ("create", None),        # new results.h5 written under its temporary name, not yet renamed
    ("summary-json", None),  # the `running` summary.json written to its temporary name
    ("copy", None),          # halfway through copying results.h5 to the spare
    ("synced", 1),           # spare brought up to date, nothing of the new chunk yet
    ("mid-append", 1),       # time_s appended, states and series not
    ("appended", 1),         # all rows appended, chunk row and commit record not (issue 16's kill)
    ("chunk-row", 1),        # chunk row appended, commit record not
    ("recorded", 1),         # commit record written, file not closed
    ("closed", 1),           # spare closed, not fsynced
    ("fsynced", 1),          # spare fsynced, not renamed
    ("linked", 2),           # results.h5 hard-linked to .prev, spare not renamed
    ("replaced", 2),         # spare renamed over results.h5, .prev not yet the new spare
    ("rotated", 3),          # .prev renamed to the spare, directory not fsynced
    ("repacked", None),      # end of run: compacted copy written, not renamed
]


def env(fault: str | None = None, commit_every_s: float | None = None) -> dict:
    """The environment of a CLI run: this tree on the path, a fault point, a commit interval."""
    e = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    for key in ("ROTORLANDING_FAULT", "ROTORLANDING_COMMIT_EVERY_S"):
        e.pop(key, None)
    if fault:
        e["ROTORLANDING_FAULT"] = fault
    if commit_every_s is not None:
        e["ROTORLANDING_COMMIT_EVERY_S"] = str(commit_every_s)
    return e


def args(out: Path, overrides=TINY, resume=False) -> list[str]:
    return ([sys.executable, "-m", "rotorlanding", "coastdown", str(SCEN), "--out", str(out), "--quiet",
             "--no-plots"] + [a for kv in overrides for a in ("--set", kv)] + (["--resume"] if resume else []))


def run(out: Path, overrides=TINY, *, fault=None, kill_after=None, resume=False,
        commit_every_s=None) -> tuple[int, str]:
    """(exit code, stderr); ``kill_after`` seconds: SIGKILL from outside if still running.
    A named fault point commits every chunk (``commit_every_s`` 0), so that the point is passed
    at the chunk it names; otherwise the default interval batches chunks."""
    if commit_every_s is None:
        # a named point: a commit per chunk, so the point is passed at the chunk it names; a
        # random kill: batches of a few chunks (the tiny run fits in one default interval)
        commit_every_s = 0 if fault else RANDOM_COMMIT_EVERY_S
    proc = subprocess.Popen(args(out, overrides, resume), env=env(fault, commit_every_s), stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    if kill_after is not None:
        try:
            proc.wait(timeout=kill_after)
        except subprocess.TimeoutExpired:
            proc.send_signal(signal.SIGKILL)
    _, err = proc.communicate(timeout=600)
    return proc.returncode, err


def run_fork(out: Path, overrides=TINY, *, fault=None, kill_after=None) -> tuple[int, str]:
    """Like :func:`run` (not resumed), in a fork of this process; (exit code or -signal, "")."""
    pid = os.fork()
    if pid == 0:  # the child: never return into the caller (a test runner)
        code = 1
        try:
            from rotorlanding.coastdown_run import load_coastdown, run_coastdown

            os.environ.pop("ROTORLANDING_FAULT", None)
            if fault:
                os.environ["ROTORLANDING_FAULT"] = fault
            sc, cd = load_coastdown(SCEN, overrides)
            run_coastdown(sc, cd, out, progress=False, plots=False,
                          commit_every_s=0 if fault else RANDOM_COMMIT_EVERY_S)
            code = 0
        finally:
            os._exit(code)
    deadline = None if kill_after is None else time.monotonic() + kill_after
    while True:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            break
        if deadline is not None and time.monotonic() >= deadline:
            os.kill(pid, signal.SIGKILL)
            _, status = os.waitpid(pid, 0)
            break
        time.sleep(0.005)
    return os.waitstatus_to_exitcode(status), ""


def resume_here(out: Path, overrides=TINY) -> tuple[int, str]:
    """``--resume`` in this process: (0, "") or (2, the one-line refusal)."""
    from rotorlanding.coastdown_run import load_coastdown, run_coastdown
    from rotorlanding.errors import InputError

    sc, cd = load_coastdown(SCEN, overrides)
    try:
        summary = run_coastdown(sc, cd, out, resume=True, progress=False, plots=False)
    except InputError as err:
        return 2, str(err) + "\n"
    return (0 if summary["complete"] else 1), ""


def snapshot(out: Path) -> dict:
    """Everything a resume must reproduce: every stored row, chunk column (but the wall time) and
    the restart state."""
    with h5py.File(out / "results.h5", "r") as h5:
        snap = {"time_s": h5["time_s"][()], "q": h5["states/q"][()], "v": h5["states/v"][()]}
        snap.update({"series/" + k: h5["series"][k][()] for k in h5["series"]})
        snap.update({"chunks/" + k: h5["coastdown/chunks"][k][()] for k in h5["coastdown/chunks"] if k != "wall_s"})
        r = h5["coastdown/restart"]
        snap.update({"restart/q": r["q"][()], "restart/v": r["v"][()], "restart/t_s": np.float64(r.attrs["t_s"]),
                     "complete": np.bool_(h5.attrs["complete"])})
    return snap


def same(a: dict, b: dict) -> bool:
    return a.keys() == b.keys() and all(np.array_equal(a[k], b[k], equal_nan=True) for k in a)


def _left(out: Path) -> str:
    """What a kill left: 'nothing' (before results.h5), 'chunks=N' (committed chunks), plus
    '+spare' when a spare (possibly half written) was beside it."""
    if not (out / "results.h5").exists():
        return "nothing"
    try:
        with h5py.File(out / "results.h5", "r") as h5:
            n = int(h5["coastdown/restart"].attrs["chunks"])
    except (OSError, KeyError) as exc:  # must not happen: results.h5 is only ever a whole commit
        return f"unreadable ({exc})"
    return f"chunks={n}" + ("+spare" if (out / ".results.h5.spare").exists() else "")


def _claims_complete(out: Path) -> bool:
    try:
        return bool(json.loads((out / "summary.json").read_text()).get("complete"))
    except (OSError, ValueError):
        return False


def trial(out: Path, ref: dict, *, fault=None, kill_after=None, overrides=TINY, mode="cli") -> dict:
    """Kill one run (at a point or after a delay), then resume it. Outcome:
    ``exact`` (resumed to the reference bit for bit), ``refused`` (one-line error, exit 2),
    ``wrong`` (a result that differs from the reference, or `complete` where it is not), ``error``."""
    rc1, err1 = (run if mode == "cli" else run_fork)(out, overrides, fault=fault, kill_after=kill_after)
    killed = rc1 == -signal.SIGKILL
    info = {"fault": fault, "kill_after": kill_after, "killed": killed, "rc_killed": rc1,
            "left": _left(out) if killed else None}
    if not killed and rc1 != 0:
        return info | {"outcome": "error", "detail": err1[-500:]}
    # never a wrong `complete`: a summary that says so must describe the reference result
    if _claims_complete(out) and not same(snapshot(out), ref):
        return info | {"outcome": "wrong", "detail": "complete: true after the kill, data differ"}
    rc2, err2 = run(out, overrides, resume=True) if mode == "cli" else resume_here(out, overrides)
    info["rc_resume"] = rc2
    lines = err2.strip().splitlines()
    if rc2 == 2 and len(lines) == 1 and "Traceback" not in err2:
        return info | {"outcome": "refused", "detail": lines[0]}
    if rc2 != 0:
        return info | {"outcome": "error", "detail": err2[-500:]}
    if not _claims_complete(out):
        return info | {"outcome": "wrong", "detail": "exit 0 without complete: true"}
    return info | {"outcome": "exact" if same(snapshot(out), ref) else "wrong"}


def reference(out: Path, overrides=TINY, mode="cli") -> tuple[dict, float]:
    """The uninterrupted run (snapshot, wall time of its process)."""
    t0 = time.perf_counter()
    rc, err = (run if mode == "cli" else run_fork)(out, overrides)
    if rc != 0:
        raise RuntimeError(f"reference run failed ({rc}): {err[-500:]}")
    return snapshot(out), time.perf_counter() - t0


def campaign(base: Path, n_random: int, points=POINTS, seed: int = 16, stream=None, workers: int = 1,
             mode: str = "cli") -> dict:
    """Every named point once, then ``n_random`` kills at random moments; the tally.
    ``workers``: trials run side by side (each is a separate process and folder; ``cli`` mode
    only: forking from several threads is unsafe)."""
    from concurrent.futures import ThreadPoolExecutor

    if mode != "cli":
        workers = 1
    ref, wall = reference(base / "ref", mode=mode)
    rng = random.Random(seed)
    plan = [(f"{p}:{k}" if k is not None else p, None) for p, k in points]
    # random moments over the run's whole wall time (interpreter start and imports included: the
    # first ~40 % of it kill before anything is written, which must resume as well)
    plan += [(None, rng.uniform(0.2 * wall, 0.85 * wall)) for _ in range(n_random)]

    def one(item):
        i, (fault, delay) = item
        res = trial(base / f"t{i:03d}", ref, fault=fault, kill_after=delay, mode=mode)
        if stream:
            stream.write(f"{i:3d} {fault or f'kill after {delay:.2f} s':24s} killed={res['killed']!s:5s} "
                         f"left={res['left']!s:16s} "
                         f"{res['outcome']}{(': ' + res['detail']) if res.get('detail') else ''}\n")
            stream.flush()
        return res

    with ThreadPoolExecutor(max_workers=max(1, workers)) as pool:
        results = list(pool.map(one, enumerate(plan)))
    tally = {k: sum(r["outcome"] == k for r in results) for k in ("exact", "refused", "wrong", "error")}
    tally["trials"] = len(results)
    tally["killed"] = sum(r["killed"] for r in results)
    tally["left_by_kills"] = {}
    for r in results:
        if r["killed"]:
            key = r["left"] if not str(r["left"]).startswith("chunks=") else r["left"].split("+")[0] + \
                ("+spare" if "+spare" in r["left"] else "")
            tally["left_by_kills"][key] = tally["left_by_kills"].get(key, 0) + 1
    tally["reference_wall_s"] = wall
    return {"tally": tally, "trials": results}

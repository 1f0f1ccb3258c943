"""Coast-down to rest: a landing run for minutes of machine time, streamed to ``results.h5``.

The machinery behind ``rotorlanding coastdown`` and the Python API's ``rotorlanding.coastdown(...)``
(:mod:`rotorlanding.api_studies`, which returns a ``Coastdown``); the module is named ``coastdown_run`` so
that the package attribute ``rotorlanding.coastdown`` is the function.

The run is cut into *chunks* of fixed simulated length ``[coastdown] chunk_s``. Every chunk is a
fresh Exudyn model (:func:`rotorlanding.exudyn_model.build_exudyn` with the chunk's start state)
solved from the chunk's start time to its end time; its samples are post-processed
(:func:`rotorlanding.postprocess.evaluate`), decimated where the motion is smooth and appended
to ``results.h5`` by a *commit* (below) every ``COMMIT_EVERY_S`` (2 s) of wall time, or every
chunk with ``commit_every_s = 0``. One chunk at full rate is held in memory, plus the decimated
rows of the chunks since the last commit (at most ``MAX_PENDING_CHUNKS``), so memory does not
grow with the run length.

Restart, exact by design
------------------------
Each chunk starts from the previous chunk's end state: q, v, the time, the number of finished
chunks and the last row of every cumulative series (dissipated / input energy), exactly the
values the commit stores in the restart record ``/coastdown/restart`` and the rows (float64
written and read back bit for bit); a resumed run reads them from the file. Nothing else carries
over from one chunk to the next: the model is rebuilt, so the tilt holder
of the axial face is recomputed from q, the gyroscopic damping C + Omega G is set from v by the
first pre-step, the AMB forces depend on time only, and the generalized-alpha solver starts
anew (initial accelerations from the equations of motion). Chunk boundaries are
``t_k = k * chunk_s`` (never accumulated). An uninterrupted run and a run killed and resumed
(``--resume``) therefore execute the same sequence of solves on bit-identical inputs and end in
the same final state. Rows beyond the committed row count (the partial chunk of a failed solve) are
dropped before the next chunk is appended.

Crash safety
------------
The file, its layout and the commit protocol (spare file, commit record with a sha256 hash chain,
fsync and ``os.replace``, the checks before ``--resume``) live in :mod:`rotorlanding.results`
("Crash safety: the commit protocol"); this module runs the chunks and hands each commit a
function that appends them (:func:`_chunk_writer`).

Decimation rule (documented in docs/scenario_file.md)
-----------------------------------------------------
Exudyn stores states every ``solver.output_period``. A sample is kept in ``results.h5`` if
(a) it lies in a *fast* phase: within ``decimate_every`` samples of an output interval in which
a bearing's contact normal force changed faster than ``fast_force_rate_n_s`` or a contact
opened or closed; or (b) its global sample index ``round(t / output_period)`` is a multiple of
``decimate_every``; or (c) it is the first or last sample of a chunk (the last one is the restart state). The fast
phases are found from the contact normal forces at the full rate (the radial contact law, compiled
over the samples: ``bearing_kernel.contact_normal_forces``); forces, powers and energies are then
evaluated on the kept samples
only and the cumulative energies integrated over them, which keeps post-processing at a small
fraction of the solve (the summary's energy balance error shows the cost of decimation). Whirl is
classified per chunk on the full-rate orbit. ``/time_s`` holds the actual times of the kept
samples (irregular by design).
"""

from __future__ import annotations

import json
import math
import os
import resource
import sys
import time
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np

from .config import Table, load_toml
from .errors import InputError
from .bearing_kernel import contact_normal_forces
from .mechanisms import carried_series, dissipation_entries, retuned_spec, rotor_force, series_units
from .postprocess import energy_summary, evaluate, uniform
from .results import (CUMULATIVE_PREFIXES, Checkpoint, Store, check_resumable, create_file, read_restart, repack,
                      verify_checkpoint)
from .safeio import WriteError, atomic_write_text, check_out_dir, fault, save_figure
from .scenario import Scenario, scenario_from_dict
from .thermal_feedback import first_runaway
from .thermal_states import file_summary as thermal_file_summary, format_lines as format_thermal
from .whirl import longest_whirl

FIELDS = ("stop_speed_rpm", "chunk_s", "decimate_every", "fast_force_rate_n_s", "landing_s", "smooth_step")


@dataclass(frozen=True)
class Coastdown:
    """The ``[coastdown]`` table."""

    stop_speed_rpm: float = 10.0        # rpm: the run ends after the chunk in which |rotor speed| <= this
    #                                     (or in which a bearing runs away: thermal_feedback.first_runaway)
    chunk_s: float = 0.1                # s: simulated length of one chunk (one Exudyn solve)
    decimate_every: int = 100           # -: in smooth phases keep every k-th output sample
    fast_force_rate_n_s: float = 2.0e5  # N/s: contact-force rate above which samples are kept at full rate
    landing_s: float = 0.0              # s: chunks starting before this use solver.step (impacts) ...
    smooth_step: float | None = None    # s: ... later chunks this step (None: solver.step throughout)


def coastdown_from_dict(data: dict | None, scenario: Scenario) -> Coastdown:
    """Validate the ``[coastdown]`` table against the (already validated) scenario."""
    t = Table({} if data is None else data, "coastdown")
    d = Coastdown()
    stop = t.number("stop_speed_rpm", d.stop_speed_rpm, positive=True)
    chunk = t.number("chunk_s", d.chunk_s, positive=True)
    k = t.integer("decimate_every", d.decimate_every, minimum=1)
    rate = t.number("fast_force_rate_n_s", d.fast_force_rate_n_s, positive=True)
    landing = t.number("landing_s", d.landing_s, nonnegative=True)
    smooth = t.number("smooth_step", scenario.solver.step, positive=True)
    t.finish()
    if scenario.solver.step_control != "fixed":
        # the chunks, checkpoints and smooth_step are laid out on fixed steps, and the auto step is
        # verified on the paper landings only (docs/performance.md, issue 21)
        raise InputError("solver.step_control", scenario.solver.step_control,
                         "coast-down runs need 'fixed' (use [coastdown] landing_s / smooth_step for a larger step later)")
    if stop >= scenario.speed_rpm:
        raise InputError("coastdown.stop_speed_rpm", stop,
                         f"must be below operating.speed_rpm ({scenario.speed_rpm:g} rpm)")
    sv = scenario.solver
    for name, period in (("solver.step", sv.step), ("solver.output_period", sv.output_period)):
        n = chunk / period
        if abs(n - round(n)) > 1e-6 * n:
            raise InputError("coastdown.chunk_s", chunk, f"must be a whole multiple of {name} ({period:g} s)")
    if chunk < 20 * sv.output_period or chunk > 10.0:
        raise InputError("coastdown.chunk_s", chunk, f"must lie in [20 x solver.output_period "
                         f"({20 * sv.output_period:g} s), 10 s] (chunk samples are held in memory)")
    if smooth < sv.step or smooth > chunk / 20:
        raise InputError("coastdown.smooth_step", smooth,
                         f"must lie in [solver.step ({sv.step:g} s), chunk_s / 20 ({chunk / 20:g} s)]")
    n = chunk / smooth
    if abs(n - round(n)) > 1e-6 * n:
        raise InputError("coastdown.chunk_s", chunk, f"must be a whole multiple of coastdown.smooth_step ({smooth:g} s)")
    if scenario.spin.drive != "coast":
        raise InputError("spin.drive", scenario.spin.drive, "a coast-down needs drive = 'coast' (no drive torque)")
    return Coastdown(stop, chunk, k, rate, landing, smooth)


def load_coastdown(path, overrides: list[str] | None = None) -> tuple[Scenario, Coastdown]:
    """Read a coast-down scenario file (a landing scenario plus an optional ``[coastdown]``
    table), apply ``--set key=value`` overrides, validate both parts."""
    from .scenario import apply_overrides

    path = Path(path)
    if path.suffix == ".h5":
        data = _stored_input(path)
    else:
        try:
            data = load_toml(path)
        except InputError as err:
            raise err.with_file(str(path)) from None
    apply_overrides(data, overrides, tables={"coastdown": FIELDS})
    cd_raw = data.pop("coastdown", None)
    scenario = scenario_from_dict(data, source=str(path))
    try:
        cd = coastdown_from_dict(cd_raw, scenario)
    except InputError as err:
        raise err.with_file(str(path)) from None
    return scenario, cd


def _stored_input(path: Path) -> dict:
    """The scenario (and [coastdown] table) stored in a results.h5, read behind the results guard
    (a damaged, foreign or text file is one line, exit 2)."""
    import h5py

    from .readers import read_results_guarded

    data = read_results_guarded(path, ("scenario",), field="file")["scenario"]
    try:
        with h5py.File(path, "r") as h5:
            if "coastdown_json" in h5:
                data["coastdown"] = json.loads(h5["coastdown_json"][()])
    except (OSError, RuntimeError, ValueError, KeyError) as exc:
        raise InputError("coastdown_json", "unreadable", f"damaged results file ({str(exc)[:120]})",
                         file=str(path)) from None
    return data


# --------------------------------------------------------------------------------------------
# decimation

def keep_mask(t: np.ndarray, forces: list[np.ndarray], cd: Coastdown, output_period: float) -> tuple:
    """Samples of one chunk to keep (see the module docstring); returns (mask, fast mask)."""
    n = len(t)
    fast_iv = np.zeros(max(n - 1, 0), bool)
    dt = np.maximum(np.diff(t), 1e-15)
    for f in forces:
        fast_iv |= np.abs(np.diff(f)) / dt > cd.fast_force_rate_n_s
        fast_iv |= (f[1:] > 0) != (f[:-1] > 0)
    fast = np.zeros(n, bool)
    k = cd.decimate_every
    idx = np.flatnonzero(fast_iv)
    if len(idx):
        # interval i joins samples i and i+1; dilate by k samples on each side
        marks = np.zeros(n + 1, int)
        np.add.at(marks, np.clip(idx - k, 0, n), 1)
        np.add.at(marks, np.clip(idx + 1 + k + 1, 0, n), -1)
        fast = np.cumsum(marks[:n]) > 0
    g = np.floor(t / output_period + 0.5).astype(np.int64)
    keep = fast | (g % k == 0)
    if n:
        keep[0] = keep[-1] = True
    return keep, fast


# --------------------------------------------------------------------------------------------
# the run

class Interrupted(Exception):
    """Raised by a test hook to simulate a kill between chunks."""


def _classify_whirl(spec, t, q, v, chunk_s):
    """The landing's whirl within one chunk (the DE journal's, else the bearing whose journal whirls
    first: ``whirl.landing_whirl_bearing``), from the full-rate samples (before decimation):
    (direction -1/0/1, frequency [Hz] or nan, index of that bearing in spec.bearings or -1 when
    none whirls)."""
    from .whirl import WhirlResult, landing_whirl_bearing, whirl_analysis

    whirls = {}
    for b in spec.bearings:
        try:
            tu, yu, zu, rpm = uniform(t, q[:, b.i_station], q[:, b.i_station + 1], v[:, spec.i_theta] * 30 / math.pi)
            window = min(0.05, chunk_s / 2)
            whirls[b.name] = whirl_analysis(tu, yu, zu, clearance=b.params.clearance,
                                            spin_hz=np.maximum(np.abs(rpm) / 60.0, 1e-6), window_s=window,
                                            min_duration_s=0.5 * (chunk_s - window)).to_dict()
        except (ValueError, InputError):
            whirls[b.name] = WhirlResult("none", None, None, 0.0).to_dict()
    name = landing_whirl_bearing(whirls)
    wr = whirls[name]
    d = {"none": 0, "forward": 1, "backward": -1}[wr["direction"]]
    # the bearing as an index (-1: no whirl): the chunk columns are numeric so that the commit's
    # hash chain reads back the stored bytes (a variable-length string would hash a pointer)
    return (d, (wr["frequency_hz"] if wr["frequency_hz"] is not None else float("nan")),
            spec.bearing_names.index(name) if d else -1)


def run_coastdown(scenario: Scenario, cd: Coastdown, out_dir, *, resume: bool = False, overwrite: bool = False,
                  progress=True, plots: bool = True, on_chunk=None, commit_every_s: float | None = None) -> dict:
    """Run (or resume) the chunked coast-down; returns the summary (also in summary.json).

    ``on_chunk(info)`` is called for each chunk once it is committed to the file (a test hook;
    raising there simulates an interruption). ``progress``: True/False or a stream.
    ``commit_every_s``: wall seconds between commits (None: ROTORLANDING_COMMIT_EVERY_S or
    COMMIT_EVERY_S; 0: every chunk)."""
    import h5py

    from .exudyn_model import SolverSettings
    from .landing import build_spec

    out = check_out_dir(out_dir)  # an existing file, /dev/null, an unwritable folder: exit 2 before any work
    path = out / "results.h5"
    spec = build_spec(scenario)
    settings = SolverSettings.from_spec(spec)
    stream = sys.stderr if progress is True else (progress or None)
    cd_json = json.dumps(asdict(cd))

    existing = path.is_file()
    notes = []
    if resume and not existing:
        # said, not silent: a user who meant another folder would otherwise wait for a whole new run.
        # Up front on the caller's progress stream, and in the returned summary for a quiet caller
        notes.append(f"--resume: {out} holds no coast-down to continue; a new one was started")
        if stream:
            stream.write(f"note: {notes[-1]}\n")
    if existing and resume:
        check_resumable(path, scenario, cd_json)
    elif existing and not overwrite:
        try:
            with h5py.File(path, "r") as h5:
                unfinished = h5.attrs.get("kind") == "coastdown" and not bool(h5.attrs.get("complete"))
                t_r = float(h5["coastdown/restart"].attrs["t_s"]) if unfinished else 0.0
        except (OSError, KeyError):
            unfinished, t_r = False, 0.0
        if unfinished:
            raise InputError("--out", str(out), f"holds an unfinished coast-down (t = {t_r:g} s): pass --resume to "
                             "continue it or --overwrite to start over")
    ckpt = Checkpoint(path)
    ckpt.discard_leftovers()
    try:
        if not (existing and resume):
            create_file(path, scenario, cd, spec, series_units(spec.bearing_names), spec.bearing_names)
        else:
            verify_checkpoint(path, spec, stream)
            if stream:
                stream.write(f"resuming {path} from t = {read_restart(path)['t_s']:g} s\n")
        # an earlier summary.json (perhaps `complete: true`) must not outlive the start of this run
        atomic_write_text(out / "summary.json", json.dumps(RUNNING_SUMMARY | {"scenario": scenario.name}, indent=2))
        summary = _chunks(path, ckpt, spec, scenario, cd, settings, stream, on_chunk, plots, commit_every_s)
        max_buffer = summary.pop("_max_buffer")
    except (OSError, WriteError) as exc:
        err = exc if isinstance(exc, WriteError) else WriteError(getattr(exc, "filename", None) or path, exc)
        raise WriteError(path, err.exc, _kept(path)) from None
    finally:
        ckpt.discard_leftovers()  # the spare doubles the disk use; a resume copies it anew
    summary["performance"]["max_buffer_samples_this_process"] = max_buffer
    if notes:
        summary["notes"] = notes
    try:
        atomic_write_text(out / "summary.json", json.dumps(summary, indent=2))
    except OSError as exc:
        raise WriteError(out / "summary.json", exc) from None
    return summary


def _kept(path: Path) -> str:
    """What a failed write left behind (results.h5 is never written in place)."""
    try:
        rs = read_restart(path)
    except Exception:  # noqa: BLE001 - only the message depends on it
        return "nothing was committed"
    return (f"the checkpoint at t = {float(rs['t_s']):g} s ({int(rs['chunks'])} chunks) is intact: "
            "continue with --resume once there is space")


RUNNING_SUMMARY = {"kind": "coastdown", "complete": False, "status": "running",
                   "message": "written when a coast-down starts and replaced when it ends: if no run is active, it "
                              "was interrupted (resume with --resume)"}


COMMIT_EVERY_S = 2.0  # s of wall time between commits (a kill repeats at most this much work)
MAX_PENDING_CHUNKS = 64  # ... or this many chunks (their decimated rows wait in memory)


def _commit_every_s(value: float | None) -> float:
    """The commit interval: ``value``, else ROTORLANDING_COMMIT_EVERY_S, else COMMIT_EVERY_S (0:
    every chunk is committed at once; the results are bitwise the same for any interval)."""
    if value is None:
        text = os.environ.get("ROTORLANDING_COMMIT_EVERY_S", "")
        try:
            value = float(text) if text else COMMIT_EVERY_S
        except ValueError:
            raise InputError("ROTORLANDING_COMMIT_EVERY_S", text, "must be a number of seconds >= 0") from None
    if not value >= 0:
        raise InputError("commit_every_s", value, "must be >= 0")
    return float(value)


def _chunk_writer(k, rows, row, rec, t_stop, t_reached, q_end, v_end, t1, fail_message):
    """A function writing chunk ``k`` (its rows, chunk row and commit record; or, for a failed
    solve, its rows beyond the commit and the stop) into an open Store. All values are fixed
    here, so writing is the same whenever the chunk is committed."""
    def write(store):
        store.append(*rows, chunk=k)
        fault("appended", k)  # rows appended, commit record not yet: the kill of issue 16
        store.h5.attrs["t_reached_s"] = t_reached
        r = store.r
        if row is None:
            # the partial chunk stays for inspection (beyond the committed rows); the restart
            # record stays at the last finished chunk (resuming would repeat the same failure)
            store.h5.attrs["message"] = fail_message
            r.attrs["stop_reason"] = "solver failed"
        else:
            store.append_chunk_row(row)
            if t_stop is not None:
                r.attrs["t_stop_s"] = t_stop
            fault("chunk-row", k)
            store.commit(k, q_end, v_end, t1, **rec)  # restart state, row counts, hash-chain link
        fault("recorded", k)  # the commit record written, the file not yet closed
    return write


def _chunks(path, ckpt, spec, scenario, cd, settings, stream, on_chunk, plots, commit_every_s=None) -> dict:
    """The chunk loop (each chunk committed through ``ckpt``), then :func:`finish`."""
    from .exudyn_model import build_exudyn, collect, solve

    t_end = scenario.t_end
    stop_rpm = cd.stop_speed_rpm
    max_buffer = 0
    wall_start = time.perf_counter()
    t_first = None
    last_print = -1e9
    # the files are open only while a commit is read or written: a kill during a solve (nearly
    # all of the wall time) finds nothing open; other programs can read results.h5 meanwhile.
    # Chunks are committed in batches (every commit_every_s of wall time; see the module
    # docstring): a commit's fixed cost (sync of the spare, flush, fsync, rename) is shared.
    # Wall time of a chunk runs from its start to its record; the time after (the commit of a
    # batch included) is carried into the next chunk's record
    carry_s = 0.0
    commit_every = _commit_every_s(commit_every_s)
    pending, pending_bytes, infos = [], 0, []
    last_commit = time.perf_counter()
    carried = carried_series(spec.bearing_names)
    with Store(path, "r") as store:
        rs = store.restart()  # the first chunk starts from what is committed in the file
        # a file begun before the per-chunk whirl bearing was stored resumes without that column
        # (every chunk row must fill the same columns; its verdict then names no whirl bearing)
        has_whirl_bearing = "coastdown/chunks/whirl_bearing" in store.chunk_paths
    while True:
        wall_chunk0 = time.perf_counter()
        k = int(rs["chunks"])
        t0 = float(rs["t_s"])
        if rs["stop_reason"]:
            break
        if t_first is None:
            t_first = t0
        t1 = min((k + 1) * cd.chunk_s, t_end)
        # the laws at the temperatures the chunk starts from (registry retune hooks: thermal feedback;
        # spec itself when none is active), frozen over the chunk
        spec_k = retuned_spec(spec, rs["carry"])
        model = build_exudyn(spec_k, rs["q"], rs["v"])
        # the step is a function of the chunk's start time only, so a resumed run repeats it
        s_k = settings
        if cd.smooth_step is not None and t0 >= cd.landing_s - 1e-12 and cd.smooth_step != settings.step:
            s_k = replace(settings, step=cd.smooth_step,
                          output_period=max(settings.output_period, cd.smooth_step))
        ok, msg, stats = solve(model, t0, t1, s_k)
        t, q, v = collect(model)
        qe, ve = final_state(model)
        del model
        if not ok:
            sel = t <= stats["t_reached"] + 1e-12
            t, q, v = t[sel], q[sel], v[sel]
        elif abs(t[-1] - t1) > 1e-9 * max(1.0, t1):
            t, q, v = np.append(t, t1), np.vstack([q, qe]), np.vstack([v, ve])
        else:
            t[-1], q[-1], v[-1] = t1, qe, ve
        max_buffer = max(max_buffer, len(t))
        keep, fast = keep_mask(t, contact_normal_forces(spec_k, q, v), cd, s_k.output_period)
        whirl = _classify_whirl(spec_k, t, q, v, t1 - t0) if ok and len(t) > 8 else (0, float("nan"), -1)
        t, q, v = t[keep], q[keep], v[keep]
        # on the kept samples only; cumulative from the chunk start, carried states (temperatures)
        # from the previous chunk's last row
        series = evaluate(spec_k, t, q, v, carry=rs["carry"] or None)
        for name, off in rs["offsets"].items():
            series[name] = series[name] + off
        speed_now = abs(v[-1, spec.i_theta]) * 30 / math.pi
        new = slice(1 if k > 0 else 0, None)  # a chunk's first sample is the previous chunk's last
        rows = (t[new], q[new], v[new], {name: arr[new] for name, arr in series.items()})
        if ok:
            row = {"t_start_s": t0, "t_end_s": t1, "rotor_speed_rpm": speed_now, "wall_s": stats["wall_s"],
                   "steps": stats["steps"], "newton_iterations": stats["newton_iterations"],
                   "jacobians": stats["jacobians"], "samples_kept": len(t) - (1 if k > 0 else 0),
                   "samples_fast": int(fast.sum()), "whirl_direction": whirl[0], "whirl_frequency_hz": whirl[1]}
            if has_whirl_bearing:
                row["whirl_bearing"] = whirl[2]
            for b in spec.bearing_names:
                row[f"{b}_max_contact_force_n"] = float(np.max(np.hypot(*rotor_force(series, b))))
            reason, t_stop = "", None
            runaway = first_runaway(spec_k, t, series)
            if speed_now <= stop_rpm:
                reason = f"rotor speed {speed_now:.1f} rpm <= stop_speed_rpm {stop_rpm:g}"
                rpm = np.abs(series["rotor_speed_rpm"])
                i = int(np.argmax(rpm <= stop_rpm))  # first sample at or below the stop speed
                t_stop = float(t[i] if i == 0 else np.interp(stop_rpm, [rpm[i], rpm[i - 1]], [t[i], t[i - 1]]))
            elif runaway:
                reason = f"thermal runaway of {runaway[0]} at t = {runaway[1]:.3f} s ({runaway[2]})"
            elif t1 >= t_end - 0.5 * settings.step:
                reason = f"t_end ({t_end:g} s) reached at {speed_now:.4g} rpm"
            rec = dict(wall_s=float(rs["wall_s"]) + carry_s + (time.perf_counter() - wall_chunk0),
                       solver_wall_s=float(rs["solver_wall_s"]) + stats["wall_s"],
                       steps=int(rs["steps"]) + stats["steps"],
                       newton_iterations=int(rs["newton_iterations"]) + stats["newton_iterations"],
                       jacobians=int(rs["jacobians"]) + stats["jacobians"], stop_reason=reason,
                       peak_rss_mb=max(float(rs.get("peak_rss_mb", 0.0)), _maxrss_mb()))
        else:
            row, reason, t_stop, rec = None, "solver failed", None, None
        pending.append(_chunk_writer(k, rows, row, rec, t_stop, float(t[-1]), q[-1], v[-1], t1,
                                     f"solver stopped at t = {t[-1]:.6g} s: {msg}"))
        pending_bytes += 8 * (len(t) * (1 + 2 * spec.n + len(series)) + 64)
        # the next chunk starts from this one's end state: bitwise the values stored (float64
        # written and read back unchanged), so it is the state a resume would read from the file
        if ok:
            rs = dict(rs, q=q[-1].copy(), v=v[-1].copy(), t_s=t1, chunks=k + 1, **rec,
                      offsets={name: float(series[name][-1]) for name in rs["offsets"]},
                      carry={name: float(series[name][-1]) for name in rs["carry"] or carried})
        else:
            rs = dict(rs, stop_reason=reason)
        done = bool(rs["stop_reason"])
        t_record = time.perf_counter()
        infos.append({"chunk": k, "t_s": float(t[-1]), "rotor_speed_rpm": speed_now, "ok": ok,
                      "buffer_samples": len(keep), "max_buffer_samples": max_buffer})
        if done or len(pending) >= MAX_PENDING_CHUNKS or t_record - last_commit >= commit_every:
            batch = pending

            def fill(store, batch=batch):
                for write in batch:
                    write(store)

            ckpt.write_chunk(fill, k, new_bytes=pending_bytes)
            pending, pending_bytes = [], 0
            last_commit = time.perf_counter()
            for info in infos:  # after the commit: a hook that raises finds these chunks in the file
                if on_chunk is not None:
                    on_chunk(info)
            infos = []
        now = time.perf_counter()
        if stream and (now - last_print > 2.0 or done):
            last_print = now
            w = now - wall_start
            stream.write(f"t = {t[-1]:8.3f} s  rotor {speed_now:7.1f} rpm  chunk {k + 1}  wall {w:7.1f} s  "
                         f"({w / max(t[-1] - t_first, 1e-9):.2f} s wall per simulated s; "
                         f"peak {_maxrss_mb():.0f} MB)\n")
            stream.flush()
        carry_s = time.perf_counter() - t_record
    summary = finish(path, spec, scenario, cd, plots=plots)
    summary["_max_buffer"] = max_buffer
    return summary


def final_state(model) -> tuple[np.ndarray, np.ndarray]:
    """(q, v) of the model's nodes now (after a solve: at its end time), in spec order."""
    import exudyn as exu

    q = np.zeros(model.spec.n)
    v = np.zeros(model.spec.n)
    for nd, sl in model.node_slices:
        q[sl] = model.mbs.GetNodeOutput(nd, exu.OutputVariableType.Coordinates)
        v[sl] = model.mbs.GetNodeOutput(nd, exu.OutputVariableType.Coordinates_t)
    return q, v


def _maxrss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def whirl_phases(t_start, t_end, direction, freq, speed_end, bearing=None, bearing_names=()) -> list[dict]:
    """Contiguous runs of chunks with the same per-chunk whirl direction. ``bearing``: per chunk the
    index into ``bearing_names`` of the bearing that whirls (-1 none; None: a file without that
    column). A whirling phase names its ``bearing`` (the one whirling for the most chunk time in
    it; the first to whirl on a tie) and ``bearing_time_s`` (whirl time per bearing), so a
    verdict can name the bearing of the whole run."""
    names = {0: "none", 1: "forward", -1: "backward"}
    out = []
    i = 0
    n = len(direction)
    while i < n:
        j = i
        while j + 1 < n and direction[j + 1] == direction[i]:
            j += 1
        f = freq[i:j + 1]
        f = f[np.isfinite(f)]
        ph = {"direction": names[int(direction[i])], "t_start_s": float(t_start[i]), "t_end_s": float(t_end[j]),
              "rotor_speed_rpm_at_end": float(speed_end[j]),
              "frequency_hz_median": float(np.median(f)) if len(f) else None}
        if ph["direction"] != "none":
            times = {}
            if bearing is not None:
                for m in range(i, j + 1):
                    b = int(bearing[m])
                    if 0 <= b < len(bearing_names):
                        key = bearing_names[b]
                        times[key] = times.get(key, 0.0) + float(t_end[m] - t_start[m])
            ph["bearing"] = longest_whirl(times)
            ph["bearing_time_s"] = times
        out.append(ph)
        i = j + 1
    return out


def stored_span_deflection(spec, q_dataset, n: int, block: int = 20000) -> dict:
    """``postprocess.span_deflection`` over the stored samples of a coast-down (read in blocks: a long
    run's states do not fit in memory at once). The stored samples are the kept ones (every
    ``decimate_every``-th where the contact forces change slowly, all of them round impacts), so a
    whirl's peak is sampled at the stored rate: a few per cent low at worst."""
    from .postprocess import span_deflection

    parts = [span_deflection(spec, q_dataset[i:min(i + block, n)]) for i in range(0, n, block)]
    best = max(parts, key=lambda p: p["peak_m"])
    return {"station_peak_m": {k: max(p["station_peak_m"][k] for p in parts) for k in parts[0]["station_peak_m"]},
            "peak_m": best["peak_m"], "peak_x_m": best["peak_x_m"], "x_m": parts[0]["x_m"],
            "node_peak_m": [max(v) for v in zip(*(p["node_peak_m"] for p in parts))],
            "station_x_m": parts[0]["station_x_m"]}


def finish(path: Path, spec, scenario: Scenario, cd: Coastdown, *, plots: bool = True) -> dict:
    """Summary of the run from the file (reads only a few series), summary_json, figure. The file
    is rewritten compactly under a temporary name with the summary and renamed (results.h5 is
    never modified in place); the caller writes summary.json."""
    import h5py

    with h5py.File(path, "r") as h5:
        r = h5["coastdown/restart"]
        n_file = h5["time_s"].shape[0]
        s = h5["series"]
        last = {k: float(s[k][n_file - 1]) for k in s if k.startswith(CUMULATIVE_PREFIXES)} if n_file else {}
        ch = {k: h5["coastdown/chunks"][k][()] for k in h5["coastdown/chunks"]}
        first_last = {k: (float(s[k][0]), float(s[k][n_file - 1])) for k in ("kinetic_energy_j", "potential_energy_j",
                                                                               "rotor_speed_rpm")} if n_file else {}
        races = {b: float(s[b + "_race_speed_rpm"][n_file - 1]) for b in spec.bearing_names} if n_file else {}
        reason = str(r.attrs["stop_reason"])
        complete = bool(reason) and reason != "solver failed"
        t_reached = float(h5.attrs["t_reached_s"])
        perf = {"simulated_s": float(r.attrs["t_s"]), "wall_s": float(r.attrs["wall_s"]),
                "solver_wall_s": float(r.attrs["solver_wall_s"]),
                "steps": int(r.attrs["steps"]), "newton_iterations": int(r.attrs["newton_iterations"]),
                "jacobians": int(r.attrs["jacobians"]), "chunks": int(r.attrs["chunks"]), "chunk_s": cd.chunk_s,
                "step_s": scenario.solver.step, "output_period_s": scenario.solver.output_period,
                "samples_stored": n_file,
                "samples_full_rate": int(round(float(r.attrs["t_s"]) / scenario.solver.output_period)) + 1}
        perf["wall_s_per_simulated_s"] = perf["wall_s"] / max(perf["simulated_s"], 1e-12)
        perf["decimation_ratio"] = perf["samples_full_rate"] / max(n_file, 1)
        summary = {"scenario": scenario.name, "kind": "coastdown", "complete": complete,
                   "stop_reason": reason or "interrupted (resume with --resume)", "t_reached_s": t_reached,
                   "coastdown": asdict(cd)}
        if n_file:
            ser = {"kinetic_energy_j": np.array(first_last["kinetic_energy_j"]),
                   "potential_energy_j": np.array(first_last["potential_energy_j"])}
            for k2, v2 in last.items():
                ser[k2] = np.array([0.0, v2])
            summary["time_to_stop_s"] = float(r.attrs["t_stop_s"]) if "t_stop_s" in r.attrs else None
            summary["speeds"] = {"initial_rotor_rpm": scenario.speed_rpm, "final_rotor_rpm": first_last["rotor_speed_rpm"][1],
                                 "final_inner_race_rpm": races}
            summary["energy"] = energy_summary(ser)
            summary["bearings"] = {b: {"max_contact_force_n": float(np.max(ch[f"{b}_max_contact_force_n"]))
                                       if len(ch[f"{b}_max_contact_force_n"]) else 0.0} for b in spec.bearing_names}
            summary["whirl_phases"] = whirl_phases(ch["t_start_s"], ch["t_end_s"], ch["whirl_direction"],
                                                   ch["whirl_frequency_hz"], ch["rotor_speed_rpm"],
                                                   ch.get("whirl_bearing"), spec.bearing_names)
            thermal = thermal_file_summary(h5, spec)
            if thermal:
                summary["thermal"] = thermal
            summary["rotor_deflection"] = stored_span_deflection(spec, h5["states/q"], n_file)
            from .run import close_clearances  # the landing's one reading of them

            summary["rotor_deflection"]["close_clearances_m"] = close_clearances(scenario)
        if not complete and reason == "solver failed":
            summary["message"] = str(h5.attrs["message"])
        summary["units"] = "SI (m, N, s, J); speeds in rpm as named"
        # peak resident memory over every process that worked on this run
        perf["peak_memory_mb"] = max(float(r.attrs.get("peak_rss_mb", 0.0)), _maxrss_mb())
        summary["performance"] = perf
    repack(path, attrs={"complete": complete, "message": summary.get("message", reason)},
           summary_json=json.dumps(summary))
    perf["results_h5_mb"] = path.stat().st_size / 1e6
    if plots and n_file:
        summary["figures"] = [plot_coastdown(path, path.parent / "coastdown.png").name]
    return summary


def plot_coastdown(h5_path: Path, png: Path) -> Path:
    """Speed vs time (rotor and inner races), per-chunk peak contact force, energy dissipated."""
    import h5py

    from .plots import _plt

    plt = _plt()
    with h5py.File(h5_path, "r") as h5:
        t = h5["time_s"][()]
        s = h5["series"]
        rotor = s["rotor_speed_rpm"][()]
        races = {k[:-len("_race_speed_rpm")]: s[k][()] for k in s if k.endswith("_race_speed_rpm")}
        diss = {k: s["dissipated_" + k + "_j"][()] for k in dissipation_entries() if "dissipated_" + k + "_j" in s}
        ch = h5["coastdown/chunks"]
        tc = ch["t_end_s"][()]
        fmax = {k[:-len("_max_contact_force_n")]: ch[k][()] for k in ch if k.endswith("_max_contact_force_n")}
        wd = ch["whirl_direction"][()]
        name = h5.attrs["scenario_name"]
    fig, axes = plt.subplots(3, 1, figsize=(9, 9), sharex=True)
    ax = axes[0]
    ax.plot(t, rotor, "k", label="rotor")
    for b, w in races.items():
        ax.plot(t, w, label=f"{b} inner race", alpha=0.8)
    for d, col in ((1, "tab:red"), (-1, "tab:blue")):
        sel = wd == d
        if np.any(sel):
            ax.plot(tc[sel], np.interp(tc[sel], t, rotor), "o", ms=3, color=col,
                    label=f"{'forward' if d > 0 else 'backward'} whirl (chunk)")
    ax.set_ylabel("speed [rpm]")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    for b, f in fmax.items():
        axes[1].step(tc, f, where="pre", label=b)
    axes[1].set_ylabel("peak contact force\nper chunk [N]")
    axes[1].legend(fontsize=8)
    axes[1].grid(alpha=0.3)
    for k, e in sorted(diss.items(), key=lambda kv: -kv[1][-1] if len(kv[1]) else 0)[:6]:
        axes[2].plot(t, e, label=k)
    axes[2].set_ylabel("energy dissipated [J]")
    axes[2].set_xlabel("time [s]")
    axes[2].legend(fontsize=8)
    axes[2].grid(alpha=0.3)
    fig.suptitle(f"{name}: coast-down")
    fig.tight_layout()
    save_figure(fig, png, dpi=110)
    plt.close(fig)
    return png


def format_summary(summary: dict) -> str:
    lines = [f"scenario: {summary['scenario']} (coast-down)" +
             ("" if summary.get("complete") else f"  [INCOMPLETE: {summary.get('message', summary['stop_reason'])}]")]
    lines.append(f"stopped: {summary['stop_reason']} at t = {summary['t_reached_s']:.3f} s" +
                 (f" (stop speed crossed at {summary['time_to_stop_s']:.3f} s)" if summary.get("time_to_stop_s") else ""))
    s = summary.get("speeds")
    if s:
        lines.append(f"rotor speed: {s['initial_rotor_rpm']:.0f} -> {s['final_rotor_rpm']:.1f} rpm; inner races " +
                     ", ".join(f"{b} {w:.1f}" for b, w in s["final_inner_race_rpm"].items()) + " rpm")
    e = summary.get("energy")
    if e:
        top = sorted(e["dissipated_j"].items(), key=lambda kv: -kv[1])
        lines.append(f"energy dissipated: {e['dissipated_total_j']:.1f} J (" +
                     ", ".join(f"{k} {v:.1f} J" for k, v in top if v > 1e-3 * max(e['dissipated_total_j'], 1e-12)) +
                     f"); balance error {100 * e['balance_error_relative']:.2f} %")
    for ph in summary.get("whirl_phases", []):
        if ph["direction"] != "none":
            f = f" ~{ph['frequency_hz_median']:.1f} Hz" if ph["frequency_hz_median"] else ""
            lines.append(f"whirl: {ph['direction']}{f} from {ph['t_start_s']:.2f} to {ph['t_end_s']:.2f} s")
    lines += format_thermal(summary.get("thermal"))
    lines += [f"note: {n}" for n in summary.get("notes", [])]
    p = summary["performance"]
    lines.append(f"performance: {p['simulated_s']:.2f} s simulated in {p['wall_s']:.1f} s wall (solver "
                 f"{p['solver_wall_s']:.1f} s; {p['wall_s_per_simulated_s']:.2f} s/s), {p['chunks']} chunks of "
                 f"{p['chunk_s']:g} s, "
                 f"{p['samples_stored']} of {p['samples_full_rate']} samples stored, peak memory "
                 f"{p['peak_memory_mb']:.0f} MB, results.h5 {p['results_h5_mb']:.1f} MB")
    return "\n".join(lines)

"""Coast-down to rest: a landing run for minutes of machine time, streamed to ``results.h5``.

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

Crash safety: the commit protocol
---------------------------------
``results.h5`` is only ever replaced whole, never opened for writing (an HDF5 file killed while
open for writing can be unreadable or even crash the library on the next open). Beside it lives
``.results.h5.spare``, the previous commit. The chunks since the last commit are committed in
this order:

1. open the spare, copy into it the rows committed since it was written (the previous commit's
   chunks: a committed row never changes), cut rows beyond its commit; then per chunk append its
   rows and its ``/coastdown/chunks`` row and
2. write its *commit record* into the same file: ``/coastdown/commits`` (per chunk: the committed
   row count and a sha256 hash-chain link over the chunk's rows of every dataset and its chunk
   row, read back as stored) and the restart record (q, v, t_s, chunks, n_rows, and
   ``state_sha256`` over them);
3. close, fsync; hard-link results.h5 to ``.results.h5.prev``; ``os.replace`` the spare over
   results.h5 (this rename *is* the commit); rename prev to the spare name (the next chunk's
   spare); fsync the directory.

State, time, row counts and checksums therefore change together in one atomic rename, and the
cost is two small appends per chunk, not a copy of the file (a one-hour run has ~18000 chunks).
A kill at any point leaves results.h5 at the previous or the new commit; it loses at most the
chunks since the last commit (~2 s of wall time) and the one being solved. The spare is treated as
garbage by every new process (deleted, then copied afresh from results.h5), so a half-written
file is never opened. Where hard links are impossible the next chunk copies the file instead.
The end of the run (:func:`finish`) writes a compacted copy with the summary and renames it.
Readers may keep results.h5 open meanwhile: HDF5 locks files it has open, so if the previous
commit (the next spare) is still held by a reader, the run takes a fresh copy instead of writing
under it. Before each commit, space for it is reserved (``posix_fallocate``: about 1 MB plus
twice the chunk), so a full disk is found outside the HDF5 library (:mod:`rotorlanding.safeio`).
Cost: batching shares a commit's fixed part (sync, flush, fsync, rename; ~0.1 s) among the
chunks of 2 s: on the rig coast-down (0.2 s chunks) the time per chunk outside the solver fell
from ~0.10 s (one append, file opened and closed per chunk, before issue 16) to ~0.07 s. The
spare doubles the disk use while the run goes (it is deleted at the end).

``--resume`` first verifies results.h5 (:func:`verify_checkpoint`): every chain link against the
stored rows, the row counts against the dataset lengths, the restart state against its hash and
against the last committed row (bitwise). A file that disagrees is cut back to its last
consistent chunk (a new commit; the restart state is then that chunk's last row, which is
bitwise the state the chunk ended in); a file that cannot be read, is not a coast-down file or
has no commit record is refused with one line (:class:`rotorlanding.errors.InputError`, exit 2).
A write that fails (disk full, file too large, I/O error) leaves results.h5 at its last commit
and raises :class:`rotorlanding.safeio.WriteError` (one line, exit 3); a resume with space
available continues bit for bit. ``ROTORLANDING_FAULT=point[:chunk]`` kills the process at a
named point of this path (:func:`rotorlanding.safeio.fault`; used by the fault-injection tests).

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

import hashlib
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
from .mechanisms import dissipation_entries, rotor_force, series_units
from .postprocess import energy_summary, evaluate, uniform
from .safeio import WriteError, atomic_write_text, check_out_dir, copy_file, fault, fsync_dir, fsync_path, new_h5, reserve, tmp_name
from .safeio import h5_guard as _guard
from .safeio import unlink_quietly
from .scenario import Scenario, scenario_from_dict

CUMULATIVE_PREFIXES = ("dissipated_", "input_")
FIELDS = ("stop_speed_rpm", "chunk_s", "decimate_every", "fast_force_rate_n_s", "landing_s", "smooth_step")
H5_ROW_CHUNK = 1024  # HDF5 chunk rows of the resizable datasets
H5_COMPRESSION = {"compression": "gzip", "compression_opts": 1, "shuffle": True}


@dataclass(frozen=True)
class Coastdown:
    """The ``[coastdown]`` table."""

    stop_speed_rpm: float = 10.0        # rpm: the run ends after the chunk in which |rotor speed| <= this
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
# results file

def _units(names):
    from .results import coordinate_units

    uq = coordinate_units(names)
    uv = [u.replace("rad", "rad/s") if u == "rad" else (u + "/s") for u in uq]
    return uq, uv


CHUNK_COLUMNS = {  # /coastdown/chunks/NAME: one row per finished chunk
    "t_start_s": "s", "t_end_s": "s", "rotor_speed_rpm": "rpm", "wall_s": "s (solver only)", "steps": "-",
    "newton_iterations": "-", "jacobians": "-", "samples_kept": "-", "samples_fast": "-",
    "whirl_direction": "-1 backward, 0 none, +1 forward (per chunk; the DE journal's, else the bearing that whirls)", "whirl_frequency_hz": "Hz",
}


def _resizable(g, name, shape_tail, dtype=float, unit=None):
    ds = g.create_dataset(name, shape=(0,) + shape_tail, maxshape=(None,) + shape_tail, dtype=dtype,
                          chunks=(H5_ROW_CHUNK if not shape_tail else max(64, H5_ROW_CHUNK // shape_tail[0]),)
                          + shape_tail, **H5_COMPRESSION)
    if unit is not None:
        ds.attrs["unit"] = unit
    return ds


def _append(ds, rows):
    n = ds.shape[0]
    ds.resize(n + len(rows), axis=0)
    ds[n:] = rows


def create_file(path: Path, scenario: Scenario, cd: Coastdown, spec, series_units_: dict, bearing_names):
    """A new coast-down results.h5 with empty resizable datasets (layout of rotorlanding.results
    plus /coastdown), written under a temporary name and renamed into place (commit 0)."""
    import exudyn

    from . import __version__
    tmp = tmp_name(path, "part")
    # persistent free-space tracking: a partly filled compressed HDF5 chunk is rewritten at each
    # append, and without it the space it held is lost whenever the file is closed (file 2-4x larger)
    try:
        h5 = new_h5(tmp, CREATE_RESERVE, fs_strategy="fsm", fs_persist=True)
        with _guard(h5, tmp):
            h5.attrs["package"] = "rotorlanding"
            h5.attrs["package_version"] = __version__
            h5.attrs["exudyn_version"] = exudyn.__version__
            h5.attrs["scenario_name"] = scenario.name
            h5.attrs["kind"] = "coastdown"
            h5.attrs["complete"] = False
            h5.attrs["t_reached_s"] = 0.0
            h5.attrs["message"] = "running"
            h5.attrs["created_utc"] = _utc()
            h5["scenario_json"] = json.dumps(scenario.raw)
            h5["coastdown_json"] = json.dumps(asdict(cd))
            _resizable(h5, "time_s", (), unit="s")
            g = h5.create_group("states")
            uq, uv = _units(spec.names)
            for key, units in (("q", uq), ("v", uv)):
                ds = _resizable(g, key, (spec.n,))
                ds.attrs["names"] = json.dumps(spec.names)
                ds.attrs["units"] = json.dumps(units)
            s = h5.create_group("series")
            for name, unit in series_units_.items():
                _resizable(s, name, (), unit=unit)
            h5["summary_json"] = json.dumps({"scenario": scenario.name, "complete": False})
            c = h5.create_group("coastdown")
            ch = c.create_group("chunks")
            for name, unit in CHUNK_COLUMNS.items():
                _resizable(ch, name, (), unit=unit)
            for b in bearing_names:
                _resizable(ch, f"{b}_max_contact_force_n", (), unit="N")
            cm = c.create_group("commits")
            cm.attrs["description"] = ("commit record per chunk: n_rows = committed rows after the chunk, sha256 = "
                                       "hash chain over the chunk's rows (time_s, states, series) and its chunks/* row")
            _resizable(cm, "n_rows", (), dtype=np.int64)
            _resizable(cm, "sha256", (), dtype="S64")
            r = c.create_group("restart")
            r.attrs["description"] = ("state a chunk restarts from: q, v at time t_s after `chunks` finished chunks; "
                                      "rows beyond n_rows are uncommitted; state_sha256 checks q, v, t_s, chunks, n_rows")
            q0, v0 = spec.initial_state()
            r["q"] = q0
            r["v"] = v0
            r.attrs.update(t_s=0.0, chunks=0, n_rows=0, wall_s=0.0, solver_wall_s=0.0, steps=0, newton_iterations=0,
                           jacobians=0, stop_reason="", rows_sha256="", state_sha256=_state_digest(q0, v0, 0.0, 0, 0))
        fault("create")
        fsync_path(tmp)
        os.replace(tmp, path)
    except (OSError, WriteError):
        unlink_quietly(tmp)
        raise
    fsync_dir(path.parent)


def _utc():
    import datetime as _dt

    return _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")


CREATE_RESERVE = 256 << 10  # bytes reserved for a new results.h5 (its empty layout is ~60 kB)


# --------------------------------------------------------------------------------------------
# the commit protocol (see "Crash safety" in the module docstring)

def _state_digest(q, v, t_s: float, chunks: int, n_rows: int) -> str:
    """sha256 of the restart state and where it sits (time, chunks done, committed rows)."""
    h = hashlib.sha256()
    for arr in (np.asarray(q, np.float64), np.asarray(v, np.float64), np.float64(t_s),
                np.int64(chunks), np.int64(n_rows)):
        h.update(np.ascontiguousarray(arr).tobytes())
    return h.hexdigest()


def _chunk_digest(prev: str, ds, row_paths, r0: int, r1: int, chunk_paths, j: int) -> str:
    """Link j of the hash chain: the previous link, the chunk's rows [r0, r1) of every row dataset
    and row j of every chunk column, exactly as stored (read back from the file; ``ds(path)``
    returns a dataset)."""
    h = hashlib.sha256(prev.encode())
    for p in row_paths:
        h.update(p.encode())
        h.update(np.ascontiguousarray(ds(p)[r0:r1]).tobytes())
    for p in chunk_paths:
        h.update(p.encode())
        h.update(np.ascontiguousarray(ds(p)[j:j + 1]).tobytes())
    return h.hexdigest()


class Store:
    """An open coast-down results file with cached dataset handles: read the restart record,
    bring a spare copy up to date, truncate uncommitted rows, append one chunk."""

    def __init__(self, path: Path, mode: str = "r"):
        import h5py

        self.path = path
        self.h5 = h5py.File(path, mode)
        try:
            h5 = self.h5
            self.r = h5["coastdown/restart"]
            self.commits = h5["coastdown/commits"] if "coastdown/commits" in h5 else None
            series_names = sorted(h5["series"].keys())  # names only: datasets are opened on demand
            chunk_names = sorted(h5["coastdown/chunks"].keys())
        except Exception:
            self.h5.close()
            raise
        self._ds = {}
        self.cumulative = [k for k in series_names if k.startswith(CUMULATIVE_PREFIXES)]
        self.row_paths = ["time_s", "states/q", "states/v"] + [f"series/{k}" for k in series_names]
        self.chunk_paths = [f"coastdown/chunks/{k}" for k in chunk_names]

    def ds(self, p: str):
        """The dataset at path ``p``, opened once (h5py path lookups cost ~0.1 ms each, and a
        commit touches ~100 datasets several times)."""
        d = self._ds.get(p)
        if d is None:
            d = self._ds[p] = self.h5[p]
        return d

    @property
    def rows(self) -> dict:
        return {"time_s": self.ds("time_s"), "q": self.ds("states/q"), "v": self.ds("states/v")}

    @property
    def series(self) -> dict:
        return {p[7:]: self.ds(p) for p in self.row_paths[3:]}

    @property
    def chunks(self) -> dict:
        return {p[17:]: self.ds(p) for p in self.chunk_paths}

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def restart(self) -> dict:
        out = dict(self.r.attrs)
        out["q"] = self.r["q"][()]
        out["v"] = self.r["v"][()]
        n = int(out["n_rows"])
        out["offsets"] = {k: float(self.ds(f"series/{k}")[n - 1]) if n else 0.0 for k in self.cumulative}
        return out

    def _row_sets(self):
        """(dataset path, committed length) of every resizable dataset."""
        n, k = int(self.r.attrs["n_rows"]), int(self.r.attrs["chunks"])
        return ([(p, n) for p in self.row_paths] + [(p, k) for p in self.chunk_paths]
                + [(f"coastdown/commits/{c}", k) for c in ("n_rows", "sha256")])

    def sync_from(self, src: "Store"):
        """Make this (spare) file equal to ``src``, a later commit of the same run: rows this file
        has committed are identical in ``src`` (committed rows never change), so only the rows
        from this file's commit on are copied (one or two chunks), not the whole file."""
        for p, m in self._row_sets():
            s, d = src.ds(p), self.ds(p)
            n = s.shape[0]
            m = min(m, n, d.shape[0])
            d.resize(n, axis=0)
            if n > m:
                d[m:n] = s[m:n]
        self.r["q"][...] = src.r["q"][()]
        self.r["v"][...] = src.r["v"][()]
        for key in set(self.r.attrs) - set(src.r.attrs):
            del self.r.attrs[key]
        self.r.attrs.update(dict(src.r.attrs))
        self.h5.attrs.update(dict(src.h5.attrs))
        text = src.h5["summary_json"][()]
        if self.h5["summary_json"][()] != text:
            del self.h5["summary_json"]
            self.h5["summary_json"] = text

    def truncate(self):
        """Drop rows written after the last commit (the partial chunk of a failed solve, or rows
        appended by hand)."""
        for p, n in self._row_sets():
            ds = self.ds(p)
            if ds.shape[0] > n:
                ds.resize(n, axis=0)

    def append(self, t, q, v, series: dict, chunk: int | None = None):
        _append(self.ds("time_s"), t)
        fault("mid-append", chunk)  # time_s longer than the states: a torn append
        for ds, arr in ((self.ds("states/q"), q), (self.ds("states/v"), v)):
            _append(ds, arr)
        for name, arr in series.items():
            _append(self.ds(f"series/{name}"), arr)

    def commit(self, k: int, q, v, t1: float, **attrs):
        """Restart record and hash-chain link for chunk ``k`` (its rows and chunks/* row appended)."""
        n = self.ds("time_s").shape[0]
        prev = str(self.r.attrs.get("rows_sha256", ""))
        r0 = int(self.r.attrs["n_rows"])
        link = _chunk_digest(prev, self.ds, self.row_paths, r0, n, self.chunk_paths, k)
        _append(self.commits["n_rows"], [n])
        _append(self.commits["sha256"], [link.encode()])
        self.r["q"][...] = q
        self.r["v"][...] = v
        self.r.attrs.update(t_s=t1, chunks=k + 1, n_rows=n, rows_sha256=link,
                            state_sha256=_state_digest(q, v, t1, k + 1, n), **attrs)

    def close(self):
        self.h5.close()


def read_restart(path: Path) -> dict:
    with Store(path, "r") as st:
        return st.restart()


class Checkpoint:
    """The committed file ``results.h5`` and its spare copy ``.results.h5.spare`` (the previous
    commit). A chunk is written into the spare (brought up to date first), which is closed,
    fsynced and renamed over results.h5; the replaced file, kept through a hard link, becomes the
    next spare. results.h5 is therefore only ever replaced by a complete, closed file and never
    opened for writing: a kill leaves the previous or the new commit, never a mix."""

    def __init__(self, path: Path):
        self.path = path
        self.spare = tmp_name(path, "spare")
        self.prev = tmp_name(path, "prev")
        self.spare_ok = False  # the spare is a closed earlier commit of this process (else: copy)
        self.allowance = None  # bytes: see _margin

    def discard_leftovers(self):
        """A spare or prev left by a killed process may be half written: never open it."""
        for p in (self.spare, self.prev, tmp_name(self.path, "part"), tmp_name(self.path, "repack")):
            unlink_quietly(p)
        self.spare_ok = False

    def publish(self, k: int | None = None):
        """Make the closed spare the committed results.h5 (fsync, link, rename, fsync dir)."""
        fsync_path(self.spare)
        fault("fsynced", k)
        unlink_quietly(self.prev)
        try:
            os.link(self.path, self.prev)  # keep the current commit: it becomes the next spare
            linked = True
        except OSError:  # no hard links here: the next chunk copies the file instead
            linked = False
        fault("linked", k)
        os.replace(self.spare, self.path)  # the commit
        fault("replaced", k)
        if linked:
            os.replace(self.prev, self.spare)
        self.spare_ok = linked
        fault("rotated", k)
        fsync_dir(self.path.parent)

    def _margin(self, new_bytes: int) -> int:
        """Bytes to reserve in the spare for one commit: the rows it lacks (twice their size in
        results.h5), the new chunk (twice its raw size), every dataset's last HDF5 chunk written
        anew (a compressed chunk moves when it grows; at most its raw size), and 64 kB of metadata.
        Measured on the short test run: the spare grows by 0.05-0.25 MB per commit, the margin is
        ~1 MB."""
        import h5py

        if self.allowance is None:
            total = 0
            with h5py.File(self.path, "r") as h5:
                def visit(_, obj):
                    nonlocal total
                    if isinstance(obj, h5py.Dataset) and obj.chunks:
                        total += int(np.prod(obj.chunks)) * obj.dtype.itemsize
                h5.visititems(visit)
            self.allowance = total + (64 << 10)
        lag = max(self.path.stat().st_size - self.spare.stat().st_size, 0)
        return 2 * lag + 2 * int(new_bytes) + self.allowance

    def write_chunk(self, fill, k: int | None = None, new_bytes: int = 0):
        """One commit: bring the spare up to date with results.h5 (a copy if it is not a closed
        earlier commit of this process), cut it to its commit, ``fill(store)`` appends the chunk
        and its commit record, close, publish. Any error leaves results.h5 as it was (the spare is
        dropped) and a failed write raises WriteError naming the file."""
        try:
            try:
                if not self.spare_ok:
                    copy_file(self.path, self.spare, point="copy", chunk=k)
                reserve(self.spare, self._margin(new_bytes))
            except OSError as exc:
                raise WriteError(self.spare, exc) from None
            try:
                work = Store(self.spare, "a")
            except BlockingIOError:
                # a reader still holds the previous results.h5 (now the spare) open, and HDF5
                # locks it: never write under a reader's feet, take a fresh copy instead
                unlink_quietly(self.spare)
                try:
                    copy_file(self.path, self.spare)
                    reserve(self.spare, self._margin(new_bytes))
                except OSError as exc:
                    raise WriteError(self.spare, exc) from None
                work = Store(self.spare, "a")
            with _guard(work.h5, self.spare):
                with Store(self.path, "r") as src:
                    work.sync_from(src)
                work.truncate()
                fault("synced", k)
                fill(work)
                work.h5.flush()  # a failed write surfaces here, inside the guard (not in a dealloc)
            fault("closed", k)
            try:
                self.publish(k)
            except OSError as exc:
                raise WriteError(self.path, exc) from None
        except BaseException:
            self.spare_ok = False
            unlink_quietly(self.spare)
            raise


def verify_checkpoint(path: Path, spec, stream=None) -> dict:
    """Check results.h5 against its commit record before a resume; truncate to the last
    consistent chunk if needed (a new commit), or refuse with an InputError.

    Checked: every chunk's hash-chain link over its stored rows and chunk row, the committed row
    counts against the dataset lengths, the restart state's hash, and that the restart state is
    bitwise the last committed row (its time, q and v)."""
    def refuse(why):
        return InputError("--resume", str(path), f"{why}; start over with --overwrite")

    try:
        with Store(path, "r") as st:
            if st.commits is None or "state_sha256" not in st.r.attrs:
                raise refuse("has no commit record (written by an older rotorlanding)")
            h5 = st.h5
            K, N = int(st.r.attrs["chunks"]), int(st.r.attrs["n_rows"])
            n_min = min(st.ds(p).shape[0] for p in st.row_paths)
            c_min = min(st.ds(p).shape[0] for p in st.chunk_paths)
            cn, cs = st.commits["n_rows"][()], st.commits["sha256"][()]
            good, prev, r0 = 0, "", 0
            for j in range(min(K, len(cn), len(cs), c_min)):
                r1 = int(cn[j])
                if not r0 < r1 <= n_min:
                    break
                link = _chunk_digest(prev, st.ds, st.row_paths, r0, r1, st.chunk_paths, j)
                if link != cs[j].decode():
                    break
                good, prev, r0 = j + 1, link, r1
            q, v, t_s = st.r["q"][()], st.r["v"][()], float(st.r.attrs["t_s"])
            state_ok = (good == K and N == r0 and prev == str(st.r.attrs["rows_sha256"])
                        and _state_digest(q, v, t_s, K, N) == str(st.r.attrs["state_sha256"])
                        and (N == 0 or (np.array_equal(q, h5["states/q"][N - 1])
                                        and np.array_equal(v, h5["states/v"][N - 1])
                                        and t_s == float(h5["time_s"][N - 1]))))
    except InputError:
        raise
    except (OSError, KeyError, ValueError, TypeError) as exc:
        raise refuse(f"cannot be read as a coast-down checkpoint ({str(exc).splitlines()[0] if str(exc) else exc!r})") \
            from None
    if state_ok:
        return {"chunks": K, "repaired": False}
    # truncate to the last consistent chunk: a new commit with the restart record rebuilt from it
    tmp = tmp_name(path, "repack")
    copy_file(path, tmp)
    reserve(tmp, CREATE_RESERVE)  # a repair only shrinks datasets and rewrites a few attributes
    st = Store(tmp, "a")
    with _guard(st.h5, tmp):
        st.r.attrs.update(n_rows=r0, chunks=good)
        st.truncate()
        if good:
            q, v, t_s = st.rows["q"][r0 - 1], st.rows["v"][r0 - 1], float(st.rows["time_s"][r0 - 1])
        else:
            q, v = spec.initial_state()
            t_s = 0.0
        ch = {k: ds[()] for k, ds in st.chunks.items()}
        st.r["q"][...] = q
        st.r["v"][...] = v
        if "t_stop_s" in st.r.attrs:
            del st.r.attrs["t_stop_s"]
        st.r.attrs.update(t_s=t_s, rows_sha256=prev, stop_reason="", state_sha256=_state_digest(q, v, t_s, good, r0),
                          wall_s=float(np.sum(ch["wall_s"])), solver_wall_s=float(np.sum(ch["wall_s"])),
                          **{c: int(np.sum(ch[c])) for c in ("steps", "newton_iterations", "jacobians")})
        st.h5.attrs.update(complete=False, t_reached_s=t_s, message="running")
    fsync_path(tmp)
    os.replace(tmp, path)
    fsync_dir(path.parent)
    if stream:
        stream.write(f"checkpoint check: {path} was consistent up to chunk {good} of {K} (t = {t_s:g} s); "
                     f"later rows dropped\n")
    return {"chunks": good, "repaired": True, "recorded_chunks": K}


# --------------------------------------------------------------------------------------------
# the run

class Interrupted(Exception):
    """Raised by a test hook to simulate a kill between chunks."""


def _classify_whirl(spec, t, q, v, chunk_s):
    """The landing's whirl within one chunk (the DE journal's, else the bearing whose journal whirls
    first: ``whirl.landing_whirl_bearing``), from the full-rate samples (before decimation):
    (direction -1/0/1, frequency [Hz] or nan)."""
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
    wr = whirls[landing_whirl_bearing(whirls)]
    d = {"none": 0, "forward": 1, "backward": -1}[wr["direction"]]
    return d, (wr["frequency_hz"] if wr["frequency_hz"] is not None else float("nan"))


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
    if existing and resume:
        _check_resumable(path, scenario, cd_json)
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
            for name, val in row.items():
                _append(store.ds(f"coastdown/chunks/{name}"), [val])
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
    with Store(path, "r") as store:
        rs = store.restart()  # the first chunk starts from what is committed in the file
    while True:
        wall_chunk0 = time.perf_counter()
        k = int(rs["chunks"])
        t0 = float(rs["t_s"])
        if rs["stop_reason"]:
            break
        if t_first is None:
            t_first = t0
        t1 = min((k + 1) * cd.chunk_s, t_end)
        model = build_exudyn(spec, rs["q"], rs["v"])
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
        keep, fast = keep_mask(t, contact_normal_forces(spec, q, v), cd, s_k.output_period)
        whirl = _classify_whirl(spec, t, q, v, t1 - t0) if ok and len(t) > 8 else (0, float("nan"))
        t, q, v = t[keep], q[keep], v[keep]
        series = evaluate(spec, t, q, v)  # on the kept samples only; cumulative from the chunk start
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
            for b in spec.bearing_names:
                row[f"{b}_max_contact_force_n"] = float(np.max(np.hypot(*rotor_force(series, b))))
            reason, t_stop = "", None
            if speed_now <= stop_rpm:
                reason = f"rotor speed {speed_now:.1f} rpm <= stop_speed_rpm {stop_rpm:g}"
                rpm = np.abs(series["rotor_speed_rpm"])
                i = int(np.argmax(rpm <= stop_rpm))  # first sample at or below the stop speed
                t_stop = float(t[i] if i == 0 else np.interp(stop_rpm, [rpm[i], rpm[i - 1]], [t[i], t[i - 1]]))
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
                      offsets={name: float(series[name][-1]) for name in rs["offsets"]})
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


def _check_resumable(path: Path, scenario: Scenario, cd_json: str):
    import h5py

    try:
        with h5py.File(path, "r") as h5:
            if h5.attrs.get("kind") != "coastdown" or "coastdown/restart" not in h5:
                raise InputError("--resume", str(path), "is not a coast-down results file; run without --resume")
            same = json.loads(h5["scenario_json"][()]) == json.loads(json.dumps(scenario.raw)) \
                and json.loads(h5["coastdown_json"][()]) == json.loads(cd_json)
    except OSError as exc:
        raise InputError("--resume", str(path), f"cannot be read ({exc}); start over with --overwrite") from None
    if not same:
        raise InputError("--resume", str(path), "was written for a different scenario or [coastdown] table; "
                         "resume with the same file and --set values, or start over with --overwrite")


def _maxrss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def whirl_phases(t_start, t_end, direction, freq, speed_end) -> list[dict]:
    """Contiguous runs of chunks with the same per-chunk whirl direction."""
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
        out.append({"direction": names[int(direction[i])], "t_start_s": float(t_start[i]), "t_end_s": float(t_end[j]),
                    "rotor_speed_rpm_at_end": float(speed_end[j]),
                    "frequency_hz_median": float(np.median(f)) if len(f) else None})
        i = j + 1
    return out


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
                                                   ch["whirl_frequency_hz"], ch["rotor_speed_rpm"])
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


def repack(path: Path, attrs: dict | None = None, summary_json: str | None = None) -> None:
    """Rewrite the file compactly (appending to compressed datasets leaves freed space behind),
    with root ``attrs`` and ``/summary_json`` replaced; written to a temporary file, fsynced and
    renamed, so an interruption leaves the original."""
    import h5py

    tmp = tmp_name(path, "repack")
    try:
        dst = new_h5(tmp, path.stat().st_size + CREATE_RESERVE, fs_strategy="fsm", fs_persist=True)
        with _guard(dst, tmp), h5py.File(path, "r") as src:
            for key, val in src.attrs.items():
                dst.attrs[key] = val
            dst.attrs.update(attrs or {})
            for key in src:
                if key == "summary_json" and summary_json is not None:
                    dst[key] = summary_json
                else:
                    src.copy(src[key], dst, name=key)
        fault("repacked")
        fsync_path(tmp)
        os.replace(tmp, path)
    except (OSError, WriteError):
        unlink_quietly(tmp)
        raise
    fsync_dir(path.parent)


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
    fig.savefig(png, dpi=110)
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
    p = summary["performance"]
    lines.append(f"performance: {p['simulated_s']:.2f} s simulated in {p['wall_s']:.1f} s wall (solver "
                 f"{p['solver_wall_s']:.1f} s; {p['wall_s_per_simulated_s']:.2f} s/s), {p['chunks']} chunks of "
                 f"{p['chunk_s']:g} s, "
                 f"{p['samples_stored']} of {p['samples_full_rate']} samples stored, peak memory "
                 f"{p['peak_memory_mb']:.0f} MB, results.h5 {p['results_h5_mb']:.1f} MB")
    return "\n".join(lines)

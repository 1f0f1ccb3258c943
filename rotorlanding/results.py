"""Results files: ``results.h5`` (every time series with units, the resolved scenario, the
package version) and ``summary.json``.

HDF5 layout::

    /                 attrs: package, package_version, exudyn_version, scenario_name, complete,
                             t_reached_s, message, created_utc
    /scenario_json    the fully resolved scenario tables (JSON text): `rotorlanding run results.h5`
                      re-runs exactly this case
    /time_s           sample times [s]
    /states/q, /states/v   generalised coordinates and velocities, attrs: names, units
    /series/NAME      derived time series; attr unit (SI, declared in mechanisms.series_units)
    /summary_json     the summary (JSON text)

A coast-down (``rotorlanding coastdown``, :mod:`rotorlanding.coastdown_run`) writes the same datasets
as resizable, appended chunk by chunk (decimated, irregular ``time_s``), plus attrs ``kind =
"coastdown"``::

    /coastdown_json          the [coastdown] table (JSON text)
    /coastdown/chunks/NAME   one row per finished chunk (CHUNK_COLUMNS, NAME_max_contact_force_n per bearing)
    /coastdown/commits       n_rows, sha256: the commit record per chunk (below)
    /coastdown/restart       q, v; attrs t_s, chunks, n_rows, rows_sha256, state_sha256, stop_reason, totals

This module owns that layout and its crash-safe store (:func:`create_file`, :class:`Store`,
:class:`Checkpoint`, :func:`verify_checkpoint`, :func:`repack`); :mod:`rotorlanding.coastdown_run`
runs the chunks and hands each commit a function that appends its rows.

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
The end of the run (:func:`rotorlanding.coastdown_run.finish`, through :func:`repack`) writes a compacted copy with the summary and renames it.
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
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import json
import os
from contextlib import contextmanager
from dataclasses import asdict
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from . import __version__, safeio
from .errors import InputError
from .mechanisms import carried_series
from .safeio import WriteError, copy_file, fault, fsync_dir, fsync_path, h5_guard, new_h5, tmp_name, unlink_quietly

if TYPE_CHECKING:
    from .coastdown_run import Coastdown
    from .scenario import Scenario

CUMULATIVE_PREFIXES = ("dissipated_", "input_")  # cumulative series: a chunk continues from the last row
H5_ROW_CHUNK = 1024  # HDF5 chunk rows of the coast-down's resizable datasets
H5_COMPRESSION = {"compression": "gzip", "compression_opts": 1, "shuffle": True}


def coordinate_units(names: list[str]) -> list[str]:
    out = []
    for nm in names:
        if nm.startswith("mode"):
            out.append("kg^0.5 m (mass-normalised modal coordinate)")
        elif nm == "theta" or nm.endswith("phi"):
            out.append("rad")
        else:
            out.append("m")
    return out


def state_units(names: list[str]) -> tuple[list[str], list[str]]:
    """Units of the coordinates q and of their velocities v."""
    uq = coordinate_units(names)
    uv = [u.replace("rad", "rad/s") if u == "rad" else (u + "/s") for u in uq]
    return uq, uv


def _utc() -> str:
    return _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")


def write_results(path, *, scenario_raw: dict, scenario_name: str, names: list[str], t, q, v, series: dict,
                  units: dict, summary: dict, complete: bool, t_reached: float, message: str = "") -> Path:
    """Write results.h5 atomically: a temporary name beside it, fsync, rename. ``units``: the unit
    of every series (``mechanisms.series_units``; a series without one is an error)."""
    path = Path(path)
    tmp = tmp_name(path, "part")
    arrays = [np.asarray(t), np.asarray(q), np.asarray(v)] + [np.asarray(a) for a in series.values()]
    # disk reserved up front (raw size + 1 %: gzip never grows data by more) so a full disk fails
    # before HDF5 writes (see rotorlanding.safeio)
    need = int(1.01 * sum(a.nbytes for a in arrays)) + (1 << 20)
    try:
        h5 = new_h5(tmp, need)
        with h5_guard(h5, tmp):
            # the datasets stay referenced until the flush: one freed earlier flushes its data
            # on its own, where a failed write cannot be caught
            held = _fill(h5, scenario_raw, scenario_name, names, t, q, v, series, units, summary, complete,
                         t_reached, message)
            h5.flush()
            del held
        fault("results-written")
        fsync_path(tmp)
        os.replace(tmp, path)
    except (OSError, WriteError) as exc:
        unlink_quietly(tmp)
        raise WriteError(path, exc.exc if isinstance(exc, WriteError) else exc) from None  # name the file a user knows
    fsync_dir(path.parent)
    return path


def _fill(h5, scenario_raw, scenario_name, names, t, q, v, series, units, summary, complete, t_reached,
          message) -> list:
    """Write the layout into the open file; returns the datasets created (see write_results)."""
    import exudyn

    held = []

    h5.attrs["package"] = "rotorlanding"
    h5.attrs["package_version"] = __version__
    h5.attrs["exudyn_version"] = exudyn.__version__
    h5.attrs["scenario_name"] = scenario_name
    h5.attrs["complete"] = bool(complete)
    h5.attrs["t_reached_s"] = float(t_reached)
    h5.attrs["message"] = message
    h5.attrs["created_utc"] = _utc()
    held.append(h5.create_dataset("scenario_json", data=json.dumps(scenario_raw)))
    held.append(h5.create_dataset("time_s", data=np.asarray(t)))
    held[-1].attrs["unit"] = "s"
    g = h5.create_group("states")
    for key, arr, cu in zip(("q", "v"), (q, v), state_units(names)):
        ds = g.create_dataset(key, data=np.asarray(arr), compression="gzip", compression_opts=4, shuffle=True)
        ds.attrs["names"] = json.dumps(names)
        ds.attrs["units"] = json.dumps(cu)
        held.append(ds)
    s = h5.create_group("series")
    for name, arr in series.items():
        ds = s.create_dataset(name, data=np.asarray(arr), compression="gzip", compression_opts=4, shuffle=True)
        ds.attrs["unit"] = units[name]
        held.append(ds)
    held.append(h5.create_dataset("summary_json", data=json.dumps(summary)))
    return held + [g, s]


def read_results(path) -> dict:
    """Load a results file into plain numpy arrays and dicts."""
    import h5py

    with h5py.File(path, "r") as h5:
        out = {"attrs": dict(h5.attrs), "scenario": json.loads(h5["scenario_json"][()]),
               "time_s": h5["time_s"][()], "q": h5["states/q"][()], "v": h5["states/v"][()],
               "names": json.loads(h5["states/q"].attrs["names"]),
               "series": {k: h5["series"][k][()] for k in h5["series"]},
               "units": {k: str(h5["series"][k].attrs.get("unit", "")) for k in h5["series"]},
               "summary": json.loads(h5["summary_json"][()])}
    return out


# --------------------------------------------------------------------------------------------
# the coast-down file: created empty, then appended chunk by chunk

CHUNK_COLUMNS = {  # /coastdown/chunks/NAME: one row per finished chunk
    "t_start_s": "s", "t_end_s": "s", "rotor_speed_rpm": "rpm", "wall_s": "s (solver only)", "steps": "-",
    "newton_iterations": "-", "jacobians": "-", "samples_kept": "-", "samples_fast": "-",
    "whirl_direction": "-1 backward, 0 none, +1 forward (per chunk; the DE journal's, else the bearing that whirls)", "whirl_frequency_hz": "Hz",
    "whirl_bearing": "- (index into the attribute 'names' of the bearing whose whirl is whirl_direction; -1 none)",
}
CHUNK_INT_COLUMNS = ("whirl_bearing",)  # stored as int64 (an index), the other columns as float


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


@contextmanager
def _replaced_whole(path: Path, tag: str, point: str):
    """Write a new version of ``path`` under a temporary name (yielded): once the block has closed
    it, fault ``point``, fsync, rename over ``path``, fsync the folder. An OSError or WriteError
    in the block or the rename removes the temporary file and propagates; ``path`` is untouched."""
    tmp = tmp_name(path, tag)
    try:
        yield tmp
        fault(point)
        fsync_path(tmp)
        os.replace(tmp, path)
    except (OSError, WriteError):
        unlink_quietly(tmp)
        raise
    fsync_dir(path.parent)


def create_file(path: Path, scenario: Scenario, cd: Coastdown, spec, series_units_: dict, bearing_names):
    """A new coast-down results.h5 with empty resizable datasets (layout of rotorlanding.results
    plus /coastdown), written under a temporary name and renamed into place (commit 0)."""
    import exudyn

    # persistent free-space tracking: a partly filled compressed HDF5 chunk is rewritten at each
    # append, and without it the space it held is lost whenever the file is closed (file 2-4x larger)
    with _replaced_whole(path, "part", "create") as tmp:
        h5 = new_h5(tmp, CREATE_RESERVE, fs_strategy="fsm", fs_persist=True)
        with h5_guard(h5, tmp):
            h5.attrs["package"] = "rotorlanding"
            h5.attrs["package_version"] = __version__
            h5.attrs["exudyn_version"] = exudyn.__version__
            h5.attrs["scenario_name"] = scenario.name
            h5.attrs["kind"] = "coastdown"
            h5.attrs["complete"] = False
            h5.attrs["t_reached_s"] = 0.0
            h5.attrs["message"] = "running"
            h5.attrs["created_utc"] = _utc()
            # series that are states (the thermal networks): a chunk starts from their last row
            h5.attrs["carried_series"] = json.dumps(list(carried_series(bearing_names)))
            h5["scenario_json"] = json.dumps(scenario.raw)
            h5["coastdown_json"] = json.dumps(asdict(cd))
            _resizable(h5, "time_s", (), unit="s")
            g = h5.create_group("states")
            uq, uv = state_units(spec.names)
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
                ds = _resizable(ch, name, (), dtype=np.int64 if name in CHUNK_INT_COLUMNS else float, unit=unit)
                if name == "whirl_bearing":
                    ds.attrs["names"] = json.dumps(list(bearing_names))
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


CREATE_RESERVE = 256 << 10  # bytes reserved for a new results.h5 (its empty layout is ~60 kB)
# space is reserved through safeio.reserve, looked up at each call (a test switches it off there)


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
        self.carried = [k for k in json.loads(self.h5.attrs.get("carried_series", "[]")) if k in series_names]
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
        # the carried states (temperatures) of the last committed row; none before the first chunk
        out["carry"] = {k: float(self.ds(f"series/{k}")[n - 1]) for k in self.carried} if n else {}
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

    def append_chunk_row(self, row: dict):
        """One row of ``/coastdown/chunks`` (a value per column named in ``row``)."""
        for name, val in row.items():
            _append(self.ds(f"coastdown/chunks/{name}"), [val])

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
                safeio.reserve(self.spare, self._margin(new_bytes))
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
                    safeio.reserve(self.spare, self._margin(new_bytes))
                except OSError as exc:
                    raise WriteError(self.spare, exc) from None
                work = Store(self.spare, "a")
            with h5_guard(work.h5, self.spare):
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
    safeio.reserve(tmp, CREATE_RESERVE)  # a repair only shrinks datasets and rewrites a few attributes
    st = Store(tmp, "a")
    with h5_guard(st.h5, tmp):
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



def check_resumable(path: Path, scenario: Scenario, cd_json: str):
    """Refuse a --resume of a file that is not a coast-down, or was written for another scenario or
    [coastdown] table (one InputError line)."""
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



def repack(path: Path, attrs: dict | None = None, summary_json: str | None = None) -> None:
    """Rewrite the file compactly (appending to compressed datasets leaves freed space behind),
    with root ``attrs`` and ``/summary_json`` replaced; written to a temporary file, fsynced and
    renamed, so an interruption leaves the original."""
    import h5py

    with _replaced_whole(path, "repack", "repacked") as tmp:
        dst = new_h5(tmp, path.stat().st_size + CREATE_RESERVE, fs_strategy="fsm", fs_persist=True)
        with h5_guard(dst, tmp), h5py.File(path, "r") as src:
            for key, val in src.attrs.items():
                dst.attrs[key] = val
            dst.attrs.update(attrs or {})
            for key in src:
                if key == "summary_json" and summary_json is not None:
                    dst[key] = summary_json
                else:
                    src.copy(src[key], dst, name=key)

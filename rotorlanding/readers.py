"""Guards of the input readers: one function per kind of file a user hands to rotorlanding.

Every reader of user files goes through one of these, so a damaged, empty, mis-encoded or
foreign file gives one :class:`~rotorlanding.errors.InputError` line (file, field, value, what
is allowed; the CLI exits 2) instead of a traceback from tomllib, h5py, numpy or scipy:

* :func:`read_text`        - TOML / JSON text (scenario, rotor, sweep, space, feature files and
                             every ``include``): missing, a directory, empty, binary, UTF-16,
                             not UTF-8.
* :func:`read_results_guarded` - a ``results.h5`` (re-run with ``run``, ``animate``, measured data
                             of ``diagnose``): empty, truncated, zeroed or overwritten head, text,
                             another program's HDF5, missing or unreadable datasets.
* :func:`read_columns`     - measured channels in CSV or MATLAB .mat: header, numbers per cell,
                             column lengths (the values themselves are checked by
                             :func:`rotorlanding.measured._from_columns`).

(The write side of results.h5 lives in :mod:`rotorlanding.results`; this module only reads.)
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np

from .errors import InputError

#: what the results file must hold, per part a caller may ask for (HDF5 path of each)
RESULT_PARTS = {"scenario": "scenario_json", "time_s": "time_s", "q": "states/q", "v": "states/v",
                "series": "series", "summary": "summary_json"}

_HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"


def _check_file(path: Path, field: str) -> None:
    if not path.exists():
        raise InputError(field, str(path), "file not found")
    if not path.is_file():
        raise InputError(field, str(path), "must be a file, not a directory or device")


def read_text(path, *, kind: str = "TOML", field: str = "file") -> str:
    """The text of a UTF-8 input file (a UTF-8 byte-order mark is accepted)."""
    path = Path(path)
    _check_file(path, field)
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise InputError(field, str(path), f"cannot be read ({exc.strerror or exc})") from None
    if not raw.strip():
        # an empty file would otherwise surface later as a missing table or, worse, as an error
        # about a --set override the user gave for a key the empty file lacks
        raise InputError("(file)", "empty", f"the file is empty; expected {kind} text", file=str(path))
    if raw[:2] in (b"\xff\xfe", b"\xfe\xff") or b"\x00" in raw[:4096]:
        # UTF-16/32 text has NUL bytes between ASCII characters, as binary files have
        raise InputError("(file)", "binary or UTF-16", f"must be {kind} text in UTF-8 (save it as UTF-8)",
                         file=str(path))
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        raise InputError("(file)", f"byte 0x{raw[exc.start]:02x} on line {line}",
                         f"not UTF-8: must be {kind} text in UTF-8 (save it as UTF-8)", file=str(path)) from None


def _dataset(h5, key: str, path: Path):
    try:
        return h5[key][()]
    except KeyError:
        raise InputError(key, "missing", "a rotorlanding results.h5 holds scenario_json, time_s, states/q, "
                         "states/v, series/* and summary_json (file incomplete or from an older format?)",
                         file=str(path)) from None
    except (OSError, RuntimeError, ValueError) as exc:  # damaged chunk, bad filter data
        raise InputError(key, "unreadable", f"damaged results file ({str(exc).splitlines()[0][:120]})",
                         file=str(path)) from None


def read_results_guarded(path, parts=tuple(RESULT_PARTS), *, field: str = "results") -> dict:
    """Read a rotorlanding results.h5 like :func:`rotorlanding.results.read_results` (the same keys;
    only ``parts`` of them, plus ``attrs``), with every failure one :class:`InputError`."""
    import h5py

    path = Path(path)
    _check_file(path, field)
    try:
        with open(path, "rb") as fh:
            head = fh.read(8)
    except OSError as exc:
        raise InputError(field, str(path), f"cannot be read ({exc.strerror or exc})") from None
    if not head:
        raise InputError("(file)", "empty", "the file is empty; expected a results.h5 written by rotorlanding",
                         file=str(path))
    if head != _HDF5_SIGNATURE:
        # rotorlanding writes the superblock at offset 0; a zeroed or overwritten head, a text file
        # or a truncated download all fail here before the HDF5 library sees them
        raise InputError("(file)", f"starts with {head!r}", "not an HDF5 file (damaged head, or not a results.h5 "
                         "written by rotorlanding)", file=str(path))
    try:
        h5 = h5py.File(path, "r")
    except (OSError, RuntimeError, ValueError) as exc:
        raise InputError("(file)", "unreadable HDF5", f"damaged or truncated ({str(exc).splitlines()[0][:120]})",
                         file=str(path)) from None
    with h5:
        try:
            attrs = dict(h5.attrs)
        except (OSError, RuntimeError, ValueError, KeyError) as exc:
            raise InputError("(attributes)", "unreadable", f"damaged results file ({str(exc)[:120]})",
                             file=str(path)) from None
        if attrs.get("package") != "rotorlanding":
            raise InputError("package", attrs.get("package"), "not a results file of rotorlanding (written by "
                             "another program?); give a results.h5 written by `rotorlanding run`", file=str(path))
        out = {"attrs": attrs}
        for part in parts:
            key = RESULT_PARTS[part]
            if part == "series":
                grp = h5.get(key)
                if not isinstance(grp, h5py.Group):
                    raise InputError(key, "missing", "a rotorlanding results.h5 holds the group series/*",
                                     file=str(path))
                out["series"] = {k: _dataset(h5, f"{key}/{k}", path) for k in grp}
                continue
            value = _dataset(h5, key, path)
            if part in ("scenario", "summary"):
                try:
                    value = json.loads(value)
                except (TypeError, ValueError, UnicodeDecodeError):
                    raise InputError(key, "not JSON", "damaged results file", file=str(path)) from None
                if not isinstance(value, dict):
                    raise InputError(key, type(value).__name__, "must hold a JSON table", file=str(path))
            elif part == "q":
                try:
                    out["names"] = json.loads(h5[key].attrs["names"])
                except (KeyError, TypeError, ValueError, OSError):
                    raise InputError(f"{key}.names", "missing", "damaged results file (coordinate names)",
                                     file=str(path)) from None
            out[part] = value
    t = out.get("time_s")
    if t is not None:
        t = np.asarray(t)
        if t.ndim != 1 or t.dtype.kind != "f":
            raise InputError("time_s", f"shape {t.shape}", "must be a 1-D float array", file=str(path))
        for part in ("q", "v"):
            if part in out and (np.ndim(out[part]) != 2 or len(out[part]) != len(t)):
                raise InputError(RESULT_PARTS[part], f"shape {np.shape(out[part])}",
                                 f"must have one row per time_s sample ({len(t)})", file=str(path))
    return out


def _cell(text: str, name: str, row: int, path: Path) -> float:
    s = text.strip()
    if s == "" or s.lower() == "nan":
        return math.nan  # a channel without a sample at this time (different sampling rates)
    try:
        return float(s)
    except ValueError:
        raise InputError(name, s, f"row {row}: must be a number (empty or NaN where a channel has no sample)",
                         file=str(path)) from None


def read_columns(path) -> dict[str, np.ndarray]:
    """Columns (name -> 1-D float array) of a measured-data CSV (header of channel names, then
    numbers) or MATLAB .mat file (one variable per channel)."""
    path = Path(path)
    _check_file(path, "--measured")
    if path.suffix.lower() == ".mat":
        from scipy.io import loadmat

        try:
            raw = loadmat(path)
        except Exception as exc:  # scipy raises ValueError, TypeError, OSError, MatReadError... on damage
            raise InputError("(file)", "unreadable .mat", f"must be a MATLAB .mat file (v4-v7.2) with one numeric "
                             f"variable per channel ({str(exc).splitlines()[0][:120] if str(exc) else type(exc).__name__})",
                             file=str(path)) from None
        cols = {}
        for k, v in raw.items():
            if k.startswith("__"):
                continue
            arr = np.asarray(v)
            if arr.dtype.kind not in "iuf" or arr.size == 0 or (arr.ndim == 2 and min(arr.shape) > 1):
                raise InputError(k, f"{arr.dtype} {arr.shape}", "must be a numeric vector (one channel)",
                                 file=str(path))
            cols[k] = arr.astype(float).ravel()
        return cols
    text = read_text(path, kind="CSV", field="--measured")
    lines = text.splitlines()
    # as numpy.genfromtxt did before: '#' starts a comment in the data rows
    rows = list(csv.reader([lines[0]] + [ln.split("#", 1)[0] for ln in lines[1:]]))
    names = [h.strip() for h in rows[0]]
    if len(set(names)) != len(names) or "" in names:
        raise InputError("(csv header)", ",".join(names), "channel names must be unique and non-empty",
                         file=str(path))
    data = []
    for i, row in enumerate(rows[1:], start=2):
        if not row or not any(c.strip() for c in row):
            continue
        if len(row) != len(names):
            raise InputError("(csv)", f"{len(row)} columns on line {i}", f"the header names {len(names)}",
                             file=str(path))
        data.append([_cell(c, names[j], i, path) for j, c in enumerate(row)])
    if not data:
        raise InputError("(csv)", "no data rows", "a header line and then one row of numbers per sample",
                         file=str(path))
    arr = np.array(data, float)
    return {n: arr[:, j] for j, n in enumerate(names)}

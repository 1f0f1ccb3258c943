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

A coast-down (``rotorlanding coastdown``, :mod:`rotorlanding.coastdown`) writes the same datasets
as resizable, appended chunk by chunk (decimated, irregular ``time_s``), plus attrs ``kind =
"coastdown"``, ``/coastdown_json``, ``/coastdown/chunks/*`` and ``/coastdown/restart``.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
from pathlib import Path

import numpy as np

from . import __version__
from .safeio import WriteError, fault, fsync_dir, fsync_path, h5_guard, new_h5, tmp_name, unlink_quietly

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
    h5.attrs["created_utc"] = _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")
    held.append(h5.create_dataset("scenario_json", data=json.dumps(scenario_raw)))
    held.append(h5.create_dataset("time_s", data=np.asarray(t)))
    held[-1].attrs["unit"] = "s"
    g = h5.create_group("states")
    for key, arr, vel in (("q", q, False), ("v", v, True)):
        ds = g.create_dataset(key, data=np.asarray(arr), compression="gzip", compression_opts=4)
        cu = coordinate_units(names)
        if vel:
            cu = [u.replace("rad", "rad/s") if u == "rad" else (u + "/s") for u in cu]
        ds.attrs["names"] = json.dumps(names)
        ds.attrs["units"] = json.dumps(cu)
        held.append(ds)
    s = h5.create_group("series")
    for name, arr in series.items():
        ds = s.create_dataset(name, data=np.asarray(arr), compression="gzip", compression_opts=4)
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
               "summary": json.loads(h5["summary_json"][()])}
    return out

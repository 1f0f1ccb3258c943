"""The gap diagnose calibrates on, scanned finely over one parameter, for one bench case (issue 20,
session 47: why does the four-record ``param_mu_rad_0.3`` case fit mu_rad = 0.208 (gap 1.20) when
the truth 0.3 gives 0.672?).

The case's records are rebuilt as ``benchmarks/diagnose_bench.py --repeats R`` builds them (the
same seeds, ``diagnose_bench.write_records``), read as the bench reads them
(``records_for_diagnosis`` / ``measured_for_diagnosis``), and the model is the one diagnose builds
from them (:class:`rotorlanding.diagnose_run._Simulator` with the records' sensor model: R drops
over the disc, each read 8 times). The scan's gap at the scenario's own value must equal the
bench's "gap before" (a check that this is diagnose's landscape, printed).

usage: RECORDS=4 python docs/studies/diagnose_param_scan.py CASE KEY LO HI N [--log] [--ensemble M]
       [--set KEY=VALUE ...] [--scatter-scales] [--out scan.json]
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "benchmarks"))


def build(name: str, records: int, workers: int = 2, ensemble: int | None = None, scatter: bool = False):
    """The case and the simulator diagnose builds for its records (``ensemble``: the model's drops
    per variant; None: as diagnose, as many as records)."""
    import diagnose_bench as B
    from sensor_model import THRUST, known_rig_model

    from rotorlanding.diagnose_run import (DEFAULT_JOURNALS, Point, _journal_rows, _Simulator, measured_for_diagnosis,
                                           records_for_diagnosis, records_sensor_model)
    from rotorlanding.features import ensemble_features

    allc = B.cases()
    names = [c["case"] for c in allc]
    if name not in names:
        raise SystemExit(f"diagnose_param_scan.py: unknown case {name!r}; the bench's cases: {', '.join(names)}")
    i = names.index(name)
    case = allc[i]
    tmp = Path(tempfile.mkdtemp())
    model = known_rig_model(tmp / f"{name}.toml", case["off"], extra=THRUST if case["thrust"] else "")
    sen = B.sensor(i, case)
    recs = B.write_records(i, case, model, tmp, sen, records)
    if records == 1:
        clearance, _, meas, info = measured_for_diagnosis(model, recs[0], [], None)
        feats = meas
    else:
        clearance, _, meas, info = records_for_diagnosis(model, recs, [])
        feats = ensemble_features(meas.features)
    noise = records_sensor_model(info["sensor_noise"], info["sampling_rate_hz"], info["channels"])
    sim = _Simulator(model, [Point("", [], _journal_rows(feats, DEFAULT_JOURNALS))], clearance, workers, [],
                     ensemble=ensemble or records, records=records, as_recorded=noise,
                     scatter=scatter)
    return case, sim


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case")
    ap.add_argument("key")
    ap.add_argument("lo", type=float)
    ap.add_argument("hi", type=float)
    ap.add_argument("n", type=int)
    ap.add_argument("--log", action="store_true", help="log-spaced values")
    ap.add_argument("--ensemble", type=int, default=None,
                    help="the model's drops per variant (default: as diagnose, as many as records)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="also set this in every variant (e.g. effects.axial_rub=true, to scan an effect's parameter)")
    ap.add_argument("--scatter-scales", action="store_true", help="diagnose --scatter-scales (session 48)")
    ap.add_argument("--out", default=None)
    a = ap.parse_args(argv)
    records = int(os.environ.get("RECORDS", "4"))
    values = (np.geomspace if a.log else np.linspace)(a.lo, a.hi, a.n)
    case, sim = build(a.case, records, ensemble=a.ensemble, scatter=a.scatter_scales)
    try:
        g0 = sim.gap([])[0]
        print(f"{a.case}, {records} record(s): the model as it is, gap {g0:.3f}", flush=True)
        res = sim.gaps([[*a.set, f"{a.key}={float(v)!r}"] for v in values])
    finally:
        sim.close()
    rows = [{"value": float(v), "gap": float(g),
             "top": sorted(((r["feature"], round(r["distance"], 2)) for r in rows_), key=lambda x: -x[1])[:3]}
            for v, (g, rows_, _, _) in zip(values, res)]
    for r in rows:
        print(f"{a.key} = {r['value']:.4g}: gap {r['gap']:.3f}  {r['top']}", flush=True)
    if a.out:
        from rotorlanding.safeio import atomic_write_text

        atomic_write_text(Path(a.out), json.dumps({"case": a.case, "records": records, "key": a.key,
                                                   "ensemble": a.ensemble or records, "sets": a.set, "scatter_scales": a.scatter_scales,
                                                   "truth_sets": case["sets"], "gap_as_is": g0, "scan": rows},
                                                  indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

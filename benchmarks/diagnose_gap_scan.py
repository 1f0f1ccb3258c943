"""Is the diagnose gap smooth in a parameter? (issue 20, point 1: the needle landscape)

A "measured" landing from our own sensor model (tests/sensor_model.py: 4 kHz, random phase, 1 um /
2 rpm noise, pre-trigger) of the known rig with radial friction mu_rad = 0.22, against the same model
at a scan of mu_rad: the gap of one drop per value (the features of one chaotic trajectory) and of
an ensemble per value (``diagnose --ensemble N --ensemble-radius-m R``: features as means over drops
from a circle). Prints both scans and the number of interior local minima of each; writes JSON
(atomically) with --out.

usage: python benchmarks/diagnose_gap_scan.py [--mu 0.05,0.1,...] [--ensemble 8] [--radius-m 3e-5]
       [--workers 2] [--records 4] [--as-recorded] [--out scan.json]
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))


def local_minima(g: list[float]) -> int:
    return sum(1 for i in range(1, len(g) - 1) if g[i] < g[i - 1] and g[i] < g[i + 1])


def significant_minima(g: list[float], se: list[float], z: float = 2.0) -> int:
    """Interior local minima whose well is deeper, on both sides, than ``z`` standard errors of
    the difference of the two gaps (hypot of their errors): a ripple inside the gaps' own noise is
    no second basin (session 25: 1.35 / 1.37 beside 1.70, an ensemble's 0.02 ripple)."""
    return sum(1 for i in range(1, len(g) - 1)
               if all(g[j] - g[i] > z * (se[i] ** 2 + se[j] ** 2) ** 0.5 for j in (i - 1, i + 1)))


def one_basin(g: list[float], se: list[float], z: float = 2.0) -> bool:
    """Whether the scan falls to its lowest point and rises after it, every step against that
    direction smaller than ``z`` standard errors of the difference of its two gaps (a ripple
    within the noise is allowed, a second well beyond it is not; with errors 0 any rise before
    the minimum, or fall after it, breaks the basin)."""
    k = min(range(len(g)), key=g.__getitem__)
    tol = [z * (se[i] ** 2 + se[i + 1] ** 2) ** 0.5 for i in range(len(g) - 1)]
    return (all(g[i + 1] - g[i] <= tol[i] for i in range(k))
            and all(g[i] - g[i + 1] <= tol[i] for i in range(k, len(g) - 1)))


def jackknife_se(leave_one_out: list[float]) -> float:
    """Jackknife standard error of a statistic from its n leave-one-out values (Efron & Tibshirani,
    An Introduction to the Bootstrap, ch. 11): sqrt((n - 1) / n sum (g_i - mean g)^2)."""
    n = len(leave_one_out)
    m = sum(leave_one_out) / n
    return ((n - 1) / n * sum((x - m) ** 2 for x in leave_one_out)) ** 0.5


def scan(mus, ensemble: int, radius_m: float, workers: int, truth: float = 0.22, t_end: float = 0.3,
         records: int = 1, as_recorded: bool = False) -> dict:
    """``records`` > 1: the "measurement" is that many records of repeated landings, each dropped
    from its own random point within 5 um (seeded), compared as their mean features (diagnose's
    ``Repeated``) with the model's ensembles (``ensemble`` drops of radius ``radius_m``).
    ``as_recorded``: every model drop read 8 times through the records' sensor model (the last
    record's; ``_Simulator.as_recorded``, seeds common to every mu), diagnose's reads since session
    46. Not quite diagnose's comparison: the drops stay on this scan's circle, and the ensemble is
    the mean of each drop's mean read (diagnose: one mean over drops and reads)."""
    import numpy as np
    from sensor_model import C, known_rig_model, write_record

    from rotorlanding.diagnose_run import Point, _Simulator, measured_for_diagnosis, records_sensor_model
    from rotorlanding.ensemble import drop_offsets, random_drop_offset
    from rotorlanding.features import ensemble_features, gap_points

    with tempfile.TemporaryDirectory() as tmp:
        model = known_rig_model(Path(tmp) / "model.toml", ["windage"], t_end=t_end)
        if records == 1:
            write_record(model, [f"contact.mu_rad={truth!r}"], Path(tmp) / "rig.csv", clearance=C, seed=3)
            _, _, meas, info = measured_for_diagnosis(model, Path(tmp) / "rig.csv", [], None)
        else:
            rng, feats = np.random.default_rng(3), []
            for k in range(records):
                write_record(model, [f"contact.mu_rad={truth!r}"] + random_drop_offset(rng), Path(tmp) / f"rig{k}.csv",
                             clearance=C, seed=3 + k)
                _, _, f, info = measured_for_diagnosis(model, Path(tmp) / f"rig{k}.csv", [], None)
                feats.append(f)
            meas = ensemble_features(feats)
        out = {"mu_rad": list(mus), "truth": truth, "ensemble": ensemble, "radius_m": radius_m, "records": records,
               "as_recorded": as_recorded}
        sensor = records_sensor_model(info["sensor_noise"], info["sampling_rate_hz"], info["channels"])
        sim = _Simulator(model, [Point("", [], meas)], C, workers, [], as_recorded=sensor if as_recorded else None)
        try:
            out["single"] = [r[0] for r in sim.gaps([[f"contact.mu_rad={mu!r}"] for mu in mus])]
            # the ensemble's drops landed one by one (the same drop points as diagnose --ensemble), so
            # that each ensemble gap also gets its jackknife error over the drops
            offs = drop_offsets(ensemble, radius_m)
            drops = sim.features([[f"contact.mu_rad={mu!r}"] + o for mu in mus for o in offs])
        finally:
            sim.close()
        out["ensemble"], out["ensemble_se"] = [], []
        for i in range(len(mus)):
            d = [x[0] for x in drops[i * ensemble:(i + 1) * ensemble]]
            if any("__error__" in x for x in d):  # a landing that failed: no gap (as diagnose's)
                out["ensemble"].append(float("inf"))
                out["ensemble_se"].append(float("inf"))
                continue
            gap = gap_points([meas], [ensemble_features(d)])[0]
            loo = [gap_points([meas], [ensemble_features(d[:k] + d[k + 1:])])[0] for k in range(ensemble)]
            out["ensemble"].append(gap)
            out["ensemble_se"].append(jackknife_se(loo))
        for label in ("single", "ensemble"):
            out[label + "_local_minima"] = local_minima(out[label])
        out["ensemble_significant_minima"] = significant_minima(out["ensemble"], out["ensemble_se"])
        out["ensemble_one_basin"] = one_basin(out["ensemble"], out["ensemble_se"])
        out["single_one_basin"] = one_basin(out["single"], [0.0] * len(mus))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mu", default="0.05,0.1,0.15,0.2,0.22,0.25,0.3,0.4,0.5")
    ap.add_argument("--ensemble", type=int, default=8)
    ap.add_argument("--radius-m", type=float, default=3e-5)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--records", type=int, default=1,
                    help="records of repeated landings as the measurement (default 1: one record, dropped centred)")
    ap.add_argument("--as-recorded", action="store_true",
                    help="the model's drops read through the records' sensor model, as diagnose compares them")
    ap.add_argument("--out", default=None)
    a = ap.parse_args(argv)
    res = scan([float(x) for x in a.mu.split(",")], a.ensemble, a.radius_m, a.workers, records=a.records,
               as_recorded=a.as_recorded)
    for label in ("single", "ensemble"):
        print(f"{label:8s}: " + " ".join(f"{g:.2f}" for g in res[label]) + f"  (local minima {res[label + '_local_minima']})")
    print("  s.e.  : " + " ".join(f"{g:.2f}" for g in res["ensemble_se"])
          + f"  (ensemble minima beyond 2 s.e. of the difference: {res['ensemble_significant_minima']})")
    if a.out:
        from rotorlanding.safeio import atomic_write_text

        atomic_write_text(a.out, json.dumps(res, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""Session-18 study (issue 15, point 4): what a backward calibration on the frequency alone predicts
of the rest of Table 1 (onset, DE vertical displacement max and min).

It reads the output of the worn-bearing calibration (`rotorlanding calibrate
scenarios/calibration/worn_bearing.toml --out DIR`: its calibration.csv, one row per design, each landed as the
backward scenario's ensemble) and applies the rule `rotorlanding validate` reports on the stored worn fit
(`rotorlanding.validate.frequency_only_backward`, since session 42): a calibration on the frequency alone cannot
reject a design whose ensemble whirls backward in >= 7 of 8 drops with its median frequency inside Table 1's band;
the design nearest 49 Hz is the point such a fit would report. The rule lives in validate; this script only reads
another run's CSV. `docs/studies/backward_frequency_only/` keeps session 18's output (its own, older format).

usage (from the repository root):
    python docs/studies/backward_frequency_only.py DIR [--json OUT.json]"""
import argparse
import csv
import json
import sys
from pathlib import Path

from rotorlanding.safeio import atomic_write_text
from rotorlanding.validate import _fmt, frequency_only_backward


def _value(x):
    # calibration.csv holds every field as text: numbers back to floats, the rest (directions) as they are
    if x in (None, "", "None"):
        return None
    try:
        return float(x)
    except ValueError:
        return x


def designs(out_dir) -> list[dict]:
    path = Path(out_dir) / "calibration.csv"
    if not path.is_file():
        raise SystemExit(f"{path}: not found: give the --out folder of `rotorlanding calibrate "
                         "scenarios/calibration/worn_bearing.toml`")
    with open(path, encoding="utf-8") as fh:
        return [{k: _value(v) for k, v in row.items()} for row in csv.DictReader(fh)]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir")
    ap.add_argument("--json", default=None)
    a = ap.parse_args(argv)
    res = frequency_only_backward(designs(a.dir))
    if res is None:
        raise SystemExit(f"{a.dir}/calibration.csv: no design whirls backward inside Table 1's frequency band")
    fit = res["fit"]
    print(f"{res['admissible']} of {res['designs']} designs whirl backward inside {res['frequency_hz']:g} "
          f"+/- {res['frequency_band_hz']:.2g} Hz (a frequency-only calibration cannot reject them); the one nearest "
          f"the target: T_w {fit['worn_drag_torque_n_m']:.3g} N m, growth {fit['growth_angle_rad']:.3g} rad, "
          f"{fit['frequency_hz']:.1f} Hz")
    print("| Table 1 | frequency-only fit | admissible designs: min / max | inside the band |")
    print("|---|---|---|---|")
    for r in res["rows"].values():
        print(f"| {r['name']} [{r['unit']}] | {_fmt(r['fit'], r['scale'])} | {_fmt(r['min'], r['scale'])} / "
              f"{_fmt(r['max'], r['scale'])} | {r['in_band']} of {r['n']} |")
    if a.json:
        atomic_write_text(Path(a.json), json.dumps(res, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Wall time of ``rotorlanding diagnose`` as a user runs it (its defaults: 2 workers, maxiter 10), on
one-record, one-effect cases of the diagnose bench (benchmarks/diagnose_bench.py: the same record and
model files), with the default model drops and with ``--ensemble 1``, one after the other in one run,
so the ratio is measured on the same machine state. The issue 20 limit is 3 minutes per one-effect,
one-point case.

usage: python benchmarks/diagnose_command_time.py [--only CASE,...] [--out F.md]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "benchmarks"))

DEFAULT_CASES = "single_windage_strong,single_outer_race_coulomb_strong"


def main(argv=None) -> int:
    import diagnose_bench as bench
    from sensor_model import THRUST, known_rig_model

    from rotorlanding.safeio import atomic_write_text

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default=DEFAULT_CASES, help=f"comma-separated bench cases (default {DEFAULT_CASES})")
    ap.add_argument("--out", default=None, help="markdown table to write (default: print only)")
    a = ap.parse_args(argv)
    wanted = a.only.split(",")
    all_cases = bench.cases()
    unknown = [c for c in wanted if c not in {k["case"] for k in all_cases}]
    if unknown:
        print(f"--only: unknown case {unknown[0]!r}; see benchmarks/diagnose_bench.py --list", file=sys.stderr)
        return 2
    lines = ["| case (one record) | `--ensemble 1` [s] | default [s] | ratio | named (default) | gap (default) |",
             "|---|---|---|---|---|---|"]
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for i, case in enumerate(all_cases):
            if case["case"] not in wanted:
                continue
            model = known_rig_model(tmp / f"{case['case']}.toml", case["off"], extra=THRUST if case["thrust"] else "")
            rec = bench.write_records(i, case, model, tmp, bench.sensor(i, case), 1)[0]
            walls, reps = {}, {}
            for label, extra in (("one", ["--ensemble", "1"]), ("default", [])):
                out = tmp / f"{case['case']}_{label}"
                t0 = time.perf_counter()
                subprocess.run([sys.executable, "-m", "rotorlanding", "diagnose", "--measured", str(rec),
                                "--scenario", str(model), "--out", str(out), *extra], check=True,
                               stdout=subprocess.DEVNULL)
                walls[label] = time.perf_counter() - t0
                reps[label] = json.loads((out / "report.json").read_text())
            d = reps["default"]
            lines.append(f"| {case['case']} | {walls['one']:.1f} | {walls['default']:.1f} | "
                         f"{walls['default'] / walls['one']:.2f} | {d['named_effect'] or '-'} (drops: {d['ensemble']}) | "
                         f"{d['gap_before']:.3g} -> {d['gap_after']:.3g} |")
            print(lines[-1], flush=True)
    if a.out:
        atomic_write_text(Path(a.out), "\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

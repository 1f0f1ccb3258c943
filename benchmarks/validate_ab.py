"""`rotorlanding validate` wall time, two code trees side by side (issue 21: "validate in <= 30 s").

Each run is a fresh process, ``python -m rotorlanding validate`` with ``--a-tree`` / ``--b-tree``
first on PYTHONPATH, into a temporary folder (deleted after the run: a validate writes ~1 GB of
results.h5). The trees alternate, ``--repeat`` times; reported per run: the 1-min load average at
its start, the wall time, and the report's check count. The two reports must be equal apart from
their run-time line (printed: SAME or the differing lines).

usage: python benchmarks/validate_ab.py --a-tree DIR [--b-tree DIR (default: this checkout)] [--repeat 2]
           [--python PY] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def one(tree: Path, python: str) -> dict:
    tmp = Path(tempfile.mkdtemp(prefix="validate_ab_"))
    try:
        (tmp / "pub").mkdir()
        load = os.getloadavg()[0]
        env = {**os.environ, "PYTHONPATH": str(tree)}
        t0 = time.perf_counter()
        p = subprocess.run([python, "-m", "rotorlanding", "validate", "--out", str(tmp / "out"), "--publish",
                            str(tmp / "pub")], cwd=tree, env=env, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        report = (tmp / "pub" / "validation.md").read_text() if (tmp / "pub" / "validation.md").exists() else ""
        m = re.search(r"(\d+) of (\d+) checks pass", report)
        return {"tree": str(tree), "load": load, "wall_s": wall, "exit": p.returncode,
                "checks": m.group(0) if m else None,
                "report": "\n".join(line for line in report.splitlines() if not line.startswith("Run time"))}
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--a-tree", required=True, type=Path)
    ap.add_argument("--b-tree", type=Path, default=ROOT)
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--python", default=sys.executable)
    ap.add_argument("--json", type=Path)
    a = ap.parse_args(argv)
    runs = []
    for r in range(a.repeat):
        for name, tree in (("A", a.a_tree), ("B", a.b_tree)):
            x = one(tree.resolve(), a.python)
            runs.append({"variant": name, "run": r + 1, **x})
            print(f"{name} run {r + 1}: {x['wall_s']:.1f} s wall, load {x['load']:.2f}, exit {x['exit']}, {x['checks']}",
                  flush=True)
    best = {v: min(x["wall_s"] for x in runs if x["variant"] == v) for v in ("A", "B")}
    print(f"best of {a.repeat}: A {best['A']:.1f} s, B {best['B']:.1f} s, B / A = {best['B'] / best['A']:.3f}")
    reports = {x["report"] for x in runs}
    print("reports: SAME" if len(reports) == 1 else f"reports: {len(reports)} DIFFERENT versions")
    if a.json:
        a.json.write_text(json.dumps({"runs": [{k: v for k, v in x.items() if k != "report"} for x in runs],
                                      "best_s": best}, indent=1))
    return 0 if len(reports) == 1 and all(x["exit"] == 0 for x in runs) else 1


if __name__ == "__main__":
    sys.exit(main())

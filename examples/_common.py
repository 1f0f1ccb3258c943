"""Shared bits of the examples: the command line (--short, --out) and the repository's paths."""

import argparse
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCENARIOS = ROOT / "scenarios"


def arguments(doc: str, name: str, argv=None):
    p = argparse.ArgumentParser(description=doc.strip().splitlines()[0])
    p.add_argument("--short", action="store_true", help="a short version (seconds; what the test suite runs)")
    p.add_argument("--out", default=str(Path("out") / "examples" / name), help="folder for figures and results")
    args = p.parse_args(argv)
    args.out = Path(args.out)
    args.out.mkdir(parents=True, exist_ok=True)
    return args

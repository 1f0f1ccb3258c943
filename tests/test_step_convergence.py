"""Step-size convergence of the landing model (slow: run with `pytest -m slow`).

Acceptance rule: halving the default step (5e-5 s) changes the peak contact force by < 5 % and
the whirl frequency by < 1 %. Recorded figures (0.5 s, this machine): radial landing peak force
-0.47 %; combined landing (4 kN thrust, forward whirl at 82.6 Hz) peak force -1.9 %, whirl
frequency 0.00 %.
"""

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))


@pytest.mark.slow
@pytest.mark.parametrize("sets, whirl", [([], False), (["axial.f_thrust=4000.0", "amb.drop_axial=true"], True)])
def test_halving_the_default_step(tmp_path, sets, whirl):
    import json

    import step_convergence

    out = tmp_path / "conv.json"
    args = [str(ROOT / "scenarios" / "landing_7000rpm.toml"), "--t-end", "0.5", "--steps", "5e-5,2.5e-5",
            "--json", str(out)]
    for s in sets:
        args += ["--set", s]
    step_convergence.main(args)
    coarse, fine = json.loads(out.read_text())
    assert coarse["complete"] and fine["complete"]
    assert coarse["peak_force_change_on_halving"] < 0.05
    if whirl:
        assert coarse["whirl"] == fine["whirl"] != "none"
        assert coarse["whirl_change_on_halving"] < 0.01

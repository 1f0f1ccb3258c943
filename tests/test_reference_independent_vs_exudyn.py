"""Exudyn landing model vs the independent scipy reference (rotorlanding.reference_independent)
over the first 50 ms of a drop: journal motion, rotor speed, race spins (and the axial motion for
the combined landing).

Exudyn runs at solver.step = 1e-5 s: at the scenario's 5e-5 s its own time-discretisation error
is 4-12 um on the journal over 50 ms (2nd order: 0.25-0.8 um at 1e-5 s), above the 3 um tolerance.
The reference at rtol 1e-7 differs from rtol 1e-8 by < 1e-4 um, so its error is negligible here.
"""

from pathlib import Path

import numpy as np
import pytest

from rotorlanding.exudyn_model import SolverSettings, build_exudyn, collect, solve
from rotorlanding.landing import build_spec
from rotorlanding.reference_independent import simulate_reference
from rotorlanding.scenario import load_scenario

SCEN = Path(__file__).resolve().parents[1] / "scenarios" / "landing_7000rpm.toml"
T_END = 0.05
STEP = 1e-5
JOURNAL_TOL = 3e-6          # m


#: the combined drop at half the step: on the session-28 rig rotor its DE journal's second impact (35-46 ms)
#: amplifies the step's error; at 1e-5 s the journals differ from the reference by 4.0 um, at 5e-6 s by 1.2 um
#: (3.4x less for half the step: the integrator's order, so the equations agree and the step sets the rest)
CASE_STEP = {"radial": STEP, "combined": STEP / 2}


@pytest.mark.parametrize("case, sets", [
    ("radial", []),
    ("combined", ["axial.f_thrust=4000.0", "amb.drop_axial=true"]),
])
def test_exudyn_matches_independent_reference(case, sets):
    sc = load_scenario(SCEN, sets + [f"solver.step={CASE_STEP[case]}", "solver.output_period=1e-4"])
    spec = build_spec(sc)
    model = build_exudyn(spec)
    ok, msg, _ = solve(model, 0.0, T_END, SolverSettings.from_spec(spec))
    assert ok, msg
    t, q, v = collect(model)
    tr, qr, vr = simulate_reference(spec, T_END, t_eval=t, rtol=1e-7, atol=1e-10)
    assert np.allclose(tr, t)

    for b in spec.bearings:
        s = b.i_station
        err = np.max(np.hypot(q[:, s] - qr[:, s], q[:, s + 1] - qr[:, s + 1]))
        assert err < JOURNAL_TOL, f"{case} {b.name}: journal differs by {err * 1e6:.2f} um"
        assert np.min(qr[:, s + 1]) < -0.9 * b.params.clearance, f"{b.name} did not land within 50 ms"

    omega0 = sc.omega0
    it = spec.i_theta
    err_w = np.max(np.abs(v[:, it] - vr[:, it]))
    assert err_w < 1e-3 * omega0, f"{case}: rotor speed differs by {err_w:.4f} rad/s"
    for b in spec.bearings:
        i = b.i_race + 2
        err_r = np.max(np.abs(v[:, i] - vr[:, i]))
        assert err_r < 0.02 * omega0, f"{case} {b.name}: race spin differs by {err_r:.3f} rad/s"
        assert np.max(np.abs(vr[:, i])) > 0.05 * omega0, f"{b.name}: race was not spun up"

    ix = spec.i_axial
    if case == "combined":
        # the rotor reached the axial face (axial force and face friction active)
        assert np.max(np.abs(qr[:, ix])) > sc.axial.cl_ax
        assert np.max(np.abs(q[:, ix])) > sc.axial.cl_ax
        err_x = np.max(np.abs(q[:, ix] - qr[:, ix]))
        assert err_x < 1e-6, f"axial motion differs by {err_x * 1e6:.3f} um"
    else:
        assert np.max(np.abs(q[:, ix])) < 1e-9 and np.max(np.abs(qr[:, ix])) < 1e-9

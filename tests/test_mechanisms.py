"""The mechanism registry and output schema (rotorlanding.mechanisms): every series a run writes is
declared once with its unit, an effect that is off leaves its series and energy entries at zero,
the force on the rotor at a bearing is the sum of the outputs declared on the rotor, and the
coast-down's compiled normal force is the radial contact law's."""

import math
from pathlib import Path

import numpy as np
import pytest

from user_forces.radial_contact import radial_contact

from rotorlanding import mechanisms as mech
from rotorlanding.bearing_kernel import contact_normal_forces
from rotorlanding.landing import build_spec
from rotorlanding.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[1]
FORWARD = ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml"


def _states(spec, n=40, seed=3):
    """Random states around the static start, journals pushed into their races (some contact)."""
    rng = np.random.default_rng(seed)
    q0, v0 = spec.initial_state()
    q = q0 + 2e-5 * rng.standard_normal((n, spec.n))
    v = v0 + 1e-2 * rng.standard_normal((n, spec.n))
    for b in spec.bearings:
        q[:, b.i_station + 1] -= b.laws.clearance * rng.uniform(0.5, 1.2, n)
    t = np.linspace(0.0, 1e-3 * (n - 1), n)
    return t, q, v


@pytest.fixture(scope="module")
def forward():
    return build_spec(load_scenario(FORWARD))


def test_every_series_is_declared_once_with_a_unit(forward):
    t, q, v = _states(forward)
    series = mech.evaluate(forward, t, q, v)
    units = mech.series_units(forward.bearing_names)
    assert list(series) == list(units)       # same names, same order: the schema is what is written
    assert all(u for u in units.values())
    assert units["DE_contact_force_y_n"] == "N" and units["NDE_drag_torque_nm"] == "N m"
    assert units["DE_slip_velocity_m_s"] == "m/s" and units["dissipated_windage_j"] == "J"
    # every energy entry of the registry has its power and its integral, nothing else is an entry
    for e in mech.dissipation_entries():
        assert units["power_" + e + "_w"] == "W" and units["dissipated_" + e + "_j"] == "J"
    assert {k[len("power_"):-2] for k in units if k.startswith("power_")} == set(mech.dissipation_entries())


def test_an_effect_that_is_off_contributes_nothing():
    spec_on = build_spec(load_scenario(FORWARD))
    spec_off = build_spec(load_scenario(FORWARD, ["effects.ball_drag=false", "effects.axial_rub=false",
                                                  "effects.windage=false"]))
    t, q, v = _states(spec_on)
    a = spec_on.scenario.axial
    # the face carries load: the rotor pressed onto its thrust face, beyond the axial clearance
    q[:, spec_on.i_axial] = a.cl_ax + 0.5 * a.delta_m
    on, off = mech.evaluate(spec_on, t, q, v), mech.evaluate(spec_off, t, q, v)
    face = spec_on.axial_face_bearing().name
    for name in ("ball_drag", "axial_rub", "windage"):
        assert np.any(on["power_" + name + "_w"] > 0)        # on: it dissipates
        assert not np.any(off["power_" + name + "_w"])       # off: exactly zero
    assert np.any(on[face + "_rub_force_y_n"]) and not np.any(off[face + "_rub_force_y_n"])
    assert not np.any(off["DE_drag_torque_nm"]) and not np.any(off["NDE_drag_torque_nm"])
    # the mechanisms that were not switched are evaluated the same
    for k in ("DE_contact_force_y_n", "NDE_ball_force_z_n", "power_radial_friction_w", "axial_force_n"):
        np.testing.assert_array_equal(on[k], off[k])


def test_rotor_force_sums_the_outputs_declared_on_the_rotor(forward):
    t, q, v = _states(forward)
    a = forward.scenario.axial
    q[:, forward.i_axial] = a.cl_ax + 0.5 * a.delta_m
    s = mech.evaluate(forward, t, q, v)
    for b in forward.bearing_names:
        fy, fz = mech.rotor_force(s, b)
        np.testing.assert_array_equal(fy, s[b + "_contact_force_y_n"] + s[b + "_rub_force_y_n"])
        np.testing.assert_array_equal(fz, s[b + "_contact_force_z_n"] + s[b + "_rub_force_z_n"])


def test_compiled_normal_force_is_the_radial_contact_law(forward):
    t, q, v = _states(forward, n=200)
    fn = contact_normal_forces(forward, q, v)
    n_contact = 0
    for b, f in zip(forward.bearings, fn):
        L = b.laws
        s, r = b.i_station, b.i_race
        for k in range(len(t)):
            ref = radial_contact(q[k, s] - q[k, r], q[k, s + 1] - q[k, r + 1], v[k, s] - v[k, r],
                                 v[k, s + 1] - v[k, r + 1], 0.0, 0.0, L.clearance, L.k_hertz, L.exponent, L.k_visc,
                                 0.0, L.v_reg, L.sleeve_radius, L.race_radius)[4]
            assert f[k] == ref
            n_contact += ref > 0
    assert n_contact > 20     # the states do press the journals into their races
    # and it is F_N = delta^e (k + k_visc delta'), by hand at one contact sample
    b = forward.bearings[0]
    L, s, r = b.laws, b.i_station, b.i_race
    k = int(np.argmax(fn[0]))
    dy, dz = q[k, s] - q[k, r], q[k, s + 1] - q[k, r + 1]
    dist = math.hypot(dy, dz)
    rate = (dy * (v[k, s] - v[k, r]) + dz * (v[k, s + 1] - v[k, r + 1])) / dist
    assert fn[0][k] == pytest.approx((dist - L.clearance) ** L.exponent * (L.k_hertz + L.k_visc * rate), rel=1e-12)


def test_results_file_carries_the_schema_units(tmp_path):
    import h5py

    from rotorlanding.run import run_scenario

    sc = load_scenario(ROOT / "scenarios" / "paper" / "no_whirl_landing.toml", ["operating.t_end=0.01"])
    run_scenario(sc, tmp_path, progress=False, plots=False)
    units = mech.series_units(list(sc.bearings))
    with h5py.File(tmp_path / "results.h5") as h5:
        stored = {k: h5["series"][k].attrs["unit"] for k in h5["series"]}
    assert stored == units


def test_results_false_writes_the_same_summary_and_no_results_file(tmp_path):
    """An ensemble member that nothing reads back (validate's members outside its figure, study
    drops) keeps summary.json only: the summary is the one a full run writes, and an earlier run's
    results.h5 in the folder does not survive to pass as this run's."""
    import json

    from rotorlanding.run import run_scenario
    from rotorlanding.validate import FIGURE_CASES, _run_case

    sc = load_scenario(ROOT / "scenarios" / "paper" / "no_whirl_landing.toml", ["operating.t_end=0.01"])
    full = run_scenario(sc, tmp_path / "full", progress=False, plots=False)
    (tmp_path / "lean").mkdir()
    (tmp_path / "lean" / "results.h5").write_bytes(b"stale")
    lean = run_scenario(sc, tmp_path / "lean", progress=False, plots=False, results=False)
    assert (tmp_path / "full" / "results.h5").is_file() and not (tmp_path / "lean" / "results.h5").exists()
    strip = lambda s: {k: v for k, v in s.items() if k != "performance"}  # noqa: E731 (wall times differ)
    assert strip(lean) == strip(full)
    assert strip(json.loads((tmp_path / "lean" / "summary.json").read_text())) == strip(full)
    # validate: every job says whether it writes results.h5; the members of the figure's cases do
    from rotorlanding.validate import _ensemble_jobs

    jobs = _ensemble_jobs(tmp_path, 0.01, None)
    assert {j[0].rsplit("_drop", 1)[0] for j in jobs if j[-1]} == set(FIGURE_CASES)
    assert any(j[0].startswith("heldout_") for j in jobs) and not any(j[-1] for j in jobs if j[0].startswith("heldout_"))
    ens = tmp_path / "ensembles"
    for key, keep in ((f"{FIGURE_CASES[0]}_drop0", True), ("heldout_3000_drop3", False)):
        _run_case((key, "no_whirl_landing.toml", [], str(ens), 0.01, None, False, keep))
    assert (ens / f"{FIGURE_CASES[0]}_drop0" / "results.h5").is_file()
    assert not (ens / "heldout_3000_drop3" / "results.h5").exists()
    assert (ens / "heldout_3000_drop3" / "summary.json").is_file()


def test_radial_post_hook_books_each_power_and_force_in_its_series(tmp_path):
    """The compiled radial series feed the right outputs (a swap of the friction and damping powers
    would keep the energy balance): at samples in contact, the hook's series equal the law, and
    the two power series equal the law's friction and Hunt-Crossley powers summed over the bearings."""
    from rotorlanding.postprocess import evaluate
    from rotorlanding.run import simulate

    sc = load_scenario(ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml", ["operating.t_end=0.08"])
    spec, t, q, v, _ = simulate(sc, progress=False)
    ser = evaluate(spec, t, q, v)
    pre = spec.bearings[0].name + "_"
    hit = np.flatnonzero(ser[pre + "penetration_m"] > 0)
    assert hit.size > 10
    for k in hit[:: max(1, hit.size // 7)]:
        p_fric = p_damp = 0.0
        for b in spec.bearings:
            L, s, r = b.laws, b.i_station, b.i_race
            dy, dz = q[k, s] - q[k, r], q[k, s + 1] - q[k, r + 1]
            dvy, dvz = v[k, s] - v[k, r], v[k, s + 1] - v[k, r + 1]
            fy, fz, _, _, fn, delta, vs, pf = radial_contact(dy, dz, dvy, dvz, v[k, spec.i_theta], v[k, r + 2],
                                                             L.clearance, L.k_hertz, L.exponent, L.k_visc, L.mu_rad,
                                                             L.v_reg, L.sleeve_radius, L.race_radius)
            got = [ser[b.name + "_" + n][k] for n in ("contact_force_y_n", "contact_force_z_n", "normal_force_n",
                                                     "penetration_m", "slip_velocity_m_s")]
            assert got == pytest.approx([fy, fz, fn, delta, vs], rel=1e-12, abs=1e-15)
            p_fric += pf
            if delta > 0:
                p_damp += (fn - L.k_hertz * delta ** L.exponent) * (dy * dvy + dz * dvz) / math.hypot(dy, dz)
        assert ser["power_radial_friction_w"][k] == pytest.approx(p_fric, rel=1e-12)
        assert ser["power_contact_damping_w"][k] == pytest.approx(p_damp, rel=1e-9, abs=1e-9)
        assert p_fric > 0 and p_damp != 0.0

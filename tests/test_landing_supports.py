"""Supports that act in the landing (`[[rotor.supports]] in_landing = true`, e.g. the motor coupling):
parsed, added once, in force balance at rest and in the energy balance of a landing."""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from rotorlanding.errors import InputError
from rotorlanding.postprocess import evaluate, summarize
from rotorlanding.rotor import rotor_from_dict
from rotorlanding.run import simulate
from rotorlanding.scenario import load_scenario
from rotorlanding.timoshenko import GRAVITY, assemble, support_matrices, with_landing_supports

ROOT = Path(__file__).resolve().parents[1]
SCEN = ROOT / "scenarios" / "landing_7000rpm.toml"
STEEL = {"youngs_modulus": 2.1e11, "poisson_ratio": 0.3, "density": 7850.0}


def _rotor(supports):
    return rotor_from_dict({"rotor": {
        "materials": {"steel": STEEL},
        "sections": [{"length": 0.5, "outer_diameter": 0.05, "material": "steel", "elements": 5}],
        "stations": {"left": 0.0, "mid": 0.25, "right": 0.5},
        "supports": supports}})


def test_in_landing_is_off_unless_asked_and_checked():
    r = _rotor([{"station": "left", "kyy": 1e7, "kzz": 1e7}, {"station": "mid", "kyy": 2e6, "kzz": 3e6, "in_landing": True}])
    assert [s.in_landing for s in r.supports] == [False, True]
    with pytest.raises(InputError, match=r"in_landing"):
        _rotor([{"station": "mid", "kyy": 2e6, "in_landing": "yes"}])


def test_only_in_landing_supports_are_added_once():
    r = _rotor([{"station": "left", "kyy": 1e7, "kzz": 1e7}, {"station": "mid", "kyy": 2e6, "kzz": 3e6, "cyy": 50.0,
                                                           "in_landing": True}])
    fe = assemble(r)
    fl = with_landing_supports(fe)
    dk, dc = fl.K - fe.K, fl.C - fe.C
    iy, iz = fe.dof("mid", "y"), fe.dof("mid", "z")
    expected_k = np.zeros_like(dk)
    expected_k[iy, iy], expected_k[iz, iz] = 2e6, 3e6
    np.testing.assert_array_equal(dk, expected_k)
    assert dc[iy, iy] == 50.0 and np.count_nonzero(dc) == 1
    np.testing.assert_array_equal(fe.K, assemble(r).K)  # the free rotor is not changed in place
    # modal analysis takes every support once, landing ones included
    ks_all, _ = support_matrices(fe)
    ks_land, _ = support_matrices(fe, in_landing_only=True)
    np.testing.assert_array_equal(ks_land, expected_k)
    assert ks_all[fe.dof("left", "y"), fe.dof("left", "y")] == 1e7
    # none marked: the same object, so a rig without them is bit-for-bit the rig before
    plain = assemble(_rotor([{"station": "left", "kyy": 1e7, "kzz": 1e7}]))
    assert with_landing_supports(plain) is plain


def _landing(k_c, *sets, damping=0.0):
    """The 7000 rpm rig landing with the rig rotor's coupling entry at k_c, set the way a user sets it
    (``--set rotor.supports.2.kyy=...``); ``damping``: the rotor's mass-proportional damping [1/s]."""
    sc = load_scenario(SCEN, [f"rotor.supports.2.kyy={k_c}", f"rotor.supports.2.kzz={k_c}", *sets])
    coupling = sc.rotor.supports[2]
    assert coupling.station == "coupling" and coupling.in_landing and coupling.kzz == k_c
    return replace(sc, rotor=replace(sc.rotor, mass_proportional_damping=damping)) if damping else sc


@pytest.mark.parametrize("k_c, offset_z", [(0.0, 0.0), (2.0e6, 0.0), (2.0e6, -2.0e-4)])
def test_rotor_at_rest_is_in_force_balance_with_the_coupling(k_c, offset_z):
    """A non-rotating drop settles; then the weight is carried by the two catcher contacts and the
    coupling spring, -k_c times the coupling hub's displacement from the spring's rest point (on the
    levitated axis, or ``offset_z`` off it: a motor aligned with the rotor at rest on its catchers)
    (vertical force balance of the whole rotor, an independent check of the spring's sign and size)."""
    sc = _landing(k_c, "operating.speed_rpm=0", "operating.t_end=0.4", "effects.windage=false",
                  f"rotor.supports.2.offset_z={offset_z}", damping=40.0)
    spec, t, q, v, info = simulate(sc, progress=False)
    assert info["complete"]
    series = evaluate(spec, t, q, v)
    node = spec.fe.station_nodes["coupling"]
    z_c = float(spec.cb.T[4 * node + 1] @ q[-1, :spec.n_lat])
    contacts = sum(series[f"{b.name}_contact_force_z_n"][-1] for b in spec.bearings)
    coupling = -k_c * (z_c - offset_z)
    weight = spec.rotor_mass * GRAVITY
    assert contacts + coupling == pytest.approx(weight, rel=2e-3)
    if k_c and not offset_z:
        assert z_c < -1e-4            # the hub has dropped with the rotor ...
        assert coupling > 0.1 * weight  # ... and the spring carries a real share
    if offset_z:
        # relaxed near where the landed hub sits (one clearance low; the rest is the chain's deflection and the
        # rotor's tilt): the spring is stretched by under a quarter of the hub's drop and carries little
        assert abs(z_c - offset_z) < 0.25 * abs(z_c)
        assert abs(coupling) < 0.15 * weight


def test_support_offset_is_checked():
    r = _rotor([{"station": "mid", "kyy": 2e6, "kzz": 2e6, "in_landing": True, "offset_z": -2e-4}])
    assert (r.supports[0].offset_y, r.supports[0].offset_z) == (0.0, -2e-4)
    assert _rotor([{"station": "mid", "kyy": 2e6}]).supports[0].offset_z == 0.0
    with pytest.raises(InputError, match=r"rotor\.supports\[0\]\.offset_z.*unless in_landing"):
        _rotor([{"station": "mid", "kyy": 2e6, "offset_z": -2e-4}])
    with pytest.raises(InputError, match=r"rotor\.supports\[0\]\.offset_y.*<= 0\.001 m"):
        _rotor([{"station": "mid", "kyy": 2e6, "in_landing": True, "offset_y": 2e-3}])


def test_static_loads_with_a_relaxed_off_axis_support():
    """Closed form: a spring relaxed exactly where the rotor sits on its other supports carries
    nothing, so those supports carry what they carry without it; any other rest point shares the
    weight, whose total the supports always carry (statics)."""
    from rotorlanding.modefit import static_support_loads
    from rotorlanding.reduction import full_model

    ends = [{"station": "left", "kyy": 1e7, "kzz": 1e7}, {"station": "right", "kyy": 1e7, "kzz": 1e7}]
    data = {"rotor": {"materials": {"steel": STEEL},
                      "sections": [{"length": 0.5, "outer_diameter": 0.05, "material": "steel", "elements": 5}],
                      "stations": {"left": 0.0, "mid": 0.25, "right": 0.5}, "supports": ends}}
    fe = assemble(rotor_from_dict(data))
    sys2 = full_model(fe).with_supports()
    z_mid = float(np.linalg.solve(sys2.K, sys2.gravity_load())[fe.dof("mid", "z")])
    two = static_support_loads(data)
    weight = fe.mass * GRAVITY
    for off, carries in ((z_mid, False), (0.0, True), (-3 * abs(z_mid), True)):
        d = {"rotor": {**data["rotor"], "supports": [*ends, {"station": "mid", "kyy": 5e6, "kzz": 5e6, "in_landing": True,
                                                               "offset_z": off}]}}
        loads = static_support_loads(d)
        assert sum(loads.values()) == pytest.approx(weight, rel=1e-9)
        if carries:
            assert abs(loads["mid"]) > 0.05 * weight
        else:
            assert loads["mid"] == pytest.approx(0.0, abs=1e-9 * weight)
            assert loads["left"] == pytest.approx(two["left"], rel=1e-9)


@pytest.mark.parametrize("offset_z", [0.0, -2.0e-4])
def test_energy_balance_with_the_coupling(offset_z):
    sc = _landing(4.0e6, "operating.t_end=0.25", "solver.output_period=5e-5", f"rotor.supports.2.offset_z={offset_z}")
    spec, t, q, v, info = simulate(sc, progress=False)
    assert info["complete"]
    e = summarize(spec, t, evaluate(spec, t, q, v))["energy"]
    assert e["dissipated_total_j"] > 10.0
    assert e["balance_error_relative"] < 0.01, e


def test_circulatory_stiffness_is_refused_in_the_landing():
    """A cross-coupled stiffness with kyz != kzy is allowed for modal analysis, but not in the landing:
    there it joins K before the (symmetric) Craig-Bampton solves and the energy ledger."""
    _rotor([{"station": "mid", "kyz": 1e6, "kzy": -1e6}])  # modal only: fine
    _rotor([{"station": "mid", "kyy": 1e6, "kyz": 2e5, "kzy": 2e5, "in_landing": True}])  # symmetric: fine
    with pytest.raises(InputError, match=r"rotor\.supports\[0\]\.kzy.*must equal kyz"):
        _rotor([{"station": "mid", "kyz": 1e6, "kzy": -1e6, "in_landing": True}])


def test_with_supports_never_adds_a_landing_support_twice():
    """A model built on the landing's rotor (coupling already in K) gets only the other supports from
    with_supports(): full and reduced models of the landing rotor agree with the free rotor plus all
    supports."""
    from rotorlanding.reduction import craig_bampton, full_model

    r = _rotor([{"station": "left", "kyy": 1e7, "kzz": 1e7}, {"station": "right", "kyy": 1e7, "kzz": 1e7},
                {"station": "mid", "kyy": 2e6, "kzz": 2e6, "in_landing": True}])
    fe = assemble(r)
    fl = with_landing_supports(fe)
    assert fl.landing_supports_included and with_landing_supports(fl) is fl
    np.testing.assert_allclose(full_model(fl).with_supports().K, full_model(fe).with_supports().K, rtol=0, atol=0)
    a = craig_bampton(fl, ["left", "right"], 4).with_supports()
    b = craig_bampton(fe, ["left", "right"], 4).with_supports()
    # the landing rotor's reduction has the coupling inside its fixed-interface modes; the free
    # rotor's gets it afterwards through T: both represent K_free + all supports, so their static
    # boundary response agrees (Guyan is exact there)
    ua = np.linalg.solve(a.K, a.gravity_load())[:4]
    ub_full = np.linalg.solve(full_model(fe).with_supports().K, full_model(fe).gravity_load())
    idx = [fe.dof(st, d) for st in ("left", "right") for d in ("y", "z")]
    np.testing.assert_allclose(ua, ub_full[idx], rtol=1e-9, atol=1e-20)
    assert b.K.shape == a.K.shape

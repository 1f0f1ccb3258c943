"""The force a catcher bearing puts on its housing (what a load cell between them reads,
``mechanisms.housing_force``): the sum of the outputs declared on the housing (ribbon, eqs 28-29;
the face friction of eq 30; the races' damping to ground, eqs 7 and 9), zero for an effect that is
off, and, by the races' momentum balance, the force on the rotor plus the races' weight once the
races' accelerations average out."""

from pathlib import Path

import numpy as np
import pytest

from rotorlanding import mechanisms as mech
from rotorlanding.landing import build_spec
from rotorlanding.scenario import load_scenario
from test_mechanisms import _states

ROOT = Path(__file__).resolve().parents[1]
FORWARD = ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml"
NO_WHIRL = ROOT / "scenarios" / "paper" / "no_whirl_landing.toml"
G = mech.GRAVITY


def _pressed_states(spec):
    """test_mechanisms' random states (journals in their races, the races moving, so friction and damping
    have a direction), with the rotor on its thrust face."""
    t, q, v = _states(spec, seed=5)
    a = spec.scenario.axial
    q[:, spec.i_axial] = a.cl_ax + 0.5 * a.delta_m
    return t, q, v


@pytest.mark.parametrize("sets", [[], ["effects.outer_race_coulomb=false"],
                                  ["bearings.DE.outer_race_damping=50.0", "bearings.NDE.inner_race_damping=20.0"]])
def test_housing_force_sums_the_outputs_declared_on_the_housing(sets):
    spec = build_spec(load_scenario(FORWARD, sets))
    t, q, v = _pressed_states(spec)
    s = mech.evaluate(spec, t, q, v)
    face = spec.axial_face_bearing().name
    for b in spec.bearings:
        n = b.name
        for i, ax in enumerate("yz"):
            want = s[f"{n}_ribbon_force_{ax}_n"] + s[f"{n}_housing_friction_{ax}_n"] + s[f"{n}_race_damping_force_{ax}_n"]
            np.testing.assert_array_equal(mech.housing_force(s, n)[i], want)
        friction = np.hypot(s[f"{n}_housing_friction_y_n"], s[f"{n}_housing_friction_z_n"])
        if sets == ["effects.outer_race_coulomb=false"] or n != face:
            assert not np.any(friction)          # off, or no axial load on this outer race: nothing
        else:
            # eq 30: |F_oh| = mu_d F_ax where the outer race slides (the regularised sign below v_reg)
            assert np.max(friction) > 0.5 * b.laws.mu_d * np.max(s["axial_force_n"])
        damping = np.hypot(s[f"{n}_race_damping_force_y_n"], s[f"{n}_race_damping_force_z_n"])
        assert np.any(damping) == (b.laws.inner_race_damping > 0 or b.laws.outer_race_damping > 0)


def test_the_housing_carries_the_rotor_load_plus_the_races_weight():
    """Races' momentum balance: m_i a_i + m_o a_o = F_housing - F_rotor - (m_i + m_o) g e_z (the
    ball set is massless), so over a stretch where the races' velocities hardly change the mean of
    F_housing - F_rotor is the races' weight, vertical, and nothing sideways. The no-whirl landing's
    last 0.1 s (rolling calm on both catchers)."""
    from rotorlanding.postprocess import evaluate
    from rotorlanding.run import simulate

    sc = load_scenario(NO_WHIRL, ["operating.t_end=0.5"])
    spec, t, q, v, _ = simulate(sc, progress=False)
    s = evaluate(spec, t, q, v)
    late = t >= t[-1] - 0.1
    for b in spec.bearings:
        L = b.laws
        weight = (L.inner_race_mass + L.outer_race_mass) * G
        (hy, hz), (ry, rz) = mech.housing_force(s, b.name), mech.rotor_force(s, b.name)
        assert np.max(rz) > 1000.0                          # the landing did load the catcher
        assert np.mean(hz[late] - rz[late]) == pytest.approx(weight, rel=0.01)
        assert abs(np.mean(hy[late] - ry[late])) < 0.01 * weight

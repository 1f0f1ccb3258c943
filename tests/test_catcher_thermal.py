"""Issue 18, step 1: the catcher bearings' thermal networks integrated with the landing
(rotorlanding/thermal_states.py, the registry's ``catcher_thermal`` mechanism).

Checked against: the closed form of a single lumped node (temperature and heat lost), the law
layer's own exact stepper (user_forces.thermal.step_exact) on the five-node network, and on a real
short landing the energy ledger (heat in = the routed dissipated energies) and conservation (heat in
= heat stored from the capacities + heat lost)."""

from pathlib import Path

import numpy as np
import pytest

from rotorlanding import mechanisms
from rotorlanding.landing import build_spec
from rotorlanding.mechanisms import carried_series, evaluate, heat_routes
from rotorlanding.run import simulate
from rotorlanding.scenario import load_scenario
from rotorlanding.thermal_states import NODE_SERIES, ModalStepper, network_for
from user_forces.thermal import CatcherThermalGeometry, ThermalNetwork, catcher_bearing_network, step_exact

ROOT = Path(__file__).resolve().parents[1]
LANDING = ROOT / "scenarios" / "landing_7000rpm.toml"


@pytest.fixture(scope="module")
def landing():
    sc = load_scenario(LANDING, ["operating.t_end=0.03"])
    spec, t, q, v, stats = simulate(sc)
    assert stats["complete"]
    return sc, spec, t, q, v, evaluate(spec, t, q, v)


def test_single_node_against_its_exponential():
    """C dT/dt = Q - g (T - Ta): T = Ta + Q/g + (T0 - Ta - Q/g) e^(-t/tau), tau = C/g; heat lost
    int g (T - Ta) = Q t + (T0 - Ta - Q/g) g tau (1 - e^(-t/tau)). Irregular steps, Q constant."""
    cap, g, q, ta, t0 = 100.0, 2.0, 50.0, 293.15, 300.0
    net = ThermalNetwork(capacity=(cap,), links=(), g_ambient=(g,), t_ambient=ta, names=("node",))
    rng = np.random.default_rng(1)
    dt = rng.uniform(0.1, 20.0, 40)
    temps, lost = ModalStepper(net).run(dt, (q * dt)[:, None], np.array([t0]))
    t = np.cumsum(dt)
    tau = cap / g
    exact = ta + q / g + (t0 - ta - q / g) * np.exp(-t / tau)
    lost_exact = q * t + (t0 - ta - q / g) * g * tau * (1.0 - np.exp(-t / tau))
    assert np.max(np.abs(temps[:, 0] - exact)) < 1e-10
    assert np.max(np.abs(np.cumsum(lost) - lost_exact)) < 1e-8 * lost_exact[-1]
    assert ModalStepper(net).fastest_time_constant_s == pytest.approx(tau, rel=1e-12)


def test_modal_stepper_is_the_law_layers_exact_step():
    """The once-decomposed stepper against user_forces.thermal.step_exact (eigen-decomposed at
    every call), five nodes, random heat and steps."""
    net = catcher_bearing_network()
    cap, lap, g = net.arrays()
    rng = np.random.default_rng(2)
    dt = rng.uniform(1e-4, 30.0, 25)
    heat = rng.uniform(0.0, 50.0, (25, 5)) * dt[:, None]
    temps, lost = ModalStepper(net).run(dt, heat, np.full(5, net.t_ambient))
    t = np.full(5, net.t_ambient)
    for k in range(25):
        t, lo = step_exact(t, heat[k] / dt[k], cap, lap, g, net.t_ambient, dt[k])
        assert np.max(np.abs(temps[k] - t)) < 1e-9
        assert lost[k] == pytest.approx(lo, rel=1e-9, abs=1e-12)


def test_a_landing_heats_the_networks_with_what_the_ledger_dissipates(landing):
    """Heat in = the routed entries of the energy ledger (all bearings), and per bearing heat in =
    sum C (T - T0) + heat lost: the capacities from the law layer's network builder."""
    sc, spec, t, q, v, s = landing
    routed = sum(s["dissipated_" + e + "_j"][-1] for e in heat_routes())
    heat_in = sum(s[b + "_heat_in_j"][-1] for b in spec.bearing_names)
    assert routed > 1.0  # J: the landing does heat the bearings
    assert heat_in == pytest.approx(routed, rel=1e-12)
    for b in spec.bearings:
        cap = np.array(network_for(b.laws).capacity)
        temps = np.column_stack([s[b.name + "_" + n] for n in NODE_SERIES])
        stored = float(np.sum(cap * (temps[-1] - temps[0])))
        hin, lost = s[b.name + "_heat_in_j"][-1], s[b.name + "_heat_lost_j"][-1]
        assert abs(hin - stored - lost) < 1e-9 * hin
        assert np.all(temps >= b.laws.extra["thermal_ambient_k"] - 1e-9)  # heat only flows in
        # the landed sleeve runs at the rotor's surface speed on a slower ring: Blok gives it most
        # of the slip heat, so it is the hottest node after a short landing
        assert temps[-1, 0] == np.max(temps[-1])


def test_off_contributes_nothing_and_mechanics_are_unchanged(landing):
    sc, spec, t, q, v, s_on = landing
    spec_off = build_spec(load_scenario(LANDING, ["operating.t_end=0.03", "effects.catcher_thermal=false"]))
    s_off = evaluate(spec_off, t, q, v)
    carried = set(carried_series(spec.bearing_names))
    for name, arr in s_off.items():
        if name in carried:
            assert not np.any(arr), name
        else:
            assert np.array_equal(arr, s_on[name]), name


def test_carried_state_continues_a_split_evaluation(landing):
    """Evaluating the samples in two pieces, the second starting from the first one's last row of
    every carried series (a coast-down chunk), gives the temperatures of one evaluation."""
    sc, spec, t, q, v, s = landing
    k = len(t) // 2
    first = evaluate(spec, t[:k + 1], q[:k + 1], v[:k + 1])
    carry = {n: float(first[n][-1]) for n in carried_series(spec.bearing_names)}
    second = evaluate(spec, t[k:], q[k:], v[k:], carry=carry)
    for n in carry:
        assert second[n][-1] == pytest.approx(s[n][-1], rel=1e-12, abs=1e-12), n


def test_every_bearing_dissipation_has_a_heat_route(monkeypatch):
    leak = mechanisms.Mechanism("leak", "bearing", (), (), (), ("leaky",))
    monkeypatch.setattr(mechanisms, "REGISTRY", mechanisms.REGISTRY + (leak,))
    with pytest.raises(RuntimeError, match="leaky"):
        mechanisms._check_heat_routes()


def test_heat_by_route_adds_up_to_the_heat_in(landing):
    sc, spec, t, q, v, s = landing
    from rotorlanding.thermal_states import ROUTE_SERIES

    for b in spec.bearing_names:
        routes = sum(s[f"{b}_{r}"][-1] for r in ROUTE_SERIES)
        assert routes == pytest.approx(s[f"{b}_heat_in_j"][-1], rel=1e-12)
        assert s[f"{b}_heat_sleeve_contact_j"][-1] > 0.5 * s[f"{b}_heat_in_j"][-1]  # the landed sleeve dominates


def test_a_hot_bearing_with_feedback_keeps_its_heat_capacities(landing):
    """With thermal feedback the solver's laws carry the grown sleeve and bore; the network must
    still be the cold geometry's (the rings' masses do not change), so heat in = stored (cold
    capacities) + lost holds to round-off from a hot carried state too (it missed by 2.9e-4 in a
    wired runaway)."""
    from rotorlanding.mechanisms import retuned_spec

    sc, _, t, q, v, _ = landing
    spec = build_spec(load_scenario(LANDING, ["operating.t_end=0.03", "effects.thermal_feedback=true"]))
    rise = {"sleeve": 150.0, "inner_ring": 120.0, "ball_set": 100.0, "outer_ring": 30.0, "housing": 10.0}
    carry = {}
    for b in spec.bearings:
        ta = b.laws.extra["thermal_ambient_k"]
        carry.update({f"{b.name}_temperature_{n}_k": ta + d for n, d in rise.items()})
        carry.update({f"{b.name}_{n}": 0.0 for n in ("heat_in_j", "heat_lost_j", "heat_sleeve_contact_j",
                                                     "heat_face_rub_j", "heat_ball_contacts_j",
                                                     "heat_outer_support_j")})
    hot = retuned_spec(spec, carry)
    assert hot.bearings[0].laws.sleeve_radius > spec.bearings[0].laws.sleeve_radius  # the feedback grew it
    s = evaluate(hot, t, q, v, carry=carry)
    for b in spec.bearings:
        cap = np.array(network_for(b.laws).capacity)  # the cold laws' network
        temps = np.column_stack([s[b.name + "_" + n] for n in NODE_SERIES])
        stored = float(np.sum(cap * (temps[-1] - temps[0])))
        hin, lost = s[b.name + "_heat_in_j"][-1], s[b.name + "_heat_lost_j"][-1]
        assert abs(hin - stored - lost) < 1e-9 * max(abs(hin), abs(lost))


def test_modal_stepper_refuses_shapes_its_compiled_loop_would_overrun():
    net = catcher_bearing_network(CatcherThermalGeometry())
    st = ModalStepper(net)
    dt = np.full(4, 1e-3)
    with pytest.raises(ValueError, match="heat"):
        st.run(dt, np.zeros((3, net.n)), np.full(net.n, net.t_ambient))
    with pytest.raises(ValueError, match="heat"):
        st.run(dt, np.zeros((4, net.n - 1)), np.full(net.n, net.t_ambient))
    with pytest.raises(ValueError, match="> 0 s"):
        st.run(np.array([1e-3, 0.0]), np.zeros((2, net.n)), np.full(net.n, net.t_ambient))
    temps, lost = st.run(np.empty(0), np.empty((0, net.n)), np.full(net.n, net.t_ambient))
    assert temps.shape == (0, net.n) and lost.shape == (0,)

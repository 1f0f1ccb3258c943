"""Landing model checks: static rest by hand, energy balance, restitution of the contact law."""

import copy
import math
from pathlib import Path

import numpy as np
import pytest

from rotorlanding.config import load_toml
from rotorlanding.postprocess import evaluate, summarize
from rotorlanding.reduction import full_model
from rotorlanding.run import simulate
from rotorlanding.scenario import apply_overrides, scenario_from_dict
from rotorlanding.timoshenko import GRAVITY, assemble
from user_forces.radial_contact import radial_contact

ROOT = Path(__file__).resolve().parents[1]
SCEN = ROOT / "scenarios" / "landing_7000rpm.toml"


def _scenario(sets=(), **changes):
    data = apply_overrides(load_toml(SCEN), list(sets))
    for dotted, value in changes.items():
        node = data
        keys = dotted.split("__")
        for k in keys[:-1]:
            node = node.setdefault(k, {})
        node[keys[-1]] = value
    return scenario_from_dict(copy.deepcopy(data), source=str(SCEN))


def _rotor_mass_and_cg(rotor):
    """Mass and centre of gravity straight from the geometry (independent of the FE matrices)."""
    m, mx, x0 = 0.0, 0.0, 0.0
    for s in rotor.sections:
        ms = s.material.density * s.area * s.length
        m += ms
        mx += ms * (x0 + 0.5 * s.length)
        x0 += s.length
    for d in rotor.disks:
        m += d.mass
        mx += d.mass * d.position
    return m, mx / m


def _hand_equilibrium(sc, spec):
    """Each sleeve's rest position [m] by hand: the rotor on two supports, each Hertz + balls +
    ribbon in series under its reaction, and the motor coupling (an ``in_landing`` spring, 1e5 N/m on
    the rig since session 40) lifting it by k_c times its station's drop; force and moment balance,
    iterated to a fixed point (k_c is small beside the chains). The coupling station's drop is the
    line through the sleeves plus the shaft's own bending there with the sleeves pinned (gravity sag
    and compliance to the coupling's force: two static solves of the FE stiffness, no reduction, no
    contact law; the overhang sags ~77 um, a third of the clearance)."""
    m, xcg = _rotor_mass_and_cg(sc.rotor)
    x_nde, x_de = sc.rotor.stations["NDE_sleeve"], sc.rotor.stations["DE_sleeve"]
    w = m * GRAVITY
    c = sc.contact
    params = {b.name: b.params for b in spec.bearings}
    fe = assemble(sc.rotor)
    pins = [fe.dof(s, d) for s in ("NDE_sleeve", "DE_sleeve") for d in ("y", "z")]
    free = [i for i in range(fe.ndof) if i not in pins]
    k_free = fe.K[np.ix_(free, free)]

    def pinned(load):  # the shaft's deflection with its sleeves held on the line
        u = np.zeros(fe.ndof)
        u[free] = np.linalg.solve(k_free, load[free])
        return u

    sag = pinned(full_model(fe).gravity_load())
    springs = []
    for s in sc.rotor.supports:
        if s.in_landing:
            i = fe.dof(s.station, "z")
            unit = np.zeros(fe.ndof)
            unit[i] = 1.0
            springs.append((sc.rotor.stations[s.station], s.kzz, s.offset_z, sag[i], pinned(unit)[i]))

    def sleeve_z(name, r):
        p = params[name]
        hertz = (r / c.k_hertz) ** (1 / c.exponent)
        fb = r + p.inner_race_mass * GRAVITY  # balls carry the rotor share and the inner race
        balls = (-p.k_b1 + math.sqrt(p.k_b1**2 + 4 * p.k_b2 * fb)) / (2 * p.k_b2)
        ribbon = (fb + p.outer_race_mass * GRAVITY) / p.k_rib
        return -(p.clearance + hertz + balls + ribbon)

    def line(z, x):  # the line through the sleeves
        return z["NDE"] + (z["DE"] - z["NDE"]) * (x - x_nde) / (x_de - x_nde)

    z = {"NDE": -params["NDE"].clearance, "DE": -params["DE"].clearance}
    for _ in range(50):
        # -k (line + sag + a F - z0) = F
        lifts = [(x, -k * (line(z, x) + sg - z0) / (1.0 + k * a)) for x, k, z0, sg, a in springs]
        r_de = (w * (xcg - x_nde) - sum(f * (x - x_nde) for x, f in lifts)) / (x_de - x_nde)
        r_nde = w - sum(f for _, f in lifts) - r_de
        z = {"NDE": sleeve_z("NDE", r_nde), "DE": sleeve_z("DE", r_de)}
    return z, sum(f for _, f in lifts)


@pytest.mark.parametrize("sets", [[], ["rotor.supports.2.kyy=0.0", "rotor.supports.2.kzz=0.0"]], ids=["rig", "free_coupling"])
def test_non_rotating_drop_settles_at_hand_equilibrium(sets):
    """Weight shared by force and moment balance (the lever rule with the coupling laterally free);
    each support = Hertz + balls + ribbon in series; the rig's coupling lifts its share."""
    sc = _scenario(sets, operating__speed_rpm=0.0, operating__t_end=0.4,
                   rotor__damping={"mass_proportional": 40.0}, effects__windage=False)
    spec, t, q, v, info = simulate(sc, progress=False)
    assert info["complete"]
    expected, lift = _hand_equilibrium(sc, spec)
    assert (lift > 10.0) if not sets else (lift == 0.0)  # the rig's coupling: ~1e5 N/m x 0.2 mm
    for b in spec.bearings:
        p = b.params
        z_end = q[-1, b.i_station + 1]
        # compare the deflection beyond the clearance (the part the laws produce)
        # (to 1e-3: the coupling moves the NDE by 0.6 %, the DE by 12 %; the landing meets the hand values to 1e-5
        # with it and 5e-4 without)
        assert (z_end + p.clearance) == pytest.approx(expected[b.name] + p.clearance, rel=1e-3), b.name
        assert abs(q[-1, b.i_station]) < 1e-7  # no friction-driven drift without spin
        assert np.max(np.abs(v[-200:, b.i_station + 1])) < 1e-4  # at rest


def test_energy_balance_half_second_landing_at_7000rpm():
    sc = _scenario(operating__t_end=0.5, solver__output_period=5e-5)  # one sample per step
    spec, t, q, v, info = simulate(sc, progress=False)
    assert info["complete"] and t[-1] == pytest.approx(0.5)
    series = evaluate(spec, t, q, v)
    e = summarize(spec, t, series)["energy"]
    assert e["dissipated_total_j"] > 50.0  # a real landing: friction heats the sleeve
    assert e["balance_error_relative"] < 0.01, e
    # of what the landing itself dissipates (windage, ~1 kW at 7000 rpm, runs with or without it),
    # the sleeve's sliding on the race is most
    landing = e["dissipated_total_j"] - e["dissipated_j"]["windage"]
    assert e["dissipated_j"]["radial_friction"] > 0.5 * landing
    assert all(val >= -1e-9 for val in e["dissipated_j"].values())


@pytest.mark.parametrize("law, value", [
    # a race rolling at ~700 rad/s against 2 x 1 N m loses > 100 W; over > 0.1 s that is > 10 J
    ("worn_drag_torque", 1.0),
    # the load-proportional part: a few hundred N at ~700 rad/s, 0.05 x 0.0425 m x 300 N x 700 rad/s ~ 0.45 kW
    ("worn_drag_friction", 0.05),
])
def test_energy_balance_with_worn_bearing_drag(law, value):
    """The worn-bearing drag (its load-independent torque, or its load-proportional part: ball
    contacts sliding) is accounted for: its dissipation is positive and the energy balance still
    closes (independent check of the drag's sign and power bookkeeping)."""
    sc = _scenario(operating__t_end=0.25, solver__output_period=5e-5, effects__worn_bearing_drag=True,
                   **{f"bearings__DE__{law}": value, f"bearings__NDE__{law}": value})
    spec, t, q, v, info = simulate(sc, progress=False)
    assert info["complete"]
    e = summarize(spec, t, evaluate(spec, t, q, v))["energy"]
    assert e["dissipated_j"]["worn_bearing_drag"] > 10.0
    assert e["balance_error_relative"] < 0.01, e


def test_worn_bearing_drag_needs_a_torque():
    from rotorlanding.errors import InputError

    with pytest.raises(InputError, match="effects.worn_bearing_drag.*worn_drag_torque"):
        _scenario(effects__worn_bearing_drag=True)
    with pytest.raises(InputError, match="worn_drag_torque"):
        _scenario(bearings__DE__worn_drag_torque=-1.0)


@pytest.mark.parametrize("e_target", [0.95, 0.9])
def test_hunt_crossley_restitution(e_target):
    """A mass striking the race with k_visc = 3 k (1 - e) / (2 v_in) rebounds with ~e v_in."""
    from scipy.integrate import solve_ivp

    k, n, m, v_in, cl = 2e11, 1.5, 10.0, 0.06, 2e-4
    kv = 3 * k * (1 - e_target) / (2 * v_in)

    def rhs(t, y):
        fy, fz = radial_contact(0.0, y[0], 0.0, y[1], 0.0, 0.0, cl, k, n, kv, 0.0, 1e-3, 0.03, 0.0302)[:2]
        return [y[1], fz / m]

    def leave(t, y):
        return y[0] + cl - 1e-12 if t > 0 else -1.0
    leave.terminal, leave.direction = True, 1
    sol = solve_ivp(rhs, (0, 0.01), [-cl, -v_in], events=leave, rtol=1e-10, atol=1e-14, max_step=1e-6)
    e = sol.y[1, -1] / v_in
    assert (1 - e) == pytest.approx(1 - e_target, rel=0.12)


def test_amb_hold_then_drop_with_unbalance():
    """Levitated by the PD AMBs until t_drop (unbalance gives a forward 1x orbit), then it lands."""
    sc = _scenario(amb__t_drop=0.12, operating__t_end=0.15, effects__unbalance=True,
                   unbalance={"station": "thrust_disk", "magnitude": 2e-4, "phase_deg": 0.0})
    spec, t, q, v, info = simulate(sc, progress=False)
    assert info["complete"]
    de = spec.bearings[0]
    s = de.i_station
    hold = (t > 0.02) & (t < 0.12)
    assert np.max(np.hypot(q[hold, s], q[hold, s + 1])) < 0.25 * de.params.clearance  # levitated
    # synchronous components of w = y + i z: forward (e^{+i Omega t}) dominates backward
    w = q[hold, s] + 1j * q[hold, s + 1]
    w = w - w.mean()
    ph = np.exp(1j * v[hold, spec.i_theta] * t[hold])
    fwd, bwd = abs(np.mean(w / ph)), abs(np.mean(w * ph))
    assert fwd > 5 * bwd and fwd > 1e-7
    assert np.min(q[t > 0.135, s + 1]) < -0.9 * de.params.clearance  # landed after the drop

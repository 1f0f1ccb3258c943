"""Tests of user_forces.thermal (lumped catcher-bearing network, partition, steppers)."""

from __future__ import annotations

import math
import random

import numpy as np
import pytest

from user_forces.thermal import (BALLS, HOUSING, INNER, OUTER, SLEEVE, STEEL_52100, Material, ThermalNetwork,
                                 ball_set_heat_capacity, blok_partition, catcher_bearing_network,
                                 constriction_resistance, half_ring_conductance, heat_sources, network_rhs,
                                 radiation_conductance, ring_heat_capacity, shell_conductance, steady_state,
                                 step_backward_euler, step_exact)

TA = 293.15


def one_node(c=100.0, g=2.0):
    return np.array([c]), np.zeros((1, 1)), np.array([g])


def test_single_node_exponential():
    """C dT/dt = Q - g (T - Ta): T(t) = Ta + Q/g + (T0 - Ta - Q/g) exp(-g t / C)
    (C = 100 J/K, g = 2 W/K, Q = 50 W, T0 = 300 K: tau = 50 s, T_inf = Ta + 25 K)."""
    cap, lap, g = one_node()
    q = np.array([50.0])
    t0 = 300.0

    def exact(t):
        return TA + 25.0 + (t0 - TA - 25.0) * math.exp(-2.0 * t / 100.0)

    t = np.array([t0])
    for k in range(1, 41):                        # exact stepper, steps of 5 s
        t, _ = step_exact(t, q, cap, lap, g, TA, 5.0)
        assert t[0] == pytest.approx(exact(5.0 * k), abs=1e-11)
    # backward Euler: first order, the error at t = 100 s halves when dt halves
    errs = []
    for dt in (2.0, 1.0, 0.5):
        t = np.array([t0])
        for _ in range(int(round(100.0 / dt))):
            t, _ = step_backward_euler(t, q, cap, lap, g, TA, dt)
        errs.append(abs(t[0] - exact(100.0)))
    assert errs[0] < 0.1 and errs[1] / errs[0] == pytest.approx(0.5, abs=0.03)
    assert errs[2] / errs[1] == pytest.approx(0.5, abs=0.03)


def test_two_node_steady_conduction_hand_value():
    """Q = 100 W into node 0; node 0 -- 2 W/K -- node 1 -- 5 W/K -- ambient:
    T1 = Ta + 100/5 = Ta + 20 K, T0 = T1 + 100/2 = Ta + 70 K."""
    nw = ThermalNetwork(capacity=(50.0, 80.0), links=((0, 1, 2.0),), g_ambient=(0.0, 5.0), t_ambient=TA,
                        names=("a", "b"))
    cap, lap, g = nw.arrays()
    q = np.array([100.0, 0.0])
    ts = steady_state(q, lap, g, TA)
    assert ts == pytest.approx([TA + 70.0, TA + 20.0], abs=1e-10)
    t, _ = step_exact(np.array([TA, TA]), q, cap, lap, g, TA, 1.0e5)   # ~ 1000 time constants
    assert t == pytest.approx([TA + 70.0, TA + 20.0], abs=1e-9)
    assert network_rhs(ts, q, cap, lap, g, TA) == pytest.approx([0.0, 0.0], abs=1e-12)


def test_energy_balance_long_coastdown_both_steppers():
    """Five-node catcher network, a decaying and fluctuating heat input for 3 hours in 10 s steps
    (like a coast-down): heat in = stored + lost to ambient to 1e-9 of the heat in, for both
    steppers; and the two steppers agree to the first-order error of backward Euler."""
    nw = catcher_bearing_network()
    cap, lap, g = nw.arrays()
    rng = random.Random(3)
    dt, n = 10.0, 1080
    t_be = np.full(5, TA)
    t_ex = np.full(5, TA)
    e_in = lost_be = lost_ex = 0.0
    for k in range(n):
        p = 400.0 * math.exp(-k * dt / 2000.0) * (1.0 + 0.3 * rng.random())
        q = np.array(heat_sources(0.3 * p, 0.1 * p, 0.4 * p, 0.1 * p, 0.1 * p, 0.8, 0.6))
        e_in += dt * float(np.sum(q))
        t_be, l1 = step_backward_euler(t_be, q, cap, lap, g, TA, dt)
        t_ex, l2 = step_exact(t_ex, q, cap, lap, g, TA, dt)
        lost_be += l1
        lost_ex += l2
    for t_end, lost in ((t_be, lost_be), (t_ex, lost_ex)):
        stored = float(np.sum(cap * (t_end - TA)))
        assert abs(e_in - stored - lost) <= 1e-9 * e_in
        assert lost > 0.5 * e_in                # 3 h >> the network's time constants: mostly lost
    assert t_be == pytest.approx(t_ex, abs=0.5)


def test_rhs_matches_the_exact_flow():
    """The loop-based right-hand side equals the derivative of the exact (eigen) solution."""
    nw = catcher_bearing_network(g_sleeve_ring_contact=3.0)
    cap, lap, g = nw.arrays()
    t0 = np.array([400.0, 350.0, 330.0, 310.0, 300.0])
    q = np.array([50.0, 30.0, 20.0, 10.0, 5.0])
    h = 1e-3
    tp, _ = step_exact(t0, q, cap, lap, g, TA, h)
    tm, _ = step_exact(t0, q, cap, lap, g, TA, -h)        # the modal solution runs backwards too
    # central difference: O(h^2) truncation (~1e-8 K/s here) plus round-off ~1e-13 K / h
    assert network_rhs(t0, q, cap, lap, g, TA) == pytest.approx((tp - tm) / (2 * h), abs=1e-7)


def test_rhs_and_backward_euler_compile_with_numba():
    numba = pytest.importorskip("numba")
    nw = catcher_bearing_network()
    cap, lap, g = nw.arrays()
    t0 = np.array([400.0, 350.0, 330.0, 310.0, 300.0])
    q = np.array([50.0, 30.0, 20.0, 10.0, 5.0])
    rhs_c = numba.njit(network_rhs)
    be_c = numba.njit(step_backward_euler)
    assert rhs_c(t0, q, cap, lap, g, TA) == pytest.approx(network_rhs(t0, q, cap, lap, g, TA), rel=1e-13)
    t1c, lc = be_c(t0, q, cap, lap, g, TA, 2.0)
    t1, l1 = step_backward_euler(t0, q, cap, lap, g, TA, 2.0)
    assert t1c == pytest.approx(t1, rel=1e-13) and lc == pytest.approx(l1, rel=1e-12)


def test_capacities_from_dimensions():
    """7212 inner ring 60/75 x 22 mm: V = pi/4 (0.075^2 - 0.060^2) 0.022 = 3.4989e-5 m^3,
    m = 7810 V = 0.2733 kg (rig.toml: 0.28 kg), C = 475 m = 129.80 J/K.
    15 balls of 15.875 mm: V = 15 pi D^3 / 6 = 3.1420e-5 m^3, C = 116.57 J/K."""
    assert ring_heat_capacity(0.060, 0.075, 0.022, STEEL_52100) == pytest.approx(129.80, abs=0.01)
    assert ball_set_heat_capacity(15, 15.875e-3, STEEL_52100) == pytest.approx(116.57, abs=0.01)
    with pytest.raises(ValueError, match="d_out = 0.05"):
        ring_heat_capacity(0.060, 0.05, 0.022, STEEL_52100)


def test_shell_and_half_ring_conductances():
    """g = 2 pi k L / ln(r2/r1); the two halves about the log-mean radius add up to the whole."""
    g = shell_conductance(0.030, 0.0375, 0.022, 46.6)
    assert g == pytest.approx(2 * math.pi * 46.6 * 0.022 / math.log(1.25), rel=1e-14)
    g1 = half_ring_conductance(0.030, 0.030, 0.0375, 0.022, 46.6)
    g2 = half_ring_conductance(0.0375, 0.030, 0.0375, 0.022, 46.6)
    assert 1 / (1 / g1 + 1 / g2) == pytest.approx(g, rel=1e-14)
    assert g1 == pytest.approx(g2, rel=1e-14)


def test_constriction_resistance_circle_and_ellipse():
    """Circle: R = 1/(4 k a) (Holm). Ellipse: between the circles of radius a and b, and the
    slender limit R -> ln(4 a/b) / (2 pi k a) (K(m) ~ ln(4/k') as the eccentricity -> 1)."""
    assert constriction_resistance(1e-3, 1e-3, 46.6) == pytest.approx(1 / (4 * 46.6 * 1e-3), rel=1e-14)
    r = constriction_resistance(2e-3, 2e-4, 46.6)
    assert constriction_resistance(2e-3, 2e-3, 46.6) < r < constriction_resistance(2e-4, 2e-4, 46.6)
    a, b = 1e-3, 1e-6
    assert constriction_resistance(a, b, 46.6) == pytest.approx(math.log(4 * a / b) / (2 * math.pi * 46.6 * a),
                                                                 rel=1e-6)


def test_blok_partition_limits():
    """Equal bodies at equal speeds: 1/2. Both fast: Blok's sqrt(k rho c V) ratio, i.e. for equal
    steel sqrt(V1)/(sqrt(V1) + sqrt(V2)). Both at rest: k1/(k1 + k2). A fast sleeve on a ring at
    rest takes most of the heat."""
    s = STEEL_52100
    assert blok_partition(20.0, 20.0, 2e-3, s, s) == pytest.approx(0.5, abs=1e-15)
    beta = blok_partition(40.0, 10.0, 2e-3, s, s)
    assert beta == pytest.approx(math.sqrt(40) / (math.sqrt(40) + math.sqrt(10)), rel=2e-3)
    other = Material(density=2700.0, specific_heat=900.0, conductivity=200.0, expansion=23e-6)
    assert blok_partition(0.0, 0.0, 2e-3, s, other) == pytest.approx(46.6 / (46.6 + 200.0), rel=1e-14)
    assert blok_partition(22.0, 0.0, 2e-3, s, s) > 0.95


def test_heat_sources_conserve_power_and_check_input():
    out = heat_sources(100.0, 20.0, 30.0, 50.0, 10.0, 0.9, 0.6)
    assert sum(out) == pytest.approx(210.0, rel=1e-15)
    assert out[SLEEVE] == pytest.approx(0.9 * 100 + 0.6 * 20)
    assert out[BALLS] == pytest.approx(40.0) and out[INNER] == pytest.approx(10 + 8 + 20)
    assert out[OUTER] == pytest.approx(20 + 5) and out[HOUSING] == pytest.approx(5.0)
    with pytest.raises(ValueError, match="p_ribbon = -1.0"):
        heat_sources(1.0, 0.0, 0.0, 0.0, -1.0, 0.5, 0.5)
    with pytest.raises(ValueError, match="beta_radial = 1.5"):
        heat_sources(1.0, 0.0, 0.0, 0.0, 0.0, 1.5, 0.5)


def test_radiation_secant_is_exact_loss():
    g = radiation_conductance(0.3, 0.05, 400.0, TA)
    assert g * (400.0 - TA) == pytest.approx(0.3 * 5.670374419e-8 * 0.05 * (400.0 ** 4 - TA ** 4), rel=1e-14)


def test_network_validation_names_the_argument():
    with pytest.raises(ValueError, match=r"capacity\[1\] = 0.0"):
        ThermalNetwork(capacity=(1.0, 0.0), links=(), g_ambient=(0.0, 0.0), t_ambient=TA, names=("a", "b"))
    with pytest.raises(ValueError, match=r"link \(0, 0\)"):
        ThermalNetwork(capacity=(1.0, 1.0), links=((0, 0, 1.0),), g_ambient=(0.0, 0.0), t_ambient=TA, names=("a", "b"))
    with pytest.raises(ValueError, match="g_ambient: 1 values"):
        ThermalNetwork(capacity=(1.0, 1.0), links=(), g_ambient=(0.0,), t_ambient=TA, names=("a", "b"))
    with pytest.raises(ValueError, match="names: 5 names, must be 2"):
        ThermalNetwork(capacity=(1.0, 1.0), links=(), g_ambient=(0.0, 0.0), t_ambient=TA)


def test_partition_and_sources_fast_leaves_compile_with_numba():
    numba = pytest.importorskip("numba")
    from user_forces.thermal import blok_partition_fast, heat_sources_fast
    s = STEEL_52100
    bp = numba.njit(blok_partition_fast)
    assert bp(22.0, 3.0, 2e-3, s.conductivity, s.diffusivity, 46.6, s.diffusivity) == pytest.approx(
        blok_partition(22.0, 3.0, 2e-3, s, s), rel=1e-14)
    hs = numba.njit(heat_sources_fast)
    assert hs(100.0, 20.0, 30.0, 50.0, 10.0, 0.9, 0.6, 0.5, 0.25, 0.5) == pytest.approx(
        heat_sources(100.0, 20.0, 30.0, 50.0, 10.0, 0.9, 0.6), rel=1e-15)

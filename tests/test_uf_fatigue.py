"""Tests of user_forces.fatigue (ASTM E1049 rainflow, ISO 281-anchored stress-life, Miner, ISO 76)."""

from __future__ import annotations

import math
import random

import pytest

from user_forces.contact_stress import BEARING_7212BE_ASSUMED as G, ball_race_peak_pressures
from user_forces.fatigue import (ISO281_FATIGUE_LIMIT_PA, LUNDBERG_PALMGREN_EXPONENT, StressLife, allowable_drops,
                                 overrolling_damage, rainflow, rainflow_damage, rainflow_histogram, reversals,
                                 static_exceedance, stress_life_from_rating)


def test_astm_e1049_example():
    """ASTM E1049-85 section 5.4.4 example, loads A..I = -2, 1, -3, 5, -1, 3, -4, 4, -2.
    Trace of the three-point rules (S = starting point):
      A B C: X=|C-B|=4 >= Y=|B-A|=3, Y contains S  -> 1/2 cycle of 3, drop A, S=B
      B C D: X=8 >= Y=4, Y contains S               -> 1/2 cycle of 4, drop B, S=C
      C D E: X=6 <  Y=8;  D E F: X=4 < Y=6          -> read on
      E F G: X=7 >= Y=|F-E|=4, Y without S           -> 1 cycle of 4, drop E F
      C D G: X=9 >= Y=8, Y contains S               -> 1/2 cycle of 8, drop C, S=D
      D G H: X=8 < Y=9;  G H I: X=6 < Y=8; end      -> residue D-G 9, G-H 8, H-I 6 as 1/2 each
    Totals: range 3: 0.5, 4: 1.5, 6: 0.5, 8: 1.0, 9: 0.5."""
    h = rainflow_histogram(rainflow([-2, 1, -3, 5, -1, 3, -4, 4, -2]))
    assert h == {3.0: 0.5, 4.0: 1.5, 6.0: 0.5, 8.0: 1.0, 9.0: 0.5}
    # the E-F cycle's mean is (-1 + 3)/2 = 1
    assert (4.0, 1.0, 1.0) in rainflow([-2, 1, -3, 5, -1, 3, -4, 4, -2])


def test_reversals_drop_intermediate_and_flat_points():
    assert reversals([0, 1, 2, 2, 1, 0, 0, 3, 5, 4]) == [0.0, 2.0, 0.0, 5.0, 4.0]
    with pytest.raises(ValueError, match="series"):
        reversals([])


def _four_point_closed_cycles(rev):
    """Independent four-point rainflow (FVA / DIN 45667 form): B-C is a closed cycle when it lies
    inside A-D. Returns the sorted closed ranges."""
    stack, out = [], []
    for x in rev:
        stack.append(x)
        while len(stack) >= 4:
            a, b, c, d = stack[-4:]
            if min(b, c) >= min(a, d) and max(b, c) <= max(a, d):
                out.append(abs(b - c))
                del stack[-3:-1]
            else:
                break
    return sorted(out)


def test_rainflow_equals_four_point_method_on_random_histories():
    """For a history that starts and ends at its maximum every cycle closes, and the ASTM
    three-point count must equal the independent four-point count cycle by cycle."""
    rng = random.Random(7)
    for _ in range(50):
        body = [rng.uniform(-1.0, 1.0) for _ in range(rng.randint(5, 60))]
        hist = [2.0] + body + [2.0]
        cyc = rainflow(hist)
        full = sorted(r for r, _m, c in cyc if c == 1.0)
        halves = [r for r, _m, c in cyc if c == 0.5]
        # ASTM: the excursion from the starting maximum to the minimum and back is two half cycles
        assert halves == pytest.approx([2.0 - min(body)] * 2)
        # four-point: the same closed cycles, the max-min-max excursion left as its residue
        assert full == pytest.approx(_four_point_closed_cycles(reversals(hist)), rel=1e-14)


def test_constant_amplitude_sine_counts_its_cycles():
    n = 10
    hist = [math.sin(2 * math.pi * k / 40.0) for k in range(40 * n + 1)]
    h = rainflow_histogram(rainflow(hist))
    full = sum(c for r, c in h.items() if r == pytest.approx(2.0, abs=1e-12))
    # reversals 0, 1, -1, ..., 1, -1, 0: the 2n - 1 swings of range 2 each start at the current
    # starting point S, so the three-point rules count each as a half cycle: n - 1/2 cycles of 2;
    # the first rise 0 -> 1 and the last 1/4 period -1 -> 0 are half cycles of range 1
    assert full == pytest.approx(n - 0.5)
    assert sum(c for r, c in h.items() if abs(r - 1.0) < 1e-12) == pytest.approx(1.0)
    assert sum(c * r for r, c in h.items()) == pytest.approx(2.0 * (n - 0.5) + 2 * 0.5 * 1.0, rel=1e-12)


def test_stress_life_reproduces_iso281_variable_load_rule():
    """Miner in pressure with exponent 9 == ISO 281's cube-mean load: two load blocks on the
    assumed 7212 BE, C = 61 kN (assumed catalogue value, see docs).
      ISO 281 by hand: D = n1 (P1/C)^3 / 1e6 + n2 (P2/C)^3 / 1e6
      law: D = sum n_i / N(p_i), p_i = Hertz peak pressure at P_i, p_ref = Hertz pressure at C.
    Independent paths: loads cubed vs Hertz pressures to the 9th; they agree because the law
    p ~ Q^(1/3) holds exactly in the Hertz solution and the load distribution is linear in scale
    only to that power (zero clearance: the ball loads scale with F_r)."""
    c_dyn = 61.0e3
    p_c = ball_race_peak_pressures(c_dyn, 0.0, G)[0]
    law = stress_life_from_rating(p_c)
    loads = (2.0e3, 20.0e3)
    revs = (3.0e5, 1.0e4)
    p = [ball_race_peak_pressures(f, 0.0, G)[0] for f in loads]
    d_law = overrolling_damage(p, revs, law)
    d_hand = sum(n * (f / c_dyn) ** 3 / 1e6 for f, n in zip(loads, revs))
    assert d_law == pytest.approx(d_hand, rel=1e-6)
    # at P = C, 1e6 revolutions is one L10 life
    assert overrolling_damage([p_c], [1.0e6], law) == pytest.approx(1.0, rel=1e-12)
    assert allowable_drops(d_law) == pytest.approx(1.0 / d_hand, rel=1e-6)
    assert LUNDBERG_PALMGREN_EXPONENT == 9.0


def test_rainflow_damage_miner_sum_and_measures():
    """A pressure history of 3 closed cycles 0 -> 2 GPa plus one of 1 -> 3 GPa: by hand
    D_peak = 3 (2/p_ref)^9 / N_ref + (3/p_ref)^9 / N_ref (+ the residue's half cycles)."""
    law = StressLife(p_ref=4.0e9, n_ref=1.0e6)
    hist = [0.0, 2e9, 0.0, 2e9, 0.0, 2e9, 0.0, 3.5e9, 1e9, 3e9, 0.0]
    cyc = rainflow(hist)
    d_hand = sum(c * ((m + r / 2) / 4e9) ** 9 / 1e6 for r, m, c in cyc)
    assert rainflow_damage(hist, law) == pytest.approx(d_hand, rel=1e-12)
    assert rainflow_damage(hist, law, "range") <= rainflow_damage(hist, law, "peak")
    with pytest.raises(ValueError, match="measure = 'max'"):
        rainflow_damage(hist, law, "max")


def test_fatigue_limit_option():
    law = StressLife(p_ref=4.0e9, n_ref=1.0e6, p_limit=ISO281_FATIGUE_LIMIT_PA)
    assert law.damage_per_cycle(1.4e9) == 0.0
    assert law.cycles_to_failure(1.5e9) == float("inf")
    assert law.damage_per_cycle(2.0e9) == pytest.approx(0.5 ** 9 / 1e6, rel=1e-12)
    assert allowable_drops(0.0) == float("inf")
    with pytest.raises(ValueError, match="exponent = 0"):
        StressLife(p_ref=1.0, n_ref=1.0, exponent=0)


def test_static_exceedance_triangle():
    """Triangle 0 -> 5 GPa -> 0 over 0..2 s, twice: above 4.2 GPa during 2 x 2 x (0.8/5) s = 0.64 s,
    two up-crossings, peak 5 GPa."""
    t = [0.0, 1.0, 2.0, 3.0, 4.0]
    p = [0.0, 5e9, 0.0, 5e9, 0.0]
    above, count, peak = static_exceedance(t, p, 4.2e9)
    assert above == pytest.approx(0.64, rel=1e-12)
    assert count == 2 and peak == 5e9
    assert static_exceedance(t, [1e9] * 5)[:2] == (0.0, 0)
    with pytest.raises(ValueError, match="t\\[2\\]"):
        static_exceedance([0.0, 1.0, 0.5], [0.0, 0.0, 0.0])

"""The reference Timoshenko frequencies themselves: Euler-Bernoulli limit and an independent
shooting solution of the Timoshenko ODEs."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from rotorlanding.analytic import (euler_bernoulli_free_free, euler_bernoulli_pinned_pinned, timoshenko_free_free,
                                   timoshenko_pinned_pinned)

E, NU, RHO = 2.1e11, 0.3, 7850.0
G = E / (2 * (1 + NU))
KAPPA = 6 * (1 + NU) / (7 + 6 * NU)


def props(length, d):
    return dict(length=length, youngs_modulus=E, shear_modulus=G, density=RHO, area=math.pi / 4 * d**2,
                second_moment=math.pi / 64 * d**4, shear_coefficient=KAPPA)


def test_slender_limit_is_euler_bernoulli():
    p = props(200 * 0.01, 0.01)
    np.testing.assert_allclose(timoshenko_pinned_pinned(3, **p), euler_bernoulli_pinned_pinned(3, **p), rtol=5e-4)
    np.testing.assert_allclose(timoshenko_free_free(3, **p), euler_bernoulli_free_free(3, **p), rtol=5e-4)


def _shoot(omega, p, bc):
    """Boundary residual at x = L of the Timoshenko ODEs integrated from x = 0 (2x2 determinant)."""
    L, A, I, k = p["length"], p["area"], p["second_moment"], p["shear_coefficient"]
    g = RHO * omega**2 / (k * G)

    def rhs(x, y):  # y = [w, w', psi, psi']
        w, dw, psi, dpsi = y
        return [dw, dpsi - g * w, dpsi, (-k * G * A * (dw - psi) - RHO * I * omega**2 * psi) / (E * I)]

    if bc == "free":  # psi'(0) = 0, w'(0) = psi(0)
        starts = ([1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 1.0, 0.0])
    else:  # pinned: w(0) = 0, psi'(0) = 0
        starts = ([0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0])
    cols = []
    for y0 in starts:
        y = solve_ivp(rhs, (0, L), y0, rtol=1e-11, atol=1e-14, method="DOP853").y[:, -1]
        cols.append([y[3], y[1] - y[2]] if bc == "free" else [y[0], y[3]])
    m = np.array(cols).T
    return np.linalg.det(m / np.abs(m).max())


@pytest.mark.parametrize("bc", ["free", "pinned"])
@pytest.mark.parametrize("ld", [5.0, 20.0])
def test_against_independent_shooting(bc, ld):
    d = 0.05
    p = props(ld * d, d)
    ref = timoshenko_free_free(3, **p) if bc == "free" else timoshenko_pinned_pinned(3, **p)
    for w in ref:
        lo, hi = w * (1 - 2e-3), w * (1 + 2e-3)
        assert _shoot(lo, p, bc) * _shoot(hi, p, bc) < 0  # a sign change brackets the reference root
        root = brentq(_shoot, lo, hi, args=(p, bc), xtol=1e-12 * w)
        assert root == pytest.approx(w, rel=1e-6)


def test_stocky_beam_well_below_euler_bernoulli():
    p = props(0.25, 0.05)  # L/D = 5
    tim, eb = timoshenko_free_free(3, **p), euler_bernoulli_free_free(3, **p)
    assert np.all(tim < eb)
    assert 0.85 < tim[0] / eb[0] < 0.95 and tim[2] / eb[2] < 0.75

"""The reference beam frequencies of ``rotorlanding.analytic`` checked against independent results:
the Euler-Bernoulli limit, the first-order shear/rotary-inertia correction (Rayleigh quotient of the
Euler-Bernoulli mode), and a numerical shooting solution of the Timoshenko ODEs."""

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from rotorlanding.analytic import (cutoff_frequency, euler_bernoulli_free_free, euler_bernoulli_pinned_pinned,
                                   free_free_beta_l, timoshenko_free_free, timoshenko_pinned_pinned)

E, NU, RHO = 2.1e11, 0.3, 7850.0
G = E / (2 * (1 + NU))
KAPPA = 6 * (1 + NU) / (7 + 6 * NU)  # solid circle
D = 0.05


def props(slenderness, d=D):
    """Solid steel circular shaft, L/D = slenderness."""
    return dict(length=slenderness * d, youngs_modulus=E, shear_modulus=G, density=RHO, area=math.pi / 4 * d**2,
                second_moment=math.pi / 64 * d**4, shear_coefficient=KAPPA)


def eb_props(p):
    return {k: v for k, v in p.items() if k not in ("shear_modulus", "shear_coefficient")}


# ----------------------------------------------------------------------------- Euler-Bernoulli


def test_euler_bernoulli_free_free_roots():
    bl = free_free_beta_l(8)
    np.testing.assert_allclose(bl[:3], [4.730040745, 7.853204624, 10.995607838], rtol=0, atol=2e-9)
    np.testing.assert_allclose(np.cos(bl) - 1 / np.cosh(bl), 0.0, rtol=0, atol=1e-14)  # cos cosh = 1, scaled
    assert np.all(np.diff(bl) > 3.0)  # consecutive elastic roots, none skipped or repeated
    p = eb_props(props(20))
    c = math.sqrt(E * p["second_moment"] / (RHO * p["area"])) / p["length"] ** 2
    np.testing.assert_allclose(euler_bernoulli_free_free(3, **p), bl[:3] ** 2 * c, rtol=1e-14)
    np.testing.assert_allclose(euler_bernoulli_pinned_pinned(3, **p), (np.arange(1, 4) * math.pi) ** 2 * c,
                               rtol=1e-14)


# ----------------------------------------------------------------------------- slender limit


def test_slender_limit_is_euler_bernoulli():
    p = props(200)
    for tim, eb in ((timoshenko_pinned_pinned(3, **p), euler_bernoulli_pinned_pinned(3, **eb_props(p))),
                    (timoshenko_free_free(3, **p), euler_bernoulli_free_free(3, **eb_props(p)))):
        np.testing.assert_allclose(tim, eb, rtol=5e-4)
        assert np.all(tim < eb)


def _first_order_reduction(kind, beta_l, p):
    """1 - omega_T / omega_EB to first order in (r/L)^2, from the Rayleigh quotient of the EB mode W:
    omega^2 = omega_EB^2 (1 - eps), eps = (I/A) int W'^2 / int W^2 + (E I/(kappa G A)) int W'''^2 / int W''^2
    (rotary inertia, shear flexibility), lengths in units of L."""
    b = beta_l
    if kind == "pinned":
        derivs = [lambda x, m=m: (b**m) * math.sin(b * x + m * math.pi / 2) for m in range(4)]
    else:
        s = (math.cosh(b) - math.cos(b)) / (math.sinh(b) - math.sin(b))
        derivs = [lambda x, m=m: b**m * (_hyp(m, b * x, True) + math.cos(b * x + m * math.pi / 2)
                                          - s * (_hyp(m, b * x, False) + math.sin(b * x + m * math.pi / 2)))
                  for m in range(4)]
    sq = [quad(lambda x, f=f: f(x) ** 2, 0, 1, limit=200, epsabs=0, epsrel=1e-12)[0] for f in derivs]
    r2 = p["second_moment"] / p["area"] / p["length"] ** 2
    eps = r2 * sq[1] / sq[0] + r2 * E / (KAPPA * G) * sq[3] / sq[2]
    return 1 - math.sqrt(1 - eps)


def _hyp(m, z, cosh_first):
    """m-th derivative (per unit argument) of cosh (cosh_first) or sinh."""
    return math.cosh(z) if (m % 2 == 0) == cosh_first else math.sinh(z)


@pytest.mark.parametrize("kind", ["pinned", "free"])
def test_first_order_shear_and_rotary_inertia_correction(kind):
    """For a slender beam the exact reduction below Euler-Bernoulli tends to the first-order
    Rayleigh-quotient value, free-end boundary terms included (free-free first mode: ~3 % below the
    naive 1/2 (beta r)^2 (1 + E / kappa G))."""
    p = props(100)
    if kind == "pinned":
        tim, eb, bl = (timoshenko_pinned_pinned(3, **p), euler_bernoulli_pinned_pinned(3, **eb_props(p)),
                       np.arange(1, 4) * math.pi)
    else:
        tim, eb, bl = timoshenko_free_free(3, **p), euler_bernoulli_free_free(3, **eb_props(p)), free_free_beta_l(3)
    reduction = 1 - tim / eb
    first_order = np.array([_first_order_reduction(kind, b, p) for b in bl])
    # the neglected terms are O(eps) relative: eps < 3e-3 here
    np.testing.assert_allclose(reduction, first_order, rtol=5e-3)
    if kind == "free":
        naive = 0.5 * (bl * math.sqrt(p["second_moment"] / p["area"]) / p["length"]) ** 2 * (1 + E / (KAPPA * G))
        assert reduction[0] < 0.985 * naive[0]  # the free-end boundary terms matter and are captured


# ----------------------------------------------------------------------------- stocky beam


def test_stocky_beam_below_euler_bernoulli_by_a_plausible_amount():
    p = props(5)  # L/D = 5
    for kind, tim, eb, bl in (
            ("pinned", timoshenko_pinned_pinned(3, **p), euler_bernoulli_pinned_pinned(3, **eb_props(p)),
             np.arange(1, 4) * math.pi),
            ("free", timoshenko_free_free(3, **p), euler_bernoulli_free_free(3, **eb_props(p)), free_free_beta_l(3))):
        reduction = 1 - tim / eb
        assert np.all(np.diff(reduction) > 0), kind  # shear matters more for shorter wavelengths
        first_order = _first_order_reduction(kind, bl[0], p)
        # first mode: a few to ~10 % below EB; the first-order estimate overshoots at this slenderness
        assert 0.03 < reduction[0] < 0.12, (kind, reduction)
        assert 0.75 * first_order < reduction[0] < first_order, (kind, reduction[0], first_order)
    assert 0.25 < 1 - tim[2] / eb[2] < 0.4  # free-free third mode: ~31 % below EB


# ----------------------------------------------------------------------------- shooting cross-check


def _shoot(omega, p, bc):
    """Shooting solution of the Timoshenko ODEs (x/L, w/L): integrate from x = 0 and from x = L to the
    midspan, each for the two independent states that satisfy that end's boundary conditions, and
    return the normalised 4x4 matching determinant at x = L/2 (zero at a natural frequency).
    Meeting at midspan keeps the growth of the hyperbolic part to e^{a L/2}."""
    L, A, I = p["length"], p["area"], p["second_moment"]
    lam = RHO * omega**2 * L**2 / (KAPPA * G)  # from kappa G A (w'' - psi') + rho A omega^2 w = 0
    sig = KAPPA * G * A * L**2 / (E * I)  # from E I psi'' + kappa G A (w' - psi) + rho I omega^2 psi = 0
    rot = RHO * omega**2 * L**2 / E

    def rhs(x, y):  # two stacked states [w, w', psi, psi']
        out = []
        for w, dw, psi, dpsi in (y[:4], y[4:]):
            out += [dw, dpsi - lam * w, dpsi, -sig * (dw - psi) - rot * psi]
        return out

    if bc == "free":  # psi' = 0 (moment), w' - psi = 0 (shear force)
        y0 = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0]
    else:  # pinned: w = 0, psi' = 0
        y0 = [0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0]
    cols = []
    for span in ((0.0, 0.5), (1.0, 0.5)):
        y = solve_ivp(rhs, span, y0, method="DOP853", rtol=1e-13, atol=1e-16).y[:, -1]
        cols += [y[:4] / np.linalg.norm(y[:4]), y[4:] / np.linalg.norm(y[4:])]
    return np.linalg.det(np.array(cols).T)


def _shooting_roots(p, bc, omega_max, n_grid):
    grid = np.linspace(omega_max / n_grid, omega_max, n_grid)
    vals = np.array([_shoot(w, p, bc) for w in grid])
    return np.array([brentq(_shoot, grid[i], grid[i + 1], args=(p, bc), xtol=1e-13 * grid[i + 1])
                     for i in np.nonzero(vals[:-1] * vals[1:] < 0)[0]])


@pytest.mark.parametrize("slenderness, n_modes", [(5, 6), (4, 4), (50, 3)])
def test_free_free_against_shooting(slenderness, n_modes):
    """All shooting roots up to just past mode n_modes (rigid-body modes at 0 excluded) are the
    closed-form roots: none missing, none spurious."""
    p = props(slenderness)
    ref = timoshenko_free_free(n_modes + 1, **p)
    top = 0.5 * (ref[-2] + ref[-1])
    shoot = _shooting_roots(p, "free", top, 60 * n_modes)
    assert len(shoot) == n_modes
    np.testing.assert_allclose(shoot, ref[:-1], rtol=1e-9)


def test_free_free_cutoff_stocky():
    """L/D = 2: exactly two modes lie below omega_c (shooting agrees); the third raises ValueError."""
    p = props(2)
    wc = cutoff_frequency(**p)
    shoot = _shooting_roots(p, "free", wc * (1 - 1e-9), 200)
    ref = timoshenko_free_free(2, **p)
    assert len(shoot) == 2
    np.testing.assert_allclose(shoot, ref, rtol=1e-9)
    with pytest.raises(ValueError, match="cut-off"):
        timoshenko_free_free(3, **p)


def test_pinned_pinned_quadratic_against_shooting():
    """Below omega_c the pinned-pinned spectrum is exactly the lower roots of the quadratic."""
    p = props(5)
    wc = cutoff_frequency(**p)
    ref = timoshenko_pinned_pinned(12, **p)
    ref = ref[ref < wc]
    assert len(ref) >= 4
    shoot = _shooting_roots(p, "pinned", wc * (1 - 1e-9), 400)
    np.testing.assert_allclose(shoot, ref, rtol=1e-9)


def test_pinned_pinned_second_spectrum_excluded():
    """The quadratic's upper root (n = 1) is a genuine solution of the ODEs (shooting sign change) but
    belongs to the second spectrum; the returned values are the lower roots, which satisfy both ODEs
    with w = sin(k x), psi = C cos(k x)."""
    p = props(5)
    L, A, I = p["length"], p["area"], p["second_moment"]
    om = timoshenko_pinned_pinned(8, **p)
    for n, w in enumerate(om, start=1):  # direct substitution into the two ODEs
        k = n * math.pi / L
        c = (k**2 - RHO * w**2 / (KAPPA * G)) / k  # first equation, amplitude of psi per unit w
        residual = -E * I * k**2 * c + KAPPA * G * A * (k - c) + RHO * I * w**2 * c
        assert abs(residual) < 1e-9 * KAPPA * G * A * k
    k = math.pi / L
    qa, qb, qc = RHO**2 * I / (KAPPA * G), -(RHO * A + RHO * I * k**2 * (1 + E / (KAPPA * G))), E * I * k**4
    upper = math.sqrt((-qb + math.sqrt(qb * qb - 4 * qa * qc)) / (2 * qa))
    assert upper > cutoff_frequency(**p)
    assert _shoot(upper * (1 - 1e-4), p, "pinned") * _shoot(upper * (1 + 1e-4), p, "pinned") < 0
    assert np.all(np.abs(om / upper - 1) > 1e-3) and om[0] < upper


def test_free_free_moderate_beam_has_no_spurious_roots_near_cutoff():
    """L/D = 10: every mode up to omega_c, checked for count and value against shooting."""
    p = props(10)
    wc = cutoff_frequency(**p)
    shoot = _shooting_roots(p, "free", wc * (1 - 1e-9), 300)
    n = len(shoot)
    np.testing.assert_allclose(timoshenko_free_free(n, **p), shoot, rtol=1e-9)
    with pytest.raises(ValueError, match="cut-off"):
        timoshenko_free_free(n + 1, **p)


def test_input_validation():
    p = props(5)
    with pytest.raises(ValueError):
        timoshenko_free_free(2, **{**p, "length": -1.0})
    with pytest.raises(ValueError):
        timoshenko_pinned_pinned(2, **{**p, "shear_coefficient": 0.0})
    assert timoshenko_free_free(0, **p).shape == (0,)

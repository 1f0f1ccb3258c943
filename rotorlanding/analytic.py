"""Exact natural frequencies of a uniform beam (reference values for the finite element).

Used by the tests to verify the finite-element rotor (``rotorlanding.timoshenko``). SI inputs,
frequencies in rad/s, ascending; one bending plane.

Timoshenko theory (shear deformation and rotary inertia), harmonic motion at omega, deflection
w(x), cross-section rotation psi(x), shear coefficient kappa::

    kappa G A (w'' - psi') + rho A omega^2 w = 0
    E I psi'' + kappa G A (w' - psi) + rho I omega^2 psi = 0

Solutions e^{s x} require, with g = rho omega^2 / (kappa G), r = rho omega^2 / E,
sigma = kappa G A / (E I)::

    s^4 + (g + r) s^2 + g (r - sigma) = 0,        psi = (s^2 + g) / s * w.

Below the cut-off frequency omega_c = sqrt(kappa G A / (rho I)) (where r = sigma) the roots in s^2
are a^2 > 0 and -b^2 < 0.

Pinned-pinned, w = 0 and E I psi' = 0 at x = 0, L: w = sin(k x), psi = C cos(k x), k = n pi / L is
exact, and omega solves the quadratic in omega^2::

    (rho^2 I / (kappa G)) omega^4 - [rho A + rho I k^2 (1 + E / (kappa G))] omega^2 + E I k^4 = 0.

Mode n is its lower root (the first spectrum). The upper root belongs to the second spectrum
(its k -> 0 limit is omega_c); it is excluded.

Free-free, bending moment E I psi' = 0 and shear force kappa G A (w' - psi) = 0 at x = 0, L. The
general solution is w = C1 cosh(a x) + C2 sinh(a x) + C3 cos(b x) + C4 sin(b x), and psi follows from
the first equation (psi' = w'' + g w). A uniform beam's modes are symmetric or antisymmetric about
the midspan. With xi = x - L/2, h = L/2 and bounded, pole-free basis functions, the 4x4 boundary
determinant therefore splits into two 2x2 determinants::

    symmetric:      (a^2 + g) sin(b h) / b  +  (b^2 - g) cos(b h) tanh(a h) / a
    antisymmetric:  (a^2 + g) a tanh(a h) cos(b h)  -  (b^2 - g) b sin(b h)

(rows normalised to unit length in the code). a^2 + g > 0 and b^2 - g > 0 for 0 < omega < omega_c,
and tanh(a h)/a -> h as a -> 0, so both are continuous and finite: every sign change is a root, and
there are no poles. Roots are bracketed on a fine grid (steps of pi/100 in b L) and refined with
brentq. Each root is then checked against the full 4x4 determinant of the free-boundary conditions,
built independently in the exponential basis e^{-a x}, e^{a (x - L)}, cos(b x), sin(b x) on [0, L]
(its rows and columns normalised, smallest singular value ~ 0). Only modes below omega_c are
computed. If a requested mode would lie above omega_c, the functions raise ValueError.

Euler-Bernoulli references: pinned-pinned beta_n L = n pi; free-free beta_n L are the elastic roots
of cos(beta L) cosh(beta L) = 1; omega = beta^2 sqrt(E I / (rho A)).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

__all__ = ["timoshenko_pinned_pinned", "timoshenko_free_free", "euler_bernoulli_pinned_pinned",
           "euler_bernoulli_free_free", "cutoff_frequency", "free_free_beta_l"]

_SCAN_STEP = math.pi / 100.0  # grid step in b L (roots of each symmetry class are ~2 pi apart)
_ROOT_TOL = 1e-8  # normalised residual (smallest singular value / largest) accepted at a root


def _check_positive(**kw):
    for name, value in kw.items():
        if not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a positive finite number, got {value!r}")


def _check_n(n_modes):
    if int(n_modes) != n_modes or n_modes < 0:
        raise ValueError(f"n_modes must be a non-negative integer, got {n_modes!r}")
    return int(n_modes)


def cutoff_frequency(*, youngs_modulus=None, shear_modulus, density, area, second_moment, shear_coefficient, **_):
    """omega_c = sqrt(kappa G A / (rho I)) [rad/s], where the second frequency spectrum starts."""
    return math.sqrt(shear_coefficient * shear_modulus * area / (density * second_moment))


# ----------------------------------------------------------------------------- Euler-Bernoulli


def free_free_beta_l(n_modes):
    """First ``n_modes`` elastic roots beta L of cos(beta L) cosh(beta L) = 1."""
    n_modes = _check_n(n_modes)
    out = []
    for n in range(1, n_modes + 1):
        # the root lies within 0.02 of (n + 1/2) pi; f = cos - sech has exactly one zero in +-0.5
        mid = (n + 0.5) * math.pi
        out.append(brentq(lambda x: math.cos(x) - 1.0 / math.cosh(x), mid - 0.5, mid + 0.5, xtol=1e-15, rtol=1e-15))
    return np.array(out)


EB_FREE_FREE_BETA_L = tuple(free_free_beta_l(5))  # 4.730040745, 7.853204624, 10.995607838, ...


def _eb_scale(length, youngs_modulus, density, area, second_moment):
    _check_positive(length=length, youngs_modulus=youngs_modulus, density=density, area=area,
                    second_moment=second_moment)
    return math.sqrt(youngs_modulus * second_moment / (density * area)) / length**2


def euler_bernoulli_pinned_pinned(n_modes, *, length, youngs_modulus, density, area, second_moment, **_):
    """Euler-Bernoulli pinned-pinned bending frequencies [rad/s]: beta_n L = n pi."""
    n_modes = _check_n(n_modes)
    c = _eb_scale(length, youngs_modulus, density, area, second_moment)
    return (np.arange(1, n_modes + 1) * math.pi) ** 2 * c


def euler_bernoulli_free_free(n_modes, *, length, youngs_modulus, density, area, second_moment, **_):
    """Euler-Bernoulli free-free elastic bending frequencies [rad/s]: cos(beta L) cosh(beta L) = 1."""
    c = _eb_scale(length, youngs_modulus, density, area, second_moment)
    return free_free_beta_l(n_modes) ** 2 * c


# ----------------------------------------------------------------------------- Timoshenko


def _timo_props(length, youngs_modulus, shear_modulus, density, area, second_moment, shear_coefficient):
    _check_positive(length=length, youngs_modulus=youngs_modulus, shear_modulus=shear_modulus, density=density,
                    area=area, second_moment=second_moment, shear_coefficient=shear_coefficient)
    return (float(length), float(youngs_modulus), float(shear_modulus), float(density), float(area),
            float(second_moment), float(shear_coefficient))


def _lower_omega(k, E, G, rho, A, I, kap):
    """Lower (first-spectrum) root omega of the wavenumber-k Timoshenko dispersion quadratic."""
    k = np.asarray(k, dtype=float)
    qa = rho**2 * I / (kap * G)
    qb = rho * A + rho * I * k**2 * (1.0 + E / (kap * G))
    qc = E * I * k**4
    # omega^2 = (qb - sqrt(qb^2 - 4 qa qc)) / (2 qa), written without cancellation
    return np.sqrt(2.0 * qc / (qb + np.sqrt(qb * qb - 4.0 * qa * qc)))


def timoshenko_pinned_pinned(n_modes, *, length, youngs_modulus, shear_modulus, density, area, second_moment,
                             shear_coefficient):
    """Pinned-pinned Timoshenko bending frequencies [rad/s], modes n = 1..n_modes (first spectrum).

    Exact: w = sin(n pi x / L), omega = lower root of the dispersion quadratic (module docstring).
    The second-spectrum branch (upper roots, all >= omega_c) is excluded.
    """
    n_modes = _check_n(n_modes)
    p = _timo_props(length, youngs_modulus, shear_modulus, density, area, second_moment, shear_coefficient)
    return _lower_omega(np.arange(1, n_modes + 1) * math.pi / p[0], *p[1:])


def _ab(omega, L, E, G, rho, A, I, kap):
    """Dimensionless a L, b L, g L^2 for 0 < omega < omega_c (arrays)."""
    w2 = np.asarray(omega, dtype=float) ** 2
    g = rho * w2 / (kap * G) * L**2
    r = rho * w2 / E * L**2
    sigma = kap * G * A / (E * I) * L**2
    p = g + r
    q = g * (r - sigma)  # < 0 below the cut-off
    root = p + np.sqrt(p * p - 4.0 * q)
    return np.sqrt(-2.0 * q / root), np.sqrt(root / 2.0), g


def _tanh_over(a, h):
    """tanh(a h) / a, with its limit h at a -> 0."""
    a = np.asarray(a, dtype=float)
    safe = np.where(a * h > 1e-8, a, 1.0)
    return np.where(a * h > 1e-8, np.tanh(safe * h) / safe, h)


def _free_free_dets(omega, p):
    """Normalised symmetric and antisymmetric free-free determinants (each in [-1, 1])."""
    a, b, g = _ab(omega, *p)
    h = 0.5
    ta = _tanh_over(a, h)
    cb, sb = np.cos(b * h), np.sin(b * h)
    m1, m2 = a * a + g, b * b - g  # both > 0 below the cut-off
    # symmetric: w = cosh(a xi)/cosh(a h), cos(b xi); rows: E I psi'(h), -(w' - psi)(h)/g
    s11, s12, s21, s22 = m1, -m2 * cb, ta, sb / b
    d_sym = (s11 * s22 - s12 * s21) / (np.hypot(s11, s12) * np.hypot(s21, s22))
    # antisymmetric: w = sinh(a xi)/(alpha cosh(a h)) with psi = cosh(a xi)/cosh(a h), alpha = (a^2+g)/a; sin(b xi)
    a11, a12, a21, a22 = a * a * ta, -m2 * sb, -1.0 / m1, cb / b
    d_anti = (a11 * a22 - a12 * a21) / (np.hypot(a11, a12) * np.hypot(a21, a22))
    return d_sym, d_anti


def _free_free_matrix(omega, p):
    """Full 4x4 free-free boundary matrix in the exponential basis on [0, 1] (dimensionless, normalised).

    Columns: e^{-a x}, e^{a (x - 1)}, cos(b x), sin(b x) with psi = (s^2 + g)/s w for each exponent s.
    Rows: psi'(0), (w' - psi)(0), psi'(1), (w' - psi)(1).
    """
    a, b, g = (float(v) for v in _ab(omega, *p))
    e = math.exp(-a)
    cb, sb = math.cos(b), math.sin(b)
    m1, m2 = a * a + g, b * b - g
    # e^{-a x}: psi = -(m1/a) e^{-a x}, psi' = m1 e^{-a x}, w' - psi = (g/a) e^{-a x}
    # e^{a(x-1)}: psi = (m1/a) e^{a(x-1)}, psi' = m1 e^{a(x-1)}, w' - psi = -(g/a) e^{a(x-1)}
    # cos(b x): psi = -(m2/b) sin, psi' = -m2 cos, w' - psi = -(g/b) sin;  sin(b x): psi = (m2/b) cos,
    # psi' = -m2 sin, w' - psi = (g/b) cos.  Shear rows divided by g, so the hyperbolic columns carry 1/a.
    m = np.array([
        [m1, m1 * e, -m2, 0.0],
        [1.0 / a, -e / a, 0.0, 1.0 / b],
        [m1 * e, m1, -m2 * cb, -m2 * sb],
        [e / a, -1.0 / a, -sb / b, cb / b],
    ])
    m /= np.linalg.norm(m, axis=1, keepdims=True)
    m /= np.linalg.norm(m, axis=0, keepdims=True)
    return m


def _free_free_residual(omega, p):
    sv = np.linalg.svd(_free_free_matrix(omega, p), compute_uv=False)
    return sv[-1] / sv[0]


def timoshenko_free_free(n_modes, *, length, youngs_modulus, shear_modulus, density, area, second_moment,
                         shear_coefficient):
    """Free-free Timoshenko elastic bending frequencies [rad/s] (the plane's 2 rigid-body modes excluded).

    Raises ValueError if fewer than ``n_modes`` modes lie below the cut-off frequency omega_c.
    """
    n_modes = _check_n(n_modes)
    p = _timo_props(length, youngs_modulus, shear_modulus, density, area, second_moment, shear_coefficient)
    L, E, G, rho, A, I, kap = p
    wc = cutoff_frequency(shear_modulus=G, density=rho, area=A, second_moment=I, shear_coefficient=kap)
    if n_modes == 0:
        return np.zeros(0)
    # b L at omega_c (there a = 0, b^2 = g + r)
    bl_c = L * math.sqrt(rho * wc**2 * (1.0 / (kap * G) + 1.0 / E))

    def f_sym(w):
        return float(_free_free_dets(w, p)[0])

    def f_anti(w):
        return float(_free_free_dets(w, p)[1])

    roots = []
    bl_lo, bl_top = 0.05, bl_c * (1.0 - 1e-12)  # first elastic mode has b L > 4 (a scan from 1e-3 agrees)
    chunk = 2000
    while len(roots) < n_modes and bl_lo < bl_top:
        bl = bl_lo + _SCAN_STEP * np.arange(chunk + 1)
        last = bl[-1] >= bl_top
        bl = np.append(bl[bl < bl_top], bl_top) if last else bl
        grid = np.minimum(_lower_omega(bl / L, E, G, rho, A, I, kap), wc * (1.0 - 1e-12))  # omega(b): monotonic
        d_sym, d_anti = _free_free_dets(grid, p)
        for d, f in ((d_sym, f_sym), (d_anti, f_anti)):
            for i in np.nonzero(np.sign(d[:-1]) * np.sign(d[1:]) < 0)[0]:
                w = brentq(f, grid[i], grid[i + 1], xtol=1e-15 * grid[i + 1], rtol=1e-15, maxiter=200)
                # genuine root: continuous sign change to ~0 in the 2x2, and the full 4x4 is singular
                r2, r4 = abs(f(w)), _free_free_residual(w, p)
                if r2 > _ROOT_TOL or r4 > _ROOT_TOL:
                    raise RuntimeError(f"free-free root check failed at omega = {w!r} rad/s "
                                       f"(2x2 residual {r2:.2e}, 4x4 residual {r4:.2e})")
                roots.append(w)
        bl_lo = float(bl[-1])  # the next chunk starts where this one ended
    roots = np.sort(np.array(roots))
    if len(roots) < n_modes:
        raise ValueError(f"free-free Timoshenko beam: only {len(roots)} bending mode(s) lie below the cut-off "
                         f"frequency omega_c = {wc:.6g} rad/s ({wc / (2 * math.pi):.6g} Hz); mode {len(roots) + 1} "
                         f"of the {n_modes} requested would lie above it (second spectrum), where this "
                         f"solution form does not hold")
    return roots[:n_modes]

"""Closed-form / exact natural frequencies of a uniform Timoshenko beam (reference values).

Used by the tests to verify the finite-element rotor (``rotorlanding.timoshenko``). Timoshenko
theory with shear deformation and rotary inertia, harmonic motion at omega, deflection w(x) and
section rotation psi(x)::

    kappa G A (w'' - psi') + rho A omega^2 w = 0
    E I psi'' + kappa G A (w' - psi) + rho I omega^2 psi = 0

Pinned-pinned (w = 0, E I psi' = 0 at both ends): w = sin(n pi x / L) exactly, and omega solves

    (rho^2 I / (kappa G)) omega^4 - [rho A + rho I k^2 (1 + E / (kappa G))] omega^2 + E I k^4 = 0,
    k = n pi / L  (lower root; the upper root belongs to the second frequency spectrum).

Free-free (E I psi' = 0 and kappa G A (w' - psi) = 0 at both ends): with g = rho omega^2/(kappa G)
and r = rho omega^2 / E, exponential solutions e^{s x} have s^2 = S from
S^2 + (g + r) S + g (r - kappa G A/(E I)) = 0; below the cut-off omega_c = sqrt(kappa G A/(rho I))
one root is a^2 > 0 and the other -b^2 < 0, so

    w = D1 e^{-a x} + D2 e^{a (x - L)} + C3 cos(b x) + C4 sin(b x),   psi' = w'' + g w,

and the 4x4 boundary determinant (bounded exponentials, rows normalised) vanishes at the natural
frequencies. Roots are bracketed on a fine omega grid and refined with brentq. All frequencies in
rad/s, ascending; SI inputs.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

__all__ = ["timoshenko_pinned_pinned", "timoshenko_free_free", "euler_bernoulli_pinned_pinned",
           "euler_bernoulli_free_free", "cutoff_frequency"]

EB_FREE_FREE_BETA_L = (4.730040744862704, 7.853204624095838, 10.995607838001671, 14.137165491257464,
                       17.27875965739948)


def cutoff_frequency(*, youngs_modulus, shear_modulus, density, area, second_moment, shear_coefficient, **_):
    """omega_c = sqrt(kappa G A / (rho I)), start of the second frequency spectrum [rad/s]."""
    return math.sqrt(shear_coefficient * shear_modulus * area / (density * second_moment))


def euler_bernoulli_pinned_pinned(n_modes, *, length, youngs_modulus, density, area, second_moment, **_):
    c = math.sqrt(youngs_modulus * second_moment / (density * area))
    return np.array([(n * math.pi / length) ** 2 * c for n in range(1, n_modes + 1)])


def euler_bernoulli_free_free(n_modes, *, length, youngs_modulus, density, area, second_moment, **_):
    c = math.sqrt(youngs_modulus * second_moment / (density * area))
    beta = list(EB_FREE_FREE_BETA_L)
    while len(beta) < n_modes:  # asymptotic roots of cos cosh = 1
        beta.append((2 * len(beta) + 3) * math.pi / 2)
    return np.array([(bl / length) ** 2 * c for bl in beta[:n_modes]])


def timoshenko_pinned_pinned(n_modes, *, length, youngs_modulus, shear_modulus, density, area, second_moment,
                             shear_coefficient):
    E, G, rho, A, I, kap = youngs_modulus, shear_modulus, density, area, second_moment, shear_coefficient
    out = []
    for n in range(1, n_modes + 1):
        k = n * math.pi / length
        qa = rho**2 * I / (kap * G)
        qb = -(rho * A + rho * I * k**2 * (1 + E / (kap * G)))
        qc = E * I * k**4
        # lower root, written to avoid cancellation
        w2 = 2 * qc / (-qb + math.sqrt(qb * qb - 4 * qa * qc))
        out.append(math.sqrt(w2))
    return np.array(out)


def _free_free_det(omega, L, E, G, rho, A, I, kap):
    g = rho * omega**2 / (kap * G)
    r = rho * omega**2 / E
    p = g + r
    q = g * (r - kap * G * A / (E * I))
    disc = math.sqrt(p * p - 4 * q)
    a = math.sqrt((-p + disc) / 2)
    b = math.sqrt((p + disc) / 2)
    e0 = math.exp(-a * L)
    cb, sb = math.cos(b * L), math.sin(b * L)
    m = np.array([
        [a * a + g, (a * a + g) * e0, g - b * b, 0.0],          # E I psi'(0)
        [1 / a, -e0 / a, 0.0, 1 / b],                           # (w' - psi)(0) / g
        [(a * a + g) * e0, a * a + g, (g - b * b) * cb, (g - b * b) * sb],  # E I psi'(L)
        [e0 / a, -1 / a, -sb / b, cb / b],                      # (w' - psi)(L) / g
    ])
    m /= np.abs(m).max(axis=1, keepdims=True)
    return np.linalg.det(m)


def timoshenko_free_free(n_modes, *, length, youngs_modulus, shear_modulus, density, area, second_moment,
                         shear_coefficient):
    """Elastic bending frequencies of a free-free Timoshenko beam (rigid-body modes excluded)."""
    args = (length, youngs_modulus, shear_modulus, density, area, second_moment, shear_coefficient)
    wc = cutoff_frequency(youngs_modulus=youngs_modulus, shear_modulus=shear_modulus, density=density, area=area,
                          second_moment=second_moment, shear_coefficient=shear_coefficient)
    eb = euler_bernoulli_free_free(n_modes + 1, length=length, youngs_modulus=youngs_modulus, density=density,
                                   area=area, second_moment=second_moment)
    # Timoshenko frequencies lie below the Euler-Bernoulli ones: scan up to the next EB root
    top = min(eb[-1] * 1.05, wc * (1 - 1e-9))
    grid = np.linspace(eb[0] * 1e-3, top, 4000 * (n_modes + 1))
    vals = np.array([_free_free_det(w, *args) for w in grid])
    roots = []
    for k in np.nonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0)[0]:
        w = brentq(_free_free_det, grid[k], grid[k + 1], args=args, xtol=1e-13 * grid[k + 1], rtol=1e-14)
        # a genuine root: |det| small on both sides relative to the scan values (no pole/jump)
        if abs(_free_free_det(w, *args)) < 1e-8:
            roots.append(w)
        if len(roots) == n_modes:
            break
    if len(roots) < n_modes:
        raise ValueError(f"only {len(roots)} free-free modes below min(EB bound, cut-off {wc:.4g} rad/s); "
                         f"requested {n_modes}: the higher modes lie in the second spectrum")
    return np.array(roots)

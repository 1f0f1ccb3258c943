"""FE rotor vs the closed-form Timoshenko frequency equations; mesh convergence rate."""

import numpy as np
import pytest

from rotorlanding.analytic import timoshenko_free_free, timoshenko_pinned_pinned
from rotorlanding.timoshenko import assemble, cowper_shear_coefficient

from helpers import STEEL, planar_frequencies_rad, plane_y, uniform_shaft

E, NU, RHO = STEEL["youngs_modulus"], STEEL["poisson_ratio"], STEEL["density"]
G = E / (2 * (1 + NU))


def _exact(kind, length, d_out, d_in=0.0, n=3):
    area = np.pi / 4 * (d_out**2 - d_in**2)
    inertia = np.pi / 64 * (d_out**4 - d_in**4)
    f = timoshenko_pinned_pinned if kind == "pinned" else timoshenko_free_free
    return f(n, length=length, youngs_modulus=E, shear_modulus=G, density=RHO, area=area, second_moment=inertia,
             shear_coefficient=cowper_shear_coefficient(NU, d_in, d_out))


def _fe(kind, length, d_out, elements, d_in=0.0, n=3):
    fe = assemble(uniform_shaft(length, d_out, elements, inner_diameter=d_in))
    if kind == "pinned":
        dofs = plane_y(fe, fixed_nodes=(0, len(fe.nodes) - 1))
        return planar_frequencies_rad(fe, dofs, n)
    w = planar_frequencies_rad(fe, plane_y(fe), n + 2)
    assert np.all(w[:2] < 1e-3 * w[2])  # the plane's two rigid-body modes
    return w[2:]


# slender (L/D = 40), stocky (L/D = 4) and a stocky hollow shaft
CASES = [(1.2, 0.03, 0.0), (0.24, 0.06, 0.0), (0.3, 0.08, 0.05)]


@pytest.mark.parametrize("kind", ["pinned", "free"])
@pytest.mark.parametrize("length, d_out, d_in", CASES)
def test_first_three_frequencies_within_0p1_percent(kind, length, d_out, d_in):
    exact = _exact(kind, length, d_out, d_in)
    fe = _fe(kind, length, d_out, 64, d_in)
    np.testing.assert_allclose(fe, exact, rtol=1e-3)


def test_stocky_shaft_is_timoshenko_not_euler_bernoulli():
    """The shear/rotary-inertia reduction is large for L/D = 4 and the FE reproduces it."""
    length, d = 0.24, 0.06
    area, inertia = np.pi / 4 * d**2, np.pi / 64 * d**4
    eb = np.array([(n * np.pi / length) ** 2 * np.sqrt(E * inertia / (RHO * area)) for n in (1, 2, 3)])
    tim = _exact("pinned", length, d)
    assert np.all(tim < 0.97 * eb) and tim[2] < 0.8 * eb[2]
    fe = _fe("pinned", length, d, 64)
    assert np.all(np.abs(fe - tim) < 0.05 * np.abs(eb - tim))


def test_mesh_convergence_rate():
    """Frequency error falls as h^2 for the stocky shaft (constant-shear-strain element:
    the shear and rotary-inertia terms converge at second order) and at least as fast for a
    slender one (bending-dominated: up to h^4 pre-asymptotically)."""
    for (length, d), lo, hi in (((0.24, 0.06), 1.8, 2.3), ((1.2, 0.03), 1.8, 4.3)):
        exact = _exact("pinned", length, d)
        errs = [np.abs(_fe("pinned", length, d, n) - exact) / exact for n in (8, 16, 32)]
        for coarse, fine in zip(errs[:-1], errs[1:]):
            order = np.log2(coarse / fine)
            assert np.all(order > lo) and np.all(order < hi), order

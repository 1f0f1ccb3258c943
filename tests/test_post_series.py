"""The compiled post-processing series (rotorlanding.bearing_kernel.*_series) against the plain
per-sample loop of the same user_forces law: an independent evaluation of the same equations, on
random states that cover contact and no contact, both whirl senses and loaded and unloaded faces."""

import math

import numpy as np
import pytest

from rotorlanding import bearing_kernel as K
from user_forces.ball_bearing import ball_force, harris_palmgren_constants, harris_palmgren_fast
from user_forces.contact_stress import STEEL_E_STAR, conformal_radius, sleeve_ring_line
from user_forces.radial_contact import radial_contact
from user_forces.ribbon import ribbon_force
from user_forces.thermal import STEEL_52100, blok_partition_fast

RNG = np.random.default_rng(16)
N = 4000
CL, RR = 2e-4, 0.0298


def _u(lo, hi, n=N):
    return RNG.uniform(lo, hi, n)


def test_radial_series_is_the_law_per_sample():
    dy, dz = _u(-3e-4, 3e-4), _u(-3e-4, 3e-4)  # about half the samples in contact
    dvy, dvz, om, wi = _u(-0.1, 0.1), _u(-0.1, 0.1), _u(-800, 800), _u(-800, 800)
    law = (CL, 6e10, 1.5, 1.4e12, 0.3, 1e-3, RR, RR + CL)
    out = np.zeros((N, 8))
    K.radial_series(dy, dz, dvy, dvz, om, wi, *law, out)
    ref = np.zeros((N, 8))
    for i in range(N):
        fy, fz, _, _, fn, delta, vs, pf = radial_contact(dy[i], dz[i], dvy[i], dvz[i], om[i], wi[i], *law)
        ref[i, [0, 1, 2, 4, 5]] = fy, fz, fn, vs, pf
        if delta > 0:
            ddot = (dy[i] * dvy[i] + dz[i] * dvz[i]) / math.hypot(dy[i], dz[i])
            ref[i, 3], ref[i, 6], ref[i, 7] = delta, (fn - 6e10 * delta ** 1.5) * ddot, 6e10 * delta ** 2.5 / 2.5
    assert 0.2 < np.mean(ref[:, 3] > 0) < 0.8
    np.testing.assert_allclose(out, ref, rtol=1e-13, atol=1e-300)


def test_ball_drag_and_ribbon_series_are_the_laws_per_sample():
    ey, ez, evy, evz = _u(-1e-4, 1e-4), _u(-1e-4, 1e-4), _u(-0.05, 0.05), _u(-0.05, 0.05)
    out = np.zeros((N, 3))
    K.ball_series(ey, ez, evy, evz, 1.5e8, 2.4e12, 3000.0, out)
    for i in range(0, N, 7):
        assert tuple(out[i, :2]) == pytest.approx(ball_force(ey[i], ez[i], 1.5e8, 2.4e12, evy[i], evz[i], 3000.0),
                                                  rel=1e-14)
        r = math.hypot(ey[i], ez[i])
        assert out[i, 2] == pytest.approx(1.5e8 * r * r / 2 + 2.4e12 * r ** 3 / 3, rel=1e-14)
    hp = harris_palmgren_constants(40.0, 4.5e4, 0.0425, 1e-3, 0.33)  # a 7212 BE as in the rig file
    wi, n_ax = _u(-800, 800), np.where(_u(0, 1) > 0.5, _u(0, 4000), 0.0)
    thp = np.zeros(N)
    K.drag_series(wi, out[:, 0], out[:, 1], n_ax, 150.0, tuple(hp), thp)
    ref = [harris_palmgren_fast(wi[i], math.hypot(out[i, 0], out[i, 1]), n_ax[i] + 150.0, hp) for i in range(N)]
    np.testing.assert_allclose(thp, ref, rtol=1e-13)
    oy, oz, ovy, ovz = _u(-1e-4, 1e-4), _u(-1e-4, 1e-4), _u(-0.05, 0.05), _u(-0.05, 0.05)
    rib = np.zeros((N, 4))
    K.ribbon_series(oy, oz, ovy, ovz, 6.3e7, 2e3, 0.1, 1e-3, rib)
    for i in range(0, N, 7):
        fy, fz = ribbon_force(oy[i], oz[i], ovy[i], ovz[i], 6.3e7, 2e3, 0.1, 1e-3)
        assert tuple(rib[i, :2]) == pytest.approx((fy, fz), rel=1e-13)
        assert rib[i, 2] == pytest.approx(0.5 * 6.3e7 * (oy[i] ** 2 + oz[i] ** 2), rel=1e-14)
        cc = (fy + 2e3 * ovy[i] + 6.3e7 * oy[i], fz + 2e3 * ovz[i] + 6.3e7 * oz[i])
        assert rib[i, 3] == pytest.approx(-(cc[0] * ovy[i] + cc[1] * ovz[i]), rel=1e-9, abs=1e-12)


def test_blok_series_are_the_partition_per_sample():
    fn = np.where(_u(0, 1) > 0.3, _u(0, 8000), 0.0)
    om, wi = _u(0, 800), _u(0, 800)
    m = STEEL_52100
    out = np.zeros(N)
    K.blok_sleeve_series(fn, om, wi, RR, RR + CL, conformal_radius(RR, RR + CL), 0.022, STEEL_E_STAR,
                         m.conductivity, m.diffusivity, out)
    for i in range(N):
        b = sleeve_ring_line(fn[i], RR, RR + CL, 0.022, STEEL_E_STAR)[1] if fn[i] > 0 else 0.0
        ref = blok_partition_fast(om[i] * RR, wi[i] * (RR + CL), b, m.conductivity, m.diffusivity, m.conductivity,
                                  m.diffusivity) if b > 0 else 0.5
        assert out[i] == pytest.approx(ref, rel=1e-13)
    face = np.zeros(N)
    K.blok_face_series(om - 400, wi - 400, 0.036, 0.004, m.conductivity, m.diffusivity, face)
    for i in range(0, N, 7):
        assert face[i] == pytest.approx(blok_partition_fast(abs(om[i] - 400) * 0.036, abs(wi[i] - 400) * 0.036, 0.004,
                                                            m.conductivity, m.diffusivity, m.conductivity,
                                                            m.diffusivity), rel=1e-13)

"""Timoshenko element: closed-form matrices, symmetry, gyroscopic sign and the disk split."""

import numpy as np
import pytest

from rotorlanding.modal import modal_analysis
from rotorlanding.reduction import full_model
from rotorlanding.errors import InputError
from rotorlanding.rotor import rotor_from_dict
from rotorlanding.timoshenko import assemble, cowper_shear_coefficient, element_matrices, plane_matrices

from helpers import STEEL

L, E, G, RHO, A, I, KAPPA = 0.13, 2.1e11, 8.1e10, 7850.0, 2.8e-3, 6.2e-7, 0.85


def test_plane_matrices_match_closed_form_with_shear():
    """Quadrature of the shape functions = the textbook closed forms (Friswell 2010 eq 5.x)."""
    mt, mr, k = plane_matrices(L, E, G, RHO, A, I, KAPPA)
    p = 12 * E * I / (KAPPA * G * A * L**2)
    assert p > 0.1  # a stocky element, so the shear terms matter
    kc = E * I / (L**3 * (1 + p)) * np.array([
        [12, 6 * L, -12, 6 * L], [6 * L, (4 + p) * L**2, -6 * L, (2 - p) * L**2],
        [-12, -6 * L, 12, -6 * L], [6 * L, (2 - p) * L**2, -6 * L, (4 + p) * L**2]])
    m1, m2 = 13 / 35 + 7 / 10 * p + p**2 / 3, 11 / 210 + 11 / 120 * p + p**2 / 24
    m3, m4 = 9 / 70 + 3 / 10 * p + p**2 / 6, 13 / 420 + 3 / 40 * p + p**2 / 24
    m5, m6 = 1 / 105 + p / 60 + p**2 / 120, 1 / 140 + p / 60 + p**2 / 120
    mtc = RHO * A * L / (1 + p) ** 2 * np.array([
        [m1, m2 * L, m3, -m4 * L], [m2 * L, m5 * L**2, m4 * L, -m6 * L**2],
        [m3, m4 * L, m1, -m2 * L], [-m4 * L, -m6 * L**2, -m2 * L, m5 * L**2]])
    m7, m8, m9, m10 = 6 / 5, 1 / 10 - p / 2, 2 / 15 + p / 6 + p**2 / 3, 1 / 30 + p / 6 - p**2 / 6
    mrc = RHO * I / (L * (1 + p) ** 2) * np.array([
        [m7, m8 * L, -m7, m8 * L], [m8 * L, m9 * L**2, -m8 * L, -m10 * L**2],
        [-m7, -m8 * L, m7, -m8 * L], [m8 * L, -m10 * L**2, -m8 * L, m9 * L**2]])
    np.testing.assert_allclose(k, kc, rtol=1e-12, atol=1e-9 * np.abs(kc).max())
    np.testing.assert_allclose(mt, mtc, rtol=1e-12, atol=1e-12 * np.abs(mtc).max())
    np.testing.assert_allclose(mr, mrc, rtol=1e-12, atol=1e-12 * np.abs(mrc).max())


def test_element_symmetry_rigid_modes_and_skew_gyroscopic():
    m, k, g = element_matrices(L, E, G, RHO, A, I, KAPPA)
    np.testing.assert_allclose(m, m.T, atol=1e-14)
    np.testing.assert_allclose(k, k.T, atol=1e-6)
    np.testing.assert_allclose(g, -g.T, atol=1e-14)
    assert np.abs(g).max() > 0
    # rigid motions carry no strain: translation and tilt in both planes
    x2 = L
    for rigid in ([1, 0, 0, 0, 1, 0, 0, 0], [0, 1, 0, 0, 0, 1, 0, 0],
                  [0, 0, 0, 1, x2, 0, 0, 1],        # y = x, beta = dy/dx = 1
                  [0, 0, -1, 0, 0, x2, -1, 0]):     # z = x, alpha = -dz/dx = -1
        assert np.linalg.norm(k @ np.array(rigid, float)) < 1e-6 * np.abs(k).max()
    # G is the rotary-inertia pattern doubled (Ip = 2 I), coupling the two bending planes only
    mt, mr, _ = plane_matrices(L, E, G, RHO, A, I, KAPPA)
    assert g[2, 3] == pytest.approx(2 * mr[1, 1], rel=1e-12)
    plane_y, plane_z = [0, 3, 4, 7], [1, 2, 5, 6]
    assert np.abs(g[np.ix_(plane_y, plane_y)]).max() == 0.0
    assert np.abs(g[np.ix_(plane_z, plane_z)]).max() == 0.0


def test_assembled_gyroscopic_is_skew_and_total_mass():
    rotor = rotor_from_dict({"rotor": {
        "materials": {"s": STEEL},
        "sections": [{"length": 0.5, "outer_diameter": 0.06, "inner_diameter": 0.02, "material": "s", "elements": 5},
                     {"length": 0.3, "outer_diameter": 0.04, "material": "s", "elements": 3}],
        "disks": [{"name": "d", "position": 0.65, "mass": 3.0, "polar_inertia": 0.02, "transverse_inertia": 0.011}],
    }})
    fe = assemble(rotor)
    np.testing.assert_allclose(fe.G, -fe.G.T, atol=1e-15)
    # rigid translation: total mass = 1^T M 1 over the y DOFs
    ones = np.zeros(fe.ndof)
    ones[0::4] = 1.0
    shaft = 7850 * (np.pi / 4 * (0.06**2 - 0.02**2) * 0.5 + np.pi / 4 * 0.04**2 * 0.3)
    assert ones @ fe.M @ ones == pytest.approx(shaft + 3.0, rel=1e-12)
    assert fe.mass == pytest.approx(shaft + 3.0, rel=1e-12)
    # disk sits on a node and carries G[alpha, beta] = +Ip
    k = fe.disk_nodes["d"]
    assert fe.nodes[k] == pytest.approx(0.65)


def test_disk_given_by_geometry_equals_the_annulus_closed_form():
    base = {"materials": {"s": STEEL},
            "sections": [{"length": 0.5, "outer_diameter": 0.06, "material": "s", "elements": 2}]}
    rotor = rotor_from_dict({"rotor": dict(base, disks=[
        {"name": "a", "position": 0.0, "outer_diameter": 0.4, "inner_diameter": 0.06, "thickness": 0.05,
         "material": "s"}])})
    d = rotor.disks[0]
    assert rotor.name == "rotor" and d.name == "a"
    m = 7850 * np.pi / 4 * (0.4**2 - 0.06**2) * 0.05  # rho V
    # Ip = integral of r^2 dm over the annulus; Id = Ip/2 + m t^2/12 (thin-disk + thickness term)
    r_o, r_i = 0.2, 0.03
    ip = 7850 * 0.05 * np.pi / 2 * (r_o**4 - r_i**4)
    assert (d.mass, d.polar_inertia) == (pytest.approx(m, rel=1e-12), pytest.approx(ip, rel=1e-12))
    assert d.transverse_inertia == pytest.approx(ip / 2 + m * 0.05**2 / 12, rel=1e-12)
    for extra, field in (({"mass": 3.0}, "disks[0].mass"), ({"material": "x"}, "disks[0].material"),
                         ({"inner_diameter": 0.5}, "disks[0].inner_diameter")):
        disk = {"position": 0.0, "outer_diameter": 0.4, "thickness": 0.05, "material": "s"}
        disk.update(extra)
        with pytest.raises(InputError, match=field.replace("[", r"\[").replace("]", r"\]")):
            rotor_from_dict({"rotor": dict(base, disks=[disk])})


def test_cowper_coefficient_solid_and_thin_tube():
    assert cowper_shear_coefficient(0.3, 0.0, 1.0) == pytest.approx(6 * 1.3 / (7 + 1.8))
    # thin-walled tube limit m -> 1: 2(1+nu)/(4+3nu)
    assert cowper_shear_coefficient(0.3, 0.9999, 1.0) == pytest.approx(2 * 1.3 / (4 + 0.9), rel=1e-3)


def _overhung_disk_exact(a, b, d, m, ip, id_, speed):
    """Analytic whirl frequencies (Hz) of a disk overhung by b beyond a span a (massless EB shaft).

    Complex coordinates r = y + i z and phi = beta - i alpha (slope) turn the 4-DOF model into
    (k11 - m w^2)(k22 - Id w^2 + Ip Omega w) - k12^2 = 0; w > 0 forward, w < 0 backward.
    Flexibilities of the overhang (Roark): tip force -> b^2 (a+b)/3EI, b(2a+3b)/6EI;
    tip moment -> b(2a+3b)/6EI, (a+3b)/3EI.
    """
    ei = 2.1e11 * np.pi / 64 * d**4
    f = np.array([[b**2 * (a + b) / 3, b * (2 * a + 3 * b) / 6], [b * (2 * a + 3 * b) / 6, (a + 3 * b) / 3]]) / ei
    k = np.linalg.inv(f)
    om = speed * np.pi / 30
    # expand (k11 - m w^2)(k22 - Id w^2 + Ip om w) - k12^2 in powers of w
    p1 = np.array([-m, 0.0, k[0, 0]])
    p2 = np.array([-id_, ip * om, k[1, 1]])
    poly = np.polymul(p1, p2)
    poly[-1] -= k[0, 1] ** 2
    w = np.roots(poly)
    assert np.all(np.abs(w.imag) < 1e-6 * np.abs(w).max())
    w = w.real / (2 * np.pi)
    return np.sort(w[w > 0]), np.sort(-w[w < 0])


@pytest.mark.parametrize("speed", [0.0, 3000.0, 10000.0, 30000.0])
def test_overhung_disk_forward_backward_split(speed):
    a, b, d = 0.4, 0.15, 0.03
    m, ip, id_ = 10.0, 0.10, 0.06
    # Euler-Bernoulli (shear rigid), massless shaft; nu kept at 0.3 so kappa stays ~0.89
    massless = dict(STEEL, density=1.0, shear_modulus=1e18)
    rotor = rotor_from_dict({"rotor": {
        "materials": {"m": massless},
        "sections": [{"length": a, "outer_diameter": d, "material": "m", "elements": 4},
                     {"length": b, "outer_diameter": d, "material": "m", "elements": 2}],
        "stations": {"left": 0.0, "right": a},
        "disks": [{"name": "disk", "position": a + b, "mass": m, "polar_inertia": ip, "transverse_inertia": id_}],
        "supports": [{"station": "left", "kyy": 1e11, "kzz": 1e11}, {"station": "right", "kyy": 1e11, "kzz": 1e11}],
    }})
    system = full_model(assemble(rotor)).with_supports()
    res = modal_analysis(system, speed)
    fwd_exact, bwd_exact = _overhung_disk_exact(a, b, d, m, ip, id_, speed)
    modes = [md for md in res.modes if md.frequency_hz < 1.5 * max(fwd_exact.max(), bwd_exact.max())]
    if speed == 0.0:
        # no split: each frequency twice, no whirl sense
        f = np.sort([md.frequency_hz for md in modes])
        np.testing.assert_allclose(f[0::2], f[1::2], rtol=1e-7)
        np.testing.assert_allclose(f[0::2], fwd_exact, rtol=1e-3)
        np.testing.assert_allclose(bwd_exact, fwd_exact, rtol=1e-12)
        assert {md.whirl for md in modes} == {"none"}
        return
    fwd = np.sort([md.frequency_hz for md in modes if md.whirl == "forward"])
    bwd = np.sort([md.frequency_hz for md in modes if md.whirl == "backward"])
    np.testing.assert_allclose(fwd, fwd_exact, rtol=1e-3)
    np.testing.assert_allclose(bwd, bwd_exact, rtol=1e-3)
    # the conical (upper) forward mode stiffens with speed, the backward one softens
    assert fwd[-1] > bwd[-1]


def test_whirl_label_is_invariant_to_eigenvector_phase():
    from rotorlanding.modal import whirl_label

    rng = np.random.default_rng(1)
    shape = np.zeros(8, complex)
    shape[0], shape[1] = 1.0, -0.8j  # y = cos wt, z = 0.8 sin wt: turns +x (forward)
    shape[4], shape[5] = 0.5, -0.45j
    for _ in range(5):
        c = np.exp(1j * rng.uniform(0, 2 * np.pi)) * rng.uniform(0.1, 10)
        assert whirl_label(c * shape, symmetric=False)[0] == "forward"
        assert whirl_label(np.conj(c * shape), symmetric=False)[0] == "backward"
    assert whirl_label(np.array([1, 0, 0, 0, 1, 0, 0, 0], complex), symmetric=False)[0] == "none"

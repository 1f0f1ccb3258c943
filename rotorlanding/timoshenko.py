"""Timoshenko shaft element with gyroscopics, and assembly of the free rotor (paper eq 1).

Coordinates and sign conventions
--------------------------------
Rotor axis x (positions from the left end of the first section), lateral y (horizontal) and z
(vertical, gravity along -z); spin Omega about +x. Four DOFs per node, in this order::

    [y, z, alpha, beta]      alpha = rotation about +y,  beta = rotation about +z

For small rotations a section that turns by beta moves points further along +x towards +y and
by alpha towards -z, so for a thin (shear-free) shaft

    beta = +dy/dx,   alpha = -dz/dx.

Global DOF index of node k, DOF j is ``4 k + j``. Equation of motion of the lateral model::

    M q'' + (C + Omega G) q' + K q = F                                   (paper eq 1)

with G skew-symmetric. For a disk of polar inertia Ip, G[alpha, beta] = +Ip and
G[beta, alpha] = -Ip: Euler's equations for a disk with spin axis (1, beta, -alpha) give
Id alpha'' + Ip Omega beta' = M_y and Id beta'' - Ip Omega alpha' = M_z. Forward whirl (orbit of
y + i z turning in the sense of the spin) then stiffens with speed, backward softens; the test
suite checks this against the closed-form disk-on-shaft result.

Element (Friswell et al., *Dynamics of Rotating Machines*, 2010, sec. 5.4; Nelson 1980)
----------------------------------------------------------------------------------------
Each bending plane uses the "interdependent interpolation" Timoshenko element: cubic deflection
and quadratic section-rotation shape functions that make the shear strain constant along the
element and are exact for static end loads. With phi = 12 E I / (kappa G A L^2)::

    M_t = rho A  int N_v^T N_v dx        (translational, consistent)
    M_r = rho I  int N_psi^T N_psi dx    (rotary inertia)
    K   = E I int N_psi'^T N_psi' dx + kappa G A int (N_v' - N_psi)^T (N_v' - N_psi) dx
    G   = rho Ip int (N_alpha^T N_beta - N_beta^T N_alpha) dx,   Ip = 2 I  (so G = 2 x M_r pattern)

The integrals are evaluated by 5-point Gauss-Legendre quadrature, which is exact for these
polynomials; ``tests/test_timoshenko.py`` compares them with the closed-form matrices.
Shear coefficient: Cowper (1966) for a hollow circle, :func:`cowper_shear_coefficient`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .rotor import Rotor

DOF_NAMES = ("y", "z", "alpha", "beta")
NDOF_NODE = 4
GRAVITY = 9.80665  # m/s^2

_GAUSS_X, _GAUSS_W = np.polynomial.legendre.leggauss(5)
_GAUSS_XI = 0.5 * (_GAUSS_X + 1.0)
_GAUSS_W = 0.5 * _GAUSS_W

# In-plane element DOFs u = [v1, psi1, v2, psi2] (psi = section rotation, + like dv/dx).
# Plane x-y: v = y, psi = beta.   Plane x-z: v = z, psi = -alpha.
# Rows of P map the 8 element DOFs [y1 z1 a1 b1 y2 z2 a2 b2] to u.
_P_Y = np.zeros((4, 8))
_P_Y[[0, 1, 2, 3], [0, 3, 4, 7]] = 1.0
_P_Z = np.zeros((4, 8))
_P_Z[[0, 1, 2, 3], [1, 2, 5, 6]] = [1.0, -1.0, 1.0, -1.0]


def cowper_shear_coefficient(poisson_ratio: float, inner_diameter: float, outer_diameter: float) -> float:
    """Cowper's shear coefficient of a hollow circular section, m = d_in / d_out.

    kappa = 6 (1+nu)(1+m^2)^2 / [(7+6 nu)(1+m^2)^2 + (20+12 nu) m^2]; solid: 6(1+nu)/(7+6nu).
    """
    nu = poisson_ratio
    m2 = (inner_diameter / outer_diameter) ** 2
    return 6.0 * (1 + nu) * (1 + m2) ** 2 / ((7 + 6 * nu) * (1 + m2) ** 2 + (20 + 12 * nu) * m2)


def _shape_functions(xi: float, length: float, phi: float):
    """Deflection N_v, rotation N_psi and their x-derivatives at xi = x / L."""
    L, p, c = length, phi, 1.0 / (1.0 + phi)
    nv = c * np.array([
        1 - 3 * xi**2 + 2 * xi**3 + p * (1 - xi),
        L * (xi - 2 * xi**2 + xi**3 + 0.5 * p * (xi - xi**2)),
        3 * xi**2 - 2 * xi**3 + p * xi,
        L * (-xi**2 + xi**3 - 0.5 * p * (xi - xi**2)),
    ])
    dnv = c / L * np.array([
        -6 * xi + 6 * xi**2 - p,
        L * (1 - 4 * xi + 3 * xi**2 + 0.5 * p * (1 - 2 * xi)),
        6 * xi - 6 * xi**2 + p,
        L * (-2 * xi + 3 * xi**2 - 0.5 * p * (1 - 2 * xi)),
    ])
    npsi = c * np.array([
        6.0 / L * (xi**2 - xi),
        1 - 4 * xi + 3 * xi**2 + p * (1 - xi),
        6.0 / L * (xi - xi**2),
        -2 * xi + 3 * xi**2 + p * xi,
    ])
    dnpsi = c / L * np.array([
        6.0 / L * (2 * xi - 1),
        -4 + 6 * xi - p,
        6.0 / L * (1 - 2 * xi),
        -2 + 6 * xi + p,
    ])
    return nv, dnv, npsi, dnpsi


def plane_matrices(length, youngs_modulus, shear_modulus, density, area, second_moment, kappa, taper=None):
    """In-plane 4x4 (translational mass, rotary mass, stiffness) for u = [v1, psi1, v2, psi2].

    ``taper``: a conical element, (outer, inner) diameters [m] at its left and right ends
    ``(do_l, di_l, do_r, di_r)``; ``area`` and ``second_moment`` are then those of the mid-length
    section, which set phi (Genta & Gugliotta 1988, the conical element of ROSS), while the
    integrals take A(x) and I(x) of the linearly varying diameters (degree 2 and 4: the 5-point
    rule stays exact)."""
    L, E, G_, rho, A, I = length, youngs_modulus, shear_modulus, density, area, second_moment
    phi = 12.0 * E * I / (kappa * G_ * A * L**2)
    mt = np.zeros((4, 4))
    mr = np.zeros((4, 4))
    k = np.zeros((4, 4))
    for xi, w in zip(_GAUSS_XI, _GAUSS_W):
        if taper is not None:
            A, I = _section_properties(taper, xi)
        nv, dnv, npsi, dnpsi = _shape_functions(xi, L, phi)
        # shear strain dv/dx - psi per unit DOF, constant along the element; written out
        # because dnv - npsi cancels catastrophically for slender elements (phi -> 0)
        gamma = phi / ((1.0 + phi) * L) * np.array([-1.0, -0.5 * L, 1.0, -0.5 * L])
        mt += w * L * rho * A * np.outer(nv, nv)
        mr += w * L * rho * I * np.outer(npsi, npsi)
        k += w * L * (E * I * np.outer(dnpsi, dnpsi) + kappa * G_ * A * np.outer(gamma, gamma))
    return mt, mr, k


def _section_properties(taper, xi: float) -> tuple[float, float]:
    """(area [m^2], second moment [m^4]) at xi of a conical element ``(do_l, di_l, do_r, di_r)``."""
    do_l, di_l, do_r, di_r = taper
    do, di = do_l + (do_r - do_l) * xi, di_l + (di_r - di_l) * xi
    return np.pi / 4.0 * (do**2 - di**2), np.pi / 64.0 * (do**4 - di**4)


def element_matrices(length, youngs_modulus, shear_modulus, density, area, second_moment, kappa, taper=None):
    """8x8 (M, K, G) of one shaft element in DOF order [y1 z1 alpha1 beta1 y2 z2 alpha2 beta2]
    (``taper``: see :func:`plane_matrices`)."""
    mt, mr, k = plane_matrices(length, youngs_modulus, shear_modulus, density, area, second_moment, kappa, taper)
    mp = mt + mr
    m = _P_Y.T @ mp @ _P_Y + _P_Z.T @ mp @ _P_Z
    kk = _P_Y.T @ k @ _P_Y + _P_Z.T @ k @ _P_Z
    # beta(x) = N_psi P_Y q and alpha(x) = -N_psi P_Z q; rho*Ip*int N^T N = 2 * mr.
    p_alpha = -_P_Z
    g = 2.0 * (p_alpha.T @ mr @ _P_Y - _P_Y.T @ mr @ p_alpha)
    return m, kk, g


@dataclass
class RotorFE:
    """Finite element model of the free rotor (no supports)."""

    rotor: Rotor
    nodes: np.ndarray  # axial node positions, m
    M: np.ndarray
    K: np.ndarray
    G: np.ndarray  # gyroscopic matrix per unit spin speed (multiply by Omega in rad/s)
    C: np.ndarray  # non-rotating (Rayleigh) damping
    station_nodes: dict[str, int]
    disk_nodes: dict[str, int]
    mass: float  # total rotor mass, kg
    polar_inertia: float  # total polar moment of inertia about x, kg m^2
    # True once the supports marked in_landing are in K and C (``with_landing_supports``): then
    # ``support_matrices`` leaves them out, so ``with_supports`` of a model built on it cannot add them twice
    landing_supports_included: bool = False

    @property
    def ndof(self) -> int:
        return self.M.shape[0]

    def dof(self, station: str, name: str) -> int:
        """Global index of DOF ``name`` ('y', 'z', 'alpha', 'beta') at a station."""
        return NDOF_NODE * self.station_nodes[station] + DOF_NAMES.index(name)

    def node_dof(self, node: int, name: str) -> int:
        return NDOF_NODE * node + DOF_NAMES.index(name)

    def gravity_load(self, g: float = GRAVITY) -> np.ndarray:
        """Consistent nodal load of gravity along -z (forces and moments)."""
        accel = np.zeros(self.ndof)
        accel[1::NDOF_NODE] = -g
        return self.M @ accel


def _mesh(rotor: Rotor) -> tuple[np.ndarray, list[int]]:
    """Node positions and, per element, the index of the section it belongs to.

    Each section gets its own number of equal elements; stations and disks inside a section
    split it so that every station and disk sits on a node.
    """
    nodes = [0.0]
    owner = []
    x0 = 0.0
    points = sorted(set(list(rotor.stations.values()) + [d.position for d in rotor.disks]))
    for si, sec in enumerate(rotor.sections):
        x1 = x0 + sec.length
        tol = 1e-9 * max(1.0, x1)
        inner = [p for p in points if x0 + tol < p < x1 - tol]
        breaks = [x0] + inner + [x1]
        for a, b in zip(breaks[:-1], breaks[1:]):
            n = max(1, int(round(sec.elements * (b - a) / sec.length)))
            for j in range(1, n + 1):
                nodes.append(a + (b - a) * j / n)
                owner.append(si)
        x0 = x1
    return np.array(nodes), owner


def assemble(rotor: Rotor) -> RotorFE:
    """Assemble M, K, G, C of the free rotor (shaft elements + rigid disks)."""
    nodes, owner = _mesh(rotor)
    n = NDOF_NODE * len(nodes)
    M = np.zeros((n, n))
    K = np.zeros((n, n))
    G = np.zeros((n, n))
    mass = 0.0
    ip_total = 0.0
    starts = np.concatenate([[0.0], np.cumsum([s.length for s in rotor.sections])])
    for e, si in enumerate(owner):
        for sec in rotor.sections[si].parts:  # the section, then its coaxial layers on the same nodes
            mat = sec.material
            L = nodes[e + 1] - nodes[e]
            if sec.tapered:
                # the element's end diameters on the section's linear taper; kappa from the mean
                # diameters and phi from the mid-length section, as ROSS's conical element
                (do_l, di_l), (do_r, di_r) = (sec.diameters((x - starts[si]) / sec.length) for x in nodes[e:e + 2])
                taper = (do_l, di_l, do_r, di_r)
                kappa = cowper_shear_coefficient(mat.poisson_ratio, 0.5 * (di_l + di_r), 0.5 * (do_l + do_r))
                a_mid, i_mid = _section_properties(taper, 0.5)
                me, ke, ge = element_matrices(L, mat.youngs_modulus, mat.shear_modulus, mat.density,
                                              a_mid, i_mid, kappa, taper)
                a_mean = sum(w * _section_properties(taper, xi)[0] for xi, w in zip(_GAUSS_XI, _GAUSS_W))
                i_mean = sum(w * _section_properties(taper, xi)[1] for xi, w in zip(_GAUSS_XI, _GAUSS_W))
            else:
                kappa = cowper_shear_coefficient(mat.poisson_ratio, sec.inner_diameter, sec.outer_diameter)
                me, ke, ge = element_matrices(L, mat.youngs_modulus, mat.shear_modulus, mat.density,
                                              sec.area, sec.second_moment, kappa)
                a_mean, i_mean = sec.area, sec.second_moment
            idx = slice(NDOF_NODE * e, NDOF_NODE * (e + 2))
            M[idx, idx] += me
            K[idx, idx] += ke
            G[idx, idx] += ge
            mass += mat.density * a_mean * L
            ip_total += mat.density * 2.0 * i_mean * L

    m_shaft = M.copy() if rotor.damping_shaft_only else None

    def node_at(x: float) -> int:
        return int(np.argmin(np.abs(nodes - x)))

    disk_nodes = {}
    for d in rotor.disks:
        k = node_at(d.position)
        disk_nodes[d.name] = k
        b = NDOF_NODE * k
        M[b, b] += d.mass
        M[b + 1, b + 1] += d.mass
        M[b + 2, b + 2] += d.transverse_inertia
        M[b + 3, b + 3] += d.transverse_inertia
        G[b + 2, b + 3] += d.polar_inertia
        G[b + 3, b + 2] -= d.polar_inertia
        mass += d.mass
        ip_total += d.polar_inertia

    # Rayleigh damping of the whole free rotor, or (damping.shaft_only, ROSS's element damping) of
    # the shaft elements without the disks' mass
    C = rotor.mass_proportional_damping * (m_shaft if rotor.damping_shaft_only else M) + \
        rotor.stiffness_proportional_damping * K
    stations = {name: node_at(x) for name, x in rotor.stations.items()}
    return RotorFE(rotor, nodes, M, K, G, C, stations, disk_nodes, mass, ip_total)


def support_matrices(fe: RotorFE, *, in_landing_only: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Full-size stiffness and damping matrices of the rotor's linear supports (``in_landing_only``:
    of those that act in the landing model too)."""
    ks = np.zeros((fe.ndof, fe.ndof))
    cs = np.zeros((fe.ndof, fe.ndof))
    for s in fe.rotor.supports:
        if (in_landing_only and not s.in_landing) or (s.in_landing and fe.landing_supports_included):
            continue
        iy, iz = fe.dof(s.station, "y"), fe.dof(s.station, "z")
        ks[iy, iy] += s.kyy
        ks[iz, iz] += s.kzz
        ks[iy, iz] += s.kyz
        ks[iz, iy] += s.kzy
        cs[iy, iy] += s.cyy
        cs[iz, iz] += s.czz
        cs[iy, iz] += s.cyz
        cs[iz, iy] += s.czy
    return ks, cs


def landing_support_preload(fe: RotorFE) -> np.ndarray:
    """Full-size constant load [N, N m] of the ``in_landing`` supports relaxed off the levitated axis: a
    spring relaxed at u0 acts with -K_s (u - u0), whose constant part K_s u0 joins gravity (zero when every
    offset is 0). u0 is the supports' ``offset_y`` / ``offset_z`` at their stations."""
    f = np.zeros(fe.ndof)
    for s in fe.rotor.supports:
        if s.in_landing and (s.offset_y or s.offset_z):
            iy, iz = fe.dof(s.station, "y"), fe.dof(s.station, "z")
            f[iy] += s.kyy * s.offset_y + s.kyz * s.offset_z
            f[iz] += s.kzy * s.offset_y + s.kzz * s.offset_z
    return f


def with_landing_supports(fe: RotorFE) -> RotorFE:
    """The rotor as the landing model sees it: the free rotor plus the supports marked
    ``in_landing`` (springs to ground relaxed on the levitated axis, so the AMBs' hold before the
    drop is unchanged; one relaxed off it adds the constant load :func:`landing_support_preload`, which
    the landing adds to gravity). Without such supports, ``fe`` itself."""
    ks, cs = support_matrices(fe, in_landing_only=True)
    if not (ks.any() or cs.any()):  # (also when they are included already: then the matrices are zero)
        return fe
    return replace(fe, K=fe.K + ks, C=fe.C + cs, landing_supports_included=True)

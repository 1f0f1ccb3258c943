"""Linear rotor systems and Craig-Bampton reduction (paper section 2.2.1, ref. [22]).

A :class:`LinearRotor` holds M, K, C, G in some coordinates q and the map ``T`` from q to the
full FE DOFs (identity for the full model). Craig-Bampton keeps the boundary DOFs (y, z and
optionally alpha, beta of chosen stations) as physical coordinates and adds the lowest
fixed-interface modes::

    q_full = T [u_b; eta],   T = [[I, 0], [Psi, Phi]] (rows permuted to full order),
    Psi = -K_ii^-1 K_ib (static constraint modes),  Phi: K_ii Phi = M_ii Phi Lambda, Phi^T M_ii Phi = I

Rigid-body modes of the free rotor: the constraint modes reproduce rigid motion exactly, so the
reduced free rotor keeps its four rigid-body modes (two translations, two tilts) provided the
boundary DOFs restrain them (K_ii non-singular): two stations at different positions, or one
station with rotations. Otherwise :func:`craig_bampton` raises an InputError saying so.
Static response to loads anywhere is exact at the boundary DOFs whatever the number of modes,
because the condensed stiffness equals the Guyan (static) condensation.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg as sla

from .blas import blas_threads
from .errors import InputError
from .timoshenko import DOF_NAMES, NDOF_NODE, RotorFE, support_matrices


@dataclass
class LinearRotor:
    """Linear rotor model M q'' + (C + Omega G) q' + K q = f in coordinates q, q_full = T q."""

    M: np.ndarray
    K: np.ndarray
    C: np.ndarray
    G: np.ndarray
    T: np.ndarray
    names: list[str]
    fe: RotorFE
    boundary: list[int]  # indices into q of physical boundary DOFs (all DOFs for the full model)
    n_modes: int = 0  # fixed-interface modes kept (0 for the full model)

    @property
    def n(self) -> int:
        return self.M.shape[0]

    def index(self, station: str, dof: str) -> int:
        """Index in q of a physical station DOF (must be a boundary DOF of a reduced model)."""
        name = f"{station}.{dof}"
        if name not in self.names:
            raise InputError("station", name, f"not a coordinate of this model; coordinates: {', '.join(self.names[:12])}...")
        return self.names.index(name)

    def with_supports(self) -> "LinearRotor":
        """The same model with the rotor's linear supports added (K + T^T Ks T, C + T^T Cs T)."""
        ks, cs = support_matrices(self.fe)
        return replace(self, K=self.K + self.T.T @ ks @ self.T, C=self.C + self.T.T @ cs @ self.T)

    def gravity_load(self) -> np.ndarray:
        return self.T.T @ self.fe.gravity_load()


def _full_names(fe: RotorFE) -> list[str]:
    node_names = {k: f"node{k}" for k in range(len(fe.nodes))}
    for st, k in sorted(fe.station_nodes.items(), key=lambda kv: kv[1], reverse=True):
        node_names[k] = st
    return [f"{node_names[k]}.{d}" for k in range(len(fe.nodes)) for d in DOF_NAMES]


def full_model(fe: RotorFE) -> LinearRotor:
    """The unreduced FE model as a LinearRotor (T = identity)."""
    n = fe.ndof
    return LinearRotor(fe.M, fe.K, fe.C, fe.G, np.eye(n), _full_names(fe), fe, list(range(n)))


def boundary_dofs(fe: RotorFE, stations, rotations: bool) -> tuple[list[int], list[str]]:
    dofs, names = [], []
    seen = {}
    for st in stations:
        node = fe.station_nodes[st]
        if node in seen:
            raise InputError("rotor.reduction.boundary_stations", list(stations),
                             f"stations '{seen[node]}' and '{st}' sit on the same node")
        seen[node] = st
        for d in (DOF_NAMES if rotations else DOF_NAMES[:2]):
            dofs.append(NDOF_NODE * node + DOF_NAMES.index(d))
            names.append(f"{st}.{d}")
    return dofs, names


@blas_threads(1)  # one thread: faster at this size, the same floats on every machine (rotorlanding.blas)
def craig_bampton(fe: RotorFE, stations, n_modes: int, rotations: bool = False) -> LinearRotor:
    """Craig-Bampton reduction of the free rotor onto ``stations`` plus ``n_modes`` modes."""
    b, names = boundary_dofs(fe, stations, rotations)
    i = [k for k in range(fe.ndof) if k not in set(b)]
    if n_modes > len(i):
        raise InputError("rotor.reduction.modes", n_modes, f"must be <= {len(i)} (interior DOFs of the mesh)")
    K, M = fe.K, fe.M
    kii = K[np.ix_(i, i)]
    unrestrained = InputError("rotor.reduction.boundary_stations", list(stations),
                              "boundary DOFs do not restrain the rigid-body motion of the free rotor; "
                              "use two stations at different positions or boundary_rotations = true")
    # geometric test: the four rigid-body motions (y, z translations; tilts y = x, dy/dx = beta = 1
    # and z = x, alpha = -dz/dx = -1) must be fixed by the boundary DOFs. (A failing Cholesky alone
    # misses it when round-off leaves a tiny positive pivot, as for a rotor with a heavy disk.)
    x = np.asarray(fe.nodes, dtype=float)
    x = x - x.mean()
    rigid = np.zeros((fe.ndof, 4))
    rigid[0::4, 0] = 1.0
    rigid[1::4, 1] = 1.0
    rigid[0::4, 2], rigid[3::4, 2] = x, 1.0
    rigid[1::4, 3], rigid[2::4, 3] = x, -1.0
    sv = np.linalg.svd(rigid[b, :] / np.linalg.norm(rigid, axis=0), compute_uv=False)
    if len(sv) < 4 or sv[-1] < 1e-8 * max(sv[0], 1e-300):
        raise unrestrained
    try:
        chol = sla.cho_factor(kii)
    except np.linalg.LinAlgError:
        raise unrestrained from None
    psi = -sla.cho_solve(chol, K[np.ix_(i, b)])
    if n_modes:
        lam, phi = sla.eigh(kii, M[np.ix_(i, i)], subset_by_index=[0, n_modes - 1])
        phi = phi[:, np.argsort(lam)]
    else:
        phi = np.zeros((len(i), 0))
    T = np.zeros((fe.ndof, len(b) + n_modes))
    T[b, : len(b)] = np.eye(len(b))
    T[np.ix_(i, range(len(b)))] = psi
    T[np.ix_(i, range(len(b), len(b) + n_modes))] = phi

    def project(a):
        return T.T @ a @ T

    names = names + [f"mode{k + 1}" for k in range(n_modes)]
    return LinearRotor(project(M), project(K), project(fe.C), project(fe.G), T, names, fe,
                       list(range(len(b))), n_modes)


def reduce_rotor(fe: RotorFE) -> LinearRotor:
    """Craig-Bampton reduction as specified in the rotor's ``[rotor.reduction]`` table."""
    spec = fe.rotor.reduction
    if spec is None:
        raise InputError("rotor.reduction", None, "missing table: give boundary_stations and modes")
    return craig_bampton(fe, spec.boundary_stations, spec.modes, spec.boundary_rotations)

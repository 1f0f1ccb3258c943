"""Small builders shared by the tests (plain dicts in the rotor TOML schema)."""

from __future__ import annotations

import numpy as np

from rotorlanding.rotor import rotor_from_dict

STEEL = {"youngs_modulus": 2.1e11, "poisson_ratio": 0.3, "density": 7850.0}


def uniform_shaft(length, diameter, elements, inner_diameter=0.0, material=None, **extra):
    rotor = {
        "materials": {"m": dict(material or STEEL)},
        "sections": [{"length": length, "outer_diameter": diameter, "inner_diameter": inner_diameter,
                      "material": "m", "elements": elements}],
    }
    rotor.update(extra)
    return rotor_from_dict({"rotor": rotor})


def plane_y(fe, fixed_nodes=()):
    """Indices of the x-y bending plane DOFs (y, beta), without y at ``fixed_nodes``."""
    fixed = {4 * k for k in fixed_nodes}
    return [i for i in range(fe.ndof) if i % 4 in (0, 3) and i not in fixed]


def planar_frequencies_rad(fe, dofs, n):
    import scipy.linalg as sla

    lam = sla.eigh(fe.K[np.ix_(dofs, dofs)], fe.M[np.ix_(dofs, dofs)], eigvals_only=True)
    return np.sqrt(np.clip(lam, 0.0, None))[:n]

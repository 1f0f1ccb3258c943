"""Compiled arithmetic of the auto step's controller (rotorlanding.exudyn_model.StepController).

Its own module so the bearing kernel's numba cache is untouched. In plain numpy/Python the
controller cost ~5 us (error: fancy indexing, abs, max) plus ~10 us (the look-ahead's loop over the
bearings) per step, against a step of ~40-60 us (session 12, load ~4); compiled each is one call.
"""

from __future__ import annotations

import math

import numba
import numpy as np

_njit = numba.njit(cache=True, fastmath=False)


@_njit
def max_jump(a1, a0, idx):
    """max over idx of |a1 - a0| (the acceleration change of a step at the error coordinates)."""
    m = 0.0
    for k in range(idx.shape[0]):
        d = abs(a1[idx[k]] - a0[idx[k]])
        if d > m:
            m = d
    return m


@_njit
def time_to_contact(q, v, iy, ir, cl):
    """Smallest time until a free journal reaches its clearance circle at the present radial speed
    (inf when none is closing); bearing k: station y index iy[k], inner race y index ir[k] (z
    follows each), clearance cl[k]."""
    tau = np.inf
    for k in range(iy.shape[0]):
        a, b = iy[k], ir[k]
        dy = q[a] - q[b]
        dz = q[a + 1] - q[b + 1]
        # numba's hypot is the C library's: it differs from Python's math.hypot (the first, plain-Python
        # version) in the last bit for ~0.6 % of inputs, so a look-ahead-limited step can end 1 ulp
        # apart and a chaotic landing take another path (docs/performance.md 3b)
        dist = math.hypot(dy, dz)
        if dist >= cl[k] or dist == 0.0:
            continue
        rate = (dy * (v[a] - v[b]) + dz * (v[a + 1] - v[b + 1])) / dist
        if rate > 0.0:
            t = (cl[k] - dist) / rate
            if t < tau:
                tau = t
    return tau

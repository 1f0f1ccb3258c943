"""Modal analysis at any spin speed, whirl labels, Campbell diagram.

Damped eigenvalues of M q'' + (C + Omega G) q' + K q = 0 from the first-order form. Each
oscillatory mode is reported once (eigenvalue with positive imaginary part, lambda = s + i w):
frequency w / 2 pi (damped), damping ratio -s / |lambda|.

Whirl label from the orbit sense of the mode shape (not from signs of single DOFs): at every node
the motion Re(phi e^{i w t}) of w = y + i z splits into a forward circle of radius |phi_y + i phi_z|/2
and a backward one of radius |phi_y - i phi_z|/2. Summed over the nodes, the larger share decides:
forward if it turns with the spin (+x), backward otherwise. The label is invariant to the
arbitrary complex scaling of eigenvectors, so it cannot flip between runs. Without any
non-symmetric term (no spin, no cross-coupling) the modes are planar standing modes and repeated
pairs have no defined sense: they are labelled ``"none"``; so is a mode whose forward and
backward shares differ by less than 0.1 %.

Rigid-body modes of a free rotor are flagged and excluded from the reported modes: the rigid-body
subspace is the null space of K (undamped modes of (K, M) below 0.1 Hz), and a damped mode whose
mass-weighted shape lies more than 99 % in it is rigid. At speed this includes the gyroscopic
nutation of the free rigid rotor (a forward mode at about (Ip/Id) Omega), which is a rigid-body
motion with a non-zero frequency.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .safeio import save_figure
import scipy.linalg as sla

from .blas import blas_threads
from .reduction import LinearRotor
from .timoshenko import NDOF_NODE

RPM = 2.0 * np.pi / 60.0
PLANAR_TOL = 1e-3
RIGID_FREQ_HZ = 0.1
RIGID_SHARE = 0.99


@dataclass
class Mode:
    eigenvalue: complex
    frequency_hz: float
    damping_ratio: float
    whirl: str  # "forward" | "backward" | "none"
    forward_share: float  # forward orbit energy share in [0, 1]
    shape: np.ndarray  # complex shape in full FE DOFs (node-major y, z, alpha, beta)
    rigid: bool

    def to_dict(self) -> dict:
        return {"frequency_hz": float(self.frequency_hz), "damping_ratio": float(self.damping_ratio),
                "whirl": self.whirl}


@dataclass
class ModalResult:
    speed_rpm: float
    modes: list[Mode]  # elastic modes, sorted by frequency
    rigid_modes: list[Mode]


def whirl_label(shape_full: np.ndarray, symmetric: bool) -> tuple[str, float]:
    """(label, forward share) of a complex mode shape in full FE DOF order."""
    y = shape_full[0::NDOF_NODE]
    z = shape_full[1::NDOF_NODE]
    fwd = float(np.sum(np.abs(y + 1j * z) ** 2))
    bwd = float(np.sum(np.abs(y - 1j * z) ** 2))
    if fwd + bwd <= 1e-20 * max(1e-300, float(np.sum(np.abs(shape_full) ** 2))):
        # no translation anywhere (pure tilt): use the slope pair (dy/dx, dz/dx) = (beta, -alpha)
        sy = shape_full[3::NDOF_NODE]
        sz = -shape_full[2::NDOF_NODE]
        fwd = float(np.sum(np.abs(sy + 1j * sz) ** 2))
        bwd = float(np.sum(np.abs(sy - 1j * sz) ** 2))
    total = fwd + bwd
    share = fwd / total if total > 0 else 0.5
    if symmetric or abs(fwd - bwd) <= PLANAR_TOL * total:
        return "none", share
    return ("forward" if fwd > bwd else "backward"), share


def rigid_body_basis(system: LinearRotor) -> np.ndarray:
    """M-orthonormal basis of the rigid-body (zero-stiffness) subspace, shape (n, n_rigid)."""
    ks = 0.5 * (system.K + system.K.T)
    ms = 0.5 * (system.M + system.M.T)
    lam, vec = sla.eigh(ks, ms)
    return vec[:, lam < (2 * np.pi * RIGID_FREQ_HZ) ** 2]


@blas_threads(1)
def modal_analysis(system: LinearRotor, speed_rpm: float) -> ModalResult:
    """Damped modes of ``system`` at ``speed_rpm`` (spin about +x; negative speeds spin about -x).
    On one BLAS thread (``rotorlanding.blas``): faster at this size, the same floats on every machine."""
    omega = speed_rpm * RPM
    n = system.n
    D = system.C + omega * system.G
    K = system.K
    minv_k = np.linalg.solve(system.M, K)
    minv_d = np.linalg.solve(system.M, D)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-minv_k, -minv_d]])
    lam, vec = sla.eig(A)
    scale = np.max(np.abs(lam)) if lam.size else 1.0
    symmetric = np.allclose(K, K.T, rtol=1e-10, atol=1e-12 * np.max(np.abs(K)) + 1e-300) and \
        np.allclose(D, D.T, rtol=1e-10, atol=1e-12 * (np.max(np.abs(D)) + 1e-300))
    rb = rigid_body_basis(system)
    modes, rigid = [], []
    used = np.zeros(lam.size, dtype=bool)
    # each oscillatory pair once (positive imaginary part); zero and overdamped real eigenvalues
    # carry no whirl frequency and are not reported
    for k in np.argsort(np.abs(lam)):
        lk = lam[k]
        if lk.imag <= 1e-9 * scale or used[k]:
            continue
        used[k] = True
        phi = vec[:n, k]
        full = system.T @ phi
        is_rigid = False
        if rb.shape[1]:
            coeff = rb.T @ (system.M @ phi)
            is_rigid = np.vdot(coeff, coeff).real > RIGID_SHARE * np.vdot(phi, system.M @ phi).real
        label, share = whirl_label(full, symmetric)
        mode = Mode(complex(lk), abs(lk.imag) / (2 * np.pi),
                    float(-lk.real / abs(lk)) if abs(lk) > 0 else 0.0,
                    label, share, full, bool(is_rigid))
        (rigid if is_rigid else modes).append(mode)
    modes.sort(key=lambda m: m.frequency_hz)
    return ModalResult(float(speed_rpm), modes, rigid)


def campbell(system: LinearRotor, speeds_rpm, n_modes: int | None = None) -> list[ModalResult]:
    out = []
    for s in speeds_rpm:
        r = modal_analysis(system, s)
        if n_modes is not None:
            r.modes = r.modes[:n_modes]
        out.append(r)
    return out


def plot_campbell(results: list[ModalResult], path, *, title: str = "Campbell diagram", max_frequency_hz=None):
    """Campbell diagram (PNG): frequencies vs speed, marker colour = whirl sense, with the 1x line."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 5.5))
    styles = {"forward": ("tab:red", "^", "forward whirl"), "backward": ("tab:blue", "v", "backward whirl"),
              "none": ("0.4", "o", "no whirl sense (0 rpm / planar)")}
    seen = set()
    fmax = 0.0
    for r in results:
        for m in r.modes:
            c, mk, lab = styles[m.whirl]
            ax.plot(r.speed_rpm, m.frequency_hz, mk, color=c, ms=4, label=None if m.whirl in seen else lab)
            seen.add(m.whirl)
            fmax = max(fmax, m.frequency_hz)
    speeds = np.array([r.speed_rpm for r in results])
    top = max_frequency_hz or fmax * 1.05
    s = np.linspace(0, speeds.max() if speeds.size else 1.0, 50)
    ax.plot(s, s / 60.0, "k--", lw=1, label="1x (synchronous)")
    ax.set_xlim(left=0)
    ax.set_ylim(0, top)
    ax.set_xlabel("spin speed [rpm]")
    ax.set_ylabel("damped natural frequency [Hz]")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8, framealpha=0.9)
    fig.tight_layout()
    save_figure(fig, path, dpi=120)
    plt.close(fig)
    return path


def reduction_report(full: LinearRotor, reduced: LinearRotor, speeds_rpm, f_limit_hz: float) -> list[dict]:
    """Per speed and mode below ``f_limit_hz``: full vs reduced frequency and relative error."""
    rows = []
    for s in speeds_rpm:
        mf = modal_analysis(full, s).modes
        mr = modal_analysis(reduced, s).modes
        for k, m in enumerate(mf):
            if m.frequency_hz > f_limit_hz:
                break
            fr = mr[k].frequency_hz if k < len(mr) else float("nan")
            rows.append({"speed_rpm": float(s), "mode": k + 1, "whirl": m.whirl,
                         "full_hz": m.frequency_hz, "reduced_hz": fr,
                         "relative_error": (fr - m.frequency_hz) / m.frequency_hz})
    return rows

"""Rigid-body axial model of the rotor: axial contact force, eqs 2-5 (section 2.2.2), corrected.

x = rotor axial displacement from its centred position (x = 0, clearance cl_ax on either side),
v = dx/dt.  Stiffnesses: k_cb catcher bearing, k_ws axial (wave-spring) support, k_h housing;
series combinations

    k1 = (1/k_cb + 1/k_ws)^-1   (support not yet bottomed out),
    k2 = (1/k_cb + 1/k_h)^-1    (support fully deflected, housing in series with the bearing).

Axial force on the rotor F_ax (eqs 3-5), for x >= 0 (odd-symmetric for x < 0):

    0 <= x <= cl_ax                  : F_ax = 0
    cl_ax < x <= cl_ax + delta_m     : F_ax = -k1 (x - cl_ax)                       - c_ax v
    x > cl_ax + delta_m              : F_ax = -k2 (x - cl_ax - delta_m) - k1 delta_m - c_ax v

The term -k1 delta_m is the preload of the fully deflected support, so the elastic force is
continuous at both breakpoints.  delta_m is, as in the paper, the rotor travel beyond the
clearance at which the support bottoms out (the support's own deflection there is
k1 delta_m / k_ws).

Corrections / choices:

- eq 2 prints x'' = -F_thrust/m_r + F_ax: the mass divides only the thrust.  Newton:
  m_r x'' = F_thrust + F_ax (``axial_acceleration``), with F_thrust the signed actuator force
  along +x (the sign of the printed minus is a convention for the thrust direction; we keep the
  force signed, so a thrust towards +x is positive).
- The paper applies c_ax v in eq 3 at all x.  The damper belongs to the contact path
  (bearing + support); without contact nothing transmits it, so a free rotor inside the clearance
  would otherwise be braked by a phantom damper.  We apply c_ax only while in contact, and
  moreover clip the total contact force so that it never pulls (F_ax <= 0 for x > cl_ax,
  F_ax >= 0 for x < -cl_ax): a separating face cannot adhere.  The elastic force is continuous at
  both breakpoints; at x = +-cl_ax the damping part jumps from 0 to -c_ax v on impact (the usual
  Kelvin-Voigt impact jump) and is continuous on separation thanks to the clipping.
"""


def axial_force(x, v, cl_ax, delta_m, k_cb, k_ws, k_h, c_ax):
    """Axial contact force on the rotor F_ax [N] (eqs 3-5, corrected; see module docstring).

    x, v    : rotor axial displacement [m] and velocity [m/s]
    cl_ax   : axial clearance on each side [m];  delta_m: travel beyond cl_ax until the support
              bottoms out [m]
    k_cb, k_ws, k_h : bearing, support and housing axial stiffnesses [N/m]
    c_ax    : axial damping [N s/m], acting only in contact
    """
    if x > cl_ax:
        e = x - cl_ax
        k1 = 1.0 / (1.0 / k_cb + 1.0 / k_ws)
        if e <= delta_m:
            f = -k1 * e - c_ax * v
        else:
            f = -(e - delta_m) / (1.0 / k_cb + 1.0 / k_h) - k1 * delta_m - c_ax * v
        return f if f < 0.0 else 0.0
    if x < -cl_ax:
        e = x + cl_ax
        k1 = 1.0 / (1.0 / k_cb + 1.0 / k_ws)
        if e >= -delta_m:
            f = -k1 * e - c_ax * v
        else:
            f = -(e + delta_m) / (1.0 / k_cb + 1.0 / k_h) + k1 * delta_m - c_ax * v
        return f if f > 0.0 else 0.0
    return 0.0


def axial_acceleration(x, v, f_thrust, m_r, cl_ax, delta_m, k_cb, k_ws, k_h, c_ax):
    """Rotor axial acceleration from m_r x'' = F_thrust + F_ax (eq 2 corrected) [m/s^2]."""
    return (f_thrust + axial_force(x, v, cl_ax, delta_m, k_cb, k_ws, k_h, c_ax)) / m_r

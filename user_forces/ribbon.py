"""Ribbon damper (eqs 28-29) and axial-support friction (eq 30) on the outer race.

Ribbon (eqs 28-29).  x = (y, z) = outer-race centre relative to the housing centre, v its rate.
Force on the outer race (the housing gets the opposite):

    F = -c_rib v - k_rib x - k_rib Q x,   Q = [[0, -eta S_v], [eta S_v, 0]],

so -k_rib Q x = k_rib eta S_v (z, -y).  S_v is the (regularised) sign of the tangential velocity
v_t = (x cross v)_x / |x| = (y v_z - z v_y) / |x|, i.e. of the whirl sense of the outer race:

    S_v = reg(v_t) = h / sqrt(h^2 + v_reg^2 |x|^2),  h = y v_z - z v_y,

written without dividing by |x| (S_v = 0 at x = 0, where the cross term vanishes anyway).

What the cross-coupled term does: its force k_rib eta S_v (z, -y) is tangential and points against
the whirl sense, so its power is F_cc . v = -k_rib eta |x| v_t reg(v_t) <= 0 for any motion.  On a
circular orbit of radius R at whirl rate w (either sense) it dissipates k_rib eta R^2 |w| per unit
time, i.e. 2 pi k_rib eta R^2 per cycle independent of frequency: a hysteretic (structural)
damping with loss factor eta, as the paper's "structural and viscous damping" says.  (With the
opposite sign of Q it would be a destabilising follower force.)

Axial-support friction (eq 30).  The axial support presses on the outer race with the axial force,
so its lateral sliding is resisted by Coulomb friction (force on the outer race)

    F = -mu_d |F_ax| v / sqrt(|v|^2 + v_reg^2).

The paper prints -F_ax mu_d v / ||v||: singular at v = 0 and sign-dependent on F_ax (a negative F_ax
would drive the race).  We use |F_ax| and the vector regularisation.

Default regularisation velocity ``V_REG_DEFAULT`` = 1e-3 m/s: the outer race orbits with ~0.1 mm at
~50 Hz (~0.02-0.06 m/s), and friction is within 0.5 % of Coulomb for |v| > 10 v_reg.
"""

from math import sqrt

V_REG_DEFAULT = 1.0e-3


def ribbon_force(y, z, vy, vz, k_rib, c_rib, eta, v_reg):
    """Ribbon force (Fy, Fz) on the outer race (eqs 28-29; the housing gets the opposite).

    y, z   : outer-race centre relative to the housing centre [m];  vy, vz: its rate [m/s]
    k_rib  : ribbon stiffness [N/m] (paper: 6.3e7);  c_rib: viscous damping [N s/m]
    eta    : cross-coupled (hysteretic) stiffness factor [-];  v_reg: regularisation [m/s] (> 0)
    """
    h = y * vz - z * vy
    den = h * h + v_reg * v_reg * (y * y + z * z)
    ke = 0.0
    if den > 0.0:
        ke = k_rib * eta * h / sqrt(den)
    return (-c_rib * vy - k_rib * y + ke * z, -c_rib * vz - k_rib * z - ke * y)


def outer_race_friction(vy, vz, f_axial, mu_d, v_reg):
    """Coulomb friction (Fy, Fz) of the axial support on the outer race (eq 30, regularised).

    vy, vz : outer-race velocity relative to the housing [m/s]
    f_axial: axial force pressing the support [N] (absolute value used);  mu_d: friction coeff.
    v_reg  : regularisation velocity [m/s] (> 0)
    """
    s = -mu_d * abs(f_axial) / sqrt(vy * vy + vz * vz + v_reg * v_reg)
    return (s * vy, s * vz)

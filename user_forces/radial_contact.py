"""Radial contact rotor sleeve / inner-race bore: paper eqs 10-17 (section 2.4.1), corrected.

Kinematics (eqs 10-13).  d = O_r - O_i (rotor centre minus race centre, eq 10), dv = its rate.
With |d| > 0 the contact normal is n = d/|d| (from the race centre towards the rotor centre, i.e.
towards the contact point) and the tangent is t = e_x x n = (-n_z, n_y).

Penetration (eq 14).  delta = |d| - c_r.  The paper prints ``delta = y_ri - c_r``; it must be the
radial distance |d| (a contact at the bottom of the bore has y_ri = 0).  Contact iff delta > 0.

Frame (eqs 11-12).  The printed R = [[cos s, sin s], [sin s, -cos s]] has determinant -1: it is a
reflection, which flips the sense of the tangential direction on one side of the bore.  We use the
proper rotation with columns (n, t), i.e. radial/tangential components d.n and d.t.

Normal force (eq 15).  The printed ``K_hertz delta^y + K_visc delta delta`` is garbled (exponent
symbol, duplicated delta).  We use the Hunt-Crossley form

    F_N = max(0, k_hertz delta^e + k_visc delta^e delta_dot),   delta_dot = dv . n,

``e = exponent``: 1.5 for Hertz point contact (``EXPONENT_HERTZ_POINT``); a cylinder in a bore
(line contact) is closer to 1.0-1.1.  The damping term is proportional to delta^e, so the force is
zero at contact onset (continuous, no jump at impact) and the max() forbids adhesion while the
bodies separate quickly.  Units: k_hertz [N/m^e], k_visc [N s/m^(e+1)] (Hunt-Crossley:
k_visc = 1.5 (1 - e_restitution) k_hertz / v_impact is a common choice).

Friction (eqs 15-16).  Slip velocity of the rotor surface relative to the race surface at the
contact point (both surface speeds, eq 16):

    v_s = dv . t + Omega_r r_r - Omega_i r_i.

Friction on the rotor = -mu F_N reg(v_s) t, on the race the opposite, with the smooth sign
reg(v) = v / sqrt(v^2 + v_reg^2) (the paper uses the discontinuous sign S).  The normal force on
the rotor is -F_N n, on the race +F_N n.

Torques (eq 17).  The paper applies the mean radius (r_i + r_r)/2 to both bodies.  We use each
body's own radius: torque on the rotor about its centre r_r (n x F_fric,rotor)_x = -r_r mu F_N reg,
on the race about its centre r_i (n x F_fric,race)_x = +r_i mu F_N reg.  Why: the power of all
contact actions is then exactly

    F_rotor . dv + T_rotor Omega_r + T_race Omega_i = -F_N delta_dot - mu F_N v_s reg(v_s),

i.e. friction only dissipates, P_diss = mu F_N v_s reg(v_s) = mu F_N |v_s| |reg| >= 0.  With the
mean radius an extra power -mu F_N reg (c_r/2)(Omega_r + Omega_i) appears (friction would create or
destroy energy at zero slip); the torque difference is a relative O(c_r / r) (about 0.3 % for
0.1 mm clearance on 30 mm), so the paper's results are not affected, but energy accounting is.
Angular momentum about a fixed point is conserved up to the contact-point ambiguity of a
penetrating contact: T_rotor + T_race + (d x F_rotor)_x = -mu F_N reg(v_s) delta = O(delta).

Default regularisation velocity: ``V_REG_DEFAULT`` = 1e-3 m/s.  It is well below the tangential
speeds that matter: the whirl orbit speed ~ 2 pi 50 Hz x 0.2 mm = 0.06 m/s and the surface speed
~ 22 m/s (30 mm at 7000 rpm); for |v_s| > 10 v_reg the friction is within 0.5 % of Coulomb.  The
price is a stiff "slip damper" mu F_N / v_reg (about 1e6 N s/m at F_N = 4 kN, mu = 0.3): use an
implicit integrator or raise v_reg if the step size must be large.

Returned tuple (all floats):
(Fy_rotor, Fz_rotor, T_rotor, T_race, F_N, delta, v_s, P_diss); the force on the race is
(-Fy_rotor, -Fz_rotor).  Without contact (|d| <= c_r, including |d| = 0) every entry is 0 (delta and
v_s are also reported as 0 there).  When in geometric contact but F_N is clipped to 0 (fast
separation) forces are 0 but delta and v_s are reported.
"""

from math import sqrt

EXPONENT_HERTZ_POINT = 1.5
V_REG_DEFAULT = 1.0e-3

_ZERO8 = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


def radial_contact(dy, dz, dvy, dvz, omega_rotor, omega_race, clearance, k_hertz, exponent,
                   k_visc, mu, v_reg, r_rotor, r_race):
    """Rotor sleeve / inner-race radial contact (eqs 10-17, corrected; see module docstring).

    dy, dz      : d = rotor centre - race centre [m]
    dvy, dvz    : rate of d [m/s]
    omega_rotor : rotor spin about +x [rad/s];  omega_race: inner-race spin [rad/s]
    clearance   : radial clearance c_r = r_race - r_rotor [m]
    k_hertz     : contact stiffness [N/m^exponent];  exponent: e (1.5 Hertz point contact)
    k_visc      : Hunt-Crossley damping [N s/m^(e+1)];  mu: friction coefficient
    v_reg       : friction regularisation velocity [m/s] (> 0; default choice 1e-3)
    r_rotor     : sleeve outer radius [m];  r_race: inner-race bore radius [m]

    Returns (Fy_rotor, Fz_rotor, T_rotor, T_race, F_N, delta, v_s, P_diss).
    """
    dist = sqrt(dy * dy + dz * dz)
    if dist <= clearance or dist == 0.0:
        return _ZERO8
    ny = dy / dist
    nz = dz / dist
    delta = dist - clearance
    v_s = ny * dvz - nz * dvy + omega_rotor * r_rotor - omega_race * r_race
    fn = delta ** exponent * (k_hertz + k_visc * (ny * dvy + nz * dvz))
    if fn <= 0.0:
        return (0.0, 0.0, 0.0, 0.0, 0.0, delta, v_s, 0.0)
    ff = mu * fn * v_s / sqrt(v_s * v_s + v_reg * v_reg)   # friction on rotor = -ff * t
    return (-fn * ny + ff * nz, -fn * nz - ff * ny, -r_rotor * ff, r_race * ff,
            fn, delta, v_s, ff * v_s)

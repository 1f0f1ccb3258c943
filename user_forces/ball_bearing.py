"""Catcher-bearing balls: race-to-race force (eq 22) and Harris-Palmgren drag torque (eqs 23-27).

Ball force (eq 22).  r = O_inner - O_outer (displacement of the inner-race centre relative to the
outer-race centre), r = |r|, r_hat = r / r.  Force on the inner race from the balls

    F_io = -(k_b2 r^2 + k_b1 r) r_hat - c_b dv = -(k_b2 r + k_b1) r - c_b dv

(the paper prints ``+(...) i_1`` without the restoring sign; the balls pull the inner race back).
The second form needs no division, so r = 0 is regular.  The outer race gets F_oi = -F_io.  The
optional viscous term c_b dv (dv = rate of r) is not in the paper (default 0).

Drag torque (eqs 23-27, Harris & Kotzalas "Rolling Bearing Analysis", Palmgren load term):

    T = -f1 F_beta d_m reg(omega),  reg(w) = w / sqrt(w^2 + omega_reg^2)

on the inner race, opposing its spin ``omega`` relative to the outer race (the paper prints eq 23
without sign and with the discontinuous sign implied).  Loads enter as absolute values
Fr = |f_radial|, Fa = |f_axial| (dynamic loads, as in the paper).

- eq 26: Y_s = c1 a^2 + c2 a + c3 with the contact angle a in DEGREES (check: 15 deg -> 0.47,
  40 deg -> 0.26, the catalogue Y0 values of angular-contact ball bearings).
- eq 25: F_s = X_s Fr + Y_s Fa, with the catalogue rule F_s >= Fr (the static equivalent load is
  never below the radial load): F_s = max(X_s Fr + Y_s Fa, Fr).
- eq 24: printed ``f1 = z F_s^y / C_s`` is garbled; Harris: f1 = z (F_s / C_s)^y, for
  angular-contact ball bearings z ~ 0.001, y = 0.33.
- eq 27: F_beta = c4 Fa cot(a) + c5 Fr = 0.9 Fa cot a - 0.1 Fr goes negative at small Fa (a pure
  radial load would give a negative, i.e. driving, torque).  Harris's rule is
  F_beta = max(0.9 Fa cot a - 0.1 Fr, Fr), which we implement: max(c4 Fa cot a + c5 Fr, Fr).

Default ``omega_reg`` = 0.1 rad/s (~1 rpm): far below the race speeds of interest (up to ~1000
rad/s), while the equivalent viscous coefficient f1 F_beta d_m / omega_reg (~0.5 N m s for
T ~ 0.05 N m) keeps the race spin equation only mildly stiff (time constant ~1e-4 s for a race of
1e-4..1e-3 kg m^2).
"""

from math import cos, exp, sin, sqrt, radians

OMEGA_REG_DEFAULT = 0.1


def ball_force(dy, dz, k_b1, k_b2, dvy=0.0, dvz=0.0, c_b=0.0):
    """Force (Fy, Fz) on the INNER race from the balls (eq 22); the outer race gets (-Fy, -Fz).

    dy, dz : r = inner-race centre - outer-race centre [m];  dvy, dvz: its rate [m/s]
    k_b1 [N/m], k_b2 [N/m^2] : linear and quadratic coefficients of the load-deflection fit
    c_b [N s/m] : optional viscous damping between the races (not in the paper; default 0)
    """
    k = k_b2 * sqrt(dy * dy + dz * dz) + k_b1
    return (-k * dy - c_b * dvy, -k * dz - c_b * dvz)


def worn_drag_development(angle, growth_angle):
    """Developed share g of the worn drag and dg/d(angle) after the race has turned ``angle`` [rad].

    g = 1 - exp(-|angle| / growth_angle) for growth_angle > 0 [rad]; g = 1 (drag present from the
    start) for growth_angle = 0. Why the race angle: the drag of a worn bearing rises as the bearing
    heats (debris and spall friction heat the inner ring, its thermal growth takes up the internal
    clearance, the ball preload and the friction rise: docs/paper_corrections.md, "worn bearing").
    Over a landing (about 1 s, far below the ring's thermal time constant of minutes) the heat the
    drag itself has made is its work, about T |angle|, so the developed share follows the turned
    angle, and saturates at the worn level as the clearance is used up.
    """
    if growth_angle <= 0.0:
        return 1.0, 0.0
    e = exp(-abs(angle) / growth_angle)
    s = 1.0 if angle >= 0.0 else -1.0
    return 1.0 - e, s * e / growth_angle


def worn_drag_torque(omega_race_rel, torque, omega_reg=OMEGA_REG_DEFAULT, angle=0.0, growth_angle=0.0):
    """Drag torque of a worn catcher bearing on the inner race [N m] (not in the paper).

    A bearing damaged by repeated landings (spalled races, debris, a worn cage) has a friction
    torque several times that of a new one, and most of it does not scale with load: we model
    it as a speed-independent Coulomb torque ``torque`` [N m] (>= 0), regularised like eq 23,

        T = -torque * g(angle) * omega / sqrt(omega^2 + omega_reg^2),

    with g the developed share after the race has turned ``angle`` [rad] since the landing
    (:func:`worn_drag_development`; g = 1 when ``growth_angle`` = 0, the drag present from the start).

    It is the missing effect of the backward-whirl landing (docs/paper_corrections.md, "worn
    bearing"): with it the race cannot keep rolling when the landed load dips, the sleeve keeps
    slipping, and the slip friction feeds a backward whirl.
    """
    # g inline (not via worn_drag_development) so that numba compiles this law unchanged
    g = 1.0 - exp(-abs(angle) / growth_angle) if growth_angle > 0.0 else 1.0
    return -torque * g * omega_race_rel / sqrt(omega_race_rel * omega_race_rel + omega_reg * omega_reg)


def worn_friction_constants(friction, contact_angle_deg, d_m, growth_angle=0.0, omega_reg=OMEGA_REG_DEFAULT,
                            c4=0.9, c5=-0.1):
    """Load-independent constants of :func:`worn_friction_with_derivatives`, once per bearing:
    (friction d_m / 2, c4 cot(a), c5, omega_reg^2, growth_angle)."""
    if not 0.0 < contact_angle_deg < 90.0:
        raise ValueError("contact_angle_deg must be in (0, 90)")
    ar = radians(contact_angle_deg)
    return (0.5 * friction * d_m, c4 * cos(ar) / sin(ar), c5, omega_reg * omega_reg, growth_angle)


def worn_friction_with_derivatives(omega_race_rel, f_radial, f_axial, angle, k):
    """Load-proportional drag of a worn catcher bearing on the inner race (not in the paper) and
    its derivatives: (T, dT/d|F_r|, dT/d|F_a|, dT/d omega, dT/d angle), constants ``k`` from
    :func:`worn_friction_constants`.

        T = -mu_w (d_m / 2) F_beta g(angle) omega / sqrt(omega^2 + omega_reg^2)

    A bearing whose ball contacts slide (lubricant lost, debris, spalls, a damaged cage) turns
    against Coulomb friction in those contacts, and Coulomb friction scales with the load they
    carry. F_beta = max(c4 F_a cot a + c5 F_r, F_r) is Harris's measure of that load (eq 27 as
    corrected, docs/paper_corrections.md #16), d_m / 2 the ball contacts' lever arm, mu_w their
    friction coefficient: about 0.0015 for a healthy lubricated angular-contact bearing (SKF's
    constant coefficient 0.002 on the bore, M = mu P d / 2) up to dry steel-on-steel sliding
    (0.5) for a seized ball set. g is the developed share after the race has turned ``angle``
    (:func:`worn_drag_development`).

    Why load-proportional matters (docs/paper_corrections.md, "worn bearing"): the tangential force
    the sleeve must pass to turn the race is then T / r_race, a fixed fraction of the contact load
    at every load, bouncing included, so whether the sleeve can carry the race (mu_rad r_race N
    against T) no longer hangs on the load of the moment: radial friction decides it.
    """
    half_mu_dm, c4cot, c5, wreg2, growth = k
    fr = abs(f_radial)
    fa = abs(f_axial)
    f_beta = c4cot * fa + c5 * fr
    dbr, dba = c5, c4cot
    if f_beta < fr:
        f_beta, dbr, dba = fr, 1.0, 0.0
    if growth > 0.0:
        e = exp(-abs(angle) / growth)
        g = 1.0 - e
        dg = (1.0 if angle >= 0.0 else -1.0) * e / growth
    else:
        g, dg = 1.0, 0.0
    m2 = omega_race_rel * omega_race_rel + wreg2
    m = sqrt(m2)
    s = omega_race_rel / m
    ds = wreg2 / (m2 * m)
    A = -half_mu_dm * f_beta
    T = A * g * s
    return T, -half_mu_dm * dbr * g * s, -half_mu_dm * dba * g * s, A * g * ds, A * dg * s


def worn_friction_torque(omega_race_rel, f_radial, f_axial, *, friction, contact_angle_deg, d_m,
                         omega_reg=OMEGA_REG_DEFAULT, angle=0.0, growth_angle=0.0):
    """The torque of :func:`worn_friction_with_derivatives` [N m] from plain arguments: ``friction``
    mu_w [-], loads [N], contact angle [deg], pitch diameter d_m [m], race angle and growth angle
    [rad]."""
    k = worn_friction_constants(friction, contact_angle_deg, d_m, growth_angle, omega_reg)
    return worn_friction_with_derivatives(omega_race_rel, f_radial, f_axial, angle, k)[0]


def harris_palmgren_torque(omega_race_rel, f_radial, f_axial, *, contact_angle_deg, C_s, d_m,
                           z_hp, y_hp, X_s=0.5, c1=7.1429e-5, c2=-1.2443e-2, c3=0.64129,
                           c4=0.9, c5=-0.1, omega_reg=OMEGA_REG_DEFAULT):
    """Harris-Palmgren load-dependent drag torque on the inner race (eqs 23-27, corrected) [N m].

    omega_race_rel : inner-race spin relative to the outer race [rad/s]
    f_radial, f_axial : radial and axial bearing loads [N] (absolute values are used)
    contact_angle_deg : contact angle a [deg], 0 < a < 90;  C_s: static load rating C0 [N]
    d_m : pitch diameter [m];  z_hp, y_hp: Harris f1 coefficients (ball: ~0.001, 0.33)
    X_s, c1..c5 : eqs 25-27 coefficients (paper values by default)
    omega_reg : regularisation of the sign of omega [rad/s] (> 0)

    Returns T = -f1 F_beta d_m reg(omega_race_rel) (opposes the relative spin).
    """
    return harris_palmgren_fast(omega_race_rel, f_radial, f_axial,
                                harris_palmgren_constants(contact_angle_deg, C_s, d_m, z_hp, y_hp, X_s=X_s, c1=c1,
                                                          c2=c2, c3=c3, c4=c4, c5=c5, omega_reg=omega_reg))


def harris_palmgren_constants(contact_angle_deg, C_s, d_m, z_hp, y_hp, *, X_s=0.5, c1=7.1429e-5, c2=-1.2443e-2,
                              c3=0.64129, c4=0.9, c5=-0.1, omega_reg=OMEGA_REG_DEFAULT):
    """Load-independent constants of eqs 23-27, computed once per bearing (validates the angle).

    Returns (X_s, Y_s, 1/C_s, z_hp d_m, y_hp, c4 cot(a), c5, omega_reg^2)."""
    if not 0.0 < contact_angle_deg < 90.0:
        raise ValueError("contact_angle_deg must be in (0, 90)")
    a = contact_angle_deg
    y_s = (c1 * a + c2) * a + c3
    ar = radians(a)
    return (X_s, y_s, 1.0 / C_s, z_hp * d_m, y_hp, c4 * cos(ar) / sin(ar), c5, omega_reg * omega_reg)


def harris_palmgren_fast(omega_race_rel, f_radial, f_axial, k):
    """Drag torque from precomputed constants ``k`` (:func:`harris_palmgren_constants`): the same law
    as :func:`harris_palmgren_torque` without per-call keyword handling (solver hot path); the torque
    of :func:`harris_palmgren_with_derivatives`, rounded the same way."""
    return harris_palmgren_with_derivatives(omega_race_rel, f_radial, f_axial, k)[0]


def harris_palmgren_with_derivatives(omega_race_rel, f_radial, f_axial, k):
    """(T, dT/d|F_r|, dT/d|F_a|, dT/d omega) of the drag torque (eqs 23-27 as corrected above) from
    the constants ``k``: the law and its analytic Jacobian in one place (the compiled bearing kernel
    uses this function; tests/test_uf_ball_bearing.py checks the derivatives by differences).

    Derivatives are with respect to the absolute loads; on the branches F_s = F_r and
    F_beta = F_r (the catalogue floors) they are the floor's. T = A(F_s) F_beta g(omega) with
    A = -z d_m (F_s / C_s)^y and g = omega / sqrt(omega^2 + omega_reg^2)."""
    x_s, y_s, inv_cs, zdm, y_hp, c4cot, c5, wreg2 = k
    fr = abs(f_radial)
    fa = abs(f_axial)
    f_s = x_s * fr + y_s * fa
    dsr, dsa = x_s, y_s
    if f_s < fr:
        f_s, dsr, dsa = fr, 1.0, 0.0
    if f_s <= 0.0:
        return 0.0, 0.0, 0.0, 0.0
    f_beta = c4cot * fa + c5 * fr
    dbr, dba = c5, c4cot
    if f_beta < fr:
        f_beta, dbr, dba = fr, 1.0, 0.0
    m2 = omega_race_rel * omega_race_rel + wreg2
    m = sqrt(m2)
    g = omega_race_rel / m
    dg = wreg2 / (m2 * m)
    A = -zdm * (f_s * inv_cs) ** y_hp
    dA = A * y_hp / f_s
    T = A * f_beta * g
    dT_fr = (dA * dsr * f_beta + A * dbr) * g
    dT_fa = (dA * dsa * f_beta + A * dba) * g
    return T, dT_fr, dT_fa, A * f_beta * dg
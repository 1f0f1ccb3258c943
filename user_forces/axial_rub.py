"""Axial rub: friction between the rotor sleeve face and the inner-race thrust face, eqs 18-21.

This is the Wilkes et al. (ASME GT2013-94594, the paper's ref. [19]) forward-whirl mechanism:
with the race spinning with the rotor and the rotor eccentric by d, every point of the face slips
with the same velocity -Omega e_x x d, so the friction on the rotor is ~ mu_ax |F_ax| along
e_x x d / |d|: tangential, in the spin sense, i.e. a forward cross-coupled force.

Geometry and notation (ours; eqs 18-20 as printed mix i_1/j_1 unit vectors, dotted radii and
angular rates, and a pressure index that is never defined):

- O_i race centre, O_r rotor centre, d = O_r - O_i = (d_y, d_z), dv = its rate.
- Contact annulus r1 <= rho_A <= r2 centred on the RACE centre (eq 18 measures A from there):
  face point p = O_i + rho_A e(theta), e = (cos theta, sin theta), dA = rho_A dtheta drho_A.
- Tilt: alpha = rotation of the rotor about y, beta = about z (small).  A face point at
  rho = p - O_r moves axially by u_x = -beta rho_y + alpha rho_z.
- face_sign s = +1 if the rotor face looks towards +x (it presses the race when the rotor moves
  to +x, x_r > cl_ax), -1 if it looks towards -x.  Local compression
      delta(p) = delta_ax + s u_x(p),
  delta_ax = axial approach at the rotor centre (e.g. |x_r| - cl_ax from the axial model, or a
  face-layer compression if one is modelled).  Since delta is linear in p the contact boundary is a
  straight line: delta = A + rho_A (a_c cos theta + a_s sin theta) with
  A = delta_ax + s (beta d_y - alpha d_z), a_c = -s beta, a_s = s alpha.
- Pressure (Winkler foundation, normalised to the axial force of the axial model):
      p(A) = |F_ax| g(A) / int g dA,   g = max(0, delta);   F_ax = 0 or g = 0 -> no friction.
- Slip of the rotor face over the race face at p (in-plane; axial tilt rates ignored):
      w(p) = v_rotor(p) - v_race(p),
      v_rotor(p) = v_r + Omega_r e_x x (p - O_r),  v_race(p) = v_i + Omega_i e_x x (p - O_i),
  so w = dv + e_x x [(Omega_r - Omega_i) rho_A e - Omega_r d] depends on relative kinematics only.
- Traction on the rotor tau = -mu_ax p w / sqrt(|w|^2 + v_reg^2); the race gets -tau.
  Our eqs 19-21:
      F_rotor = int tau dA,
      T_rotor = int ((p - O_r) x tau)_x dA          (about the rotor centre),
      T_race  = -int ((p - O_i) x tau)_x dA         (about the race centre),
  and F_race = -F_rotor.  Eq 21 (T_rotor = -T_race) holds only for d = 0; in general the exact
  angular-momentum balance is T_rotor + T_race + (d x F_rotor)_x = 0, and the total power
      F_rotor . dv + T_rotor Omega_r + T_race Omega_i = int tau . w dA = -P_diss <= 0.
  Both identities hold exactly for the quadrature sums too.
  Not returned: the tilting moments of the pressure about y and z (the axial model applies F_ax
  at the centre).

Quadrature (``axial_rub``, the hot path): Gauss-Legendre in rho_A (``N_R`` = 3 points) x
``N_THETA`` = 24 points in theta, tabulated at import.  To keep the accuracy with partial contact
the contact line is treated exactly: the radial interval is split at rho* = |A| / |a| (where the
line is tangent to a circle), a circle in full contact uses the periodic trapezoid rule (spectral
for the smooth periodic integrand), a partially loaded circle is integrated only over its loaded
arc theta0 +- acos(-A / (|a| rho_A)) with Gauss-Legendre (N_THETA points).  Cost: ~72 points,
~1-2 trig calls per point only on partial arcs.
Limitation: when Omega_r - Omega_i is within a few d / r of zero, the slip centre lies on the
annulus and the direction field has a vortex of size ~ v_reg / |Omega_r - Omega_i|; there the
fast rule is less accurate (the bounded traction limits the error to that small area; ~0.4 % on
the force for Omega_r - Omega_i = 2 rad/s, |d| = 0.1 mm, r = 32-45 mm).  Elsewhere the fast rule
agrees with the reference to ~1e-5 or better (tests/test_uf_axial_rub.py).
``axial_rub_reference`` is a plain, independent fine rule (40 x 2000 points, max() evaluated per
point, no splitting) used by the tests.

Default regularisation velocity ``V_REG_DEFAULT`` = 1e-3 m/s; in the Wilkes state the slip is
Omega |d| ~ 733 rad/s x 0.1 mm = 0.07 m/s, so the friction is within 0.01 % of Coulomb.

Returned tuple: (Fy_rotor, Fz_rotor, T_rotor, T_race, P_diss).
"""

from math import acos, atan2, cos, pi, sin, sqrt

V_REG_DEFAULT = 1.0e-3
N_R = 3
N_THETA = 24
N_R_REF = 40
N_THETA_REF = 2000


def _gauss_legendre(n):
    """Gauss-Legendre nodes and weights on [-1, 1] as a tuple of (x, w) pairs (pure Python)."""
    out = []
    for i in range(1, n + 1):
        x = cos(pi * (i - 0.25) / (n + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for k in range(2, n + 1):
                p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
            dp = n * (x * p1 - p0) / (x * x - 1.0)
            dx = p1 / dp
            x -= dx
            if abs(dx) < 1e-16:
                break
        p0, p1 = 1.0, x
        for k in range(2, n + 1):
            p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
        dp = n * (x * p1 - p0) / (x * x - 1.0)
        out.append((x, 2.0 / ((1.0 - x * x) * dp * dp)))
    return tuple(sorted(out))


def _uniform_circle(n):
    """(cos, sin) of n equispaced angles (periodic trapezoid rule; weight 2 pi / n each)."""
    return tuple((cos(2.0 * pi * k / n), sin(2.0 * pi * k / n)) for k in range(n))


_GL_R = _gauss_legendre(N_R)
_GL_ARC = _gauss_legendre(N_THETA)
_CIRCLE = _uniform_circle(N_THETA)
_W_CIRCLE = 2.0 * pi / N_THETA

_ZERO5 = (0.0, 0.0, 0.0, 0.0, 0.0)  # the reference rule's "no contact"


def axial_rub(dy, dz, dvy, dvz, omega_rotor, omega_race, alpha, beta, delta_ax, f_axial,
              face_sign, mu_ax, v_reg, r1, r2):
    """Axial-face friction between rotor sleeve and inner race (eqs 18-21, our notation).

    dy, dz      : d = rotor centre - race centre [m];  dvy, dvz: its rate [m/s]
    omega_rotor, omega_race : spins about +x [rad/s]
    alpha, beta : rotor tilt about y and about z [rad] (small)
    delta_ax    : axial approach at the rotor centre [m] (sets, with the tilt, where the faces touch)
    f_axial     : axial contact force from the axial model [N] (|f_axial| = integral of pressure)
    face_sign   : +1 rotor face looking towards +x, -1 towards -x
    mu_ax       : face friction coefficient;  v_reg: slip regularisation [m/s] (> 0)
    r1, r2      : inner and outer radius of the contact annulus about the race centre [m]

    Returns (Fy_rotor, Fz_rotor, T_rotor, T_race, P_diss); the force on the race is
    (-Fy_rotor, -Fz_rotor); torques about each body's own centre; P_diss >= 0.
    Compiled callers compile :func:`axial_rub_quadrature` (this is its first five values).
    """
    r = axial_rub_quadrature(dy, dz, dvy, dvz, omega_rotor, omega_race, alpha, beta, delta_ax, f_axial,
                             face_sign, mu_ax, v_reg, r1, r2, False)
    return r[0], r[1], r[2], r[3], r[4]


def axial_rub_slip_jacobian(dy, dz, dvy, dvz, omega_rotor, omega_race, alpha, beta, delta_ax, f_axial,
                            face_sign, mu_ax, v_reg, r1, r2):
    """``axial_rub`` with the forward-mode derivatives of its quadrature sums, for the analytic
    Jacobian: (Fy_rotor, Fz_rotor, T_rotor, T_race, sc, d), see :func:`axial_rub_quadrature`."""
    r = axial_rub_quadrature(dy, dz, dvy, dvz, omega_rotor, omega_race, alpha, beta, delta_ax, f_axial,
                             face_sign, mu_ax, v_reg, r1, r2, True)
    return r[0], r[1], r[2], r[3], r[5], r[6]


_ZERO9 = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
_ZERO7 = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, _ZERO9)


def axial_rub_quadrature(dy, dz, dvy, dvz, omega_rotor, omega_race, alpha, beta, delta_ax, f_axial,
                         face_sign, mu_ax, v_reg, r1, r2, derivatives):
    """The one quadrature behind ``axial_rub`` and ``axial_rub_slip_jacobian`` (arguments as
    ``axial_rub``; ``derivatives``: also the forward-mode derivatives).

    With the slip field w = (cy0 - dom rho sin, cz0 + dom rho cos), cy0 = dvy + Omega_r dz,
    cz0 = dvz - Omega_r dy, dom = Omega_r - Omega_i, the rub is F_rotor = -sc (sy, sz), T_rotor =
    -sc (mi - dy sz + dz sy), T_race = sc mi, with sc = mu_ax |F_ax| / sum(q) and (sy, sz, mi) sums
    over the patch. Returns (Fy_rotor, Fz_rotor, T_rotor, T_race, P_diss, sc, d) with d =
    d(sy, sz, mi)/d(cy0, cz0, dom) row-major (9 floats, zeros without ``derivatives``) at a fixed
    contact patch; the chain rule to the caller's coordinates, the explicit d in T_rotor and the
    patch's dependence on the axial approach A (which moves with dy, dz, delta_ax and the tilt) are
    the caller's. Without contact everything is 0.
    """
    fa = abs(f_axial)
    if fa == 0.0 or mu_ax == 0.0:
        return _ZERO7
    s = face_sign
    a0 = delta_ax + s * (beta * dy - alpha * dz)
    ac = -s * beta
    as_ = s * alpha
    kk = sqrt(ac * ac + as_ * as_)
    th0 = atan2(as_, ac)
    # radial pieces [ra, rb] and [rc, r2]: split where the contact line touches a circle
    ra, rb, rc = r1, r2, r2
    if kk * r2 > 1e-12 * abs(a0):
        rstar = abs(a0) / kk
        if r1 < rstar < r2:
            rb = rstar
            rc = rstar
    elif a0 <= 0.0:
        return _ZERO7
    cy0 = dvy + omega_rotor * dz
    cz0 = dvz - omega_rotor * dy
    dom = omega_rotor - omega_race
    vr2 = v_reg * v_reg
    gs = sy = sz = mi = pw = 0.0
    # d(sy, sz, mi)/d(cy0, cz0, dom), row-major
    d00 = d01 = d02 = d10 = d11 = d12 = d20 = d21 = d22 = 0.0
    for ip in (0, 1):
        if ip == 0:
            lo, hi = ra, rb
        else:
            lo, hi = rc, r2
        if hi <= lo:
            continue
        hh = 0.5 * (hi - lo)
        mm = 0.5 * (hi + lo)
        for xj, wj in _GL_R:
            rho = mm + hh * xj
            wr = hh * wj * rho
            bb = kk * rho
            full = a0 >= bb       # full circle in contact: periodic trapezoid
            if not full and a0 <= -bb:
                continue
            phi = 0.0
            if not full:          # loaded arc th0 +- phi: Gauss-Legendre on the arc
                phi = acos(-a0 / bb)
            for k in range(N_THETA):
                if full:
                    c, sn = _CIRCLE[k]
                    wq = wr * _W_CIRCLE
                else:
                    th = th0 + phi * _GL_ARC[k][0]
                    c = cos(th)
                    sn = sin(th)
                    wq = wr * phi * _GL_ARC[k][1]
                g = a0 + rho * (ac * c + as_ * sn)
                if g <= 0.0:
                    continue
                q = wq * g
                pcy = rho * c
                pcz = rho * sn
                wy = cy0 - dom * pcz
                wz = cz0 + dom * pcy
                m2 = wy * wy + wz * wz + vr2
                a = q / sqrt(m2)
                uy = wy * a
                uz = wz * a
                gs += q
                sy += uy
                sz += uz
                mi += pcy * uz - pcz * uy
                pw += wy * uy + wz * uz
                if derivatives:
                    uyy = a * (1.0 - wy * wy / m2)
                    uyz = -a * wy * wz / m2
                    uzz = a * (1.0 - wz * wz / m2)
                    duy2 = -pcz * uyy + pcy * uyz
                    duz2 = -pcz * uyz + pcy * uzz
                    d00 += uyy
                    d10 += uyz
                    d20 += pcy * uyz - pcz * uyy
                    d01 += uyz
                    d11 += uzz
                    d21 += pcy * uzz - pcz * uyz
                    d02 += duy2
                    d12 += duz2
                    d22 += pcy * duz2 - pcz * duy2
    if gs <= 0.0:
        return _ZERO7
    sc = mu_ax * fa / gs
    return (-sc * sy, -sc * sz, -sc * (mi - dy * sz + dz * sy), sc * mi, sc * pw, sc,
            (d00, d01, d02, d10, d11, d12, d20, d21, d22))


def axial_rub_reference(dy, dz, dvy, dvz, omega_rotor, omega_race, alpha, beta, delta_ax,
                        f_axial, face_sign, mu_ax, v_reg, r1, r2, n_r=N_R_REF,
                        n_theta=N_THETA_REF):
    """Same as ``axial_rub`` by a plain fine rule (tests only; slow): Gauss-Legendre n_r in
    radius x uniform n_theta in angle over the whole annulus, pressure max(0, delta) evaluated
    point by point from the definitions (no contact-line splitting)."""
    fa = abs(f_axial)
    if fa == 0.0 or mu_ax == 0.0:
        return _ZERO5
    gl = _gauss_legendre(n_r)
    dth = 2.0 * pi / n_theta
    gs = fy = fz = tr = ti = pw = 0.0
    for xj, wj in gl:
        rho = 0.5 * (r1 + r2) + 0.5 * (r2 - r1) * xj
        wr = 0.5 * (r2 - r1) * wj * rho * dth
        for k in range(n_theta):
            th = k * dth
            py = rho * cos(th)            # p - O_i
            pz = rho * sin(th)
            ry = py - dy                  # p - O_r
            rz = pz - dz
            u_x = -beta * ry + alpha * rz
            g = delta_ax + face_sign * u_x
            if g <= 0.0:
                continue
            wy = dvy - omega_rotor * rz + omega_race * pz   # v_rotor(p) - v_race(p)
            wz = dvz + omega_rotor * ry - omega_race * py
            m = sqrt(wy * wy + wz * wz + v_reg * v_reg)
            ty = -g * wy / m * wr                          # traction on rotor / (mu p0)
            tz = -g * wz / m * wr
            gs += g * wr
            fy += ty
            fz += tz
            tr += ry * tz - rz * ty
            ti -= py * tz - pz * ty
            pw -= ty * wy + tz * wz
    if gs <= 0.0:
        return _ZERO5
    sc = mu_ax * fa / gs
    return (sc * fy, sc * fz, sc * tr, sc * ti, sc * pw)

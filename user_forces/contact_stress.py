"""Contact stresses of a catcher bearing: Hertz line and point contact, ball load distribution.

Laws (SI units: N, m, Pa; angles in degrees only where the name says ``_deg``):

Effective modulus (Hertz; Johnson, Contact Mechanics, 1985, ch. 4):
    1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.

Line contact, two parallel cylinders of length L (Johnson, Contact Mechanics, sec. 4.3; quoted;
the tests check the load balance, the sqrt(F) scaling, and that it is the slender limit of
the exact elliptical solution below, to 2e-5 at R_y/R_x = 1e4):
    b  = sqrt(4 F R* / (pi L E*))          (half-width)
    p0 = sqrt(F E* / (pi L R*)) = 2 F / (pi b L),
    1/R* = 1/R1 + 1/R2, with a concave surface (the inner-race bore) counted negative: a sleeve
    of radius r_s in a bore of radius r_b > r_s gives R* = r_s r_b / (r_b - r_s).
    The sleeve-ring contact "as it is": an aligned sleeve in the bore is a conformal line contact
    over the engaged length. Hertz needs the contact half-width small against the radii
    (b / R ~ 0.07 at 2 kN on the rig): :func:`line_contact` reports b so the caller can check it.
    A crowned (barrel-shaped) sleeve, or a tilted one touching on an edge radius, is a point
    contact: :func:`sleeve_ring_crowned` (circumferential radius R*, axial radius = the crown).

Point contact (Hertz, elliptical; Johnson section 4.2, quoted; the curvature-ratio relation
checked in a contact-stress handbook table, "9 Contact Stresses", Table 9-4, yumpu copy):
principal relative curvatures A = 1/(2 R_big), B = 1/(2 R_small), B >= A; contact ellipse
semi-axes a >= b, e^2 = 1 - b^2/a^2, with the complete elliptic integrals K(e), E(e)
(parameter m = e^2):
    B/A = (E/(1 - e^2) - K) / (K - E)                     (fixes e from the geometry)
    a^3 = 3 P (K - E) / (2 pi A E* e^2),  b = a sqrt(1 - e^2)
    p0  = 3 P / (2 pi a b)                                 (peak pressure)
    delta = p0 b K / E*                                    (approach of distant points)
Limit e -> 0 (sphere): a^3 = 3 P R / (4 E*), p0 = 3P/(2 pi a^2), delta = a^2/R (checked in the
tests, with Hamrock's exact relations as an independent second form and the Brewe-Hamrock
approximations). K and E by the arithmetic-geometric mean (Abramowitz & Stegun 17.6), exact to
round-off, plain floats (numba-compilable).

Ball-race curvatures (Harris & Kotzalas, Rolling Bearing Analysis, ch. 2; gamma = D cos(a)/d_m):
    inner: R_x = D (1 - gamma) / 2,  R_y = f_i D / (2 f_i - 1)
    outer: R_x = D (1 + gamma) / 2,  R_y = f_o D / (2 f_o - 1)
(R_x in the rolling direction, R_y across the groove; f = groove radius / D).

Load distribution over the balls (Stribeck 1901; Sjovall 1933; Harris & Kotzalas ch. 7):
ball j at azimuth psi_j from the load line, rings rigid, contact angle held at a:
    delta_j = delta_a sin a + delta_r cos a cos psi_j - P_d/2 cos a,   Q_j = K_n max(0, delta_j)^1.5
    F_r = sum Q_j cos a cos psi_j,   F_a = sum Q_j sin a.
For a pure radial load the continuous (many-ball) form is Q_max = F_r / (Z J_r(eps) cos a),
    J_r(eps) = 1/(2 pi) int_{-psi_l}^{psi_l} [1 - (1 - cos psi)/(2 eps)]^1.5 cos psi dpsi,
and zero clearance (eps = 0.5) gives J_r = 0.2288, Q_max = 4.37 F_r / (Z cos a): Stribeck's
number, checked (NSK technical report, section 5, Table 1 and eq 4: "Q_max = 4.37 F_r / (Z cos a)
point contact"; the rig's bounds note quotes J_r(0.5) = 0.2288). ISO 76 uses 5 F_r / (Z cos a) to
allow for a normal clearance. Here the discrete sum over the Z balls is solved (it is what a
simulated instant has), the continuous J_r is provided for the hand check.

Static limit (ISO 76:2006, clause 3, checked: NSK handbook "Static load ratings" and the ISO 76
text): the basic static load rating corresponds to a calculated contact stress at the centre of
the most heavily loaded contact of 4600 MPa (self-aligning ball), 4200 MPa (other ball
bearings), 4000 MPa (roller bearings); permanent deformation ~1e-4 of the rolling element
diameter.

7212 BE internal geometry: NOT found in a public source here. ``BEARING_7212BE_ASSUMED`` takes
Z = 15 balls of 15.875 mm (5/8 in), d_m = 85 mm, a = 40 deg, f_i = 0.52, f_o = 0.53 (typical
values, Harris & Kotzalas' examples use 0.52; the rig's bounds note gives the plausible ranges
Z 14-16, D 15.08-15.875 mm, f 0.515-0.54). Replace by the maker's data when available.

Bad input raises ValueError naming the argument, its value and what is allowed.
"""

from __future__ import annotations

from dataclasses import dataclass
from math import acos, cos, pi, radians, sin, sqrt

ISO76_BALL_PA = 4200.0e6            # Pa, ISO 76 basis, ball bearings other than self-aligning
ISO76_SELF_ALIGNING_BALL_PA = 4600.0e6
ISO76_ROLLER_PA = 4000.0e6
STRIBECK_ZERO_CLEARANCE = 4.37      # Q_max Z cos(a) / F_r for zero clearance (NSK, Harris)


def _positive(name, value):
    if not value > 0.0:
        raise ValueError(f"{name} = {value!r}: must be > 0")


def _nonnegative(name, value):
    if not value >= 0.0:
        raise ValueError(f"{name} = {value!r}: must be >= 0")


def effective_modulus(e1, nu1, e2, nu2):
    """E* = 1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2) [Pa]."""
    _positive("e1", e1)
    _positive("e2", e2)
    for name, nu in (("nu1", nu1), ("nu2", nu2)):
        if not -1.0 < nu < 0.5:
            raise ValueError(f"{name} = {nu!r}: Poisson's ratio must be in (-1, 0.5)")
    return 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2)


def elliptic_ke(m):
    """Complete elliptic integrals (K(m), E(m)) of parameter m = e^2 in [0, 1) by the AGM.

    a0 = 1, b0 = sqrt(1 - m), c0^2 = m; K = pi / (2 a_N); E = K (1 - sum_n 2^(n-1) c_n^2)
    (Abramowitz & Stegun 17.6.1-17.6.4). Converges quadratically (< 10 iterations to 1e-16)."""
    if not 0.0 <= m < 1.0:
        raise ValueError(f"m = {m!r}: elliptic parameter must be in [0, 1)")
    a = 1.0
    b = sqrt(1.0 - m)
    s = 0.5 * m                      # 2^(-1) c0^2
    w = 0.5
    for _ in range(40):
        c = 0.5 * (a - b)
        a, b = 0.5 * (a + b), sqrt(a * b)
        w *= 2.0
        s += w * c * c
        if abs(c) < 1e-17 * a:
            break
    k = pi / (2.0 * a)
    return k, k * (1.0 - s)


def hertz_point_contact(force, r_x, r_y, e_star):
    """Elliptical Hertz contact: (p0, a, b, delta) for normal load ``force`` [N].

    r_x, r_y : principal relative radii of curvature [m] (1/r = 1/r_body1 + 1/r_body2, concave
               negative; both must come out > 0)
    e_star   : effective modulus [Pa]
    Returns peak pressure p0 [Pa], semi-axes a >= b [m] (a along the larger radius) and the
    approach delta [m]. force = 0 gives zeros. Checks its input, then :func:`hertz_point_fast`.
    """
    _nonnegative("force", force)
    _positive("r_x", r_x)
    _positive("r_y", r_y)
    _positive("e_star", e_star)
    return hertz_point_fast(force, r_x, r_y, e_star)


def hertz_point_fast(force, r_x, r_y, e_star):
    """:func:`hertz_point_contact` without checks and without calls (a numba leaf, per step).

    Solves B/A(e) = R_big/R_small by bisection on kappa = b/a (B/A increases as kappa falls),
    with K(m), E(m) by the AGM inline (as :func:`elliptic_ke`)."""
    if force <= 0.0:
        return 0.0, 0.0, 0.0, 0.0
    r_big = r_x if r_x >= r_y else r_y
    r_small = r_y if r_x >= r_y else r_x
    ratio = r_big / r_small
    if ratio < 1.0 + 1e-9:
        # sphere-like: the e -> 0 limit (the ellipse formula loses digits as K - E -> 0)
        r = sqrt(r_x * r_y)          # relative radius of the sphere (Johnson's R, not Hamrock's sum)
        a = (3.0 * force * r / (4.0 * e_star)) ** (1.0 / 3.0)
        return 3.0 * force / (2.0 * pi * a * a), a, a, a * a / r
    lo, hi = 0.0, 1.0                # kappa
    kk = ee = m = kap = 0.0
    for _ in range(200):
        kap = 0.5 * (lo + hi)
        m = 1.0 - kap * kap
        ag, bg, sg, wg = 1.0, kap, 0.5 * m, 0.5
        for _ in range(40):
            c = 0.5 * (ag - bg)
            ag, bg = 0.5 * (ag + bg), sqrt(ag * bg)
            wg *= 2.0
            sg += wg * c * c
            if abs(c) < 1e-17 * ag:
                break
        kk = pi / (2.0 * ag)
        ee = kk * (1.0 - sg)
        if (ee / (1.0 - m) - kk) / (kk - ee) > ratio:
            lo = kap                 # too eccentric: raise kappa
        else:
            hi = kap
        if hi - lo < 1e-15:
            break
    a_curv = 1.0 / (2.0 * r_big)
    a = (3.0 * force * (kk - ee) / (2.0 * pi * a_curv * e_star * m)) ** (1.0 / 3.0)
    b = a * kap
    p0 = 3.0 * force / (2.0 * pi * a * b)
    return p0, a, b, p0 * b * kk / e_star


def line_contact(force, length, r_equiv, e_star):
    """Hertz line contact: (p0, b) for total load ``force`` [N] over ``length`` [m].

    p0 = sqrt(F E* / (pi L R*)), b = sqrt(4 F R* / (pi L E*)) (Johnson sec. 4.3);
    r_equiv = R* [m] (> 0), e_star [Pa]."""
    _nonnegative("force", force)
    _positive("length", length)
    _positive("r_equiv", r_equiv)
    _positive("e_star", e_star)
    return line_contact_fast(force, length, r_equiv, e_star)


def line_contact_fast(force, length, r_equiv, e_star):
    """:func:`line_contact` without the argument checks (numba leaf: the post-processing compiles it
    for every output sample, ``rotorlanding.bearing_kernel.blok_sleeve_series``)."""
    if force == 0.0:
        return 0.0, 0.0
    return sqrt(force * e_star / (pi * length * r_equiv)), sqrt(4.0 * force * r_equiv / (pi * length * e_star))


def conformal_radius(r_inner_body, r_bore):
    """R* of a cylinder (radius r_inner_body) inside a bore (radius r_bore > r_inner_body) [m]."""
    _positive("r_inner_body", r_inner_body)
    if not r_bore > r_inner_body:
        raise ValueError(f"r_bore = {r_bore!r}: must be larger than r_inner_body = {r_inner_body!r}")
    return r_inner_body * r_bore / (r_bore - r_inner_body)


def sleeve_ring_line(force, r_sleeve, r_bore, length, e_star):
    """Sleeve-ring contact as an aligned line contact: (p0, b) [Pa, m]."""
    return line_contact(force, length, conformal_radius(r_sleeve, r_bore), e_star)


def sleeve_ring_crowned(force, r_sleeve, r_bore, crown_radius, e_star):
    """Sleeve-ring contact of a crowned (or edge-loaded) sleeve: point contact (p0, a, b, delta).

    Circumferential relative radius R* = r_s r_b / (r_b - r_s) (conformal), axial radius =
    ``crown_radius`` [m] (the bore is straight axially)."""
    return hertz_point_contact(force, conformal_radius(r_sleeve, r_bore), crown_radius, e_star)


@dataclass(frozen=True)
class BallBearingGeometry:
    """Internal geometry of a single-row (angular-contact) ball bearing, SI units."""
    ball_diameter: float          # D [m]
    n_balls: int                  # Z
    pitch_diameter: float         # d_m [m]
    contact_angle_deg: float      # a [deg]
    f_inner: float                # inner groove radius / D (> 0.5)
    f_outer: float                # outer groove radius / D (> 0.5)
    e_star: float                 # ball-race effective modulus [Pa]

    def __post_init__(self):
        _positive("ball_diameter", self.ball_diameter)
        _positive("pitch_diameter", self.pitch_diameter)
        if not (isinstance(self.n_balls, int) and self.n_balls >= 3):
            raise ValueError(f"n_balls = {self.n_balls!r}: must be an integer >= 3")
        if not 0.0 <= self.contact_angle_deg < 90.0:
            raise ValueError(f"contact_angle_deg = {self.contact_angle_deg!r}: must be in [0, 90)")
        for name in ("f_inner", "f_outer"):
            f = getattr(self, name)
            if not f > 0.5:
                raise ValueError(f"{name} = {f!r}: groove conformity must be > 0.5")
        _positive("e_star", self.e_star)
        if not self.ball_diameter < self.pitch_diameter:
            raise ValueError(f"ball_diameter = {self.ball_diameter!r}: must be < pitch_diameter")

    @property
    def gamma(self):
        return self.ball_diameter * cos(radians(self.contact_angle_deg)) / self.pitch_diameter


STEEL_E_STAR = effective_modulus(208.0e9, 0.3, 208.0e9, 0.3)   # 52100 on 52100 (E, nu: see docs)

BEARING_7212BE_ASSUMED = BallBearingGeometry(
    ball_diameter=15.875e-3, n_balls=15, pitch_diameter=0.085, contact_angle_deg=40.0,
    f_inner=0.52, f_outer=0.53, e_star=STEEL_E_STAR)


def race_radii(geom, race):
    """Relative radii (R_x rolling direction, R_y across the groove) of the ball on ``race``."""
    d = geom.ball_diameter
    g = geom.gamma
    if race == "inner":
        return 0.5 * d * (1.0 - g), geom.f_inner * d / (2.0 * geom.f_inner - 1.0)
    if race == "outer":
        return 0.5 * d * (1.0 + g), geom.f_outer * d / (2.0 * geom.f_outer - 1.0)
    raise ValueError(f"race = {race!r}: must be 'inner' or 'outer'")


def ball_race_contact(q, geom, race):
    """Hertz contact of one ball load ``q`` [N] on ``race``: (p0, a, b, delta)."""
    rx, ry = race_radii(geom, race)
    return hertz_point_contact(q, rx, ry, geom.e_star)


def ball_stiffness_kn(geom):
    """K_n [N/m^1.5] of one ball between both races: Q = K_n delta^1.5 along the contact normal.

    Each contact has delta = c P^(2/3) exactly (Hertz), so K = P / delta^1.5 is load-free; the
    two contacts in series: K_n = (K_i^(-2/3) + K_o^(-2/3))^(-3/2) (Harris & Kotzalas ch. 7)."""
    ks = []
    for race in ("inner", "outer"):
        delta = ball_race_contact(1.0, geom, race)[3]
        ks.append(1.0 / delta ** 1.5)
    return (ks[0] ** (-2.0 / 3.0) + ks[1] ** (-2.0 / 3.0)) ** -1.5


def load_zone_integral(epsilon, n_steps=4000):
    """Radial load integral J_r(eps) of a point-contact bearing (Harris & Kotzalas ch. 7).

    J_r = 1/(2 pi) int [1 - (1 - cos psi)/(2 eps)]_+^1.5 cos psi dpsi over the loaded arc
    (cos psi_l = 1 - 2 eps for eps <= 1, the whole circle for eps > 1); composite Simpson."""
    _positive("epsilon", epsilon)
    psi_l = pi if epsilon >= 1.0 else _acos(1.0 - 2.0 * epsilon)
    n = n_steps + (n_steps % 2)
    h = 2.0 * psi_l / n
    total = 0.0
    for i in range(n + 1):
        psi = -psi_l + i * h
        x = 1.0 - (1.0 - cos(psi)) / (2.0 * epsilon)
        f = x ** 1.5 * cos(psi) if x > 0.0 else 0.0
        w = 1.0 if i in (0, n) else (4.0 if i % 2 else 2.0)
        total += w * f
    return total * h / 3.0 / (2.0 * pi)


def _acos(x):
    return acos(max(-1.0, min(1.0, x)))


def _ball_sums(delta_r, delta_a, geom, k_n, clearance_diametral, phase):
    ca = cos(radians(geom.contact_angle_deg))
    sa = sin(radians(geom.contact_angle_deg))
    fr = fa = qmax = 0.0
    for j in range(geom.n_balls):
        psi = phase + 2.0 * pi * j / geom.n_balls
        d = delta_a * sa + (delta_r * cos(psi) - 0.5 * clearance_diametral) * ca
        if d > 0.0:
            q = k_n * d ** 1.5
            fr += q * ca * cos(psi)
            fa += q * sa
            if q > qmax:
                qmax = q
    return fr, fa, qmax


def ball_load_distribution(f_radial, f_axial, geom, k_n=None, clearance_diametral=0.0, phase=0.0):
    """Ball loads of a bearing under (F_r, F_a) with rigid rings and a fixed contact angle.

    Solves F_r = sum Q_j cos a cos psi_j and F_a = sum Q_j sin a for the ring displacements
    (delta_r, delta_a) (module docstring); ball 0 at azimuth ``phase`` [rad] from the load line.
    A radial load on an angular-contact bearing induces a thrust (about 1.2 F_r tan a at half the
    balls loaded): when ``f_axial`` is below the thrust carried at delta_a = 0, the rings are taken
    as held axially by the mounting (delta_a = 0) and the carried thrust is reported, not imposed.
    Above it, both F_r and F_a are matched.

    Returns (Q_max [N], delta_r [m], delta_a [m], F_a_carried [N]). Checks its input, then
    :func:`ball_loads_fast`.
    """
    _nonnegative("f_radial", f_radial)
    _nonnegative("f_axial", f_axial)
    _nonnegative("clearance_diametral", clearance_diametral)
    if k_n is None:
        k_n = ball_stiffness_kn(geom)
    _positive("k_n", k_n)
    if f_axial > 0.0 and geom.contact_angle_deg == 0.0:
        raise ValueError(f"f_axial = {f_axial!r}: a radial bearing (contact_angle_deg = 0) carries no axial load here")
    return ball_loads_fast(f_radial, f_axial, geom.n_balls, radians(geom.contact_angle_deg), k_n,
                           clearance_diametral, phase)


def ball_loads_fast(f_radial, f_axial, n_balls, contact_angle_rad, k_n, clearance_diametral, phase):
    """:func:`ball_load_distribution` without checks (a numba leaf: plain floats, inner helpers).

    Nested bisections: delta_r for F_r at a given delta_a (the radial sum rises with delta_r), and
    delta_a for F_a (the axial sum at the matching delta_r rises with delta_a); each bracket is
    grown by doubling from the Hertz scale (F / (Z K_n))^(2/3) + max(P_d, 0)."""
    ca = cos(contact_angle_rad)
    sa = sin(contact_angle_rad)

    def sums(dr, da):
        fr = 0.0
        fa = 0.0
        qmax = 0.0
        for j in range(n_balls):
            psi = phase + 2.0 * pi * j / n_balls
            d = da * sa + (dr * cos(psi) - 0.5 * clearance_diametral) * ca
            if d > 0.0:
                q = k_n * d ** 1.5
                fr += q * ca * cos(psi)
                fa += q * sa
                if q > qmax:
                    qmax = q
        return fr, fa, qmax

    def dr_for(da, scale):
        if f_radial <= 0.0:
            return 0.0
        lo, hi = 0.0, scale
        for _ in range(200):
            if sums(hi, da)[0] >= f_radial:
                break
            lo, hi = hi, 2.0 * hi
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if sums(mid, da)[0] < f_radial:
                lo = mid
            else:
                hi = mid
            if hi - lo <= 1e-15 * hi:
                break
        return 0.5 * (lo + hi)

    if f_radial <= 0.0 and f_axial <= 0.0:
        return 0.0, 0.0, 0.0, 0.0
    big = f_radial if f_radial > f_axial else f_axial
    # the brackets grow by doubling, so the start must be > 0: an interference (P_d < 0, a thermal
    # preload) already compresses every ball at zero displacement and adds nothing to it
    scale = (big / (n_balls * k_n)) ** (2.0 / 3.0) + (clearance_diametral if clearance_diametral > 0.0 else 0.0)
    dr0 = dr_for(0.0, scale)
    fr0, fa0, q0 = sums(dr0, 0.0)
    if clearance_diametral < 0.0 and fa0 >= f_axial:
        # interference (a thermal preload): the rings move apart axially (delta_a < 0) until the
        # balls carry f_axial, which must then include the preload the mounting holds; at
        # delta_a = P_d cos a / (2 sin a) the interference is taken up and no ball is compressed
        # by it (only by delta_r)
        lo, hi = 0.5 * clearance_diametral * ca / sa, 0.0
    elif f_radial > 0.0 and fa0 >= f_axial:
        return q0, dr0, 0.0, fa0                 # held axially: carries its induced thrust
    else:
        lo, hi = 0.0, scale
        for _ in range(200):
            if sums(dr_for(hi, scale), hi)[1] >= f_axial:
                break
            lo, hi = hi, 2.0 * hi
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if sums(dr_for(mid, scale), mid)[1] < f_axial:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-15 * max(abs(hi), abs(lo)):
            break
    da = 0.5 * (lo + hi)
    dr = dr_for(da, scale)
    fr, fa, qmax = sums(dr, da)
    return qmax, dr, da, fa


def ball_race_peak_pressures(f_radial, f_axial, geom, clearance_diametral=0.0, phase=0.0):
    """Peak Hertz pressures (p_inner, p_outer) [Pa] at the most loaded ball, and its load Q_max."""
    qmax = ball_load_distribution(f_radial, f_axial, geom, None, clearance_diametral, phase)[0]
    return ball_race_contact(qmax, geom, "inner")[0], ball_race_contact(qmax, geom, "outer")[0], qmax

"""Rotor spin model: windage torque of eq 6 (section 2.2.3).

Eq 6, I Omega' = T_aux1 + T_aux2 + T_wind, leaves T_wind unspecified.  We use a laminar + turbulent
air-drag law

    T_wind = -(c_w1 Omega + c_w2 Omega |Omega|)        [N m, about +x]

which always opposes the spin (power -c_w1 Omega^2 - c_w2 |Omega|^3 <= 0) and is odd in Omega.

Magnitude basis (``windage_coefficients_cylinder``) for a smooth cylinder of radius r and length L
spinning in still air (density rho, dynamic viscosity mu_air, nu = mu_air / rho):

- laminar (exact for a cylinder in unbounded fluid, potential-vortex flow, shear stress 2 mu Omega):
      T = 4 pi mu_air r^2 L Omega          ->  c_w1 = 4 pi mu_air r^2 L;
- turbulent skin friction, with the moment coefficient defined by
      T = C_m (rho/2) (Omega r)^2 (2 pi r L) r = C_m pi rho Omega^2 r^4 L,
  and a turbulent boundary-layer power law C_m = 0.03 Re^-0.2, Re = Omega r^2 / nu, evaluated at a
  reference speed Omega_ref (the weak Re^-0.2 dependence is frozen there):
      c_w2 = C_m(Omega_ref) pi rho r^4 L.
  This is an order-of-magnitude estimate (published cylinder/annulus correlations differ by about
  a factor 2, and housings, disks and seals usually dominate): calibrate c_w1, c_w2 on a measured
  coast-down when one is available.

Example: 60 mm shaft (r = 0.03 m), L = 1 m, 7000 rpm (Omega = 733 rad/s), air rho = 1.2 kg/m^3,
mu_air = 1.8e-5 Pa s: Re = 4.4e4, C_m = 0.03 x 0.118 = 3.5e-3,
c_w1 = 2.0e-7 N m s, c_w2 = 1.08e-8 N m s^2, T_wind = -(1.5e-4 + 5.8e-3) = -5.95e-3 N m
(about 4.4 W): negligible against the catcher-bearing friction torques, as expected for a bare
shaft.
"""

from math import pi


def windage_torque(omega, c_w1, c_w2):
    """Windage torque on the rotor about +x [N m]: -(c_w1 Omega + c_w2 Omega |Omega|).

    omega : rotor spin [rad/s];  c_w1 [N m s], c_w2 [N m s^2] >= 0.
    """
    return -(c_w1 + c_w2 * abs(omega)) * omega


def windage_coefficients_cylinder(radius, length, omega_ref, rho=1.2, mu_air=1.8e-5):
    """(c_w1, c_w2) of a smooth cylinder in still air (formulas in the module docstring).

    Not for the hot path (called once when the model is built).
    """
    re = abs(omega_ref) * radius * radius * rho / mu_air
    c_m = 0.03 * re ** -0.2
    c_w1 = 4.0 * pi * mu_air * radius * radius * length
    c_w2 = c_m * pi * rho * radius ** 4 * length
    return c_w1, c_w2


def drive_torque(omega, gain, omega0):
    """Torque of a speed-controlled drive on the rotor about +x [N m]: gain (omega0 - Omega).

    Not in the paper (its landings coast, spin.drive = "coast"): a proportional speed loop holding
    the set speed omega0, for rigs whose motor keeps driving after the drop (spin.drive =
    "constant"). Its work gain (omega0 - Omega) Omega is an input of the energy balance.
    omega, omega0 [rad/s]; gain [N m s] >= 0.
    """
    return gain * (omega0 - omega)


def windage_torque_derivative(omega, c_w1, c_w2):
    """d T_wind / d Omega [N m s]: -(c_w1 + 2 c_w2 |Omega|) (for analytic Jacobians)."""
    return -(c_w1 + 2.0 * c_w2 * abs(omega))

"""Force laws of the auxiliary-bearing landing model, as plain functions of relative kinematics.

Reference: "Development and Experimental Validation of Auxiliary Rolling Bearing Models for
Active Magnetic Bearings (AMBs) Applications" (sections 2.2.2-2.4.4, eqs 2-30); our corrections
of its typos are listed in each module docstring and in ``docs/paper_corrections.md``.

Modules (one law each):

- ``radial_contact`` : rotor sleeve / inner-race bore contact, Hertz + Hunt-Crossley + friction
  (eqs 10-17).
- ``ball_bearing``   : ball force between the races (eq 22) and Harris-Palmgren drag torque
  (eqs 23-27).
- ``ribbon``         : ribbon damper between outer race and housing (eqs 28-29) and Coulomb
  friction of the axial support on the outer race (eq 30).
- ``axial``          : piecewise axial contact force of the rotor (eqs 2-5).
- ``spin``           : windage torque of the spin model (eq 6) and its derivative; the drive torque
  of a speed-controlled motor (not in the paper).
- ``amb``            : the AMB axis before the drop and the rotating unbalance (the levitated
  state, not in the paper's equations).
- ``axial_rub``      : friction between the rotor sleeve face and the inner-race thrust face,
  integrated over the annulus (eqs 18-21; the Wilkes forward-whirl mechanism).

Conventions (all modules)
-------------------------
- SI units throughout (m, s, kg, N, N m, rad, rad/s).  The one exception is the contact angle of
  the Harris-Palmgren law, given in degrees as in the catalogue fit of eq 26.
- Rotor axis = x.  Lateral coordinates: y horizontal, z vertical up (gravity along -z).
  The frame (x, y, z) is right-handed, so e_x x e_y = e_z and e_x x e_z = -e_y.
- Spin about +x; a positive Omega is a right-handed rotation about +x (it turns +y towards +z).
- For a radial unit vector n = (n_y, n_z) the tangential unit vector is
  t = e_x x n = (-n_z, n_y): (n, t) is a proper rotation of (e_y, e_z) (determinant +1), and a
  surface point at radius r of a body spinning at Omega moves with Omega * r * t.
- Forces are returned as components (Fy, Fz); torques are about the x axis (positive = about +x).
  Each function states on which body its force acts and about which point its torque is taken.
- Relative quantities are "first body minus second body" as named in each function
  (e.g. d = rotor centre - race centre).

Implementation rules: the laws are called inside Exudyn user functions millions of times, so they
take and return plain Python floats, use only ``math``, create no objects apart from the returned
tuple, and import neither numpy nor exudyn.  Regularised sign functions are
``reg(v) = v / sqrt(v^2 + v_reg^2)`` (scalar) and ``v / sqrt(|v|^2 + v_reg^2)`` (vector); every
``v_reg`` / ``omega_reg`` must be > 0.
"""

# Default regularisation velocities (see the module docstrings for the justification).
V_REG_DEFAULT = 1.0e-3      # m/s, slip velocities (radial contact, axial rub, ribbon, eq 30)
OMEGA_REG_DEFAULT = 0.1     # rad/s, relative race spin in the Harris-Palmgren drag torque

__all__ = ["V_REG_DEFAULT", "OMEGA_REG_DEFAULT"]

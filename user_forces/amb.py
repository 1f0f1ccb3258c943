"""Active magnetic bearings before the drop, and the rotating unbalance (not among the paper's
eqs 2-30: the paper starts its landings from the levitated state; these are the loads of that
state and of a rotor with residual unbalance).

- ``amb_force``: the levitating AMB axis as a linearised spring-damper about its set point, plus
  the bias that carries the static load (the rotor's weight share, or the thrust axially):
  F = bias - k x - c x'. The AMB "fails" at amb.t_drop: from then on the caller no longer applies
  it (amb.drop_radial / amb.drop_axial say which axes drop).
- ``unbalance_force``: the force of a point unbalance m e on the rotor spinning at Omega, rotating
  with the rotor: F = m e Omega^2 (cos phi, sin phi), phi = theta + phase (right-handed about +x,
  y towards z as in ``user_forces``).

Plain floats in and out (the functions also work element-wise on numpy arrays, which the
post-processing uses); SI units.
"""

from math import cos, sin


def amb_force(x, v, bias, stiffness, damping):
    """Force of one AMB axis on the rotor [N]: bias - stiffness x - damping v.

    x [m], v [m/s]: the rotor's displacement and velocity on that axis; bias [N]; stiffness [N/m];
    damping [N s/m].
    """
    return bias - stiffness * x - damping * v


def unbalance_force(omega, angle, magnitude):
    """(Fy, Fz) of a rotating unbalance on the rotor [N]: m e Omega^2 (cos angle, sin angle).

    omega [rad/s]: rotor spin; angle [rad]: the unbalance's angle theta + phase; magnitude [kg m]: m e.
    """
    fu = magnitude * omega * omega
    return fu * cos(angle), fu * sin(angle)

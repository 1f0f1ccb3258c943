"""The laws' parameters, resolved once: scenario values with every effect switch applied.

A scenario carries raw values (``Contact.mu_rad``, ``Bearing.eta``, ...) and switches
(``[effects]``). Before this module each consumer (the Python closures in ``forces``, the compiled
``bearing_kernel``, ``postprocess``, ``reference`` and the coast-down's decimation) resolved
``c.mu_rad if effects["radial_friction"] else 0.0`` itself. Here the switch is applied once, the
way PyBaMM's "off" submodels work: an effect that is off is the same law with the parameter that
makes it contribute nothing (mu_rad = 0, k_visc = 0, eta = 0, worn torque 0, windage
coefficients 0), or, where a law has no such value, a flag that is False (ball drag, outer-race
Coulomb friction, axial rub, gyroscopics). Consumers read :class:`BearingLaws` /
:class:`RotorLaws` and never look at ``scenario.effects`` again.

``reference_independent`` is the exception on purpose: it re-derives the model from the scenario
by its own route, so that a wiring mistake here cannot hide in both the model and its check.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from user_forces.ball_bearing import OMEGA_REG_DEFAULT, harris_palmgren_constants, worn_friction_constants

OMEGA_REG_HP = OMEGA_REG_DEFAULT  # rad/s: sign regularisation of the ball and worn drag torques (its reason there)


@dataclass(frozen=True)
class BearingLaws:
    """Effective parameters of one catcher bearing's laws (SI units; equation numbers of the paper)."""

    name: str
    # radial contact, eqs 10-17
    clearance: float            # m
    sleeve_radius: float        # m, r_r
    race_radius: float          # m, r_i = r_r + clearance
    k_hertz: float              # N/m^exponent
    exponent: float             # -
    k_visc: float               # s/m (0: effect contact_damping off)
    mu_rad: float               # - (0: effect radial_friction off)
    v_reg: float                # m/s
    # balls, eq 22
    k_b1: float                 # N/m
    k_b2: float                 # N/m^2
    c_b: float                  # N s/m
    # drag, eqs 23-27, and the worn bearing's drag (docs/paper_corrections.md)
    ball_drag: bool             # effect ball_drag
    hp: tuple                   # harris_palmgren_constants(...) at OMEGA_REG_HP
    contact_angle_deg: float    # deg (the Harris-Palmgren inputs, for the unfactored reference law)
    static_load_rating: float   # N
    pitch_diameter: float       # m
    hp_z: float                 # -
    hp_y: float                 # -
    worn_drag_torque: float     # N m (0: effect worn_bearing_drag off)
    worn_drag_growth_angle: float  # rad
    worn_drag_friction: float   # - (0: effect worn_bearing_drag off)
    worn: tuple                 # worn_friction_constants(...) at OMEGA_REG_HP
    # ribbon damper and outer race, eqs 28-30
    k_rib: float                # N/m
    c_rib: float                # N s/m
    eta: float                  # - (0: effect ribbon_cross_coupling off)
    outer_coulomb: bool         # eq 30 acts (effect outer_race_coulomb and this bearing has the axial face)
    mu_d: float                 # -
    # races, eqs 7-9
    inner_race_mass: float      # kg
    inner_race_inertia: float   # kg m^2
    inner_race_damping: float   # N s/m
    outer_race_mass: float      # kg
    outer_race_damping: float   # N s/m
    # axial face, eqs 18-21
    axial_face: bool            # this bearing takes the axial thrust
    axial_rub: bool             # eqs 18-21 act (effect axial_rub and axial_face)
    mu_ax: float                # -
    face_inner_radius: float    # m, r1
    face_outer_radius: float    # m, r2
    v_reg_axial: float          # m/s
    # inputs of the registry's mechanisms outside the kernel (mechanisms.Param): key -> value, 0 when
    # the mechanism's effect is off
    extra: dict = field(default_factory=dict)
    # the thermal preload's axial resultant [N], added to the axial load of the drag laws (Harris-
    # Palmgren, worn friction); 0 unless the registry's thermal_feedback mechanism retunes the laws
    drag_axial_preload: float = 0.0


@dataclass(frozen=True)
class RotorLaws:
    """Effective parameters of the rotor's own loads (spin eq 6, gyroscopics)."""

    gyroscopic: bool            # effect gyroscopic: -Omega G q' acts
    windage: bool               # effect windage: T_wind acts
    c_w1: float                 # N m s/rad (0 with windage off)
    c_w2: float                 # N m s^2/rad^2 (0 with windage off)
    constant_drive: bool        # spin.drive = "constant": T_drive = gain (omega0 - omega)
    drive_gain: float           # N m s/rad
    omega0: float               # rad/s, the drive's set speed (the speed at the drop)


def bearing_laws(scenario, bearing) -> BearingLaws:
    """Resolve one ``scenario.Bearing`` against the scenario's contact table and effects."""
    eff, c, p = scenario.effects, scenario.contact, bearing
    return BearingLaws(
        name=p.name, clearance=p.clearance, sleeve_radius=p.sleeve_radius, race_radius=p.race_radius,
        k_hertz=c.k_hertz, exponent=c.exponent,
        k_visc=c.k_visc if eff["contact_damping"] else 0.0,
        mu_rad=c.mu_rad if eff["radial_friction"] else 0.0,
        v_reg=c.v_reg, k_b1=p.k_b1, k_b2=p.k_b2, c_b=p.c_b,
        ball_drag=bool(eff["ball_drag"]),
        hp=tuple(harris_palmgren_constants(p.contact_angle_deg, p.static_load_rating, p.pitch_diameter, p.hp_z,
                                           p.hp_y, omega_reg=OMEGA_REG_HP)),
        contact_angle_deg=p.contact_angle_deg, static_load_rating=p.static_load_rating,
        pitch_diameter=p.pitch_diameter, hp_z=p.hp_z, hp_y=p.hp_y,
        worn_drag_torque=p.worn_drag_torque if eff["worn_bearing_drag"] else 0.0,
        worn_drag_growth_angle=p.worn_drag_growth_angle,
        worn_drag_friction=p.worn_drag_friction if eff["worn_bearing_drag"] else 0.0,
        worn=tuple(worn_friction_constants(p.worn_drag_friction if eff["worn_bearing_drag"] else 0.0,
                                           p.contact_angle_deg, p.pitch_diameter, p.worn_drag_growth_angle,
                                           omega_reg=OMEGA_REG_HP)),
        k_rib=p.k_rib, c_rib=p.c_rib,
        eta=p.eta if eff["ribbon_cross_coupling"] else 0.0,
        outer_coulomb=bool(eff["outer_race_coulomb"] and p.axial_face), mu_d=p.mu_d,
        inner_race_mass=p.inner_race_mass, inner_race_inertia=p.inner_race_inertia,
        inner_race_damping=p.inner_race_damping, outer_race_mass=p.outer_race_mass,
        outer_race_damping=p.outer_race_damping,
        axial_face=bool(p.axial_face), axial_rub=bool(p.axial_face and eff["axial_rub"]),
        mu_ax=c.mu_ax, face_inner_radius=p.face_inner_radius, face_outer_radius=p.face_outer_radius,
        v_reg_axial=c.v_reg_axial, extra=_extra(eff, p))


def _extra(eff, bearing) -> dict:
    """The registry mechanisms' own inputs, 0 where the mechanism's effect is off."""
    from .mechanisms import REGISTRY  # the registry reads this module's records

    return {par.key: (bearing.extra[par.key] if eff[m.effect] else 0.0) for m in REGISTRY for par in m.params}


def rotor_laws(scenario) -> RotorLaws:
    """Resolve the rotor's spin loads and gyroscopics against the scenario's effects."""
    eff, s = scenario.effects, scenario.spin
    wind = bool(eff["windage"])
    return RotorLaws(gyroscopic=bool(eff["gyroscopic"]), windage=wind,
                     c_w1=s.c_w1 if wind else 0.0, c_w2=s.c_w2 if wind else 0.0,
                     constant_drive=s.drive == "constant", drive_gain=s.drive_gain, omega0=scenario.omega0)

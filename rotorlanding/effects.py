"""The effect catalogue of the model-gap workflow: every switchable effect of the landing model,
the parameters a calibration may move (with bounds), and its physical signature (which features
it moves and how). Effects are switched in a scenario's ``[effects]`` table (PyBaMM-style "off"
variants); parameters are scenario keys (a parameter may drive several keys, e.g. both bearings).
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Parameter:
    name: str
    keys: tuple[str, ...]     # scenario keys set to the same value
    lower: float
    upper: float
    log: bool = False         # search in log space


@dataclass(frozen=True)
class Effect:
    name: str
    signature: str
    parameters: tuple[Parameter, ...] = field(default_factory=tuple)
    # a fault of a damaged machine rather than physics every landing has: `diagnose` tries it only
    # when named in its candidates (its signature overlaps healthy effects such as windage)
    fault: bool = False


CATALOGUE = {
    "axial_rub": Effect("axial_rub", "with axial thrust: forward whirl locked near a rotor mode, orbit of the order "
                        "of the clearance, large contact forces; no effect without thrust",
                        (Parameter("mu_ax", ("contact.mu_ax",), 0.05, 0.5),)),
    "ball_drag": Effect("ball_drag", "slower inner-race spin-up, race speed stays below the rotor speed; slightly "
                        "faster rotor deceleration while the races slip",
                        (Parameter("hp_z", ("bearings.DE.hp_z", "bearings.NDE.hp_z"), 2e-4, 2e-2, True),)),
    "worn_bearing_drag": Effect("worn_bearing_drag", "worn catcher bearing: the race slips whenever the landed "
                                "load dips, and the slip friction feeds a backward whirl of the order of the "
                                "clearance that starts tenths of a second after the drop",
                                (Parameter("worn_drag_torque", ("bearings.DE.worn_drag_torque",
                                                                "bearings.NDE.worn_drag_torque"), 0.1, 5.0, True),),
                                fault=True),
    "windage": Effect("windage", "rotor deceleration growing with speed squared, present before and after "
                      "contact; races unaffected", (Parameter("c_w2", ("spin.c_w2",), 1e-8, 2e-6, True),)),
    "ribbon_cross_coupling": Effect("ribbon_cross_coupling", "hysteretic damping of orbiting motion: smaller "
                                    "whirl orbits and forces, faster decay of bounces",
                                    (Parameter("eta", ("bearings.DE.eta", "bearings.NDE.eta"), 0.02, 0.5),)),
    "outer_race_coulomb": Effect("outer_race_coulomb", "with axial thrust: friction on the loaded outer race "
                                 "damps its orbit (smaller whirl radius, lower forces)",
                                 (Parameter("mu_d", ("bearings.NDE.mu_d",), 0.02, 0.4),)),
    "contact_damping": Effect("contact_damping", "lower rebound after the first impacts, lower peak forces",
                              (Parameter("k_visc", ("contact.k_visc",), 1e11, 1e13, True),)),
    "radial_friction": Effect("radial_friction", "race spin-up through the contact, sideways kick at landing, "
                              "backward whirl at high friction",
                              (Parameter("mu_rad", ("contact.mu_rad",), 0.05, 0.5),)),
    "unbalance": Effect("unbalance", "synchronous forward orbit component at the spin frequency",
                        (Parameter("magnitude", ("unbalance.magnitude",), 1e-6, 1e-3, True),)),
    "gyroscopic": Effect("gyroscopic", "forward/backward split of whirl frequencies growing with speed"),
    "rotor_flexibility": Effect("rotor_flexibility", "whirl frequencies and mid-span motion of a bending rotor; "
                                "without it the rotor is rigid"),
}

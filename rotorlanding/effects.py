"""The effect catalogue of the model-gap workflow: every switchable effect of the landing model,
the parameters a calibration may move (with bounds), and its physical signature (which features
it moves and how). Effects are switched in a scenario's ``[effects]`` table (PyBaMM-style "off"
variants); parameters are scenario keys (a parameter may drive several keys, e.g. both bearings).

Which effects there are comes from the mechanism registry (:data:`rotorlanding.mechanisms.REGISTRY`):
every ``[effects]`` switch a registry entry resolves (its ``switches``), in registry order, with
the entry that reads it. What the registry does not know is kept here, per switch, in
:data:`DIAGNOSIS`: the signature, the search ranges of ``diagnose`` and whether the effect is a
fault. A switch of the registry without a ``DIAGNOSIS`` entry (or the other way round) stops the
import. A registry mechanism's own switch (``Mechanism.effect``, e.g. ``race_windage``) is not a
diagnose candidate.
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
    mechanism: str = ""       # the registry entry whose switch this is (derived, see _catalogue)


def _d(signature: str, parameters: tuple[Parameter, ...] = (), fault: bool = False) -> Effect:
    """An entry of DIAGNOSIS; its name and mechanism are filled in from the registry."""
    return Effect("", signature, parameters, fault)


#: per [effects] switch: what diagnose needs beyond the registry (signature, search ranges, fault)
DIAGNOSIS = {
    "axial_rub": _d("with axial thrust: forward whirl locked near a rotor mode, orbit of the order "
                    "of the clearance, large contact forces; no effect without thrust",
                    (Parameter("mu_ax", ("contact.mu_ax",), 0.05, 0.5),)),
    "ball_drag": _d("slower inner-race spin-up, race speed stays below the rotor speed; slightly "
                    "faster rotor deceleration while the races slip",
                    (Parameter("hp_z", ("bearings.DE.hp_z", "bearings.NDE.hp_z"), 2e-4, 2e-2, True),)),
    "worn_bearing_drag": _d("worn catcher bearing: the race slips whenever the landed "
                            "load dips, and the slip friction feeds a backward whirl of the order of the "
                            "clearance that starts tenths of a second after the drop",
                            (Parameter("worn_drag_torque", ("bearings.DE.worn_drag_torque",
                                                            "bearings.NDE.worn_drag_torque"), 0.1, 5.0, True),
                             # the drag develops over this race rotation (the backward onset: Table 1's
                             # 0.4 s); one revolution to ~1000 rad (1.4 s of race rotation at 7000 rpm)
                             Parameter("worn_drag_growth_angle", ("bearings.DE.worn_drag_growth_angle",
                                                                  "bearings.NDE.worn_drag_growth_angle"),
                                       6.28, 1000.0, True)),
                            fault=True),
    "windage": _d("rotor deceleration growing with speed squared, present before and after "
                  "contact; races unaffected", (Parameter("c_w2", ("spin.c_w2",), 1e-8, 2e-6, True),)),
    "ribbon_cross_coupling": _d("hysteretic damping of orbiting motion: smaller "
                                "whirl orbits and forces, faster decay of bounces",
                                (Parameter("eta", ("bearings.DE.eta", "bearings.NDE.eta"), 0.02, 0.5),)),
    "outer_race_coulomb": _d("with axial thrust: friction on the loaded outer race "
                             "damps its orbit (smaller whirl radius, lower forces)",
                             (Parameter("mu_d", ("bearings.NDE.mu_d",), 0.02, 0.4),)),
    "contact_damping": _d("lower rebound after the first impacts, lower peak forces",
                          (Parameter("k_visc", ("contact.k_visc",), 1e11, 1e13, True),)),
    "radial_friction": _d("race spin-up through the contact, sideways kick at landing, "
                          "backward whirl at high friction",
                          (Parameter("mu_rad", ("contact.mu_rad",), 0.05, 0.5),)),
    "unbalance": _d("synchronous forward orbit component at the spin frequency",
                    (Parameter("magnitude", ("unbalance.magnitude",), 1e-6, 1e-3, True),)),
    "gyroscopic": _d("forward/backward split of whirl frequencies growing with speed"),
    "rotor_flexibility": _d("whirl frequencies and mid-span motion of a bending rotor; "
                            "without it the rotor is rigid"),
}


def _catalogue() -> dict[str, Effect]:
    """The catalogue: names and switches from the registry, the rest from DIAGNOSIS."""
    from dataclasses import replace

    from .mechanisms import REGISTRY

    out = {}
    for m in REGISTRY:
        for name in m.switches:
            if name == m.effect:
                continue  # the mechanism's own switch: not a diagnose candidate
            if name not in DIAGNOSIS:
                raise RuntimeError(f"effects.DIAGNOSIS has no entry for the switch {name!r} of mechanism {m.name!r}")
            out.setdefault(name, replace(DIAGNOSIS[name], name=name, mechanism=m.name))
    stray = sorted(set(DIAGNOSIS) - set(out))
    if stray:
        raise RuntimeError(f"effects.DIAGNOSIS names switches no registry mechanism has: {', '.join(stray)}")
    return out


#: every effect diagnose may try, by [effects] switch name (registry order)
CATALOGUE = _catalogue()

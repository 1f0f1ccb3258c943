"""The landing model's equations as numbers: coordinates, matrices and law parameters.

:func:`build_spec` turns a :class:`~rotorlanding.scenario.Scenario` into a :class:`LandingSpec`
that both the Exudyn model (``exudyn_model``) and the independent scipy reference
(``reference``) use. It holds no Exudyn objects.

Generalised coordinates (this order is also the layout of stored results)::

    q = [ lateral rotor (n_lat) | theta, x_ax | per bearing b in spec.bearing_names:
          race_y, race_z, race_phi, outer_y, outer_z ]

lateral rotor = Craig-Bampton coordinates: (y, z) of each boundary station in
``spec.stations`` order, then the fixed-interface modal coordinates. theta is the rotor spin
angle (Omega = theta'), x_ax the rigid axial displacement of the rotor.

Equations (paper section 2; our corrections in docs/paper_corrections.md)::

  rotor lateral   M q'' + (C + Omega G) q' + K q = f_g + f_amb + f_unb + sum_b S_b^T F_b
  rotor spin      I_p theta'' = sum_b T_b + T_wind + T_drive                          (eq 6)
  rotor axial     m_r x'' = F_thrust(t) + F_ax(x, x') (+ axial AMB before the drop)   (eq 2-5)
  inner race b    m_i r_i'' = -F_b + F_ball,b - C_i r_i' + m_i g;  I_i phi'' = T_race,b + T_HP,b (eq 7-8)
  outer race b    m_o r_o'' = -F_ball,b + F_ribbon,b + F_coulomb,b - C_o r_o' + m_o g (eq 9, 28-30)

F_b = radial contact force (+ axial-rub friction for the bearing with the axial face) on the
rotor at the station of bearing b, T_b its torque on the rotor.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .params import BearingLaws, RotorLaws, bearing_laws, rotor_laws
from .reduction import LinearRotor, craig_bampton
from .scenario import Scenario
from .timoshenko import GRAVITY, RotorFE, assemble, landing_support_preload, with_landing_supports


@dataclass
class BearingSpec:
    """Index bookkeeping and law parameters of one catcher bearing."""

    name: str
    station: str
    i_station: int              # index in q of the station's y (z follows)
    i_race: int                 # index in q of race_y (race_z, race_phi, outer_y, outer_z follow)
    tilt_alpha: np.ndarray      # row of T giving the rotor's alpha at the station from q_lat
    tilt_beta: np.ndarray
    params: object              # scenario.Bearing (raw values, as written)
    laws: BearingLaws           # the same bearing with the effect switches applied (params.bearing_laws)

    @property
    def i_outer(self) -> int:
        return self.i_race + 3


@dataclass
class LandingSpec:
    scenario: Scenario
    fe: RotorFE
    cb: LinearRotor
    stations: list[str]
    n_lat: int
    M: np.ndarray               # lateral reduced matrices
    K: np.ndarray
    C: np.ndarray
    G: np.ndarray
    f_gravity: np.ndarray       # reduced constant load on the lateral coordinates: gravity and the preload of
    #                             in_landing supports relaxed off the levitated axis (timoshenko.landing_support_preload)
    rotor_mass: float
    rotor_polar_inertia: float
    i_theta: int
    i_axial: int
    bearings: list[BearingSpec]
    unbalance_rows: tuple[np.ndarray, np.ndarray] | None = None
    amb_rows: list[tuple[int, int]] = field(default_factory=list)  # AMB acts on these (y, z) q-indices
    names: list[str] = field(default_factory=list)
    rotor_laws: RotorLaws | None = None   # spin loads and gyroscopics with the effect switches applied

    @property
    def n(self) -> int:
        return len(self.names)

    @property
    def bearing_names(self) -> list[str]:
        return [b.name for b in self.bearings]

    def axial_face_bearing(self) -> BearingSpec | None:
        for b in self.bearings:
            if b.params.axial_face:
                return b
        return None

    def thrust(self, t: float) -> float:
        """Axial thrust F_thrust(t) [N]: off until t_thrust, linear ramp over ramp_s, then constant."""
        a = self.scenario.axial
        if t < a.t_thrust:
            return 0.0
        if a.ramp_s > 0 and t < a.t_thrust + a.ramp_s:
            return a.f_thrust * (t - a.t_thrust) / a.ramp_s
        return a.f_thrust

    def mass_vector_races(self) -> dict:
        return {b.name: (b.params.inner_race_mass, b.params.inner_race_inertia, b.params.outer_race_mass)
                for b in self.bearings}

    def initial_state(self) -> tuple[np.ndarray, np.ndarray]:
        """Levitated start: sleeves centred (held by the AMBs), the rotor's static sag between
        them in the modal coordinates (Craig-Bampton K is block-diagonal, so the modal part of
        K q = f_g decouples), spin at speed, races at rest and centred, axial at 0."""
        q0 = np.zeros(self.n)
        v0 = np.zeros(self.n)
        nb = 2 * len(self.stations)
        if self.n_lat > nb:
            km = self.K[nb:self.n_lat, nb:self.n_lat]
            q0[nb:self.n_lat] = np.linalg.solve(km, self.f_gravity[nb:self.n_lat])
        dy, dz = self.scenario.amb.drop_offset_m
        if dy or dz:  # rigid shift: the Craig-Bampton boundary translations move, the modes do not
            for i, name in enumerate(self.names[:nb]):
                q0[i] += dy if name.endswith(".y") else dz if name.endswith(".z") else 0.0
        v0[self.i_theta] = self.scenario.omega0
        return q0, v0


def build_spec(scenario: Scenario, *, reduction=None) -> LandingSpec:
    """The landing's equations from a scenario. ``reduction``: the Craig-Bampton function to use
    (a study passes its ``runner.ReductionCache``; default ``reduction.craig_bampton``)."""
    fe = with_landing_supports(assemble(scenario.rotor))
    red = scenario.rotor.reduction
    n_modes = red.modes if scenario.effects["rotor_flexibility"] else 0
    cb = (reduction or craig_bampton)(fe, red.boundary_stations, n_modes, rotations=False)
    stations = list(red.boundary_stations)
    n_lat = cb.n
    names = list(cb.names) + ["theta", "x_axial"]
    i_theta, i_axial = n_lat, n_lat + 1
    bearings = []
    for bname, p in scenario.bearings.items():  # the scenario's order (DE, NDE in the rig files)
        i_race = len(names)
        names += [f"{bname}.race_y", f"{bname}.race_z", f"{bname}.race_phi", f"{bname}.outer_y", f"{bname}.outer_z"]
        node = fe.station_nodes[p.station]
        bearings.append(BearingSpec(bname, p.station, cb.index(p.station, "y"), i_race,
                                    cb.T[4 * node + 2].copy(), cb.T[4 * node + 3].copy(), p,
                                    bearing_laws(scenario, p)))
    unb = None
    if scenario.unbalance is not None and scenario.effects["unbalance"]:
        node = fe.station_nodes[scenario.unbalance.station]
        unb = (cb.T[4 * node].copy(), cb.T[4 * node + 1].copy())
    amb_rows = [(cb.index(s, "y"), cb.index(s, "z")) for s in stations]
    f_const = cb.gravity_load() + cb.T.T @ landing_support_preload(fe)
    return LandingSpec(scenario, fe, cb, stations, n_lat, cb.M, cb.K, cb.C, cb.G, f_const,
                       fe.mass, fe.polar_inertia, i_theta, i_axial, bearings, unb, amb_rows, names,
                       rotor_laws(scenario))


G_ACC = GRAVITY  # m/s^2, re-exported for the force closures

"""Landing scenario: the TOML schema of a landing case, read into dataclasses with validation.

A scenario file holds (directly or via ``include``) these tables; field reference with units
in ``docs/scenario_file.md``::

    [rotor]            the rotor (docs/rotor_file.md); [rotor.reduction] is required here
    [bearings.NAME]    one per catcher bearing (DE, NDE, or any name): station, races, balls, ribbon
    [contact]          sleeve / inner-race radial contact and axial-face friction
    [axial]            rigid-body axial model (eqs 2-5) and the thrust load profile
    [amb]              magnetic bearings before the drop (PD hold) and the drop instant
    [spin]             rotor drive and windage (eq 6)
    [unbalance]        optional unbalance
    [effects]          switches of the physical effects (model-gap workflow toggles them)
    [operating]        speed_rpm, t_end, orientation (only "horizontal")
    [solver]           time step, generalized-alpha and Newton settings, output sampling

Every effect has an "off" variant selected by ``[effects]``; names are listed in ``EFFECTS``.
"""

from __future__ import annotations

import copy
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from .config import Table, deep_merge, get_dotted, load_toml, parse_value, set_dotted, split_override
from .errors import InputError
from .limits import FIELDS as LIMIT_FIELDS
from .limits import limits_from_dict
from .mechanisms import extra_bearing_params, extra_effects
from .rotor import Rotor, rotor_from_dict

#: switchable effects and their defaults (True = on)
EFFECTS = {
    "gyroscopic": True,              # Omega G q' of the rotor (eq 1)
    "radial_friction": True,         # Coulomb friction of the sleeve on the inner race (eq 15-17)
    "contact_damping": True,         # Hunt-Crossley dissipation of the radial contact (eq 15)
    "axial_rub": True,               # friction on the axial thrust face, lateral coupling (eq 18-21)
    "ball_drag": True,               # Harris-Palmgren drag torque on the inner race (eq 23-27)
    "ribbon_cross_coupling": True,   # sign-switching cross-coupled ribbon stiffness (eq 28-29)
    "outer_race_coulomb": True,      # outer race / housing Coulomb friction from axial load (eq 30)
    "windage": True,                 # aerodynamic drag torque on the rotor (eq 6)
    "worn_bearing_drag": False,      # load-independent drag torque of a worn catcher bearing (not in the paper)
    "unbalance": False,              # rotating unbalance force from [unbalance]
    "rotor_flexibility": True,       # keep the fixed-interface modes (false: rigid-rotor model)
    **extra_effects(),               # switches of mechanisms outside the compiled kernel (mechanisms.py)
}

#: the two catcher bearings of the paper's rig; any other name of letters and digits works too
#: (a rotor with three catcher bearings: [bearings.DE], [bearings.MID], [bearings.NDE])
BEARING_NAMES = ("DE", "NDE")
_BEARING_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9]{0,15}$")

# Physical plausibility limits (docs/scenario_file.md, "Plausibility limits"): a value beyond one is
# not a rig that exists, and the solver would either stop or, worse, finish with numbers that mean
# nothing. Each limit is set where the physics ends, not at the edge of today's rig, so unusual but
# real machines pass; rotor limits (density, stiffness, disk mass, burst speed) live in rotor.py.

#: -: friction coefficients (mu_rad, mu_ax, mu_d and the ribbon's friction ratio eta). Clean
#: unlubricated metals in air show 0.5-1.5 (ASM Handbook Vol. 18, Friction, Lubrication and Wear
#: Technology; steel on steel 0.6-0.8 dry); beyond ~2 only atomically clean surfaces in vacuum,
#: i.e. seizure, which a Coulomb law does not describe
MAX_FRICTION = 2.0
#: -: radial clearance / sleeve radius. Catcher-bearing clearances are 0.1-1 % of the journal radius
#: (about half the AMB air gap); the contact model (Hertz contact of nearly conforming circles,
#: small journal excursions) is meaningless long before the clearance reaches 10 % of the radius
MAX_CLEARANCE_RATIO = 0.1
#: -: k h^2 / m (and c h / m) of a spring (damper) on the lightest body it acts on. Above 1e6 the
#: body's inertia term in the Newton matrix, M / (beta h^2) + C gamma / (beta h) + K, is below the
#: Newton tolerance (1e-6 relative): the solver no longer sees the body move, the spring is a rigid
#: link the solver cannot resolve with this solver.step
MAX_STEP_RATIO = 1.0e6
#: Harris-Palmgren f1 = z (F_s/C_s)^y: Harris gives z = 0.0004-0.003, y = 0.33-0.55
MAX_HP_Z = 0.1
MAX_HP_Y = 2.0
#: m/s: friction regularisation velocity; wider turns Coulomb friction into viscous damping
MAX_V_REG = 1.0
#: s: one day of simulated time; a landing lasts seconds, a coast-down to rest minutes to hours
MAX_T_END = 86400.0


@dataclass(frozen=True)
class Bearing:
    name: str
    station: str
    clearance: float            # m, radial clearance sleeve / inner-race bore
    sleeve_radius: float        # m, rotor landing-sleeve radius r_r
    inner_race_mass: float      # kg
    inner_race_inertia: float   # kg m^2, about the spin axis
    inner_race_damping: float   # N s/m, C_i of eq 7 (to ground)
    outer_race_mass: float      # kg (ring plus what moves with it)
    outer_race_damping: float   # N s/m, C_o of eq 9 (to ground)
    k_b1: float                 # N/m, ball load-deflection, linear term (eq 22)
    k_b2: float                 # N/m^2, quadratic term
    c_b: float                  # N s/m, ball-set damping
    contact_angle_deg: float    # deg
    static_load_rating: float   # N, C_s
    pitch_diameter: float       # m, d_m
    hp_z: float                 # Harris-Palmgren z
    hp_y: float                 # Harris-Palmgren exponent y
    worn_drag_torque: float     # N m, Coulomb drag of a worn bearing (effect worn_bearing_drag)
    worn_drag_growth_angle: float  # rad, race rotation over which that drag develops (0: from the start)
    worn_drag_friction: float   # -, load-proportional part of that drag: Coulomb coefficient of the ball contacts
    k_rib: float                # N/m (eq 28)
    c_rib: float                # N s/m
    eta: float                  # -, ribbon cross-coupling factor (eq 29)
    mu_d: float                 # -, outer race / housing Coulomb friction (eq 30)
    axial_face: bool            # this bearing takes the axial thrust on its face
    face_inner_radius: float    # m, r1 of the thrust-face annulus
    face_outer_radius: float    # m, r2
    #: inputs of mechanisms outside the compiled kernel, key -> value (mechanisms.Param, SI)
    extra: dict = field(default_factory=dict)

    @property
    def race_radius(self) -> float:
        """Inner-race bore radius r_i = r_r + clearance."""
        return self.sleeve_radius + self.clearance


@dataclass(frozen=True)
class Contact:
    k_hertz: float      # N/m^exponent
    exponent: float     # -
    k_visc: float       # s/m, Hunt-Crossley: F = k_hertz delta^e (1 + k_visc/k_hertz ... ) see user_forces
    mu_rad: float       # -
    mu_ax: float        # -
    v_reg: float        # m/s, friction regularisation velocity (radial contact, ribbon sign, eq 30)
    v_reg_axial: float  # m/s, regularisation of the axial-face friction (eqs 19-20)


@dataclass(frozen=True)
class Axial:
    cl_ax: float        # m
    delta_m: float      # m
    k_cb: float         # N/m
    k_ws: float         # N/m
    k_h: float          # N/m
    c_ax: float         # N s/m
    f_thrust: float     # N, thrust towards the axial face (positive pushes the rotor to +x)
    t_thrust: float     # s, thrust switched on
    ramp_s: float       # s, linear ramp duration


@dataclass(frozen=True)
class Amb:
    stiffness: float    # N/m, PD hold of each radial AMB before the drop
    damping: float      # N s/m
    axial_stiffness: float
    axial_damping: float
    t_drop: float       # s
    drop_radial: bool
    drop_axial: bool
    drop_offset_m: tuple[float, float] = (0.0, 0.0)   # m, (y, z) of the rotor at the drop (AMB position error)


@dataclass(frozen=True)
class Spin:
    drive: str          # "coast" | "constant"
    drive_gain: float   # N m s/rad, speed controller gain when drive = "constant"
    c_w1: float         # N m s/rad
    c_w2: float         # N m s^2/rad^2


@dataclass(frozen=True)
class Unbalance:
    station: str
    magnitude: float    # kg m (mass x eccentricity)
    phase_deg: float


@dataclass(frozen=True)
class Solver:
    step: float         # s
    spectral_radius: float
    modified_newton: bool
    output_period: float  # s
    newton_relative_tolerance: float = 1e-6
    newton_absolute_tolerance: float = 1e-8
    #: "fixed": every step is ``step`` (halved only where Newton fails); "auto": error-controlled
    #: step in [min_step, max_step] starting at ``step`` (rotorlanding.exudyn_model.StepController,
    #: docs/performance.md issue 21)
    step_control: str = "fixed"
    #: auto: allowed local position error per step [m] (estimate |beta - 1/6| h^2 |a_end - a_start|)
    step_tolerance: float = 1e-7
    max_step: float = 4e-4      # s, auto only
    min_step: float = 1e-7      # s, auto only


STEP_CONTROLS = ("fixed", "auto")


@dataclass(frozen=True)
class Bound:
    """The plausible physical range of one rig parameter and where that range comes from
    (``[bounds]`` in a rig or rotor file: ``"bearings.DE.eta" = {min = .., max = .., source = ".."}``).
    A calibrated parameter must lie inside its bound and not on it (``validate``)."""
    min: float
    max: float
    source: str
    log: bool = False   # a scale parameter: positions are measured on a log axis

    def position(self, value: float) -> float:
        """Where ``value`` lies in the range: 0 at min, 1 at max (on a log axis for ``log``)."""
        if self.log:
            return math.log(value / self.min) / math.log(self.max / self.min) if value > 0 else -math.inf
        return (value - self.min) / (self.max - self.min)


def _bounds(data: dict) -> dict[str, Bound]:
    raw = data.get("bounds", {})
    if not isinstance(raw, dict):
        raise InputError("bounds", raw, "must be a table of \"dotted.key\" = {min, max, source}")
    out = {}
    for key, b in raw.items():
        field_ = f"bounds.{key}"
        if not (isinstance(b, dict) and {"min", "max", "source"} <= set(b) <= {"min", "max", "source", "log"}):
            raise InputError(field_, b, "must be {min = a, max = b, source = \"where the range comes from\"} "
                                        "(optional log = true)")
        lo, hi, src, log = b["min"], b["max"], b["source"], b.get("log", False)
        if not all(isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) for x in (lo, hi)) \
                or not lo < hi or (log is True and not lo > 0) or not isinstance(log, bool):
            raise InputError(field_, b, "needs finite numbers min < max (min > 0 with log = true)")
        if not (isinstance(src, str) and src.strip()):
            raise InputError(field_ + ".source", src, "must name the source of the range")
        try:
            value = get_dotted(data, key)
        except InputError:
            # a bound of a parameter this scenario does not have (e.g. a rotor overlaid with fewer
            # disks): it bounds nothing here; tests/test_rig_bounds.py checks every bound of the
            # rig files resolves in the paper scenarios, so a misspelt key does not go unseen
            continue
        if isinstance(value, (dict, list)):
            raise InputError(field_, key, "names a table or list, not a numeric parameter")
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            # the value is what is wrong (a text where a number belongs), not its bound
            raise InputError(key, value, f"must be a finite number (its [bounds] entry: {lo:g} .. {hi:g})")
        out[key] = Bound(float(lo), float(hi), src.strip(), log)
    return out


@dataclass
class Scenario:
    name: str
    rotor: Rotor
    bearings: dict[str, Bearing]
    contact: Contact
    axial: Axial
    amb: Amb
    spin: Spin
    unbalance: Unbalance | None
    effects: dict[str, bool]
    speed_rpm: float
    t_end: float
    solver: Solver
    raw: dict = field(repr=False, default_factory=dict)  # the fully resolved input tables
    source: str | None = None
    #: plausible physical range of rig parameters, dotted key -> Bound (``[bounds]`` of the rig files)
    bounds: dict[str, "Bound"] = field(default_factory=dict)

    @property
    def omega0(self) -> float:
        return self.speed_rpm * math.pi / 30.0


def _bearing(name: str, t: Table, rotor: Rotor) -> Bearing:
    station = t.string("station")
    if station not in rotor.stations:
        raise InputError(f"{t.path}.station", station, f"unknown station; defined: {', '.join(rotor.stations)}")
    pos = dict(positive=True)
    nn = dict(nonnegative=True)
    b = Bearing(
        name=name, station=station,
        clearance=t.number("clearance", **pos),
        sleeve_radius=t.number("sleeve_radius", **pos),
        inner_race_mass=t.number("inner_race_mass", **pos),
        inner_race_inertia=t.number("inner_race_inertia", **pos),
        inner_race_damping=t.number("inner_race_damping", 0.0, **nn),
        outer_race_mass=t.number("outer_race_mass", **pos),
        outer_race_damping=t.number("outer_race_damping", 0.0, **nn),
        k_b1=t.number("k_b1", **pos), k_b2=t.number("k_b2", 0.0, **nn), c_b=t.number("c_b", 0.0, **nn),
        contact_angle_deg=t.number("contact_angle_deg", **pos, upper=90.0),
        static_load_rating=t.number("static_load_rating", **pos),
        pitch_diameter=t.number("pitch_diameter", **pos),
        hp_z=t.number("hp_z", **nn), hp_y=t.number("hp_y", **nn),
        worn_drag_torque=t.number("worn_drag_torque", 0.0, **nn),
        worn_drag_growth_angle=t.number("worn_drag_growth_angle", 0.0, **nn),
        worn_drag_friction=t.number("worn_drag_friction", 0.0, **nn),
        k_rib=t.number("k_rib", **pos), c_rib=t.number("c_rib", 0.0, **nn),
        eta=t.number("eta", 0.0, **nn), mu_d=t.number("mu_d", 0.0, **nn),
        axial_face=t.boolean("axial_face", False),
        face_inner_radius=t.number("face_inner_radius", 0.0, **nn),
        face_outer_radius=t.number("face_outer_radius", 0.0, **nn),
        extra={p.key: _param(t, p) for p in extra_bearing_params()},
    )
    from .rotor import MAX_DIMENSION

    amb, limit = b.extra.get("thermal_ambient_k"), b.extra.get("thermal_runaway_limit_k")
    if amb is not None and limit is not None and not limit > amb:
        # a limit the bearing starts above would report runaway at the first step
        raise InputError(f"{t.path}.thermal_runaway_limit_k", limit, f"must be above the ambient thermal_ambient_k "
                         f"= {amb:g} K")
    for key in ("sleeve_radius", "pitch_diameter", "face_inner_radius", "face_outer_radius"):
        if getattr(b, key) > MAX_DIMENSION:  # plausibility (see _plausible); first, as the face check uses them
            raise InputError(f"{t.path}.{key}", getattr(b, key), f"must be <= {MAX_DIMENSION:g} m (the largest rotors "
                             "built are ~2 m across)")
    if b.axial_face and not 0 < b.face_inner_radius < b.face_outer_radius:
        raise InputError(f"{t.path}.face_outer_radius", b.face_outer_radius,
                         f"with axial_face = true need 0 < face_inner_radius ({b.face_inner_radius}) < face_outer_radius")
    t.finish()
    return b


def _param(t: Table, p) -> float:
    """A registry mechanism's per-bearing input (``mechanisms.Param``): >= 0 (> 0 where zero means
    nothing), at most its physical maximum, whose reason the one-line error gives."""
    value = t.number(p.key, p.default, positive=p.positive, nonnegative=True)
    if value > p.upper:
        raise InputError(f"{t.path}.{p.key}", value, f"must be <= {p.upper:g} {p.unit}: {p.why}")
    return value


def _drop_offset(value, clearance: float) -> tuple[float, float]:
    """[y, z] of the rotor at the drop [m]: a rigid shift of the levitated rotor (the AMBs' position
    error; an ensemble of drops from a small circle samples the landing's sensitivity)."""
    ok = isinstance(value, (list, tuple)) and len(value) == 2 and all(
        isinstance(x, (int, float)) and not isinstance(x, bool) for x in value)
    if not ok:
        raise InputError("amb.drop_offset_m", value, "must be [y, z] in m, e.g. [5e-6, 0.0]")
    y, z = float(value[0]), float(value[1])
    if not (y * y + z * z) ** 0.5 < clearance:
        raise InputError("amb.drop_offset_m", value, f"must lie inside the radial clearance ({clearance:g} m)")
    return (y, z)


def scenario_from_dict(data: dict, *, source: str | None = None, name: str | None = None) -> Scenario:
    try:
        return _scenario(copy.deepcopy(data), source, name)
    except InputError as err:
        raise err.with_file(source) if source else err


def _scenario(data: dict, source, name) -> Scenario:
    rotor = rotor_from_dict(data)
    if rotor.reduction is None:
        raise InputError("rotor.reduction", None, "missing table: the landing model needs boundary_stations and modes")
    top = Table(data, "")
    top.raw("rotor")
    bounds = _bounds(data)
    top.raw("bounds", {})
    limits = limits_from_dict(top.raw("limits", None))  # validated here (before any run); read by rotorlanding.verdict
    for station in limits.close_clearances_m:  # a gap at a station the rotor lacks would never be judged
        if station not in rotor.stations:
            raise InputError(f"limits.close_clearances_m.{station}", limits.close_clearances_m[station],
                             f"unknown rotor station; defined: {', '.join(rotor.stations) or 'none'}")
    title = top.string("name", name or (Path(source).stem if source else "scenario"))

    bt = top.table("bearings")
    bearings = {}
    for key in bt.data:
        # the name prefixes every output series of the bearing (DE_contact_force_y_n): letters and
        # digits only, so a series name splits back into bearing and quantity at its first "_"
        if not _BEARING_NAME.match(key):
            raise InputError(f"bearings.{key}", "(table)", "a bearing name is a letter followed by up to 15 letters "
                             "or digits (e.g. DE, NDE, MID, B3)")
        bearings[key] = _bearing(key, bt.table(key), rotor)
    if not bearings:
        raise InputError("bearings", {}, "define at least one catcher bearing, e.g. [bearings.DE] and [bearings.NDE]")
    seen = {}
    for b in bearings.values():
        if b.station in seen:
            raise InputError(f"bearings.{b.name}.station", b.station,
                             f"already carries bearing {seen[b.station]}: one catcher bearing per station")
        seen[b.station] = b.name
    for b in bearings.values():
        if b.station not in rotor.reduction.boundary_stations:
            raise InputError(f"bearings.{b.name}.station", b.station,
                             f"must be a Craig-Bampton boundary station ({', '.join(rotor.reduction.boundary_stations)})")
    if sum(b.axial_face for b in bearings.values()) > 1:
        raise InputError("bearings", "axial_face", "at most one bearing can take the axial thrust (axial_face = true)")

    c = top.table("contact")
    exponent = c.number("exponent", 1.5, positive=True)
    if not 1.0 <= exponent <= 2.0:
        raise InputError("contact.exponent", exponent, "must lie in [1, 2] (1 linear, 10/9 line, 1.5 point contact)")
    contact = Contact(c.number("k_hertz", positive=True), exponent,
                      c.number("k_visc", 0.0, nonnegative=True), c.number("mu_rad", nonnegative=True),
                      c.number("mu_ax", nonnegative=True), c.number("v_reg", 1e-3, positive=True),
                      c.number("v_reg_axial", 1e-2, positive=True))
    c.finish()

    a = top.table("axial")
    axial = Axial(a.number("cl_ax", nonnegative=True), a.number("delta_m", positive=True),
                  a.number("k_cb", positive=True), a.number("k_ws", positive=True), a.number("k_h", positive=True),
                  a.number("c_ax", 0.0, nonnegative=True), a.number("f_thrust", 0.0),
                  a.number("t_thrust", 0.0, nonnegative=True), a.number("ramp_s", 0.0, nonnegative=True))
    a.finish()

    m = top.table("amb")
    amb = Amb(m.number("stiffness", positive=True), m.number("damping", 0.0, nonnegative=True),
              m.number("axial_stiffness", positive=True), m.number("axial_damping", 0.0, nonnegative=True),
              m.number("t_drop", 0.0, nonnegative=True), m.boolean("drop_radial", True), m.boolean("drop_axial", False),
              _drop_offset(m.raw("drop_offset_m", [0.0, 0.0]), min(b.clearance for b in bearings.values())))
    m.finish()

    s = top.table("spin", {})
    drive = s.string("drive", "coast")
    if drive not in ("coast", "constant"):
        raise InputError("spin.drive", drive, "must be 'coast' or 'constant'")
    spin = Spin(drive, s.number("drive_gain", 0.0, nonnegative=True),
                s.number("c_w1", 0.0, nonnegative=True), s.number("c_w2", 0.0, nonnegative=True))
    s.finish()

    e = top.table("effects", {})
    effects = dict(EFFECTS)
    for key in e.data:
        if key not in EFFECTS:
            raise InputError(f"effects.{key}", e.data[key], f"unknown effect; allowed: {', '.join(EFFECTS)}")
        effects[key] = e.boolean(key)
    e.finish()

    unbalance = None
    if top.has("unbalance"):
        u = top.table("unbalance")
        st = u.string("station")
        if st not in rotor.stations:
            raise InputError("unbalance.station", st, f"unknown station; defined: {', '.join(rotor.stations)}")
        unbalance = Unbalance(st, u.number("magnitude", nonnegative=True), u.number("phase_deg", 0.0))
        u.finish()
    elif effects["unbalance"]:
        raise InputError("effects.unbalance", True, "needs an [unbalance] table (station, magnitude)")
    if effects["worn_bearing_drag"] and not any(b.worn_drag_torque > 0 or b.worn_drag_friction > 0
                                                for b in bearings.values()):
        raise InputError("effects.worn_bearing_drag", True,
                         "needs worn_drag_torque > 0 [N m] or worn_drag_friction > 0 on at least one bearing "
                         "(e.g. bearings.DE.worn_drag_friction)")

    o = top.table("operating")
    speed = o.number("speed_rpm", nonnegative=True)
    t_end = o.number("t_end", positive=True)
    # gravity acts along -z of the lateral plane (races' static load, the AMB bias, the sag of the
    # start state); a vertical machine would put it along the axis, onto the axial support
    orientation = o.string("orientation", "horizontal")
    if orientation != "horizontal":
        raise InputError("operating.orientation", orientation, "only 'horizontal' is modelled: gravity acts "
                         "laterally (-z) on the rotor and races; a vertical machine (gravity along the axis, the "
                         "rotor resting on its axial support) is not")
    o.finish()
    if t_end <= amb.t_drop:
        raise InputError("operating.t_end", t_end, f"must be > amb.t_drop ({amb.t_drop} s)")
    if spin.drive == "constant" and spin.drive_gain <= 0:
        raise InputError("spin.drive_gain", spin.drive_gain, "must be > 0 when drive = 'constant'")

    sv = top.table("solver", {})
    solver = Solver(sv.number("step", 1e-5, positive=True), sv.number("spectral_radius", 0.8),
                    sv.boolean("modified_newton", True), sv.number("output_period", 1e-4, positive=True),
                    sv.number("newton_relative_tolerance", 1e-6, positive=True),
                    sv.number("newton_absolute_tolerance", 1e-8, positive=True),
                    sv.string("step_control", "fixed"), sv.number("step_tolerance", 1e-7, positive=True),
                    sv.number("max_step", 4e-4, positive=True), sv.number("min_step", 1e-7, positive=True))
    sv.finish()
    if solver.step_control not in STEP_CONTROLS:
        raise InputError("solver.step_control", solver.step_control, "must be one of " + " | ".join(map(repr, STEP_CONTROLS)))
    if solver.step_tolerance >= 1e-3:
        raise InputError("solver.step_tolerance", solver.step_tolerance,
                         "must be < 1e-3 m (a local error above any catcher clearance controls nothing)")
    if solver.step_control == "auto":
        # the controller moves the step inside [min_step, max_step] and starts at step
        if solver.max_step > t_end:
            raise InputError("solver.max_step", solver.max_step, f"must be <= operating.t_end ({t_end} s)")
        if not solver.min_step <= solver.step <= solver.max_step:
            raise InputError("solver.step", solver.step, f"must lie in [solver.min_step ({solver.min_step:g} s), "
                             f"solver.max_step ({solver.max_step:g} s)] when solver.step_control = 'auto'")
    if not 0.0 <= solver.spectral_radius <= 1.0:
        raise InputError("solver.spectral_radius", solver.spectral_radius, "must lie in [0, 1]")
    if solver.step > t_end:
        raise InputError("solver.step", solver.step, f"must be <= operating.t_end ({t_end} s)")
    if solver.output_period < solver.step:
        raise InputError("solver.output_period", solver.output_period, f"must be >= solver.step ({solver.step} s)")
    top.finish()
    sc = Scenario(title, rotor, bearings, contact, axial, amb, spin, unbalance, effects, speed, t_end, solver,
                  raw=data, source=source, bounds=bounds)
    _plausible(sc)
    return sc


def _plausible(sc: Scenario) -> None:
    """Physical plausibility limits of a scenario (module constants above, with their reasons)."""
    from .rotor import MAX_DENSITY
    from .timoshenko import GRAVITY

    # the stiffness / damping limits below bound the largest step the solver takes: that is
    # solver.step for a fixed step, but the auto step grows to solver.max_step (StepController;
    # solver.step is only its first step and the contact look-ahead's floor)
    if sc.solver.step_control == "auto":
        h, h_name = sc.solver.max_step, "solver.max_step"
    else:
        h, h_name = sc.solver.step, "solver.step"

    h_text = f"{h_name} = {h:g} s" + (" (the auto step grows up to it)" if h_name == "solver.max_step" else "")

    def or_smaller(h_max):
        """Under auto the other way out: max_step is a solver choice, not the machine's."""
        return f"; or solver.max_step <= {h_max:.3g} s" if h_name == "solver.max_step" else ""

    # the speed first: the spin terms below scale with it
    burst, part = sc.rotor.burst_speed_rpm()
    if sc.speed_rpm > burst:
        raise InputError("operating.speed_rpm", sc.speed_rpm, f"must be <= {burst:.4g} rpm: above it {part} bursts even "
                         "if made of the strongest steel (solid-disk rim speed sqrt(8 sigma_u/((3+nu) rho)), "
                         "sigma_u = 2.5 GPa)")

    def friction(field_, mu):
        if mu > MAX_FRICTION:
            raise InputError(field_, mu, f"a friction coefficient must lie in [0, {MAX_FRICTION:g}] (clean dry metals "
                             "in air: 0.5-1.5; beyond that is seizure, not Coulomb friction)")

    def stiff(field_, k, m, body, unit="N/m"):
        if k * h * h / m > MAX_STEP_RATIO:
            raise InputError(field_, k, f"must be <= {MAX_STEP_RATIO * m / h ** 2:.3g} {unit} here: on the {body} "
                             f"({m:.3g} kg) with {h_text} its inertia is below the Newton tolerance "
                             f"(k h^2/m <= {MAX_STEP_RATIO:g}); a rigid link the solver cannot resolve"
                             + or_smaller(math.sqrt(MAX_STEP_RATIO * m / k)))

    def damp(field_, c, m, body):
        if c * h / m > MAX_STEP_RATIO:
            raise InputError(field_, c, f"must be <= {MAX_STEP_RATIO * m / h:.3g} N s/m here: on the {body} "
                             f"({m:.3g} kg) with {h_text} its inertia is below the Newton tolerance "
                             f"(c h/m <= {MAX_STEP_RATIO:g})" + or_smaller(MAX_STEP_RATIO * m / c))

    for b in sc.bearings.values():
        p = f"bearings.{b.name}"
        if b.clearance > MAX_CLEARANCE_RATIO * b.sleeve_radius:
            raise InputError(f"{p}.clearance", b.clearance, f"must be <= {MAX_CLEARANCE_RATIO:g} x sleeve_radius "
                             f"({MAX_CLEARANCE_RATIO * b.sleeve_radius:.3g} m): catcher-bearing clearances are "
                             "0.1-1 % of the journal radius")
        r_i, r_p = b.race_radius, b.pitch_diameter / 2.0
        if not r_p > r_i:
            raise InputError(f"{p}.pitch_diameter", b.pitch_diameter, f"must be > the bore diameter 2 (sleeve_radius + "
                             f"clearance) = {2 * r_i:.4g} m: the balls run outside the inner race's bore")
        # the most a race can weigh: the densest element filling the space from the bore to the
        # pitch circle (inner) or from the pitch circle to twice its radius (outer, with what moves
        # with it), as wide as the pitch diameter (wider than any rolling bearing)
        m_in = MAX_DENSITY * math.pi * (r_p ** 2 - r_i ** 2) * 2.0 * r_p
        m_out = MAX_DENSITY * math.pi * 3.0 * r_p ** 2 * 2.0 * r_p
        for key, m, cap in (("inner_race_mass", b.inner_race_mass, m_in), ("outer_race_mass", b.outer_race_mass, m_out)):
            if m > cap:
                raise InputError(f"{p}.{key}", m, f"must be <= {cap:.3g} kg: a ring of the densest element (osmium) "
                                 "that fills the bearing's envelope (pitch_diameter, sleeve_radius) weighs no more")
        if b.inner_race_inertia > m_in * r_p ** 2:
            raise InputError(f"{p}.inner_race_inertia", b.inner_race_inertia, f"must be <= {m_in * r_p ** 2:.3g} kg m^2: "
                             "the heaviest possible inner race (osmium, bore to pitch circle) with all its mass at "
                             "the pitch radius")
        # ISO 76: C0 = f0 i Z Dw^2 cos(alpha) with f0 <= 14 MPa; the balls sit on the pitch circle
        # (Z Dw <= pi d_m, Dw <= d_m/2) in at most 2 rows: C0 <= 14 MPa x 2 x pi d_m^2 / 2
        c0_max = 14e6 * math.pi * b.pitch_diameter ** 2
        if b.static_load_rating > c0_max:
            raise InputError(f"{p}.static_load_rating", b.static_load_rating, f"must be <= {c0_max:.3g} N: the static "
                             "rating of a double-row bearing full of balls of half the pitch diameter (ISO 76, f0 <= 14 MPa)")
        if b.hp_z > MAX_HP_Z or b.hp_y > MAX_HP_Y:
            key, v, cap = ("hp_z", b.hp_z, MAX_HP_Z) if b.hp_z > MAX_HP_Z else ("hp_y", b.hp_y, MAX_HP_Y)
            raise InputError(f"{p}.{key}", v, f"must be <= {cap:g}: Harris gives z = 0.0004-0.003 and y = 0.33-0.55 "
                             "for rolling bearings (Harris, Rolling Bearing Analysis, Table 'f1'); diagnose searches "
                             "z up to 0.02")
        friction(f"{p}.mu_d", b.mu_d)
        friction(f"{p}.eta", b.eta)
        friction(f"{p}.worn_drag_friction", b.worn_drag_friction)
        lighter = min(b.inner_race_mass, b.outer_race_mass)
        stiff(f"{p}.k_b1", b.k_b1, lighter, "lighter race")
        # the ball set's tangent stiffness k_b1 + 2 k_b2 r at a deflection of one clearance
        stiff(f"{p}.k_b2", b.k_b1 + 2.0 * b.k_b2 * b.clearance, lighter, "lighter race (k_b1 + 2 k_b2 clearance)")
        stiff(f"{p}.k_rib", b.k_rib, b.outer_race_mass, "outer race")
        damp(f"{p}.c_b", b.c_b, lighter, "lighter race")
        damp(f"{p}.c_rib", b.c_rib, b.outer_race_mass, "outer race")
        damp(f"{p}.inner_race_damping", b.inner_race_damping, b.inner_race_mass, "inner race")
        damp(f"{p}.outer_race_damping", b.outer_race_damping, b.outer_race_mass, "outer race")

    c = sc.contact
    friction("contact.mu_rad", c.mu_rad)
    friction("contact.mu_ax", c.mu_ax)
    # the contact's tangent stiffness when it carries the whole rotor's weight, on the lightest
    # inner race: F = k d^e  ->  dF/dd = e k^(1/e) F^((e-1)/e)
    weight = sc.rotor.mass * GRAVITY
    k_t = c.exponent * c.k_hertz ** (1.0 / c.exponent) * weight ** ((c.exponent - 1.0) / c.exponent)
    m_race = min(b.inner_race_mass for b in sc.bearings.values())
    if k_t * h * h / m_race > MAX_STEP_RATIO:
        raise InputError("contact.k_hertz", c.k_hertz, f"too stiff for {h_text}: carrying the rotor's "
                         f"weight its tangent stiffness {k_t:.3g} N/m on the inner race ({m_race:.3g} kg) gives "
                         f"k h^2/m > {MAX_STEP_RATIO:g} (inertia below the Newton tolerance)"
                         + or_smaller(math.sqrt(MAX_STEP_RATIO * m_race / k_t)))
    # Hunt-Crossley damping coefficient k_visc d^e = k_visc F / k_hertz at the same load
    damp("contact.k_visc", c.k_visc * weight / c.k_hertz, m_race, "inner race (k_visc x weight / k_hertz)")
    for key in ("v_reg", "v_reg_axial"):
        if getattr(c, key) > MAX_V_REG:
            raise InputError(f"contact.{key}", getattr(c, key), f"must be <= {MAX_V_REG:g} m/s: a wider regularisation "
                             "turns Coulomb friction into viscous damping at a landing's slip speeds (face slip "
                             "~0.06 m/s, sleeve slip 1-30 m/s)")
    m_rotor = sc.rotor.mass
    stiff("amb.stiffness", sc.amb.stiffness, m_rotor, "rotor")
    stiff("amb.axial_stiffness", sc.amb.axial_stiffness, m_rotor, "rotor")
    damp("amb.damping", sc.amb.damping, m_rotor, "rotor")
    damp("amb.axial_damping", sc.amb.axial_damping, m_rotor, "rotor")
    m_outer = min(b.outer_race_mass for b in sc.bearings.values())
    for key in ("k_cb", "k_ws", "k_h"):
        stiff(f"axial.{key}", getattr(sc.axial, key), m_outer, "outer race (axial chain)")
    damp("axial.c_ax", sc.axial.c_ax, m_outer, "outer race (axial chain)")

    r_min = min(b.sleeve_radius for b in sc.bearings.values())
    for key in ("cl_ax", "delta_m"):
        if getattr(sc.axial, key) > MAX_CLEARANCE_RATIO * r_min:
            raise InputError(f"axial.{key}", getattr(sc.axial, key), f"must be <= {MAX_CLEARANCE_RATIO:g} x the "
                             f"smallest sleeve_radius ({MAX_CLEARANCE_RATIO * r_min:.3g} m): axial catcher clearances "
                             "and support travel are of the order of the radial clearance")
    c_max = max(b.static_load_rating for b in sc.bearings.values())
    if abs(sc.axial.f_thrust) > 10.0 * c_max:
        raise InputError("axial.f_thrust", sc.axial.f_thrust, f"|thrust| must be <= {10 * c_max:.3g} N (10 x the "
                         "largest static_load_rating: beyond it the catcher bearing is crushed, ISO 76)")
    for key in ("t_thrust", "ramp_s"):
        if getattr(sc.axial, key) > MAX_T_END:
            raise InputError(f"axial.{key}", getattr(sc.axial, key), f"must be <= {MAX_T_END:g} s (as operating.t_end)")
    # spin damping terms on the rotor's polar inertia: drive gain and windage c_w1 + 2 c_w2 Omega
    ip = sc.rotor.polar_inertia
    omega = sc.speed_rpm * math.pi / 30.0
    damp("spin.drive_gain", sc.spin.drive_gain, ip, "rotor's spin (polar inertia, kg m^2)")
    damp("spin.c_w1", sc.spin.c_w1, ip, "rotor's spin (polar inertia, kg m^2)")
    damp("spin.c_w2", 2.0 * sc.spin.c_w2 * omega, ip, "rotor's spin (2 c_w2 Omega on the polar inertia, kg m^2)")
    if sc.unbalance is not None and sc.unbalance.magnitude > sc.rotor.mass * max(
            s_.max_outer_diameter for s_ in sc.rotor.sections) / 2.0:
        raise InputError("unbalance.magnitude", sc.unbalance.magnitude, "must be <= rotor mass x its largest radius "
                         "(all of the rotor at its rim)")
    if sc.solver.output_period > sc.t_end:
        raise InputError("solver.output_period", sc.solver.output_period, f"must be <= operating.t_end ({sc.t_end:g} s)")
    if sc.t_end > MAX_T_END:
        raise InputError("operating.t_end", sc.t_end, f"must be <= {MAX_T_END:g} s (one day of simulated time; a "
                         "landing lasts seconds, a coast-down minutes to hours)")


def load_scenario(path, overrides: list[str] | None = None, overlays=()) -> Scenario:
    """Read a scenario file, merge ``overlays`` (files, e.g. another rig rotor) on top, apply
    ``--set key=value`` overrides, validate."""
    path = Path(path)
    try:
        data = load_toml(path)
        for extra in overlays:
            data = deep_merge(data, load_toml(Path(extra)))
    except InputError as err:
        raise err.with_file(str(path)) from None
    apply_overrides(data, overrides)
    return scenario_from_dict(data, source=str(path))


def apply_overrides(data: dict, overrides, *, tables: dict | None = None) -> dict:
    """The one ``--set key=value`` parser (scenario files, a stored results.h5's scenario, coast-down
    files): each item is set in the raw input ``data`` (in place; returned). A key must exist in
    the input, except an effect switch (a known switch with its default) and a field of an
    optional table named in ``tables`` (table -> its allowed fields, e.g. ``coastdown``), which
    are created; the schema validation afterwards judges the value."""
    tables = {"limits": LIMIT_FIELDS, **(tables or {})}  # an optional table: --set limits.x=... creates it
    for item in overrides or []:
        key, text = split_override(item)
        head, _, rest = key.partition(".")
        if tables and head in tables:
            if rest.partition(".")[0] not in tables[head]:  # limits.close_clearances_m.DE_AMB: a table field
                raise InputError(f"--set {key}", text.strip(), f"unknown field; allowed: {', '.join(tables[head])}")
            sub, dot, _ = rest.partition(".")
            table = data.setdefault(head, {})
            if dot and isinstance(table, dict):  # a field that is itself a table
                table.setdefault(sub, {})
        try:
            set_dotted(data, key, parse_value(text), must_exist=not (head == "effects" and rest in EFFECTS),
                       create_leaf=True)
        except InputError as err:
            raise InputError(f"--set {key}", text, err.allowed) from None
    return data

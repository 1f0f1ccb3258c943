"""Rotor description: the ``[rotor]`` table of a rotor or scenario TOML file.

Read with :func:`load_rotor` (file) or :func:`rotor_from_dict` (already-parsed table). Every field
is checked; a problem raises :class:`~rotorlanding.errors.InputError` naming the file, the dotted
field (``rotor.sections[2].outer_diameter``), the value and what is allowed. Unknown keys are
errors too, so a typo never silently falls back to a default. Field reference with units:
``docs/rotor_file.md``.

Axial positions are measured in metres along the rotor axis x from the left end of the first
shaft section (x = 0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from .config import Table as _Table
from .config import load_toml
from .errors import InputError


#: Physical plausibility limits of rotor values (docs/rotor_file.md, "Plausibility limits"): beyond
#: them no real rotor exists and a run would only produce numbers.
#: kg/m^3: osmium (22 590 kg/m^3) is the densest element
MAX_DENSITY = 22600.0
#: Pa: diamond (about 1.05e12 Pa) is the stiffest known material
MAX_YOUNGS_MODULUS = 1.2e12
#: kg: a disk heavier than 100 t; the largest rotors on magnetic bearings (turbo-compressors) weigh
#: a few tonnes, large turbine-generator rotors (not magnetically levitated) up to ~300 t per piece
MAX_DISK_MASS = 1.0e5
#: m: the largest dimension of a rotor part (length, diameter, thickness); the largest rotors built,
#: turbine-generator shafts, are ~2 m across and ~15 m long
MAX_DIMENSION = 20.0
#: N/m and N s/m: linear supports of the modal model. No bearing or foundation is stiffer than
#: ~1e10 N/m; 1e13 leaves x1000 for a pinned idealisation, beyond which the eigenproblem's range of
#: stiffnesses (the rotor's own ~1e6-1e8 N/m) approaches double precision and its modes are lost
MAX_SUPPORT_STIFFNESS = 1.0e13
MAX_SUPPORT_DAMPING = 1.0e10
# m: largest offset of an in_landing spring's rest point from the levitated axis (design reasoning: five
# catcher clearances; a motor further off its rotor's axis would not be a coupling alignment)
MAX_SUPPORT_OFFSET = 1.0e-3
#: Pa: ultimate strength of the strongest structural steels (maraging steel grade 350: ~2.4 GPa).
#: A solid disk, the least stressed rotating shape, reaches it at its centre at the rim speed
#: v = sqrt(8 sigma / ((3 + nu) rho)) (Timoshenko & Goodier, rotating disks): 880 m/s in steel
MAX_STRENGTH = 2.5e9


@dataclass(frozen=True)
class Material:
    name: str
    youngs_modulus: float  # Pa
    shear_modulus: float  # Pa
    density: float  # kg/m^3
    poisson_ratio: float  # -


@dataclass(frozen=True)
class ShaftSection:
    length: float  # m
    outer_diameter: float  # m
    inner_diameter: float  # m
    material: Material
    elements: int
    # a conical (tapered) section: the diameters at its right end, linear in x in between (None:
    # uniform, the left values); ROSS's conical shaft elements map onto it (docs/ross.md)
    outer_diameter_right: float | None = None  # m
    inner_diameter_right: float | None = None  # m
    # coaxial layers on the same length (a sleeve, an impeller hub modelled as a tube): each a
    # ShaftSection of its own material and diameters whose element matrices add to this section's
    # (ROSS's shaft elements sharing a node); their length and elements are this section's
    layers: tuple["ShaftSection", ...] = ()

    @property
    def parts(self) -> tuple["ShaftSection", ...]:
        """This section and its coaxial layers."""
        return (self,) + self.layers

    @property
    def tapered(self) -> bool:
        return self.outer_diameter_right is not None or self.inner_diameter_right is not None

    def diameters(self, xi: float) -> tuple[float, float]:
        """(outer, inner) diameter [m] at xi = (x - x_left) / length, linear along the section."""
        if not self.tapered:
            return self.outer_diameter, self.inner_diameter
        do_r = self.outer_diameter if self.outer_diameter_right is None else self.outer_diameter_right
        di_r = self.inner_diameter if self.inner_diameter_right is None else self.inner_diameter_right
        return (self.outer_diameter + (do_r - self.outer_diameter) * xi,
                self.inner_diameter + (di_r - self.inner_diameter) * xi)

    @property
    def max_outer_diameter(self) -> float:
        """m: the largest outer diameter of the section and its layers."""
        return max(max(p.diameters(0.0)[0], p.diameters(1.0)[0]) for p in self.parts)

    @property
    def area(self) -> float:
        """m^2; of a tapered section, its mean over the length (volume / length)."""
        if self.tapered:
            return math.pi / 4.0 * (_mean_power(self, 0, 2) - _mean_power(self, 1, 2))
        return math.pi / 4.0 * (self.outer_diameter**2 - self.inner_diameter**2)

    @property
    def second_moment(self) -> float:
        """m^4; of a tapered section, its mean over the length (so polar inertia = rho 2 I L)."""
        if self.tapered:
            return math.pi / 64.0 * (_mean_power(self, 0, 4) - _mean_power(self, 1, 4))
        return math.pi / 64.0 * (self.outer_diameter**4 - self.inner_diameter**4)


def _mean_power(sec: ShaftSection, which: int, p: int) -> float:
    """Mean over a tapered section of (its outer, which=0, or inner, which=1, diameter)^p for a
    diameter linear in x: (a^p + a^(p-1) b + ... + b^p) / (p + 1)."""
    a, b = sec.diameters(0.0)[which], sec.diameters(1.0)[which]
    return sum(a ** (p - k) * b ** k for k in range(p + 1)) / (p + 1)


@dataclass(frozen=True)
class Disk:
    name: str
    position: float  # m
    mass: float  # kg
    polar_inertia: float  # kg m^2, about the spin axis
    transverse_inertia: float  # kg m^2, about a diameter through the disk centre


@dataclass(frozen=True)
class Support:
    """Linear support at a station. Modal analysis uses every support; the landing model only
    those with ``in_landing`` (a part of the machine that is there during the landing too, e.g.
    the motor coupling; the others stand in for the landed catcher bearings, which the landing
    models itself)."""

    station: str
    kyy: float = 0.0  # N/m
    kzz: float = 0.0
    kyz: float = 0.0  # cross-coupled: force in y per displacement in z
    kzy: float = 0.0
    cyy: float = 0.0  # N s/m
    czz: float = 0.0
    cyz: float = 0.0
    czy: float = 0.0
    in_landing: bool = False  # also a spring-damper to ground in the landing model, relaxed on the levitated axis
    #                          (or at offset_y / offset_z below)
    # m: where an in_landing spring is relaxed, from the levitated axis: a motor whose axis is off the
    # levitated one (e.g. aligned with the rotor resting on its catcher bearings, z = -clearance)
    offset_y: float = 0.0
    offset_z: float = 0.0


@dataclass(frozen=True)
class ReductionSpec:
    boundary_stations: tuple[str, ...]
    boundary_rotations: bool = False
    modes: int = 8


@dataclass(frozen=True)
class Rotor:
    name: str
    sections: tuple[ShaftSection, ...]
    disks: tuple[Disk, ...]
    stations: dict[str, float]
    supports: tuple[Support, ...] = ()
    reduction: ReductionSpec | None = None
    mass_proportional_damping: float = 0.0  # 1/s (Rayleigh alpha)
    stiffness_proportional_damping: float = 0.0  # s (Rayleigh beta)
    max_speed_rpm: float = 10000.0
    source: str | None = field(default=None, compare=False)
    # Rayleigh damping on the shaft elements only, without the disks' mass (ROSS's convention:
    # its element alpha/beta; docs/ross.md); False: alpha M + beta K of the whole free rotor
    damping_shaft_only: bool = False

    @property
    def length(self) -> float:
        return sum(s.length for s in self.sections)

    @property
    def polar_inertia(self) -> float:
        """kg m^2 about the spin axis: shaft sections and disks."""
        return sum(s.material.density * s.length * (2.0 * s.second_moment if s.tapered else
                                                    math.pi / 32.0 * (s.outer_diameter ** 4 - s.inner_diameter ** 4))
                   for sec in self.sections for s in sec.parts) + sum(d.polar_inertia for d in self.disks)

    @property
    def mass(self) -> float:
        """kg: shaft sections and disks."""
        return sum(s.area * s.length * s.material.density for sec in self.sections for s in sec.parts) + \
            sum(d.mass for d in self.disks)

    def burst_speed_rpm(self) -> tuple[float, str]:
        """(speed [rpm], part) at which the first part would burst even if made of the strongest
        steel: the rim speed of a section (outer radius) or disk (radius of gyration sqrt(Ip/m),
        a lower bound of its rim radius) reaches sqrt(8 sigma_u / ((3 + nu) rho)) (solid disk, the
        least stressed rotating shape). Disks carry no material: the rotor's lightest is taken."""
        def v_burst(m: Material) -> float:
            return math.sqrt(8.0 * MAX_STRENGTH / ((3.0 + m.poisson_ratio) * m.density))

        best = (math.inf, "")
        for i, sec in enumerate(self.sections):
            for s in sec.parts:
                omega = v_burst(s.material) / (s.max_outer_diameter / 2.0)
                best = min(best, (omega * 30.0 / math.pi, f"rotor.sections[{i}] (outer diameter {s.max_outer_diameter:g} m)"))
        if self.disks:
            light = min((s.material for s in self.sections), key=lambda m: m.density)
            for i, d in enumerate(self.disks):
                if d.mass > 0 and d.polar_inertia > 0:
                    k = math.sqrt(d.polar_inertia / d.mass)
                    omega = v_burst(light) / k
                    best = min(best, (omega * 30.0 / math.pi, f"rotor.disks[{i}] '{d.name}' (radius of gyration {k:.3g} m)"))
        return best


def _material(name: str, t: _Table) -> Material:
    e = t.number("youngs_modulus", positive=True)
    if e > MAX_YOUNGS_MODULUS:
        raise InputError(f"{t.path}.youngs_modulus", e, f"must be <= {MAX_YOUNGS_MODULUS:g} Pa (diamond, the stiffest "
                         "known material)")
    rho = t.number("density", positive=True)
    if rho > MAX_DENSITY:
        raise InputError(f"{t.path}.density", rho, f"must be <= {MAX_DENSITY:g} kg/m^3 (osmium, the densest element)")
    has_nu, has_g = t.has("poisson_ratio"), t.has("shear_modulus")
    if not (has_nu or has_g):
        raise InputError(f"{t.path}.poisson_ratio", None, "missing: give poisson_ratio or shear_modulus")
    if has_nu:
        nu = t.number("poisson_ratio")
        if not -1.0 < nu < 0.5:
            raise InputError(f"{t.path}.poisson_ratio", nu, "must lie in (-1, 0.5)")
    if has_g:
        g = t.number("shear_modulus", positive=True)
        if not has_nu:
            nu = e / (2.0 * g) - 1.0
            if not -1.0 < nu < 0.5:
                raise InputError(f"{t.path}.shear_modulus", g, "implies a Poisson ratio outside (-1, 0.5)")
    else:
        g = e / (2.0 * (1.0 + nu))
    t.finish()
    return Material(name, e, g, rho, nu)


def rotor_from_dict(data: dict, *, source: str | None = None) -> Rotor:
    """Build a :class:`Rotor` from the parsed top-level TOML dict (which holds ``rotor``)."""
    try:
        return _rotor_from_dict(data, source)
    except InputError as err:
        raise err.with_file(source) if source else err


def disk_from_geometry(outer_diameter: float, inner_diameter: float, thickness: float,
                       material: Material, path: str = "disk") -> tuple[float, float, float]:
    """(mass [kg], polar inertia [kg m^2], transverse inertia about a diameter through the centre
    [kg m^2]) of an annular disk: m = rho pi/4 (D^2 - d^2) t, Ip = m (D^2 + d^2)/8,
    Id = Ip/2 + m t^2/12."""
    if inner_diameter >= outer_diameter:
        raise InputError(f"{path}.inner_diameter", inner_diameter, f"must be < outer_diameter ({outer_diameter})")
    m = material.density * math.pi / 4.0 * (outer_diameter ** 2 - inner_diameter ** 2) * thickness
    ip = m * (outer_diameter ** 2 + inner_diameter ** 2) / 8.0
    return m, ip, ip / 2.0 + m * thickness ** 2 / 12.0


def _dimension(t: _Table, key: str) -> float:
    x = t.number(key, positive=True)
    if x > MAX_DIMENSION:
        raise InputError(t._field(key), x, f"must be <= {MAX_DIMENSION:g} m (the largest rotors built are ~2 m across "
                         "and ~15 m long)")
    return x


def _disk_material(d, materials: dict) -> Material:
    name = d.string("material")
    if name not in materials:
        raise InputError(f"{d.path}.material", name, f"unknown material; defined: {', '.join(materials)}")
    return materials[name]


def _rotor_from_dict(data: dict, source: str | None) -> Rotor:
    if "rotor" not in data:
        raise InputError("rotor", None, "missing required table [rotor]")
    r = _Table(data["rotor"], "rotor")
    name = r.string("name", "rotor")

    mats_t = r.table("materials")
    materials = {}
    for key in mats_t.data:
        materials[key] = _material(key, mats_t.table(key))
    if not materials:
        raise InputError("rotor.materials", {}, "define at least one material")

    def cross_section(s: _Table) -> tuple:
        """(outer, inner, material, outer at the right end, inner at the right end) of a section or layer."""
        d_out = _dimension(s, "outer_diameter")
        d_in = s.number("inner_diameter", 0.0, nonnegative=True)
        if d_in >= d_out:
            raise InputError(f"{s.path}.inner_diameter", d_in, f"must be < outer_diameter ({d_out})")
        d_out_r = _dimension(s, "outer_diameter_right") if s.has("outer_diameter_right") else None
        d_in_r = s.number("inner_diameter_right", nonnegative=True) if s.has("inner_diameter_right") else None
        if d_out_r is not None or d_in_r is not None:
            right_out = d_out if d_out_r is None else d_out_r
            right_in = d_in if d_in_r is None else d_in_r
            if right_in >= right_out:
                raise InputError(f"{s.path}.inner_diameter_right", right_in,
                                 f"must be < the outer diameter at the right end ({right_out})")
        mat_name = s.string("material")
        if mat_name not in materials:
            raise InputError(f"{s.path}.material", mat_name, f"unknown material; defined: {', '.join(materials)}")
        return d_out, d_in, materials[mat_name], d_out_r, d_in_r

    sections = []
    for s in r.array_of_tables("sections"):
        length = _dimension(s, "length")
        d_out, d_in, mat, d_out_r, d_in_r = cross_section(s)
        n_el = s.integer("elements", 1)
        layers = []
        for lay in s.array_of_tables("layers", []):
            lo, li, lm, lo_r, li_r = cross_section(lay)
            lay.finish()
            layers.append(ShaftSection(length, lo, li, lm, n_el, lo_r, li_r))
        s.finish()
        sections.append(ShaftSection(length, d_out, d_in, mat, n_el, d_out_r, d_in_r, tuple(layers)))
    if not sections:
        raise InputError("rotor.sections", [], "define at least one shaft section")
    total = sum(s.length for s in sections)

    def position(t: _Table, key: str) -> float:
        x = t.number(key)
        if not -1e-12 <= x <= total + 1e-12:
            raise InputError(t._field(key), x, f"must lie on the rotor, 0 <= x <= {total:g} m")
        return min(max(x, 0.0), total)

    stations_t = r.table("stations", {})
    stations = {key: position(stations_t, key) for key in stations_t.data}

    disks = []
    for d in r.array_of_tables("disks", []):
        disk_name = d.string("name", f"disk{len(disks) + 1}")
        x = position(d, "position")
        if d.has("outer_diameter") or d.has("thickness"):
            # a solid-of-revolution disk given by its geometry (a plain steel disk, a thrust or
            # actuator disk): mass and inertias follow from the annulus
            for key in ("mass", "polar_inertia", "transverse_inertia"):
                if d.has(key):
                    raise InputError(f"{d.path}.{key}", d.raw(key),
                                     "give either mass and inertias or outer_diameter/thickness/material, not both")
            mass, ip, it = disk_from_geometry(_dimension(d, "outer_diameter"),
                                              d.number("inner_diameter", 0.0, nonnegative=True),
                                              _dimension(d, "thickness"),
                                              _disk_material(d, materials), d.path)
        else:
            mass = d.number("mass", nonnegative=True)
            ip = d.number("polar_inertia", nonnegative=True)
            it = d.number("transverse_inertia", nonnegative=True)
        d.finish()
        if mass > 0 and math.sqrt(ip / mass) > MAX_DIMENSION / 2.0:
            raise InputError(f"{d.path}.polar_inertia", ip, f"radius of gyration sqrt(polar_inertia/mass) = "
                             f"{math.sqrt(ip / mass):.3g} m: must be <= {MAX_DIMENSION / 2:g} m (the largest rotors built "
                             "are ~2 m across)")
        # a body of revolution: It = Ip/2 + integral of x^2 dm, with every axial distance x from
        # the disk's centre within the rotor's length
        if it > ip / 2.0 + mass * total ** 2:
            raise InputError(f"{d.path}.transverse_inertia", it, f"must be <= polar_inertia/2 + mass x (rotor length)^2 "
                             f"= {ip / 2.0 + mass * total ** 2:.4g} kg m^2 (a disk cannot extend beyond the rotor)")
        if mass > MAX_DISK_MASS:
            raise InputError(f"{d.path}.mass", mass, f"must be <= {MAX_DISK_MASS:g} kg (100 t: heavier than any rotor "
                             "on magnetic bearings; see docs/rotor_file.md)")
        disks.append(Disk(name=disk_name, position=x, mass=mass, polar_inertia=ip, transverse_inertia=it))

    def station_name(t: _Table, key: str) -> str:
        st = t.string(key)
        if st not in stations:
            raise InputError(t._field(key), st, f"unknown station; defined: {', '.join(stations) or 'none'}")
        return st

    supports = []
    for s in r.array_of_tables("supports", []):
        kw = {"station": station_name(s, "station")}
        for key in ("kyy", "kzz", "cyy", "czz"):
            kw[key] = s.number(key, 0.0, nonnegative=True)
        for key in ("kyz", "kzy", "cyz", "czy"):
            kw[key] = s.number(key, 0.0)
        for key, v in kw.items():
            cap = MAX_SUPPORT_STIFFNESS if key[0] == "k" else MAX_SUPPORT_DAMPING
            if key != "station" and abs(v) > cap:
                raise InputError(s._field(key), v, f"|value| must be <= {cap:g} {'N/m' if key[0] == 'k' else 'N s/m'} "
                                 "(stiffer than any bearing or foundation x1000: beyond it the modal problem loses "
                                 "the rotor's own stiffness to rounding)")
        kw["in_landing"] = s.boolean("in_landing", False)
        for key in ("offset_y", "offset_z"):
            kw[key] = s.number(key, 0.0)
            if abs(kw[key]) > MAX_SUPPORT_OFFSET:
                raise InputError(s._field(key), kw[key], f"|value| must be <= {MAX_SUPPORT_OFFSET:g} m (five catcher "
                                 "clearances: a motor axis that far off the levitated one is no coupling alignment)")
            if kw[key] and not kw["in_landing"]:
                raise InputError(s._field(key), kw[key], "must be 0 unless in_landing = true (it is where the landing's "
                                 "spring is relaxed; modal analysis is linear about the levitated axis)")
        if kw["in_landing"] and kw["kyz"] != kw["kzy"]:
            # in the landing the support joins K before the Craig-Bampton reduction, whose solves assume
            # a symmetric K, and the energy ledger books 1/2 q^T K q: an unsymmetric (circulatory)
            # stiffness would be reduced wrongly and its work left out
            raise InputError(s._field("kzy"), kw["kzy"], f"must equal kyz ({kw['kyz']:g} N/m) when in_landing = true "
                             "(a circulatory cross-coupled stiffness is allowed in modal analysis only)")
        s.finish()
        supports.append(Support(**kw))

    reduction = None
    if r.has("reduction"):
        red = r.table("reduction")
        names = red.raw("boundary_stations")
        if not isinstance(names, list) or not names:
            raise InputError(f"{red.path}.boundary_stations", names, "must be a non-empty list of station names")
        for i, st in enumerate(names):
            if st not in stations:
                raise InputError(f"{red.path}.boundary_stations[{i}]", st,
                                 f"unknown station; defined: {', '.join(stations) or 'none'}")
        if len(set(names)) != len(names):
            raise InputError(f"{red.path}.boundary_stations", names, "station names must be unique")
        reduction = ReductionSpec(tuple(names), red.boolean("boundary_rotations", False),
                                  red.integer("modes", 8, minimum=0))
        red.finish()

    damping = r.table("damping", {})
    alpha = damping.number("mass_proportional", 0.0, nonnegative=True)
    beta = damping.number("stiffness_proportional", 0.0, nonnegative=True)
    shaft_only = damping.boolean("shaft_only", False)
    damping.finish()
    max_speed = r.number("max_speed_rpm", 10000.0, positive=True)
    r.finish()
    rotor = Rotor(name, tuple(sections), tuple(disks), stations, tuple(supports), reduction,
                  alpha, beta, max_speed, source, damping_shaft_only=shaft_only)
    burst, part = rotor.burst_speed_rpm()
    if max_speed > burst:
        raise InputError("rotor.max_speed_rpm", max_speed, f"must be <= {burst:.4g} rpm: above it {part} bursts even if "
                         "made of the strongest steel (docs/scenario_file.md, plausibility limits)")
    return rotor


def read_rotor_table(path, **ross) -> dict:
    """The ``[rotor]`` table of a rotor file, of a scenario file that contains one (``include``
    resolved), or of a rotor file written by ROSS's ``Rotor.save`` (converted by
    :func:`rotorlanding.from_ross.rotor_table` with the options ``ross``). Not validated yet."""
    path = Path(path)
    try:
        data = load_toml(path)
    except InputError as err:
        raise err.with_file(str(path)) from None
    if "rotor" not in data:
        from .from_ross import is_ross_layout, rotor_table

        if is_ross_layout(data):
            return rotor_table(data, source=str(path), **ross)
        raise InputError("rotor", None, "missing required table [rotor] (nor is it a rotor saved by ROSS)",
                         file=str(path))
    return data["rotor"]


def load_rotor(path, bearings_at_rpm: float | None = None) -> Rotor:
    """Read and validate the rotor of a rotor, scenario or ROSS file (:func:`read_rotor_table`);
    ``bearings_at_rpm`` [rpm]: a ROSS file's frequency-dependent bearing coefficients at that speed."""
    ross = {} if bearings_at_rpm is None else {"bearings_at_rpm": bearings_at_rpm}
    return rotor_from_dict({"rotor": read_rotor_table(path, **ross)}, source=str(path))

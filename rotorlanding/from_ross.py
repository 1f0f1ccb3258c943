"""Rotors from ROSS (``ross-rotordynamics``): a file written by ``ross.Rotor.save`` read without
ROSS, or a live ``ross.Rotor`` converted when ROSS is installed (``pip install '.[ross]'``).

The result is the ``[rotor]`` table of a rotorlanding rotor file (``docs/rotor_file.md``), so
everything downstream (validation, ``modes``, landings) is the one rotor path. What maps where
(``docs/ross.md``):

- ``ShaftElement`` -> one ``[[rotor.sections]]`` entry (``elements = 1``) in node order; a
  conical element (``idl != idr`` or ``odl != odr``) keeps its end diameters
  (``outer_diameter_right``, ``inner_diameter_right``), which our Timoshenko element integrates
  exactly with phi from the mid-length section, as ROSS's conical element (Genta & Gugliotta 1988);
  the material's ``E``, ``G_s`` and ``rho`` become ``youngs_modulus``, ``shear_modulus`` and
  ``density`` (Poisson's ratio E / (2 G_s) - 1, as ROSS's ``Material``);
- shaft elements sharing a node (coaxial layers) -> the innermost a section, the others its
  ``layers`` (their matrices add on the same nodes, as in ROSS);
- ``DiskElement`` -> ``[[rotor.disks]]`` at its node (``m``, ``Ip``, ``Id``); a ``PointMass`` with
  ``mx == my`` on a shaft node -> a disk with no inertia;
- ``BearingElement`` (and the ball / roller bearing elements, saved with their coefficients) with
  constant coefficients -> a station named by its tag and a ``[[rotor.supports]]`` entry for
  ``modes``: ROSS x (horizontal), y (vertical), z (axial) are our y, z, x, so ``kxx, kyy, kxy, kyx``
  -> ``kyy, kzz, kyz, kzy`` (damping alike); the axial ``kzz``/``czz`` act on no lateral DOF;
- the element Rayleigh factors ``alpha``, ``beta`` (equal on every shaft element) -> ``[rotor.damping]``
  with ``shaft_only = true`` (on the shaft elements, not the disks, as ROSS);
- the catcher-bearing stations, chosen by the user (positions [m] or ROSS node numbers), become
  stations and the Craig-Bampton boundary of ``[rotor.reduction]``.

Anything else stops the conversion with one line naming the file, the element, its class and why
(seals, frequency-dependent bearings unless ``bearings_at_rpm`` is given, linked bearings, bearing
mass coefficients, elements without shear / rotary inertia / gyroscopics, axial force or torque, other shear
coefficients, couplings, gears, ...). ``ignore=`` drops elements by tag or class on purpose.

ROSS layouts: 2.x writes ``ross_version``, ``[parameters]`` and one table per element named
``<Class>_<tag>``, shaft materials inline; 1.x writes the same tables without ``ross_version``
(``toml`` package), bearing coefficients possibly as scalars, and 6-DoF classes
``ShaftElement6DoF`` / ``DiskElement6DoF`` / ``BearingElement6DoF``, read alike.
"""

from __future__ import annotations

import json
import math
import re
import tempfile
from pathlib import Path

from .errors import InputError

#: classes that map onto a rotorlanding rotor; the 1.x 6-DoF variants read alike
SHAFT_CLASSES = ("ShaftElement", "ShaftElement6DoF")
DISK_CLASSES = ("DiskElement", "DiskElement6DoF")
BEARING_CLASSES = ("BearingElement", "BearingElement6DoF", "BallBearingElement", "RollerBearingElement")
POINT_MASS_CLASSES = ("PointMass",)

#: why the other known ROSS classes cannot be converted (one clause each)
UNSUPPORTED = {
    "SealElement": "a seal (annular seal coefficients) is not a support of the rotor in a landing model; drop it "
                   "with ignore=['SealElement'] to convert the rest knowingly",
    "BearingFluidFlow": "a fluid-film bearing (frequency-dependent coefficients computed by ROSS)",
    "CylindricalBearing": "a fluid-film bearing (load- and speed-dependent coefficients)",
    "PlainJournal": "a fluid-film bearing (load- and speed-dependent coefficients)",
    "TiltingPad": "a fluid-film bearing (load- and speed-dependent coefficients)",
    "THDCylindrical": "a fluid-film bearing (load- and speed-dependent coefficients)",
    "SqueezeFilmDamper": "a squeeze-film damper (amplitude-dependent coefficients)",
    "MagneticBearingElement": "an active magnetic bearing saved by its electromagnet and controller "
                              "parameters only (ROSS 2.3 saves one as a BearingElement with its coefficients "
                              "over frequency, which converts with bearings_at_rpm)",
    "CouplingElement": "a coupling (its lumped masses and stiffnesses join two shaft lines)",
    "GearElement": "a gear (couples shaft lines and torsion)",
    "Probe": "a probe (not an element)",
}

_KEY = re.compile(r"^([A-Za-z][A-Za-z0-9]*)_(.*)$", re.S)


def is_ross_layout(data: dict) -> bool:
    """True when a parsed TOML/JSON dict is a rotor written by ``ross.Rotor.save`` (1.x or 2.x):
    a ``parameters`` table or a ``ross_version`` and at least one ``ShaftElement*_<tag>`` table,
    and no ``[rotor]`` table."""
    if not isinstance(data, dict) or "rotor" in data:
        return False
    if "parameters" not in data and "ross_version" not in data:
        return False
    return any(isinstance(v, dict) and _class_of(k) in SHAFT_CLASSES for k, v in data.items())


def _class_of(key: str) -> str | None:
    m = _KEY.match(key)
    return m.group(1) if m else None


def _fail(file, key, value, allowed):
    raise InputError(key, value, allowed, file=file)


def _scalar(file, key, el: dict, name: str, default=0.0, at: float | None = None):
    """A bearing coefficient: a number, or a list (per frequency) whose values are all equal, or,
    given ``at`` [rad/s], a frequency-dependent list evaluated there as ROSS evaluates it."""
    v = el.get(name, default)
    if isinstance(v, (list, tuple)):
        if not all(isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) for x in v):
            _fail(file, f"{key}.{name}", v, "must be finite numbers")
        vals = [float(x) for x in v]
        if not vals:
            return float(default)
        if any(x != vals[0] for x in vals):
            freq = el.get("frequency")
            if not (isinstance(freq, list) and len(freq) == len(vals)
                    and all(isinstance(f, (int, float)) and not isinstance(f, bool) for f in freq)):
                _fail(file, f"{key}.frequency", freq, f"must be a list of {len(vals)} numbers [rad/s], one per "
                      f"value of {name}")
            if at is None:
                _fail(file, f"{key}.{name}", _short(vals), f"frequency-dependent coefficients ({len(vals)} values at "
                      f"{min(freq):g}-{max(freq):g} rad/s): rotorlanding's supports are constant; give one value per "
                      "coefficient in ROSS, or convert in Python with rl.Rotor.from_ross(..., bearings_at_rpm=SPEED) "
                      "(the coefficients at that speed, as ROSS's run_modal takes them)")
            return _ross_interpolation([float(f) for f in freq], vals, at)
        return vals[0]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        _fail(file, f"{key}.{name}", v, "must be a finite number")
    return float(v)


def _ross_interpolation(freq: list, vals: list, at: float) -> float:
    """A frequency-dependent bearing coefficient at ``at`` [rad/s], interpolated as ROSS 2.x's
    ``BearingElement`` does (``_process_coefficient``): scipy's smoothing spline
    ``UnivariateSpline(frequency, values)`` (cubic, default smoothing), or, where that cannot be
    built (2 or 3 points), ``interp1d`` of degree points - 1, extrapolating."""
    import warnings

    from scipy import interpolate

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return float(interpolate.UnivariateSpline(freq, vals)(at))
    except Exception:  # scipy raises its internal dfitpack error for too few points, as ROSS notes
        return float(interpolate.interp1d(freq, vals, kind=len(freq) - 1, fill_value="extrapolate")(at))


def _short(vals: list) -> str:
    """A long list as its ends, for a one-line message."""
    return repr(vals) if len(vals) <= 3 else f"[{vals[0]:.6g}, {vals[1]:.6g}, ..., {vals[-1]:.6g}]"


def _number(file, key, el: dict, name: str, default=None):
    if name not in el:
        if default is None:
            _fail(file, f"{key}.{name}", None, "missing (a ROSS element of this class always has it)")
        return default
    v = el[name]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        _fail(file, f"{key}.{name}", v, "must be a finite number")
    return float(v)


def _node(file, key, el: dict) -> int:
    n = el.get("n")
    if isinstance(n, bool) or not isinstance(n, int) or n < 0:
        _fail(file, f"{key}.n", n, "must be a node number >= 0 (ROSS writes it for every assembled element)")
    return n


def _shaft(file, key, el: dict) -> dict:
    for flag in ("shear_effects", "rotary_inertia", "gyroscopic"):
        if el.get(flag, True) is not True:
            _fail(file, f"{key}.{flag}", el.get(flag), "only true can be converted: rotorlanding's Timoshenko "
                  "element always has shear, rotary inertia and gyroscopics")
    method = el.get("shear_method_calc", "cowper")
    if method != "cowper":
        _fail(file, f"{key}.shear_method_calc", method, "only 'cowper' can be converted (rotorlanding uses "
              "Cowper's shear coefficient)")
    for load in ("axial_force", "torque"):
        if _number(file, key, el, load, 0.0) != 0.0:
            _fail(file, f"{key}.{load}", el[load], "only 0 can be converted (rotorlanding's element has no "
                  "geometric stiffness from axial force or torque)")
    mat = el.get("material")
    if isinstance(mat, str):
        _fail(file, f"{key}.material", mat, "a material by name only (ROSS's available_materials) cannot be "
              "read without ROSS: save the rotor with ROSS >= 1.0, which writes rho, E and G_s inline")
    if not isinstance(mat, dict):
        _fail(file, f"{key}.material", mat, "must be a table with rho, E and G_s")
    props = {}
    for k in ("rho", "E", "G_s"):
        if k not in mat:
            if k == "G_s" and "Poisson" in mat:
                continue
            _fail(file, f"{key}.material.{k}", None, "missing (ROSS writes rho, E and G_s)")
        props[k] = _number(file, f"{key}.material", mat, k)
    if "G_s" not in props:
        props["G_s"] = props["E"] / (2.0 * (1.0 + _number(file, f"{key}.material", mat, "Poisson")))
    idl = _number(file, key, el, "idl")
    odl = _number(file, key, el, "odl")
    return {"n": _node(file, key, el), "L": _number(file, key, el, "L"), "idl": idl, "odl": odl,
            "idr": idl if el.get("idr") is None else _number(file, key, el, "idr"),
            "odr": odl if el.get("odr") is None else _number(file, key, el, "odr"),
            "material": (str(mat.get("name", "material")), props["rho"], props["E"], props["G_s"]),
            "alpha": _number(file, key, el, "alpha", 0.0), "beta": _number(file, key, el, "beta", 0.0)}


def _station_name(tag: str, used: set) -> str:
    name = re.sub(r"[^A-Za-z0-9_-]+", "_", tag.strip()).strip("_") or "bearing"
    base, k = name, 2
    while name in used:
        name, k = f"{base}_{k}", k + 1
    used.add(name)
    return name


def rotor_table(data: dict, *, source: str | None = None, catchers: dict | None = None,
                catcher_nodes: dict | None = None, reduction_modes: int = 8, name: str | None = None,
                max_speed_rpm: float | None = None, ignore=(), bearings_at_rpm: float | None = None) -> dict:
    """The ``[rotor]`` table (dict) of a ROSS rotor given as the dict its ``Rotor.save`` file parses
    to. ``catchers``: {station name: x [m]}; ``catcher_nodes``: {station name: ROSS node number};
    they become stations and the Craig-Bampton boundary (``reduction_modes`` fixed-interface modes).
    ``ignore``: element tags or class names to leave out on purpose. ``bearings_at_rpm``: evaluate
    frequency-dependent bearing coefficients at this spin speed [rpm] (ROSS's ``run_modal`` takes
    them at the spin frequency) and keep them constant. Raises :class:`InputError` (one line: file,
    element, value, why) for what cannot be converted."""
    file = source
    at = None
    if bearings_at_rpm is not None:
        if isinstance(bearings_at_rpm, bool) or not isinstance(bearings_at_rpm, (int, float)) \
                or not math.isfinite(bearings_at_rpm) or bearings_at_rpm < 0:
            _fail(file, "bearings_at_rpm", bearings_at_rpm, "must be a spin speed >= 0 rpm")
        at = bearings_at_rpm * math.pi / 30.0
    if not is_ross_layout(data):
        _fail(file, "file", sorted(data)[:4] if isinstance(data, dict) else type(data).__name__,
              "not a rotor written by ross.Rotor.save (no [parameters]/ross_version with ShaftElement_<tag> tables)")
    ignore = set(ignore or ())
    shafts, disks, bearings, problems = [], [], [], []
    for key, el in data.items():
        if key in ("parameters", "ross_version") or key.startswith("_") or not isinstance(el, dict):
            continue
        cls = _class_of(key)
        tag = str(el.get("tag", key[len(cls) + 1:] if cls else key))
        if cls in ignore or tag in ignore:
            continue
        if cls in SHAFT_CLASSES:
            shafts.append((key, _shaft(file, key, el)))
        elif cls in DISK_CLASSES:
            disks.append((key, tag, _node(file, key, el), _number(file, key, el, "m"),
                          _number(file, key, el, "Ip"), _number(file, key, el, "Id")))
        elif cls in POINT_MASS_CLASSES:
            mx, my = _number(file, key, el, "mx", 0.0), _number(file, key, el, "my", 0.0)
            if "m" in el:
                mx = my = _number(file, key, el, "m")
            if mx != my:
                problems.append((key, cls, f"a point mass with mx != my ({mx} != {my} kg): rotorlanding's disks are "
                                 "axisymmetric"))
                continue
            disks.append((key, tag, _node(file, key, el), mx, 0.0, 0.0))
        elif cls in BEARING_CLASSES:
            if el.get("n_link") is not None:
                problems.append((key, cls, f"a bearing linked to node {el['n_link']} (a support structure): "
                                 "rotorlanding's supports connect the rotor to the ground"))
                continue
            try:
                for m in ("mxx", "myy", "mxy", "myx"):
                    if _scalar(file, key, el, m, at=at) != 0.0:
                        raise InputError(f"{key}.{m}", el[m], "bearing mass coefficients: rotorlanding's supports "
                                         "are stiffness and damping")
                coef = {ours: _scalar(file, key, el, theirs, at=at) for ours, theirs in (
                    ("kyy", "kxx"), ("kzz", "kyy"), ("kyz", "kxy"), ("kzy", "kyx"),
                    ("cyy", "cxx"), ("czz", "cyy"), ("cyz", "cxy"), ("czy", "cyx"))}
            except InputError as err:
                problems.append((err.field, err.value, err.allowed))
                continue
            bearings.append((key, tag, _node(file, key, el), coef))
        else:
            why = UNSUPPORTED.get(cls, f"an element of class {cls!r} that rotorlanding does not know")
            problems.append((key, cls, why))
    if problems:
        key, value, why = problems[0]
        others = [p[0] for p in problems[1:]]
        more = f" (and {len(others)} more: {', '.join(others[:3])}{', ...' if len(others) > 3 else ''})" if others else ""
        _fail(file, key, value, f"cannot be converted: {why}{more}; rotorlanding converts shaft elements, disks, "
              "point masses and bearings with constant coefficients (ignore=[tag or class] leaves elements out)")
    if not shafts:
        _fail(file, "ShaftElement", None, "no shaft element left to convert")

    # node positions from the element lengths, in node order; elements sharing a node are coaxial
    # layers (ROSS adds their matrices): the innermost is the section, the others its layers
    by_node: dict[int, list] = {}
    for key, s in shafts:
        by_node.setdefault(s["n"], []).append((key, s))
    groups = []
    for n in sorted(by_node):
        group = sorted(by_node[n], key=lambda ks: (ks[1]["idl"], ks[1]["odl"]))
        for key, s in group[1:]:
            if abs(s["L"] - group[0][1]["L"]) > 1e-12 * group[0][1]["L"]:
                _fail(file, f"{key}.L", s["L"], f"a coaxial layer (same node n = {n} as {group[0][0]}) must have "
                      f"its length, {group[0][1]['L']} m")
        groups.append(group)
    for g0, g1 in zip(groups, groups[1:]):
        if g1[0][1]["n"] != g0[0][1]["n"] + 1:
            _fail(file, g1[0][0], f"n = {g1[0][1]['n']}", f"leaves a gap after {g0[0][0]} (n = {g0[0][1]['n']}): "
                  "the shaft must be continuous")
    n0 = groups[0][0][1]["n"]
    x = [0.0]
    for group in groups:
        x.append(x[-1] + group[0][1]["L"])

    def position(key, n, what="n"):
        if not n0 <= n <= n0 + len(shafts):
            _fail(file, f"{key}.{what}", n, f"must be a shaft node, {n0}..{n0 + len(shafts)}")
        return x[n - n0]

    damping = {(s["alpha"], s["beta"]) for _, s in shafts}
    if len(damping) > 1:
        _fail(file, "ShaftElement.alpha/beta", sorted(damping)[:3], "must be equal on every shaft element: "
              "rotorlanding has one Rayleigh damping per rotor")
    alpha, beta = damping.pop()

    materials, mat_names = {}, {}

    def cross_section(s: dict) -> dict:
        mname, rho, e, g = s["material"]
        ident = (rho, e, g)
        if ident not in mat_names:
            nm = re.sub(r"[^A-Za-z0-9_-]+", "_", mname).strip("_") or "material"
            base, k = nm, 2
            while nm in materials:
                nm, k = f"{base}_{k}", k + 1
            mat_names[ident] = nm
            materials[nm] = {"youngs_modulus": e, "shear_modulus": g, "density": rho}
        out = {"outer_diameter": s["odl"], "inner_diameter": s["idl"], "material": mat_names[ident]}
        if s["odr"] != s["odl"]:
            out["outer_diameter_right"] = s["odr"]
        if s["idr"] != s["idl"]:
            out["inner_diameter_right"] = s["idr"]
        return out

    sections = []
    for group in groups:
        sec = {"length": group[0][1]["L"], **cross_section(group[0][1]), "elements": 1}
        if len(group) > 1:
            sec["layers"] = [cross_section(s) for _, s in group[1:]]
        sections.append(sec)

    used: set = set()
    stations, supports = {}, []
    for key, tag, n, coef in bearings:
        st = _station_name(tag, used)
        stations[st] = position(key, n)
        supports.append({"station": st, **coef})
    out_disks = []
    for key, tag, n, m, ip, it in disks:
        out_disks.append({"name": tag, "position": position(key, n), "mass": m, "polar_inertia": ip,
                          "transverse_inertia": it})
    boundary = []
    for label, given, is_node in (("catchers", catchers, False), ("catcher_nodes", catcher_nodes, True)):
        for st, where in (given or {}).items():
            if not isinstance(st, str) or not st:
                _fail(file, label, st, "station names must be non-empty strings")
            if st in stations:
                _fail(file, f"{label}.{st}", where, f"station name already used by a ROSS bearing; "
                      f"taken: {', '.join(stations)}")
            if is_node:
                if isinstance(where, bool) or not isinstance(where, int):
                    _fail(file, f"{label}.{st}", where, "must be a ROSS node number (int)")
                pos = position(f"{label}.{st}", where, "node")
            else:
                if isinstance(where, bool) or not isinstance(where, (int, float)) or not 0.0 <= where <= x[-1]:
                    _fail(file, f"{label}.{st}", where, f"must be a position on the rotor, 0 <= x <= {x[-1]:g} m")
                pos = float(where)
            used.add(st)
            stations[st] = pos
            boundary.append(st)

    params = data.get("parameters") or {}
    if max_speed_rpm is None:
        w = params.get("max_w") if isinstance(params, dict) else None  # 1.x: rad/s
        max_speed_rpm = float(w) * 30.0 / math.pi if isinstance(w, (int, float)) and w > 0 else 10000.0
    if name is None:
        tag = params.get("tag") if isinstance(params, dict) else None
        name = str(tag) if tag else (f"ROSS rotor {Path(file).stem}" if file else "ROSS rotor")
    table = {"name": name, "max_speed_rpm": max_speed_rpm, "materials": materials, "sections": sections}
    if stations:
        table["stations"] = stations
    if out_disks:
        table["disks"] = out_disks
    if supports:
        table["supports"] = supports
    if boundary:
        table["reduction"] = {"boundary_stations": boundary, "modes": reduction_modes}
    if alpha or beta:
        table["damping"] = {"mass_proportional": alpha, "stiffness_proportional": beta, "shaft_only": True}
    return table


def has_speed_dependent_bearings(path) -> bool:
    """True when ``path`` is a ROSS rotor file with a bearing whose coefficients vary with
    frequency (the command line then takes them at each spin speed, as ROSS's ``run_modal``).
    Any file that cannot be read so answers False (the rotor reader names its problem)."""
    try:
        data = read_ross_file(path)
    except InputError:
        return False
    if not is_ross_layout(data):
        return False
    for key, el in data.items():
        if isinstance(el, dict) and _class_of(key) in BEARING_CLASSES:
            for v in el.values():
                if isinstance(v, list) and len(v) > 1 and any(x != v[0] for x in v) and v is not el.get("frequency"):
                    return True
    return False


def read_ross_file(path) -> dict:
    """The dict of a ROSS rotor file (``.toml`` or ``.json``), without ROSS."""
    path = Path(path)
    if path.suffix.lower() == ".json":
        from .readers import read_text

        text = read_text(path, kind="JSON")
        try:
            return json.loads(text)
        except json.JSONDecodeError as err:
            raise InputError("file", str(path), f"not valid JSON ({err.msg}, line {err.lineno})", file=str(path)) from None
    from .config import load_toml

    try:
        return load_toml(path)
    except InputError as err:
        raise err.with_file(str(path)) from None


def table_from_ross(source, **kw) -> tuple[dict, str | None]:
    """(``[rotor]`` table, source file) from a ROSS file path or a live ``ross.Rotor`` (saved by
    ROSS's own ``Rotor.save`` into a temporary file and read back without ROSS's loader)."""
    if isinstance(source, (str, Path)):
        return rotor_table(read_ross_file(source), source=str(source), **kw), str(source)
    if not (hasattr(source, "save") and hasattr(source, "shaft_elements")):
        raise InputError("rotor", type(source).__name__, "must be a ROSS rotor file (.toml/.json) or a ross.Rotor")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "ross_rotor.toml"
        source.save(path)
        kw.setdefault("name", getattr(source, "tag", None) or "ROSS rotor")
        return rotor_table(read_ross_file(path), source=None, **kw), None

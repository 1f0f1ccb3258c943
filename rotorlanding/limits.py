"""The ``[limits]`` table of a scenario: the designer's acceptance limits for the verdict (issue 18).

Every field is optional; the defaults and their sources (docs/designer_models.md says what was
read and what is recalled):

| field | default | meaning, source |
|---|---|---|
| ``ball_contact_pressure_pa`` | 4.2e9 | peak Hertz pressure of the most loaded ball-race contact: ISO 76 static load rating basis for ball bearings, 4200 MPa (checked: NSK handbook "Static load ratings", ISO 76:2006 excerpt) |
| ``sleeve_contact_pressure_pa`` | 4.0e9 | peak pressure of the sleeve-bore line contact: ISO 76's basis for line (roller) contacts, 4000 MPa, for a through-hardened steel sleeve (same sources; applying it to the sleeve is our choice) |
| ``temperature_degc`` | 120.0 | any node of a catcher bearing (rings, balls, sleeve): AISI 52100 data sheets give continuous operation up to 120 degC (checked: stindia / compraco 52100 sheets); common bearing greases have their upper limit there too (quoted) |
| ``drops_required`` | 1 | drops (each a landing, or a coast-down when the scenario is one) the bearing must survive: the purchaser's number (API 617/684 leave it to the purchaser; not available here) |
| ``whirl_acceptable_below_rpm`` | 0.0 | whirl (forward or backward) of the landed journal is acceptable only while the rotor turns slower than this (default: no whirl is acceptable) |
| ``contact_force_n`` | 0.0 | peak contact force on the rotor at a bearing; 0: not judged, reported only (the pressures are the criteria) |
| ``whirl_time_s`` | 0.0 | time the landed journal may whirl (whirl severity); 0: not judged, reported only |
| ``whirl_orbit_over_clearance`` | 0.0 | whirl orbit amplitude over the radial clearance (landing runs; whirl severity); 0: not judged, reported only |
| ``dynamic_load_rating_n`` | 61000.0 | C of the catcher bearing, the stress-life anchor of the damage per drop (SKF 7212 BECBP, quoted; public tables also list 51.5 kN: damage scales with C^-3) |
| ``stress_life_exponent`` | 9.0 | N ~ p^-n (ISO 281 ball exponent 3 x Hertz 3, Lundberg-Palmgren; Zaretsky finds ~12) |
| ``close_clearances_m`` | {} | radial gap [m] between the rotor and a stationary part other than the catcher bearings (an AMB stator, a sensor, a seal), per rotor station: ``{DE_AMB = 4e-4}``. The rotor's largest displacement off the bearings' axis there over the run (``summary.json`` ``rotor_deflection``) must stay below it. Empty: nothing judged. The machine's drawing gives the gaps; a catcher bearing protects only the sleeves, and a landed rotor that bends reaches the others first (docs/calibration.md, session 35) |

Temperatures are given in degC (the key says so) and used in K inside.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

from .config import Table
from .errors import InputError

KELVIN_0C = 273.15


@dataclass(frozen=True)
class Limits:
    ball_contact_pressure_pa: float = 4.2e9
    sleeve_contact_pressure_pa: float = 4.0e9
    temperature_degc: float = 120.0
    drops_required: int = 1
    whirl_acceptable_below_rpm: float = 0.0
    contact_force_n: float = 0.0
    whirl_time_s: float = 0.0
    whirl_orbit_over_clearance: float = 0.0
    dynamic_load_rating_n: float = 61000.0
    stress_life_exponent: float = 9.0
    close_clearances_m: dict = field(default_factory=dict)

    @property
    def temperature_k(self) -> float:
        return self.temperature_degc + KELVIN_0C

    def to_dict(self) -> dict:
        return asdict(self)


FIELDS = tuple(Limits.__dataclass_fields__)
SOURCES = {
    "ball_contact_pressure_pa": "ISO 76 basis for ball bearings, 4200 MPa",
    "sleeve_contact_pressure_pa": "ISO 76 basis for line (roller) contacts, 4000 MPa",
    "temperature_degc": "AISI 52100 continuous operation up to 120 degC (data sheets); grease limit of the same order",
    "drops_required": "purchaser's number",
    "whirl_acceptable_below_rpm": "designer's choice (default: no whirl)",
    "contact_force_n": "designer's choice (0: reported, not judged)",
    "whirl_time_s": "designer's choice (0: reported, not judged)",
    "whirl_orbit_over_clearance": "designer's choice (0: reported, not judged)",
    "dynamic_load_rating_n": "SKF 7212 BECBP C = 61 kN (quoted)",
    "stress_life_exponent": "ISO 281 / Lundberg-Palmgren: 3 x 3 = 9",
    "close_clearances_m": "the scenario's radial gaps of AMB stators, sensors, seals at rotor stations (the machine's "
                          "drawing; the paper rig's AMB gaps: twice its catcher clearance, a design rule, "
                          "scenarios/rig/rig.toml; none: not judged)",
}

#: m: a radial gap at least this large is no close clearance for a landing model (the small-excursion FE
#: rotor and the contact laws hold for displacements of a few tenths of a millimetre)
CLOSE_CLEARANCE_MAX_M = 0.05


def _close_clearances(t: Table) -> dict:
    """``close_clearances_m``: station -> radial gap, each 0 < gap < ``CLOSE_CLEARANCE_MAX_M`` (the
    station names are checked against the rotor where the scenario is read)."""
    raw = t.raw("close_clearances_m", {})
    if not isinstance(raw, dict):
        raise InputError(t._field("close_clearances_m"), raw,
                         "must be a table of rotor station = radial gap in m, e.g. {DE_AMB = 4.0e-4}")
    gaps = Table(raw, t._field("close_clearances_m"))
    out = {}
    for station in gaps.data:
        value = gaps.number(station, upper=CLOSE_CLEARANCE_MAX_M)
        if not value > 0 or not math.isfinite(value):
            raise InputError(gaps._field(station), value, f"must be a radial gap in m, > 0 and < {CLOSE_CLEARANCE_MAX_M}")
        out[station] = value
    return out


def limits_from_dict(data) -> Limits:
    """Validate a ``[limits]`` table (None: the defaults); a bad value is one InputError line."""
    t = Table({} if data is None else data, "limits")
    d = Limits()
    out = Limits(
        ball_contact_pressure_pa=t.number("ball_contact_pressure_pa", d.ball_contact_pressure_pa, positive=True),
        sleeve_contact_pressure_pa=t.number("sleeve_contact_pressure_pa", d.sleeve_contact_pressure_pa, positive=True),
        temperature_degc=t.number("temperature_degc", d.temperature_degc),
        drops_required=t.integer("drops_required", d.drops_required, minimum=1),
        whirl_acceptable_below_rpm=t.number("whirl_acceptable_below_rpm", d.whirl_acceptable_below_rpm,
                                            nonnegative=True),
        contact_force_n=t.number("contact_force_n", d.contact_force_n, nonnegative=True),
        whirl_time_s=t.number("whirl_time_s", d.whirl_time_s, nonnegative=True),
        whirl_orbit_over_clearance=t.number("whirl_orbit_over_clearance", d.whirl_orbit_over_clearance,
                                            nonnegative=True),
        dynamic_load_rating_n=t.number("dynamic_load_rating_n", d.dynamic_load_rating_n, positive=True),
        stress_life_exponent=t.number("stress_life_exponent", d.stress_life_exponent, positive=True),
        close_clearances_m=_close_clearances(t),
    )
    t.finish()
    if not -KELVIN_0C < out.temperature_degc < 1000.0:
        raise InputError("limits.temperature_degc", out.temperature_degc,
                         "must lie above absolute zero (-273.15 degC) and below 1000 degC")
    return out

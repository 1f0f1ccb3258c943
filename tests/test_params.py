"""Parameters resolved once (rotorlanding.params): an effect that is off reaches every consumer as
the law's "contributes nothing" value, and the kernel's parameter vector is filled from the
resolved record, every slot exactly once."""

from dataclasses import fields
from pathlib import Path

import numpy as np
import pytest

from rotorlanding import bearing_kernel as bk
from rotorlanding.landing import build_spec
from rotorlanding.params import BearingLaws, bearing_laws, rotor_laws
from rotorlanding.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[1]
FORWARD = ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml"
BACKWARD = ROOT / "scenarios" / "paper" / "backward_whirl_landing.toml"

OFF = ["effects.radial_friction=false", "effects.contact_damping=false", "effects.ribbon_cross_coupling=false",
       "effects.worn_bearing_drag=false", "effects.ball_drag=false", "effects.outer_race_coulomb=false",
       "effects.axial_rub=false", "effects.windage=false", "effects.gyroscopic=false"]


def test_effects_off_resolve_to_laws_that_contribute_nothing():
    # the NDE bearing of the backward landing is healthy (session 15): give it a worn drag here, so
    # that every bearing has a non-zero raw value for the switch to zero
    worn_nde = ["bearings.NDE.worn_drag_torque=2.0"]
    on = load_scenario(BACKWARD, worn_nde + ["effects.ribbon_cross_coupling=true", "effects.windage=true"])
    off = load_scenario(BACKWARD, worn_nde + OFF)
    for name, p in on.bearings.items():
        L_on, L_off = bearing_laws(on, p), bearing_laws(off, off.bearings[name])
        # the scenario's raw values are non-zero, so a zero below is the switch, not the input
        assert L_on.mu_rad == on.contact.mu_rad > 0 and L_on.k_visc == on.contact.k_visc > 0
        assert L_on.worn_drag_torque == p.worn_drag_torque > 0 and L_on.eta == p.eta > 0 and L_on.ball_drag
        assert (L_off.mu_rad, L_off.k_visc, L_off.eta, L_off.worn_drag_torque) == (0.0, 0.0, 0.0, 0.0)
        assert L_off.worn_drag_friction == 0.0 and L_off.worn[0] == 0.0
        assert not (L_off.ball_drag or L_off.outer_coulomb or L_off.axial_rub)
        # values no effect switches stay as written
        assert (L_off.clearance, L_off.k_rib, L_off.k_hertz) == (p.clearance, p.k_rib, on.contact.k_hertz)
    r_on, r_off = rotor_laws(on), rotor_laws(off)
    assert r_on.windage and r_on.c_w2 == on.spin.c_w2 > 0 and r_on.gyroscopic
    assert (r_off.windage, r_off.c_w1, r_off.c_w2, r_off.gyroscopic) == (False, 0.0, 0.0, False)


def test_axial_rub_and_coulomb_act_only_at_the_axial_face():
    sc = load_scenario(FORWARD, ["effects.outer_race_coulomb=true"])
    laws = {name: bearing_laws(sc, p) for name, p in sc.bearings.items()}
    faces = [n for n, p in sc.bearings.items() if p.axial_face]
    assert len(faces) == 1
    for name, L in laws.items():
        assert L.axial_rub == L.outer_coulomb == (name in faces)


@pytest.mark.parametrize("overrides", [[], OFF])
def test_kernel_vector_is_the_resolved_record(overrides):
    spec = build_spec(load_scenario(FORWARD, overrides))
    slots = list(bk._P_FIELDS) + list(range(bk.P_XS, bk.P_WREG2 + 1)) + list(range(bk.P_WMU, bk.P_WPHI + 1)) \
        + [bk.P_WI, bk.P_WO, bk.P_CLAX, bk.P_DM, bk.P_KCB, bk.P_KWS, bk.P_KHS, bk.P_CAX]
    assert sorted(slots) == list(range(bk.P_SIZE))       # every slot filled, none twice
    names = {f.name for f in fields(BearingLaws)}
    assert set(bk._P_FIELDS.values()) <= names
    for b in spec.bearings:
        P = bk.bearing_parameters(spec, b)
        for slot, name in bk._P_FIELDS.items():
            assert P[slot] == float(getattr(b.laws, name)), name
        assert np.array_equal(P[bk.P_XS:bk.P_WREG2 + 1], np.array(b.laws.hp))
        assert np.array_equal(P[bk.P_WMU:bk.P_WPHI + 1], np.array(b.laws.worn))

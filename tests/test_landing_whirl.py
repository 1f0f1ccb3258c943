"""Which bearing's whirl is the landing's whirl (whirl.landing_whirl_bearing)."""

import pytest

from rotorlanding.ensemble import ensemble_stats
from rotorlanding.whirl import landing_whirl, landing_whirl_bearing


def _w(direction, onset=None):
    return {"direction": direction, "frequency_hz": None if direction == "none" else 50.0, "onset_s": onset}


def test_the_de_whirl_is_the_landings_when_the_de_journal_whirls():
    assert landing_whirl_bearing({"DE": _w("backward", 0.3), "NDE": _w("forward", 0.0)}) == "DE"


def test_a_whirl_at_another_bearing_is_not_called_calm():
    # the 3000 rpm combined landing: the NDE journal goes round, the loaded DE journal does not
    assert landing_whirl_bearing({"DE": _w("none"), "NDE": _w("forward", 0.0)}) == "NDE"


def test_no_whirl_anywhere_reports_the_reference_bearing():
    assert landing_whirl_bearing({"DE": _w("none"), "NDE": _w("none")}) == "DE"
    assert landing_whirl_bearing({"A": _w("none"), "B": _w("none")}) == "A"   # no DE: the first bearing


def test_the_earliest_whirl_wins_when_the_reference_is_calm():
    ws = {"DE": _w("none"), "B": _w("backward", 0.4), "C": _w("forward", 0.1)}
    assert landing_whirl_bearing(ws) == "C"
    assert landing_whirl_bearing(ws, reference="B") == "B"


def test_no_bearings_is_an_error():
    with pytest.raises(ValueError, match="no bearings"):
        landing_whirl_bearing({})


def test_ensemble_counts_where_the_whirl_class_whirled():
    ms = [{"direction": "forward", "frequency_hz": 46.0, "onset_s": 0.0, "bearing": "NDE"}] * 5 + \
         [{"direction": "forward", "frequency_hz": 45.0, "onset_s": 0.1, "bearing": "DE"},
          {"direction": "none", "frequency_hz": None, "onset_s": None, "bearing": "DE"}]
    e = ensemble_stats(ms)
    assert e["direction"] == "forward" and e["bearings"] == {"NDE": 5, "DE": 1}
    assert "bearings" not in ensemble_stats([{"direction": "none", "frequency_hz": None, "onset_s": None}])


def test_a_whirling_bearing_without_onset_comes_last():
    ws = {"DE": _w("none"), "X": _w("backward", None), "NDE": _w("forward", 0.3)}
    assert landing_whirl_bearing(ws) == "NDE"


def test_old_summaries_are_re_derived_from_their_bearings():
    # written before the rule: top level = the DE's whirl, no "bearing"
    per = {"DE": _w("none"), "NDE": _w("forward", 0.0)}
    old = {**per["DE"], "per_bearing": per}
    w = landing_whirl(old)
    assert w["bearing"] == "NDE" and w["direction"] == "forward" and w["per_bearing"] is per
    new = {**per["NDE"], "bearing": "NDE", "per_bearing": per}
    assert landing_whirl(new) == new
    assert landing_whirl({"direction": "none", "frequency_hz": None, "onset_s": None})["bearing"] == "DE"


def test_member_result_without_a_de_bearing_and_with_a_stopped_rotor():
    from rotorlanding.ensemble import member_result

    per = {"A": _w("none"), "B": _w("forward", 0.1)}
    s = {"whirl": {**per["A"], "bearing": "A", "per_bearing": per},
         "bearings": {"A": {"vertical_displacement_range_m": [-1e-4, 1e-4], "vertical_force_range_n": [0.0, 1e3],
                            "final_race_speed_rpm": 50.0}},
         "speeds": {"final_rotor_rpm": 0.0}}
    m = member_result(s)
    assert m["bearing"] == "A" and m["v_disp_range_m"] == [-1e-4, 1e-4]
    assert m["race_to_rotor"] is None   # a race/rotor ratio means nothing once the rotor has stopped


def test_ensemble_counts_de_whirls_over_every_member():
    ms = [{"direction": "backward", "frequency_hz": 50.0, "onset_s": 0.1, "bearing": "DE"},
          {"direction": "forward", "frequency_hz": 46.0, "onset_s": 0.0, "bearing": "DE"},
          {"direction": "forward", "frequency_hz": 46.0, "onset_s": 0.0, "bearing": "NDE"},
          {"direction": "none", "frequency_hz": None, "onset_s": None, "bearing": "DE"}]
    e = ensemble_stats(ms)
    assert e["de_whirls"] == 2 and e["bearings"] == {"DE": 1, "NDE": 1}

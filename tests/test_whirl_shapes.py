"""Whirl shapes in the reports: the run summary names a landing whirl's shape, and validate reads a
frequency whose drops split between shapes (cylindrical and conical): the verdict holds for any
split only when every shape lies on its side of the band."""
from __future__ import annotations

import pytest

from rotorlanding.validate import _shapes, _split_robust, shape_lines


def _ens(forms):
    return {"de": {"forms": {k: {"n": n, "frequency_hz": f, **({} if se is None else {"frequency_se_hz": se})}
                             for k, (n, f, se) in forms.items()}}}


def test_two_shapes_inside_the_band_hold_for_any_split():
    """The rig's 10000 rpm drops: cylindrical 72.8 Hz x5, conical 79.4 Hz x3 against 77 +/- 7.7 Hz."""
    sh = _shapes(_ens({"cylindrical": (5, 72.8, 0.05), "conical": (3, 79.4, 0.1)}), 77.0, 7.7)
    assert [s["form"] for s in sh] == ["cylindrical", "conical"]
    assert sh[0]["margin"] == pytest.approx(7.7 - 4.2)
    assert _split_robust(sh, ok=True)
    # the same pass with one shape outside: any split with enough drops there fails
    sh = _shapes(_ens({"cylindrical": (5, 72.8, 0.05), "conical": (3, 86.0, 0.1)}), 77.0, 7.7)
    assert not _split_robust(sh, ok=True)


def test_a_fail_holds_only_beyond_one_edge():
    low_high = _shapes(_ens({"a": (4, 60.0, 0.1), "b": (4, 95.0, 0.1)}), 77.0, 7.7)
    assert not _split_robust(low_high, ok=False)  # a mix of the two can land inside the band
    both_low = _shapes(_ens({"a": (4, 60.0, 0.1), "b": (4, 65.0, 0.1)}), 77.0, 7.7)
    assert _split_robust(both_low, ok=False)


def test_one_shape_or_a_shape_without_error_keeps_the_noise_flag():
    assert not _split_robust(_shapes(_ens({"cylindrical": (8, 72.8, 0.05)}), 77.0, 7.7), ok=True)
    assert not _split_robust(_shapes(_ens({"cylindrical": (7, 72.8, 0.05), "conical": (1, 79.4, None)}), 77.0, 7.7),
                             ok=True)
    assert _shapes({"direction": "forward"}, 77.0, 7.7) == []  # a centred drop: no ensemble, no shapes


def test_the_report_says_which_shapes_and_whether_the_verdict_holds():
    sh = _shapes(_ens({"cylindrical": (5, 72.8, 0.05), "conical": (3, 79.4, 0.1)}), 77.0, 7.7)
    check = {"group": "table", "check": "Fig. 39: forward whirl frequency at the DE, 10000 rpm", "shapes": sh,
             "split_robust": True, "pass": True, "paper_experimental": 77.0, "ours": 73.0, "band": 7.7}
    text = " ".join(shape_lines([check]))
    assert "cylindrical in 5 drops at 72.8" in text and "conical in 3 drops at 79.4" in text
    assert "(-5.5%)" in text and "(+3.1%)" in text
    assert "holds for any split" in text
    assert shape_lines([{**check, "shapes": sh[:1]}]) == []  # one shape: nothing to say


def test_the_run_summary_names_the_whirl_shape():
    from rotorlanding.run import format_summary

    w = {"direction": "forward", "frequency_hz": 72.7, "onset_s": 0.07, "end_s": 1.0, "persistence": 1.0,
         "amplitude_m": 3e-4, "bearing": "DE",
         "shape": {"against": "NDE", "phase_deg": 14.2, "amplitude_ratio": 1.27, "form": "cylindrical"}}
    text = format_summary({"scenario": "x", "whirl": {**w, "per_bearing": {"DE": w}}})
    assert "shape cylindrical: the NDE journal +14 deg from it, 1.27 x its component" in text
    del w["shape"]
    assert "shape" not in format_summary({"scenario": "x", "whirl": {**w, "per_bearing": {"DE": w}}})


def test_the_sweep_table_has_the_whirl_shape():
    from rotorlanding.sweep_run import csv_fields, summary_row

    cols = csv_fields(["DE", "NDE"])
    assert cols.index("whirl_bearing") + 1 == cols.index("whirl_shape") < cols.index("DE_max_contact_force_n")
    w = {"direction": "forward", "frequency_hz": 79.3, "onset_s": 0.07, "end_s": 1.0, "persistence": 1.0,
         "amplitude_m": 3e-4, "bearing": "DE",
         "shape": {"against": "NDE", "phase_deg": 176.0, "amplitude_ratio": 1.2, "form": "conical"}}
    s = {"whirl": {**w, "per_bearing": {"DE": w}}, "bearings": {}, "speeds": {"final_rotor_rpm": 9970.0},
         "energy": {"dissipated_total_j": 1.0}}
    assert summary_row(s)["whirl_shape"] == "conical"
    old = {**s, "whirl": {k: v for k, v in s["whirl"].items() if k != "shape"}}  # summarised before the shape
    assert summary_row(old)["whirl_shape"] is None

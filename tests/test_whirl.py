"""Tests of rotorlanding.whirl on synthetic orbits with known answers (fs = 10 kHz)."""

from __future__ import annotations

import numpy as np
import pytest

from rotorlanding.whirl import FORM_PHASE_DEG, WhirlResult, default_window_s, full_spectrum, whirl_analysis, whirl_shape

FS = 10_000.0
C = 2e-4  # radial clearance [m]


def _time(duration, t0=0.0, fs=FS):
    return t0 + np.arange(int(round(duration * fs))) / fs


def _drop_then_whirl(f_whirl, *, t_on=0.4, duration=1.5, t0=0.0, radius=C, noise=0.05,
                     seed=0):
    """Bounce (damped 200 Hz z oscillation about -c) until t_on, then a circular whirl of
    ``radius`` starting at the bottom; ``f_whirl`` > 0 forward, < 0 backward; noise in units of c.
    """
    rng = np.random.default_rng(seed)
    t = _time(duration, t0)
    tr = t - t0
    w = 1j * (-C + 0.5 * C * np.exp(-tr / 0.05) * np.cos(2 * np.pi * 200.0 * tr))
    on = tr >= t_on
    w[on] = radius * np.exp(1j * (2 * np.pi * f_whirl * (tr[on] - t_on) - np.pi / 2))
    w += noise * C * (rng.standard_normal(len(t)) + 1j * rng.standard_normal(len(t)))
    return t, w.real, w.imag


# ------------------------------------------------------------------ full_spectrum
def _peak(freq, amp):
    k = int(np.argmax(amp))
    return freq[k], amp[k]


@pytest.mark.parametrize("sense", [+1, -1])
def test_full_spectrum_circle_forward_and_backward(sense):
    t = _time(1.0)  # 1 Hz bins: 65 Hz falls on a bin
    w = 1e-4 * np.exp(1j * sense * 2 * np.pi * 65.0 * t)
    freq, amp = full_spectrum(t, w.real, w.imag)
    assert np.all(np.diff(freq) > 0) and freq[0] < 0 < freq[-1]
    f_pk, a_pk = _peak(freq, amp)
    df = freq[1] - freq[0]
    assert abs(f_pk - sense * 65.0) <= df
    assert a_pk == pytest.approx(1e-4, rel=0.02)
    # the opposite sense holds essentially nothing
    assert amp[np.argmin(np.abs(freq + sense * 65.0))] < 1e-3 * a_pk


def test_full_spectrum_planar_oscillation_has_equal_peaks():
    t = _time(1.0)
    y = 1e-4 * np.cos(2 * np.pi * 65.0 * t)
    freq, amp = full_spectrum(t, y, np.zeros_like(t))
    a_pos = amp[np.argmin(np.abs(freq - 65.0))]
    a_neg = amp[np.argmin(np.abs(freq + 65.0))]
    assert a_pos == pytest.approx(0.5e-4, rel=0.02)
    assert a_neg == pytest.approx(a_pos, rel=1e-6)
    assert max(a_pos, a_neg) == pytest.approx(amp.max())


def test_full_spectrum_rectangular_window_and_detrend():
    t = _time(1.0)
    w = 3e-4j + 1e-4 * np.exp(2j * np.pi * 65.0 * t)  # static offset + circle
    freq, amp = full_spectrum(t, w.real, w.imag, window="boxcar")
    assert _peak(freq, amp)[1] == pytest.approx(1e-4, rel=1e-6)
    freq, amp = full_spectrum(t, w.real, w.imag, detrend=False)
    assert amp[np.argmin(np.abs(freq))] == pytest.approx(3e-4, rel=1e-6)


# ------------------------------------------------------------------ whirl_analysis
def test_forward_whirl_after_bounces():
    t, y, z = _drop_then_whirl(+65.0)
    res = whirl_analysis(t, y, z, clearance=C)
    assert res.direction == "forward"
    assert res.frequency_hz == pytest.approx(65.0, abs=0.5)
    assert res.onset_s == pytest.approx(0.4, abs=0.03)
    assert res.amplitude_m == pytest.approx(C, rel=0.1)


def test_backward_whirl_after_bounces():
    t, y, z = _drop_then_whirl(-49.0, seed=1)
    res = whirl_analysis(t, y, z, clearance=C, spin_hz=116.7)
    assert res.direction == "backward"
    assert res.frequency_hz == pytest.approx(49.0, abs=0.5)
    assert res.onset_s == pytest.approx(0.4, abs=0.03)


@pytest.mark.parametrize("f_whirl, window_s", [(60.0, 0.05), (-150.0, 0.1)])
def test_growing_whirl_onset_is_the_threshold_crossing(f_whirl, window_s):
    # radius grows exponentially (tau 30 ms) from 0.05 c at 0.4 s and saturates at c:
    # it reaches the threshold 0.3 c at 0.4 + 0.03 ln 6 = 0.4538 s
    t = _time(1.5)
    r = np.where(t < 0.4, 0.0, np.minimum(C, 0.05 * C * np.exp((t - 0.4) / 0.03)))
    w = np.where(t < 0.4, -1j * C, r * np.exp(2j * np.pi * f_whirl * t))
    res = whirl_analysis(t, w.real, w.imag, clearance=C, window_s=window_s)
    assert res.direction == ("forward" if f_whirl > 0 else "backward")
    assert res.frequency_hz == pytest.approx(abs(f_whirl), abs=0.5)
    assert res.onset_s == pytest.approx(0.4 + 0.03 * np.log(6.0), abs=0.005)


def test_whirl_onset_reported_in_the_time_base_of_t():
    t, y, z = _drop_then_whirl(+65.0, t0=12.3, seed=2)
    res = whirl_analysis(t, y, z, clearance=C)
    assert res.direction == "forward"
    assert res.onset_s == pytest.approx(12.7, abs=0.03)
    # t_start is in the same time base; starting after the onset moves it
    late = whirl_analysis(t, y, z, clearance=C, t_start=13.0)
    assert late.direction == "forward"
    assert late.onset_s == pytest.approx(13.0, abs=0.03)


def test_bounces_then_rest_with_unbalance_response_is_not_whirl():
    rng = np.random.default_rng(3)
    t = _time(1.5)
    spin = 116.7
    # bouncing: decaying 200 Hz z oscillation plus a few decaying lateral kicks
    w = 1j * (-C + 0.6 * C * np.exp(-t / 0.08) * np.cos(2 * np.pi * 200.0 * t))
    w += 0.3 * C * np.exp(-t / 0.03) * np.sin(2 * np.pi * 90.0 * t)
    w += 0.05 * C * np.exp(2j * np.pi * spin * t)  # synchronous unbalance response (forward)
    w += 0.05 * C * (rng.standard_normal(len(t)) + 1j * rng.standard_normal(len(t)))
    res = whirl_analysis(t, w.real, w.imag, clearance=C, spin_hz=spin)
    assert res == WhirlResult("none", None, None, 0.0)
    assert res.to_dict() == {"direction": "none", "frequency_hz": None, "onset_s": None,
                             "amplitude_m": 0.0, "end_s": None, "persistence": 0.0}


def test_rotor_at_rest_is_not_whirl():
    t = _time(1.0)
    res = whirl_analysis(t, np.zeros_like(t), np.full_like(t, -C), clearance=C)
    assert res.direction == "none" and res.amplitude_m == 0.0


def test_large_synchronous_response_is_skipped_only_when_spin_given():
    t = _time(1.0)
    spin = np.linspace(120.0, 110.0, len(t))  # decelerating rotor
    phase = 2 * np.pi * np.cumsum(spin) / FS
    w = 0.6 * C * np.exp(1j * phase)
    assert whirl_analysis(t, w.real, w.imag, clearance=C).direction == "forward"
    assert whirl_analysis(t, w.real, w.imag, clearance=C, spin_hz=spin).direction == "none"
    # a real whirl under a strong synchronous response is still found
    w2 = w + C * np.exp(-2j * np.pi * 40.0 * t)
    res = whirl_analysis(t, w2.real, w2.imag, clearance=C, spin_hz=spin)
    assert res.direction == "backward" and res.frequency_hz == pytest.approx(40.0, abs=0.5)


def test_default_window_separates_a_subsynchronous_whirl_at_low_speed():
    # 3000 rpm (50 Hz spin): forward whirl at 0.93 x spin over a synchronous response. A 0.05 s
    # window has 20 Hz bins, so the whirl falls into the skipped synchronous band and is missed;
    # the default window holds 5 spin periods (0.1 s, 10 Hz bins) and finds it.
    spin = 50.0
    t, y, z = _drop_then_whirl(0.93 * spin, t_on=0.3, duration=1.0)
    w = y + 1j * z + 0.2 * C * np.exp(2j * np.pi * spin * t)
    assert default_window_s(spin) == pytest.approx(0.1)
    assert default_window_s(7000 / 60) == 0.05 and default_window_s(None) == 0.05
    assert whirl_analysis(t, w.real, w.imag, clearance=C, spin_hz=spin, window_s=0.05).direction == "none"
    res = whirl_analysis(t, w.real, w.imag, clearance=C, spin_hz=spin)
    assert res.direction == "forward" and res.frequency_hz == pytest.approx(0.93 * spin, rel=0.01)
    assert res.onset_s == pytest.approx(0.3, abs=0.03)


def test_lowest_detectable_whirl_frequency_is_two_over_window():
    t = _time(1.5)
    w = C * np.exp(-2j * np.pi * 20.0 * t)  # 20 Hz backward whirl
    assert whirl_analysis(t, w.real, w.imag, clearance=C).direction == "none"  # 20 < 2/0.05
    res = whirl_analysis(t, w.real, w.imag, clearance=C, window_s=0.2)
    assert res.direction == "backward" and res.frequency_hz == pytest.approx(20.0, abs=0.5)


def test_short_burst_is_not_whirl():
    t = _time(1.0)
    w = np.full(len(t), -1j * C)
    burst = (t >= 0.5) & (t < 0.55)
    w[burst] = C * np.exp(1j * (2 * np.pi * 65.0 * (t[burst] - 0.5) - np.pi / 2))
    assert whirl_analysis(t, w.real, w.imag, clearance=C).direction == "none"
    # the same motion lasting 0.2 s is whirl
    longer = (t >= 0.5) & (t < 0.7)
    w[longer] = C * np.exp(1j * (2 * np.pi * 65.0 * (t[longer] - 0.5) - np.pi / 2))
    res = whirl_analysis(t, w.real, w.imag, clearance=C)
    assert res.direction == "forward" and res.onset_s == pytest.approx(0.5, abs=0.03)


def test_sustained_planar_rattle_is_not_whirl():
    t = _time(1.0)
    z = -C + 0.8 * C * np.cos(2 * np.pi * 65.0 * t)
    assert whirl_analysis(t, np.zeros_like(t), z, clearance=C).direction == "none"


def test_result_to_dict_plain_types():
    t, y, z = _drop_then_whirl(+65.0)
    d = whirl_analysis(t, y, z, clearance=C).to_dict()
    assert set(d) == {"direction", "frequency_hz", "onset_s", "amplitude_m", "end_s", "persistence"}
    assert d["direction"] == "forward"
    assert all(type(d[k]) is float for k in ("frequency_hz", "onset_s", "amplitude_m", "end_s", "persistence"))


def test_sustained_whirl_lasts_to_the_record_end():
    t, y, z = _drop_then_whirl(-49.0, seed=4)
    res = whirl_analysis(t, y, z, clearance=C, spin_hz=116.7)
    assert res.end_s == pytest.approx(t[-1], abs=1.5 / FS)
    assert res.persistence == pytest.approx(1.0)


@pytest.mark.parametrize("t_stop", [0.83, 1.07])
def test_whirl_that_dies_out_ends_at_the_threshold_crossing(t_stop):
    # whirl of radius c from 0.4 s; from t_stop the radius decays with tau 20 ms, so the orbit falls
    # below the threshold 0.3 c at t_stop + 0.02 ln(1/0.3); then the rotor rests at the bottom
    t, y, z = _drop_then_whirl(-49.0, seed=5, noise=0.0)
    w = y + 1j * z
    after = t >= t_stop
    w[after] = -1j * C + (w[after] + 1j * C) * np.exp(-(t[after] - t_stop) / 0.02)
    res = whirl_analysis(t, w.real, w.imag, clearance=C)
    assert res.direction == "backward" and res.onset_s == pytest.approx(0.4, abs=0.03)
    # envelope smoothed over three whirl periods (61 ms): about +/- half of that
    assert res.end_s == pytest.approx(t_stop + 0.02 * np.log(1 / 0.3), abs=0.035)
    # windows from the onset to the last one of the record (0.05 s long, 0.0125 s apart)
    n_after = np.floor((1.5 - 0.05 - 0.4) / 0.0125)
    assert res.persistence == pytest.approx((res.end_s - 0.4) / 0.0125 / n_after, abs=0.1)
    assert res.persistence < (t_stop - 0.3) / 1.1


def test_intermittent_whirl_end_is_the_last_burst_and_persistence_its_share():
    # backward whirl bursts of 0.3 s separated by 0.2 s of rest, the last ending at 1.5 s, then
    # rest to 1.65 s.  A Hann window (0.05 s) whirls once >= 0.3 of its Hann weight (its first
    # ~0.4 = 0.02 s) lies in a burst, so window starts from 0.03 s before to 0.02 s before a
    # burst's end whirl: 3 x 0.31 s of the 1.43 s of window starts from the first -> ~0.65
    t = _time(1.65)
    burst = (t >= 0.2) & ((t - 0.2) % 0.5 < 0.3) & (t < 1.5)
    w = np.where(burst, C * np.exp(-2j * np.pi * 49.0 * t), -1j * C)
    res = whirl_analysis(t, w.real, w.imag, clearance=C)
    assert res.direction == "backward" and res.onset_s == pytest.approx(0.2, abs=0.03)
    assert res.end_s == pytest.approx(1.5, abs=0.035)
    assert res.persistence == pytest.approx(0.65, abs=0.06)


# ------------------------------------------------------------------ bad inputs
def _ok():
    t = _time(0.5)
    return t, np.zeros_like(t), np.zeros_like(t)


@pytest.mark.parametrize("kwargs, name", [
    ({"clearance": 0.0}, "clearance"),
    ({"clearance": -1e-4}, "clearance"),
    ({"clearance": float("nan")}, "clearance"),
    ({"window_s": 0.0}, "window_s"),
    ({"window_s": 0.6}, "window_s"),
    ({"window_s": 0.0005}, "window_s"),
    ({"step_s": 0.0}, "step_s"),
    ({"step_s": 0.2}, "step_s"),
    ({"amplitude_threshold": 0.0}, "amplitude_threshold"),
    ({"min_duration_s": -0.1}, "min_duration_s"),
    ({"spin_hz": -5.0}, "spin_hz"),
    ({"spin_hz": np.ones(3)}, "spin_hz"),
    ({"t_start": 7.0}, "t_start"),
])
def test_bad_parameters_raise_value_error_naming_them(kwargs, name):
    t, y, z = _ok()
    args = {"clearance": C, **kwargs}
    with pytest.raises(ValueError, match=name) as exc:
        whirl_analysis(t, y, z, **args)
    assert repr(next(iter(kwargs.values())))[:3] in str(exc.value) or name == "spin_hz"


def test_bad_series_raise_value_error():
    t, y, z = _ok()
    t_bad = t.copy()
    t_bad[10] += 0.3 / FS
    with pytest.raises(ValueError, match=r"t = .*uniformly sampled"):
        full_spectrum(t_bad, y, z)
    with pytest.raises(ValueError, match="same length"):
        full_spectrum(t, y[:-1], z)
    with pytest.raises(ValueError, match="at least 8 samples"):
        full_spectrum(t[:5], y[:5], z[:5])
    with pytest.raises(ValueError, match=r"t = .*uniformly sampled"):
        whirl_analysis(t[::-1], y, z, clearance=C)
    with pytest.raises(ValueError, match="window"):
        full_spectrum(t, y, z, window="no-such-window")


def test_builtin_windows_equal_scipy():
    from scipy.signal import get_window

    from rotorlanding.whirl import _window

    for n in (1, 2, 7, 64, 1001):
        for name in ("hann", "boxcar"):
            np.testing.assert_allclose(_window(name, n), get_window(name, n, fftbins=True), rtol=0, atol=1e-15)
    np.testing.assert_allclose(_window("hamming", 16), get_window("hamming", 16, fftbins=True))


# ---- whirl shape at two journals -------------------------------------------------------------
def _two_journals(f, phase_deg, ratio, sense=1.0, fs=5000.0, t_end=1.0, offset=-1.5e-4, noise=0.0):
    t = np.arange(0.0, t_end, 1.0 / fs)
    r = 2e-4
    rng = np.random.default_rng(3)
    w_a = r * np.exp(1j * sense * 2 * np.pi * f * t) + offset * 1j
    w_b = ratio * r * np.exp(1j * (sense * 2 * np.pi * f * t + np.radians(phase_deg))) + offset * 1j
    w_a += noise * (rng.standard_normal(len(t)) + 1j * rng.standard_normal(len(t)))
    return t, w_a.real, w_a.imag, w_b.real, w_b.imag


@pytest.mark.parametrize("phase, form", [(0.0, "cylindrical"), (25.0, "cylindrical"), (-170.0, "conical"),
                                         (180.0, "conical"), (90.0, "mixed")])
@pytest.mark.parametrize("sense", [1.0, -1.0])
def test_whirl_shape_recovers_the_phase_between_journals(phase, form, sense):
    """Two circular orbits at 72.5 Hz, the second shifted by a known phase (in its own whirl sense)
    and 1.3 times larger, both sitting low by a constant offset: the phase and ratio come back to
    within a degree and a percent, and the form follows FORM_PHASE_DEG."""
    t, ya, za, yb, zb = _two_journals(72.5, phase, 1.3, sense=sense)
    sh = whirl_shape(t, ya, za, yb, zb, frequency_hz=72.5, direction="forward" if sense > 0 else "backward",
                     t0=0.1, t1=0.9)
    assert abs((sh["phase_deg"] - phase + 180.0) % 360.0 - 180.0) < 1.0
    assert sh["amplitude_ratio"] == pytest.approx(1.3, rel=0.01)
    assert sh["form"] == form


def test_whirl_shape_reads_the_whirl_frequency_not_a_neighbour():
    """Journal a carries a conical 79.5 Hz whirl and an in-phase 72.5 Hz one; at 72.5 Hz the shape is
    cylindrical, at 79.5 Hz conical: the demodulation picks the component at the frequency asked."""
    t, ya, za, yb, zb = _two_journals(72.5, 0.0, 1.0)
    _, ya2, za2, yb2, zb2 = _two_journals(79.5, 180.0, 1.0)
    args = (t, ya + ya2, za + za2, yb + yb2, zb + zb2)
    assert whirl_shape(*args, frequency_hz=72.5, direction="forward", t0=0.0, t1=1.0)["form"] == "cylindrical"
    assert whirl_shape(*args, frequency_hz=79.5, direction="forward", t0=0.0, t1=1.0)["form"] == "conical"


def test_whirl_shape_form_threshold_and_bad_input():
    t, ya, za, yb, zb = _two_journals(50.0, FORM_PHASE_DEG + 5.0, 1.0)
    assert whirl_shape(t, ya, za, yb, zb, frequency_hz=50.0, direction="forward", t0=0.0, t1=1.0)["form"] == "mixed"
    with pytest.raises(ValueError, match="direction"):
        whirl_shape(t, ya, za, yb, zb, frequency_hz=50.0, direction="none", t0=0.0, t1=1.0)
    with pytest.raises(ValueError, match="frequency_hz"):
        whirl_shape(t, ya, za, yb, zb, frequency_hz=-5.0, direction="forward", t0=0.0, t1=1.0)
    with pytest.raises(ValueError, match="t0, t1"):
        whirl_shape(t, ya, za, yb, zb, frequency_hz=50.0, direction="forward", t0=0.5, t1=0.5)

"""Full-spectrum whirl analysis of a rotor orbit.

Conventions: rotor axis ``x``, lateral ``y`` (horizontal) and ``z`` (vertical, gravity along
``-z``), spin about ``+x`` with speed ``Omega > 0``.  The orbit is the complex signal
``w = y + i z``; its FFT is kept over negative *and* positive frequencies (the "full spectrum").
A component at ``+f`` turns in the same sense as the spin (**forward** whirl), a component at
``-f`` turns against it (**backward** whirl).  SI units throughout (s, m, Hz).

Public API
----------
- :func:`full_spectrum`  : amplitude full spectrum of ``y + i z`` (a circle of radius R at
  ``f0`` shows R at ``+f0``).
- :func:`whirl_analysis` : sliding-window detection of sustained whirl, its direction, frequency,
  onset time and orbit radius, returned as a :class:`WhirlResult`.
- :func:`whirl_shape`    : the phase between two journals' whirl and the form it makes
  (cylindrical or conical).

Bad input raises :class:`rotorlanding.errors.InputError` (a ``ValueError``) naming the argument,
its value and what is allowed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import InputError

__all__ = ["full_spectrum", "WhirlResult", "whirl_analysis", "whirl_shape", "FORM_PHASE_DEG", "landing_whirl_bearing", "landing_whirl", "default_window_s", "MIN_DIRECTIONALITY",
           "SPIN_TOLERANCE", "MIN_WINDOW_S", "WINDOW_SPIN_PERIODS"]

#: A window only counts as whirling if its dominant component is at least this many times larger
#: than the component at the mirrored frequency ``-f``.  A planar (straight-line) oscillation, e.g.
#: vertical bouncing, has equal components at ``+f`` and ``-f`` and is therefore not whirl.
#: 1.5 accepts ellipses down to a minor/major axis ratio of 0.2.
MIN_DIRECTIONALITY = 1.5

#: Relative half-width of the band around ``+spin_hz`` whose (synchronous) component is skipped.
SPIN_TOLERANCE = 0.03

_REL_TOL_DT = 1e-6
_MIN_SAMPLES = 8


class _Text(str):
    """A string shown without quotes in :class:`InputError` messages."""

    def __repr__(self) -> str:
        return str(self)


# --------------------------------------------------------------------------------------------
# input checks
# --------------------------------------------------------------------------------------------
def _as_series(t, y, z) -> tuple[np.ndarray, np.ndarray, float]:
    """Validate ``t, y, z``; return ``(t, w = y + i z, dt)``."""
    arrays = {}
    for name, val in (("t", t), ("y", y), ("z", z)):
        try:
            arr = np.asarray(val, dtype=float)
        except (TypeError, ValueError):
            raise InputError(name, _Text(type(val).__name__),
                             "must be a 1-D array of real numbers") from None
        if arr.ndim != 1:
            raise InputError(name, _Text(f"array of shape {arr.shape}"), "must be a 1-D array")
        if not np.all(np.isfinite(arr)):
            raise InputError(name, _Text(f"array with {np.count_nonzero(~np.isfinite(arr))} "
                                         "non-finite values"), "all values must be finite")
        arrays[name] = arr
    t_, y_, z_ = arrays["t"], arrays["y"], arrays["z"]
    if not (len(t_) == len(y_) == len(z_)):
        raise InputError("y, z", _Text(f"lengths t={len(t_)}, y={len(y_)}, z={len(z_)}"),
                         "t, y and z must have the same length")
    if len(t_) < _MIN_SAMPLES:
        raise InputError("t", _Text(f"{len(t_)} samples"),
                         f"at least {_MIN_SAMPLES} samples are required")
    dt = (t_[-1] - t_[0]) / (len(t_) - 1)
    steps = np.diff(t_)
    if not dt > 0 or np.max(np.abs(steps - dt)) > _REL_TOL_DT * dt:
        raise InputError("t", _Text(f"time steps from {steps.min():.6g} to {steps.max():.6g} s"),
                         "must be strictly increasing and uniformly sampled "
                         f"(relative tolerance {_REL_TOL_DT:g})")
    return t_, y_ + 1j * z_, float(dt)


def _positive(name: str, value, *, allow_zero: bool = False) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(name, value, "must be a real number") from None
    ok = np.isfinite(v) and (v >= 0 if allow_zero else v > 0)
    if not ok:
        raise InputError(name, value, "must be a finite number " + (">= 0" if allow_zero else "> 0"))
    return v


# --------------------------------------------------------------------------------------------
# spectra
# --------------------------------------------------------------------------------------------
def _window(window, n: int) -> np.ndarray:
    if window is None or (isinstance(window, str) and window.lower() in ("none", "rect",
                                                                          "rectangular")):
        window = "boxcar"
    # the two windows the tool uses are written out (periodic forms, equal to scipy's
    # get_window(..., fftbins=True)): importing scipy.signal costs ~0.6 s, a serial cost of
    # every sweep and worker start
    if window == "boxcar":
        return np.ones(n)
    if window in ("hann", "hanning"):
        if n == 1:
            return np.ones(1)
        return 0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(n) / n)
    try:
        from scipy.signal import get_window

        return get_window(window, n, fftbins=True)
    except (ValueError, TypeError) as exc:
        raise InputError("window", window, f"must be a scipy.signal window name ({exc})") from None


def _detrend(w: np.ndarray, detrend) -> np.ndarray:
    if detrend is False or detrend is None:
        return w
    if detrend is True or detrend == "constant":
        return w - w.mean()
    if detrend == "linear":
        x = np.arange(len(w), dtype=float)
        coef = np.polyfit(x, w, 1)  # complex data: fits y and z at once
        return w - np.polyval(coef, x)
    raise InputError("detrend", detrend, "must be True/'constant', 'linear' or False")


def _spectrum_rows(w: np.ndarray, win: np.ndarray) -> np.ndarray:
    """Amplitude full spectrum (fftshift order) of each row of ``w`` (already detrended)."""
    return np.abs(np.fft.fftshift(np.fft.fft(w * win, axis=-1), axes=-1)) / win.sum()


def full_spectrum(t, y, z, *, window="hann", detrend=True) -> tuple[np.ndarray, np.ndarray]:
    """Amplitude full spectrum of the orbit ``w = y + i z``.

    Parameters
    ----------
    t, y, z : array_like, 1-D, same length (>= 8)
        Uniformly sampled time [s] (relative tolerance 1e-6 on the step) and lateral
        displacements [m].
    window : str or tuple, default ``"hann"``
        Any :func:`scipy.signal.get_window` name; ``"boxcar"``/``None`` for no window.
    detrend : bool or {"constant", "linear"}, default True
        ``True``/``"constant"`` removes the (complex) mean of ``w``, ``"linear"`` a straight
        line fitted to ``y`` and ``z``, ``False`` nothing.

    Returns
    -------
    freq_hz : ndarray
        Frequencies [Hz] sorted ascending from ``-fs/2`` to ``+fs/2``.  Positive = forward whirl
        (same sense as the spin about +x), negative = backward whirl.
    amplitude_m : ndarray
        Component amplitude [m], corrected for the window's coherent gain: a circle of radius
        ``R`` at frequency ``f0`` (``w = R exp(2 pi i f0 t)``) shows ``R`` at ``+f0`` when ``f0``
        falls on a frequency bin (bin width ``1 / (n dt)``); between bins the usual scalloping
        loss of the window applies.  A planar oscillation ``y = A cos(2 pi f t)`` shows ``A/2``
        at both ``+f`` and ``-f``.

    Raises
    ------
    InputError (ValueError)
        Non-uniform or non-increasing ``t``, fewer than 8 samples, arrays of different length,
        non-finite values, unknown window or detrend option.
    """
    t_, w, dt = _as_series(t, y, z)
    n = len(w)
    win = _window(window, n)
    amp = _spectrum_rows(_detrend(w, detrend), win)
    freq = np.fft.fftshift(np.fft.fftfreq(n, dt))
    return freq, amp


def _peaks(amp: np.ndarray, df: float, f0: float, hann: bool):
    """Local maxima of each row of ``amp`` (fftshift order) with sub-bin interpolation.

    Returns boolean peak mask, interpolated frequency [Hz] and interpolated amplitude for every
    bin (the last two are only meaningful where the mask is true).  ``f0`` is the frequency of
    column 0.  For the Hann window the exact two-bin ratio formula of its main lobe is used
    (offset ``d = (2r - 1)/(1 + r)``, amplitude ``A/(sinc(d)/(1 - d^2))``); otherwise a
    parabola through the logarithms of the three bins.
    """
    amp = np.atleast_2d(amp)
    n = amp.shape[1]
    left = np.full_like(amp, np.inf)
    right = np.full_like(amp, np.inf)
    left[:, 1:] = amp[:, :-1]
    right[:, :-1] = amp[:, 1:]
    is_peak = (amp >= left) & (amp > right) & (amp > 0)
    is_peak[:, 0] = is_peak[:, -1] = False
    left[:, 0] = right[:, -1] = 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        if hann:
            use_right = right > left
            r = np.where(use_right, right, left) / amp
            d = (2.0 * r - 1.0) / (1.0 + r)
            d = np.clip(np.nan_to_num(d), 0.0, 0.5)
            d = np.where(use_right, d, -d)
            gain = np.sinc(d) / (1.0 - d * d)
            a_int = amp / gain
        else:
            la, lm, lr = (np.log(np.maximum(x, 1e-300)) for x in (left, amp, right))
            den = la - 2.0 * lm + lr
            d = np.where(den < 0, 0.5 * (la - lr) / den, 0.0)
            d = np.clip(np.nan_to_num(d), -0.5, 0.5)
            a_int = np.exp(lm - 0.25 * (la - lr) * d)
    freq = f0 + (np.arange(n) + d) * df
    return is_peak, freq, a_int


def _spin_band(spin_lo: np.ndarray, spin_hi: np.ndarray, df: float):
    """Lower/upper edges of the skipped synchronous band (at least +/-0.2 bins wide)."""
    half = np.maximum(SPIN_TOLERANCE * spin_hi, 0.2 * df)
    return spin_lo - half, spin_hi + half


def _dominant(amp, df, f0, f_min, spin_lo=None, spin_hi=None):
    """Dominant allowed component of each row: (index, signed freq, amplitude, mirror amp)."""
    amp = np.atleast_2d(amp)
    m, n = amp.shape
    is_peak, freq, a_int = _peaks(amp, df, f0, hann=True)
    allowed = is_peak & (np.abs(freq) >= f_min)
    if spin_lo is not None:
        lo, hi = _spin_band(np.asarray(spin_lo, float), np.asarray(spin_hi, float), df)
        allowed &= ~((freq >= lo[:, None]) & (freq <= hi[:, None]))
    score = np.where(allowed, a_int, -np.inf)
    j = np.argmax(score, axis=1)
    rows = np.arange(m)
    found = np.isfinite(score[rows, j])
    f_dom = np.where(found, freq[rows, j], np.nan)
    a_dom = np.where(found, a_int[rows, j], 0.0)
    raw = amp[rows, j]
    jm = 2 * (n // 2) - j  # bin of the mirrored frequency -f
    mirror = np.max(np.stack([amp[rows, np.clip(jm + k, 0, n - 1)] for k in (-1, 0, 1)]), axis=0)
    directional = raw >= MIN_DIRECTIONALITY * mirror
    return found, f_dom, a_dom, directional


# --------------------------------------------------------------------------------------------
# whirl analysis
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class WhirlResult:
    """Outcome of :func:`whirl_analysis`.

    Attributes
    ----------
    direction : str
        ``"none"``, ``"forward"`` (same sense as the spin about +x) or ``"backward"``.
    frequency_hz : float or None
        Magnitude (> 0) of the dominant whirl frequency [Hz]; None when ``direction == "none"``.
    onset_s : float or None
        Time [s] at which the whirl starts, in the time base of the input ``t``; None when none.
    amplitude_m : float
        Orbit radius [m] of the dominant component during the whirl phase (0 when none).
    end_s : float or None
        Time [s] at which the whirl is last seen (the record end if it is still whirling), same
        time base as ``onset_s``; None when none.  Between onset and end it may pause: see
        ``persistence``.
    persistence : float
        Share (0..1) of the analysed windows from the onset to the record end that whirl in
        ``direction``: 1 for a whirl that never stops, lower for one that dies out or is
        intermittent (0 when none).
    """

    direction: str
    frequency_hz: float | None
    onset_s: float | None
    amplitude_m: float
    end_s: float | None = None
    persistence: float = 0.0

    def __post_init__(self):
        if self.direction not in ("none", "forward", "backward"):
            raise InputError("direction", self.direction, "must be 'none', 'forward' or 'backward'")

    def to_dict(self) -> dict:
        """Plain dict (built-in types only) for JSON/TOML reports."""
        return {
            "direction": self.direction,
            "frequency_hz": None if self.frequency_hz is None else float(self.frequency_hz),
            "onset_s": None if self.onset_s is None else float(self.onset_s),
            "amplitude_m": float(self.amplitude_m),
            "end_s": None if self.end_s is None else float(self.end_s),
            "persistence": float(self.persistence),
        }


_NONE = WhirlResult("none", None, None, 0.0)


def _spin_series(spin_hz, n: int):
    """None, or a per-sample spin frequency array [Hz] (scalar broadcast)."""
    if spin_hz is None:
        return None
    arr = np.asarray(spin_hz, dtype=float) if not isinstance(spin_hz, str) else None
    if arr is None or arr.ndim > 1 or (arr.ndim == 1 and len(arr) != n):
        raise InputError("spin_hz", spin_hz if np.ndim(spin_hz) == 0 else
                         _Text(f"array of shape {np.shape(spin_hz)}"),
                         f"must be None, a number > 0 or a 1-D array of {n} values > 0 (one per "
                         "sample of t)")
    if not (np.all(np.isfinite(arr)) and np.all(arr > 0)):
        raise InputError("spin_hz", spin_hz if arr.ndim == 0 else
                         _Text(f"array with min {np.nanmin(arr):.6g}"),
                         "must be finite and > 0 (spin speed in Hz)")
    return np.broadcast_to(arr, (n,)).astype(float)


#: Shortest analysis window [s] of the default (automatic) window length.
MIN_WINDOW_S = 0.05
#: The automatic window holds at least this many spin periods, so that its bin width is at most
#: 1/5 of the spin frequency: a sub-synchronous whirl at ~0.9 x spin is then a separate peak, not
#: merged into the skipped synchronous band (with 0.05 s at 3000 rpm a bin is 20 Hz = 0.4 x spin).
WINDOW_SPIN_PERIODS = 5.0


def default_window_s(spin_hz=None) -> float:
    """Automatic window length [s]: ``max(MIN_WINDOW_S, WINDOW_SPIN_PERIODS / spin)`` with the
    median spin [Hz] of the record (``MIN_WINDOW_S`` without a spin speed)."""
    if spin_hz is None:
        return MIN_WINDOW_S
    f = float(np.median(np.asarray(spin_hz, dtype=float)))
    return max(MIN_WINDOW_S, WINDOW_SPIN_PERIODS / f) if np.isfinite(f) and f > 0 else MIN_WINDOW_S


def whirl_analysis(t, y, z, *, clearance, spin_hz=None, window_s=None, step_s=None,
                   amplitude_threshold=0.3, min_duration_s=0.1, t_start=None) -> WhirlResult:
    """Detect sustained whirl in an orbit ``w = y + i z`` by sliding-window full spectra.

    Algorithm
    ---------
    1. Windows of length ``window_s`` (Hann), advanced by ``step_s``, starting at ``t_start``.
       In each window the mean of ``w`` is removed (a rotor resting at the bottom of the
       clearance is not whirl) and the full spectrum is taken.
    2. The dominant component is the largest spectral peak (sub-bin interpolated amplitude)
       with ``|f| >= 2 / window_s`` (near-DC content is skipped) and, if ``spin_hz`` is given,
       not within ``+/-3 %`` of ``+spin_hz`` (synchronous unbalance response; the band is at
       least +/-0.2 frequency bins wide).
    3. A window *whirls* if that component's amplitude is ``>= amplitude_threshold * clearance``
       and it is at least :data:`MIN_DIRECTIONALITY` times the component at the mirrored
       frequency (a planar oscillation, e.g. bouncing, is not whirl).
    4. Whirl is declared for the first run of consecutive whirling windows of the same direction
       (sign of the dominant frequency) whose span, first to last window start, is at least
       ``min_duration_s``.  The span is the whirl duration to within about ``+/-window_s``, so
       bursts clearly shorter than ``min_duration_s`` are rejected.
    5. ``onset_s``: within the first window of the run, the first instant at which the amplitude
       of the dominant component (complex demodulation at the whirl frequency, Hann-averaged over
       up to three whirl periods, which cancels the static offset) reaches the threshold; the
       window start if it is already above it there.  Resolution: about half a whirl period (a
       whirl switching on abruptly with radius = clearance is dated ~0.3 period early).
    6. ``frequency_hz`` and ``direction`` come from the full spectrum of the whole whirl phase
       (``onset_s`` to the end of the last window of the run), with sub-bin interpolation.
       ``amplitude_m`` is the median of the per-window dominant amplitudes of the run.
    7. ``end_s``: the record end if the last window whirls in the run's direction; otherwise,
       within the last window that does, the last instant at which the envelope of step 5 is at
       or above the threshold (the window end if it never reaches it there).  ``persistence``:
       share of the windows from the first of the run to the last of the record that whirl in
       the same direction.

    Parameters
    ----------
    t, y, z : array_like
        Uniformly sampled time [s] and lateral displacements [m] (see :func:`full_spectrum`).
    clearance : float
        Radial clearance of the catcher bearing [m], > 0.
    spin_hz : float, array_like or None
        Spin speed [Hz] (> 0), either constant or one value per sample (decelerating rotor);
        its forward synchronous component is not whirl.  None: nothing is skipped.
    window_s : float or None
        Window length [s], > 0, shorter than the analysed record, at least 8 samples.  None
        (default): :func:`default_window_s` of the analysed record's spin (0.05 s from 6000 rpm
        up, 5 spin periods below), capped at half the analysed record.
    step_s : float or None
        Window advance [s], 0 < step_s <= window_s; default ``window_s / 4``.
    amplitude_threshold : float
        Whirl threshold as a fraction of ``clearance`` (> 0).
    min_duration_s : float
        Minimum duration of sustained whirl [s] (>= 0).
    t_start : float or None
        Analyse from this time on (same time base as ``t``); default ``t[0]``.

    Returns
    -------
    WhirlResult
    """
    t_, w, dt = _as_series(t, y, z)
    n_all = len(w)
    clearance = _positive("clearance", clearance)
    auto_window = window_s is None
    if not auto_window:
        window_s = _positive("window_s", window_s)
    amplitude_threshold = _positive("amplitude_threshold", amplitude_threshold)
    min_duration_s = _positive("min_duration_s", min_duration_s, allow_zero=True)
    spin = _spin_series(spin_hz, n_all)

    if t_start is None:
        i0 = 0
    else:
        try:
            ts = float(t_start)
        except (TypeError, ValueError):
            ts = float("nan")
        if not np.isfinite(ts) or ts < t_[0] - 0.5 * dt or ts > t_[-1]:
            raise InputError("t_start", t_start,
                             f"must be None or within the record [{t_[0]:.6g}, {t_[-1]:.6g}] s")
        i0 = int(max(0, np.ceil((ts - t_[0]) / dt - 1e-6)))
    record_s = (n_all - i0) * dt
    if auto_window:
        window_s = min(default_window_s(None if spin is None else spin[i0:]), max(MIN_WINDOW_S, 0.5 * record_s))
    if window_s >= record_s:
        raise InputError("window_s", window_s,
                         f"must be > 0 and shorter than the analysed record ({record_s:.6g} s)")
    nwin = int(round(window_s / dt))
    if nwin < _MIN_SAMPLES:
        raise InputError("window_s", window_s,
                         f"must span at least {_MIN_SAMPLES} samples (>= {_MIN_SAMPLES * dt:.3g} s)")
    if step_s is None:
        step_s = window_s / 4.0
    step_s = _positive("step_s", step_s)
    if step_s > window_s:
        raise InputError("step_s", step_s, f"must be > 0 and <= window_s ({window_s:g} s)")
    nstep = max(1, int(round(step_s / dt)))

    wa = w[i0:]
    ta = t_[i0:]
    starts = np.arange(0, len(wa) - nwin + 1, nstep)
    if len(starts) == 0:
        return _NONE
    win = _window("hann", nwin)
    df = 1.0 / (nwin * dt)
    f0 = np.fft.fftshift(np.fft.fftfreq(nwin, dt))[0]
    f_min = 2.0 / window_s
    if spin is not None:
        csum = np.concatenate([[0.0], np.cumsum(spin[i0:])])

    # ---- per-window dominant component (chunked to bound memory) ----
    views = np.lib.stride_tricks.sliding_window_view(wa, nwin)
    f_dom = np.empty(len(starts))
    a_dom = np.empty(len(starts))
    whirls = np.empty(len(starts), dtype=bool)
    chunk = max(1, 2_000_000 // nwin)
    for c0 in range(0, len(starts), chunk):
        s = starts[c0:c0 + chunk]
        seg = views[s]
        seg = seg - seg.mean(axis=1, keepdims=True)
        amp = _spectrum_rows(seg, win)
        if spin is not None:
            sm = (csum[s + nwin] - csum[s]) / nwin
            found, fd, ad, directional = _dominant(amp, df, f0, f_min, sm, sm)
        else:
            found, fd, ad, directional = _dominant(amp, df, f0, f_min)
        f_dom[c0:c0 + chunk] = fd
        a_dom[c0:c0 + chunk] = ad
        whirls[c0:c0 + chunk] = found & directional & (ad >= amplitude_threshold * clearance)

    # ---- first sustained run of same-direction whirling windows ----
    sign = np.where(whirls, np.sign(np.nan_to_num(f_dom)), 0)
    run = None
    k = 0
    while k < len(starts):
        if sign[k] == 0:
            k += 1
            continue
        e = k
        while e + 1 < len(starts) and sign[e + 1] == sign[k]:
            e += 1
        if (starts[e] - starts[k]) * dt >= min_duration_s - 1e-9 * dt:
            run = (k, e)
            break
        k = e + 1
    if run is None:
        return _NONE
    k, e = run
    i_first = starts[k]
    i_end = starts[e] + nwin  # exclusive, index into wa
    amplitude = float(np.median(a_dom[k:e + 1]))

    # ---- whole-phase spectrum (preliminary, from the first window start) ----
    def phase_peak(i_a: int):
        seg = wa[i_a:i_end]
        seg = seg - seg.mean()
        nseg = len(seg)
        wseg = _window("hann", nseg)
        amp = _spectrum_rows(seg, wseg)[None, :]
        dfs = 1.0 / (nseg * dt)
        f0s = np.fft.fftshift(np.fft.fftfreq(nseg, dt))[0]
        if spin is not None:
            sp = spin[i0 + i_a:i0 + i_end]
            found, fd, _, _ = _dominant(amp, dfs, f0s, 2.0 / (nseg * dt),
                                        np.array([sp.min()]), np.array([sp.max()]))
        else:
            found, fd, _, _ = _dominant(amp, dfs, f0s, 2.0 / (nseg * dt))
        return float(fd[0]) if found[0] else float(np.median(f_dom[k:e + 1]))

    f_pre = phase_peak(i_first)

    # ---- onset / end refinement: envelope of the component at f_pre ----
    # Complex demodulation at f_pre, smoothed by a periodic Hann kernel spanning an integer number
    # (up to 3) of whirl periods: it cancels a constant offset and the mirror component exactly,
    # and a jump of the orbit centre by one clearance leaks at most ~0.11 clearance into it.
    period = int(min(max(round(1.0 / (abs(f_pre) * dt)), 1), nwin))
    klen = period * min(3, max(1, nwin // period))
    kernel = _window("hann", klen)
    kernel /= kernel.sum()

    def envelope(i_w: int):
        """Envelope centres and values over the window starting at ``i_w`` (plus a kernel margin)."""
        a = max(0, i_w - klen // 2)
        b = min(len(wa), i_w + nwin + klen)
        idx = np.arange(a, b)
        demod = wa[a:b] * np.exp(-2j * np.pi * f_pre * (idx - i_w) * dt)
        env = np.abs(np.convolve(demod, kernel, mode="valid"))
        centres = idx[: len(env)] + klen // 2
        inside = (centres >= i_w) & (centres < i_w + nwin)
        return centres[inside], env[inside] >= amplitude_threshold * clearance

    centres, above = envelope(i_first)
    if not above.any() or above[0]:
        i_onset = int(i_first)  # already whirling at the window start (or no crossing found)
    else:
        i_onset = int(centres[np.argmax(above)])
    if i_end - i_onset < _MIN_SAMPLES:
        i_onset = int(i_first)

    e_last = int(np.nonzero(sign == sign[k])[0][-1])  # last window whirling the same way
    if e_last == len(starts) - 1:
        i_stop = len(wa) - 1  # whirling in the last window: it lasts to the record end
    else:
        centres, above = envelope(int(starts[e_last]))
        i_stop = max(int(centres[above][-1]) if above.any() else int(starts[e_last]) + nwin - 1, i_onset)
    persistence = float(np.mean(sign[k:] == sign[k]))

    f_whirl = phase_peak(i_onset)
    if not np.isfinite(f_whirl) or f_whirl == 0:
        return _NONE
    return WhirlResult(direction="forward" if f_whirl > 0 else "backward",
                       frequency_hz=abs(f_whirl),
                       onset_s=float(ta[i_onset]),
                       amplitude_m=amplitude,
                       end_s=float(ta[i_stop]),
                       persistence=persistence)


def landing_whirl_bearing(whirls: dict, reference: str = "DE") -> str:
    """The bearing whose whirl is the landing's whirl: the reference bearing (the DE, the paper's
    measuring node) when its journal whirls, else the bearing whose journal starts whirling first.

    Why not the DE alone: in a combined landing the thrust-face friction can drive the NDE journal
    round its clearance while the gravity-loaded DE journal stays at the bottom (our 3000 rpm
    landing); a summary reading only the DE would call such a landing calm.  A whirl at any
    catcher bearing is a whirl of the rotor; ``per_bearing`` keeps every bearing's result."""
    if not whirls:
        raise ValueError("no bearings to take a whirl from")
    ref = reference if reference in whirls else next(iter(whirls))
    if whirls[ref]["direction"] != "none":
        return ref
    moving = [name for name, w in whirls.items() if w["direction"] != "none"]
    # earliest onset (unknown onsets last); dict order (the scenario's bearing order) breaks ties
    return min(moving, key=lambda name: _onset(whirls[name])) if moving else ref


def longest_whirl(times: dict) -> str | None:
    """The bearing with the longest whirl time in ``times`` (name -> s, in order of first whirl:
    the earlier wins a tie), None when empty: the whirl bearing of a coast-down, whose chunks may
    each name a different one."""
    return max(times, key=times.get) if times else None  # max keeps the first of equal times


def _onset(w: dict) -> float:
    return float("inf") if w.get("onset_s") is None else w["onset_s"]


def landing_whirl(whirl: dict) -> dict:
    """A summary's ``whirl`` entry with ``bearing`` set; a summary written before the landing's
    whirl was chosen by :func:`landing_whirl_bearing` (its top level is the DE's) is re-derived
    from its ``per_bearing`` results, so old and new results read the same way."""
    if whirl.get("bearing") or not whirl.get("per_bearing"):
        return {"bearing": "DE", **whirl}
    name = landing_whirl_bearing(whirl["per_bearing"])
    return {**whirl["per_bearing"][name], "bearing": name, "per_bearing": whirl["per_bearing"]}


# --------------------------------------------------------------------------------------------
# whirl shape at two journals
# --------------------------------------------------------------------------------------------
#: |phase| between the two journals' whirl components up to this [deg]: they go round together
#: (cylindrical form); from ``180 - FORM_PHASE_DEG`` on: against each other (conical); between:
#: "mixed". 60 deg: a third of the way from one form to the other, so a form is named only where
#: one shape clearly dominates.
FORM_PHASE_DEG = 60.0


def whirl_shape(t, y_ref, z_ref, y_other, z_other, *, frequency_hz: float, direction: str,
                t0: float, t1: float) -> dict:
    """The shape of a whirl seen at two journals: the phase of the other journal's whirl component
    against the reference journal's, at the whirl frequency over ``[t0, t1]``, and the form it makes.

    Why: a landed rotor can whirl on more than one shape at one speed. The rig's 10000 rpm combined
    landing locks either with both journals going round together (cylindrical, 0.95 of the landed
    forward mode) or against each other (conical, 1.03 of it: docs/calibration.md, session 27). A
    conical whirl tilts the rotor's disks, whose gyroscopic moments stiffen a forward whirl as the
    speed rises, so the two shapes move apart with speed. A frequency alone does not say which
    shape; the phase does.

    Method: complex demodulation of each orbit ``w = y + i z`` at ``+f`` (forward) or ``-f``
    (backward) under a Hann window over ``[t0, t1]``, ``c = sum(h w exp(-i 2 pi s f t))``; the
    phase is ``angle(c_other conj(c_ref))`` in (-180, 180] deg and the amplitude ratio
    ``|c_other| / |c_ref|``. A constant offset (the journal resting low) is removed first.

    Returns ``{"phase_deg", "amplitude_ratio", "form"}``, form ``"cylindrical"`` (|phase| <=
    :data:`FORM_PHASE_DEG`), ``"conical"`` (>= 180 - it) or ``"mixed"``.
    """
    if direction not in ("forward", "backward"):
        raise InputError("direction", direction, "must be 'forward' or 'backward' (a whirl to take the shape of)")
    f = _positive("frequency_hz", frequency_hz)
    t_, w_ref, dt = _as_series(t, y_ref, z_ref)
    _, w_oth, _ = _as_series(t, y_other, z_other)
    sel = (t_ >= t0 - 0.5 * dt) & (t_ <= t1 + 0.5 * dt)
    if int(sel.sum()) < _MIN_SAMPLES:
        raise InputError("t0, t1", _Text(f"[{t0:.6g}, {t1:.6g}] s"),
                         f"must span at least {_MIN_SAMPLES} samples of the record [{t_[0]:.6g}, {t_[-1]:.6g}] s")
    s = 1.0 if direction == "forward" else -1.0
    h = _window("hann", int(sel.sum()))
    rot = np.exp(-2j * np.pi * s * f * t_[sel])
    c = [np.sum(h * (w[sel] - w[sel].mean()) * rot) for w in (w_ref, w_oth)]
    if abs(c[0]) == 0.0:
        return {"phase_deg": None, "amplitude_ratio": None, "form": "mixed"}
    phase = float(np.degrees(np.angle(c[1] * np.conj(c[0]))))
    form = ("cylindrical" if abs(phase) <= FORM_PHASE_DEG else
            "conical" if abs(phase) >= 180.0 - FORM_PHASE_DEG else "mixed")
    return {"phase_deg": phase, "amplitude_ratio": float(abs(c[1]) / abs(c[0])), "form": form}

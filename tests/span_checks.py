"""One check of a run's ``rotor_deflection`` record, shared by the landing and coast-down tests: at the
sleeves it is the stored journal series' largest radial displacement (an independent path: the
series come from the bearing states, the record from the Craig-Bampton rebuild), and its largest
anywhere is at least every station's."""

import numpy as np
import pytest


def assert_span_matches_the_journal_series(span: dict, series: dict, bearings=("DE", "NDE")) -> None:
    for b in bearings:
        peak = np.hypot(series[f"{b}_y_m"], series[f"{b}_z_m"]).max()
        assert span["station_peak_m"][f"{b}_sleeve"] == pytest.approx(peak, rel=1e-9)
    assert span["peak_m"] >= max(span["station_peak_m"].values())

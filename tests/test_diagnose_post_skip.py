"""diagnose leaves the catcher-thermal post-processing out (a third of each landing's time): its
features must be the ones of the full post-processing, and only the thermal series may differ."""

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from sensor_model import C, known_rig_model  # noqa: E402


def test_skipping_the_thermal_post_changes_no_feature(tmp_path):
    import rotorlanding.diagnose_run as d
    from rotorlanding.postprocess import evaluate
    from rotorlanding.run import simulate
    from rotorlanding.scenario import load_scenario

    model = known_rig_model(tmp_path / "model.toml", t_end=0.12)
    spec, t, q, v, _ = simulate(load_scenario(model, []), progress=False)
    full = evaluate(spec, t, q, v)
    cut = evaluate(spec, t, q, v, skip=d.POST_NOT_NEEDED)
    thermal = [k for k in full if "temperature" in k or k.endswith("heat_in_j") or k.endswith("heat_lost_j")]
    assert thermal and any(np.any(full[k] != 0) for k in thermal)      # the full run has temperatures
    assert all(not np.any(cut[k]) for k in thermal)                    # the skipped run leaves zeros
    for k in full:
        if "temperature" not in k and "heat_" not in k:
            assert np.array_equal(full[k], cut[k]), k
    # and the features diagnose extracts are the same, with and without the skip
    with_skip = d._simulate_features(model, [], C)
    saved = d.POST_NOT_NEEDED
    try:
        d.POST_NOT_NEEDED = frozenset()
        without = d._simulate_features(model, [], C)
    finally:
        d.POST_NOT_NEEDED = saved
    assert with_skip == without and "DE_vertical_min_m" in with_skip

"""An ensemble's features compared regime by regime (issue 20, point 1: compare distributions).

A landing near a whirl threshold whirls in some drops and not in others, and a whirling drop's
extremes lie several scales from a calm one's. Means over both regimes made every extreme carry the
lottery of which drops whirled; now the landings of the measured regime are compared with the
model's of that regime, and the regimes' shares are charged once, in the whirl row (for repeated
records: the total-variation distance between the two regime distributions)."""
import math

from rotorlanding.features import DIRECTION_MISMATCH, ensemble_features, gap

SCALE = 2e-5  # 0.1 c of a 0.2 mm clearance


def _drop(direction, vmax, freq=None):
    d = {"whirl_direction": (direction, None), "DE_vertical_max_m": (vmax, SCALE)}
    if freq is not None:
        d["whirl_frequency_hz"] = (freq, 2.0)
    return d


def _row(rows, name):
    return next(r for r in rows if r["feature"] == name)


def test_a_calm_record_set_is_compared_with_the_calm_drops_of_the_model():
    """4 calm records (vertical maximum 1 um) against a model of 3 calm drops (1 um) and 1 forward
    whirl (200 um): the extreme matches within the calm regime (distance 0, where the mean over all
    four drops put it 50 um = 2.5 scales off), and the whirl row charges the quarter that whirls."""
    records = ensemble_features([_drop("none", 1e-6)] * 4)
    model = ensemble_features([_drop("none", 1e-6)] * 3 + [_drop("forward", 2e-4, 60.0)])
    assert math.isclose(model["DE_vertical_max_m"][0], (3 * 1e-6 + 2e-4) / 4)  # the pooled mean is kept
    g, rows = gap(records, model)
    assert _row(rows, "DE_vertical_max_m")["distance"] == 0.0
    assert math.isclose(_row(rows, "whirl_direction")["distance"], DIRECTION_MISMATCH * 0.25)
    assert math.isclose(g, DIRECTION_MISMATCH * 0.25 / math.sqrt(2))


def test_the_whirl_row_charges_the_distance_between_the_regime_distributions():
    """Records half forward, half calm: a model with the same split is charged nothing (the share
    of the model missing the majority direction charged it 1.5); a calm model is charged the half
    that whirls; one whirling in every drop, the half that is calm."""
    half = [_drop("forward", 2e-4, 60.0)] * 2 + [_drop("none", 1e-6)] * 2
    records = ensemble_features(half)
    assert records["whirl_direction"][0] == "forward"                 # a tie goes to the whirl class
    for model_drops, share_missed in ((half, 0.0), ([_drop("none", 1e-6)] * 4, 0.5),
                                      ([_drop("forward", 2e-4, 60.0)] * 4, 0.5)):
        g, rows = gap(records, ensemble_features(model_drops))
        assert math.isclose(_row(rows, "whirl_direction")["distance"], DIRECTION_MISMATCH * share_missed,
                            abs_tol=1e-12)


def test_within_the_regime_the_extremes_are_still_compared():
    """A model whose calm drops bounce higher than the calm records is charged for it, by the
    calm drops' mean alone (60 um against 1 um: 2.95 scales, softly capped)."""
    records = ensemble_features([_drop("none", 1e-6)] * 4)
    model = ensemble_features([_drop("none", 6e-5)] * 2 + [_drop("none", 6e-5)] * 2)
    _, rows = gap(records, model)
    d = (6e-5 - 1e-6) / SCALE
    assert math.isclose(_row(rows, "DE_vertical_max_m")["distance"], d / (1 + (d / 3.0) ** 4) ** 0.25)


def test_one_record_against_an_ensemble_is_charged_as_before():
    """A single record (no regime shares of its own) against an ensemble: the share of the model's
    drops that miss its direction, and the extremes of the model's drops in its regime."""
    record = _drop("none", 1e-6)
    model = ensemble_features([_drop("none", 1e-6)] * 3 + [_drop("forward", 2e-4, 60.0)])
    _, rows = gap(record, model)
    assert math.isclose(_row(rows, "whirl_direction")["distance"], DIRECTION_MISMATCH * 0.25)
    assert _row(rows, "DE_vertical_max_m")["distance"] == 0.0

"""effects.CATALOGUE (diagnose's candidate effects) is derived from the mechanism registry."""

from rotorlanding.effects import CATALOGUE, DIAGNOSIS
from rotorlanding.mechanisms import REGISTRY, extra_effects
from rotorlanding.scenario import EFFECTS


def test_catalogue_is_every_registry_switch_but_a_mechanisms_own():
    switches = [s for m in REGISTRY for s in m.switches if s != m.effect]
    assert list(CATALOGUE) == list(dict.fromkeys(switches))
    assert set(CATALOGUE) == set(EFFECTS) - set(extra_effects())
    assert "race_windage" in EFFECTS and "race_windage" not in CATALOGUE
    by_name = {m.name: m for m in REGISTRY}
    for name, eff in CATALOGUE.items():
        assert eff.name == name
        assert name in by_name[eff.mechanism].switches
        assert (eff.signature, eff.parameters, eff.fault) == (DIAGNOSIS[name].signature, DIAGNOSIS[name].parameters,
                                                               DIAGNOSIS[name].fault)


def test_search_ranges_are_valid():
    for eff in CATALOGUE.values():
        for p in eff.parameters:
            assert p.keys and 0.0 < p.lower < p.upper

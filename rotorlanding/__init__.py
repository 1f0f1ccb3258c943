"""rotorlanding: rotor drop onto auxiliary (catcher) rolling bearings of AMB machines.

Modules, one concept each:
- ``errors``     : InputError, the one exception type for bad user input.
- ``config``     : TOML loading with ``include`` and dotted ``--set`` overrides.
- ``rotor``      : rotor description (dataclasses) read from TOML, with validation.
- ``from_ross``  : rotors saved by ROSS (or live ``ross.Rotor`` objects) as rotorlanding rotors.
- ``timoshenko`` : Timoshenko beam element and assembly of M, K, G, C of the free rotor.
- ``reduction``  : Craig-Bampton reduction and its error report.
- ``modal``      : damped eigenvalues, whirl labels, Campbell diagram.
- ``analytic``   : closed-form reference frequencies used to verify the FE model.
- ``whirl``      : full-spectrum whirl analysis of orbits.
- ``api``        : the Python API exported here (docs/python_api.md).

Python API (SI units; names say the unit where not SI)::

    import rotorlanding as rl
    sc = rl.Scenario.load("scenarios/landing_7000rpm.toml", set={"operating.t_end": 0.05})
    landing = rl.simulate(sc)          # a Landing: .summary, .whirl, .t [s], ["DE_y_m"], .save()
"""

__version__ = "0.1.0"

from .api import InputError, Landing, Modes, Rotor, Scenario, Series, simulate  # noqa: E402

__all__ = ["Rotor", "Modes", "Scenario", "Landing", "Series", "simulate", "InputError", "__version__"]

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
- ``api``        : the Python API exported here (docs/python_api.md): rotor, scenario, landing.
- ``api_studies``: the API's coast-down, sweep and diagnosis (``coastdown``, ``sweep``,
                   ``diagnose``: functions; their machinery is ``coastdown_run``, ``sweep_run``,
                   ``diagnose_run``).

Python API (SI units; names say the unit where not SI)::

    import rotorlanding as rl
    sc = rl.Scenario.load("scenarios/landing_7000rpm.toml", set={"operating.t_end": 0.05})
    landing = rl.simulate(sc)          # a Landing: .summary, .whirl, .t [s], ["DE_y_m"], .save()
    cd = rl.coastdown("scenarios/coastdown_7000rpm.toml", "cd_out", t_end=1.0)      # a Coastdown
    sw = rl.sweep(sc, "sweep_out", grid={"contact.mu_rad": [0.1, 0.3]})            # a Sweep
    dg = rl.diagnose("scenarios/measured/paper_table2_fig39.toml",
                     "scenarios/paper/forward_whirl_landing.toml", "diag_out")     # a Diagnosis
"""

__version__ = "0.1.0"

from .api import InputError, Landing, Modes, Rotor, Scenario, Series, simulate  # noqa: E402
from .api_studies import Calibration, Coastdown, Diagnosis, Sweep, calibrate, coastdown, diagnose, sweep  # noqa: E402

__all__ = ["Rotor", "Modes", "Scenario", "Landing", "Series", "simulate", "coastdown", "Coastdown", "sweep", "Sweep",
           "diagnose", "Diagnosis", "calibrate", "Calibration", "InputError", "__version__"]

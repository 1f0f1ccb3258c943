"""rotorlanding: rotor drop onto auxiliary (catcher) rolling bearings of AMB machines.

Modules, one concept each:
- ``errors``     : InputError, the one exception type for bad user input.
- ``config``     : TOML loading with ``include`` and dotted ``--set`` overrides.
- ``rotor``      : rotor description (dataclasses) read from TOML, with validation.
- ``timoshenko`` : Timoshenko beam element and assembly of M, K, G, C of the free rotor.
- ``reduction``  : Craig-Bampton reduction and its error report.
- ``modal``      : damped eigenvalues, whirl labels, Campbell diagram.
- ``analytic``   : closed-form reference frequencies used to verify the FE model.
- ``whirl``      : full-spectrum whirl analysis of orbits.
"""

__version__ = "0.1.0"

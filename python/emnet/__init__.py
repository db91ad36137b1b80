"""emnet: lumped electromechanical networks of beams driven by dielectric elastomer actuators.

A scene (a TOML file, text or dict, see docs/scene-reference.md) describes a beam cut into
segments, its DEAs, drive, loads and probes. emnet builds its Firestone-analogy network (force
as current, velocity as voltage) and analyses it. Every function here takes a Scene (or a path)
and returns a Result: a dict with attribute access, numbers along a sweep, time or beam as numpy
arrays, units in the keys' names (x_m, frequency_hz, times_s) or beside the values ("unit"), and
its accuracy, cost and notes; result.to_frame() gives its table as a pandas DataFrame,
result.to_xarray() (ac, tran, sweep_switching) its arrays as an xarray Dataset. Numbers may be
Python's, numpy's or pandas' (scalars, arrays, Series); the package is typed (py.typed).

    >>> import emnet
    >>> fin = emnet.Scene("netlists/fishfin.toml")
    >>> emnet.modes(fin).modes["frequency_hz"][0]          # 6.385... Hz
    >>> stiffer = fin.with_values({"beam.bending_stiffness": 2.4e-3})
    >>> emnet.study(fin, vary=["beam.bending_stiffness=normal(100%,5%)"], samples=100,
    ...             analyses=["modes", "static"])          # a pandas DataFrame

Errors: bad input raises emnet.InputError (a ValueError naming the file, line and key: .where,
.key); a numerical failure raises emnet.NumericalError (a RuntimeError with the reason). No
function returns a NaN as a result (a failed variant of a study is a row with its reason).
Solves release the GIL: calls from several threads run at once and give the same results.
"""

from ._emnet import InputError, NumericalError, __version__
from ._scene import Scene
from ._results import Result
from ._analyses import (ac, crosscheck, identify, mismatch, modes, netlist, sensitivity, static,
                        sweep_switching, tran)
from ._study import study, variants

__all__ = [
    "__version__", "Scene", "Result", "InputError", "NumericalError", "static", "modes", "ac",
    "tran", "sweep_switching", "identify", "sensitivity", "mismatch", "netlist", "crosscheck",
    "study", "variants",
]

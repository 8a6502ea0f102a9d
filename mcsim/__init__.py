"""mcsim: Monte Carlo discrete-asperity simulator for adhesion and adhesional friction.

The public names are imported on first use (PEP 562), so that ``mcsim --help`` and
other light commands do not pay for SciPy, h5py or numba.
"""

import importlib

from ._version import __version__
from .errors import MCSimError, ParameterError, RunFileError, UnitError

_LAZY = {
    "AnalyticCurves": "analytic",
    "gw_curves": "analytic",
    "GAUSSIAN": "distributions",
    "Gaussian": "distributions",
    "HeightDistribution": "distributions",
    "Empirical": "empirical",
    "LAW_SETS": "laws",
    "LawSet": "laws",
    "get_law_set": "laws",
    "Material": "params",
    "Surface": "params",
    "combine_surfaces": "params",
    "plasticity_index": "params",
    "surface_energy_parameter": "params",
    "LoadControl": "loadcontrol",
    "load_control": "loadcontrol",
    "Run": "results",
    "simulate": "simulation",
    "Sweep": "sweeps",
    "sweep": "sweeps",
    "read_run": "runfile",
}

#: Submodules reachable as attributes after a plain ``import mcsim`` (``mcsim.laws.jkr``).
_SUBMODULES = {
    "adhesion",
    "analytic",
    "laws",
    "plotting",
    "presets",
    "results",
    "statistics",
    "sweeps",
    "units",
}

__all__ = [
    "MCSimError",
    "ParameterError",
    "RunFileError",
    "UnitError",
    "__version__",
    *sorted(_LAZY),
]


def __getattr__(name: str):
    if name in _LAZY:
        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    if name in _SUBMODULES:
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'mcsim' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))

"""mcsim: Monte Carlo discrete-asperity simulator for adhesion and adhesional friction.

The public names are imported on first use (PEP 562), so that ``mcsim --help`` and
other light commands do not pay for SciPy, h5py or numba.
"""

import importlib as _importlib

from mcsim._version import __version__
from mcsim.model.errors import MCSimError, ParameterError, RunFileError, UnitError

_LAZY = {
    "AnalyticCurves": "physics.analytic",
    "gw_curves": "physics.analytic",
    "GAUSSIAN": "model.distributions",
    "Gaussian": "model.distributions",
    "HeightDistribution": "model.distributions",
    "Empirical": "topography.empirical",
    "LAW_SETS": "physics.laws",
    "LawSet": "physics.laws",
    "get_law_set": "physics.laws",
    "Material": "model.params",
    "Surface": "model.params",
    "RadiusByHeight": "model.params",
    "combine": "model.counterface",
    "combine_surfaces": "model.params",
    "plasticity_index": "model.params",
    "surface_energy_parameter": "model.params",
    "LoadControl": "physics.loadcontrol",
    "load_control": "physics.loadcontrol",
    "PadReport": "studies.pads",
    "pad_report": "studies.pads",
    "Run": "store.results",
    "simulate": "studies.simulation",
    "Sweep": "store.sweepfile",
    "sweep": "studies.sweeps",
    "read_run": "store.runfile",
    "Report": "studies.report",
    "report": "studies.report",
}

#: Submodules reachable as attributes after a plain ``import mcsim`` (``mcsim.laws.jkr``), by
#: their short names of mcsim 0.2.
_SUBMODULES = {
    "adhesion": "physics.adhesion",
    "analytic": "physics.analytic",
    "laws": "physics.laws",
    "plotting": "figures",
    "presets": "model.presets",
    "results": "store.results",
    "statistics": "engine.statistics",
    "sweeps": "studies.sweeps",
    "units": "model.units",
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
        value = getattr(_importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    if name in _SUBMODULES:
        return _importlib.import_module(f".{_SUBMODULES[name]}", __name__)
    raise AttributeError(f"module 'mcsim' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))

"""mcsim: Monte Carlo discrete-asperity simulator for adhesion and adhesional friction."""

from ._version import __version__
from .analytic import AnalyticCurves, gw_curves
from .distributions import GAUSSIAN, Gaussian, HeightDistribution
from .errors import MCSimError, ParameterError, RunFileError, UnitError
from .laws import LAW_SETS, LawSet, get_law_set
from .params import (
    Material,
    Surface,
    combine_surfaces,
    plasticity_index,
    surface_energy_parameter,
)
from .simulation import Run, simulate

__all__ = [
    "GAUSSIAN",
    "LAW_SETS",
    "AnalyticCurves",
    "Gaussian",
    "HeightDistribution",
    "LawSet",
    "MCSimError",
    "Material",
    "ParameterError",
    "Run",
    "RunFileError",
    "Surface",
    "UnitError",
    "__version__",
    "combine_surfaces",
    "get_law_set",
    "gw_curves",
    "plasticity_index",
    "simulate",
    "surface_energy_parameter",
]

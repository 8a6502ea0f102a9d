"""Analytic Greenwood–Williamson curves (paper, Eqs. 1, 3, 5, 7, 8).

Each total force is N times the expectation of a per-summit law over the summit
heights. Divided by A_n·K (the normalisation that makes Eqs. 3, 5 and 7 consistent;
the paper implies it without stating it):

    X̄(h) = (η / K) ∫_h^∞ X_a(σ(s − h)) p(s) ds,     X ∈ {P, F, T},

with p the standardized height density (Gaussian in the paper). The paper prints the
dimensional load integral of Eq. 3 from 0; it must run from d (from Δ = 0 in its
dimensionless form), which is what is computed here. μ = T̄/(P̄ + F̄) (Eq. 8) and
N_c/N = ∫_h^∞ p(s) ds (Eq. 1).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from .laws import LawSet, get_law_set
from .params import Material, Surface, check_range, check_separations

#: Quantities of a GW curve, in output order, with their meaning.
QUANTITIES = {
    "contact_fraction": "N_c/N, fraction of summits in contact (Eq. 1)",
    "P": "Hertz load P/(A_n K) (Eq. 3)",
    "F": "JKR adhesion term F/(A_n K) (Eq. 5); not a pull-off force",
    "T": "adhesional friction T/(A_n K) (Eq. 7)",
    "mu": "friction coefficient T/(P + F) (Eq. 8)",
}


@dataclass(frozen=True)
class AnalyticCurves:
    """GW curves versus the dimensionless mean separation h = d/σ.

    Attributes
    ----------
    h : ndarray
        Separations d/σ.
    contact_fraction : ndarray
        N_c/N (Eq. 1).
    P, F, T : ndarray
        Load, adhesion term and friction, each divided by A_n·K (Eqs. 3, 5, 7).
    mu : ndarray
        T/(P + F) (Eq. 8); NaN where P + F = 0 (no contact possible).
    surface, material : Surface, Material
        The inputs.
    law : str
        Law-set name.
    """

    h: np.ndarray
    contact_fraction: np.ndarray
    P: np.ndarray
    F: np.ndarray
    T: np.ndarray
    mu: np.ndarray
    surface: Surface
    material: Material
    law: str

    #: Column names of :meth:`table`: each quantity with its normalisation.
    LABELS: ClassVar[dict[str, str]] = {
        "h": "h = d/σ",
        "contact_fraction": "N_c/N",
        "P": "P/(A_n K)",
        "F": "F/(A_n K)",
        "T": "T/(A_n K)",
        "mu": "μ = T/(P + F)",
    }

    def forces(self, area: float) -> dict[str, np.ndarray]:
        """Dimensional totals for a nominal area ``area`` (m², > 0): P, F, T in N and N_c."""
        area = check_range("area", area, "m^2", low=0)
        scale = area * self.material.K
        n = self.surface.eta * area
        return {
            "N_c": n * self.contact_fraction,
            "P": self.P * scale,
            "F": self.F * scale,
            "T": self.T * scale,
        }

    def columns(self) -> dict[str, np.ndarray]:
        """Arrays ``h, contact_fraction, P, F, T, mu`` (dimensionless), by short name."""
        return {"h": self.h, **{q: getattr(self, q) for q in QUANTITIES}}

    def table(self):
        """The curves as a :class:`pandas.DataFrame`, one row per separation.

        Columns, named with their normalisation (all dimensionless): ``h = d/σ``,
        ``N_c/N`` (Eq. 1), ``P/(A_n K)``, ``F/(A_n K)``, ``T/(A_n K)`` (Eqs. 3, 5, 7) and
        ``μ = T/(P + F)`` (Eq. 8).
        """
        import pandas as pd

        return pd.DataFrame({self.LABELS[c]: v for c, v in self.columns().items()})

    def _summary(self) -> tuple[str, list[tuple[str, str]]]:
        from . import _display

        return "GW analytic curves", _display.inputs(self.surface, self.material, self.law, self.h)

    def __repr__(self) -> str:
        from . import _display

        return _display.text(*self._summary())

    def _repr_html_(self) -> str:
        from . import _display

        return _display.table(*self._summary())


def gw_curves(
    surface: Surface,
    material: Material,
    h,
    law: str | LawSet = "seed",
) -> AnalyticCurves:
    """GW curves of a surface and material at separations ``h`` (= d/σ), vectorised.

    Parameters
    ----------
    surface : Surface
        Summit population (σ, R, η and the height distribution).
    material : Material
        Material pair (K, G, γ).
    h : array_like
        Dimensionless separations d/σ: finite, |h| <= 1e6
        (:data:`mcsim.params.MAX_ABS_H`); others raise a ParameterError.
    law : str or LawSet
        Per-summit law set, ``"seed"`` by default (the paper as written).

    Returns
    -------
    AnalyticCurves
        Dimensionless curves; every value finite and non-negative except μ where
        no summit can touch.
    """
    laws = get_law_set(law)
    h = check_separations(h)
    args = laws.arguments(surface, material)
    sigma = surface.sigma

    def integrand(delta: np.ndarray) -> np.ndarray:
        return np.stack([f(sigma * delta, *a) for f, a in zip(laws.laws, args)])

    scale, integral = surface.heights.gw_integrals(integrand, h)
    P, F, T = surface.eta / material.K * scale * integral
    denominator = integral[0] + integral[1]
    with np.errstate(invalid="ignore", divide="ignore"):
        mu = np.where(denominator > 0, integral[2] / denominator, np.nan)
    return AnalyticCurves(
        h=h,
        contact_fraction=np.asarray(surface.heights.sf(h), dtype=float),
        P=P,
        F=F,
        T=T,
        mu=mu,
        surface=surface,
        material=material,
        law=laws.name,
    )

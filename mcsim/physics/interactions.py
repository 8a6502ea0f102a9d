"""Gap-dependent interaction laws between a surface and a flat, per unit area.

Each law is an energy per unit area φ(g) of the local gap g ≥ 0 (J/m²), with φ(0) = −w (w the
work of adhesion) and φ → 0 far apart, and its traction t(g) = −dφ/dg (Pa), negative when
the flat pulls the surface (tensile). :mod:`mcsim.physics.adhesivebem` sums φ over the
pixels of a height map.

* :class:`MaugisDugdale`: a constant tension w/δc within the range δc, nothing beyond (the
  Dugdale law of Maugis, J. Colloid Interface Sci. 150, 243, 1992): φ = −w (1 − g/δc) for
  g < δc, 0 beyond.
* :class:`Exponential`: φ = −w e^{−g/ρ}, the law of the contact-mechanics challenge (Müser
  et al., Tribol. Lett. 65, 118, 2017, Eq. 2) and of Rey, Anciaux & Molinari (Comput.
  Mech. 60, 69, 2017).

The mesh criterion of Wang, Zhou & Müser (Lubricants 9, 17, 2021): a pixel of size Δx
resolves a law whose largest curvature is |φ''| when √(|φ''| Δx / E*) < 0.5
(:func:`mesh_parameter`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mcsim.model.errors import ParameterError

#: Largest mesh parameter √(|φ''| Δx / E*) that resolves a law (Wang, Zhou & Müser 2021).
MESH_LIMIT = 0.5


def _positive(name: str, value: float, unit: str) -> float:
    value = float(value)
    if not (math.isfinite(value) and value > 0):
        raise ParameterError(f"`{name}` must be positive and finite, {unit}, got {value!r}")
    return value


@dataclass(frozen=True)
class MaugisDugdale:
    """Dugdale's constant tension w/δc within the range δc (Maugis 1992).

    Parameters
    ----------
    w : float
        Work of adhesion, J/m², > 0.
    range : float
        Range δc, m, > 0: the tension w/δc acts while the gap is below it.
    """

    w: float
    range: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "w", _positive("w", self.w, "J/m^2"))
        object.__setattr__(self, "range", _positive("range", self.range, "m"))

    @property
    def max_traction(self) -> float:
        """Largest tension w/δc, Pa."""
        return self.w / self.range

    @property
    def max_curvature(self) -> float:
        """w/δc², Pa/m: the curvature of the law smeared over its range (its own is zero
        inside and infinite at the kink), used by the mesh criterion."""
        return self.w / self.range**2

    def energy(self, g: np.ndarray) -> np.ndarray:
        """φ(g) = −w (1 − g/δc) for g < δc, else 0, J/m².

        Parameters
        ----------
        g : array_like
            Gap, m (≥ 0).

        Returns
        -------
        ndarray
        """
        return -self.w * np.maximum(1.0 - np.asarray(g) / self.range, 0.0)

    def pressure(self, g: np.ndarray) -> np.ndarray:
        """Traction −dφ/dg = −w/δc for g < δc, else 0, Pa (negative: tensile).

        Parameters
        ----------
        g : array_like
            Gap, m (≥ 0).

        Returns
        -------
        ndarray
        """
        return np.where(np.asarray(g) < self.range, -self.max_traction, 0.0)


@dataclass(frozen=True)
class Exponential:
    """The exponential law φ = −w e^{−g/ρ} (Müser et al. 2017, Eq. 2).

    Parameters
    ----------
    w : float
        Work of adhesion, J/m², > 0.
    range : float
        Decay length ρ, m, > 0.
    """

    w: float
    range: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "w", _positive("w", self.w, "J/m^2"))
        object.__setattr__(self, "range", _positive("range", self.range, "m"))

    @property
    def max_traction(self) -> float:
        """Largest tension w/ρ (at g = 0), Pa."""
        return self.w / self.range

    @property
    def max_curvature(self) -> float:
        """Largest |φ''| = w/ρ² (at g = 0), Pa/m."""
        return self.w / self.range**2

    def energy(self, g: np.ndarray) -> np.ndarray:
        """φ(g) = −w e^{−g/ρ}, J/m².

        Parameters
        ----------
        g : array_like
            Gap, m (≥ 0).

        Returns
        -------
        ndarray
        """
        return -self.w * np.exp(-np.asarray(g) / self.range)

    def pressure(self, g: np.ndarray) -> np.ndarray:
        """Traction −dφ/dg = −(w/ρ) e^{−g/ρ}, Pa (negative: tensile).

        Parameters
        ----------
        g : array_like
            Gap, m (≥ 0).

        Returns
        -------
        ndarray
        """
        return -self.max_traction * np.exp(-np.asarray(g) / self.range)


Interaction = MaugisDugdale | Exponential


def mesh_parameter(law: Interaction, pixel_size: float, E_star: float) -> float:
    """√(|φ''|max Δx / E*): below :data:`MESH_LIMIT` the pixel resolves the law.

    Wang, Zhou & Müser, Lubricants 9, 17 (2021): the discretised adhesive contact converges
    to the continuum when the interaction's stiffness per pixel, |φ''| Δx, is small against
    the elastic stiffness E*.

    Parameters
    ----------
    law : MaugisDugdale or Exponential
        The interaction (its :attr:`max_curvature`, Pa/m).
    pixel_size : float
        Pixel size Δx, m (the larger side of a rectangular pixel).
    E_star : float
        Contact modulus E*, Pa.

    Returns
    -------
    float
        The mesh parameter, dimensionless.
    """
    return math.sqrt(law.max_curvature * float(pixel_size) / float(E_star))

"""The heights of a rough surface about its mean plane, which the environment needs.

See docs/physics.md, section 'The environment'.

The GW summits (σ_s, R, η) measure the separation from the mean summit plane; van der
Waals and capillary attraction act across the gaps of the whole surface, measured from its
mean plane (:mod:`mcsim.physics.environment`). This module gives the rms height Rq and the
summit plane's offset y_s: as given (a measured map gives both, and its height histogram),
or estimated from the summits by Nayak's (1971) and McCool's (1986) relations. A measured
height histogram (:func:`is_histogram`: an :class:`~mcsim.empirical.Empirical`) is read by the
environment's laws bin by bin, as the gaps of its bins at a mean-plane gap
(:func:`histogram_gaps`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from mcsim.model.counterface import spectral_moments, summits_of


class NayakEstimate(NamedTuple):
    """Heights of a Gaussian GW surface estimated from its summits (:func:`nayak_heights`).

    Attributes
    ----------
    rq : float
        Rms height of the surface about its mean plane √m0, m.
    summit_offset : float
        Mean summit height above the mean plane y_s, m.
    alpha : float
        Bandwidth parameter α = m0 m4/m2² (the relations are asymptotic in α ≫ 1).
    """

    rq: float
    summit_offset: float
    alpha: float


def nayak_heights(sigma, R, eta) -> NayakEstimate:
    """Rq and summit offset of a Gaussian surface from its summits' σ_s, R and η.

    Nayak (1971) and McCool (1986) relations inverted (docs/physics.md, section 'The environment';
    :func:`mcsim.model.counterface.spectral_moments` and :func:`~mcsim.model.counterface.summits_of`):
    m4 = π(0.375/R)², m2 = m4/(6π√3 η), m0 = σ_s² + 0.8968 m2²/m4, α = m0 m4/m2²,
    Rq = √m0, y_s = 4√(m0/(πα)). Rough at the low α (2.5–4.9) of the paper's surfaces.

    Parameters
    ----------
    sigma : float
        Standard deviation of the summit heights σ_s, m.
    R : float
        Mean summit radius of curvature, m.
    eta : float
        Summit density η, m⁻².

    Returns
    -------
    NayakEstimate
    """
    summits = summits_of(*spectral_moments(sigma, R, eta))
    return NayakEstimate(summits.rq, summits.summit_offset, summits.alpha)


class GapHeights(NamedTuple):
    """What the environment needs of a surface (:func:`gap_heights`).

    Attributes
    ----------
    heights : float or Empirical
        Rq of Gaussian heights about the mean plane, m, or the measured height histogram
        (an :class:`~mcsim.topography.empirical.Empirical` in m).
    rq : float
        Rms height about the mean plane, m.
    summit_offset : float
        Height of the mean summit plane above the mean plane y_s, m.
    source : str
        Where the numbers come from: ``"given"``, or ``"Nayak estimate (alpha = ...)"``.
    """

    heights: object
    rq: float
    summit_offset: float
    source: str


def gap_heights(surface) -> GapHeights:
    """Heights about the mean plane and the summit offset of a surface, for the environment.

    ``surface.rq`` and ``surface.summit_offset`` where given (a measured map gives both,
    and its height histogram ``surface.map_heights``); otherwise both from the summits'
    σ, R, η by :func:`nayak_heights` (an estimate: rough at the paper's low α).

    Parameters
    ----------
    surface : mcsim.model.params.Surface
    """
    estimate = None
    if surface.rq is None or surface.summit_offset is None:
        estimate = nayak_heights(surface.sigma, surface.mean_curvature_radius, surface.eta)
    rq = estimate.rq if surface.rq is None else surface.rq
    offset = estimate.summit_offset if surface.summit_offset is None else surface.summit_offset
    source = "given" if estimate is None else f"Nayak estimate (alpha = {estimate.alpha:.3g})"
    heights, shape = rq, surface.map_heights
    if shape is not None:  # a measured histogram in units of rq, made dimensional
        heights = type(shape)(shape.edges, shape.densities, sigma=rq, source=shape.source)
    return GapHeights(heights, rq, offset, source)


def height_histogram(heights) -> tuple[np.ndarray, np.ndarray]:
    """Bin edges (m, about the mean plane) and densities (m⁻¹) of an Empirical-like object."""
    return heights.sigma * heights.edges, heights.densities / heights.sigma


def histogram_gaps(D, heights, cutoff):
    """Per bin of the histogram: the gap interval [g_a, g_b] out of contact, the contact length
    and the density (m⁻¹), with the bins on a new last axis (g_a, g_b >= D0)."""
    edges, density = height_histogram(heights)
    D = np.asarray(D, dtype=float)[..., None]
    g_lo, g_hi = D - edges[1:], D - edges[:-1]
    g_a, g_b = np.maximum(g_lo, cutoff), np.maximum(g_hi, cutoff)
    # The bin's part below the cutoff: exactly 0 for an open bin (the bin's width less its open
    # part, g_b − g_a, would leave D's rounding there, which k(D0)/k(g) then amplifies).
    contact = np.minimum(g_hi, cutoff) - np.minimum(g_lo, cutoff)
    return g_a, g_b, contact, density


def is_histogram(heights) -> bool:
    """Whether ``heights`` is a measured height histogram (an Empirical-like object, with
    ``edges``, ``densities`` and ``sigma``) rather than Gaussian heights' rms Rq (m)."""
    return hasattr(heights, "densities")

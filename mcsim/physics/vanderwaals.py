"""Van der Waals attraction across the gaps of a rough surface (the proximity model of
:mod:`mcsim.physics.environment`).

See docs/physics.md, section 'The environment'.

Between locally flat regions, retarded (:func:`vdw_flat_energy`, :func:`vdw_flat_pressure`):
the energy per area of two flats at gap g, W(g) = A/(12π g²) · 1/(1 + b g), b = 5.32/λ
(Gregory, J. Colloid Interface Sci. 83, 138, 1981: his flat-plate expression), and its
pressure p(g) = −dW/dg; b = 0 (λ None) is the non-retarded A/(12π g²), A/(6π g³)
(Israelachvili, *Intermolecular and Surface Forces*, 3rd ed., Eq. 13.11). Over the heights
z of the surface, g = D − z (DelRio et al., Nature Materials 4, 629, 2005):
p_vdW(D) = E[p(g); g ≥ D0] (:func:`vdw_pressure`), and its work from D_t outward
W_vdW(D_t) = E[W(max(D_t − z, D0))] (:func:`vdw_work`); −dW/dD = p.

Gaussian heights: the means E[p(g); g ≥ D0] and E[W(g); g ≥ D0] by one fixed composite
Gauss–Legendre rule, vectorised over every point (see :func:`_gaussian_gap_moment`).
Histogram heights: an exact integral over each bin (:func:`_gap_moment`).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import special

from mcsim.physics.gapheights import histogram_gaps, is_histogram

# Composite Gauss–Legendre rule on [0, 1] for the Gaussian van der Waals moments:
# _PANELS equal panels of _NODES_PER_PANEL nodes in the mapped variable ξ = τ + ln τ.
_PANELS = 12
_NODES_PER_PANEL = 12
#: The van der Waals moments' Gaussian weight is cut where it has fallen by e^-VDW_TAIL
#: (≈ 1e-26) from its peak (here and in the design map's kernel,
#: :mod:`mcsim.engine.maps.environment`).
VDW_TAIL = 60.0


def _unit_rule() -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss–Legendre nodes and weights on [0, 1]."""
    x, w = np.polynomial.legendre.leggauss(_NODES_PER_PANEL)
    half = 0.5 / _PANELS
    mid = (np.arange(_PANELS) + 0.5) / _PANELS
    return (mid[:, None] + half * x).ravel(), np.tile(half * w, _PANELS)


_NODES, _WEIGHTS = _unit_rule()


def vdw_flat_energy(gap, hamaker, retardation):
    """Retarded van der Waals energy per area of two flats, J/m² (> 0 attractive).

    W(g) = A/(12π g²) · 1/(1 + b g), b = 5.32/λ: Gregory's flat plates (J. Colloid
    Interface Sci. 83, 138, 1981); by Derjaguin (F_sphere = 2πR W) a sphere pulls with
    A R/(6 g²) · 1/(1 + b g). b = 0: the non-retarded A/(12π g²) (Israelachvili,
    *Intermolecular and Surface Forces*, 3rd ed., Eq. 13.11).

    Parameters
    ----------
    gap : array_like
        Gap g between the flats, m (> 0).
    hamaker : array_like
        Hamaker constant A, J.
    retardation : array_like
        b = 5.32/λ, m⁻¹ (:func:`~mcsim.physics.environment.retardation`); 0: non-retarded.

    Returns
    -------
    ndarray
        W, J/m².
    """
    return hamaker / (12 * math.pi) * _energy_kernel(np.asarray(gap, dtype=float), retardation)


def vdw_flat_pressure(gap, hamaker, retardation):
    """Retarded van der Waals pressure between two flats, Pa (> 0 attractive).

    p(g) = −dW/dg of :func:`vdw_flat_energy`:
    (A/12π) [2/(g³(1 + b g)) + b/(g²(1 + b g)²)]; b = 0: A/(6π g³) (Israelachvili Eq. 13.11).

    Parameters
    ----------
    gap, hamaker, retardation
        As for :func:`vdw_flat_energy`.

    Returns
    -------
    ndarray
        p, Pa.
    """
    return hamaker / (6 * math.pi) * _pressure_kernel(np.asarray(gap, dtype=float), retardation)


def _energy_kernel(gap, b):
    """W/(A/12π) = g⁻²/(1 + b g), m⁻² (:func:`vdw_flat_energy`)."""
    return gap**-2 / (1 + b * gap)


def _pressure_kernel(gap, b):
    """p/(A/6π) = g⁻³/(1 + b g) + (b/2) g⁻²/(1 + b g)², m⁻³ (:func:`vdw_flat_pressure`;
    minus half the derivative of :func:`_energy_kernel`)."""
    damping = 1 / (1 + b * gap)
    return gap**-3 * damping + b / 2 * gap**-2 * damping**2


def _gaussian_gap_moment(D, rq, cutoff, n: int, b):
    """E[k_n(g); g >= D0] for g = D − z, z ~ N(0, Rq²), by a fixed quadrature: the retarded
    kernels of :func:`_gap_kernel`, k_3 = p/(A/6π) (m⁻³) and k_2 = W/(A/12π) (m⁻²); with
    b = 0, E[g⁻ⁿ; g >= D0].

    With t = (g − D0)/Rq >= 0 and a = (D − D0)/Rq the integral is
    ∫₀^∞ k_n(D0 + Rq t) φ(a − t) dt. Its two scales, the pole of k_n at g = 0, at
    distance τ = t + D0/Rq from it, and the unit width of the Gaussian, are both resolved
    by the map ξ = τ + ln τ (geometric near the pole, uniform far from it; inverse
    τ = ω(ξ), the Wright omega function, analytic in a strip of half-width π). The
    retardation's pole, at g = −1/b, lies farther from the path than g = 0 and maps to
    Im ξ = π, the strip's edge. The Gaussian is cut where it falls by e^-60, and
    [ξ(t_lo), ξ(t_hi)] is split into equal Gauss–Legendre panels: non-retarded ~1e-14
    relative against 40-digit mpmath over Rq/D0 from 1e-3 to 1e3 and a from −30 to 30
    (tests/physics/test_environment.py). Retarded, against 30-digit mpmath over λ = 1 nm,
    100 nm and none, Rq/D0 = 1e-3, 1, 1e3 and a = −3, 0.5, 30: at worst 2.6e-13 (Rq/D0 =
    1e-3, a = −3, the same with and without retardation), ~1e-14 elsewhere
    (tests/physics/test_environment_retarded.py).
    """
    a = (D - cutoff) / rq
    shift = cutoff / rq
    t_lo = np.maximum(a - math.sqrt(2 * VDW_TAIL), 0.0)
    # Above a the weight φ(a − t) falls by e^-VDW_TAIL at t² − 2 a t = 2 VDW_TAIL
    # (a < 0: steeply).
    t_hi = np.where(
        a >= 0, a + math.sqrt(2 * VDW_TAIL), 2 * VDW_TAIL / (np.sqrt(a * a + 2 * VDW_TAIL) - a)
    )
    tau_lo, tau_hi = t_lo + shift, t_hi + shift
    xi_lo = tau_lo + np.log(tau_lo)
    span = tau_hi + np.log(tau_hi) - xi_lo
    tau = special.wrightomega(xi_lo[..., None] + span[..., None] * _NODES).real
    t = tau - shift[..., None]
    gap = rq[..., None] * tau  # = D0 + Rq t
    density = np.exp(-0.5 * (a[..., None] - t) ** 2) / math.sqrt(2 * math.pi)
    kernel = _gap_kernel(gap, b[..., None], n)
    return span * np.sum(_WEIGHTS * kernel * density * tau / (1 + tau), axis=-1)


def _gap_kernel(gap, b, n: int):
    """The retarded flats' pressure over A/6π (n = 3, :func:`_pressure_kernel`, m⁻³) or
    energy over A/12π (n = 2, :func:`_energy_kernel`, m⁻²) at gap g; g⁻ⁿ for b = 0."""
    return _pressure_kernel(gap, b) if n == 3 else _energy_kernel(gap, b)


def _gap_moment(D, heights, cutoff, n: int, b):
    """E[k_3(g); g >= D0] (n = 3, m⁻³) or E[k_2(max(g, D0))] (n = 2, m⁻²) for g = D − z,
    with the retarded kernels of :func:`_gap_kernel` (b, m⁻¹); g⁻ⁿ for b = 0.

    Histogram: exact over each bin [g_a, g_b] of the piecewise-constant density, written as
    products of h = g_b − g_a (no cancellation for narrow bins), plus k_2(D0) times the
    contact length for n = 2. As −dk_2/dg = 2 k_3, ∫ k_3 dg = (k_2(g_a) − k_2(g_b))/2 =
    h [(g_a + g_b) + b (g_a² + g_a g_b + g_b²)] / [2 g_a² g_b² (1 + b g_a)(1 + b g_b)];
    and ∫ k_2 dg = [−1/g + b ln((1 + b g)/g)] from g_a to g_b =
    h/(g_a g_b) − b ln(1 + h/(g_a (1 + b g_b))), which leaves only rounding, ~(1 + b g_b) ε
    relative (the two terms cancel to 1/(1 + b g_b) of the first): 3e-14 for a bin at 1 µm
    with λ = 100 nm. For b = 0 both are the non-retarded (g_a⁻² − g_b⁻²)/2 and 1/g_a − 1/g_b.
    """
    cutoff = np.asarray(cutoff, dtype=float)
    b = np.asarray(b, dtype=float)
    if is_histogram(heights):
        g_a, g_b, contact, density = histogram_gaps(D, heights, cutoff[..., None])
        h, b = g_b - g_a, b[..., None]
        if n == 3:
            rise = (g_b + g_a) + b * (g_a * g_a + g_a * g_b + g_b * g_b)
            per_bin = h * rise / (2 * g_a**2 * g_b**2 * (1 + b * g_a) * (1 + b * g_b))
        else:
            per_bin = h / (g_a * g_b) - b * np.log1p(h / (g_a * (1 + b * g_b)))
            per_bin = per_bin + contact * _energy_kernel(cutoff[..., None], b)
        return np.sum(density * per_bin, axis=-1)
    D, rq, cutoff, b = np.broadcast_arrays(
        *(np.asarray(x, dtype=float) for x in (D, heights, cutoff, b))
    )
    moment = _gaussian_gap_moment(D, rq, cutoff, n, b)
    if n == 3:
        return moment
    return moment + special.ndtr(-(D - cutoff) / rq) * _energy_kernel(cutoff, b)


def vdw_pressure(D, heights, hamaker, cutoff, retardation):
    """Van der Waals attraction across the non-contacting gaps, Pa (positive: attractive).

    p_vdW(D) = E[p(g); g >= D0], g = D − z, with p the retarded flat–flat pressure
    (:func:`vdw_flat_pressure`; Gregory 1981) (DelRio et al. 2005, non-retarded: b = 0 gives
    (A/6π) E[g⁻³; g >= D0], Israelachvili Eq. 13.11).

    Parameters
    ----------
    D : array_like
        Gap between the mean planes, m.
    heights : array_like or Empirical
        Gaussian heights: their rms Rq, m (> 0, broadcast with ``D``); or a measured
        height histogram (an :class:`~mcsim.empirical.Empirical`: ``edges``,
        ``densities``, ``sigma``), whose bins go on a last axis summed over.
    hamaker : array_like
        Hamaker constant A, J.
    cutoff : array_like
        Cutoff gap D0, m: smaller gaps are contact.
    retardation : array_like
        b = 5.32/λ, m⁻¹ (:func:`~mcsim.physics.environment.retardation`,
        :attr:`mcsim.physics.environment.Environment.retardation`); 0: non-retarded.

    Returns
    -------
    ndarray
        p_vdW, Pa, of the broadcast shape of the arguments.
    """
    return hamaker / (6 * math.pi) * _gap_moment(D, heights, cutoff, 3, retardation)


def vdw_work(D_t, heights, hamaker, cutoff, retardation):
    """Van der Waals work of separation from ``D_t`` to infinity, J/m².

    W_vdW(D_t) = E[W(max(D_t − z, D0))], W the retarded flat–flat energy
    (:func:`vdw_flat_energy`; b = 0: DelRio et al. 2005's Σ A/(12π D_i²));
    −dW/dD = :func:`vdw_pressure`. Flat surfaces at contact: A/(12π D0²)/(1 + b D0).

    Parameters
    ----------
    D_t : array_like
        Mean-plane gap at the closest approach, m.
    heights, hamaker, cutoff, retardation
        As for :func:`vdw_pressure`.

    Returns
    -------
    ndarray
        W_vdW, J/m².
    """
    return hamaker / (12 * math.pi) * _gap_moment(D_t, heights, cutoff, 2, retardation)

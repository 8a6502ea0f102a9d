"""Capillary condensation in the gaps of a rough surface (the proximity model of
:mod:`mcsim.physics.environment`).

See docs/physics.md, section 'The environment'.

Liquid condenses in equilibrium with the vapour: Kelvin radius r_K = γ_L V_m / (R_g T ln(1/RH))
(Kelvin equation, Israelachvili, *Intermolecular and Surface Forces*, 3rd ed., Eq. 17.19;
:func:`mcsim.physics.environment.kelvin_radius`); each face carries an adsorbed film of
thickness t (:mod:`mcsim.physics.films`), liquid bridges the films across the gaps
g < g_K = 2 r_K cos θ + 2t and pulls with the Laplace pressure γ_L/r_K where f ≤ g < g_K,
above the wet floor f = max(D0, 2t) (below it the two films are pressed into each other and
their disjoining pressure balances the pull). Over the heights z of the surface, g = D − z
(DelRio et al., Appl. Phys. Lett. 90, 163104, 2007, with t = 0):
p_cap(D) = (γ_L/r_K) P(f ≤ g < g_K) (:func:`capillary_pressure`) and
W_cap(D_t) = (γ_L/r_K) E[(g_K − max(f, D_t − z))⁺] (:func:`capillary_work`); −dW/dD = p.

Gaussian heights: both in closed form (normal CDFs and densities,
:func:`_gaussian_condensate`). Histogram heights: exact over each bin (:func:`_condensate`).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import special

from mcsim.physics.gapheights import histogram_gaps, is_histogram


def _prob_between(lo, hi):
    """P(lo < X <= hi) for a standard normal X, from the nearer tail (no cancellation)."""
    upper = special.ndtr(-lo) - special.ndtr(-hi)
    return np.where(lo > 0, upper, special.ndtr(hi) - special.ndtr(lo))


def _partial_mean(h):
    """F_1(h) = E[(X − h)⁺] = φ(h) − h Q(h) for a standard normal X and h >= 0 (GW F_1,
    docs/physics.md), as φ(h) (1 − h M(h)) with the Mills ratio M = Q/φ = √(π/2) erfcx(h/√2),
    so the far tail keeps its relative accuracy."""
    mills = math.sqrt(math.pi / 2) * special.erfcx(h / math.sqrt(2))
    return np.exp(-0.5 * h * h) / math.sqrt(2 * math.pi) * (1 - h * mills)


def _gaussian_condensate(D, rq, cutoff, gap_k):
    """P(D0 <= g < g_K) and E[(g_K − max(D0, g))⁺], m, for Gaussian z (closed forms).

    With x = z/Rq, a = (D − D0)/Rq and b = (D − g_K)/Rq < a: the filled fraction is
    Φ(a) − Φ(b), and (g_K − max(D0, D − z))⁺ = Rq [(x − b)⁺ − (x − a)⁺], so the depth is
    Rq [F_1(b) − F_1(a)], evaluated with F_1 at non-negative arguments only
    (F_1(h) = −h + F_1(−h)): for a <= 0 as Rq [a − b + F_1(−b) − F_1(−a)].
    """
    a = (D - cutoff) / rq
    b = (D - gap_k) / rq
    filled = _prob_between(b, a)
    # F_1(h) = max(−h, 0) + F_1(|h|) for either sign (F_1(h) − F_1(−h) = −h).
    depth = np.where(
        a <= 0,
        a - b + _partial_mean(np.abs(b)) - _partial_mean(np.abs(a)),
        np.maximum(-b, 0) + _partial_mean(np.abs(b)) - _partial_mean(np.abs(a)),
    )
    return filled, rq * depth


def _condensate(D, heights, cutoff, gap_k):
    """P(D0 <= g < g_K) and E[(g_K − max(D0, g))⁺] (m) for g = D − z, g_K > D0.

    Histogram: exact over each bin; the filled part [g_a, g_c] (g_c = g_K clipped to the
    bin) adds (g_c − g_a)(2 g_K − g_a − g_c)/2, the contact length times g_K − D0.
    """
    if not is_histogram(heights):
        D, rq, cutoff, gap_k = np.broadcast_arrays(
            *(np.asarray(x, dtype=float) for x in (D, heights, cutoff, gap_k))
        )
        return _gaussian_condensate(D, rq, cutoff, gap_k)
    cutoff = np.asarray(cutoff, dtype=float)[..., None]
    gap_k = np.asarray(gap_k, dtype=float)[..., None]
    g_a, g_b, contact, density = histogram_gaps(D, heights, cutoff)
    g_c = np.clip(gap_k, g_a, g_b)
    filled = np.sum(density * (g_c - g_a), axis=-1)
    depth = (g_c - g_a) * (2 * gap_k - g_a - g_c) / 2 + contact * (gap_k - cutoff)
    return filled, np.sum(density * depth, axis=-1)


def _capillary(D, heights, cutoff, surface_tension, kelvin_radius, contact_angle, film,
               which: int):  # fmt: skip
    """Laplace pressure times the filled fraction (0) or the mean filled depth (1), over the
    band max(D0, 2t) <= g < g_K = 2 r_K cos θ + 2t."""
    r_k = np.asarray(kelvin_radius, dtype=float)
    film = np.asarray(film, dtype=float)
    gap_k = 2 * r_k * np.cos(contact_angle) + 2 * film
    floor = np.maximum(cutoff, 2 * film)
    active = gap_k > floor
    r_safe = np.where(active, r_k, 1.0)
    gap_safe = np.where(active, gap_k, 2 * floor)
    value = _condensate(D, heights, floor, gap_safe)[which]
    return np.where(active, surface_tension / r_safe * value, 0.0)


def capillary_pressure(D, heights, cutoff, surface_tension, kelvin_radius, contact_angle, film=0.0):
    """Capillary attraction of the condensed liquid, Pa (positive: attractive).

    p_cap(D) = (γ_L/r_K) P(f <= g < g_K), g_K = 2 r_K cos θ + 2t, f = max(D0, 2t): Laplace
    pressure on the area whose gap is bridged by liquid between the two adsorbed films of
    thickness t (DelRio et al. 2007 with t = 0), down to the wet floor f, below which the
    films are pressed into each other. Zero where g_K <= f (dry, θ >= 90°, or too little
    vapour to fill any open gap).

    Parameters
    ----------
    D : array_like
        Gap between the mean planes, m.
    heights : array_like or Empirical
        As for :func:`vdw_pressure`.
    cutoff : array_like
        Cutoff gap D0, m.
    surface_tension : array_like
        γ_L, J/m².
    kelvin_radius : array_like
        r_K, m (:func:`~mcsim.physics.environment.kelvin_radius`; 0 when dry).
    contact_angle : array_like
        θ, rad.
    film : array_like
        Adsorbed film t on each face, m (:attr:`mcsim.physics.environment.Environment.film`;
        default 0: no film, the band D0 <= g < 2 r_K cos θ).

    Returns
    -------
    ndarray
        p_cap, Pa, of the broadcast shape of the arguments.
    """
    return _capillary(D, heights, cutoff, surface_tension, kelvin_radius, contact_angle, film, 0)


def capillary_work(D_t, heights, cutoff, surface_tension, kelvin_radius, contact_angle, film=0.0):
    """Capillary work of separation from ``D_t`` to infinity, J/m².

    W_cap(D_t) = (γ_L/r_K) E[(g_K − max(f, D_t − z))⁺]; −dW/dD =
    :func:`capillary_pressure`. Flat surfaces at contact:
    (γ_L/r_K)(g_K − f) = 2γ_L cos θ − γ_L (D0 − 2t)⁺/r_K <= 2γ_L cos θ, the ceiling of
    DelRio et al. 2007, reached once 2t >= D0 (and as RH → 1).

    Parameters
    ----------
    D_t : array_like
        Mean-plane gap at the closest approach, m.
    heights, cutoff, surface_tension, kelvin_radius, contact_angle, film
        As for :func:`capillary_pressure`.

    Returns
    -------
    ndarray
        W_cap, J/m².
    """
    return _capillary(D_t, heights, cutoff, surface_tension, kelvin_radius, contact_angle, film,
                      1)  # fmt: skip

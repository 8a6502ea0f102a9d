"""Intervals of a binomial proportion: k of n pads stick (or slip).

Clopper–Pearson's exact interval (the default: its coverage never falls below the level) and
Wilson's score interval (shorter, its coverage near the level on average), both at
:data:`CONFIDENCE` unless given; and the interval of a weighted (importance-sampling)
estimate on its effective sample size (:func:`effective_clopper_pearson`).
"""

from __future__ import annotations

import math

import numpy as np

from mcsim.model.errors import ParameterError

#: Confidence level of the interval for the probability of sticking.
CONFIDENCE = 0.95

#: Intervals of the probability of sticking, by name.
INTERVALS = ("clopper-pearson", "wilson")


def _check_counts(k, n, confidence) -> None:
    if not (isinstance(n, int | np.integer) and n >= 1):
        raise ParameterError(f"n = {n!r}: the number of trials must be an integer >= 1")
    if not (isinstance(k, int | np.integer) and 0 <= k <= n):
        raise ParameterError(
            f"k = {k!r}: the number of successes must be an integer in [0, n = {n}]"
        )
    if not 0 < confidence < 1:
        raise ParameterError(f"confidence = {confidence!r}: allowed 0 < confidence < 1")


def _beta_ppf(q: float, a: float, b: float) -> float:
    """The q quantile of Beta(a, b): ``scipy.stats.beta.ppf(q, a, b)`` (its ends and NaN
    outside its domain too), by the function of scipy.special (Boost's ibeta_inv) that it
    calls, without importing scipy.stats (≈0.5 s of a command's start). A SciPy without that
    private name (older than 1.12, or a later one that moves it) takes ``beta.ppf`` itself."""
    try:
        from scipy.special._ufuncs import _beta_ppf
    except ImportError:
        from scipy.stats import beta

        return float(beta.ppf(q, a, b))
    if not (a > 0 and b > 0 and 0 <= q <= 1):
        return math.nan
    if q in (0, 1):  # the ends of the support
        return float(q)
    return float(_beta_ppf(q, a, b))


def clopper_pearson(k: int, n: int, confidence: float = CONFIDENCE) -> tuple[float, float]:
    """Clopper–Pearson exact interval of a binomial proportion from k successes in n trials.

    Lower bound: the α/2 quantile of Beta(k, n − k + 1) (0 for k = 0); upper: the
    1 − α/2 quantile of Beta(k + 1, n − k) (1 for k = n), α = 1 − confidence
    (Clopper & Pearson 1934).

    Raises
    ------
    ParameterError
        Unless 0 ≤ k ≤ n, n ≥ 1 and 0 < confidence < 1.
    """
    _check_counts(k, n, confidence)
    alpha = 1 - confidence
    lower = 0.0 if k == 0 else _beta_ppf(alpha / 2, k, n - k + 1)
    upper = 1.0 if k == n else _beta_ppf(1 - alpha / 2, k + 1, n - k)
    return lower, upper


def wilson(k: int, n: int, confidence: float = CONFIDENCE) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion from k successes in n trials.

    (p̂ + z²/(2n) ± z √(p̂(1 − p̂)/n + z²/(4n²))) / (1 + z²/n), p̂ = k/n, z the
    1 − α/2 standard normal quantile, α = 1 − confidence (Wilson 1927; Brown,
    Cai & DasGupta 2001, Sect. 4.1.1). Clipped to [0, 1] against rounding.

    Raises
    ------
    ParameterError
        Unless 0 ≤ k ≤ n, n ≥ 1 and 0 < confidence < 1.
    """
    from scipy.special import ndtri

    _check_counts(k, n, confidence)
    z = float(ndtri(1 - (1 - confidence) / 2))  # scipy.stats.norm.ppf
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return max(0.0, centre - half), min(1.0, centre + half)


def effective_sample_size(q: float, se: float) -> float:
    """The effective number of events n*·q of a weighted estimate ``q`` with standard error
    ``se``, n* = q(1 − q)/se² (the plain trials that would give that standard error;
    :mod:`mcsim.studies.tail`); 0 where n* is undefined."""
    return q * q * (1 - q) / se**2 if se > 0 and 0 < q < 1 else 0.0


def weighted_estimate(y: np.ndarray, n0: int) -> tuple[float, float, float, float]:
    """p̂ = mean(y) of weighted indicators ``y`` (the first ``n0`` from the nominal law), its
    standard error (the sample's, ddof = 1) and 95 % interval (:func:`effective_clopper_pearson`)."""
    q, se = float(np.mean(y)), float(np.std(y, ddof=1) / math.sqrt(y.size))
    k0 = int(np.count_nonzero(y[:n0]))
    return (q, se, *effective_clopper_pearson(q, se, k0, n0))


def effective_clopper_pearson(q: float, se: float, k0: int, n0: int) -> tuple[float, float]:
    """95 % interval of a weighted estimate ``q`` of a probability with standard error ``se``,
    of which ``n0`` pads from the nominal law saw ``k0`` events.

    Clopper–Pearson's (Clopper & Pearson 1934) on the effective sample size
    n* = q(1 − q)/se² with x* = n* q events, non-integer (Korn & Graubard, *Survey
    Methodology* 24, 193, 1998): the 0.025 quantile of Beta(x*, n* − x* + 1) and the 0.975
    one of Beta(x* + 1, n* − x*); for 0/1 values (se² = q(1 − q)/n) it is the plain
    Clopper–Pearson interval of n trials. Where n* is undefined (q is 0 or at least 1, or se
    is 0: no pad in the event, or all weights alike) the plain Clopper–Pearson interval of
    the nominal pads alone, ``k0`` events in ``n0`` trials: they are plain pads, so it holds
    whatever the other laws drew (with no event, [0, 1 − 0.025^(1/n0)] ≈ [0, 3.7/n0];
    :mod:`mcsim.studies.tail`: n0 = ⌈DEFENSIVE · pads⌉).
    """
    if se > 0 and 0 < q < 1:
        n = q * (1 - q) / se**2
        x = q * n
        return _beta_ppf(0.025, x, n - x + 1), _beta_ppf(0.975, x + 1, n - x)
    return clopper_pearson(k0, n0)

"""The bookkeeping of a humid pad's branch and bound, compiled: each gap's bounds and the
points that split it (:class:`mcsim.engine.pads.bounds._Curve`), and the open gaps' spline.

A humid pad's search evaluates a few hundred points in a handful of rounds, and between
rounds bounds every gap between two points and splits those that may still hold the turn
or the pull-off. Written with NumPy, each round is some hundred small array operations,
which cost more than the kernel's sums; here each is one loop over the gaps, compiled by
numba (plain functions, no fast-math: the same arithmetic in the same order as the
formulas of :meth:`~mcsim.engine.pads.bounds._Curve.bounds` and
:meth:`~mcsim.engine.pads.bounds._Curve.split`, where they are proven and documented). This
module is imported at a humid pad's first search, so that importing mcsim loads no numba.
"""

from __future__ import annotations

import math

import numba
import numpy as np

#: The ladder's first step, in tolerances: the gap about its centre is then 0.9 tolerance
#: wide, within it after rounding (at 1/2 it came out a rounding wider, and was split again).
RUNG = 0.45
#: numba options: a float division by zero gives inf or nan as in NumPy; cached on disk.
OPTIONS = {"nogil": True, "error_model": "numpy", "cache": True}


@numba.njit(**OPTIONS)
def environment_bounds(x, caps, gaps, sigma, lo, hi, slope, upper, lower):  # pragma: no cover
    """Start each gap k = [x_k, x_k+1]'s bounds (N, ``upper`` and ``lower``, written) with
    the environment's: the caps' sums ``caps`` at its ends (they attract more the closer)
    and the open gaps' ``gaps`` (N) between their mean ∓ ``slope`` (N per unit h, the
    spline's steepest times the area) times half the gap's width in h, inside the
    spline's range [``lo``, ``hi``] (h); outside it unbounded."""
    for k in range(x.size - 1):
        h0, h1 = x[k] / sigma, x[k + 1] / sigma
        slack = slope * (h1 - h0) / 2 if h0 >= lo and h1 <= hi else np.inf
        mean = (gaps[k] + gaps[k + 1]) / 2
        upper[k] = -caps[k + 1] - (mean - slack)
        lower[k] = -caps[k] - (mean + slack)


@numba.njit(**OPTIONS)
def branch_bounds(
    x, whole, below_a, zs, a, r, m, top, fb, upper, lower, lower_only
):  # pragma: no cover
    """Add to each gap's bounds (N, written) what the summits of one branch can add: their
    contact load ``whole`` at the points ``x`` (m) and the part ``below_a`` of the summits
    between the branch's lowest edge and its falling point ``a``; ``zs`` their sorted
    heights (m); ``r`` the rising point, ``m`` the least value, ``top`` = max(f(a), f(r)),
    ``fb`` = f(r) (:class:`~mcsim.engine.pads.bounds._Branch`). The classes of summits and
    their bounds are those of :meth:`~mcsim.engine.pads.bounds._Curve.bounds`; the counts are
    differences of the numbers of summits at or below x + a and x + r."""
    ra = np.searchsorted(zs, x + a, side="right")
    rr = np.searchsorted(zs, x + r, side="right")
    for k in range(x.size - 1):
        ra_lo, ra_hi, rr_lo, rr_hi = ra[k], ra[k + 1], rr[k], rr[k + 1]
        # lowest: f(δ2) if δ2 <= a; f(δ1) if δ1 > a, less top - m if δ1 <= r; else m
        low = lower[k] + below_a[k] + (whole[k + 1] - below_a[k + 1]) + m * max(ra_hi - ra_lo, 0)
        lower[k] = low - (top - m) * max(rr_hi - ra_hi, 0)
        if lower_only:
            continue
        # highest: f(δ1) for δ1 <= a, f(δ2) for δ2 > r, what the rest can add
        n1 = max(min(ra_hi, rr_lo) - ra_lo, 0)  # in (lo + a, min(hi + a, lo + r)]
        n2 = max(rr_hi - max(ra_hi, rr_lo), 0)  # in (max(hi + a, lo + r), hi + r]
        n3 = max(ra_hi - rr_lo, 0)  # in (lo + r, hi + a]
        n4 = max(rr_lo - ra_hi, 0)  # in (hi + a, lo + r]
        above_r = (whole[k] - below_a[k]) - m * max(rr_lo - ra_lo, 0)  # f >= m in (a, r]
        high = upper[k] + below_a[k + 1] + above_r + (top - m) * n1
        upper[k] = high + max(top - fb, 0.0) * n2 + (top - 2 * m) * n3 + top * n4


@numba.njit(**OPTIONS)
def split_points(
    a, b, fa, fb, change, cuts, side, sides, force, tol, parts, even, ladder
):  # pragma: no cover
    """The points that split each gap [``a``, ``b``] (m), as
    :meth:`~mcsim.engine.pads.bounds._Curve.split` describes: at up to ``parts`` − 1 of the
    sorted ``cuts`` (m) more than 2·``side`` (m) inside it, evenly by rank, ``side`` below
    each (``sides`` = 1) or on either side of each (2); with none, where the net load
    (``fa``, ``fb`` at its ends, N) crosses ``force`` (N; NaN: no force), on a ladder about
    where a straight line crosses it, its ratio from how fast the load changes against how
    much its parts do (``change``, N), within ``ladder``, its first step :data:`RUNG` times
    the tolerance ``tol`` (m); else evenly into ``even`` parts."""
    n_gaps = a.size
    first = np.searchsorted(cuts, a + 2 * side, side="right")
    count = np.searchsorted(cuts, b - side, side="left") - first
    size = 0
    for g in range(n_gaps):
        rungs = _rungs(b[g] - a[g], tol, ladder[0])  # the ratio is at least ladder[0]
        size += sides * (parts - 1) if count[g] > 0 else even + 2 * rungs
    out = np.empty(size)
    n = 0
    for g in range(n_gaps):
        if count[g] > 0:  # the cuts inside, evenly by rank, each once
            previous = -1
            for j in range(parts - 1):
                pick = first[g] + int(np.round(j / (parts - 2) * (count[g] - 1)))
                if pick != previous:
                    out[n] = cuts[pick] - side
                    if sides == 2:
                        out[n + 1] = cuts[pick] + side
                    n += sides
                    previous = pick
        elif (fa[g] - force) * (fb[g] - force) < 0:  # a ladder about the crossing
            x = a[g] + (b[g] - a[g]) * (fa[g] - force) / (fa[g] - fb[g])
            ratio = min(max(1 + abs(fb[g] - fa[g]) / (2 * change[g]), ladder[0]), ladder[1])
            for k in range(_rungs(b[g] - a[g], tol, ratio)):
                step = RUNG * tol * ratio ** float(k)
                for point in (x - step, x + step):
                    if a[g] < point < b[g]:
                        out[n] = point
                        n += 1
        else:
            for j in range(1, even):
                out[n] = a[g] + (b[g] - a[g]) * (j / even)
                n += 1
    return out[:n]


@numba.njit(**OPTIONS)
def _rungs(width, tol, ratio):  # pragma: no cover
    """Steps of a ladder (:data:`RUNG`·tol·ratio^k, k = 0, 1, ...) until they reach ``width``:
    one in a gap no wider than ``tol`` (or not a number)."""
    if not width > tol:
        return 1
    return math.ceil(math.log(width / tol) / math.log(ratio)) + 1


@numba.njit(**OPTIONS)
def piecewise(grid, c, h):  # pragma: no cover
    """The piecewise polynomial of knots ``grid`` and coefficients ``c`` (one row per piece,
    highest power first, in t = h − knot) at each ``h`` (1-D), by Horner's rule; below and
    above the knots, the end pieces (:func:`mcsim.engine.pads.load.open_gaps`)."""
    out = np.empty(h.size)
    inner = grid[1:-1]
    for i in range(h.size):
        k = np.searchsorted(inner, h[i], side="right")
        t = h[i] - grid[k]
        value = c[k, 0]
        for j in range(1, c.shape[1]):
            value = value * t + c[k, j]
        out[i] = value
    return out

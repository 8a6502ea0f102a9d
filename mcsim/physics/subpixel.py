"""Bilinear interpolation of pixel-centre values to k × k points a pixel, and its transpose.

The sub-pixel quadrature of :mod:`mcsim.physics.adhesivebem` evaluates an interaction law
at the midpoints of each pixel's k × k sub-squares, at offsets s_a = (a + ½)/k − ½ pixels
from its centre (a = 0 … k − 1), on the bilinear interpolant of the pixel-centre gaps
(B g); its traction is Bᵀ applied to the law's derivative there. A point interpolates
between its pixel's centre and the neighbour on its side, with weights 1 − |s| and |s| along
each axis: the tensor product of two linear interpolations. Beyond the map's edge the edge
pixel stands in for the missing neighbour (``wrap`` False) or the map repeats (``wrap``).
Every column of B then sums to k² (each pixel's weights over its own points and its
neighbours' add up to k along each axis), so a law linear over a pixel and its neighbours
gives the pixel-centre result again.

Compiled by numba (plain loops, which the interpreter also runs, e.g. with
``NUMBA_DISABLE_JIT=1``), in their own module so that numba is imported only when a solve
asks for sub-pixel quadrature and its on-disk cache (``cache=True``) applies.
"""

import numba
import numpy as np


@numba.njit(cache=True)
def _weights(n: int, k: int, wrap: bool) -> tuple[np.ndarray, np.ndarray]:  # pragma: no cover
    """For each of the n k points along an axis, its neighbour pixel's index and weight |s|
    (the point's own pixel has weight 1 − |s|)."""
    side, weight = np.empty(n * k, dtype=np.int64), np.empty(n * k)
    for i in range(n):
        for a in range(k):
            s = (a + 0.5) / k - 0.5
            j = i + 1 if s > 0 else i - 1
            side[i * k + a] = j % n if wrap else min(max(j, 0), n - 1)
            weight[i * k + a] = abs(s)
    return side, weight


@numba.njit(cache=True)
def spread(g: np.ndarray, k: int, wrap: bool) -> np.ndarray:  # pragma: no cover - compiled
    """B g: values g (n, m) at the pixel centres interpolated to the k × k points of each
    pixel, shape (n k, m k) (point (a, b) of pixel (i, j) at row i k + a, column j k + b)."""
    n, m = g.shape
    rows, row_w = _weights(n, k, wrap)
    cols, col_w = _weights(m, k, wrap)
    out = np.empty((n * k, m * k))
    line = np.empty(m)
    for r in range(n * k):
        i, ia, wa = r // k, rows[r], row_w[r]
        for j in range(m):
            line[j] = (1.0 - wa) * g[i, j] + wa * g[ia, j]
        for c in range(m * k):
            wb = col_w[c]
            out[r, c] = (1.0 - wb) * line[c // k] + wb * line[cols[c]]
    return out


@numba.njit(cache=True)
def gather(t: np.ndarray, k: int, wrap: bool) -> np.ndarray:  # pragma: no cover - compiled
    """Bᵀ t: values t (n k, m k) at the sub-pixel points summed back onto the pixels (n, m)
    with the interpolation's weights, so that ∂/∂g Σ φ(B g) = Bᵀ φ'(B g)."""
    n, m = t.shape[0] // k, t.shape[1] // k
    rows, row_w = _weights(n, k, wrap)
    cols, col_w = _weights(m, k, wrap)
    out = np.zeros((n, m))
    line = np.empty(m)
    for r in range(n * k):
        i, ia, wa = r // k, rows[r], row_w[r]
        line[:] = 0.0
        for c in range(m * k):
            wb, v = col_w[c], t[r, c]
            line[c // k] += (1.0 - wb) * v
            line[cols[c]] += wb * v
        for j in range(m):
            out[i, j] += (1.0 - wa) * line[j]
            out[ia, j] += wa * line[j]
    return out

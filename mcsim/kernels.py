"""Per-block partial sums of the per-summit laws over a grid of separations.

A block is a set of summit heights; the result is, for each separation d_j, the
number of contacting summits and the sums of the three forces, their squares and
their pairwise products (the moments the standard errors need). Two
implementations with one contract:

* :func:`block_sums_numpy`: the reference, a plain NumPy loop over separations
  calling the law set's vectorised functions;
* :func:`block_sums`: the fused kernel, the *same* law functions compiled by numba
  and evaluated only on contacting (summit, separation) pairs, one pass per summit.

Tests check the two against each other on random populations.
"""

from __future__ import annotations

import functools

import numpy as np

from .laws import LawSet

#: Columns of a block-sum array, in order (forces in N).
SUM_COLUMNS = ("n_contact", "P", "F", "T", "PP", "FF", "TT", "PF", "PT", "FT")


def _moments(p: np.ndarray, f: np.ndarray, t: np.ndarray) -> list[float]:
    return [p.size, p.sum(), f.sum(), t.sum(), p @ p, f @ f, t @ t, p @ f, p @ t, f @ t]


def block_sums_numpy(z: np.ndarray, d: np.ndarray, law: LawSet, args) -> np.ndarray:
    """Reference partial sums: for each separation, mask the contacting summits and sum.

    Parameters
    ----------
    z : ndarray
        Summit heights above the mean summit plane, m.
    d : ndarray
        Separations, m, any order.
    law : LawSet
        The per-summit laws.
    args : tuple of tuple
        ``law.arguments(surface, material)``.

    Returns
    -------
    ndarray, shape (len(d), 10)
        Columns :data:`SUM_COLUMNS`.
    """
    out = np.empty((d.size, len(SUM_COLUMNS)))
    for j, dj in enumerate(d):
        delta = z[z > dj] - dj
        p, f, t = (fn(delta, *a) for fn, a in zip(law.laws, args))
        out[j] = _moments(p, f, t)
    return out


@functools.cache
def _compiled(law: LawSet):
    """Fused kernel for one law set, built by numba from the law set's own functions."""
    import numba

    load, adhesion, friction = (numba.njit(fn) for fn in law.laws)

    @numba.njit(nogil=True)
    def kernel(z, d_desc, out, a_load, a_adh, a_fric):
        neg_d = -d_desc  # ascending
        m = d_desc.size
        for i in range(z.size):
            zi = z[i]
            # contacts where d_j < z_i: indices k..m-1 of the descending grid
            k = np.searchsorted(neg_d, -zi, side="right")
            for j in range(k, m):
                delta = zi - d_desc[j]
                p = load(delta, *a_load)
                f = adhesion(delta, *a_adh)
                t = friction(delta, *a_fric)
                row = out[j]
                row[0] += 1.0
                row[1] += p
                row[2] += f
                row[3] += t
                row[4] += p * p
                row[5] += f * f
                row[6] += t * t
                row[7] += p * f
                row[8] += p * t
                row[9] += f * t

    return kernel


def block_sums(z: np.ndarray, d_desc: np.ndarray, law: LawSet, args) -> np.ndarray:
    """Fused partial sums (same contract as :func:`block_sums_numpy`, ``d`` descending).

    Summits are visited in order and each contributes only to the separations it
    touches, so the work is the number of contacting pairs and the summation order
    is fixed by the order of ``z``: the result is bit-reproducible.
    """
    if d_desc.size > 1 and np.any(np.diff(d_desc) > 0):
        raise ValueError("d_desc must be sorted in descending order")
    out = np.zeros((d_desc.size, len(SUM_COLUMNS)))
    _compiled(law)(
        np.ascontiguousarray(z, dtype=float), np.ascontiguousarray(d_desc, dtype=float), out, *args
    )
    return out

"""Summit heights drawn on the GPU (:mod:`mcsim.engine.cuda`): Philox4x32-10 and the sampler.

Heights are drawn by Philox4x32-10 (Salmon, Moraes, Dror & Shaw, SC'11) keyed by (seed,
realization) with the counter (summit, block, stream), so that a summit's height depends
on nothing else: :data:`PHILOX` is the source of the device functions the kernel compiles
(plain Python too: the tests run it against Random123's known answers),
:func:`philox_key` the key of a realization and :func:`height_sampler` the kernel's
arguments for a Gaussian or a histogram of heights.
"""

from __future__ import annotations

import numpy as np

from mcsim.model.errors import ParameterError

#: Stream tag of the heights in the Philox counter.
HEIGHTS = 1

#: Source of ``_philox``, ``_unit`` and ``_height``, run in the kernel's namespace (``np``,
#: ``HEIGHTS`` and ``_ndtri``, the normal quantile, bound there).
PHILOX = '''
_M0 = np.uint64(0xD2511F53)
_M1 = np.uint64(0xCD9E8D57)
_W0 = np.uint64(0x9E3779B9)
_W1 = np.uint64(0xBB67AE85)
_MASK = np.uint64(0xFFFFFFFF)
_S32 = np.uint64(32)
_S20 = np.uint64(20)
_S12 = np.uint64(12)
_ULP = 2.0 ** -52


def _philox(c0, c1, c2, c3, k0, k1):
    """Philox4x32-10 of the counter (c0..c3) under the key (k0, k1), 32-bit words held
    in uint64 (Salmon, Moraes, Dror & Shaw, SC'11; Random123's kat_vectors)."""
    for _ in range(10):
        p0 = _M0 * c0
        p1 = _M1 * c2
        c0, c1, c2, c3 = (p1 >> _S32) ^ c1 ^ k0, p1 & _MASK, (p0 >> _S32) ^ c3 ^ k1, p0 & _MASK
        k0 = (k0 + _W0) & _MASK
        k1 = (k1 + _W1) & _MASK
    return c0, c1, c2, c3


def _unit(hi, lo):
    """Uniform in (0, 1) from 52 bits x of two words: (x + 1/2) 2^-52, exact in double
    (53 bits would round the largest to 1)."""
    return (float((hi << _S20) | (lo >> _S12)) + 0.5) * _ULP


def _height(i, block, k0, k1, dist, tail, cum, lo, hi):
    """Standardized height of summit i of a block: Gaussian above s_min by the inverse
    CDF of its upper tail (s = −Φ⁻¹(u·P(S > s_min))), or a histogram bin chosen by its
    mass above s_min and a uniform point in it (as Empirical.sample_above)."""
    w0, w1, w2, w3 = _philox(np.uint64(i), np.uint64(block), np.uint64(HEIGHTS), np.uint64(0), k0, k1)
    u = _unit(w0, w1)
    if dist == 0:
        return -_ndtri(u * tail)
    a, b = 0, cum.size
    while a < b:  # first bin whose cumulative mass exceeds u
        mid = (a + b) // 2
        if cum[mid] > u:
            b = mid
        else:
            a = mid + 1
    k = min(a, cum.size - 1)
    return hi[k] - (hi[k] - lo[k]) * _unit(w2, w3)
'''


def philox_key(entropy: int, realization: int) -> tuple[int, int]:
    """The Philox key of a realization: two 32-bit words from
    ``SeedSequence(entropy, spawn_key=(realization, 0xC0DA))``."""
    seq = np.random.SeedSequence(entropy, spawn_key=(realization, 0xC0DA))
    k0, k1 = seq.generate_state(2, np.uint32)
    return int(k0), int(k1)


def height_sampler(heights, s_min: float) -> tuple:
    """Kernel arguments drawing standardized heights above ``s_min``:
    ``(dist, tail, cum, lo, hi)``. Gaussian (``dist`` 0, ``tail`` = P(S > s_min)) or a
    histogram (``dist`` 1, :class:`mcsim.topography.empirical.Empirical`)."""
    name = getattr(heights, "name", None)
    if name == "gaussian":
        tail = float(heights.sf(s_min)) if s_min > -np.inf else 1.0
        return 0, tail, np.zeros(1), np.zeros(1), np.zeros(1)
    if name == "empirical":
        lo = np.maximum(heights.edges[:-1], s_min)
        hi = np.ascontiguousarray(heights.edges[1:])
        mass = heights.densities * np.clip(hi - lo, 0.0, None)
        if not mass.sum() > 0:
            raise ParameterError(f"no summit heights above s = {s_min:g}")
        return 1, 1.0, np.cumsum(mass) / mass.sum(), np.ascontiguousarray(lo), hi
    raise ParameterError(
        f"device = 'cuda' samples gaussian or empirical heights, not {name!r}; use device = 'cpu'"
    )

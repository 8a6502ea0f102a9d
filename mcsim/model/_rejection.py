"""Compiled rejection sampler for the Gaussian truncated to s > s_min (s_min ≤ 0).

Kept in its own module so that numba's on-disk cache (``cache=True``) applies and
numba is imported only when the Monte Carlo engine samples.
"""

import numba


@numba.njit(nogil=True, cache=True)
def truncated_standard_normal(rng, s_min, out):  # pragma: no cover - compiled
    """Fill ``out`` with standard normal draws above ``s_min`` (acceptance S(s_min) ≥ ½)."""
    i = 0
    while i < out.size:
        x = rng.standard_normal()
        if x > s_min:
            out[i] = x
            i += 1
    return out

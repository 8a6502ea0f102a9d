"""The bits of a binary64 number, for law functions that index tables by them.

See docs/physics.md, section 'Maugis-Dugdale law set' (the table these bits index).

A positive double y = 2^(e − 1023) (1 + f/2^52) has the bits e·2^52 + f (IEEE 754), so
its top bits are a piecewise-linear approximation of log2 y: a table on a geometric
grid is indexed by a shift of them, with no logarithm, root or division
(:mod:`mcsim.physics.laws.maugis_dugdale`).

Law functions may call these two functions besides ``np`` (:mod:`mcsim.physics.laws`): as
written they are NumPy (arrays or scalars); the CPU kernel compiles each call to one
LLVM bitcast (:mod:`mcsim.engine.kernels`, an inline numba overload, since numba's own
scalar ``.view`` is an out-of-line call that keeps LLVM from vectorising the loop
around it), and the GPU kernel to CUDA's ``__double_as_longlong`` and
``__longlong_as_double`` (:mod:`mcsim.engine.cuda`).
"""

from __future__ import annotations

import numpy as np


def float_bits(x):
    """The bits of binary64 ``x`` as a signed 64-bit integer (array or scalar)."""
    return np.asarray(x, dtype=np.float64).view(np.int64)[()]


def bits_float(b):
    """The binary64 number whose bits are the 64-bit integer ``b`` (array or scalar)."""
    return np.asarray(b, dtype=np.int64).view(np.float64)[()]


#: The functions above, which law functions may call.
HELPERS = (float_bits, bits_float)

"""Per-block partial sums of a law set's outputs over rows of separations.

A block is a set of summit heights; a *row* is a separation d_j with the closest
approach d_turn_j before it (d_turn_j = d_j on approach, the turn on retraction).
The result is, for each row, the number of summits in contact and the sums of the
law set's outputs, their squares and their pairwise products (the moments the
standard errors need; columns :func:`sum_columns`). Two implementations with one
contract:

* :func:`block_sums_numpy`: the reference, a plain NumPy loop over rows calling the
  law set's vectorised functions;
* :func:`block_sums`: the fused kernel, the *same* law functions compiled by numba
  and evaluated only on (summit, row) pairs that can carry force: z above the row's
  threshold :meth:`mcsim.physics.laws.Edges.threshold`.

Tests check the two against each other on random populations.

The kernel is plain numba code, as the design map's (:mod:`mcsim.engine.maps.kernel`): one
sweep (:func:`_kernel`) specialised for a law set by the compiled functions it closes over:
the laws, each called through an adapter that reads its parameters from the argument
tuple (:func:`_outputs`, :data:`_STATELESS`), and the sums of the moments as a tuple
(:func:`_accumulate`); numba inlines all of them into the sweep's loop, which LLVM then
vectorises. It is compiled once per process and law set, and cached on disk, stamped with
the laws' sources (:func:`_cache`).
"""

from __future__ import annotations

import functools
import hashlib
import inspect
import os
import sys
import threading
from pathlib import Path

import numpy as np

from mcsim.physics.laws import Edges, LawSet, Output, helpers

#: Columns of a block-sum array of the seed law set, in order (forces in N).
SUM_COLUMNS = ("n_contact", "P", "F", "T", "PP", "FF", "TT", "PF", "PT", "FT")

_TOUCHING = Edges()


@functools.lru_cache(maxsize=64)
def sum_columns(law: LawSet) -> tuple[str, ...]:
    """Columns of a block-sum array: ``n_contact``, Σ of each output, Σ of each output
    squared, then the cross products of outputs i < j in lexicographic order of (i, j).

    For the seed law set this is :data:`SUM_COLUMNS`.
    """
    names = law.names
    pairs = [(a, b) for i, a in enumerate(names) for b in names[i + 1 :]]
    return ("n_contact", *names, *(n + n for n in names), *(a + b for a, b in pairs))


def _power(unit: str, k: int) -> str:
    """``unit`` to the power ``k`` (``N`` → ``N^2``, ``m^2`` → ``m^4``)."""
    if unit == "1":
        return unit
    base, _, exponent = unit.partition("^")
    return f"{base}^{int(exponent or 1) * k}"


def sum_units(law: LawSet) -> tuple[str, ...]:
    """Unit of each of :func:`sum_columns`: ``1`` for the count, the outputs' units, their
    squares and products (the seed: ``1``, ``N`` ×3, ``N^2`` ×6)."""
    units = [o.unit for o in law.outputs]
    pairs = [(a, b) for i, a in enumerate(units) for b in units[i + 1 :]]
    return ("1", *units, *(_power(u, 2) for u in units),
            *(_power(a, 2) if a == b else f"{a} {b}" for a, b in pairs))  # fmt: skip


def _moments(values: list[np.ndarray], n_contact: int) -> list[float]:
    k = len(values)
    pairs = [(i, j) for i in range(k) for j in range(i + 1, k)]
    return [n_contact, *(v.sum() for v in values), *(v @ v for v in values),
            *(values[i] @ values[j] for i, j in pairs)]  # fmt: skip


def _rows(d, d_turn) -> tuple[np.ndarray, np.ndarray]:
    d = np.ascontiguousarray(d, dtype=float)
    if d_turn is None:  # approach
        if d.ndim != 1:
            raise ValueError("d must be a 1-D array")
        return d, d
    d_turn = np.ascontiguousarray(d_turn, dtype=float)
    if d_turn.shape != d.shape or d.ndim != 1:
        raise ValueError("d and d_turn must be 1-D arrays of the same length")
    if np.any(d_turn > d):
        raise ValueError("d_turn must not exceed d (the turn is the closest approach)")
    return d, d_turn


def block_sums_numpy(
    z: np.ndarray, d: np.ndarray, law: LawSet, args, *, d_turn=None, edges: Edges | None = None
) -> np.ndarray:
    """Reference partial sums: for each row, mask the summits that can carry force and sum.

    Parameters
    ----------
    z : ndarray
        Summit heights above the mean summit plane, m.
    d : ndarray
        Separations of the rows, m, any order.
    law : LawSet
        The per-summit laws.
    args : tuple of tuple
        ``law.arguments(surface, material)``.
    d_turn : ndarray, optional
        Closest approach before each row, m (``d_turn <= d``); ``d`` (approach) by default.
    edges : Edges, optional
        ``law.edges_for(surface, material)``; all zero (the seed's) by default.

    Returns
    -------
    ndarray, shape (len(d), len(sum_columns(law)))
        Columns :func:`sum_columns`: summits in contact, then sums of the outputs in
        their units (N, m², ...), their squares and pairwise products.
    """
    d, d_turn = _rows(d, d_turn)
    edges = _TOUCHING if edges is None else edges
    out = np.empty((d.size, len(sum_columns(law))))
    for j, (dj, tj) in enumerate(zip(d, d_turn)):
        zj = z[z > edges.threshold(dj, tj)]
        delta, delta_max = zj - dj, zj - tj
        values = [
            np.asarray(o.law(delta, delta_max, *a) if o.stateful else o.law(delta, *a), float)
            for o, a in zip(law.outputs, args)
        ]
        n_contact = int(np.count_nonzero(edges.in_contact(delta, delta_max)))
        out[j] = _moments(values, n_contact)
    return out


#: Most rows for which the kernel finds each summit's first row by counting the thresholds
#: it lies under (a branch-free loop that LLVM vectorises) rather than by bisection, whose
#: mispredicted branches cost more below about 200 rows (measured: 51 rows, 55 000 summits,
#: 0.3 ms against 1.5 ms). Both give the same index, so the sums do not depend on it.
LINEAR_ROWS = 128


def cache_dir() -> Path:
    """Folder of numba's caches of the kernels: ``$MCSIM_CACHE_DIR``, else
    ``$XDG_CACHE_HOME/mcsim``, else ``~/.cache/mcsim``."""
    if "MCSIM_CACHE_DIR" in os.environ:
        return Path(os.environ["MCSIM_CACHE_DIR"])
    return Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "mcsim"


_COMPILE_LOCK = threading.Lock()


def _counting(law: LawSet, edges: Edges) -> bool:
    """Whether the kernel must count the pairs in contact (see :func:`_kernel`)."""
    return law.stateful or (edges.reach, edges.jump_in, edges.break_off) != (0.0, 0.0, 0.0)


def _compiled(law: LawSet, counting: bool = False):
    """The fused kernel of a law set (:func:`_kernel`), built once per process.

    The code depends on the outputs' functions only, not on the parameters' values (a law
    set with an environment is made anew for each environment). The lock makes worker
    threads that start together wait for one build.
    """
    with _COMPILE_LOCK:
        return _kernel(law.outputs, law.legacy_kernel, counting, LINEAR_ROWS)


#: Options of the law functions inside a kernel other than the legacy one: a float division
#: by zero gives inf or nan as in NumPy instead of raising ZeroDivisionError, whose check
#: would keep LLVM from vectorising the loop over summits (the laws never divide by zero
#: where the edges let them act), and each is inlined into the sweep by numba (LLVM's
#: inliner leaves larger laws such as elastic-plastic out of line, which also blocks
#: vectorisation). The legacy kernel compiles them with numba's defaults.
LAW_OPTIONS = {"error_model": "numpy", "inline": "always"}


def _sweep_options(legacy: bool) -> dict:
    """numba options of the sweep: fast-math sums (LLVM may reorder them, in a fixed way,
    to vectorise). Outside the legacy kernel the law functions are inlined into the sweep
    (:data:`LAW_OPTIONS`), so these flags also apply to their arithmetic: LLVM may contract
    and reorder it at the rounding level, and ``nnan`` lets ``np.maximum`` and
    ``np.minimum`` compile to plain max/min, since the laws are finite for every finite
    input (:mod:`mcsim.physics.laws`)."""
    if legacy:
        return {"nogil": True, "fastmath": {"reassoc", "contract", "nsz"}}
    return {"nogil": True, "fastmath": {"reassoc", "contract", "nsz", "nnan"},
            "error_model": "numpy"}  # fmt: skip


@functools.cache
def _parameters(outputs: tuple[Output, ...], legacy: bool):
    """The kernel's parameters: the (output, position) in the argument tuples of each, and
    for each output the indices of its own among them. The legacy kernel takes every
    output's tuple whole; otherwise a parameter several outputs take is passed once, so
    that LLVM sees the same value and computes the work the outputs share once (the JKR
    inversion behind both load and area)."""
    where: dict[object, int] = {}
    positions, indices = [], []
    for i, o in enumerate(outputs):
        own = []
        for j, p in enumerate(o.parameter_names):
            key = (i, j) if legacy else p
            if key not in where:
                where[key] = len(positions)
                positions.append((i, j))
            own.append(where[key])
        indices.append(tuple(own))
    return tuple(positions), tuple(indices)


def _terms(k: int) -> tuple[tuple[int, int], ...]:
    """The summands of the moments of ``k`` outputs o, in the order of :func:`sum_columns`
    after ``n_contact``: o_i·o_j for each (i, j), where o_k = 1 (the sum of o_i itself)."""
    pairs = [(i, j) for i in range(k) for j in range(i + 1, k)]
    return (*((i, k) for i in range(k)), *((i, i) for i in range(k)), *pairs)


#: ``call(f, *k)``: a function of (δ, δ_max, u) that calls law ``f`` with δ and its
#: parameters ``u[k]``, one for each number of parameters (numba inlines no call with
#: ``*args``, and the laws are inlined into the kernel); ``_STATEFUL`` the same with δ_max.
_STATELESS = (
    lambda f: lambda x, y, u: f(x),
    lambda f, k0: lambda x, y, u: f(x, u[k0]),
    lambda f, k0, k1: lambda x, y, u: f(x, u[k0], u[k1]),
    lambda f, k0, k1, k2: lambda x, y, u: f(x, u[k0], u[k1], u[k2]),
    lambda f, k0, k1, k2, k3: lambda x, y, u: f(x, u[k0], u[k1], u[k2], u[k3]),
    lambda f, k0, k1, k2, k3, k4: lambda x, y, u: f(x, u[k0], u[k1], u[k2], u[k3], u[k4]),
    lambda f, k0, k1, k2, k3, k4, k5: lambda x, y, u: f(x, u[k0], u[k1], u[k2], u[k3], u[k4],
                                                        u[k5]),
    lambda f, k0, k1, k2, k3, k4, k5, k6: lambda x, y, u: f(x, u[k0], u[k1], u[k2], u[k3],
                                                            u[k4], u[k5], u[k6]),
    lambda f, k0, k1, k2, k3, k4, k5, k6, k7: lambda x, y, u: f(x, u[k0], u[k1], u[k2], u[k3],
                                                                u[k4], u[k5], u[k6], u[k7]),
    lambda f, k0, k1, k2, k3, k4, k5, k6, k7, k8: lambda x, y, u: f(
        x, u[k0], u[k1], u[k2], u[k3], u[k4], u[k5], u[k6], u[k7], u[k8]),
    lambda f, k0, k1, k2, k3, k4, k5, k6, k7, k8, k9: lambda x, y, u: f(
        x, u[k0], u[k1], u[k2], u[k3], u[k4], u[k5], u[k6], u[k7], u[k8], u[k9]),
)  # fmt: skip
_STATEFUL = (
    lambda f: lambda x, y, u: f(x, y),
    lambda f, k0: lambda x, y, u: f(x, y, u[k0]),
    lambda f, k0, k1: lambda x, y, u: f(x, y, u[k0], u[k1]),
    lambda f, k0, k1, k2: lambda x, y, u: f(x, y, u[k0], u[k1], u[k2]),
    lambda f, k0, k1, k2, k3: lambda x, y, u: f(x, y, u[k0], u[k1], u[k2], u[k3]),
    lambda f, k0, k1, k2, k3, k4: lambda x, y, u: f(x, y, u[k0], u[k1], u[k2], u[k3], u[k4]),
    lambda f, k0, k1, k2, k3, k4, k5: lambda x, y, u: f(x, y, u[k0], u[k1], u[k2], u[k3],
                                                        u[k4], u[k5]),
    lambda f, k0, k1, k2, k3, k4, k5, k6: lambda x, y, u: f(x, y, u[k0], u[k1], u[k2], u[k3],
                                                            u[k4], u[k5], u[k6]),
    lambda f, k0, k1, k2, k3, k4, k5, k6, k7: lambda x, y, u: f(
        x, y, u[k0], u[k1], u[k2], u[k3], u[k4], u[k5], u[k6], u[k7]),
    lambda f, k0, k1, k2, k3, k4, k5, k6, k7, k8: lambda x, y, u: f(
        x, y, u[k0], u[k1], u[k2], u[k3], u[k4], u[k5], u[k6], u[k7], u[k8]),
    lambda f, k0, k1, k2, k3, k4, k5, k6, k7, k8, k9: lambda x, y, u: f(
        x, y, u[k0], u[k1], u[k2], u[k3], u[k4], u[k5], u[k6], u[k7], u[k8], u[k9]),
)  # fmt: skip


def _outputs(laws, outputs: tuple[Output, ...], indices):
    """Compiled ``outputs(delta, delta_max, u)``: the tuple of the outputs' values, each
    law called with δ (and δ_max) and its parameters ``u[k]`` (:func:`_parameters`)."""
    import numba

    inline = numba.njit(inline="always")
    calls, o = _STATEFUL if outputs[-1].stateful else _STATELESS, outputs[-1]
    if len(indices[-1]) >= len(calls):
        raise ValueError(f"law {o.law.__name__} takes {len(indices[-1])} parameters; "
                         f"the kernel passes at most {len(calls) - 1}")  # fmt: skip
    last = inline(calls[len(indices[-1])](laws[-1], *indices[-1]))
    if len(laws) == 1:
        return inline(lambda x, y, u: (last(x, y, u),))
    head = _outputs(laws[:-1], outputs[:-1], indices[:-1])
    return inline(lambda x, y, u: (*head(x, y, u), last(x, y, u)))


def _accumulate(terms: tuple[tuple[int, int], ...]):
    """Compiled ``accumulate(acc, o)``: the sums ``acc`` with the summands o_i·o_j of the
    outputs ``o`` added (:func:`_terms`), up to four by each of the nested functions."""
    import numba

    inline = numba.njit(inline="always")
    if not terms:
        return inline(lambda s, o: ())
    chunk = terms[-((len(terms) - 1) % 4 + 1) :]
    head, c = _accumulate(terms[: len(terms) - len(chunk)]), len(terms) - len(chunk)
    (i0, j0), *rest = chunk
    if not rest:
        return inline(lambda s, o: (*head(s, o), s[c] + o[i0] * o[j0]))
    (i1, j1), *rest = rest
    if not rest:
        return inline(lambda s, o: (*head(s, o), s[c] + o[i0] * o[j0], s[c + 1] + o[i1] * o[j1]))
    (i2, j2), *rest = rest
    if not rest:
        return inline(lambda s, o: (*head(s, o), s[c] + o[i0] * o[j0], s[c + 1] + o[i1] * o[j1],
                                    s[c + 2] + o[i2] * o[j2]))  # fmt: skip
    ((i3, j3),) = rest
    return inline(lambda s, o: (*head(s, o), s[c] + o[i0] * o[j0], s[c + 1] + o[i1] * o[j1],
                                s[c + 2] + o[i2] * o[j2], s[c + 3] + o[i3] * o[j3]))  # fmt: skip


@functools.cache
def _kernel(outputs: tuple[Output, ...], legacy: bool, counting: bool, linear_rows: int):
    """The fused kernel of a law set's ``outputs``: numba functions specialised by the law
    functions they close over, compiled once per process and cached on disk (:func:`_cache`).

    ``counting`` False (a stateless law set whose edges are all zero, such as the seed):
    every evaluated pair is in contact and n_contact is the prefix length; with ``legacy``
    (the seed) the laws are compiled as mcsim 0.1 compiled them and each passed its own
    parameter tuple, so the seed's sums stay bit-identical. Otherwise the loop counts the
    pairs in contact (δ_max > jump_in and δ > break_off).
    """
    import numba

    _register_bitcasts()
    for h in {h: None for o in outputs for h in helpers(o.law)}:
        _register_helper(h)
    laws = tuple(numba.njit(o.law, **({} if legacy else LAW_OPTIONS)) for o in outputs)
    outputs_of = _outputs(laws, outputs, _parameters(outputs, legacy)[1])
    accumulate = _accumulate(_terms(len(outputs)))
    zero = (0.0,) * len(_terms(len(outputs)))

    def sweep(z, d, d_turn, reach, jump_in, break_off, out, *u):
        """Each row's threshold (:meth:`~mcsim.physics.laws.Edges.threshold` of the edges
        ``reach``, ``jump_in``, ``break_off``) and the rows in descending order of it (a
        stable sort) come first. Summits are then bucketed by the first row (in that order)
        at which they can carry force (a counting sort), so that for the k-th
        row the summits to evaluate are a prefix of the bucketed array. The loop over that
        prefix evaluates the laws and accumulates the moments in registers; LLVM vectorises
        it (the ``reassoc`` flag lets it reorder the sums, in a fixed way for a given block,
        so the result stays bit-reproducible). Pairs that cannot carry force are never
        evaluated. Results go to the rows' original positions.
        """
        threshold = np.minimum(d + reach, np.maximum(d_turn + jump_in, d + break_off))
        order = np.argsort(-threshold, kind="mergesort")
        thr_desc = threshold[order]
        n, m = z.size, thr_desc.size
        first = np.empty(n, np.int64)  # index of the first row at which the summit counts
        offsets = np.zeros(m + 3, np.int64)  # [lo + 2]: lo = m (never counts) included
        for i in range(n):  # first k with thr_k < z_i, i.e. the number of thr_k >= z_i
            zi = z[i]
            if m <= linear_rows:  # count: branch-free and vectorised, 3-6x faster than bisection
                lo = 0
                for k in range(m):
                    lo += thr_desc[k] >= zi
            else:
                lo, hi = 0, m
                while lo < hi:
                    mid = (lo + hi) >> 1
                    if thr_desc[mid] < zi:
                        hi = mid
                    else:
                        lo = mid + 1
            first[i] = lo
            offsets[lo + 2] += 1
        for k in range(2, m + 2):
            offsets[k] += offsets[k - 1]
        bucketed = np.empty(n)
        for i in range(n):  # stable counting sort by `first`
            k = first[i] + 1
            bucketed[offsets[k]] = z[i]
            offsets[k] += 1
        for k in range(m):
            n_eval = offsets[k + 1]  # summits with first <= k
            j = order[k]
            dj = d[j]
            dtj = d_turn[j]
            nc = 0 if counting else n_eval
            acc = zero
            for i in range(n_eval):
                zi = bucketed[i]
                delta = zi - dj
                delta_max = zi - dtj
                acc = accumulate(acc, (*outputs_of(delta, delta_max, u), 1.0))
                if counting:
                    nc += (delta_max > jump_in) * (delta > break_off)
            row = out[j]
            row[0] = nc
            for c in range(len(acc)):
                row[c + 1] = acc[c]

    kernel = numba.njit(**_sweep_options(legacy))(sweep)
    _cache(kernel, outputs, legacy, counting, linear_rows)
    return kernel


def _cache(kernel, outputs: tuple[Output, ...], *options) -> None:
    """Cache ``kernel`` on disk, in ``<cache_dir()>/kernels``: one index per law set's
    functions and ``options`` (the file name carries the output names and a hash of the
    functions' qualified names and the options), stamped with a hash of the numba version,
    this module's source and the source of every law and helper (:func:`law_source`), so a
    changed law or helper replaces the kernel instead of serving a stale one. numba's own
    cache (``cache=True``) stamps a function by its file alone and keys a closure by the
    pickle of the functions it closes over, which differs in every process.

    Where the cache cannot be written, nothing is cached: the kernel compiles in every
    process. Interpreted (``NUMBA_DISABLE_JIT=1``) there is nothing to cache.
    """
    import numba

    if not hasattr(kernel, "py_func"):
        return
    laws = [o.law for o in outputs]
    names = repr([f"{f.__module__}.{f.__qualname__}" for f in laws] + list(options))
    key = "-".join(o.name for o in outputs) + "-" + hashlib.sha256(names.encode()).hexdigest()[:12]
    sources = [numba.__version__, inspect.getsource(sys.modules[__name__]), *map(law_source, laws)]
    stamp = hashlib.sha256("\n".join(sources).encode()).hexdigest()
    stamped_cache(kernel, "kernels", stamp, key)


def stamped_cache(kernel, folder: str, stamp: str, key: str) -> None:
    """Cache the compiled ``kernel`` (a numba dispatcher) on disk with numba's own machinery,
    but located and stamped by mcsim: in ``<cache_dir()>/folder``, its index file named by the
    function and ``key``, valid while ``stamp`` (a hash of what the kernel is compiled from)
    is unchanged. numba's ``cache=True`` stamps a function by its file's time alone, and keys a
    closure by a pickle of the functions it closes over, which differs in every process; here
    the stamp and the key say which kernel, and the index holds one entry per signature.

    Where the cache folder cannot be written, nothing is cached.
    """
    kernel.py_func.mcsim_cache = folder, stamp, key
    try:
        kernel._cache = _cache_class()(kernel.py_func)
    except RuntimeError:  # no locator: the cache folder cannot be written
        pass


@functools.cache
def _cache_class():
    """numba's cache of compiled functions, located and stamped as :func:`stamped_cache`
    says (the folder, stamp and key read from the function's ``mcsim_cache``)."""
    from numba.core import caching

    class Locator(caching._CacheLocator):
        def __init__(self, py_func, py_file):
            self._py_file = py_file  # where numba's warnings point
            folder, self._stamp, self._key = py_func.mcsim_cache
            self._path = str(cache_dir() / folder)

        def get_cache_path(self):
            return self._path

        def get_source_stamp(self):
            return self._stamp

        def get_disambiguator(self):
            return self._key

        @classmethod
        def from_function(cls, py_func, py_file):
            locator = cls(py_func, py_file)
            try:
                locator.ensure_cache_path()
            except OSError:  # not writable: no cache
                return None
            return locator

    class Impl(caching.CompileResultCacheImpl):
        _locator_classes = (Locator,)

    class Cache(caching.FunctionCache):
        _impl_class = Impl

        def _index_key(self, sig, codegen):
            # the stamp and the file name say which kernel: no pickle of a closure
            return sig, codegen.magic_tuple()

    return Cache


def law_source(fn) -> str:
    """The source of law function ``fn`` and of every helper it calls
    (:func:`mcsim.physics.laws.helpers`): what its compiled code depends on, for the
    stamp of the kernel's cache (:func:`_cache`)."""
    return "\n".join(inspect.getsource(f) for f in (fn, *helpers(fn)))


def compile_law(fn, **options):
    """Law function ``fn`` compiled by numba on its own (``numba.njit(fn, **options)``),
    with its :mod:`mcsim.physics.laws.ieee` calls and its helpers compiled as in the
    kernel (:func:`_register_helper`)."""
    import numba

    _register_bitcasts()
    for h in helpers(fn):
        _register_helper(h)
    return numba.njit(fn, **options)


@functools.cache
def _register_helper(fn) -> None:
    """Let compiled law functions call helper ``fn`` (:func:`mcsim.physics.laws.helpers`),
    which stays a plain Python function: a numba overload of it whose implementation is
    its own source, inlined into each caller at numba's IR level (``inline="always"``),
    so that it is compiled with the caller's options and the kernel's loop vectorises
    as if the helper were written out in the law: the jkr and elastic-plastic sums are
    bit-identical to those of the laws written out in full, at the same cost (measured;
    a helper left out of line, ``inline="never"``, moved jkr's sums by 4e-16 relative
    and cost 2-3 % more per pair)."""
    from numba.extending import register_jitable

    register_jitable(inline="always")(fn)


@functools.cache
def _register_bitcasts() -> None:
    """Compile the law functions' :mod:`mcsim.physics.laws.ieee` calls to one LLVM bitcast each.

    Inline overloads of an intrinsic: numba's scalar ``.view`` is a call to a separate
    function, which keeps numba from removing the reference counting of the table
    arrays inside the loop and LLVM from vectorising it.
    """
    from llvmlite import ir
    from numba import types
    from numba.extending import intrinsic, overload

    from mcsim.physics.laws import ieee

    def bitcast(source, target, llvm_type):
        @intrinsic
        def cast(typingctx, x):
            if x != source:
                return None
            return target(source), lambda context, builder, sig, args: builder.bitcast(
                args[0], llvm_type
            )

        return cast

    to_int = bitcast(types.float64, types.int64, ir.IntType(64))
    to_float = bitcast(types.int64, types.float64, ir.DoubleType())

    @overload(ieee.float_bits, inline="always")
    def _float_bits(x):
        if isinstance(x, types.Float):
            return lambda x: to_int(np.float64(x))
        return None

    @overload(ieee.bits_float, inline="always")
    def _bits_float(b):
        if isinstance(b, types.Integer):
            return lambda b: to_float(np.int64(b))
        return None


def block_sums(
    z: np.ndarray, d: np.ndarray, law: LawSet, args, *, d_turn=None, edges: Edges | None = None
) -> np.ndarray:
    """Fused partial sums (same contract as :func:`block_sums_numpy`).

    The work is the number of (summit, row) pairs that can carry force, and the
    summation order is fixed by the order of ``z``: the result is bit-reproducible.
    Array parameters (tabulated curves) in ``args`` are passed to the kernel as
    arguments, never frozen into the compiled code.
    """
    d, d_turn = _rows(d, d_turn)
    return prepared(law, args, edges)(np.ascontiguousarray(z, dtype=float), d, d_turn)


def prepared_numpy(law: LawSet, args, edges: Edges | None = None):
    """:func:`prepared` with the reference sums (:func:`block_sums_numpy`)."""
    return lambda z, d, d_turn: block_sums_numpy(z, d, law, args, d_turn=d_turn, edges=edges)


def prepared(law: LawSet, args, edges: Edges | None = None):
    """:func:`block_sums` of ``law`` with ``args`` and ``edges``, its kernel looked up once:
    a function ``sums(z, d, d_turn)`` of contiguous float arrays (``d_turn`` the rows'
    closest approaches, ``d`` itself on approach), unchecked, for callers that sum one law
    set many times on a few rows (a pad's search: the lookup costs as much as the sums)."""
    edges = _TOUCHING if edges is None else edges
    kernel = _compiled(law, _counting(law, edges))
    parameters = tuple(args[i][j] for i, j in _parameters(law.outputs, law.legacy_kernel)[0])
    columns = len(sum_columns(law))
    reach, jump_in, break_off = float(edges.reach), float(edges.jump_in), float(edges.break_off)

    def sums(z: np.ndarray, d: np.ndarray, d_turn: np.ndarray) -> np.ndarray:
        out = np.zeros((d.size, columns))
        kernel(z, d, d_turn, reach, jump_in, break_off, out, *parameters)
        return out

    return sums

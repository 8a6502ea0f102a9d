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
"""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import inspect
import os
import sys
import tempfile
import threading
from pathlib import Path

import numpy as np

from mcsim.physics.laws import Edges, LawSet, helpers

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


_SWEEP_HEAD = '''\
def _sweep(z, d, d_turn, thr_desc, order, out, jump_in, break_off, {args}):
    """Fused kernel of law set {name!r}, generated by mcsim.engine.kernels (see _sweep_source).

    Summits are first bucketed by the first row (in descending order of the rows'
    thresholds) at which they can carry force (a counting sort), so that for the k-th
    row the summits to evaluate are a prefix of the bucketed array. The loop over
    that prefix evaluates the laws and accumulates the moments in registers; LLVM
    vectorises it (the ``reassoc`` flag lets it reorder the sums, in a fixed way for
    a given block, so the result stays bit-reproducible). Pairs that cannot carry
    force are never evaluated. Results go to the rows' original positions.
    """
    n, m = z.size, thr_desc.size
    first = np.empty(n, np.int64)  # index of the first row at which the summit counts
    offsets = np.zeros(m + 2, np.int64)
    for i in range(n):  # first k with thr_k < z_i, i.e. the number of thr_k >= z_i
        zi = z[i]
        if m <= {linear_rows}:  # count: branch-free and vectorised, 3-6x faster than bisection
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
'''


def _sweep_source(law: LawSet, counting: bool) -> str:
    """Source of the fused kernel of ``law``: the loop body follows its outputs.

    ``counting`` False (a stateless law set whose edges are all zero, such as the
    seed): every evaluated pair is in contact and n_contact is the prefix length; with
    ``law.legacy_kernel`` (the seed) the loop body is exactly mcsim 0.1's, so the seed's
    sums stay bit-identical. Otherwise the body also computes δ_max = z − d_turn for
    stateful outputs and counts the pairs in contact (δ_max > jump_in and δ > break_off).
    """
    k = len(law.outputs)
    s = [f"s{i}" for i in range(k)]
    ss = [f"s{i}{i}" for i in range(k)]
    pairs = [(i, j) for i in range(k) for j in range(i + 1, k)]
    sx = [f"s{i}{j}" for i, j in pairs]
    accumulators = [*s, *ss, *sx]
    lines = [_SWEEP_HEAD.format(args=", ".join(f"a{i}" for i in range(k)), name=law.name,
                                linear_rows=LINEAR_ROWS)]  # fmt: skip
    body = " " * 12
    lines.append(f"        nc = {'0' if counting else 'n_eval'}")
    lines.append(f"        {' = '.join(accumulators)} = 0.0")
    lines.append("        for i in range(n_eval):")
    if counting:
        lines.append(f"{body}zi = bucketed[i]")
        lines.append(f"{body}delta = zi - dj")
        lines.append(f"{body}delta_max = zi - dtj")
    else:
        lines.append(f"{body}delta = bucketed[i] - dj")
    # A parameter several outputs take is read from the first output's tuple, so that
    # LLVM sees the same value and computes the work the outputs share once (the JKR
    # inversion behind both load and area); the legacy kernel passes each tuple whole.
    first: dict[str, str] = {}
    for i, o in enumerate(law.outputs):
        for j, p in enumerate(o.parameter_names):
            first.setdefault(p, f"a{i}[{j}]")
    for i, o in enumerate(law.outputs):
        state = "delta_max, " if o.stateful else ""
        params = f"*a{i}" if law.legacy_kernel else ", ".join(map(first.get, o.parameter_names))
        lines.append(f"{body}o{i} = law{i}(delta, {state}{params})  # noqa: F821")
    if counting:
        lines.append(f"{body}nc += (delta_max > jump_in) * (delta > break_off)")
    lines += [f"{body}s{i} += o{i}" for i in range(k)]
    lines += [f"{body}s{i}{i} += o{i} * o{i}" for i in range(k)]
    lines += [f"{body}s{i}{j} += o{i} * o{j}" for i, j in pairs]
    lines.append("        row = out[j]")
    lines.append("        row[0] = nc")
    lines += [f"        row[{c + 1}] = {a}" for c, a in enumerate(accumulators)]
    return "\n".join(lines) + "\n"


def cache_dir() -> Path:
    """Folder of the generated kernel modules and numba's cache: ``$MCSIM_CACHE_DIR``,
    else ``$XDG_CACHE_HOME/mcsim``, else ``~/.cache/mcsim``."""
    if "MCSIM_CACHE_DIR" in os.environ:
        return Path(os.environ["MCSIM_CACHE_DIR"])
    return Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "mcsim"


_COMPILE_LOCK = threading.Lock()


def _counting(law: LawSet, edges: Edges) -> bool:
    """Whether the kernel must track δ_max and count contacts (see :func:`_sweep_source`)."""
    return law.stateful or (edges.reach, edges.jump_in, edges.break_off) != (0.0, 0.0, 0.0)


def _compiled(law: LawSet, counting: bool = False):
    """The fused kernel of a law set (see :func:`_generate`), built once per process.

    The lock makes worker threads that start together wait for one build rather than
    race to write the same module.
    """
    with _COMPILE_LOCK:
        # The code depends on the outputs' functions only, not on the parameters' values
        # (a law set with an environment is made anew for each environment).
        code = LawSet(law.name, "", law.outputs, legacy_kernel=law.legacy_kernel)
        return _generate(code, counting)


#: Options of the law functions inside the kernel: a float division by zero gives
#: inf or nan as in NumPy instead of raising ZeroDivisionError, whose check would keep
#: LLVM from vectorising the loop over summits (the laws never divide by zero where
#: the edges let them act), and each is inlined into the sweep by numba (LLVM's
#: inliner leaves larger laws such as elastic-plastic out of line, which also blocks
#: vectorisation). The legacy kernel keeps numba's defaults.
_ERROR_MODEL = "numpy"
_LAW_OPTIONS = f'error_model="{_ERROR_MODEL}", inline="always"'


def _kernel_options(law: LawSet) -> str:
    """numba options of the sweep: fast-math sums (LLVM may reorder them, in a fixed way,
    to vectorise). Outside the legacy kernel the law functions are inlined into the sweep
    (``_LAW_OPTIONS``), so these flags also apply to their arithmetic: LLVM may contract
    and reorder it at the rounding level, and ``nnan`` lets ``np.maximum`` and
    ``np.minimum`` compile to plain max/min, since the laws are finite for every finite
    input (:mod:`mcsim.physics.laws`)."""
    if law.legacy_kernel:
        return 'fastmath={"reassoc", "contract", "nsz"}'
    return f'fastmath={{"reassoc", "contract", "nsz", "nnan"}}, error_model="{_ERROR_MODEL}"'


@functools.cache
def _generate(law: LawSet, counting: bool = False):
    """The fused kernel of a law set, compiled by numba from the law set's own functions.

    A small module is generated that imports the law functions and holds the source
    of the sweep (:func:`_sweep_source`); its name carries a hash of all the sources,
    the laws' helpers included, so numba's on-disk cache (``cache=True``) is reused
    across processes and never goes stale when a law or a helper changes.
    """
    sweep = _sweep_source(law, counting)
    imports = "\n".join(
        f"from {f.__module__} import {f.__name__} as _law{i}" for i, f in enumerate(law.laws)
    )
    compiled = "\n".join(
        f"law{i} = numba.njit(_law{i}{'' if law.legacy_kernel else ', ' + _LAW_OPTIONS})"
        for i in range(len(law.laws))
    )
    text = (
        f'"""Generated by mcsim.engine.kernels for law set {law.name!r}; do not edit."""\n\n'
        f"import numba\nimport numpy as np\n\n{imports}\n\n{compiled}\n\n\n"
        f"{sweep}\n\n"
        f"kernel = numba.njit(nogil=True, cache=True, {_kernel_options(law)})(_sweep)\n"
    )
    sources = [text, *(law_source(f) for f in law.laws)]
    digest = hashlib.sha256("\n".join([numba_version(), *sources]).encode()).hexdigest()[:16]
    _register_bitcasts()
    for h in {h: None for f in law.laws for h in helpers(f)}:
        _register_helper(h)
    return generated_module(f"mcsim_kernel_{law.name.replace('-', '_')}_{digest}", text).kernel


def generated_module(name: str, text: str):
    """The module of source ``text``, written once as ``<cache>/kernels/<name>.py`` and
    imported from there (numba's on-disk cache needs a real file; ``name`` carries a hash
    of everything the source depends on, so a change makes a new file)."""
    folder = cache_dir() / "kernels"
    path = folder / f"{name}.py"
    if not path.exists():
        folder.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=folder, prefix=f".{name}.", suffix=".tmp")
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, path)  # atomic: concurrent processes never see half a module
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module  # numba's cache re-imports the module by name
    spec.loader.exec_module(module)
    return module


def law_source(fn) -> str:
    """The source of law function ``fn`` and of every helper it calls
    (:func:`mcsim.physics.laws.helpers`): what its compiled code depends on, for the
    hash that names a cached module."""
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


def numba_version() -> str:
    import numba

    return numba.__version__


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
    columns = len(sum_columns(law))
    jump_in, break_off = float(edges.jump_in), float(edges.break_off)

    def sums(z: np.ndarray, d: np.ndarray, d_turn: np.ndarray) -> np.ndarray:
        threshold = np.asarray(edges.threshold(d, d_turn), dtype=float)
        order = np.argsort(-threshold, kind="stable")
        out = np.zeros((d.size, columns))
        kernel(z, d, d_turn, np.ascontiguousarray(threshold[order]), order, out, jump_in,
               break_off, *args)  # fmt: skip
        return out

    return sums

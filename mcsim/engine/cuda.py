"""GPU backend: the law set's own functions compiled as CUDA device functions.

Optional (``pip install mcsim[gpu]``, which installs numba-cuda). Nothing here is
imported unless a run asks for ``device="cuda"``; without numba-cuda or without a GPU
that request is a :class:`~mcsim.model.errors.ParameterError`.

How a law set becomes a kernel
------------------------------
Each output function's *source* is executed again in a namespace whose ``np`` is
:func:`device_numpy`, a module holding only the restricted vocabulary of
:mod:`mcsim.physics.laws` mapped to functions the CUDA compiler knows (``np.sqrt`` →
``math.sqrt``, ``np.maximum`` → ``max``, ``np.cbrt`` → libdevice ``cbrt``, ...): numba's
CUDA target cannot compile NumPy ufuncs. The helpers a law calls
(:func:`mcsim.physics.laws.helpers`) become device functions the same way, bound to their
names in the law's namespace (:func:`device_function`). A law that uses anything else is
rejected before compilation (:func:`check_vocabulary`). The per-summit loop, the moments and the
columns are those of :func:`mcsim.engine.kernels.block_sums` (``sum_columns``): ``n_contact``,
Σ of each output, Σ of each output², Σ of the products of outputs i < j.

Reproducibility
---------------
A *block* is a fixed set of at most :data:`mcsim.engine.montecarlo.BLOCK` summits. One CUDA
thread block of :data:`THREADS` threads evaluates one block, tile by tile
(:data:`TILE` summits, summit ``t + k·THREADS + thread`` in thread ``thread``'s slot
``k``); each warp's moments are reduced by a fixed shuffle-down tree, the warps' sums
added in warp order, and the result added to the block's sums in tile order by one thread
per column. Heights are drawn by
Philox4x32-10 (Salmon et al., SC'11) keyed by (seed, realization) with the counter
(summit, block, stream; :mod:`mcsim.engine.cudaheights`): a summit's height depends on
nothing else. So the per-block
sums are bit-identical for any grid size, any number of blocks per launch and any
split of the separations between launches; blocks are added on the host in block
order. GPU and CPU draw different heights: they agree statistically, not bit for bit.
"""

from __future__ import annotations

import ast
import builtins
import functools
import importlib.util
import inspect
import math
import os
import textwrap
import threading
import types
from collections.abc import Iterator

import numpy as np

from mcsim.engine.cudaheights import HEIGHTS, PHILOX, height_sampler, philox_key
from mcsim.engine.kernels import sum_columns
from mcsim.model.errors import ParameterError
from mcsim.physics.laws import Edges, LawSet, helpers, ieee

#: Threads per CUDA block (part of the reproducibility contract: the reduction order).
THREADS = 256
#: Threads per warp (the shuffle tree of the reduction).
WARP = 32
#: Summits per thread per tile.
PER_THREAD = 8
#: Summits per tile (part of the reproducibility contract).
TILE = THREADS * PER_THREAD
#: Most blocks handled by one kernel launch: few launches keep the GPU busy (on an H200,
#: 10⁹ summits in one launch of 16384 blocks took 9 % less time than in four of 4096).
LAUNCH_BLOCKS = 1 << 14
#: Most bytes of per-block sums one launch returns (bounds the GPU memory of a run).
LAUNCH_BYTES = 1 << 28

#: ``np.<name>`` a law function may use (:mod:`mcsim.physics.laws`), and what it becomes on
#: the device: a ``math`` function, a builtin or a libdevice function.
VOCABULARY = {
    "sqrt": "math.sqrt",
    "cbrt": "libdevice.cbrt",
    "exp": "math.exp",
    "log": "math.log",
    "abs": "abs",
    "maximum": "max",
    "minimum": "min",
    "floor": "libdevice.floor",
    "arctan": "math.atan",
    "cos": "math.cos",
    "arccos": "math.acos",
    "pi": "math.pi",
    "int64": "int",
}


def simulating() -> bool:
    """Whether numba's CUDA simulator is on (``NUMBA_ENABLE_CUDASIM=1``)."""
    return os.environ.get("NUMBA_ENABLE_CUDASIM", "0") not in ("", "0")


def _cuda():
    """numba.cuda of numba-cuda (not numba's deprecated built-in target), or a
    ParameterError saying what is missing."""
    try:
        if importlib.util.find_spec("numba_cuda") is None:
            raise ImportError("No module named 'numba_cuda'")
        import numba.cuda as cuda
    except ImportError as exc:
        raise ParameterError(
            f"device = 'cuda' needs numba-cuda ({exc}); install it with pip install 'mcsim[gpu]'"
        ) from None
    return cuda


def require_gpu() -> None:
    """Raise :class:`ParameterError` (one line) unless a CUDA GPU can be used."""
    cuda = _cuda()
    if simulating():
        return
    try:
        ok = cuda.is_available()
    except Exception:  # a broken driver reads as no GPU
        ok = False
    if not ok:
        raise ParameterError(
            "device = 'cuda' but no CUDA GPU is available here (no driver or no device); "
            "use device = 'cpu'"
        )


# -- law functions as device functions ---------------------------------------------


def _np_attributes(fn) -> list[str]:
    """The ``np.<name>`` a function's source uses, in order."""
    tree = ast.parse(textwrap.dedent(inspect.getsource(fn)))
    return [
        node.attr
        for node in ast.walk(tree)
        if isinstance(node, ast.Attribute)
        and isinstance(node.value, ast.Name)
        and node.value.id == "np"
    ]


def check_vocabulary(fn) -> None:
    """Raise :class:`ParameterError` if law function ``fn``, or a helper it calls
    (:func:`mcsim.physics.laws.helpers`), uses NumPy outside :data:`VOCABULARY` or a global
    that is neither ``np``, a number, a :mod:`mcsim.physics.laws.ieee` bit cast nor a
    helper."""
    called = helpers(fn)
    for f in (fn, *called):
        bad = sorted(set(_np_attributes(f)) - set(VOCABULARY))
        if bad:
            raise ParameterError(
                f"law function {f.__module__}.{f.__qualname__} uses np.{bad[0]}, which has "
                f"no CUDA equivalent (allowed: {', '.join('np.' + v for v in VOCABULARY)})"
            )
        for name in f.__code__.co_names:
            value = f.__globals__.get(name, getattr(builtins, name, None))
            if (
                name != "np"
                and name in f.__globals__
                and not isinstance(value, int | float)
                and not any(value is h for h in (*ieee.HELPERS, *called))
            ):
                raise ParameterError(
                    f"law function {f.__module__}.{f.__qualname__} uses the global {name!r}: "
                    "law functions may use only np (restricted vocabulary), numbers, "
                    "mcsim.physics.laws.ieee and helpers defined in their own law file"
                )


@functools.cache
def device_numpy() -> types.ModuleType:
    """The ``np`` a law function sees when compiled for the GPU: a module holding only
    :data:`VOCABULARY`, mapped to ``math``, builtins and libdevice (under the simulator,
    ``math`` and NumPy stand in for libdevice)."""
    module = types.ModuleType("mcsim_device_numpy", "np for CUDA device functions")
    if simulating():
        libdevice = types.SimpleNamespace(cbrt=np.cbrt, floor=math.floor)
    else:
        from numba.cuda import libdevice
    scope = {"math": math, "libdevice": libdevice, "abs": abs, "max": max, "min": min,
             "int": int}  # fmt: skip
    for name, target in VOCABULARY.items():
        head, _, attr = target.partition(".")
        setattr(module, name, getattr(scope[head], attr) if attr else scope[head])
    return module


def _on_device(value):
    """A law function's global as a device function sees it: numbers as they are, the
    :mod:`mcsim.physics.laws.ieee` helpers as CUDA's bit casts (the simulator runs the NumPy
    ones)."""
    if simulating() or not any(value is h for h in ieee.HELPERS):
        return value
    from numba.cuda import libdevice

    if value is ieee.float_bits:
        return libdevice.double_as_longlong
    return libdevice.longlong_as_double


def device_source(fn) -> types.FunctionType:
    """A copy of law function (or helper) ``fn`` compiled from its own source with ``np``
    bound to :func:`device_numpy`, the numbers and :mod:`mcsim.physics.laws.ieee` bit casts
    it uses as globals and each helper it calls as that helper's :func:`device_function`,
    ready for ``cuda.jit(device=True)``."""
    check_vocabulary(fn)
    called = helpers(fn)
    namespace = {"np": device_numpy(), "__builtins__": builtins}
    for name in fn.__code__.co_names:
        if name in fn.__globals__ and name != "np":
            value = fn.__globals__[name]
            helper = any(value is h for h in called)
            namespace[name] = device_function(value) if helper else _on_device(value)
    source = textwrap.dedent(inspect.getsource(fn))
    code = compile(source, f"<device {fn.__module__}.{fn.__qualname__}>", "exec")
    exec(code, namespace)
    return namespace[fn.__name__]


@functools.cache
def device_function(fn):
    """Law function or helper ``fn`` as a CUDA device function (its :func:`device_source`
    under ``cuda.jit(device=True)``), built once per process, so that the outputs calling
    one helper call one device function."""
    return _cuda().jit(device=True)(device_source(fn))


# -- the kernel (its heights: mcsim.engine.cudaheights) ------------------------------

_KERNEL = """
def _kernel(z, offsets, sizes, block0, sigma, k0, k1, dist, tail, cum, lo, hi, sample,
            d, d_turn, thr, jump_in, break_off, out, {params}):
    tid = cuda.threadIdx.x
    lane = tid % WARP
    warp = tid // WARP
    red = cuda.shared.array(({rows}, {ncols}, WARPS), float64)
{scratch}
    zk = cuda.local.array(PER_THREAD, float64)
    m = d.size
    for b in range(cuda.blockIdx.x, sizes.size, cuda.gridDim.x):
        n = sizes[b]
        for t in range(0, n, TILE):
            for k in range(PER_THREAD):
                i = t + k * THREADS + tid
                if i >= n:
                    zk[k] = -math.inf
                elif sample:
                    zk[k] = sigma * _height(i, block0 + b, k0, k1, dist, tail, cum, lo, hi)
                else:
                    zk[k] = z[offsets[b] + i]
            for j0 in range(0, m, {rows}):
                rows = min({rows}, m - j0)
                for r in range(rows):
                    dj = d[j0 + r]
                    dtj = d_turn[j0 + r]
                    tj = thr[j0 + r]
                    {zero}
                    for k in range(PER_THREAD):
                        zi = zk[k]
                        if zi > tj:
                            delta = zi - dj
                            delta_max = zi - dtj
{body}
                    off = WARP // 2
                    while off > 0:
{shuffle}
                        off //= 2
                    if lane == 0:
{store}
                cuda.syncthreads()
                for q in range(tid, rows * {ncols}, THREADS):
                    r = q // {ncols}
                    c = q - r * {ncols}
                    s = red[r, c, 0]
                    for w in range(1, WARPS):
                        s += red[r, c, w]
                    out[b, j0 + r, c] += s
                cuda.syncthreads()
"""

#: Under numba's CUDA simulator, which has no warp shuffles: a step of the same exchange
#: through shared memory, so that lane 0 adds the same values in the same order as on a GPU.
_SIMULATED_SHUFFLE = """\
{write}
cuda.syncthreads()
if lane + off < WARP:
{add}
cuda.syncthreads()"""

#: Bytes of shared memory the warps' sums of a group of rows may take (of CUDA's 48 KiB of
#: static shared memory a block).
SHARED_BYTES = 16384


def group_rows(columns: int) -> int:
    """Rows whose warps' sums of ``columns`` columns fit in :data:`SHARED_BYTES` (at least one)."""
    return max(1, SHARED_BYTES // (8 * columns * (THREADS // WARP)))


def kernel_source(law: LawSet) -> str:
    """Source of the CUDA kernel of ``law`` (device functions ``law0``, ``law1``, ...
    and the helpers of the Philox sampler are globals of the module it is run in).

    Each (tile, row) is reduced in a fixed order: within each warp by a shuffle-down tree
    (``shfl_down_sync`` with offsets 16, 8, ..., 1, whose lane 0 holds the warp's sum), then
    the warps' sums added in warp order by one thread per (row, column), a group of rows
    between two barriers. Under the simulator the shuffles are exchanges through shared
    memory, the values added in the same order."""
    k = len(law.outputs)
    pairs = [(i, j) for i in range(k) for j in range(i + 1, k)]
    acc = ["nc", *(f"s{i}" for i in range(k)), *(f"s{i}{i}" for i in range(k)),
           *(f"s{i}{j}" for i, j in pairs)]  # fmt: skip
    params, body = [], []
    pad = " " * 28
    for i, o in enumerate(law.outputs):
        names = [f"a{i}_{p}" for p in range(len(o.parameter_names))]
        params += names
        state = "delta_max, " if o.stateful else ""
        body.append(f"{pad}o{i} = law{i}(delta, {state}{', '.join(names)})")
    body.append(f"{pad}nc += (delta_max > jump_in) * (delta > break_off) * 1.0")
    body += [f"{pad}s{i} += o{i}" for i in range(k)]
    body += [f"{pad}s{i}{i} += o{i} * o{i}" for i in range(k)]
    body += [f"{pad}s{i}{j} += o{i} * o{j}" for i, j in pairs]
    if simulating():
        scratch = f"    scratch = cuda.shared.array(({len(acc)}, THREADS), float64)"
        step = _SIMULATED_SHUFFLE.format(
            write="\n".join(f"scratch[{c}, tid] = {a}" for c, a in enumerate(acc)),
            add="\n".join(f"    {a} += scratch[{c}, tid + off]" for c, a in enumerate(acc)),
        )
        shuffle = textwrap.indent(step, " " * 24)
    else:
        scratch = ""
        shuffle = "\n".join(
            f"{' ' * 24}{a} += cuda.shfl_down_sync(0xFFFFFFFF, {a}, off)" for a in acc
        )
    store = "\n".join(f"{' ' * 24}red[r, {c}, warp] = {a}" for c, a in enumerate(acc))
    return _KERNEL.format(
        params=", ".join(params) or "_unused=0.0",
        ncols=len(acc),
        rows=group_rows(len(acc)),
        scratch=scratch,
        zero=" = ".join(acc) + " = 0.0",
        body="\n".join(body),
        shuffle=shuffle,
        store=store,
    )


_COMPILE_LOCK = threading.Lock()


@functools.cache
def _namespace(law: LawSet) -> dict:
    """The generated module of ``law``'s kernel: device functions and the kernel."""
    cuda = _cuda()
    from numba import float64

    device = functools.partial(cuda.jit, device=True)
    if simulating():
        from scipy.special import ndtri
    else:
        from numba.cuda.libdevice import normcdfinv as ndtri
    ns = {"np": np, "math": math, "cuda": cuda, "float64": float64, "THREADS": THREADS,
          "WARP": WARP, "WARPS": THREADS // WARP, "PER_THREAD": PER_THREAD, "TILE": TILE,
          "HEIGHTS": HEIGHTS, "_ndtri": ndtri}  # fmt: skip
    for i, fn in enumerate(law.laws):
        ns[f"law{i}"] = device_function(fn)
    exec(compile(PHILOX, "<mcsim.engine.cudaheights philox>", "exec"), ns)
    for name in ("_philox", "_unit", "_height"):
        ns[name] = device(ns[name])
    exec(compile(kernel_source(law), f"<mcsim.engine.cuda kernel {law.name}>", "exec"), ns)
    ns["kernel"] = cuda.jit(ns["_kernel"])
    return ns


def compiled(law: LawSet):
    """The CUDA kernel of a law set, built once per process."""
    with _COMPILE_LOCK:
        return _namespace(law)["kernel"]


# -- host side ------------------------------------------------------------------------


def _rows(d, d_turn, edges: Edges | None):
    d = np.ascontiguousarray(d, dtype=float)
    d_turn = d if d_turn is None else np.ascontiguousarray(d_turn, dtype=float)
    if d_turn.shape != d.shape or d.ndim != 1:
        raise ValueError("d and d_turn must be 1-D arrays of the same length")
    edges = Edges() if edges is None else edges
    thr = np.ascontiguousarray(edges.threshold(d, d_turn), dtype=float)
    return d, d_turn, thr, float(edges.jump_in), float(edges.break_off)


def _device_args(args) -> list:
    """The law parameters flattened, arrays copied to the GPU."""
    cuda = _cuda()
    flat = []
    for a in args:
        for p in a:
            if np.ndim(p) == 0:
                flat.append(float(p))
            else:
                flat.append(cuda.to_device(np.ascontiguousarray(p, dtype=float)))
    return flat or [0.0]


def _launch(law, out_shape, *, z, offsets, sizes, block0=0, sigma=1.0, key=(0, 0),
            sampler=None, rows, params, grid=None) -> np.ndarray:  # fmt: skip
    cuda = _cuda()
    d, d_turn, thr, jump_in, break_off = rows
    dist, tail, cum, lo, hi = sampler if sampler is not None else (0, 1.0, *[np.zeros(1)] * 3)
    out = cuda.to_device(np.zeros(out_shape))
    n_blocks = sizes.size
    grid = n_blocks if grid is None else grid
    compiled(law)[grid, THREADS](
        z, cuda.to_device(offsets), cuda.to_device(sizes), np.int64(block0), float(sigma),
        np.uint64(key[0]), np.uint64(key[1]), np.int64(dist), float(tail),
        cuda.to_device(cum), cuda.to_device(lo), cuda.to_device(hi), sampler is not None,
        cuda.to_device(d), cuda.to_device(d_turn), cuda.to_device(thr), jump_in, break_off,
        out, *params,
    )  # fmt: skip
    return out.copy_to_host()


def block_sums_cuda(
    z: np.ndarray,
    d: np.ndarray,
    law: LawSet,
    args,
    *,
    d_turn=None,
    edges: Edges | None = None,
    grid: int | None = None,
) -> np.ndarray:
    """Partial sums of given heights on the GPU (contract of
    :func:`mcsim.engine.kernels.block_sums_numpy`).

    Parameters
    ----------
    z : ndarray
        Summit heights, m (one block: at most :data:`mcsim.engine.montecarlo.BLOCK`).
    d, d_turn : ndarray
        Separations of the rows and the closest approach before each, m.
    law, args, edges
        As for :func:`mcsim.engine.kernels.block_sums`.
    grid : int, optional
        CUDA blocks launched (the result does not depend on it).

    Returns
    -------
    ndarray, shape (len(d), len(sum_columns(law)))
    """
    require_gpu()
    z = np.ascontiguousarray(z, dtype=float)
    out = _launch(
        law, (1, d.size if np.ndim(d) else 1, len(sum_columns(law))),
        z=_cuda().to_device(z if z.size else np.zeros(1)),
        offsets=np.zeros(1, np.int64), sizes=np.array([z.size], np.int64),
        rows=_rows(d, d_turn, edges), params=_device_args(args), grid=grid,
    )  # fmt: skip
    return out[0]


def blocks_per_launch(rows: int, columns: int) -> int:
    """Blocks one launch handles: :data:`LAUNCH_BLOCKS`, fewer where their sums (``rows`` ×
    ``columns`` doubles a block) would pass :data:`LAUNCH_BYTES`."""
    return max(1, min(LAUNCH_BLOCKS, LAUNCH_BYTES // (8 * rows * columns)))


def patch_block_sums_cuda(
    *,
    law: LawSet,
    args,
    heights,
    sigma: float,
    s_min: float,
    entropy: int,
    realization: int,
    block_sizes,
    first_block: int,
    d: np.ndarray,
    d_turn=None,
    edges: Edges | None = None,
    launch_blocks: int = LAUNCH_BLOCKS,
    grid: int | None = None,
) -> Iterator[np.ndarray]:
    """Sample and sum blocks of one patch on the GPU, in launches of at most
    ``launch_blocks`` blocks (fewer where their sums would pass :data:`LAUNCH_BYTES`);
    heights never leave the GPU.

    Parameters
    ----------
    law, args, edges
        As for :func:`block_sums_cuda`.
    heights : HeightDistribution
        Gaussian or empirical, standardized.
    sigma : float
        Height scale, m.
    s_min : float
        Heights drawn above s_min (standardized).
    entropy, realization : int
        The run's seed and the patch: the Philox key.
    block_sizes : sequence of int
        Summits of the blocks ``first_block``, ``first_block + 1``, ...
    d, d_turn : ndarray
        Rows, m.
    launch_blocks, grid : int
        Blocks per launch and CUDA blocks per launch (the result does not depend on
        either).

    Yields
    ------
    ndarray, shape (blocks in the launch, len(d), columns)
        Per-block partial sums, in block order.
    """
    require_gpu()
    rows = _rows(d, d_turn, edges)
    sampler = height_sampler(heights, s_min)
    params = _device_args(args)
    key = philox_key(entropy, realization)
    sizes = np.asarray(block_sizes, dtype=np.int64)
    dummy = _cuda().to_device(np.zeros(1))
    ncols = len(sum_columns(law))
    step = min(launch_blocks, blocks_per_launch(rows[0].size, ncols))
    for start in range(0, sizes.size, step):
        part = sizes[start : start + step]
        yield _launch(
            law, (part.size, rows[0].size, ncols), z=dummy, offsets=np.zeros(part.size, np.int64),
            sizes=part, block0=first_block + start, sigma=sigma, key=key, sampler=sampler,
            rows=rows, params=params, grid=grid,
        )  # fmt: skip

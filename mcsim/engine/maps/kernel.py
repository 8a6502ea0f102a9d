"""The design map's kernel without an environment: the jkr summaries of one batch, dry.

Plain numba functions (:func:`batch` the entry point), which the interpreter also runs
(``NUMBA_DISABLE_JIT=1``, or each function's ``py_func``); the JKR law functions
(:mod:`mcsim.physics.laws.jkr`) are compiled into them (:data:`load_law`, :data:`area_law`).
Each function follows a step of :func:`mcsim.physics.adhesion.adhesion_summary`:

* **the GW integrals** (:func:`gw_load`): E[P(σ(S − h)); in contact] for a standard normal
  S, over the s range where the Gaussian weight exceeds e^-41 of its peak (as
  :mod:`mcsim.model.distributions`), by one Gauss–Legendre panel of :data:`S_NODES` nodes
  in u = √(Δ − δ_c/σ), Δ = s − h: the substitution removes JKR's square-root branch point
  at break-off wherever the lower limit lies (on retraction it moves with h), so the
  integrand is smooth in u on the whole panel. Against the reference rule (8 panels of 24
  nodes per break-point panel, 1e-13 relative) it agrees to 2e-14 of the curve's largest
  magnitude (measured for σ = 0.3–10 nm, w = 0.05–1 J/m², both branches);
* **the zero-load turn**: the same scan as :func:`mcsim.physics.adhesion.zero_load_separation`
  (:data:`mcsim.physics.adhesion.GRID` points from the top of the summits down, extended
  downwards while the load stays tensile), then Brent's root finder (:func:`brent_root`, as
  ``scipy.optimize.brentq``) to 1e-12 in h;
* **work of separation and hysteresis**: the same rule as ``adhesion_summary`` for the
  retraction load (:data:`mcsim.physics.adhesion.PANELS` panels on [turn, top], split at
  its zeros and at the kink h = turn − δ_c/σ where the lower limit of the integral starts
  to move; :data:`mcsim.physics.adhesion.NODES` Gauss–Legendre nodes each); the approach
  load, analytic in h on [turn, top], on :data:`APPROACH_PANELS` equal panels of as many
  nodes (the reference evaluates it on the retraction's nodes, four times as many);
* **the pull-off**: Brent's bounded minimiser (:func:`brent_minimum`, as
  ``scipy.optimize.minimize_scalar(method="bounded")``) between the neighbours of the
  lowest of the panel edges and nodes, to :data:`H_TOLERANCE` in h (ten times finer than
  the reference's 1e-7).

The root finder and the minimiser take the load they work on as their first argument, a
compiled function (the contact's :func:`gw_load_only` here, the net load with an environment in
:mod:`mcsim.engine.maps.environment`), and numba inlines them into each caller
(``inline="always"``), so the load is resolved where it is compiled: a function passed
to a function compiled on its own would be passed as the address of its Python object,
which numba cannot cache on disk.

**The on-disk cache** (:func:`enable_cache`). numba's own (``cache=True``) stamps a
function's cache with its source file alone: a changed callee in another file (the law
functions, the constants of :mod:`mcsim.physics.adhesion`) would leave a stale kernel, and
a changed docstring would recompile it. Here each function's cache, in
``<mcsim.engine.kernels.cache_dir()>/designmap``, is stamped with what numba compiles into
it (:func:`fingerprint`): the bytecode, constants and options of the function and of
every function it calls, and the values of the module constants they read; not
docstrings, comments or line numbers. A changed kernel replaces its files there (numba
keeps one index per function), so nothing stale accumulates; two installs of different
kernels that share one cache folder replace each other's, each compiling again after the
other ran.
"""

from __future__ import annotations

import hashlib
import math
import types

import numba
import numpy as np
from numba.core.dispatcher import Dispatcher

from mcsim.engine.kernels import compile_law, stamped_cache
from mcsim.engine.maps.status import NO_REST, OK, REFERENCE
from mcsim.physics.adhesion import GAUSSIAN_TOP, GRID, PANELS
from mcsim.physics.laws.jkr import jkr_area, jkr_load

#: Gauss–Legendre nodes of the one-panel rule in u (module docstring).
S_NODES = 32
#: Panels of the approach load's integral on [turn, top] (the hysteresis): it is analytic
#: in h there, so 16 panels of NODES Gauss–Legendre nodes reach rounding (module docstring).
APPROACH_PANELS = 16
#: Tolerance of the pull-off separation in h (the bounded minimiser's ``xatol``).
H_TOLERANCE = 1e-8

#: √(2π), the normal density's normalisation.
SQRT_2PI = math.sqrt(2.0 * math.pi)
_TAIL = 82.0  # GAUSSIAN_TOP²: the weight above e^-41 of its peak

#: numba options of the kernel's functions: a float division by zero gives inf or nan as in
#: NumPy, no ZeroDivisionError check in the loops.
OPTIONS = {"nogil": True, "error_model": "numpy"}
#: Those of the GW integrals: their sums over the s nodes may be reordered (vectorised);
#: NaN (the turn not given) is tested outside them, so no flag that assumes it away.
FAST = OPTIONS | {"fastmath": {"reassoc", "contract", "nsz"}}
#: The JKR law functions, inlined into the GW integrals (so the fast-math flags reach them).
load_law = compile_law(jkr_load, inline="always", error_model="numpy")
area_law = compile_law(jkr_area, inline="always", error_model="numpy")


@numba.njit(**FAST)
def gw_load(h, turn, retract, sigma, factor, p, nodes, weights):
    """Load/(A_n K) and A_r/A_n of the JKR law set at separation ``h`` (see the module doc).

    ``p`` holds δ_c (m), κ, t_c, the Hertz and adhesion scales (N) and the area unit (m²)
    of :func:`mcsim.physics.laws.jkr.reduced_constants`; ``factor`` is η/K (load) and the
    area is scaled by η = factor·K, passed as ``p[6]``. On approach δ_max = δ; on
    retraction (``retract``) δ_max = σ(s − turn).
    """
    b = p[0] / sigma  # break-off edge in Δ = s − h (≤ 0)
    lo = max(turn - h, b) if retract else 0.0
    s_lo = h + lo
    peak = max(s_lo, 0.0)
    lo = max(s_lo, -GAUSSIAN_TOP) - h
    hi = math.sqrt(peak * peak + _TAIL) - h
    if hi <= lo:
        return 0.0, 0.0
    u_lo = math.sqrt(max(lo - b, 0.0))
    span = math.sqrt(hi - b) - u_lo
    load = area = 0.0
    for k in range(nodes.size):
        u = u_lo + span * nodes[k]
        delta_h = b + u * u
        s = h + delta_h
        w = math.exp(0.5 * (peak - s) * (peak + s)) * u * weights[k]
        delta = sigma * delta_h
        delta_max = sigma * (s - turn) if retract else delta
        load += w * load_law(delta, delta_max, p[0], p[1], p[2], p[3], p[4])
        area += w * area_law(delta, delta_max, p[0], p[1], p[2], p[5])
    scale = math.exp(-0.5 * peak * peak) * 2.0 * span / SQRT_2PI
    return factor * scale * load, p[6] * scale * area


@numba.njit(**FAST)
def gw_load_only(h, turn, retract, sigma, factor, p, nodes, weights):
    """Load/(A_n K) alone, as :func:`gw_load` (the area's inversion is not computed)."""
    b = p[0] / sigma
    lo = max(turn - h, b) if retract else 0.0
    s_lo = h + lo
    peak = max(s_lo, 0.0)
    lo = max(s_lo, -GAUSSIAN_TOP) - h
    hi = math.sqrt(peak * peak + _TAIL) - h
    if hi <= lo:
        return 0.0
    u_lo = math.sqrt(max(lo - b, 0.0))
    span = math.sqrt(hi - b) - u_lo
    # Two loops: the weights (exp, a library call) one node at a time, then the law over
    # all nodes, which LLVM vectorises.
    n = nodes.size
    w = np.empty(n)
    delta = np.empty(n)
    for k in range(n):
        u = u_lo + span * nodes[k]
        delta[k] = b + u * u
        s = h + delta[k]
        w[k] = math.exp(0.5 * (peak - s) * (peak + s)) * u * weights[k]
    lag = sigma * (h - turn) if retract else 0.0  # δ_max − δ
    load = 0.0
    for k in range(n):
        d = sigma * delta[k]
        load += w[k] * load_law(d, d + lag, p[0], p[1], p[2], p[3], p[4])
    return factor * math.exp(-0.5 * peak * peak) * 2.0 * span / SQRT_2PI * load


@numba.njit(inline="always", **OPTIONS)
def brent_root(load, a, b, fa, fb, xtol, turn, retract, sigma, factor, p, nodes, weights):
    """Zero of ``load`` (:func:`gw_load_only` or the net load) in [a, b] (fa·fb < 0) by Brent's
    method, as ``scipy.optimize.brentq`` (Brent 1973, ch. 4), to ``xtol`` + 4ε|x| in h."""
    rtol = 4.0 * 2.220446049250313e-16
    pre, fpre, cur, fcur = a, fa, b, fb
    blk = fblk = spre = scur = 0.0
    for _ in range(200):
        if fpre != 0.0 and fcur != 0.0 and (fpre < 0.0) != (fcur < 0.0):
            blk, fblk = pre, fpre
            spre = scur = cur - pre
        if abs(fblk) < abs(fcur):
            pre, cur, blk = cur, blk, cur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(cur)) / 2.0
        sbis = (blk - cur) / 2.0
        if fcur == 0.0 or abs(sbis) < delta:
            return cur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if pre == blk:  # secant
                stry = -fcur * (cur - pre) / (fcur - fpre)
            else:  # inverse quadratic extrapolation
                dpre = (fpre - fcur) / (pre - cur)
                dblk = (fblk - fcur) / (blk - cur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2.0 * abs(stry) < min(abs(spre), 3.0 * abs(sbis) - delta):
                spre, scur = scur, stry  # accept the step
            else:
                spre, scur = sbis, sbis  # bisect
        else:
            spre, scur = sbis, sbis
        pre, fpre = cur, fcur
        if abs(scur) > delta:
            cur += scur
        else:
            cur += delta if sbis > 0 else -delta
        fcur = load(cur, turn, retract, sigma, factor, p, nodes, weights)
    return cur


@numba.njit(inline="always", **OPTIONS)
def brent_minimum(load, a, b, xatol, turn, sigma, factor, p, nodes, weights):
    """Minimum of the retraction ``load`` (:func:`gw_load_only` or the net load) on [a, b] by
    Brent's bounded method (golden section and parabolic steps), as
    ``scipy.optimize.minimize_scalar(method="bounded")``, in the distance from ``a`` (so that
    the stop rule's relative term, √ε times the abscissa, is √ε times at most the bracket's
    width, not times |h|); returns (h, load)."""
    origin, a, b = a, 0.0, b - a
    golden = 0.5 * (3.0 - math.sqrt(5.0))
    sqrt_eps = 1.4901161193847656e-08
    fulc = a + golden * (b - a)
    nfc, xf = fulc, fulc
    rat = e = 0.0
    x = xf
    fx = load(origin + x, turn, True, sigma, factor, p, nodes, weights)
    ffulc = fnfc = fx
    xm = 0.5 * (a + b)
    tol1 = sqrt_eps * abs(xf) + xatol / 3.0
    tol2 = 2.0 * tol1
    for _ in range(500):
        if abs(xf - xm) <= (tol2 - 0.5 * (b - a)):
            break
        golden_step = True
        if abs(e) > tol1:  # try a parabola
            r = (xf - nfc) * (fx - ffulc)
            q = (xf - fulc) * (fx - fnfc)
            pp = (xf - fulc) * q - (xf - nfc) * r
            q = 2.0 * (q - r)
            if q > 0.0:
                pp = -pp
            q = abs(q)
            r, e = e, rat
            if abs(pp) < abs(0.5 * q * r) and pp > q * (a - xf) and pp < q * (b - xf):
                rat = pp / q
                x = xf + rat
                golden_step = False
                if (x - a) < tol2 or (b - x) < tol2:
                    rat = tol1 if xm >= xf else -tol1
        if golden_step:
            e = (a - xf) if xf >= xm else (b - xf)
            rat = golden * e
        x = xf + (rat if abs(rat) >= tol1 else (tol1 if rat >= 0 else -tol1))
        fu = load(origin + x, turn, True, sigma, factor, p, nodes, weights)
        if fu <= fx:
            if x >= xf:
                a = xf
            else:
                b = xf
            fulc, ffulc = nfc, fnfc
            nfc, fnfc = xf, fx
            xf, fx = x, fu
        else:
            if x < xf:
                a = x
            else:
                b = x
            if fu <= fnfc or nfc == xf:
                fulc, ffulc = nfc, fnfc
                nfc, fnfc = x, fu
            elif fu <= ffulc or fulc == xf or fulc == nfc:
                fulc, ffulc = x, fu
        xm = 0.5 * (a + b)
        tol1 = sqrt_eps * abs(xf) + xatol / 3.0
        tol2 = 2.0 * tol1
    return origin + xf, fx


@numba.njit(**OPTIONS)
def _zero_load_turn(sigma, factor, p, nodes, weights):
    """The zero of the approach load coming from far away, as
    :func:`mcsim.physics.adhesion.zero_load_separation`; (turn, status)."""
    top = GAUSSIAN_TOP - p[0] / sigma
    bottom = -GAUSSIAN_TOP
    grid = np.empty(GRID)
    values = np.empty(GRID)
    while True:
        first_tensile = after = -1
        for i in range(GRID):  # from the top down, as far as the first compressive point
            grid[i] = top + (bottom - top) * i / (GRID - 1) if i < GRID - 1 else bottom
            values[i] = gw_load_only(grid[i], 0.0, False, sigma, factor, p, nodes, weights)
            if first_tensile < 0 and values[i] < 0.0:
                first_tensile = i
            elif first_tensile >= 0 and values[i] > 0.0:
                after = i
                break
        if first_tensile < 0:
            return top, NO_REST
        if after >= 0 or bottom < -1e6:
            break
        bottom = top - 2.0 * (top - bottom)
    if after < 0:
        return math.nan, REFERENCE
    a, b = grid[after], grid[after - 1]
    turn = brent_root(gw_load_only, a, b, values[after], values[after - 1], 1e-12, 0.0, False,
                      sigma, factor, p, nodes, weights)  # fmt: skip
    return turn, OK


@numba.njit(**OPTIONS)
def retraction_panels(turn, sigma, factor, p, nodes, weights, gl_x, gl_w, extra):
    """The retraction's panel edges and nodes on [turn, top] with their loads (``extra``
    more slots at the end), top, and the work and hysteresis (in load·dh units)."""
    top = max(GAUSSIAN_TOP - p[0] / sigma, turn)
    coarse = np.empty(PANELS + 1)
    on_coarse = np.empty(PANELS + 1)
    for j in range(PANELS + 1):
        coarse[j] = turn + (top - turn) * j / PANELS
    coarse[PANELS] = top
    for j in range(PANELS + 1):
        on_coarse[j] = gw_load_only(coarse[j], turn, True, sigma, factor, p, nodes, weights)
    cuts = np.empty(2 * PANELS + 2)
    n = 0
    for j in range(PANELS + 1):
        cuts[n] = coarse[j]
        n += 1
        if j < PANELS and on_coarse[j] * on_coarse[j + 1] < 0.0:
            cuts[n] = brent_root(gw_load_only, coarse[j], coarse[j + 1], on_coarse[j],
                                 on_coarse[j + 1], 1e-13, turn, True, sigma, factor, p, nodes,
                                 weights)  # fmt: skip
            n += 1
    kink = turn - p[0] / sigma
    if turn < kink < top:
        cuts[n] = kink
        n += 1
    cuts = np.unique(cuts[:n])
    n = cuts.size
    m = gl_x.size
    grid = np.empty(n + (n - 1) * m + extra)
    values = np.empty(grid.size)
    work = hysteresis = 0.0
    c = 0  # the next coarse point: its load is known
    for j in range(n):
        grid[j * (m + 1)] = cuts[j]
        if c <= PANELS and cuts[j] == coarse[c]:
            values[j * (m + 1)] = on_coarse[c]
            c += 1
        else:
            values[j * (m + 1)] = gw_load_only(
                cuts[j], turn, True, sigma, factor, p, nodes, weights
            )
        if j == n - 1:
            break
        half = 0.5 * (cuts[j + 1] - cuts[j])
        mid = 0.5 * (cuts[j + 1] + cuts[j])
        for k in range(m):
            x = mid + half * gl_x[k]
            retract = gw_load_only(x, turn, True, sigma, factor, p, nodes, weights)
            grid[j * (m + 1) + 1 + k] = x
            values[j * (m + 1) + 1 + k] = retract
            work -= half * gl_w[k] * retract  # −∫ F dd, signed (as adhesion_summary)
            hysteresis -= half * gl_w[k] * retract
    # The approach load is smooth on [turn, top] (no kink, no zero to split at): fewer panels.
    half = 0.5 * (top - turn) / APPROACH_PANELS
    for j in range(APPROACH_PANELS):
        mid = turn + (2 * j + 1) * half
        for k in range(m):
            x = mid + half * gl_x[k]
            hysteresis += (
                half * gl_w[k] * gw_load_only(x, 0.0, False, sigma, factor, p, nodes, weights)
            )
    return grid, values, top, work, hysteresis


@numba.njit(**OPTIONS)
def _point(turn, sigma, factor, p, nodes, weights, gl_x, gl_w, out):
    """Pull-off, its separation, work and hysteresis (in load·dh units) after ``turn``."""
    grid, values, _, work, hysteresis = retraction_panels(turn, sigma, factor, p, nodes, weights,
                                                          gl_x, gl_w, 0)  # fmt: skip
    i = int(np.argmin(values))
    out[0], out[1], out[2], out[3] = 0.0, math.nan, work, hysteresis
    if values[i] < 0.0:
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
        x, value = brent_minimum(
            gw_load_only, lo, hi, H_TOLERANCE, turn, sigma, factor, p, nodes, weights
        )
        if value > values[i]:
            x, value = grid[i], values[i]
        out[0], out[1] = -value, x


@numba.njit(**OPTIONS)
def batch(sigma, factor, params, turns, h, nodes, weights, gl_x, gl_w, curves, summary, status):
    """Every point of a batch: approach curves at ``h`` and the summary (``_point``)."""
    out = np.empty(4)
    for i in range(sigma.size):
        p = params[i]
        for j in range(h.size):
            curves[i, 0, j], curves[i, 1, j] = gw_load(h[j], 0.0, False, sigma[i], factor[i], p,
                                                       nodes, weights)  # fmt: skip
        turn = turns[i]
        status[i] = OK
        if math.isnan(turn):
            turn, status[i] = _zero_load_turn(sigma[i], factor[i], p, nodes, weights)
        summary[i, 0] = turn
        out[0], out[1], out[2], out[3] = 0.0, math.nan, 0.0, 0.0
        if status[i] == OK:
            _point(turn, sigma[i], factor[i], p, nodes, weights, gl_x, gl_w, out)
        for k in range(4):
            summary[i, 1 + k] = out[k]


def gauss_rule(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights on [0, 1]."""
    x, w = np.polynomial.legendre.leggauss(n)
    return (x + 1.0) / 2.0, w / 2.0


def _closure(fn) -> tuple[list, dict]:
    """The compiled functions and the Python functions that ``fn`` is made of (itself and
    every function it calls, directly or not: a list of dispatchers and functions), and the
    module constants they read, by name."""
    found, constants = [], {}
    pending = [fn]
    while pending:
        f = pending.pop()
        if f in found:
            continue
        found.append(f)
        py_func = f.py_func if isinstance(f, Dispatcher) else f
        for name in (n for c in _codes(py_func.__code__) for n in c.co_names):
            value = py_func.__globals__.get(name)
            if isinstance(value, (Dispatcher, types.FunctionType)):
                pending.append(value)
            elif isinstance(value, (bool, int, float, tuple, np.ndarray)):
                constants[name] = value
    return found, constants


def _codes(code: types.CodeType):
    """``code`` and the code objects nested in it (comprehensions, inner functions)."""
    yield code
    for c in code.co_consts:
        if isinstance(c, types.CodeType):
            yield from _codes(c)


def fingerprint(fn) -> str:
    """A hash of what numba compiles into ``fn`` (a dispatcher): the bytecode, constants
    and numba options of it and of every function it calls, and the values of the module
    constants they read; not docstrings, comments or line numbers (module docstring)."""
    digest = hashlib.sha256()
    functions, constants = _closure(fn)
    for f in functions:
        if isinstance(f, Dispatcher):
            options = sorted((k, sorted(v) if isinstance(v, set) else v)
                             for k, v in f.targetoptions.items())  # fmt: skip
            digest.update(repr(options).encode())
            f = f.py_func
        for code in _codes(f.__code__):
            digest.update(code.co_code + repr(code.co_names).encode())
            consts = (c for c in code.co_consts if c is not f.__doc__)
            digest.update(repr([c for c in consts if not isinstance(c, types.CodeType)]).encode())
    for name, value in sorted(constants.items()):
        data = (
            value.tobytes() + repr((value.dtype, value.shape)).encode()
            if isinstance(value, np.ndarray)
            else repr(value).encode()
        )
        digest.update(name.encode() + data)
    return digest.hexdigest()


def enable_cache(*entries) -> None:
    """Cache on disk every compiled function that ``entries`` are made of (module docstring).

    Where the cache cannot be written, nothing is cached: the kernel compiles in every
    process. Interpreted (``NUMBA_DISABLE_JIT=1``) there is nothing to cache.
    """
    for entry in entries:
        for f in _closure(entry)[0]:
            if isinstance(f, Dispatcher) and not hasattr(f.py_func, "mcsim_cache"):
                # the qualified name is unique in its module: the key needs no line number
                stamped_cache(f, "designmap", fingerprint(f), "0")

"""Compiled adhesion summaries of many design points at once: the fast path of analytic sweeps.

:func:`mcsim.physics.adhesion.adhesion_summary` finds, for one point, the separation of
zero approach load, the pull-off (the most tensile retraction load) and the work of
separation and hysteresis, each step a NumPy quadrature driven from Python by SciPy's root
finder and minimiser. :func:`jkr_summaries` does the same steps for a whole batch of points
of the ``jkr`` law set on Gaussian heights in one compiled call (numba, no per-point
Python), with the same law functions (:mod:`mcsim.physics.laws.jkr`):

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
  downwards while the load stays tensile), then Brent's root finder (:func:`_root`, as
  ``scipy.optimize.brentq``) to 1e-12 in h;
* **work of separation and hysteresis**: the same rule as ``adhesion_summary`` for the
  retraction load (:data:`mcsim.physics.adhesion.PANELS` panels on [turn, top], split at
  its zeros and at the kink h = turn − δ_c/σ where the lower limit of the integral starts
  to move; :data:`mcsim.physics.adhesion.NODES` Gauss–Legendre nodes each); the approach
  load, analytic in h on [turn, top], on :data:`APPROACH_PANELS` equal panels of as many
  nodes (the reference evaluates it on the retraction's nodes, four times as many);
* **the pull-off**: Brent's bounded minimiser (:func:`_minimum`, as
  ``scipy.optimize.minimize_scalar(method="bounded")``) between the neighbours of the
  lowest of the panel edges and nodes, to :data:`H_TOLERANCE` in h (ten times finer than
  the reference's 1e-7).

With an environment (``jkr_summaries(..., environment=...)``: van der Waals attraction and
capillary condensation across the gaps of Gaussian heights about the mean plane,
:mod:`mcsim.physics.environment`) the same steps run on the net load, as
``adhesion_summary(..., environment=...)`` does (:func:`_batch_net`, a kernel of its own: the
dry one above is untouched and gives the same bits as without this part):

* **the attraction** at a separation h (mean-plane gap D = hσ + y_s): the capillary part
  (γ_L/r_K) P(D0 <= g < g_K) in closed form (:func:`_capillary`, Φ by ``math.erfc``); the
  van der Waals moment E[g⁻³; g >= D0] by :data:`VDW_PANELS` panels of :data:`VDW_NODES`
  Gauss–Legendre nodes in u, τ = t + D0/Rq = ln(1 + eᵘ) (:func:`_gap_moments`): the
  reference's map ξ = τ + ln τ has the same two regimes (geometric at the pole, uniform
  beyond) and strip of analyticity, but its inverse is Wright's ω; softplus costs one exp
  and one log1p a node. Consecutive separations within :data:`VDW_SPREAD` in
  a = (D − D0)/Rq of each other (the points of one panel of the pull-off grid, of the
  turn's scan, of the curves) share one rule over the union of their windows
  (:func:`_attractions`): one exponential per node and point. The 96 nodes agree with the
  reference's 144 to 7e-14 relative at worst, alone or shared, for Rq/D0 = 1–1000 and a
  from −30 to 30 (both ~1e-14 from the integral);
* **the turn**: the zero of the net approach load, the same scan and Brent root
  (:func:`_zero_load_turn_net`); the surfaces rest apart only where the net approach
  load is never tensile (no attraction acts and too little adhesion);
* **the pull-off**: the lowest net retraction load on the retraction's grid and on
  :data:`mcsim.physics.adhesion.PANELS` points from the top of the summits to where every
  gap is open and wider than g_K (:func:`mcsim.physics.adhesion._environment_top`), where
  the attraction alone acts, then the bounded minimiser on the net load (:func:`_point_net`);
* **work of separation and hysteresis**: the contact's, as dry, plus the works of the
  attraction from the turn to infinity: the reference's own vectorised functions
  (:func:`mcsim.physics.environment.vdw_work`, :func:`~mcsim.physics.environment.capillary_work`)
  at D_t = h_turn σ + y_s, after the kernel, over all points of the batch at once.

Against ``adhesion_summary`` with the environment (tests/engine/test_designmap_environment.py):
curves to 1e-13 of their scale, the turn to 1e-10 in h, pull-off, work of separation and its
parts and hysteresis to 1e-9 relative (the contact work after a deep turn moves with it: 5e-11
measured), Kelvin radius, Rq and y_s equal. ``_root`` and ``_minimum`` run on the net load
as ``_root_net`` and ``_minimum_net``: their source compiled a second time with the names of
:data:`_NET_NAMES` replaced.

The kernel source is compiled once and cached on disk like the Monte Carlo kernel
(:func:`_compiled`: a generated module whose name carries a hash of every source it runs).
The process in which numba compiles it would get numbers up to 5e-14 (relative) apart from
every process that loads it from the cache, so it is compiled in a child process and loaded
(:func:`_kernel`): the first sweep after an install gives the same bits as every later one.
(Inlining the fast-math callees also makes the two agree, but without their flags the batch
runs at half the speed and compiles in 18 s instead of 12, 38 instead of 16 with the
environment; all-inlined with fast-math, 36 and 95 s.)
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import inspect
import math
import os
import re
import subprocess
import sys
import threading

import numpy as np

from mcsim.engine.kernels import generated_module, numba_version
from mcsim.physics.adhesion import GAUSSIAN_TOP, GRID, NODES, PANELS
from mcsim.physics.environment import _TAIL as _GAP_TAIL
from mcsim.physics.environment import Environment
from mcsim.physics.gapheights import nayak_heights
from mcsim.physics.laws.jkr import jkr_area, jkr_load

#: Gauss–Legendre nodes of the one-panel rule in u (module docstring).
S_NODES = 32
#: Panels of the approach load's integral on [turn, top] (the hysteresis): it is analytic
#: in h there, so 16 panels of NODES Gauss–Legendre nodes reach rounding (module docstring).
APPROACH_PANELS = 16
#: Tolerance of the pull-off separation in h (the bounded minimiser's ``xatol``).
H_TOLERANCE = 1e-8
#: Status of a point: summarised; the approach load is never tensile (the surfaces rest
#: apart: zero pull-off, work and hysteresis); outside the fast path (the approach load
#: stays tensile down to h = -1e6: the reference path reports it).
OK, NO_REST, REFERENCE = 0, 1, 2

#: Panels of :data:`VDW_NODES` Gauss–Legendre nodes of the van der Waals moment's rule
#: (:func:`_gap_moment`; module docstring).
VDW_PANELS = 8
VDW_NODES = 12
#: The van der Waals moment's Gaussian weight is cut where it has fallen by e^-VDW_TAIL,
#: as in :mod:`mcsim.physics.environment`.
VDW_TAIL = _GAP_TAIL
#: Consecutive points share the van der Waals moments' rule while their a = (D − D0)/Rq
#: lie within this of each other (their window, 2√(2 VDW_TAIL) ≈ 22 wide, widens by at
#: most this), in runs of up to BLOCK points (module docstring).
VDW_SPREAD = 1.0
BLOCK = 16
#: Columns of a point's parameters after the law's seven, with an environment
#: (:func:`environment_params`): A/6π (J; 0: no van der Waals); Rq, D0, y_s (m); the Laplace
#: pressure γ_L/r_K (Pa; 0: no condensation); the condensation gap g_K (m); the top of the
#: pull-off grid above the summits (h); K (Pa).
P_VDW, P_RQ, P_CUTOFF, P_OFFSET, P_LAPLACE, P_GAP, P_TOP, P_K = range(7, 15)

_SQRT_2PI = math.sqrt(2.0 * math.pi)
_TAIL = 82.0  # GAUSSIAN_TOP²: the weight above e^-41 of its peak


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
        load += w * load_law(delta, delta_max, p[0], p[1], p[2], p[3], p[4])  # noqa: F821
        area += w * area_law(delta, delta_max, p[0], p[1], p[2], p[5])  # noqa: F821
    scale = math.exp(-0.5 * peak * peak) * 2.0 * span / _SQRT_2PI
    return factor * scale * load, p[6] * scale * area


def _load(h, turn, retract, sigma, factor, p, nodes, weights):
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
        load += w[k] * load_law(d, d + lag, p[0], p[1], p[2], p[3], p[4])  # noqa: F821
    return factor * math.exp(-0.5 * peak * peak) * 2.0 * span / _SQRT_2PI * load


def _root(a, b, fa, fb, xtol, turn, retract, sigma, factor, p, nodes, weights):
    """Zero of the load in [a, b] (fa·fb < 0) by Brent's method, as ``scipy.optimize.brentq``
    (Brent 1973, ch. 4), to ``xtol`` + 4ε|x| in h."""
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
        fcur = _load(cur, turn, retract, sigma, factor, p, nodes, weights)
    return cur


def _minimum(a, b, xatol, turn, sigma, factor, p, nodes, weights):
    """Minimum of the retraction load on [a, b] by Brent's bounded method (golden section
    and parabolic steps), as ``scipy.optimize.minimize_scalar(method="bounded")``, in the
    distance from ``a`` (so that the stop rule's relative term, √ε times the abscissa,
    is √ε times at most the bracket's width, not times |h|); returns (h, load)."""
    origin, a, b = a, 0.0, b - a
    golden = 0.5 * (3.0 - math.sqrt(5.0))
    sqrt_eps = 1.4901161193847656e-08
    fulc = a + golden * (b - a)
    nfc, xf = fulc, fulc
    rat = e = 0.0
    x = xf
    fx = _load(origin + x, turn, True, sigma, factor, p, nodes, weights)
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
        fu = _load(origin + x, turn, True, sigma, factor, p, nodes, weights)
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
            values[i] = _load(grid[i], 0.0, False, sigma, factor, p, nodes, weights)
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
    turn = _root(a, b, values[after], values[after - 1], 1e-12, 0.0, False, sigma, factor, p,
                 nodes, weights)  # fmt: skip
    return turn, OK


def _retraction(turn, sigma, factor, p, nodes, weights, gl_x, gl_w, extra):
    """The retraction's panel edges and nodes on [turn, top] with their loads (``extra``
    more slots at the end), top, and the work and hysteresis (in load·dh units)."""
    top = max(GAUSSIAN_TOP - p[0] / sigma, turn)
    coarse = np.empty(PANELS + 1)
    on_coarse = np.empty(PANELS + 1)
    for j in range(PANELS + 1):
        coarse[j] = turn + (top - turn) * j / PANELS
    coarse[PANELS] = top
    for j in range(PANELS + 1):
        on_coarse[j] = _load(coarse[j], turn, True, sigma, factor, p, nodes, weights)
    cuts = np.empty(2 * PANELS + 2)
    n = 0
    for j in range(PANELS + 1):
        cuts[n] = coarse[j]
        n += 1
        if j < PANELS and on_coarse[j] * on_coarse[j + 1] < 0.0:
            cuts[n] = _root(coarse[j], coarse[j + 1], on_coarse[j], on_coarse[j + 1], 1e-13,
                            turn, True, sigma, factor, p, nodes, weights)  # fmt: skip
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
            values[j * (m + 1)] = _load(cuts[j], turn, True, sigma, factor, p, nodes, weights)
        if j == n - 1:
            break
        half = 0.5 * (cuts[j + 1] - cuts[j])
        mid = 0.5 * (cuts[j + 1] + cuts[j])
        for k in range(m):
            x = mid + half * gl_x[k]
            retract = _load(x, turn, True, sigma, factor, p, nodes, weights)
            grid[j * (m + 1) + 1 + k] = x
            values[j * (m + 1) + 1 + k] = retract
            work += half * gl_w[k] * max(-retract, 0.0)
            hysteresis -= half * gl_w[k] * retract
    # The approach load is smooth on [turn, top] (no kink, no zero to split at): fewer panels.
    half = 0.5 * (top - turn) / APPROACH_PANELS
    for j in range(APPROACH_PANELS):
        mid = turn + (2 * j + 1) * half
        for k in range(m):
            x = mid + half * gl_x[k]
            hysteresis += half * gl_w[k] * _load(x, 0.0, False, sigma, factor, p, nodes, weights)
    return grid, values, top, work, hysteresis


def _point(turn, sigma, factor, p, nodes, weights, gl_x, gl_w, out):
    """Pull-off, its separation, work and hysteresis (in load·dh units) after ``turn``."""
    grid, values, _, work, hysteresis = _retraction(turn, sigma, factor, p, nodes, weights, gl_x,
                                                    gl_w, 0)  # fmt: skip
    i = int(np.argmin(values))
    out[0], out[1], out[2], out[3] = 0.0, math.nan, work, hysteresis
    if values[i] < 0.0:
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
        x, value = _minimum(lo, hi, H_TOLERANCE, turn, sigma, factor, p, nodes, weights)
        if value > values[i]:
            x, value = grid[i], values[i]
        out[0], out[1] = -value, x


def _batch(sigma, factor, params, turns, h, nodes, weights, gl_x, gl_w, curves, summary, status):
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


# -- with an environment: the same steps on the net load --------------------------------------


def _gap_moments(a, n, shift, rq, out):
    """E[g⁻³; g >= D0], m⁻³, for g = D − z, z ~ N(0, Rq²), at the first ``n`` of
    a = (D − D0)/Rq, into ``out``, all on one rule (module docstring).

    With t = (g − D0)/Rq each is ∫₀^∞ (D0 + Rq t)⁻³ φ(a − t) dt, over the t range where
    φ exceeds e^-VDW_TAIL of its peak for one of the ``a`` (as
    :func:`mcsim.physics.environment._gaussian_gap_moment` for one), on
    :data:`VDW_PANELS` equal Gauss–Legendre panels in u, τ = t + D0/Rq = ln(1 + eᵘ)
    (``shift`` = D0/Rq): geometric near the pole τ = 0, uniform far from it,
    dτ/du = 1/(1 + e⁻ᵘ), analytic in a strip of half-width π (as the reference's
    ξ = τ + ln τ, without its Wright ω). The nodes are shared: close ``a`` (the points of
    one panel of the pull-off grid) cost one exponential a node each.
    """
    t_lo, t_hi = math.inf, 0.0
    for k in range(n):
        t_lo = min(t_lo, max(a[k] - math.sqrt(2.0 * VDW_TAIL), 0.0))
        if a[k] >= 0.0:
            t_hi = max(t_hi, a[k] + math.sqrt(2.0 * VDW_TAIL))
        else:  # the weight falls by e^-VDW_TAIL at t² − 2at = 2 VDW_TAIL
            t_hi = max(t_hi, 2.0 * VDW_TAIL / (math.sqrt(a[k] * a[k] + 2.0 * VDW_TAIL) - a[k]))
        out[k] = 0.0
    tau_lo, tau_hi = t_lo + shift, t_hi + shift
    u_lo = tau_lo + math.log(-math.expm1(-tau_lo))  # ln(e^τ − 1), no overflow
    span = tau_hi + math.log(-math.expm1(-tau_hi)) - u_lo
    for j in range(VDW_U.size):
        u = u_lo + span * VDW_U[j]
        if u > 0.0:
            e = math.exp(-u)
            tau = u + math.log1p(e)
            slope = 1.0 / (1.0 + e)
        else:
            e = math.exp(u)
            tau = math.log1p(e)
            slope = e / (1.0 + e)
        inverse = 1.0 / (rq * tau)
        weight = VDW_W[j] * inverse * inverse * inverse * slope
        t = tau - shift
        for k in range(n):
            x = a[k] - t
            out[k] += weight * math.exp(-0.5 * x * x)
    for k in range(n):
        out[k] *= span / _SQRT_2PI


def _ndtr(x):
    """Standard normal CDF Φ(x) = erfc(−x/√2)/2."""
    return 0.5 * math.erfc(-x * 0.7071067811865476)


def _capillary(D, p):
    """Capillary pressure (Pa) at mean-plane gap D, as
    :func:`mcsim.physics.environment.capillary_pressure`: (γ_L/r_K) P(D0 <= g < g_K)."""
    if p[P_LAPLACE] == 0.0:
        return 0.0
    a = (D - p[P_CUTOFF]) / p[P_RQ]
    b = (D - p[P_GAP]) / p[P_RQ]
    # P(b < x <= a) from the nearer tail (no cancellation)
    filled = _ndtr(-b) - _ndtr(-a) if b > 0.0 else _ndtr(a) - _ndtr(b)
    return p[P_LAPLACE] * filled


def _attractions(h, n, sigma, p, vdw, capillary):
    """Van der Waals and capillary pressures (Pa) at the first ``n`` separations ``h``
    (D = hσ + y_s), into ``vdw`` and ``capillary``, as
    :func:`mcsim.physics.environment.environment_curves`, each term 0 where its coefficient
    in ``p`` is 0; the van der Waals moments of consecutive separations within
    :data:`VDW_SPREAD` of each other in a = (D − D0)/Rq on one rule (:func:`_gap_moments`)."""
    rq, cutoff = p[P_RQ], p[P_CUTOFF]
    a = np.empty(n)
    for k in range(n):
        D = h[k] * sigma + p[P_OFFSET]
        a[k] = (D - cutoff) / rq
        capillary[k] = _capillary(D, p)
    if p[P_VDW] == 0.0:
        vdw[:n] = 0.0
        return
    start = 0
    while start < n:  # runs of points within VDW_SPREAD of each other in a share a rule
        lo = hi = a[start]
        end = start + 1
        while end < n and max(hi, a[end]) - min(lo, a[end]) <= VDW_SPREAD:
            lo, hi = min(lo, a[end]), max(hi, a[end])
            end += 1
        _gap_moments(a[start:end], end - start, cutoff / rq, rq, vdw[start:end])
        start = end
    for k in range(n):
        vdw[k] = p[P_VDW] * vdw[k]


def _attraction(h, sigma, p):
    """Van der Waals plus capillary attraction per nominal area over K at separation h."""
    x = np.empty(1)
    vdw = np.empty(1)
    capillary = np.empty(1)
    x[0] = h
    _attractions(x, 1, sigma, p, vdw, capillary)
    return (vdw[0] + capillary[0]) / p[P_K]


def _net_load(h, turn, retract, sigma, factor, p, nodes, weights):
    """The net load: the contact load (:func:`_load`) minus the attraction."""
    return _load(h, turn, retract, sigma, factor, p, nodes, weights) - _attraction(h, sigma, p)


def _zero_load_turn_net(sigma, factor, p, nodes, weights):
    """As :func:`_zero_load_turn` on the net load, the attraction of :data:`BLOCK` scan points
    at a time (:func:`_attractions`)."""
    top = GAUSSIAN_TOP - p[0] / sigma
    bottom = -GAUSSIAN_TOP
    grid = np.empty(GRID)
    values = np.empty(GRID)
    vdw, capillary = np.empty(BLOCK), np.empty(BLOCK)
    while True:
        for i in range(GRID):
            grid[i] = top + (bottom - top) * i / (GRID - 1) if i < GRID - 1 else bottom
        first_tensile = after = -1
        i = 0
        while i < GRID and after < 0:  # from the top down, as far as the first compressive point
            size = min(BLOCK, GRID - i)
            _attractions(grid[i:], size, sigma, p, vdw, capillary)
            for k in range(size):
                contact = _load(grid[i + k], 0.0, False, sigma, factor, p, nodes, weights)
                values[i + k] = contact - (vdw[k] + capillary[k]) / p[P_K]
                if first_tensile < 0 and values[i + k] < 0.0:
                    first_tensile = i + k
                elif first_tensile >= 0 and values[i + k] > 0.0:
                    after = i + k
                    break
            i += size
        if first_tensile < 0:
            return top, NO_REST
        if after >= 0 or bottom < -1e6:
            break
        bottom = top - 2.0 * (top - bottom)
    if after < 0:
        return math.nan, REFERENCE
    a, b = grid[after], grid[after - 1]
    turn = _root_net(a, b, values[after], values[after - 1], 1e-12, 0.0, False, sigma, factor, p,  # noqa: F821
                     nodes, weights)  # fmt: skip
    return turn, OK


def _point_net(turn, sigma, factor, p, nodes, weights, gl_x, gl_w, out):
    """As :func:`_point`, with the pull-off of the net load, also above the summits.

    Work and hysteresis are the contact's. The pull-off grid is the retraction's points with
    the attraction taken off, and :data:`PANELS` more from the top of the summits to where
    every gap is open and wider than g_K (``p[P_TOP]``; :func:`mcsim.physics.adhesion._environment_top`),
    where the attraction alone acts.
    """
    grid, values, top, work, hysteresis = _retraction(turn, sigma, factor, p, nodes, weights, gl_x,
                                                      gl_w, PANELS)  # fmt: skip
    n = grid.size - PANELS
    m = gl_x.size + 1  # a panel's edge and nodes: close separations, one rule
    vdw, capillary = np.empty(m), np.empty(m)
    for j in range(0, n, m):
        size = min(m, n - j)
        _attractions(grid[j:], size, sigma, p, vdw, capillary)
        for k in range(size):
            values[j + k] -= (vdw[k] + capillary[k]) / p[P_K]
    step = (p[P_TOP] - top) / PANELS
    for j in range(1, PANELS + 1):
        x = top + j * step if j < PANELS else p[P_TOP]
        grid[n + j - 1] = x
        values[n + j - 1] = _net_load(x, turn, True, sigma, factor, p, nodes, weights)
    if step <= 0.0:  # that top lies below the summits' (given heights): sort
        order = np.argsort(grid, kind="mergesort")
        grid, values = grid[order], values[order]
    i = int(np.argmin(values))
    out[0], out[1], out[2], out[3] = 0.0, math.nan, work, hysteresis
    if values[i] < 0.0:
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
        x, value = _minimum_net(lo, hi, H_TOLERANCE, turn, sigma, factor, p, nodes, weights)  # noqa: F821
        if value > values[i]:
            x, value = grid[i], values[i]
        out[0], out[1] = -value, x


def _batch_net(sigma, factor, params, turns, h, nodes, weights, gl_x, gl_w, curves, summary,
               status):  # fmt: skip
    """As :func:`_batch` with an environment (the columns of ``params`` from :data:`P_VDW`
    on): the van der Waals and capillary curves/K too, the turn and the pull-off of the net
    load."""
    out = np.empty(4)
    vdw, capillary = np.empty(BLOCK), np.empty(BLOCK)
    for i in range(sigma.size):
        p = params[i]
        for j in range(h.size):
            curves[i, 0, j], curves[i, 1, j] = gw_load(h[j], 0.0, False, sigma[i], factor[i], p,
                                                       nodes, weights)  # fmt: skip
        for j in range(0, h.size, vdw.size):
            size = min(vdw.size, h.size - j)
            _attractions(h[j:], size, sigma[i], p, vdw, capillary)
            for k in range(size):
                curves[i, 2, j + k] = vdw[k] / p[P_K]
                curves[i, 3, j + k] = capillary[k] / p[P_K]
        turn = turns[i]
        status[i] = OK
        if math.isnan(turn):
            turn, status[i] = _zero_load_turn_net(sigma[i], factor[i], p, nodes, weights)
        summary[i, 0] = turn
        out[0], out[1], out[2], out[3] = 0.0, math.nan, 0.0, 0.0
        if status[i] == OK:
            _point_net(turn, sigma[i], factor[i], p, nodes, weights, gl_x, gl_w, out)
        for k in range(4):
            summary[i, 1 + k] = out[k]


#: The kernel's functions, in the order the generated module defines them.
_FUNCTIONS = (gw_load, _load, _root, _minimum, _zero_load_turn, _retraction, _point, _batch,
              _gap_moments, _ndtr, _capillary, _attractions, _attraction, _net_load,
              _zero_load_turn_net, _point_net, _batch_net)  # fmt: skip
#: Functions compiled a second time on the net load: each name in their source replaced.
_NET_VARIANTS = (_root, _minimum)
_NET_NAMES = {"_load": "_net_load", "_root": "_root_net", "_minimum": "_minimum_net"}
_COMPILE_LOCK = threading.Lock()


def _constants() -> dict:
    """The module constants the kernel reads, by name."""
    names = ("APPROACH_PANELS", "GAUSSIAN_TOP", "GRID", "H_TOLERANCE", "NO_REST", "OK", "PANELS",
             "REFERENCE", "VDW_TAIL", "VDW_SPREAD", "BLOCK", "P_VDW", "P_RQ", "P_CUTOFF", "P_OFFSET", "P_LAPLACE", "P_GAP",
             "P_TOP", "P_K", "_SQRT_2PI", "_TAIL")  # fmt: skip
    return {k: globals()[k] for k in names}


#: Set in the child process that compiles the kernel (:func:`_kernel`).
_CHILD = "MCSIM_DESIGNMAP_COMPILE"


def _kernel(entry: str):
    """The entry point ``entry`` (``_batch`` or ``_batch_net``) of the compiled module, run
    from numba's on-disk cache.

    The process in which numba compiles the kernel gets numbers up to 5e-14 (relative)
    apart from those of every process that loads it from the cache, which agree bit for
    bit among themselves (numba links the separately compiled fast-math callees differently
    in the two cases). So that the first sweep after an install gives the same bits as
    every later one, a kernel not yet compiled into the cache (no marker beside the
    generated module) is compiled in a child process (:func:`_compile_in_child`) and then
    loaded here. Should the child fail (a cache that cannot be written, say), the kernel is
    compiled here, as numba would.
    """
    with _COMPILE_LOCK:
        module = _compiled()
        marker = f"{module.__file__}.{entry}.compiled"
        if not os.path.exists(marker) and _CHILD not in os.environ:
            code = f"from mcsim.engine.designmap import _compile_in_child; _compile_in_child({entry!r})"
            path = os.pathsep.join(p for p in sys.path if isinstance(p, str))  # as imported here
            env = os.environ | {_CHILD: "1", "PYTHONPATH": path}
            with contextlib.suppress(subprocess.TimeoutExpired):  # then compiled here
                subprocess.run([sys.executable, "-c", code], env=env, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL, check=False, timeout=600)  # fmt: skip
        return getattr(module, entry)


def _compile_in_child(entry: str) -> None:
    """Compile ``entry`` into the on-disk cache by one tiny batch (or find it there), then
    leave its marker."""
    with_environment = entry == "_batch_net"
    environment = Environment(hamaker=1e-19, rh=0.5) if with_environment else None
    jkr_summaries([1e-9], [1e-6], [1e13], [1e11], [4e11 / 3], [0.1], [1.0, 0.0],
                  environment=environment)  # fmt: skip
    # Compiled into the cache, or found there (an earlier mcsim's, or another process's).
    open(f"{_compiled().__file__}.{entry}.compiled", "w").close()


def _net_source(f) -> str:
    """The source of ``f`` renamed to its net-load variant (:data:`_NET_NAMES`)."""
    text = inspect.getsource(f)
    for old, new in _NET_NAMES.items():
        text = re.sub(rf"\b{old}\(", f"{new}(", text)
    return text


@functools.cache
def _compiled():
    """The module of ``_batch`` and ``_batch_net``, compiled by numba with the JKR law
    functions inlined, cached on disk.

    The generated module holds the source of every function of :data:`_FUNCTIONS` and the
    net-load variants of :data:`_NET_VARIANTS`; its name carries a hash of those sources,
    the law functions' and numba's version, so the on-disk cache is reused across
    processes and never goes stale.
    """
    options = 'nogil=True, cache=True, error_model="numpy"'
    # The sums over the s nodes may be reordered (vectorised); NaN (the turn not given)
    # is tested outside them, so no flag that assumes it away.
    fast = options + ', fastmath={"reassoc", "contract", "nsz"}'
    law = 'inline="always", error_model="numpy"'
    parts = [
        '"""Generated by mcsim.engine.designmap; do not edit."""\n',
        "import math\n\nimport numba\nimport numpy as np\n",
        "from mcsim.physics.laws.jkr import jkr_area, jkr_load",
        # numba freezes globals into the compiled code: their values are written here, so
        # that the hash below changes with them
        *(f"{k} = {v!r}" for k, v in _constants().items()),
        *(f"{k} = np.array({globals()[k].tolist()!r})" for k in ("VDW_U", "VDW_W")),
        "",
        f"load_law = numba.njit(jkr_load, {law})",
        f"area_law = numba.njit(jkr_area, {law})\n",
    ]
    for f in _FUNCTIONS:
        flags = fast if f in (gw_load, _load) else options
        parts += [inspect.getsource(f), f"{f.__name__} = numba.njit({flags})({f.__name__})\n"]
    for f in _NET_VARIANTS:
        name = _NET_NAMES[f.__name__]
        parts += [_net_source(f), f"{name} = numba.njit({options})({name})\n"]
    text = "\n".join(parts)
    sources = [text, inspect.getsource(jkr_load), inspect.getsource(jkr_area), numba_version()]
    digest = hashlib.sha256("\n".join(sources).encode()).hexdigest()[:16]
    return generated_module(f"mcsim_designmap_jkr_{digest}", text)


def _rule(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights on [0, 1]."""
    x, w = np.polynomial.legendre.leggauss(n)
    return (x + 1.0) / 2.0, w / 2.0


def _vdw_rule() -> tuple[np.ndarray, np.ndarray]:
    """:data:`VDW_PANELS` equal panels of :data:`VDW_NODES` Gauss–Legendre nodes on [0, 1]."""
    x, w = _rule(VDW_NODES)
    start = np.arange(VDW_PANELS)[:, None] / VDW_PANELS
    return (start + x / VDW_PANELS).ravel(), np.tile(w / VDW_PANELS, VDW_PANELS)


#: Nodes and weights of the van der Waals moments' rule on [0, 1] (:func:`_gap_moments`).
VDW_U, VDW_W = _vdw_rule()


def environment_params(environment, rq, summit_offset, sigma, K) -> np.ndarray:
    """The environment's columns of the kernel's parameters (from :data:`P_VDW` on), one row
    per point.

    Parameters
    ----------
    environment : sequence of Environment
        One per point.
    rq, summit_offset, sigma, K : array_like
        Per point: Rq and y_s of the Gaussian heights about the mean plane (m), σ (m), K (Pa).
    """
    rows = np.empty((len(environment), P_K - P_VDW + 1))
    for i, env in enumerate(environment):
        # as mcsim.physics.environment._capillary: no condensation where g_K <= D0
        r_k = env.kelvin_radius
        gap_k = 2 * r_k * np.cos(env.contact_angle)
        laplace = env.surface_tension / r_k if env.has_capillary and gap_k > env.cutoff else 0.0
        # as mcsim.physics.adhesion._environment_top
        widest = max(env.cutoff, env.condensation_gap)
        top = (GAUSSIAN_TOP * rq[i] + widest - summit_offset[i]) / sigma[i]
        vdw = env.hamaker / (6 * math.pi) if env.has_vdw else 0.0
        rows[i] = (vdw, rq[i], env.cutoff, summit_offset[i], laplace, gap_k, top, K[i])
    return rows


def jkr_summaries(sigma, R, eta, E_star, K, gamma, h, turn=None, environment=None, rq=None,
                  summit_offset=None) -> dict[str, np.ndarray]:  # fmt: skip
    """Approach curves and adhesion summaries of the ``jkr`` law set at many points at once.

    Parameters
    ----------
    sigma, R, eta : array_like
        Per point: standard deviation of the summit heights (m, Gaussian), summit radius
        (m), summit density (1/m²).
    E_star, K, gamma : array_like
        Per point: contact modulus E* and K = 4E*/3 (Pa), work of adhesion w (J/m²).
    h : array_like
        Separations d/σ of the approach curves.
    turn : float, optional
        Closest approach h_turn before retraction; default the zero of the approach load.
    environment : Environment or sequence of Environment, optional
        For every point, or one per point: van der Waals and capillary attraction across the
        gaps of Gaussian heights, as ``adhesion_summary(..., environment=...)`` (module
        docstring). None (default): the contact alone.
    rq, summit_offset : array_like, optional
        Per point, with ``environment``: Rq and the summit plane's offset y_s of the heights
        about the mean plane, m (:func:`mcsim.physics.gapheights.gap_heights`); default both
        Nayak's estimates from σ, R, η (:func:`mcsim.physics.gapheights.nayak_heights`).

    Returns
    -------
    dict of str to ndarray
        ``load`` (load/(A_n K)) and ``area`` (A_r/A_n), shape (points, len(h)); per point
        ``turn``, ``pull_off`` (force/(A_n K)), ``h_pull_off``, ``work_of_separation`` and
        ``hysteresis`` (J/m²), and ``status`` (:data:`OK`, :data:`NO_REST`: the surfaces
        rest apart, summary zero and ``turn`` the top of the summits, or
        :data:`REFERENCE`: give the point to :func:`mcsim.physics.adhesion.adhesion_summary`).
        With ``environment``: ``load`` is the net load, ``vdw`` and ``capillary`` the
        attractions per nominal area/K (as :func:`mcsim.gw_curves`), and per point
        ``work_of_separation_contact``, ``work_of_separation_vdw`` and
        ``work_of_separation_capillary`` (J/m²; with the surfaces in contact at rest their
        sum is ``work_of_separation``), ``kelvin_radius``, ``rq`` and ``summit_offset`` (m).
    """
    from mcsim.physics.laws.jkr import reduced_constants

    sigma, R, eta, E_star, K, gamma = np.broadcast_arrays(
        *(np.atleast_1d(np.asarray(x, dtype=float)) for x in (sigma, R, eta, E_star, K, gamma))
    )
    params = np.empty((sigma.size, 7))
    for i in range(sigma.size):
        c = reduced_constants(R[i], E_star[i], gamma[i])
        params[i] = (c["delta_c"], c["jkr_kappa"], c["jkr_t_c"], c["jkr_hertz"],
                     c["jkr_adhesion"], c["jkr_area_unit"], eta[i])  # fmt: skip
    if environment is not None:
        if isinstance(environment, Environment):
            environment = [environment] * sigma.size
        if rq is None or summit_offset is None:
            rq, summit_offset, _ = zip(*map(nayak_heights, sigma, R, eta))
        rq, summit_offset = (np.broadcast_to(np.asarray(x, dtype=float), sigma.shape)
                             for x in (rq, summit_offset))  # fmt: skip
        params = np.hstack([params, environment_params(environment, rq, summit_offset, sigma, K)])
    h = np.ascontiguousarray(h, dtype=float)
    turns = np.full(sigma.size, math.nan if turn is None else float(turn))
    curves = np.empty((sigma.size, 2 if environment is None else 4, h.size))
    summary = np.empty((sigma.size, 5))
    status = np.empty(sigma.size, dtype=np.int64)
    kernel = _kernel("_batch" if environment is None else "_batch_net")
    kernel(np.ascontiguousarray(sigma), np.ascontiguousarray(eta / K), params, turns, h,
           *_rule(S_NODES), *np.polynomial.legendre.leggauss(NODES), curves, summary, status)  # fmt: skip
    scale = K * sigma  # load·K is force per nominal area; dd = σ dh
    out = {
        "load": curves[:, 0],
        "area": curves[:, 1],
        "turn": summary[:, 0],
        "pull_off": summary[:, 1],
        "h_pull_off": summary[:, 2],
        "work_of_separation": scale * summary[:, 3],
        "hysteresis": scale * summary[:, 4],
        "status": status,
    }
    if environment is not None:
        out |= _environment_outputs(environment, params, out, curves, sigma)
    return out


def _environment_outputs(environment, params, out, curves, sigma) -> dict[str, np.ndarray]:
    """The net load, the attraction curves and the summary's works, over all points at once
    (as :func:`mcsim.physics.adhesion._environment_parts` point by point)."""
    from mcsim.physics.environment import capillary_work, vdw_work

    hamaker = np.array([e.hamaker if e.has_vdw else 0.0 for e in environment])
    field = {k: np.array([getattr(e, k) for e in environment])
             for k in ("surface_tension", "kelvin_radius", "contact_angle")}  # fmt: skip
    rq, cutoff, offset = params[:, P_RQ], params[:, P_CUTOFF], params[:, P_OFFSET]
    rest = out["status"] != OK  # apart (or left to the reference): no work
    D_t = np.where(out["status"] == REFERENCE, offset, out["turn"] * sigma + offset)
    vdw = np.where(rest | (hamaker == 0), 0.0, vdw_work(D_t, rq, hamaker, cutoff))
    capillary = np.where(rest, 0.0, capillary_work(D_t, rq, cutoff, field["surface_tension"],
                                                   field["kelvin_radius"], field["contact_angle"]))  # fmt: skip
    contact = out["work_of_separation"]
    return {
        "load": curves[:, 0] - curves[:, 2] - curves[:, 3],
        "vdw": curves[:, 2],
        "capillary": curves[:, 3],
        "work_of_separation": np.where(rest, contact, contact + vdw + capillary),
        "work_of_separation_contact": contact,
        "work_of_separation_vdw": vdw,
        "work_of_separation_capillary": capillary,
        "kelvin_radius": field["kelvin_radius"],
        "rq": rq,
        "summit_offset": offset,
    }

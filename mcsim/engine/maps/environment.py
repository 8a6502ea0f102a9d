"""The design map's kernel with an environment: the same steps on the net load.

With an environment (``jkr_summaries(..., environment=...)``: van der Waals attraction and
capillary condensation across the gaps of Gaussian heights about the mean plane,
:mod:`mcsim.physics.environment`) the steps of :mod:`mcsim.engine.maps.kernel` run on the net
load, as ``adhesion_summary(..., environment=...)`` does (:func:`batch_net`, a kernel of
its own: the dry one is untouched and gives the same bits as without this part). Like the
dry kernel, these are plain numba functions that the interpreter also runs:

* **the attraction** at a separation h, as
  :func:`mcsim.physics.surfaceenvironment.environment_curves` (docs/physics.md, section 'The
  environment covers the surface once'): the whole surface's, over its heights about the
  mean plane (D = hσ + y_s, g = D − z, z ~ N(0, Rq²)), which the summits' caps and the open
  gaps share (:func:`_attractions`): (γ_L/r_K) P(f <= g < g_K) in closed form (f = max(D0, 2t) the
  adsorbed films' wet floor), and
  (A/6π) E[k_3(g); g >= D0], k_3 the retarded flats' pressure over A/6π (g⁻³ for b = 0,
  b = 5.32/λ, Gregory 1981; :func:`_kernel`) (:func:`_gap_moments`): :data:`VDW_PANELS` panels of
  :data:`VDW_NODES` Gauss–Legendre nodes in u, τ = t + c/ρ = ln(1 + eᵘ) (c the lower end,
  ρ the Gaussian's width): the reference's map ξ = τ + ln τ has the same two regimes
  (geometric at the pole, uniform beyond) and strip of analyticity, but its inverse is
  Wright's ω; softplus costs one exp and one log1p a node. Consecutive separations within
  :data:`VDW_SPREAD` in a = (D − c)/ρ of each other (the points of one panel of the pull-off
  grid, of the turn's scan, of the curves) share one rule over the union of their windows
  (:func:`_moments`): one exponential per node and point. The 96 nodes agree with the
  reference's 144 to 7e-14 relative at worst, alone or shared, for Rq/D0 = 1–1000 and a
  from −30 to 30 (both ~1e-14 from the integral);
* **the contact load**: the dry kernel's GW integrals (:func:`mcsim.engine.maps.kernel.gw_load`)
  with :data:`S_NODES_NET` nodes instead of 32: the attraction pulls the turn deep, and
  below h ≈ −4 the 32-node rule, whose one panel in u then holds the Gaussian's whole
  width far from its lower end, loses accuracy (measured against mpmath: 5e-12 relative at
  h = −4, 1e-9 at −6, 2e-7 at −9); 64 nodes keep 1e-14 down to h = −30;
* **the turn**: the zero of the net approach load, the same scan and Brent root
  (:func:`_zero_load_turn_net`); the surfaces rest apart only where the net approach
  load is never tensile (no attraction acts and too little adhesion);
* **the pull-off**: the lowest net retraction load on the retraction's grid and on
  :data:`mcsim.physics.adhesion.PANELS` points from the top of the summits to where every
  gap is open and wider than max(g_K, u_c) (:func:`mcsim.physics.adhesion.environment_top_separation`),
  where the attraction alone acts, then the bounded minimiser on the net load (:func:`_point_net`);
* **work of separation and hysteresis**: the contact's, as dry (signed, −∫ load dd from the
  turn), plus the works of the attractions from the turn to infinity by the reference's own
  function (:func:`mcsim.physics.surfaceenvironment.environment_works`, caps and open gaps) at
  each point's turn, after the kernel.

Against ``adhesion_summary`` and ``gw_curves`` with the environment
(tests/engine/test_designmap_environment.py), measured on 113 points (the test's random
draws of nine seeds and its corners; turns down to h = −6.3): curves to 6e-15 of their
scale, the turn to 6e-13 in h, pull-off, work of separation and its parts and hysteresis to
2e-11 relative, Kelvin radius, Rq and y_s equal. The dry kernel's root finder and minimiser
(:func:`~mcsim.engine.maps.kernel.brent_root`,
:func:`~mcsim.engine.maps.kernel.brent_minimum`) run on the net load (:func:`_net_load`) given
as their first argument.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from mcsim.engine.maps.kernel import (
    H_TOLERANCE,
    OPTIONS,
    SQRT_2PI,
    brent_minimum,
    brent_root,
    gauss_rule,
    gw_load,
    gw_load_only,
    retraction_panels,
)
from mcsim.engine.maps.status import NO_REST, OK, REFERENCE
from mcsim.physics.adhesion import GAUSSIAN_TOP, GRID, PANELS, environment_top_separation
from mcsim.physics.surfaceenvironment import environment_works
from mcsim.physics.vanderwaals import VDW_TAIL

#: Gauss–Legendre nodes of the contact's one-panel rule in u (as
#: :data:`mcsim.engine.maps.kernel.S_NODES`, which has 32): the attraction pulls the turn deep
#: (h < −4), where 32 nodes lose accuracy (module docstring).
S_NODES_NET = 64
#: Panels of :data:`VDW_NODES` Gauss–Legendre nodes of the van der Waals moment's rule
#: (:func:`_gap_moments`; module docstring).
VDW_PANELS = 8
VDW_NODES = 12
#: Consecutive points share the van der Waals moments' rule while their a = (D − D0)/Rq
#: lie within this of each other (their window, 2√(2 VDW_TAIL) ≈ 22 wide, widens by at
#: most this), in runs of up to BLOCK points (module docstring).
VDW_SPREAD = 1.0
BLOCK = 16
#: Columns of a point's parameters after the law's seven, with an environment
#: (:func:`environment_params`): A/6π (J; 0: no van der Waals); Rq, D0, y_s (m); the Laplace
#: pressure γ_L/r_K (Pa; 0: no condensation); the condensation gap g_K (m; 0 without
#: condensation); the top of the pull-off grid above the summits (h); K (Pa); the wet floor
#: max(D0, 2t) of the adsorbed films t (m; D0 without condensation); the van der Waals
#: retardation b = 5.32/λ (m⁻¹; 0: non-retarded).
(P_VDW, P_RQ, P_CUTOFF, P_OFFSET, P_LAPLACE, P_GAP, P_TOP, P_K, P_FLOOR,
 P_RETARD) = range(7, 17)  # fmt: skip


def _vdw_rule() -> tuple[np.ndarray, np.ndarray]:
    """:data:`VDW_PANELS` equal panels of :data:`VDW_NODES` Gauss–Legendre nodes on [0, 1]."""
    x, w = gauss_rule(VDW_NODES)
    start = np.arange(VDW_PANELS)[:, None] / VDW_PANELS
    return (start + x / VDW_PANELS).ravel(), np.tile(w / VDW_PANELS, VDW_PANELS)


#: Nodes and weights of the van der Waals moments' rule on [0, 1] (:func:`_gap_moments`).
VDW_U, VDW_W = _vdw_rule()


@numba.njit(**OPTIONS)
def _kernel(gap, retard, power):
    """The retarded flats' energy over A/12π, 1/(g²(1 + b g)) (``power`` 2, m⁻²), or pressure
    over A/6π, 1/(g³(1 + b g)) + b/(2 g²(1 + b g)²) (``power`` 3, m⁻³), as
    :func:`mcsim.physics.vanderwaals._gap_kernel`; b = ``retard`` (m⁻¹), 0: g⁻ⁿ."""
    inverse = 1.0 / gap
    damping = 1.0 / (1.0 + retard * gap)
    if power == 2:
        return inverse * inverse * damping
    return inverse * inverse * damping * (inverse + 0.5 * retard * damping)


@numba.njit(**OPTIONS)
def _gap_moments(a, n, shift, scale, power, t_cap, retard, out):
    """E[k(g) − k(u); c <= g < u] (m⁻ⁿ, n = ``power``, 2 or 3; k the retarded kernel of
    :func:`_kernel`, b = ``retard``, g⁻ⁿ for b = 0) for g = D − z,
    z ~ N(0, ρ²) (ρ = ``scale``), at the first ``n`` of a = (D − c)/ρ, into ``out``, all on
    one rule (module docstring); u = c + ρ·``t_cap`` (``t_cap`` = inf: no upper end).

    With t = (g − c)/ρ each is ∫₀^t_cap (k(c + ρt) − k(u)) φ(a − t) dt, over the t range
    where φ exceeds e^-VDW_TAIL of its peak for one of the ``a`` (as
    :func:`mcsim.physics.vanderwaals._gaussian_gap_moment` for one), on
    :data:`VDW_PANELS` equal Gauss–Legendre panels in u, τ = t + c/ρ = ln(1 + eᵘ)
    (``shift`` = c/ρ): geometric near the pole τ = 0, uniform far from it,
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
    t_hi = min(t_hi, t_cap)
    if t_hi <= t_lo:
        return
    tau_lo, tau_hi = t_lo + shift, t_hi + shift
    u_lo = tau_lo + math.log(-math.expm1(-tau_lo))  # ln(e^τ − 1), no overflow
    span = tau_hi + math.log(-math.expm1(-tau_hi)) - u_lo
    edge = 0.0 if t_cap == math.inf else _kernel(scale * (t_cap + shift), retard, power)
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
        weight = VDW_W[j] * (_kernel(scale * tau, retard, power) - edge) * slope
        t = tau - shift
        for k in range(n):
            x = a[k] - t
            out[k] += weight * math.exp(-0.5 * x * x)
    for k in range(n):
        out[k] *= span / SQRT_2PI


@numba.njit(**OPTIONS)
def _moments(a, n, shift, scale, power, t_cap, retard, out):
    """:func:`_gap_moments` at the first ``n`` of ``a``, consecutive ones within
    :data:`VDW_SPREAD` of each other on one rule."""
    start = 0
    while start < n:
        lo = hi = a[start]
        end = start + 1
        while end < n and max(hi, a[end]) - min(lo, a[end]) <= VDW_SPREAD:
            lo, hi = min(lo, a[end]), max(hi, a[end])
            end += 1
        _gap_moments(a[start:end], end - start, shift, scale, power, t_cap, retard,
                     out[start:end])  # fmt: skip
        start = end


@numba.njit(**OPTIONS)
def _upper(x):
    """Upper tail Q(x) = P(X > x) = erfc(x/√2)/2 of a standard normal X."""
    return 0.5 * math.erfc(x * 0.7071067811865476)


@numba.njit(**OPTIONS)
def _between(lo, hi):
    """P(lo < X <= hi) for a standard normal X, from the nearer tail (no cancellation)."""
    return _upper(lo) - _upper(hi) if lo > 0.0 else _upper(-hi) - _upper(-lo)


@numba.njit(**OPTIONS)
def _attractions(h, n, sigma, p, vdw, capillary):
    """Van der Waals and capillary pressures (Pa) at the first ``n`` separations ``h``, into
    ``vdw`` and ``capillary``, as :func:`mcsim.physics.surfaceenvironment.environment_curves`, each
    term 0 where its coefficient in ``p`` is 0 (module docstring): the whole surface's, over
    its heights about the mean plane (D = hσ + y_s, g = D − z, z ~ N(0, Rq²)),
    (A/6π) E[k_3(g); g >= D0] (k_3 the retarded flats'
    pressure over A/6π, :func:`_kernel`) and (γ_L/r_K) P(f <= g < g_K), f = max(D0, 2t) the
    films' wet floor.
    """
    rq, cutoff = p[P_RQ], p[P_CUTOFF]
    a = np.empty(n)
    for k in range(n):
        capillary[k] = 0.0
        if p[P_LAPLACE] != 0.0 and p[P_GAP] > p[P_FLOOR]:
            D = h[k] * sigma + p[P_OFFSET]
            capillary[k] = p[P_LAPLACE] * _between((D - p[P_GAP]) / rq, (D - p[P_FLOOR]) / rq)
    if p[P_VDW] == 0.0:
        vdw[:n] = 0.0
        return
    for k in range(n):  # E[k_3(g); g >= D0], a = (D − D0)/Rq
        a[k] = (h[k] * sigma + p[P_OFFSET] - cutoff) / rq
    _moments(a, n, cutoff / rq, rq, 3, math.inf, p[P_RETARD], vdw)
    for k in range(n):
        vdw[k] *= p[P_VDW]


@numba.njit(**OPTIONS)
def _attraction(h, sigma, p):
    """Van der Waals plus capillary attraction per nominal area over K at separation h."""
    x = np.empty(1)
    vdw = np.empty(1)
    capillary = np.empty(1)
    x[0] = h
    _attractions(x, 1, sigma, p, vdw, capillary)
    return (vdw[0] + capillary[0]) / p[P_K]


@numba.njit(**OPTIONS)
def _net_load(h, turn, retract, sigma, factor, p, nodes, weights):
    """The net load: the contact load (:func:`gw_load_only`) minus the attraction."""
    return gw_load_only(h, turn, retract, sigma, factor, p, nodes, weights) - _attraction(
        h, sigma, p
    )


@numba.njit(**OPTIONS)
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
                contact = gw_load_only(grid[i + k], 0.0, False, sigma, factor, p, nodes, weights)
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
    turn = brent_root(_net_load, a, b, values[after], values[after - 1], 1e-12, 0.0, False,
                      sigma, factor, p, nodes, weights)  # fmt: skip
    return turn, OK


@numba.njit(**OPTIONS)
def _point_net(turn, sigma, factor, p, nodes, weights, gl_x, gl_w, out):
    """As :func:`_point`, with the pull-off of the net load, also above the summits.

    Work and hysteresis are the contact's. The pull-off grid is the retraction's points with
    the attraction taken off, and :data:`PANELS` more from the top of the summits to where
    every gap is open and wider than max(g_K, u_c) (``p[P_TOP]``;
    :func:`mcsim.physics.adhesion.environment_top_separation`), where the attraction alone acts.
    """
    grid, values, top, work, hysteresis = retraction_panels(turn, sigma, factor, p, nodes,
                                                            weights, gl_x, gl_w, PANELS)  # fmt: skip
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
        x, value = brent_minimum(_net_load, lo, hi, H_TOLERANCE, turn, sigma, factor, p, nodes,
                            weights)  # fmt: skip
        if value > values[i]:
            x, value = grid[i], values[i]
        out[0], out[1] = -value, x


@numba.njit(**OPTIONS)
def batch_net(sigma, factor, params, turns, h, nodes, weights, gl_x, gl_w, curves, summary,
               status):  # fmt: skip
    """As :func:`batch` with an environment (the columns of ``params`` from :data:`P_VDW`
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


def environment_params(environment, surfaces, K) -> np.ndarray:
    """The environment's columns of the kernel's parameters (from :data:`P_VDW` on), one row
    per point.

    Parameters
    ----------
    environment : sequence of Environment
        One per point.
    surfaces : sequence of Surface
        One per point, with Gaussian heights and their ``rq`` and ``summit_offset`` given.
    K : array_like
        Per point: K = 4E*/3, Pa.
    """
    rows = np.empty((len(environment), P_RETARD - P_VDW + 1))
    for i, (env, surface) in enumerate(zip(environment, surfaces)):
        vdw = env.hamaker / (6 * math.pi) if env.has_vdw else 0.0
        rows[i] = (vdw, surface.rq, env.cutoff, surface.summit_offset, env.laplace_pressure,
                   env.condensation_gap, environment_top_separation(surface, env), K[i], env.wet_floor,
                   env.retardation)  # fmt: skip
    return rows


def environment_outputs(environment, surfaces, out, curves) -> dict[str, np.ndarray]:
    """The net load, the attraction curves and the summary's works: the works of the
    attractions from each point's turn outward by the reference's own function
    (:func:`mcsim.physics.surfaceenvironment.environment_works`, as
    :func:`mcsim.physics.adhesion._environment_parts`), point by point."""
    works = np.zeros((2, len(environment)))
    for i, (env, surface) in enumerate(zip(environment, surfaces)):
        if out["status"][i] == OK:  # else apart (or left to the reference): no work
            w = environment_works(np.float64(out["turn"][i]), surface, env)
            works[:, i] = w["vdw"], w["capillary"]
    contact = out["work_of_separation"]
    return {
        "load": curves[:, 0] - curves[:, 2] - curves[:, 3],
        "vdw": curves[:, 2],
        "capillary": curves[:, 3],
        "work_of_separation": contact + works[0] + works[1],
        "work_of_separation_contact": contact,
        "work_of_separation_vdw": works[0],
        "work_of_separation_capillary": works[1],
        "kelvin_radius": np.array([e.kelvin_radius for e in environment]),
        "rq": np.array([s.rq for s in surfaces]),
        "summit_offset": np.array([s.summit_offset for s in surfaces]),
    }

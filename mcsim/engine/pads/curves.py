"""One pad's turn, pull-off and work of separation, exactly, on its own load curve
(:mod:`mcsim.engine.pads.load`).

* :func:`pull_off`: the pad's pull-off after the closest approach d_t, −min over d ≥ d_t
  of F_r(d) = Σ f_r(z_i − d; z_i − d_t) (docs/physics.md, section 'Finite pads'). The curve is
  smooth between the separations where a summit crosses an edge of its law set
  (:func:`~mcsim.engine.pads.load.smooth_intervals`). Every such interval is evaluated at its two
  one-sided ends (:data:`~mcsim.engine.pads.load.EDGE` inside it: the load jumps there, e.g.
  JKR's break-off at δ_c, where the most tensile value is the limit from inside) and at
  :data:`~mcsim.engine.pads.load.SUB` interior points; the lowest interior points of the
  :data:`REFINE` lowest intervals are refined, all at once, by zooming: :data:`ZOOM` points
  between the lowest point's neighbours, the lowest of them, and again, until the bracket
  is within :data:`~mcsim.engine.pads.load.XTOL` in h. The retraction runs until every summit
  has left the range of its law, whatever the run's grid.
* :func:`force_turn`: the pad's own closest approach under force control, the largest d
  with Σ f_a(z_i − d) ≥ F (an actuator pressing the pad with F = P·A from far away),
  bracketed on the same intervals of the approach curve, evaluated from the top down to the
  first point that reaches F only (:func:`_approach_prefix`), and bisected to XTOL in h.
* :func:`pad_work`: its work of separation, the integral of its net force, summit by summit.

In humid air (an environment; with one summit radius or a radius by height) the turn and the
pull-off's intervals come from a branch and bound instead (:mod:`mcsim.engine.pads.bounds`),
and after the REFINE lowest intervals the pull-off zooms on every other one whose bound lies
at or below the lowest value met. The dry path keeps its own points: its results are bit-identical to what they were (its sums,
summed in other batches, would move in their last bits).
"""

from __future__ import annotations

import functools
import math

import numpy as np

from mcsim.engine.pads import bounds as padbounds
from mcsim.engine.pads.load import (
    XTOL,
    Part,
    caps_parts,
    contact_edges,
    contact_parts,
    interval_points,
    open_gap_work,
    pad_load,
    smooth_intervals,
    summit_bands,
)
from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.errors import ParameterError
from mcsim.physics.laws import attraction

#: Intervals whose lowest interior point is refined.
REFINE = 4
#: Points of each refining step between the neighbours of the lowest point (the bracket
#: shrinks by (ZOOM + 1)/2 per step).
ZOOM = 15


def pull_off(spec: MonteCarloSpec, z: np.ndarray, d_turn: float) -> tuple[float, float]:
    """A pad's pull-off (N, a magnitude) and its separation (m) after the closest approach ``d_turn``.

    See the module docstring. (0, NaN) when the retraction load is nowhere tensile.
    """
    sigma = spec.surface.sigma
    e = spec.edges
    if z.size == 0:
        return 0.0, math.nan
    top = float(z.max()) - min(e.reach, e.break_off, 0.0)  # no summit reaches beyond
    if top <= d_turn:
        return 0.0, math.nan
    floor = curve = None  # in humid air: a lower bound of each interval's values, its curve
    if not padbounds.bounded(spec):
        cuts = smooth_intervals(spec, z, d_turn, top, contact_edges(spec))
        points = interval_points(cuts, sigma)
        values = pad_load(spec, z, points.ravel(), d_turn).reshape(points.shape)
        best = int(np.argmin(values))
        force, at = float(values.flat[best]), float(points.flat[best])
    else:
        curve, points, values, floor, force, at = padbounds.humid_pull_off(spec, z, d_turn, top)
        if values.size == 0:
            return (-force, at) if force < 0 else (0.0, math.nan)
        if values.min() < force:
            force, at = float(values.min()), float(points.flat[np.argmin(values)])
    # Zoom on the lowest interior point of the REFINE lowest intervals, all at once (in humid
    # air, dropping the intervals whose bound lies above the lowest value met); in humid air
    # then on every other interval whose bound still lies at or below it: the minimum's
    # interval need not be among the REFINE whose interior points are lowest (without this,
    # 9 of 1440 one-radius humid pull-offs, 3 law sets x 2 presets x RH 0.3, 0.7, 0.9 x 40
    # pads x preloads 0, 1 MPa, came out 1.2e-5 to 5.9 % short: tests/engine/test_padcurves.py).
    rows = np.argsort(values[:, 1:-1].min(axis=1))
    force, at = _zoom(spec, z, d_turn, points, values, rows[:REFINE], floor, curve, force, at)
    if floor is not None:
        rest = rows[REFINE:][floor[rows[REFINE:]] <= force]
        force, at = _zoom(spec, z, d_turn, points, values, rest, floor, curve, force, at)
    return (-force, at) if force < 0 else (0.0, math.nan)


def _zoom(spec, z, d_turn, points, values, rows, floor, curve, force, at):
    """The lowest retraction load met (N) and where (m), from ``force`` at ``at``, zooming on
    the lowest interior point of each interval ``rows`` of :func:`pull_off`'s ``points`` and
    ``values``, all at once: a grid of :data:`ZOOM` points between its neighbours, the lowest
    again, until within XTOL; in humid air (``floor``: a lower bound of each interval's
    values), dropping the brackets whose bound (:func:`~mcsim.engine.pads.bounds.bracket_floors`
    on ``curve``) lies above the lowest value met."""
    sigma = spec.surface.sigma
    j = 1 + np.argmin(values[rows, 1:-1], axis=1)
    lo, hi = points[rows, j - 1], points[rows, j + 1]
    if floor is not None:
        floor = floor[rows]
        lo, hi, floor = lo[floor <= force], hi[floor <= force], floor[floor <= force]
    frac = np.linspace(0.0, 1.0, ZOOM + 2)[None, :]
    check = floor is not None  # bound the brackets again (until a check drops none)
    while lo.size and np.max(hi - lo) > XTOL * sigma:
        x = lo[:, None] + (hi - lo)[:, None] * frac
        v = pad_load(spec, z, x.ravel(), d_turn).reshape(x.shape)
        k = np.clip(np.argmin(v, axis=1), 1, ZOOM)
        i = np.arange(k.size)
        lo, hi = x[i, k - 1], x[i, k + 1]
        if v.min() < force:
            force, at = float(v.min()), float(x.flat[np.argmin(v)])
        if check and lo.size > 1:  # the bound of each bracket, now narrower
            floor = padbounds.bracket_floors(curve, lo, hi)
            check = bool(np.any(floor > force))
        if floor is not None:
            lo, hi, floor = lo[floor <= force], hi[floor <= force], floor[floor <= force]
    return force, at


#: Gauss–Legendre nodes on each smooth piece of a summit's retraction load for its work.
WORK_NODES = 16


def pad_work(spec: MonteCarloSpec, z: np.ndarray, d_turn: float) -> float:
    """A pad's work of separation after the closest approach ``d_turn`` (m), J/m².

    The integral of its net retraction force from the turn to infinity per nominal area,
    −∫ F_r dd / A (signed: a compressive start gives back elastic energy), the sum of its
    parts' integrals, summit by summit (the load is a sum over summits, so is its integral):
    the contact law's by :func:`contact_works`; the environment's in closed form, each
    summit's caps from its interference at the turn
    (:func:`mcsim.physics.laws.attraction.vdw_summit_work`,
    :func:`~mcsim.physics.laws.attraction.capillary_summit_work`) and the open gaps from the
    turn, the integral of the pressure the curve subtracts
    (:func:`~mcsim.engine.pads.load.open_gap_work`).
    """
    work = -float(np.sum(contact_works(spec, z, d_turn))) / spec.area
    if spec.environment is not None:
        band = summit_bands(spec, z)
        for k, caps in enumerate(caps_parts(spec)):  # each band's caps with its radius
            for term, args in zip(caps.law.names, caps.args):
                work += float(np.sum(CAP_WORKS[term](z[band == k] - d_turn, *args))) / spec.area
        work += float(open_gap_work(spec)(d_turn / spec.surface.sigma))
    return work


def contact_works(spec: MonteCarloSpec, z: np.ndarray, d_turn: float) -> np.ndarray:
    """∫ f_r(δ; δ_t) dδ (J) of the contact law's retraction load of each summit of heights
    ``z`` (m) after the closest approach ``d_turn`` (m), from where it leaves the law to its
    δ_t = z − d_turn: minus its work of separation.

    Each summit's load is smooth between the edges of the law (jump-in, break-off, reach,
    breakpoints); on each piece the substitution δ = a + (b − a)(3u² − 2u³) makes the
    square-root ends smooth in u (JKR's load at its break-off δ_c grows as √(δ − δ_c)), and
    :data:`WORK_NODES` Gauss–Legendre nodes in u integrate it to ~1e-7 relative (measured
    against 64 nodes on four sub-pieces: DMT's 1/D² tail the worst;
    tests/engine/test_padcurves.py). The law set's ``load`` is evaluated at all nodes at
    once, where the summit carries force (:meth:`~mcsim.physics.laws.Edges.threshold`), as
    the kernel's reference does (:func:`~mcsim.engine.kernels.block_sums_numpy`).
    """
    band, works = summit_bands(spec, z), np.zeros(z.shape)
    for k, part in enumerate(contact_parts(spec)):  # each band of heights with its radius
        works[band == k] = _piece_works(part, z[band == k] - d_turn)
    return works


def _piece_works(part: Part, delta_turn: np.ndarray) -> np.ndarray:
    """:func:`contact_works` of summits with the law set, arguments and edges of ``part``."""
    e = part.edges
    low = min(e.reach, e.break_off, 0.0)  # below it no summit carries force on retraction
    works = np.zeros(delta_turn.shape)
    acting = np.flatnonzero(delta_turn > low)
    top = delta_turn[acting, None]
    inner = np.unique([0.0, e.reach, e.jump_in, e.break_off, *e.breakpoints])
    cuts = np.sort(np.clip(np.hstack([np.full_like(top, low), np.broadcast_to(inner, (top.size,
                   inner.size)), top]), low, top), axis=1)  # fmt: skip
    a, length = cuts[:, :-1, None], np.diff(cuts, axis=1)[..., None]
    u, weight = _work_rule(WORK_NODES)
    nodes = a + length * (3 * u**2 - 2 * u**3)
    turn = np.broadcast_to(top[..., None], nodes.shape)
    summit = np.broadcast_to(acting[:, None, None], nodes.shape)
    scale = np.broadcast_to(length * weight, nodes.shape)  # dδ = (b − a)·6u(1 − u) du
    carries = (0.0 > e.threshold(-nodes, -turn)) & (length > 0)
    i = part.law.names.index("load")
    out, args = part.law.outputs[i], part.args[i]
    delta, delta_max = nodes[carries], turn[carries]
    load = out.law(delta, delta_max, *args) if out.stateful else out.law(delta, *args)
    works += np.bincount(summit[carries], scale[carries] * load, minlength=works.size)
    return works


@functools.cache
def _work_rule(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes u on [0, 1] and weights (with the Jacobian 6u(1 − u) of :func:`contact_works`'s
    substitution) of an ``n``-point Gauss–Legendre rule, computed once."""
    x, w = np.polynomial.legendre.leggauss(n)
    u = (x + 1) / 2
    return u, w / 2 * 6 * u * (1 - u)


#: The work of each of the caps' outputs (same parameters as the force).
CAP_WORKS = {"vdw": attraction.vdw_summit_work, "capillary": attraction.capillary_summit_work}


#: Stride of the coarse pass of :func:`_approach_prefix` through a pad's approach points.
STRIDE = 64


def _approach_prefix(spec: MonteCarloSpec, z: np.ndarray, points: np.ndarray, reaches):
    """The approach load (N) at ``points`` (m, descending) from the first down to the first
    that ``reaches``, exactly as :func:`pad_load` gives it at all of them (all of them if
    none does).

    The turn needs only the largest d that reaches the force, and the rows below it hold
    the most summits. On approach the kernel's rows are ordered by d (its thresholds
    rise with d), so for a prefix of ``points`` it buckets the summits of those rows as for
    all of them and adds them in the same order: the prefix's values are those of the
    whole, bit for bit. A coarse pass (every :data:`STRIDE`-th point, its sums in another
    order) says where to cut; if the prefix holds no reached point after all (a narrow
    peak the coarse pass stepped over lies below, or the cut point reached by a rounding
    only), every point is evaluated.
    """
    coarse = np.flatnonzero(reaches(pad_load(spec, z, points[::STRIDE])))
    if coarse.size:
        values = pad_load(spec, z, points[: coarse[0] * STRIDE + 1])
        if np.any(reaches(values)):
            return values
    return pad_load(spec, z, points)


def pad_turn(spec: MonteCarloSpec, z: np.ndarray, turn: float, preload: float | None) -> float:
    """A pad's closest approach (m), as plain pads and their importance sampling take it: under
    a ``preload`` (Pa) its own, where its approach load reaches P·A (:func:`force_turn`), else
    the common ``turn`` (d/σ)."""
    if preload is None:
        return turn * spec.surface.sigma
    return force_turn(spec, z, preload * spec.area)[0]


def force_turn(spec: MonteCarloSpec, z: np.ndarray, force: float) -> tuple[float, float]:
    """A pad's closest approach under force control: the largest d (m) with approach load ≥ ``force``.

    Parameters
    ----------
    spec : MonteCarloSpec
        The run; its lowest separation min(h) bounds the search (summits below s_min are
        not drawn).
    z : ndarray
        The pad's summit heights, m (:func:`patch_heights`).
    force : float
        Applied compressive force P·A, N (>= 0). With 0 the pad rests under its own
        attraction: the largest d below its first touch (the tallest summit at its contact
        law's jump-in) where the net load turns compressive (far away the load is 0 too,
        which does not count).

    Returns
    -------
    d_turn, load : float
        The turn (m) and the approach load reached there (N; ≥ ``force``, above it only
        where the load jumps past it, as when a summit jumps into contact).

    Raises
    ------
    ParameterError
        If the pad's approach load stays below ``force`` down to min(h).
    """
    sigma = spec.surface.sigma
    bottom = float(spec.h.min()) * sigma
    # with an environment, the first touch: the tallest summit at its contact law's jump-in
    # (0 without one): the open gaps may push back slightly above the summits, where the caps
    # claim more than the surface (docs/physics.md, 'The environment covers the surface
    # once'), and a pad rests on its summits, not on that; dry, as before, the law's reach
    edges = contact_edges(spec)
    touch = min(edges.reach if spec.environment is None else edges.jump_in, 0.0)
    top = max(float(z.max()) - touch, bottom) if z.size else bottom

    def reaches(load):  # at 0 the force must be exceeded: far away the load is 0 too
        return load > force if force == 0 else load >= force

    if padbounds.bounded(spec):
        return padbounds.humid_turn(spec, z, force, bottom, top, reaches)
    cuts = smooth_intervals(spec, z, bottom, top, contact_edges(spec))
    points = np.unique(np.concatenate([[bottom, top], interval_points(cuts, sigma).ravel()]))[::-1]
    values = _approach_prefix(spec, z, points, reaches)
    reached = np.flatnonzero(reaches(values))
    if reached.size == 0:
        raise ParameterError(
            f"preload force {force:.4g} N: the pad's approach load is {values[-1]:.4g} N at the "
            f"grid's lowest separation h = {spec.h.min():g}; extend the separations (--h) down"
        )
    i = int(reached[0])
    if i == 0:
        return float(points[0]), float(values[0])
    # Bisection keeping load(lo) >= force > load(hi): exact also where the load jumps.
    lo, hi, load = float(points[i]), float(points[i - 1]), float(values[i])
    while hi - lo > XTOL * sigma:
        mid = 0.5 * (lo + hi)
        at = float(pad_load(spec, z, [mid])[0])
        if reaches(at):
            lo, load = mid, at
        else:
            hi = mid
    return lo, load

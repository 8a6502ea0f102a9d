"""One pad's own load curves, exactly: its summits regenerated from the run's seed.

A ``--cycle`` run stores sums on a grid of separations, so the most tensile grid value
of a pad's retraction load is biased (the grid misses the minimum between its points,
and ends somewhere). Its summits, though, are a pure function of the seed: realization
r draws its counts from the stream ``(r, 0)`` and block b its heights from ``(r, 1 + b)``
(:func:`mcsim.engine.montecarlo.plan_patch`, :func:`~mcsim.engine.montecarlo.sample_block`).
:func:`patch_heights` draws them again, the same numbers the run summed, and the load of
the pad at any separation is the compiled kernel's sum of the law set's per-summit
``load`` (:func:`mcsim.engine.kernels.block_sums`) over those heights. On them:

* :func:`pull_off`: the pad's pull-off after the closest approach d_t, −min over d ≥ d_t
  of F_r(d) = Σ f_r(z_i − d; z_i − d_t) (docs/physics.md, section 'Finite pads'). The curve is smooth
  between the separations where a summit crosses an edge of its law set (break-off,
  jump-in, reach, breakpoints: d = z_i − e). Every such interval is evaluated at its two
  one-sided ends (:data:`EDGE` inside it: the load jumps there, e.g. JKR's break-off at
  δ_c, where the most tensile value is the limit from inside) and at :data:`SUB` interior
  points; the lowest interior points of the :data:`REFINE` lowest intervals are refined,
  all at once, by zooming: :data:`ZOOM` points between the lowest point's neighbours, the
  lowest of them, and again, until the bracket is within :data:`XTOL` in h. The retraction runs until every summit has
  left the range of its law, whatever the run's grid.
* :func:`force_turn`: the pad's own closest approach under force control, the largest d
  with Σ f_a(z_i − d) ≥ F (an actuator pressing the pad with F = P·A from far away),
  bracketed on the same intervals of the approach curve, evaluated from the top down to the
  first point that reaches F only (:func:`_approach_prefix`), and bisected to :data:`XTOL` in h.
"""

from __future__ import annotations

import functools
import math
from typing import NamedTuple

import numpy as np

from mcsim.engine.kernels import block_sums, sum_columns
from mcsim.engine.montecarlo import MonteCarloSpec, plan_patch, sample_block, sums
from mcsim.model.errors import ParameterError
from mcsim.physics.laws import Edges, LawSet, attraction, get_law_set
from mcsim.physics.surfaceenvironment import (
    active_terms,
    open_gap_pressures,
    open_gap_works,
    with_environment,
)

#: Interior points at which each smooth interval of a pad's curve is evaluated.
SUB = 3
#: Intervals whose lowest interior point is refined.
REFINE = 4
#: Points of each refining step between the neighbours of the lowest point (the bracket
#: shrinks by (ZOOM + 1)/2 per step).
ZOOM = 15
#: Tolerance of the pull-off and turn separations, in h = d/σ.
XTOL = 1e-7
#: One-sided limits at an interval's ends are evaluated this far inside it, in h
#: (a summit's load at its break-off is then within ~1e-6 relative of the limit even
#: where it has a square-root singularity, as JKR's at δ_c).
EDGE = 1e-13


def patch_heights(spec: MonteCarloSpec, r: int) -> np.ndarray:
    """The heights (m) that realization ``r`` of ``spec`` summed: every summit above s_min.

    Raises
    ------
    ParameterError
        For a run on the GPU (its heights come from other streams).
    """
    if spec.device != "cpu":
        raise ParameterError(f"device = {spec.device!r}: the summit heights of a GPU run cannot "
                             "be drawn again on the CPU (other random streams)")  # fmt: skip
    plan = plan_patch(spec, r)
    blocks = [sample_block(spec, plan, r, b) for b in range(plan.n_blocks)]
    return np.concatenate(blocks) if blocks else np.empty(0)


def pad_load(spec: MonteCarloSpec, z: np.ndarray, d, d_turn=None) -> np.ndarray:
    """Net load (N, compressive positive) of the pad of summits ``z`` (m) at separations ``d`` (m).

    The sum of the law set's ``load``; with an environment, less its summits' ``vdw`` and
    ``capillary`` and the open gaps' attraction times the pad's area
    (:func:`mcsim.physics.surfaceenvironment.open_gap_pressures`). On approach without ``d_turn``;
    on retraction after the closest approach ``d_turn`` (m).
    """
    d = np.atleast_1d(np.asarray(d, dtype=float))
    if spec.environment is None:
        return contact_load(spec, z, d, d_turn)
    if spec.surface.radius_by_height is not None:  # each band's contact and caps, its radius
        turn = None if d_turn is None else np.full_like(d, d_turn)
        return net_load(spec, sums(spec, z, d, turn), d)
    # Two sums over the pad's summits: the contact law's over those that can touch, and the
    # caps' over every summit within their reach (each evaluated only where it acts).
    parts = _split_laws(spec)
    load = _load(parts.contact, z, d, d_turn)
    attraction = block_sums(z, d, parts.caps.law, parts.caps.args, edges=parts.caps.edges)
    for column in parts.caps_columns:
        load = load - attraction[:, column]
    return load - spec.area * parts.open_gaps(d / spec.surface.sigma)


def contact_load(spec: MonteCarloSpec, z: np.ndarray, d, d_turn=None) -> np.ndarray:
    """The contact law's load alone (N, the sum of its ``load``) of the pad of summits ``z``
    (m) at separations ``d`` (m); on retraction after ``d_turn`` (m), as :func:`pad_load`."""
    d = np.atleast_1d(np.asarray(d, dtype=float))
    if spec.surface.radius_by_height is not None:  # each band of heights with its radius
        turn = None if d_turn is None else np.full_like(d, d_turn)
        return sums(spec, z, d, turn)[:, sum_columns(spec.law_set).index("load")]
    if spec.environment is None:
        return _load(_Part(spec.law_set, spec.arguments, spec.edges), z, d, d_turn)
    return _load(_split_laws(spec).contact, z, d, d_turn)


class _Part(NamedTuple):
    law: LawSet
    args: tuple
    edges: Edges


def _load(contact: _Part, z: np.ndarray, d: np.ndarray, d_turn) -> np.ndarray:
    """The sum of ``contact``'s output ``load`` (N) over summits ``z`` at separations ``d``."""
    turn = None if d_turn is None else np.full_like(d, d_turn)
    sums = block_sums(z, d, contact.law, contact.args, d_turn=turn, edges=contact.edges)
    return sums[:, sum_columns(contact.law).index("load")]


class _Split(NamedTuple):
    contact: _Part
    caps: _Part
    caps_columns: tuple[int, ...]
    open_gaps: object


@functools.lru_cache(maxsize=16)
def _split_laws(spec: MonteCarloSpec) -> _Split:
    """The contact law set and the environment's caps alone (a law set of the outputs ``vdw``
    and ``capillary``), with their arguments and edges, the caps' columns in their sums, and
    the open gaps' pressure (:func:`open_gaps`), for a humid pad's net load."""
    contact = get_law_set(spec.law)
    caps = with_environment(LawSet("caps", "the environment's caps", ()), spec.surface,
                            spec.environment)  # fmt: skip
    contact, caps = (_Part(law, law.arguments(spec.surface, spec.material),
                           law.edges_for(spec.surface, spec.material)) for law in (contact, caps))  # fmt: skip
    columns = tuple(sum_columns(caps.law).index(term) for term in caps.law.names)
    return _Split(contact, caps, columns, open_gaps(spec))


def net_load(spec: MonteCarloSpec, sums: np.ndarray, d) -> np.ndarray:
    """Net load (N) of a pad of area ``spec.area`` from its sums (last axis the columns of
    :func:`~mcsim.engine.kernels.sum_columns`) at separations ``d`` (m, the second-last axis):
    ``load``, less the caps' ``vdw`` and ``capillary`` and the open gaps' attraction."""
    columns = sum_columns(spec.law_set)
    load = sums[..., columns.index("load")]
    if spec.environment is None:
        return load
    for term in active_terms(spec.environment):
        load = load - sums[..., columns.index(term)]
    return load - spec.area * open_gaps(spec)(np.asarray(d) / spec.surface.sigma)


#: Points of the table of the open gaps' pressure (:func:`open_gaps`), equally spaced in h.
OPEN_GAP_POINTS = 4097


@functools.lru_cache(maxsize=16)
def open_gaps(spec: MonteCarloSpec):
    """The open gaps' attraction (Pa, van der Waals plus capillary) as a function of h = d/σ,
    :func:`mcsim.physics.surfaceenvironment.open_gap_pressures` tabulated once per spec.

    A pad's curve evaluates it at thousands of separations, the same for every pad: a cubic
    spline through :data:`OPEN_GAP_POINTS` values from the lowest separation of ``spec`` to
    where the highest summit's cap ends (beyond, and below, the function itself). It is a
    smooth function of h (a Gaussian average), and the spline is within 1e-9 of its largest
    value (tests/engine/test_padcurves.py).
    """
    from scipy.interpolate import CubicSpline

    surface, env = spec.surface, spec.environment

    def exact(h):
        p = open_gap_pressures(h, surface, env)
        return p["vdw"] + p["capillary"]

    reach = -spec.edges.reach / surface.sigma
    heights = surface.heights  # the highest summit: a measured histogram's top, else 12σ
    top = float(heights.edges[-1]) if hasattr(heights, "edges") else 12.0
    lo, hi = float(spec.h.min()) - 1.0, top + reach + 1.0
    grid = np.linspace(lo, hi, OPEN_GAP_POINTS)
    spline = CubicSpline(grid, exact(grid))

    def pressure(h):
        h = np.asarray(h, dtype=float)
        inside = (h >= lo) & (h <= hi)
        if np.all(inside):
            return spline(h)
        return np.where(inside, spline(h), exact(h))

    return pressure


def contact_edges(spec: MonteCarloSpec) -> Edges:
    """The edges of the contact law alone: where a pad's load can jump or turn sharply.
    The environment's caps add kinks only (their forces are continuous): the search for a
    pad's pull-off and turn samples their intervals inside and does not cut at them."""
    return spec.edges if spec.environment is None else _split_laws(spec).contact.edges


def _intervals(spec: MonteCarloSpec, z: np.ndarray, low: float, high: float,
               edges: Edges | None = None) -> np.ndarray:  # fmt: skip
    """Sorted separations (m) cutting [low, high] where a summit crosses an edge of its law
    (of ``edges``; by default the spec's, the environment's caps included; with a radius by
    height, each band's summits at the edges of their radius)."""

    def cuts_at(z, e):
        in_delta = np.unique([0.0, e.reach, e.jump_in, e.break_off, *e.breakpoints])
        return (z[:, None] - in_delta[None, :]).ravel()

    if spec.surface.radius_by_height is not None:
        band = spec.surface.radius_by_height.band_of(z / spec.surface.sigma)
        cuts = np.concatenate([cuts_at(z[band == k], e) for k, (_, e) in enumerate(spec.parts)])
    else:
        cuts = cuts_at(z, spec.edges if edges is None else edges)
    return np.unique(np.concatenate([[low, high], cuts[(cuts > low) & (cuts < high)]]))


def _points(cuts: np.ndarray, sigma: float) -> np.ndarray:
    """Per interval of ``cuts``: its two one-sided ends and :data:`SUB` interior points."""
    a, b = cuts[:-1, None], cuts[1:, None]
    inside = np.minimum(EDGE * sigma, (b - a) / 4)
    frac = (np.arange(1, SUB + 1) / (SUB + 1))[None, :]
    return np.hstack([a + inside, a + (b - a) * frac, b - inside])  # (intervals, SUB + 2)


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
    cuts = _intervals(spec, z, d_turn, top, contact_edges(spec))
    points = _points(cuts, sigma)
    values = pad_load(spec, z, points.ravel(), d_turn).reshape(points.shape)
    best = int(np.argmin(values))
    force, at = float(values.flat[best]), float(points.flat[best])
    # Zoom on the lowest interior point of the REFINE lowest intervals, all at once: a
    # grid of ZOOM points between its neighbours, the lowest again, until within XTOL.
    rows = np.argsort(values[:, 1:-1].min(axis=1))[:REFINE]
    j = 1 + np.argmin(values[rows, 1:-1], axis=1)
    lo, hi = points[rows, j - 1], points[rows, j + 1]
    frac = np.linspace(0.0, 1.0, ZOOM + 2)[None, :]
    while np.max(hi - lo) > XTOL * sigma:
        x = lo[:, None] + (hi - lo)[:, None] * frac
        v = pad_load(spec, z, x.ravel(), d_turn).reshape(x.shape)
        k = np.clip(np.argmin(v, axis=1), 1, ZOOM)
        i = np.arange(k.size)
        lo, hi = x[i, k - 1], x[i, k + 1]
        if v.min() < force:
            force, at = float(v.min()), float(x.flat[np.argmin(v)])
    return (-force, at) if force < 0 else (0.0, math.nan)


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
    turn (:func:`mcsim.physics.surfaceenvironment.open_gap_works`).
    """
    work = -float(np.sum(contact_works(spec, z, d_turn))) / spec.area
    if spec.environment is not None:
        band = _band(spec, z)
        for k, caps in enumerate(_caps_parts(spec)):  # each band's caps with its radius
            for term, args in zip(caps.law.names, caps.args):
                work += float(np.sum(CAP_WORKS[term](z[band == k] - d_turn, *args))) / spec.area
        gaps = open_gap_works(
            np.float64(d_turn / spec.surface.sigma), spec.surface, spec.environment
        )
        work += float(gaps["vdw"] + gaps["capillary"])
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
    band, works = _band(spec, z), np.zeros(z.shape)
    for k, part in enumerate(_contact_parts(spec)):  # each band of heights with its radius
        works[band == k] = _piece_works(part, z[band == k] - d_turn)
    return works


def _band(spec: MonteCarloSpec, z: np.ndarray) -> np.ndarray:
    """The band of heights of each summit (all 0 with one radius)."""
    if spec.surface.radius_by_height is None:
        return np.zeros(z.shape, dtype=np.intp)
    return spec.surface.radius_by_height.band_of(z / spec.surface.sigma)


@functools.lru_cache(maxsize=16)
def _contact_parts(spec: MonteCarloSpec) -> tuple[_Part, ...]:
    """The contact law alone, with its arguments and edges, for each band of heights."""
    law = get_law_set(spec.law)
    return tuple(_Part(law, law.arguments(part, spec.material), law.edges_for(part, spec.material))
                 for part in spec.surface.components())  # fmt: skip


@functools.lru_cache(maxsize=16)
def _caps_parts(spec: MonteCarloSpec) -> tuple[_Part, ...]:
    """The environment's caps alone (:func:`_split_laws`) for each band of heights."""
    caps = _split_laws(spec).caps.law
    return tuple(_Part(caps, caps.arguments(part, spec.material), caps.edges_for(part, spec.material))
                 for part in spec.surface.components())  # fmt: skip


def _piece_works(part: _Part, delta_turn: np.ndarray) -> np.ndarray:
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
        attraction: the largest d below its first touch where the net load turns
        compressive (far away the load is 0 too, which does not count).

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
    top = max(float(z.max()) - min(spec.edges.reach, 0.0), bottom) if z.size else bottom
    cuts = _intervals(spec, z, bottom, top, contact_edges(spec))
    points = np.unique(np.concatenate([[bottom, top], _points(cuts, sigma).ravel()]))[::-1]

    def reaches(load):  # at 0 the force must be exceeded: far away the load is 0 too
        return load > force if force == 0 else load >= force

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

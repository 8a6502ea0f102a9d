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

In humid air (an environment; one summit radius) both searches are one branch and bound instead
(:func:`_humid_turn`, :func:`_humid_pull_off`): every summit within the caps' band edge
attracts at every separation, and the attraction turns the pad deeper (hundreds of summits
touch), so sampling every interval between every summit's edges costs the square of the
summits. Bounds on the net load over a whole range of separations, proven summit by summit
from the shape of each branch of the contact law (:func:`branches`, :meth:`_Curve.bounds`),
leave only the ranges that can hold the turn or the pull-off to be split; the same
tolerance (:data:`XTOL`) and, for the pull-off, the same sampling and zoom of the intervals
left. The dry path keeps its own points: its results are bit-identical to what they were
(its sums, summed in other batches, would move in their last bits).
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
    contact = _load(parts.contact, z, d, d_turn)
    caps = block_sums(z, d, parts.caps.law, parts.caps.args, edges=parts.caps.edges)
    caps = caps[:, list(parts.caps_columns)].sum(axis=1)
    return contact - caps - spec.area * open_gaps(spec)(d / spec.surface.sigma)


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


@functools.lru_cache(maxsize=16)
def _split_laws(spec: MonteCarloSpec) -> _Split:
    """The contact law set and the environment's caps alone (a law set of the outputs ``vdw``
    and ``capillary``), with their arguments and edges, and the caps' columns in their sums,
    for a humid pad's net load."""
    contact = get_law_set(spec.law)
    caps = with_environment(LawSet("caps", "the environment's caps", ()), spec.surface,
                            spec.environment)  # fmt: skip
    contact, caps = (_Part(law, law.arguments(spec.surface, spec.material),
                           law.edges_for(spec.surface, spec.material)) for law in (contact, caps))  # fmt: skip
    columns = tuple(sum_columns(caps.law).index(term) for term in caps.law.names)
    return _Split(contact, caps, columns)


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
    table = _open_gap_table(spec)

    def pressure(h):
        h = np.asarray(h, dtype=float)
        inside = (h >= table.lo) & (h <= table.hi)
        if np.all(inside):
            return table.spline(h)
        return np.where(inside, table.spline(h), table.exact(h))

    return pressure


class _GapTable(NamedTuple):
    """:func:`_open_gap_table`: the spline (Pa of h), its range in h, the function, the
    spline's steepest |slope| (Pa per unit h)."""

    spline: object
    lo: float
    hi: float
    exact: object
    slope: float


@functools.lru_cache(maxsize=16)
def _open_gap_table(spec: MonteCarloSpec) -> _GapTable:
    """The spline of :func:`open_gaps`, its range [lo, hi] in h, the function itself, and the
    spline's largest |dp/dh| (Pa) on the range: its derivative is a quadratic on each piece,
    so the largest magnitude lies at a knot or where the (linear) second derivative is 0."""
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
    slope = spline.derivative()
    c = spline.c  # piece k: c[0] t^3 + c[1] t^2 + c[2] t + c[3], t = h - grid[k]
    with np.errstate(divide="ignore", invalid="ignore"):
        vertex = np.clip(-c[1] / (3 * c[0]), 0.0, np.diff(grid))  # p'' = 0 inside the piece
    vertex = np.where(np.isfinite(vertex), vertex, 0.0)
    steepest = max(np.max(np.abs(slope(grid))), np.max(np.abs(slope(grid[:-1] + vertex))))
    return _GapTable(spline, lo, hi, exact, float(steepest))


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
    floor = None  # in humid air: a lower bound of each interval's values
    if not _bounded(spec):
        cuts = _intervals(spec, z, d_turn, top, contact_edges(spec))
        points = _points(cuts, sigma)
        values = pad_load(spec, z, points.ravel(), d_turn).reshape(points.shape)
        best = int(np.argmin(values))
        force, at = float(values.flat[best]), float(points.flat[best])
    else:
        points, values, floor, force, at = _humid_pull_off(spec, z, d_turn, top)
        if values.size == 0:
            return (-force, at) if force < 0 else (0.0, math.nan)
        if values.min() < force:
            force, at = float(values.min()), float(points.flat[np.argmin(values)])
    # Zoom on the lowest interior point of the REFINE lowest intervals, all at once: a
    # grid of ZOOM points between its neighbours, the lowest again, until within XTOL
    # (in humid air, dropping the intervals whose bound lies above the lowest value met).
    rows = np.argsort(values[:, 1:-1].min(axis=1))[:REFINE]
    j = 1 + np.argmin(values[rows, 1:-1], axis=1)
    lo, hi = points[rows, j - 1], points[rows, j + 1]
    if floor is not None:
        floor = floor[rows]
        lo, hi, floor = lo[floor <= force], hi[floor <= force], floor[floor <= force]
    frac = np.linspace(0.0, 1.0, ZOOM + 2)[None, :]
    while lo.size and np.max(hi - lo) > XTOL * sigma:
        x = lo[:, None] + (hi - lo)[:, None] * frac
        v = pad_load(spec, z, x.ravel(), d_turn).reshape(x.shape)
        k = np.clip(np.argmin(v, axis=1), 1, ZOOM)
        i = np.arange(k.size)
        lo, hi = x[i, k - 1], x[i, k + 1]
        if v.min() < force:
            force, at = float(v.min()), float(x.flat[np.argmin(v)])
        if floor is not None:
            lo, hi, floor = lo[floor <= force], hi[floor <= force], floor[floor <= force]
    return (-force, at) if force < 0 else (0.0, math.nan)


# --- Humid pads: branch and bound on the pad's curve ------------------------------------


def _bounded(spec: MonteCarloSpec) -> bool:
    """Whether a pad's turn and pull-off are searched by branch and bound: in humid air with
    one summit radius (with a radius by height each band has its own law; those pads keep
    the sampling of every interval)."""
    return spec.environment is not None and spec.surface.radius_by_height is None


class _Branch(NamedTuple):
    """One branch of the contact law's ``load`` of a summit, f(δ) (:func:`branches`): it
    carries force above ``low``, does not rise up to ``falling``, does not fall from
    ``rising`` on, and its values are ``fa`` = f(falling), ``fb`` = f(rising) and at least
    ``m`` (N; interferences in m)."""

    low: float
    falling: float
    rising: float
    fa: float
    fb: float
    m: float


#: Points of :func:`branches`' grid on each branch, reaching this many times the law's
#: largest edge at first.
_BRANCH_POINTS, _BRANCH_SPAN = 4001, 64.0
#: Margin on the minimum found numerically, relative.
_MIN_MARGIN = 1e-6


@functools.lru_cache(maxsize=16)
def branches(spec: MonteCarloSpec) -> tuple[_Branch, _Branch]:
    """The approach and retraction branches of the contact law's load of one summit.

    Law sets with a retraction are *quasiconvex* on each branch (a requirement of
    :mod:`mcsim.physics.laws`): as δ grows, f(δ) is 0 up to the branch's lowest edge, then
    does not rise (it jumps down and falls) to its minimum at some x*, then does not fall.
    On retraction a summit in contact at the turn follows a branch that does not depend on
    δ_max, and one out of contact keeps its approach load (also required). This finds, on a
    geometric grid from the lowest edge, the lowest point y: ``falling`` is the last grid
    point before y with f > f(y) (or the edge) and ``rising`` the first after y with
    f > f(y). Both are proven sides of x*: were ``rising`` at or before x*, f could not rise
    from y to it; were ``falling`` at or past x*, f could not fall from it to y. So f does
    not rise on (−∞, falling] and does not fall on [rising, ∞), and on [falling, rising] it
    stays below max(fa, fb) (the argument takes the law's values as exact; its rounding moves
    these points by where f changes in its last bits only). ``m`` is the least value met,
    with a golden-section search between y's neighbours, made :data:`_MIN_MARGIN` more
    negative: the one number here found numerically rather than proven (the tests check it
    against Johnson's forces for JKR and a dense grid for every law set).
    """
    from scipy.optimize import minimize_scalar

    part = _split_laws(spec).contact
    e = part.edges
    i = part.law.names.index("load")
    out, args = part.law.outputs[i], part.args[i]
    scale = max(abs(x) for x in (e.reach, e.jump_in, e.break_off, *e.breakpoints, 1e-12))
    result = []
    for low, retract in ((e.reach, False), (min(e.reach, e.break_off), True)):
        span = _BRANCH_SPAN
        while True:
            x = low + scale * np.geomspace(1e-9, span, _BRANCH_POINTS)
            turn = max(x[-1], e.jump_in) + scale  # on retraction: in contact, past every x

            def f(delta, turn=turn if retract else None):
                delta = np.asarray(delta, dtype=float)
                state = delta if turn is None else np.full_like(delta, turn)
                return out.law(delta, state, *args) if out.stateful else out.law(delta, *args)

            y = f(x)
            k = int(np.argmin(y))
            after = np.flatnonzero(y[k + 1 :] > y[k])
            if after.size:
                break
            span *= 4  # the minimum lies beyond the grid: look further
        before = np.flatnonzero(y[:k] > y[k])
        falling = float(x[before[-1]]) if before.size else low
        rising = float(x[k + 1 + after[0]])
        left = x[k - 1] if k else low
        best = minimize_scalar(lambda t: float(f(np.array([t]))[0]), bounds=(left, x[k + 1]),
                               method="bounded", options={"xatol": 1e-12 * (x[k + 1] - left)})  # fmt: skip
        m = min(float(y[k]), float(best.fun), 0.0) * (1 + _MIN_MARGIN)
        fa = float(f(np.array([falling]))[0]) if before.size else 0.0
        result.append(_Branch(low, falling, rising, fa, float(f(np.array([rising]))[0]), m))
    return result[0], result[1]


def _count(zs: np.ndarray, lo, hi) -> np.ndarray:
    """How many of the sorted heights ``zs`` lie in (lo, hi] (m), elementwise (0 if empty)."""
    return np.maximum(np.searchsorted(zs, hi, "right") - np.searchsorted(zs, lo, "right"), 0)


class _Group(NamedTuple):
    """Summits on one branch: sorted heights (m) and the branch."""

    z: np.ndarray
    branch: _Branch


class _Setup(NamedTuple):
    """What a humid pad's search needs of its spec, looked up once (hashing a spec costs)."""

    sigma: float
    area: float
    parts: _Split
    edges: Edges
    branches: tuple[_Branch, _Branch]
    gaps: object
    table: _GapTable


@functools.lru_cache(maxsize=16)
def _setup(spec: MonteCarloSpec) -> _Setup:
    """The :class:`_Setup` of ``spec``."""
    parts = _split_laws(spec)
    return _Setup(spec.surface.sigma, spec.area, parts, parts.contact.edges, branches(spec),
                  open_gaps(spec), _open_gap_table(spec))  # fmt: skip


def _above(part: _Part, z, d, d_turn, theta):
    """The contact law's load (N) summed over the summits above d + ``theta`` (m) at ``d``."""
    return _load(_Part(part.law, part.args, Edges(theta, theta, theta)), z, d, d_turn)


class _Curve:
    """The points of a humid pad's curve evaluated so far: separations ``x`` (ascending, m),
    net load ``net`` (N), and the ``sums`` (N) its bounds need (:meth:`bounds`): for each
    group of summits (one branch each) the contact load, and what the summits between the
    branch's lowest edge and its ``falling`` and ``rising`` points add to it; last the caps'
    attraction. ``cuts`` (m) are where a summit crosses an edge of its branch."""

    def __init__(self, setup, groups, z, d_turn, cuts, lower=False):
        self.setup, self.groups, self.z, self.d_turn, self.cuts = setup, groups, z, d_turn, cuts
        self.lower = lower  # only the lower bounds are asked for
        self.x = np.empty(0)
        self.sums = np.empty((0, 3 * len(groups) + 1))

    def add(self, d):
        """Evaluate the curve at the new separations ``d`` (m)."""
        if d.size == 0:
            return
        setup = self.setup
        contact, caps = setup.parts.contact, setup.parts.caps
        columns = []
        for g in self.groups:
            b = g.branch
            whole = _load(contact, g.z, d, self.d_turn)
            columns.append(whole)
            for theta in (b.falling, b.rising):  # what the summits in (d + low, d + theta] add
                empty = theta <= b.low or not np.any(_count(g.z, d + b.low, d + theta))
                empty |= theta == b.rising and self.lower  # the lower bound needs falling only
                columns.append(np.zeros(d.size) if empty else
                               whole - _above(contact, g.z, d, self.d_turn, theta))  # fmt: skip
        k = block_sums(self.z, d, caps.law, caps.args, edges=caps.edges)  # no history
        columns.append(k[:, list(setup.parts.caps_columns)].sum(axis=1))
        x = np.concatenate([self.x, d])
        order = np.argsort(x, kind="stable")
        self.x = x[order]
        self.sums = np.concatenate([self.sums, np.stack(columns, axis=1)])[order]
        self.gaps = setup.area * setup.gaps(self.x / setup.sigma)
        self.net = self.sums[:, 0:-1:3].sum(axis=1) - self.sums[:, -1] - self.gaps

    def bounds(self):
        """The highest and the lowest net load (N) that each gap between two points can hold.

        Proven, summit by summit. In the gap [x_k, x_k+1] a summit at z spans the
        interferences [δ1, δ2] = [z − x_k+1, z − x_k]; on its branch (:func:`branches`) its
        load f does not rise up to a = ``falling``, does not fall from r = ``rising`` on, and
        lies between m and top = max(f(a), f(r)) on [a, r]. Its lowest value over the gap:
        f(δ2) (at x_k) if δ2 <= a, f(δ1) (at x_k+1) if δ1 > r, else at least m, which is
        at most f(δ1) − (top − m) where a < δ1 <= r: so the lower bound needs the sums about
        a only (a curve asked for ``lower`` bounds only leaves the sums about r out, and
        has no upper bounds: None). Its highest:
        f(δ1) (at x_k+1) if δ2 <= a, f(δ2) (at x_k) if δ1 > r; if δ1 <= a < δ2 <= r at most
        f(δ1) + top − m; if a < δ1 <= r < δ2 at most f(δ2) + (top − f(r))⁺; if it spans
        [a, r] at most f(δ1) + f(δ2) + top − 2m (all three at least m); inside (a, r] top.
        The sums over each class are the kernel's sums at x_k or x_k+1 over the summits
        above or below d + a or d + r, where d is that end (``sums``); the counts come from
        the sorted heights. The caps attract more the closer (each summit's van der Waals
        and meniscus force rise with δ: :mod:`mcsim.physics.laws.attraction`), so they lie
        between their sums at the two ends; the open gaps' term between the mean of its ends
        ∓ the spline's steepest slope times half the gap (:func:`_open_gap_table`).
        """
        x, s = self.x, self.sums
        lo_x, hi_x = x[:-1], x[1:]
        table, h = self.setup.table, x / self.setup.sigma
        inside = (h[:-1] >= table.lo) & (h[1:] <= table.hi)
        slack = np.where(inside, self.setup.area * table.slope * np.diff(h) / 2, np.inf)
        mean = (self.gaps[:-1] + self.gaps[1:]) / 2
        upper = -s[1:, -1] - (mean - slack)  # the caps attract least at the top of a gap
        lower = -s[:-1, -1] - (mean + slack)
        for j, g in enumerate(self.groups):
            whole, below_a, below_b = s[:, 3 * j], s[:, 3 * j + 1], s[:, 3 * j + 2]
            above_b = whole - below_b
            b, zs = g.branch, g.z
            a, r, m, top = b.falling, b.rising, b.m, max(b.fa, b.fb)
            # lowest: f(δ2) if δ2 <= a; f(δ1) if δ1 > a, less top - m if δ1 <= r; else m
            lower = (
                lower + below_a[:-1] + (whole - below_a)[1:] + m * _count(zs, lo_x + a, hi_x + a)
            )
            lower = lower - (top - m) * _count(zs, hi_x + a, hi_x + r)
            # highest: f(δ1) for δ1 <= a, f(δ2) for δ2 > r, what the rest can add
            n1 = _count(zs, lo_x + a, np.minimum(hi_x + a, lo_x + r))
            n2 = _count(zs, np.maximum(hi_x + a, lo_x + r), hi_x + r)
            n3 = _count(zs, lo_x + r, hi_x + a)
            n4 = _count(zs, hi_x + a, lo_x + r)
            upper = upper + below_a[1:] + above_b[:-1] + (top - m) * n1
            upper = upper + max(top - b.fb, 0.0) * n2 + (top - 2 * m) * n3 + top * n4
        return (None if self.lower else upper), lower

    def split(self, gaps, ends=(), force=None):
        """New points splitting each gap ``gaps`` (indices; or the range ``ends``): at up to
        :data:`PARTS` − 1 of the cuts inside it, just on either side (:data:`EDGE`); with
        none, evenly into :data:`EVEN` parts, or, where the net load crosses ``force``
        (N) between the gap's ends, on a ladder about where a straight line crosses it."""
        side = EDGE * self.setup.sigma
        if len(ends):
            a, b, gaps = np.array([ends[0]]), np.array([ends[1]]), None
        else:
            a, b = self.x[gaps], self.x[gaps + 1]
        i = np.searchsorted(self.cuts, a + side, "right")
        n = np.searchsorted(self.cuts, b - side, "left") - i
        new = [np.asarray(ends, dtype=float)]
        cut = n > 0
        if np.any(cut):  # up to PARTS - 1 of the cuts inside, evenly by rank
            rank = np.arange(PARTS - 1) / (PARTS - 2)
            pick = i[cut, None] + np.round(rank[None, :] * (n[cut, None] - 1)).astype(int)
            pick = np.unique(pick)
            new += [self.cuts[pick] - side, self.cuts[pick] + side]
        even = ~cut
        if force is not None:
            crossing = even & ((self.net[gaps] - force) * (self.net[gaps + 1] - force) < 0)
            new += [self._ladder(g, force) for g in gaps[crossing]]
            even &= ~crossing
        frac = np.arange(1, EVEN) / EVEN
        new.append((a[even, None] + (b - a)[even, None] * frac[None, :]).ravel())
        return np.concatenate(new)

    def _ladder(self, g, force):
        """Points in gap ``g`` at x ± (XTOL σ/2)·r^k about the crossing x of ``force`` by the
        straight line between its ends, r from how fast the load changes against how much
        its parts do (so that the gaps of the ladder can be bounded away from the force)."""
        a, b = self.x[g], self.x[g + 1]
        fa, fb = self.net[g], self.net[g + 1]
        x = a + (b - a) * (fa - force) / (fa - fb)
        # >= |fb - fa| > 0: the net load is a sum of the parts, signed
        change = np.sum(np.abs(self.sums[g + 1] - self.sums[g])) + abs(
            self.gaps[g + 1] - self.gaps[g]
        )
        r = float(np.clip(1 + abs(fb - fa) / (2 * change), *LADDER))
        tol = XTOL * self.setup.sigma
        step = tol / 2 * r ** np.arange(math.ceil(math.log((b - a) / tol) / math.log(r)) + 1)
        points = np.concatenate([x - step, x + step])
        return points[(points > a) & (points < b)]

    def unsplit(self, gaps):
        """Whether each gap ``gaps`` holds a cut not yet split on (:meth:`split`)."""
        side = EDGE * self.setup.sigma
        x = self.x
        n = np.searchsorted(self.cuts, x[gaps + 1] - side) - np.searchsorted(
            self.cuts, x[gaps] + side, "right")  # fmt: skip
        return n > 0


#: Parts into which a humid pad's search splits a range that may hold its turn or pull-off:
#: at its cuts, or evenly where it holds none.
PARTS, EVEN = 64, 32
#: Least and largest ratio of :meth:`_Curve._ladder`'s steps.
LADDER = (1.2, 2.0)


def _cuts(z: np.ndarray, low: float, high: float, in_delta) -> np.ndarray:
    """Sorted separations in (low, high) (m) where a summit of ``z`` crosses ``in_delta``."""
    cuts = (z[:, None] - np.unique(in_delta)[None, :]).ravel()
    return np.unique(cuts[(cuts > low) & (cuts < high)])


def _humid_turn(spec, z, force, bottom, top, reaches):
    """:func:`force_turn` in humid air: the largest d in [bottom, top] (m) whose net load
    ``reaches`` the force, and the load there (N).

    Branch and bound: evaluate points, and split every gap above the highest point that
    reaches whose upper bound (:meth:`_Curve.bounds`) still reaches, at the approach's cuts
    while it holds some (jump-in, reach, breakpoints: the caps' forces are continuous), then
    evenly, or on a ladder about the crossing (:meth:`_Curve._ladder`), down to
    :data:`XTOL`. Every d above the returned point lies in a gap whose bound stays below
    the force, or in one narrower than XTOL (tests/engine/test_padcurves.py checks both
    against a dense evaluation).
    """
    setup = _setup(spec)
    e = setup.edges
    cuts = _cuts(z, bottom, top, (e.reach, e.jump_in, *e.breakpoints))
    curve = _Curve(setup, (_Group(np.sort(z), setup.branches[0]),), z, None, cuts)
    new = curve.split(None, (bottom, top))
    while new.size:
        curve.add(new)
        hit = np.flatnonzero(reaches(curve.net))
        first = int(hit[-1]) if hit.size else 0
        upper, _ = curve.bounds()
        live = np.flatnonzero(reaches(upper) & (np.diff(curve.x) > XTOL * setup.sigma))
        new = curve.split(live[live >= first], force=force)
    if not hit.size:
        raise ParameterError(
            f"preload force {force:.4g} N: the pad's approach load is {curve.net[0]:.4g} N at "
            f"the grid's lowest separation h = {spec.h.min():g}; extend the separations (--h) down"
        )
    return float(curve.x[first]), float(curve.net[first])


def _humid_pull_off(spec, z, d_turn, top):
    """The intervals of a humid pad's retraction that may hold its pull-off: their points
    and values as :func:`_points` gives them and the lower bound of their values (N), and
    the lowest value met (N) and where (m).

    Branch and bound on the retraction's cuts (break-off, reach, breakpoints for a summit in
    contact at the turn; reach, breakpoints for one that is not): evaluate points, drop
    every gap whose lower bound (:meth:`_Curve.bounds`) lies above the lowest value met,
    split the others at their cuts, until none is left; the intervals left between the
    cuts are then sampled and zoomed on as on the dry path (:func:`pull_off`).
    """
    setup = _setup(spec)
    e = setup.edges
    approach, retract = setup.branches
    held = z - d_turn > e.jump_in  # in contact at the turn: on the retraction branch
    groups = [_Group(np.sort(z[held]), retract)]
    cuts = [_cuts(z[held], d_turn, top, (e.reach, e.break_off, *e.breakpoints))]
    if approach.low < e.jump_in and not np.all(held):  # the others may feel an attraction
        groups.append(_Group(np.sort(z[~held]), approach))
        cuts.append(_cuts(z[~held], d_turn, top, (e.reach, *e.breakpoints)))
    curve = _Curve(setup, tuple(groups), z, d_turn, np.unique(np.concatenate(cuts)), lower=True)
    new = curve.split(None, (d_turn, top))
    while new.size:
        curve.add(new)
        _, lower = curve.bounds()
        live = np.flatnonzero(lower <= curve.net.min())
        new = curve.split(live[curve.unsplit(live)])
    # the live gaps between cuts (not the 2·EDGE about one), sampled as _points does
    x = curve.x
    live = live[np.diff(x)[live] > 2 * EDGE * setup.sigma]
    a, b = x[live, None], x[live + 1, None]
    inner = a + (b - a) * (np.arange(1, SUB + 1) / (SUB + 1))[None, :]
    values = pad_load(spec, z, inner.ravel(), d_turn).reshape(inner.shape)
    points = np.hstack([a, inner, b])
    values = np.hstack([curve.net[live, None], values, curve.net[live + 1, None]])
    best = int(np.argmin(curve.net))
    return points, values, lower[live], float(curve.net[best]), float(x[best])


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

    def reaches(load):  # at 0 the force must be exceeded: far away the load is 0 too
        return load > force if force == 0 else load >= force

    if _bounded(spec):
        return _humid_turn(spec, z, force, bottom, top, reaches)
    cuts = _intervals(spec, z, bottom, top, contact_edges(spec))
    points = np.unique(np.concatenate([[bottom, top], _points(cuts, sigma).ravel()]))[::-1]
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

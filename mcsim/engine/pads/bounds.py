"""Humid pads: their turn and pull-off by branch and bound on the pad's curve.

In humid air every summit within the caps' band edge attracts at every separation, and the
attraction turns the pad deeper (hundreds of summits touch), so sampling every interval
between every summit's edges, as :mod:`mcsim.engine.pads.curves` does for a dry pad, costs the
square of the summits. Bounds on the net load over a whole range of separations, proven
summit by summit from the shape of each branch of the contact law (:func:`branches`,
:meth:`_Curve.bounds`), leave only the ranges that can hold the turn (:func:`humid_turn`) or
the pull-off (:func:`humid_pull_off`) to be split; the same tolerance
(:data:`~mcsim.engine.pads.load.XTOL`) and, for the pull-off, the same sampling and zoom of the
intervals left (:func:`mcsim.engine.pads.curves.pull_off`). With a radius by height each band
of heights has its own radius, hence its own law arguments, edges and branches: its summits
are bounded on its own branches (a group per band and branch, :class:`_Group`).
"""

from __future__ import annotations

import functools
from functools import reduce
from operator import add
from typing import NamedTuple

import numpy as np

from mcsim.engine.kernels import prepared
from mcsim.engine.pads.load import (
    EDGE,
    SUB,
    XTOL,
    GapTable,
    Part,
    Split,
    open_gap_table,
    open_gaps,
    pad_load,
    split_laws,
)
from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.errors import ParameterError
from mcsim.physics.laws import Edges


def bounded(spec: MonteCarloSpec) -> bool:
    """Whether a pad's turn and pull-off are searched by branch and bound: in humid air (an
    environment), with one summit radius or a radius by height."""
    return spec.environment is not None


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
#: Refinements of :func:`branches`' bracket of the minimum, each on a grid of
#: :data:`_BRANCH_POINTS` between its two sides (fewer once f is flat there to rounding).
_BRANCH_REFINE = 8
#: Margin on the minimum found numerically, relative.
_MIN_MARGIN = 1e-6


def branches(part: Part) -> tuple[_Branch, _Branch]:
    """The approach and retraction branches of the contact law's load of one summit, of the
    law set, arguments and edges ``part`` (one band of heights; found once per spec and
    band: :func:`_setup`).

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
    these points by where f changes in its last bits only). The same argument on a grid
    between ``falling`` and ``rising``, again and again (:data:`_BRANCH_REFINE`), brings them
    together until f is flat there to rounding: the bounds of a summit between them
    (max(fa, fb) above, ``m`` below) then differ by rounding only, so that the bounds of
    :meth:`_Curve.bounds` close in on the curve as its gaps narrow (with them apart by a
    grid step, a summit between them kept the bound of a narrow gap a fixed amount above
    the curve, and the search split on down to XTOL: DMT's pads on the smooth surface took
    0.1–0.3 s each). ``m`` is the least value met,
    with a golden-section search between y's neighbours, made :data:`_MIN_MARGIN` more
    negative: the one number here found numerically rather than proven (the tests check it
    against Johnson's forces for JKR and a dense grid for every law set).
    """
    from scipy.optimize import minimize_scalar

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
                               method="bounded",
                               options={"xatol": 1e-12 * (x[k + 1] - left)})  # fmt: skip
        lowest = min(float(y[k]), float(best.fun))
        # the same argument on ever finer grids between them, until f is flat to rounding
        for _ in range(_BRANCH_REFINE):
            grid = np.linspace(falling, rising, _BRANCH_POINTS)
            values = f(grid)
            j = int(np.argmin(values))
            lowest = min(lowest, float(values[j]))
            before = np.flatnonzero(values[:j] > values[j])
            after = j + 1 + np.flatnonzero(values[j + 1 :] > values[j])
            bracket = (float(grid[before[-1]]) if before.size else falling,
                       float(grid[after[0]]) if after.size else rising)  # fmt: skip
            if bracket == (falling, rising):
                break
            falling, rising = bracket
        m = min(lowest, 0.0) * (1 + _MIN_MARGIN)
        fa = float(f(np.array([falling]))[0]) if falling > low else 0.0
        result.append(_Branch(low, falling, rising, fa, float(f(np.array([rising]))[0]), m))
    return result[0], result[1]


class _Group(NamedTuple):
    """Summits of one band of heights on one branch: sorted heights (m), the branch and the
    band (its index in :attr:`_Setup.bands`)."""

    z: np.ndarray
    branch: _Branch
    band: int


class _Band(NamedTuple):
    """One band of heights' part of a humid pad's search: its contact law's edges and
    branches, and for each branch's ``falling`` the contact law's sums over the summits
    above it."""

    edges: Edges
    branches: tuple[_Branch, _Branch]
    above: dict


class _Setup(NamedTuple):
    """What a humid pad's search needs of its spec, looked up once (hashing a spec costs)."""

    sigma: float
    area: float
    parts: Split
    bands: tuple[_Band, ...]
    gaps: object
    table: GapTable


@functools.lru_cache(maxsize=16)
def _setup(spec: MonteCarloSpec) -> _Setup:
    """The :class:`_Setup` of ``spec``."""
    parts = split_laws(spec)
    bands = []
    for band in parts.bands:
        c = band.contact
        pair = branches(c)
        above = {b.falling: prepared(c.law, c.args, Edges(*[b.falling] * 3))
                 for b in pair if b.falling > b.low}  # fmt: skip
        bands.append(_Band(c.edges, pair, above))
    return _Setup(spec.surface.sigma, spec.area, parts, tuple(bands), open_gaps(spec),
                  open_gap_table(spec))  # fmt: skip


class _Curve:
    """The points of a humid pad's curve evaluated so far: separations ``x`` (ascending, m),
    net load ``net`` (N), and the ``sums`` (N) its bounds need (:meth:`bounds`): for each
    group of summits (one band and branch each) the contact load, and what the summits
    between the branch's lowest edge and its ``falling`` point add to it; last the caps'
    attraction, summed over the bands (``z``: each band's summits, m). ``cuts`` (m) are
    where a summit crosses an edge of its branch."""

    def __init__(self, setup, groups, z, d_turn, cuts, lower=False):
        self.setup, self.groups, self.z, self.d_turn, self.cuts = setup, groups, z, d_turn, cuts
        self.lower = lower  # only the lower bounds are asked for
        self.x = self.gaps = self.net = np.empty(0)
        self.sums = np.empty((0, 2 * len(groups) + 1))

    def add(self, d):
        """Evaluate the curve at the new separations ``d`` (m)."""
        if d.size == 0:
            return
        setup, parts = self.setup, self.setup.parts
        turn = d if self.d_turn is None else np.full_like(d, self.d_turn)
        sums = np.empty((d.size, self.sums.shape[1]))
        for j, g in enumerate(self.groups):
            b = g.branch
            sums[:, 2 * j] = whole = parts.bands[g.band].contact_sums(g.z, d, turn)[:, parts.load]
            # what the summits in (d + low, d + falling] add
            sums[:, 2 * j + 1] = 0.0 if b.falling <= b.low else (
                whole - setup.bands[g.band].above[b.falling](g.z, d, turn)[:, parts.load])  # fmt: skip
        caps = (parts.caps_load(zk, d, k) for k, zk in enumerate(self.z))
        sums[:, -1] = reduce(add, caps)  # no history
        gaps = setup.area * setup.gaps(d / setup.sigma)
        net = sums[:, 0:-1:2].sum(axis=1) - sums[:, -1] - gaps
        if self.x.size:
            d, sums = np.concatenate([self.x, d]), np.concatenate([self.sums, sums])
            gaps, net = np.concatenate([self.gaps, gaps]), np.concatenate([self.net, net])
        order = np.argsort(d, kind="stable")
        self.x, self.sums, self.gaps, self.net = d[order], sums[order], gaps[order], net[order]

    def bounds(self):
        """The highest and the lowest net load (N) that each gap between two points can hold.

        Proven, summit by summit. In the gap [x_k, x_k+1] a summit at z spans the
        interferences [δ1, δ2] = [z − x_k+1, z − x_k]; on its branch (:func:`branches`) its
        load f does not rise up to a = ``falling``, does not fall from r = ``rising`` on, and
        lies between m and top = max(f(a), f(r)) on [a, r]. Its lowest value over the gap:
        f(δ2) (at x_k) if δ2 <= a, f(δ1) (at x_k+1) if δ1 > r, else at least m, which is
        at most f(δ1) − (top − m) where a < δ1 <= r: so the lower bound needs the sums about
        a only (a curve asked for ``lower`` bounds only has no upper bounds: None). Its
        highest: f(δ1) (at x_k+1) if δ2 <= a, f(δ2) (at x_k) if δ1 > r; if δ1 <= a < δ2 <= r
        at most f(δ1) + top − m; if a < δ1 <= r < δ2 at most f(δ2) + (top − f(r))⁺; if it
        spans [a, r] at most f(δ1) + f(δ2) + top − 2m (all three at least m); inside (a, r]
        top. The sums over each class are the kernel's sums at x_k or x_k+1 over the
        summits above or below d + a, where d is that end (``sums``); those above d + r are
        at most the sum above d + a less m for each summit in between, which
        :func:`branches` makes a rounding narrow; the counts come from the sorted heights.
        With a radius by height each group's summits are bounded on their own band's branch.
        The caps attract more the closer (each summit's van der Waals and meniscus force
        rise with δ, whatever its radius: :mod:`mcsim.physics.laws.attraction`), so their
        sum over every band lies between its values at the two ends; the open gaps' term
        between the mean of its ends ∓ the spline's steepest slope times half the gap
        (:func:`open_gap_table`).
        Compiled: :func:`mcsim.engine.pads.gaps.environment_bounds` and
        :func:`~mcsim.engine.pads.gaps.branch_bounds`.
        """
        from mcsim.engine.pads import gaps as padgaps

        x, s, setup = self.x, self.sums, self.setup
        upper, lower = np.empty(x.size - 1), np.empty(x.size - 1)
        table = setup.table
        padgaps.environment_bounds(x, s[:, -1], self.gaps, setup.sigma, table.lo, table.hi,
                                   setup.area * table.slope, upper, lower)  # fmt: skip
        for j, g in enumerate(self.groups):
            b = g.branch
            padgaps.branch_bounds(x, s[:, 2 * j], s[:, 2 * j + 1], g.z, b.falling, b.rising, b.m,
                                  max(b.fa, b.fb), b.fb, upper, lower, self.lower)  # fmt: skip
        return (None if self.lower else upper), lower

    def split(self, gaps, ends=(), force=None, sides=2):
        """New points splitting each gap ``gaps`` (indices; or the range ``ends``): at up to
        :data:`PARTS` − 1 of the cuts inside it, just on either side
        (:data:`~mcsim.engine.pads.load.EDGE`; ``sides`` = 1: just below, enough for the
        retraction, whose load jumps up where a summit breaks off, and for its bounds, which
        hold for any points); with none, evenly into :data:`EVEN` parts, or, where the net
        load crosses ``force`` (N) between the gap's ends, on a ladder: at x ± 0.45·XTOL
        σ·r^k about where the straight line between its ends crosses it, r (within
        :data:`LADDER`) from how fast the load changes against how much its parts do, so
        that the gaps of the ladder can be bounded away from the force. Compiled:
        :func:`mcsim.engine.pads.gaps.split_points`."""
        from mcsim.engine.pads import gaps as padgaps

        side, tol = EDGE * self.setup.sigma, XTOL * self.setup.sigma
        if len(ends):
            a, b = np.array([ends[0]]), np.array([ends[1]])
            fa = fb = change = np.full(1, np.nan)
        else:
            a, b, fa, fb = self.x[gaps], self.x[gaps + 1], self.net[gaps], self.net[gaps + 1]
            # >= |fb - fa| > 0 where it crosses: the net load is a sum of the parts, signed
            change = np.abs(self.sums[gaps + 1] - self.sums[gaps]).sum(axis=1) + np.abs(
                self.gaps[gaps + 1] - self.gaps[gaps]
            )
        force = np.nan if force is None else force
        new = padgaps.split_points(a, b, fa, fb, change, self.cuts, side, sides, force, tol, PARTS,
                                   EVEN, np.array(LADDER))  # fmt: skip
        return np.concatenate([np.asarray(ends, dtype=float), new])

    def unsplit(self, gaps):
        """Whether each gap ``gaps`` holds a cut not yet split on (:meth:`split`)."""
        side = EDGE * self.setup.sigma
        x = self.x
        n = np.searchsorted(self.cuts, x[gaps + 1] - side) - np.searchsorted(
            self.cuts, x[gaps] + 2 * side, "right")  # fmt: skip
        return n > 0


#: Parts into which a humid pad's search splits a range that may hold its turn or pull-off:
#: at its cuts, or evenly where it holds none.
PARTS, EVEN = 64, 32
#: Least and largest ratio of the steps of :meth:`_Curve.split`'s ladder.
LADDER = (1.2, 2.0)


def _cuts(z: np.ndarray, low: float, high: float, in_delta) -> np.ndarray:
    """Sorted separations in (low, high) (m) where a summit of ``z`` crosses ``in_delta``."""
    cuts = (z[:, None] - np.unique(in_delta)[None, :]).ravel()
    return np.unique(cuts[(cuts > low) & (cuts < high)])


def humid_turn(spec, z, force, bottom, top, reaches):
    """:func:`~mcsim.engine.pads.curves.force_turn` in humid air: the largest d in [bottom, top]
    (m) whose net load ``reaches`` the force, and the load there (N).

    Branch and bound: evaluate points, and split every gap above the highest point that
    reaches whose upper bound (:meth:`_Curve.bounds`) still reaches, at the approach's cuts
    while it holds some (jump-in, reach, breakpoints: the caps' forces are continuous), then
    evenly, or on a ladder about the crossing (:meth:`_Curve.split`), down to
    :data:`~mcsim.engine.pads.load.XTOL`. Every d above the returned point lies in a gap whose
    bound stays below the force, or in one narrower than XTOL (tests/engine/test_padcurves.py
    checks both against a dense evaluation).
    """
    setup = _setup(spec)
    curve = _approach(spec, z, bottom, top)
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


def _approach(spec, z, bottom, top) -> _Curve:
    """A humid pad's approach, as an empty :class:`_Curve`: each band's summits on its
    approach branch, and the cuts in (``bottom``, ``top``) (m; jump-in, reach, breakpoints of
    each summit's band: the caps' forces are continuous)."""
    setup = _setup(spec)
    z = np.ascontiguousarray(z, dtype=float)
    zs, groups, cuts = setup.parts.split(z), [], []
    for k, (zk, band) in enumerate(zip(zs, setup.bands)):
        e = band.edges
        groups.append(_Group(np.sort(zk), band.branches[0], k))
        cuts.append(_cuts(zk, bottom, top, (e.reach, e.jump_in, *e.breakpoints)))
    return _Curve(setup, tuple(groups), zs, None, np.unique(np.concatenate(cuts)))


def _retraction(spec, z, d_turn, top=None) -> _Curve:
    """A humid pad's retraction after the closest approach ``d_turn`` (m), as a :class:`_Curve`
    asked for lower bounds only: in each band of heights, the summits in contact at the turn
    on its retraction branch, the others (if they can feel an attraction) on its approach
    branch, and the cuts up to ``top`` (m; none without: break-off, reach, breakpoints of
    its band for a summit in contact, reach, breakpoints for one that is not)."""
    setup = _setup(spec)
    z = np.ascontiguousarray(z, dtype=float)
    zs, groups, cuts = setup.parts.split(z), [], []
    ends = (d_turn, d_turn if top is None else top)
    for k, (zk, band) in enumerate(zip(zs, setup.bands)):
        e, (approach, retract) = band.edges, band.branches
        held = zk - d_turn > e.jump_in  # in contact at the turn: on the retraction branch
        groups.append(_Group(np.sort(zk[held]), retract, k))
        cuts.append(_cuts(zk[held], *ends, (e.reach, e.break_off, *e.breakpoints)))
        if approach.low < e.jump_in and not np.all(held):  # the others may feel an attraction
            groups.append(_Group(np.sort(zk[~held]), approach, k))
            cuts.append(_cuts(zk[~held], *ends, (e.reach, *e.breakpoints)))
    return _Curve(setup, tuple(groups), zs, d_turn, np.unique(np.concatenate(cuts)), lower=True)


def bracket_floors(curve: _Curve, lo, hi) -> np.ndarray:
    """A lower bound (N) of the retraction load of ``curve``'s pad (:func:`humid_pull_off`) on
    each of the disjoint ranges [``lo``, ``hi``] (m): :meth:`_Curve.bounds` on a curve of
    their ends."""
    ends = _Curve(curve.setup, curve.groups, curve.z, curve.d_turn, curve.cuts, lower=True)
    ends.add(np.concatenate([lo, hi]))
    _, lower = ends.bounds()
    return lower[np.searchsorted(ends.x, lo, "right") - 1]


def humid_pull_off(spec, z, d_turn, top):
    """The curve of a humid pad's retraction (a :class:`_Curve`, for :func:`bracket_floors`),
    the intervals of it that may hold its pull-off: their points and values as
    :func:`~mcsim.engine.pads.load.interval_points` gives them and the lower bound of their values
    (N), and the lowest value met (N) and where (m).

    Branch and bound on the retraction's cuts (break-off, reach, breakpoints for a summit in
    contact at the turn; reach, breakpoints for one that is not): evaluate points, drop
    every gap whose lower bound (:meth:`_Curve.bounds`) lies above the lowest value met,
    split the others just below their cuts, until none is left; the intervals left between
    the cuts are then sampled and zoomed on as on the dry path
    (:func:`~mcsim.engine.pads.curves.pull_off`), a zoomed bracket dropped once its own bound
    (:func:`bracket_floors`) lies above the lowest value met.
    """
    setup = _setup(spec)
    curve = _retraction(spec, z, d_turn, top)
    new = curve.split(None, (d_turn, top), sides=1)
    while new.size:
        curve.add(new)
        _, lower = curve.bounds()
        live = np.flatnonzero(lower <= curve.net.min())
        new = curve.split(live[curve.unsplit(live)], sides=1)
    # the live gaps between cuts (not the 2·EDGE about one), sampled as interval_points does
    x = curve.x
    live = live[np.diff(x)[live] > 2 * EDGE * setup.sigma]
    a, b = x[live, None], x[live + 1, None]
    inner = a + (b - a) * (np.arange(1, SUB + 1) / (SUB + 1))[None, :]
    values = pad_load(spec, z, inner.ravel(), d_turn).reshape(inner.shape)
    points = np.hstack([a, inner, b])
    values = np.hstack([curve.net[live, None], values, curve.net[live + 1, None]])
    best = int(np.argmin(curve.net))
    return curve, points, values, lower[live], float(curve.net[best]), float(x[best])

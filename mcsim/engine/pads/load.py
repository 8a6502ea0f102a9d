"""One pad's own load, exactly: its summits regenerated from the run's seed, and where its
curve is smooth.

A ``--cycle`` run stores sums on a grid of separations, so the most tensile grid value
of a pad's retraction load is biased (the grid misses the minimum between its points,
and ends somewhere). Its summits, though, are a pure function of the seed: realization
r draws its counts from the stream ``(r, 0)`` and block b its heights from ``(r, 1 + b)``
(:func:`mcsim.engine.montecarlo.plan_patch`, :func:`~mcsim.engine.montecarlo.sample_block`).
:func:`patch_heights` draws them again, the same numbers the run summed, and the load of
the pad at any separation (:func:`pad_load`) is the compiled kernel's sum of the law set's
per-summit ``load`` (:func:`mcsim.engine.kernels.block_sums`) over those heights; in humid
air less its summits' caps and the open gaps (:func:`open_gaps`). The curve is smooth
between the separations where a summit crosses an edge of its law set (break-off, jump-in,
reach, breakpoints: d = z_i − e, :func:`smooth_intervals`), which the searches of
:mod:`mcsim.engine.pads.curves` and :mod:`mcsim.engine.pads.bounds` sample
(:func:`interval_points`).
"""

from __future__ import annotations

import functools
from functools import reduce
from operator import add
from typing import NamedTuple

import numpy as np

from mcsim.engine.kernels import block_sums, prepared, sum_columns
from mcsim.engine.montecarlo import plan_patch, sample_block, sums
from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.errors import ParameterError
from mcsim.physics.laws import Edges, LawSet, get_law_set
from mcsim.physics.surfaceenvironment import (
    active_terms,
    contact_law,
    open_gap_pressures,
    open_gap_works,
    with_environment,
)

#: Interior points at which each smooth interval of a pad's curve is evaluated.
SUB = 3
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
    return _loader(spec)(z, np.atleast_1d(np.asarray(d, dtype=float)), d_turn)


@functools.lru_cache(maxsize=16)
def _loader(spec: MonteCarloSpec):
    """:func:`pad_load` of ``spec`` as a function of (z, d, d_turn), its kernels looked up
    once: a pad's search sums a few rows dozens of times, and the lookup cost as much as
    the sums. Dry, the same kernel on the same arrays as :func:`contact_load`: the same
    bits."""
    if spec.environment is not None:
        return split_laws(spec).net
    if spec.surface.radius_by_height is not None:  # each band of heights with its radius
        return lambda z, d, d_turn: contact_load(spec, z, d, d_turn)
    kernel = prepared(spec.law_set, spec.arguments, spec.edges)
    column = sum_columns(spec.law_set).index("load")

    def dry(z, d, d_turn):
        d = np.ascontiguousarray(d)
        turn = d if d_turn is None else np.full_like(d, d_turn)
        return kernel(np.ascontiguousarray(z, dtype=float), d, turn)[:, column]

    return dry


def contact_load(spec: MonteCarloSpec, z: np.ndarray, d, d_turn=None) -> np.ndarray:
    """The contact law's load alone (N, the sum of its ``load``) of the pad of summits ``z``
    (m) at separations ``d`` (m); on retraction after ``d_turn`` (m), as :func:`pad_load`."""
    d = np.atleast_1d(np.asarray(d, dtype=float))
    if spec.surface.radius_by_height is not None:  # each band of heights with its radius
        turn = None if d_turn is None else np.full_like(d, d_turn)
        return sums(spec, z, d, turn)[:, sum_columns(spec.law_set).index("load")]
    if spec.environment is None:
        return _load(Part(spec.law_set, spec.arguments, spec.edges), z, d, d_turn)
    return _load(split_laws(spec).contact, z, d, d_turn)


class Part(NamedTuple):
    """A law set with its arguments and edges for one band of heights."""

    law: LawSet
    args: tuple
    edges: Edges


def _load(contact: Part, z: np.ndarray, d: np.ndarray, d_turn) -> np.ndarray:
    """The sum of ``contact``'s output ``load`` (N) over summits ``z`` at separations ``d``."""
    turn = None if d_turn is None else np.full_like(d, d_turn)
    sums = block_sums(z, d, contact.law, contact.args, d_turn=turn, edges=contact.edges)
    return sums[:, sum_columns(contact.law).index("load")]


class Band(NamedTuple):
    """One band of heights of a humid pad (:class:`Split`): its contact law set and its caps
    (:func:`contact_parts`, :func:`caps_parts`) and their kernels, looked up once
    (:func:`mcsim.engine.kernels.prepared`)."""

    contact: Part
    caps: Part
    contact_sums: object
    caps_sums: object


class Split:
    """A humid pad's net load as two sums over its summits, each evaluated only where it
    acts, in each band of heights with its own radius (one band with one summit radius):
    the contact law set's (``contact``, with its arguments and edges) over those that can
    touch, and the environment's caps' (``caps``: a law set of the outputs ``vdw`` and
    ``capillary``) over every summit within their reach; less the open gaps' attraction
    times the pad's area. Their kernels are looked up once
    (:func:`mcsim.engine.kernels.prepared`): a pad's search sums them hundreds of times on a
    few rows. ``contact`` and ``caps`` are the first band's."""

    def __init__(self, spec: MonteCarloSpec):
        self.bands = tuple(Band(c, k, prepared(*c), prepared(*k))
                           for c, k in zip(contact_parts(spec), caps_parts(spec)))  # fmt: skip
        self.contact, self.caps = self.bands[0].contact, self.bands[0].caps
        self.load = sum_columns(self.contact.law).index("load")
        self.attraction = [sum_columns(self.caps.law).index(t) for t in self.caps.law.names]
        self.area, self.sigma, self.gaps = spec.area, spec.surface.sigma, open_gaps(spec)
        self.radius_by_height = spec.surface.radius_by_height

    def split(self, z: np.ndarray) -> tuple[np.ndarray, ...]:
        """The summits ``z`` (m, contiguous) of each band, contiguous, in their order (with one
        band ``z`` itself)."""
        if len(self.bands) == 1:
            return (z,)
        band = self.radius_by_height.band_of(z / self.sigma)
        return tuple(np.ascontiguousarray(z[band == k]) for k in range(len(self.bands)))

    def contact_load(self, z: np.ndarray, d: np.ndarray, d_turn=None, band: int = 0):
        """The contact law's load (N) over summits ``z`` (m, contiguous) of band ``band`` at
        ``d`` (m)."""
        turn = d if d_turn is None else np.full_like(d, d_turn)
        return self.bands[band].contact_sums(z, d, turn)[:, self.load]

    def caps_load(self, z: np.ndarray, d: np.ndarray, band: int = 0) -> np.ndarray:
        """The caps' attraction (N, > 0) of summits ``z`` (m, contiguous) of band ``band`` at
        ``d`` (m)."""
        return self.bands[band].caps_sums(z, d, d)[:, self.attraction].sum(axis=1)

    def net(self, z: np.ndarray, d: np.ndarray, d_turn=None) -> np.ndarray:
        """The net load (N) of the pad of summits ``z`` (m) at ``d`` (m), as :func:`pad_load`:
        each band's contact load, less each band's caps, less the open gaps."""
        z, d = np.ascontiguousarray(z, dtype=float), np.ascontiguousarray(d, dtype=float)
        zs = self.split(z)
        # summed from the first band on (one band: its sum itself, not 0 + it)
        contact = reduce(add, (self.contact_load(zk, d, d_turn, k) for k, zk in enumerate(zs)))
        caps = reduce(add, (self.caps_load(zk, d, k) for k, zk in enumerate(zs)))
        return contact - caps - self.area * self.gaps(d / self.sigma)


@functools.lru_cache(maxsize=16)
def split_laws(spec: MonteCarloSpec) -> Split:
    """The :class:`Split` of a humid pad of ``spec``, built once."""
    return Split(spec)


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
#: Points of that table evaluated at once: the caps' expectation in the open gaps' pressure
#: integrates over nodes × panels per point, so the table is made in blocks (peak memory).
_GAP_BLOCK = 256


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
    table = open_gap_table(spec)
    return functools.partial(_gap_pressure, table)


def _gap_pressure(table: GapTable, h) -> np.ndarray:
    """:func:`open_gaps` of ``table`` at ``h`` (Pa)."""
    h = np.asarray(h, dtype=float)
    value = _piecewise(table.grid, table.c, h)
    inside = (h >= table.lo) & (h <= table.hi)
    return value if inside.all() else np.where(inside, value, table.exact(h))


@functools.lru_cache(maxsize=16)
def open_gap_work(spec: MonteCarloSpec):
    """The open gaps' work of separation (J/m²) from h_t = d_t/σ outward, as a function of h_t:
    the integral of the pressure a pad's curve subtracts (:func:`open_gaps`), σ times the
    spline's antiderivative from h_t to the table's top (in closed form) plus
    :func:`mcsim.physics.surfaceenvironment.open_gap_works` from there outward (outside the
    table, that function itself). Within 4e-9 of its largest value (the spline's bound
    integrated; measured 1e-13: tests/studies/test_pads_environment.py)."""
    return functools.partial(_gap_work, open_gap_table(spec), spec.surface.sigma)


def _gap_work(table: GapTable, sigma: float, h_t) -> np.ndarray:
    """:func:`open_gap_work` of ``table`` at ``h_t`` (J/m²)."""
    h_t = np.asarray(h_t, dtype=float)
    value = sigma * (table.w_top - _piecewise(table.grid, table.w, h_t)) + table.tail
    inside = (h_t >= table.lo) & (h_t <= table.hi)
    return value if inside.all() else np.where(inside, value, table.exact_work(h_t))


def _piecewise(grid: np.ndarray, c: np.ndarray, h: np.ndarray) -> np.ndarray:
    """The piecewise polynomial of knots ``grid`` and coefficients ``c`` (one row per piece,
    highest power first) at ``h`` (:func:`mcsim.engine.pads.gaps.piecewise`, compiled: a pad's
    search calls it hundreds of times on a few points, where a
    :class:`scipy.interpolate.PPoly` call costs ten times more)."""
    from mcsim.engine.pads import gaps as padgaps

    return padgaps.piecewise(grid, c, np.ascontiguousarray(h).ravel()).reshape(np.shape(h))


class GapTable(NamedTuple):
    """:func:`open_gap_table`: the spline's knots (h), its cubics' coefficients (Pa) and its
    antiderivative's from the first knot (Pa, per unit h: :func:`_piecewise`) and that at the
    last knot; its range [lo, hi] in h; the work from hi outward (J/m²); the functions
    themselves (pressure and work); the spline's steepest |slope| (Pa per unit h)."""

    grid: np.ndarray
    c: np.ndarray
    w: np.ndarray
    w_top: float
    lo: float
    hi: float
    tail: float
    exact: object
    exact_work: object
    slope: float


@functools.lru_cache(maxsize=16)
def open_gap_table(spec: MonteCarloSpec) -> GapTable:
    """The spline of :func:`open_gaps` and its antiderivative, its range [lo, hi] in h, the
    functions themselves, and the spline's largest |dp/dh| (Pa) on the range: its derivative
    is a quadratic on each piece, so the largest magnitude lies at a knot or where the
    (linear) second derivative is 0.

    It depends on the surface, the environment and its range only (not the law set, the pads
    or the seed): specs that share these share one table (:func:`_gap_table`), made once."""
    surface = spec.surface
    reach = -spec.edges.reach / surface.sigma
    heights = surface.heights  # the highest summit: a measured histogram's top, else 12σ
    top = float(heights.edges[-1]) if hasattr(heights, "edges") else 12.0
    lo, hi = float(spec.h.min()) - 1.0, top + reach + 1.0
    return _gap_table(surface, spec.environment, lo, hi)


@functools.lru_cache(maxsize=16)
def _gap_table(surface, env, lo: float, hi: float) -> GapTable:
    """:func:`open_gap_table` of ``surface`` in ``env`` on [lo, hi] (h)."""
    from scipy.interpolate import CubicSpline

    def exact(h):  # in blocks: the caps' expectation holds nodes × panels per point
        h = np.asarray(h, dtype=float)
        flat = h.ravel()
        out = np.empty(flat.shape)
        for i in range(0, flat.size, _GAP_BLOCK):
            p = open_gap_pressures(flat[i : i + _GAP_BLOCK], surface, env)
            out[i : i + _GAP_BLOCK] = p["vdw"] + p["capillary"]
        return out.reshape(h.shape)

    def exact_work(h_t):
        w = open_gap_works(h_t, surface, env)
        return w["vdw"] + w["capillary"]

    grid = np.linspace(lo, hi, OPEN_GAP_POINTS)
    spline = CubicSpline(grid, exact(grid))
    slope = spline.derivative()
    c = spline.c  # piece k: c[0] t^3 + c[1] t^2 + c[2] t + c[3], t = h - grid[k]
    with np.errstate(divide="ignore", invalid="ignore"):
        vertex = np.clip(-c[1] / (3 * c[0]), 0.0, np.diff(grid))  # p'' = 0 inside the piece
    vertex = np.where(np.isfinite(vertex), vertex, 0.0)
    steepest = max(np.max(np.abs(slope(grid))), np.max(np.abs(slope(grid[:-1] + vertex))))
    anti = spline.antiderivative()
    return GapTable(grid, np.ascontiguousarray(c.T), np.ascontiguousarray(anti.c.T),
                     float(anti(hi)), lo, hi, float(exact_work(np.float64(hi))), exact,
                     exact_work, float(steepest))  # fmt: skip


def contact_edges(spec: MonteCarloSpec) -> Edges:
    """The edges of the contact law alone: where a pad's load can jump or turn sharply.
    The environment's caps add kinks only (their forces are continuous): the search for a
    pad's pull-off and turn samples their intervals inside and does not cut at them."""
    if spec.environment is None:
        return spec.edges
    return Edges.widest([band.contact.edges for band in split_laws(spec).bands])


def smooth_intervals(spec: MonteCarloSpec, z: np.ndarray, low: float, high: float,
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


def interval_points(cuts: np.ndarray, sigma: float) -> np.ndarray:
    """Per interval of ``cuts``: its two one-sided ends and :data:`SUB` interior points."""
    a, b = cuts[:-1, None], cuts[1:, None]
    inside = np.minimum(EDGE * sigma, (b - a) / 4)
    frac = (np.arange(1, SUB + 1) / (SUB + 1))[None, :]
    return np.hstack([a + inside, a + (b - a) * frac, b - inside])  # (intervals, SUB + 2)


def summit_bands(spec: MonteCarloSpec, z: np.ndarray) -> np.ndarray:
    """The band of heights of each summit (all 0 with one radius)."""
    if spec.surface.radius_by_height is None:
        return np.zeros(z.shape, dtype=np.intp)
    return spec.surface.radius_by_height.band_of(z / spec.surface.sigma)


@functools.lru_cache(maxsize=16)
def contact_parts(spec: MonteCarloSpec) -> tuple[Part, ...]:
    """The contact law alone (its adhesion less the environment's van der Waals share,
    :func:`~mcsim.physics.surfaceenvironment.contact_law`), with its arguments and edges, for
    each band of heights."""
    return _per_band(spec, contact_law(get_law_set(spec.law), spec.environment))


@functools.lru_cache(maxsize=16)
def caps_parts(spec: MonteCarloSpec) -> tuple[Part, ...]:
    """The environment's caps alone (a law set of the outputs ``vdw`` and ``capillary``) for
    each band of heights."""
    caps = with_environment(LawSet("caps", "the environment's caps", ()), spec.environment)
    return _per_band(spec, caps)


def _per_band(spec: MonteCarloSpec, law: LawSet) -> tuple[Part, ...]:
    """``law`` with its arguments and edges for each of the surface's components."""
    m = spec.material
    return tuple(Part(law, law.arguments(part, m), law.edges_for(part, m))
                 for part in spec.surface.components())  # fmt: skip

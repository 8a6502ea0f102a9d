"""Summit-height distributions in units of σ (zero mean, unit standard deviation).

A distribution supplies what both halves of mcsim need:

* the analytic GW integrals: :meth:`HeightDistribution.gw_integrals` evaluates
  ∫_h^∞ g(s − h) p(s) ds for per-summit laws g (Eqs. 1, 3, 5, 7 with a general p);
* the Monte Carlo sampler: :meth:`HeightDistribution.sample_above` draws heights from
  the distribution truncated to s > s_min (the summits that can touch at all).

Heights are measured from the mean of the summit heights, as in the paper, so a
separation h = d/σ means the same in the sample and in the integrals.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol, runtime_checkable

import numpy as np
from scipy import special

from mcsim.model.errors import ParameterError

LawIntegrand = Callable[[np.ndarray], np.ndarray]


@runtime_checkable
class HeightDistribution(Protocol):
    """Interface of a standardized summit-height distribution (variable s = z/σ)."""

    name: str

    def pdf(self, s: np.ndarray) -> np.ndarray:
        """Probability density of s."""

    def sf(self, s: np.ndarray) -> np.ndarray:
        """Survival function P(S > s): the contact fraction N_c/N at h = s (Eq. 1)."""

    def sample_above(self, n: int, s_min: float, rng: np.random.Generator) -> np.ndarray:
        """``n`` draws from the distribution truncated to s > s_min (s_min may be -inf)."""

    def gw_integrals(
        self,
        g: LawIntegrand,
        h: np.ndarray,
        breaks: np.ndarray | None = None,
        upper: np.ndarray | None = None,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Partial expectations E[g(S − h); S > h] = scale · integral, for each h.

        ``g`` maps an array of Δ = s − h ≥ 0 to an array with one leading axis per
        quantity, shape ``(q, *Δ.shape)``. Returns ``scale`` of shape ``(len(h),)`` and
        ``integral`` of shape ``(q, len(h))``. The split keeps ratios such as μ
        finite where the expectations themselves underflow (far tails).

        With ``breaks`` (shape ``(len(h), m)``, in units of Δ): E[g(S − h); S − h >
        breaks[:, 0]], integrated piecewise between the (sorted) breakpoints in
        ``breaks[:, 1:]`` that lie above ``breaks[:, 0]``, each panel [Δ_k, Δ_k+1] in
        u = √(Δ − Δ_k); ``g`` is then called as ``g(delta, rows)`` with ``rows`` the
        index into ``h`` of each row of ``delta``.

        ``upper`` (shape ``(len(h),)``, with ``breaks``) promises that ``g`` is zero
        wherever Δ > upper: an implementation may skip the panels that start above it,
        which add exactly nothing (a band's, :meth:`Band.gw_integrals`).
        """


# Composite Gauss–Legendre rule in u = √Δ (removes the δ^{3/2} branch point at Δ = 0).
_PANELS = 8
_NODES_PER_PANEL = 24
_TAIL = 41.0  # integrate until the Gaussian weight drops below e^-41 ≈ 1.6e-18 of its peak


def _panel_rule() -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(_NODES_PER_PANEL)
    edges = np.linspace(0.0, 1.0, _PANELS + 1)
    half = np.diff(edges) / 2
    mid = (edges[:-1] + edges[1:]) / 2
    nodes = (mid[:, None] + half[:, None] * x).ravel()
    weights = (half[:, None] * w).ravel()
    return nodes, weights


_U_NODES, _U_WEIGHTS = _panel_rule()


class Gaussian:
    """Standard normal summit heights, as in Greenwood & Williamson (1966) and the paper."""

    name = "gaussian"

    def __repr__(self) -> str:
        return "Gaussian()"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Gaussian)

    def __hash__(self) -> int:
        return hash(self.name)

    def pdf(self, s: np.ndarray) -> np.ndarray:
        return np.exp(-0.5 * np.square(s)) / np.sqrt(2 * np.pi)

    def sf(self, s: np.ndarray) -> np.ndarray:
        """F_0(h) = ½ erfc(h/√2) (Eq. 1 with the Gaussian φ)."""
        return 0.5 * special.erfc(np.asarray(s, dtype=float) / np.sqrt(2))

    def sample_above(self, n: int, s_min: float, rng: np.random.Generator) -> np.ndarray:
        if s_min == -np.inf:
            return rng.standard_normal(n)
        if s_min > 0:
            p = float(self.sf(s_min))
            # Inverse transform on the upper tail: sf(s) = u·p with u ~ U(0, 1].
            return -special.ndtri((1.0 - rng.random(n)) * p)
        # Rejection from the full normal, compiled: acceptance p >= 1/2.
        from mcsim.model._rejection import truncated_standard_normal

        return truncated_standard_normal(rng, float(s_min), np.empty(n))

    def gw_integrals(
        self,
        g: LawIntegrand,
        h: np.ndarray,
        breaks: np.ndarray | None = None,
        upper: np.ndarray | None = None,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Gaussian partial expectations by Gauss–Legendre quadrature in u = √Δ.

        E[g(S−h); S>h] = ∫_0^∞ g(Δ) φ(h+Δ) dΔ. For h > 0 the factor φ(h) is taken out
        (returned as ``scale``) and the weight is exp(−hΔ − Δ²/2); for h ≤ 0 the
        weight is φ(h+Δ) itself. Δ runs over the range where the weight exceeds
        e^-41 of its peak, on 8 panels of 24 nodes in u. Accurate to ~1e-13 relative
        for smooth laws growing at most polynomially (tested against mpmath).

        With ``breaks`` the same rule runs on each panel between breakpoints, in
        u = √(Δ − Δ_k) from the panel's lower edge Δ_k (removing a square-root
        branch point there, such as JKR's at break-off), over the s range where
        the weight exceeds e^-41 of its peak above the lower limit
        (:func:`_piecewise_gaussian`). ``upper`` is not used: every panel is evaluated in
        one array operation.
        """
        if breaks is not None:
            return _piecewise_gaussian(g, np.atleast_1d(np.asarray(h, dtype=float)), breaks)
        h = np.atleast_1d(np.asarray(h, dtype=float))
        hp = np.maximum(h, 0.0)
        d_lo = np.maximum(-h - np.sqrt(2 * _TAIL), 0.0)
        d_hi = -h + np.sqrt(hp**2 + 2 * _TAIL)
        u_lo, u_hi = np.sqrt(d_lo), np.sqrt(d_hi)
        u = u_lo[:, None] + (u_hi - u_lo)[:, None] * _U_NODES
        delta = u * u
        # log weight relative to φ(max(h, 0)) · √(2π)
        log_w = -0.5 * (h[:, None] + delta) ** 2 + 0.5 * hp[:, None] ** 2
        jac = 2 * u * (u_hi - u_lo)[:, None] * _U_WEIGHTS
        weight = np.exp(log_w) * jac / np.sqrt(2 * np.pi)
        values = np.asarray(g(delta))
        integral = np.sum(values * weight, axis=-1)
        scale = np.exp(-0.5 * hp**2)
        return scale, integral


def panel_edges(breaks: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Panel edges per row: ``lo``, the breakpoints strictly inside (lo, hi), ``hi``.

    Breakpoints outside the range are clipped onto its ends (empty panels), so every
    row has ``breaks.shape[1] + 1`` panels; shape ``(rows, m + 2)``.
    """
    inner = np.clip(breaks[:, 1:], lo[:, None], hi[:, None])
    return np.sort(np.concatenate([lo[:, None], inner, hi[:, None]], axis=1), axis=1)


#: Nodes (rows × panels × quadrature nodes) of one block of :func:`_piecewise_gaussian` (at
#: least one row): its rows are independent, so the numbers are the same bits whatever the
#: block. 64 kB per temporary of one output: at or below glibc's 128 kB threshold for
#: allocating with mmap (which it raises once such a block is freed), they come from the heap
#: and stay in the cache, where larger ones were mapped, faulted in page by page and unmapped
#: again for every array (validation/fuller_tabor.py --quick: 1.1 million
#: page faults and 8 CPU-s in one block, 26 000 and 4.7 CPU-s in these; a humid spec's open-gap
#: table, 4097 rows of 22 panels, about half the time).
_BLOCK_NODES = 8192


def _piecewise_gaussian(g: LawIntegrand, h: np.ndarray, breaks) -> tuple[np.ndarray, np.ndarray]:
    """E[g(S − h); S − h > breaks[:, 0]] for a standard normal S, panel by panel.

    The peak of the weight above the lower limit s_lo = h + Δ_lo lies at
    p = max(s_lo, 0); φ(p)√(2π) is returned as ``scale`` and the s range runs from
    max(s_lo, −√82) to √(p² + 82) (the weight above e^-41 of its peak, as for the
    seed's rule). Each panel gets the composite 8 × 24-point rule in u = √(Δ − Δ_k).
    Evaluated in blocks of rows (:data:`_BLOCK_NODES`), ``g`` called once per block with
    the block's rows.
    """
    breaks = np.asarray(breaks, dtype=float).reshape(h.size, -1)
    rows = max(1, _BLOCK_NODES // ((breaks.shape[1] + 1) * _U_NODES.size))
    if h.size <= rows:
        return _piecewise_block(g, h, breaks, 0)
    scale, out = np.empty(h.size), None
    for i in range(0, h.size, rows):
        block = slice(i, i + rows)
        scale[block], values = _piecewise_block(g, h[block], breaks[block], i)
        if out is None:
            out = np.empty((*values.shape[:-1], h.size))
        out[..., block] = values
    return scale, out


def _piecewise_block(g: LawIntegrand, h: np.ndarray, breaks: np.ndarray, first: int):
    """:func:`_piecewise_gaussian` of the rows ``first``, ``first + 1``, … (``h``, ``breaks``)."""
    s_lo = h + breaks[:, 0]
    peak = np.maximum(s_lo, 0.0)
    lo = np.maximum(s_lo, -np.sqrt(2 * _TAIL)) - h
    hi = np.sqrt(peak**2 + 2 * _TAIL) - h
    edges = panel_edges(breaks, lo, hi)
    a = edges[:, :-1, None]
    span = np.sqrt(edges[:, 1:] - edges[:, :-1])[..., None]
    u = span * _U_NODES
    delta = (a + u * u).reshape(h.size, -1)
    log_w = -0.5 * (h[:, None] + delta) ** 2 + 0.5 * peak[:, None] ** 2
    jac = (2 * u * span * _U_WEIGHTS).reshape(h.size, -1)
    weight = np.exp(log_w) * jac / np.sqrt(2 * np.pi)
    values = np.asarray(g(delta, np.arange(first, first + h.size)))
    return np.exp(-0.5 * peak**2), np.sum(values * weight, axis=-1)


class Band:
    """The part of a height distribution with s in (lo, hi]: a sub-distribution of mass
    P(lo < S ≤ hi), so that GW sums over bands add up to the sum over the whole.

    A surface whose summit radius depends on height
    (:class:`~mcsim.model.params.RadiusByHeight`) is a mixture of plain GW populations, one
    per band of heights with its own radius (:meth:`~mcsim.model.params.Surface.components`);
    each is integrated over its band only. The Monte Carlo draws the whole population and
    sorts each summit into its band, so a band itself is never sampled.

    Parameters
    ----------
    parent : HeightDistribution
        The whole distribution (s = z/σ).
    lo, hi : float
        The band, lo < hi; ±inf for the outermost bands.
    """

    name = "band"

    def __init__(self, parent: HeightDistribution, lo: float, hi: float):
        if not lo < hi:
            raise ParameterError(f"band ({lo}, {hi}] is empty (need lo < hi)")
        self.parent, self.lo, self.hi = parent, float(lo), float(hi)

    def __repr__(self) -> str:
        return f"Band({self.parent!r}, {self.lo:g}, {self.hi:g})"

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Band):
            return NotImplemented
        return (self.parent, self.lo, self.hi) == (other.parent, other.lo, other.hi)

    def __hash__(self) -> int:
        return hash((self.name, self.parent, self.lo, self.hi))

    def pdf(self, s: np.ndarray) -> np.ndarray:
        s = np.asarray(s, dtype=float)
        return np.where((s > self.lo) & (s <= self.hi), self.parent.pdf(s), 0.0)

    def sf(self, s: np.ndarray) -> np.ndarray:
        """P(S > s and lo < S ≤ hi)."""
        s = np.clip(np.asarray(s, dtype=float), self.lo, self.hi)
        top = 0.0 if self.hi == np.inf else self.parent.sf(self.hi)
        return np.maximum(self.parent.sf(s) - top, 0.0)

    def sample_above(self, n: int, s_min: float, rng: np.random.Generator) -> np.ndarray:
        raise ParameterError("a band of heights is not sampled: the Monte Carlo draws the whole "
                             "distribution and sorts the summits into bands (give the surface "
                             "its radius_by_height instead)")  # fmt: skip

    def gw_integrals(
        self,
        g: LawIntegrand,
        h: np.ndarray,
        breaks: np.ndarray | None = None,
        upper: np.ndarray | None = None,
    ) -> tuple[np.ndarray, np.ndarray]:
        """The parent's integrals over the band: the lower limit raised to Δ = lo − h, a
        breakpoint at Δ = hi − h, and ``g`` zero above it (the panels split there, so the
        cut is exact; the parent is told, as ``upper``, and may skip the panels above)."""
        h = np.atleast_1d(np.asarray(h, dtype=float))
        if breaks is None:
            base = np.zeros((h.size, 1))

            def inner(delta, rows):
                return g(delta)
        else:
            base, inner = np.asarray(breaks, dtype=float).reshape(h.size, -1), g
        columns = [np.maximum(base[:, 0], self.lo - h), *base[:, 1:].T]
        cut = self.hi - h
        if self.hi < np.inf:
            columns.append(cut)

        def banded(delta, rows):
            values = np.asarray(inner(delta, rows))
            return np.where(delta <= cut[rows][:, None], values, 0.0)

        upper = cut if upper is None else np.minimum(cut, upper)
        return self.parent.gw_integrals(banded, h, np.stack(columns, axis=1), upper)


GAUSSIAN = Gaussian()

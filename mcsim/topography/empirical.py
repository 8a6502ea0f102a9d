"""Measured summit-height distributions: a piecewise-constant density on histogram bins.

:class:`Empirical` implements :class:`~mcsim.model.distributions.HeightDistribution` for a
histogram, e.g. the summit heights or the height distribution of an AFM map. The
density is taken as uniform inside each bin, and every quantity is exact for that
density:

* mean and variance are the exact moments of the piecewise-uniform density,
  μ = Σ p_k c_k and σ² = Σ p_k [(c_k − μ)² + w_k²/12] (bin probability p_k, centre
  c_k, width w_k; the w²/12 term is Sheppard's correction, exact here), not the
  moments of the bin centres;
* the distribution is *standardized* with them, s = (z − μ)/σ, as the
  :class:`~mcsim.model.params.Surface` expects; the physical σ (m) and μ (m) are kept as
  attributes, so ``Surface(sigma=emp.sigma, ...)`` rebuilds the dimensional surface;
* the survival function is piecewise linear, sampling is exact (a bin by its
  probability, then uniform within it) and the GW integrals are integrated bin by
  bin with Gauss–Legendre quadrature in u = √(s − h), which removes the δ^{3/2}
  branch point of the Hertz law at the contact edge (as in
  :class:`~mcsim.model.distributions.Gaussian`).

Whether the histogram describes *summit* heights (what GW needs) or all pixel heights
is the caller's choice: mcsim uses it as the summit-height distribution.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mcsim.model.distributions import LawIntegrand, panel_edges
from mcsim.model.errors import MCSimError, ParameterError

#: Schema of :meth:`Empirical.to_dict`; bump when the stored keys change.
SCHEMA = "mcsim.empirical/1"

# Composite Gauss–Legendre rule in u = √Δ on each (clipped) bin: 4 panels of 12 nodes.
# The seed laws are polynomials of degree ≤ 4 in u (Hertz) or analytic in u with their
# nearest complex singularity at |u| ~ (3πγR/(K R^½))^{1/3} (Johnson, Savkoor–Briggs);
# the rule reaches ~1e-13 relative against brute-force quadrature (tests/test_empirical.py).
_PANELS = 4
_NODES_PER_PANEL = 12
# Largest number of quadrature points evaluated at once (memory bound, ~16 MB per law).
_CHUNK = 2_000_000


def _unit_rule() -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss–Legendre nodes and weights on [0, 1]."""
    x, w = np.polynomial.legendre.leggauss(_NODES_PER_PANEL)
    edges = np.linspace(0.0, 1.0, _PANELS + 1)
    half = np.diff(edges) / 2
    mid = (edges[:-1] + edges[1:]) / 2
    return (mid[:, None] + half[:, None] * x).ravel(), (half[:, None] * w).ravel()


_NODES, _WEIGHTS = _unit_rule()


def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.setflags(write=False)
    return a


def _validate_histogram(edges, weights) -> tuple[np.ndarray, np.ndarray]:
    """Edges and weights as float arrays, checked; raises :class:`ParameterError`."""
    try:
        edges = np.asarray(edges, dtype=float)
        weights = np.asarray(weights, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError("histogram edges and weights must be numbers") from None
    except OverflowError:  # an integer beyond the largest float
        raise ParameterError("histogram edges and weights must be finite") from None
    if edges.ndim != 1 or weights.ndim != 1:
        raise ParameterError("histogram edges and weights must be one-dimensional")
    if weights.size < 2:
        raise ParameterError(f"a histogram needs at least two bins, got {weights.size}")
    if edges.size != weights.size + 1:
        raise ParameterError(
            f"a histogram with {weights.size} bins needs {weights.size + 1} edges, got {edges.size}"
        )
    if not (np.all(np.isfinite(edges)) and np.all(np.isfinite(weights))):
        raise ParameterError("histogram edges and weights must be finite")
    if np.any(np.diff(edges) <= 0):
        raise ParameterError("histogram edges must be strictly increasing")
    if np.any(weights < 0):
        raise ParameterError("histogram weights must be non-negative")
    if not np.any(weights > 0):
        raise ParameterError("histogram weights are all zero")
    return edges, weights


class Empirical:
    """Standardized piecewise-constant height density from a histogram.

    Build one with :meth:`from_histogram` or :meth:`from_samples`; the constructor
    takes the standardized form (as stored by :meth:`to_dict`).

    Parameters
    ----------
    edges : array_like
        Standardized bin edges s_k = (z_k − mean)/sigma, strictly increasing.
    densities : array_like
        Probability density of s in each bin (non-negative; Σ densities·widths = 1,
        zero mean and unit variance, to 1e-9).
    sigma : float
        Standard deviation of the measured heights, m.
    mean : float
        Mean of the measured heights in the instrument's reference, m.
    source : str
        Where the histogram came from (file, channel, binning); a label, not part of
        equality.

    Attributes
    ----------
    name : str
        ``"empirical"``.
    edges, densities : ndarray
        As above, read-only.
    sigma, mean : float
        As above, m.
    source : str
        As above.
    """

    name = "empirical"
    __slots__ = ("_cdf_edges", "_sf_edges", "densities", "edges", "mean", "sigma", "source")

    def __init__(self, edges, densities, sigma: float, mean: float = 0.0, source: str = ""):
        edges, densities = _validate_histogram(edges, densities)
        if not (np.isfinite(sigma) and sigma > 0):
            raise ParameterError(f"sigma = {sigma!r} m is out of range (allowed: > 0 m)")
        if not np.isfinite(mean):
            raise ParameterError(f"mean = {mean!r} m must be finite")
        p = densities * np.diff(edges)
        centre = (edges[:-1] + edges[1:]) / 2
        width = np.diff(edges)
        m1 = np.sum(p * centre)
        m2 = np.sum(p * (centre**2 + width**2 / 12))
        if abs(p.sum() - 1) > 1e-9 or abs(m1) > 1e-9 or abs(m2 - 1) > 1e-9:
            raise ParameterError(
                "densities are not a standardized distribution (need total probability 1, "
                f"mean 0, variance 1; got {p.sum():.12g}, {m1:.3g}, {m2 - m1**2:.12g}): "
                "use Empirical.from_histogram"
            )
        set_ = object.__setattr__
        set_(self, "edges", _frozen(edges))
        set_(self, "densities", _frozen(densities))
        set_(self, "sigma", float(sigma))
        set_(self, "mean", float(mean))
        set_(self, "source", str(source))
        # P(S ≤ s_k) and P(S > s_k) at the edges, each summed from its own end so the
        # far tails keep their relative accuracy.
        set_(self, "_cdf_edges", _frozen(np.concatenate([[0.0], np.cumsum(p)])))
        set_(self, "_sf_edges", _frozen(np.concatenate([np.cumsum(p[::-1])[::-1], [0.0]])))

    # -- construction --------------------------------------------------------------

    @classmethod
    def from_histogram(
        cls, edges, weights, *, density: bool = False, source: str = ""
    ) -> Empirical:
        """Standardized distribution of a histogram of heights.

        Parameters
        ----------
        edges : array_like
            Bin edges z_0 < z_1 < ... < z_n, m.
        weights : array_like
            ``n`` non-negative counts per bin, or densities (per m) with
            ``density=True``; any normalisation.
        density : bool
            Whether ``weights`` are densities (probability per unit height) rather
            than counts (probability per bin).
        source : str
            Label stored with the distribution.

        Returns
        -------
        Empirical
            Standardized with the exact mean and standard deviation of the
            piecewise-uniform density (module docstring); ``sigma`` and ``mean`` in m.

        Raises
        ------
        ParameterError
            Fewer than two bins, edges not increasing, negative, non-finite or all-zero
            weights, or a single occupied bin (zero variance).
        """
        edges, weights = _validate_histogram(edges, weights)
        width = np.diff(edges)
        with np.errstate(over="ignore", under="ignore"):
            p = weights * width if density else weights
        if not (np.all(np.isfinite(p)) and p.max() > 0):
            raise ParameterError("histogram densities × bin widths overflow or underflow")
        p = p / p.max()  # first: the sum of huge weights would overflow
        p = p / p.sum()
        # Leading and trailing empty bins carry no probability: drop them.
        occupied = np.flatnonzero(p > 0)
        first, last = occupied[0], occupied[-1]
        if first == last:
            raise ParameterError("histogram has a single occupied bin: its spread is unknown")
        p = p[first : last + 1]
        edges = edges[first : last + 2]
        width = np.diff(edges)
        centre = (edges[:-1] + edges[1:]) / 2
        with np.errstate(over="ignore", invalid="ignore"):
            mean = float(np.sum(p * centre))
            sigma = float(np.sqrt(np.sum(p * ((centre - mean) ** 2 + width**2 / 12))))
        if not math.isfinite(sigma):
            raise ParameterError("histogram edges span too wide a range: their spread "
                                 "overflows a float")  # fmt: skip
        s_edges = (edges - mean) / sigma
        return cls(s_edges, p / np.diff(s_edges), sigma=sigma, mean=mean, source=source)

    @classmethod
    def from_samples(cls, z, bins: int | str | np.ndarray = "fd", *, source: str = "") -> Empirical:
        """Distribution of raw height samples, binned with :func:`numpy.histogram`.

        Parameters
        ----------
        z : array_like
            Heights, m (any shape; flattened). Must be finite.
        bins : int, str or array_like
            Number of bins, a :func:`numpy.histogram_bin_edges` rule (default
            ``"fd"``, Freedman–Diaconis) or the edges in m.
        source : str
            Label stored with the distribution.

        Returns
        -------
        Empirical
        """
        z = np.asarray(z, dtype=float).ravel()
        if z.size < 2:
            raise ParameterError(f"need at least two height samples, got {z.size}")
        if not np.all(np.isfinite(z)):
            raise ParameterError("height samples must be finite (drop NaN pixels first)")
        counts, edges = np.histogram(z, bins=bins)
        return cls.from_histogram(edges, counts, source=source)

    # -- storage -------------------------------------------------------------------

    def to_dict(self) -> dict[str, Any]:
        """Plain-data form for run files: schema, standardized edges and densities, σ and mean in m."""
        return {
            "schema": SCHEMA,
            "edges": self.edges.tolist(),
            "densities": self.densities.tolist(),
            "sigma": self.sigma,
            "mean": self.mean,
            "source": self.source,
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Empirical:
        """Inverse of :meth:`to_dict` (exact round trip)."""
        schema = data.get("schema") if isinstance(data, dict) else None
        if schema != SCHEMA:
            raise MCSimError(
                f"not a stored empirical distribution (schema {schema!r}, expected {SCHEMA!r})"
            )
        missing = {"edges", "densities", "sigma", "mean"} - set(data)
        if missing:
            raise MCSimError(f"stored empirical distribution lacks {', '.join(sorted(missing))}")
        try:
            sigma, mean = float(data["sigma"]), float(data["mean"])
        except (TypeError, ValueError):
            raise ParameterError("stored empirical sigma and mean must be numbers") from None
        return cls(data["edges"], data["densities"], sigma, mean, str(data.get("source", "")))

    # -- value semantics -----------------------------------------------------------

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f"Empirical is immutable (cannot set {name!r})")

    def __copy__(self) -> Empirical:
        return self  # an immutable value: a copy is the same value

    def __deepcopy__(self, memo: dict) -> Empirical:
        return self

    def __reduce__(self):
        """Pickle (Dask workers) through the constructor: the attributes cannot be set."""
        return (type(self), (self.edges, self.densities, self.sigma, self.mean, self.source))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Empirical):
            return NotImplemented
        return (
            self.sigma == other.sigma
            and self.mean == other.mean
            and np.array_equal(self.edges, other.edges)
            and np.array_equal(self.densities, other.densities)
        )

    def __hash__(self) -> int:
        return hash((self.sigma, self.mean, self.edges.tobytes(), self.densities.tobytes()))

    def __repr__(self) -> str:
        return (
            f"Empirical({self.densities.size} bins on s in [{self.edges[0]:.3g}, "
            f"{self.edges[-1]:.3g}], sigma={self.sigma:.4g} m, source={self.source!r})"
        )

    # -- HeightDistribution --------------------------------------------------------

    def pdf(self, s) -> np.ndarray:
        """Density of s: the bin's density, right-continuous at the edges, 0 outside."""
        s = np.asarray(s, dtype=float)
        k = np.searchsorted(self.edges, s, side="right") - 1
        inside = (k >= 0) & (k < self.densities.size)
        return np.where(inside, self.densities[np.clip(k, 0, self.densities.size - 1)], 0.0)

    def sf(self, s) -> np.ndarray:
        """P(S > s): exact for the piecewise-uniform density (linear inside each bin)."""
        s = np.asarray(s, dtype=float)
        k = np.clip(np.searchsorted(self.edges, s, side="right") - 1, 0, self.densities.size - 1)
        inside = np.clip(self.edges[k + 1] - s, 0.0, np.diff(self.edges)[k])
        out = self._sf_edges[k + 1] + self.densities[k] * inside
        return np.where(s < self.edges[0], 1.0, out)

    def sample_above(self, n: int, s_min: float, rng: np.random.Generator) -> np.ndarray:
        """``n`` exact draws from the density truncated to s > s_min.

        A bin is chosen with probability proportional to its mass above s_min (the
        bin holding s_min clipped to (s_min, b]), then a point uniform within it.

        Raises
        ------
        MCSimError
            If ``n > 0`` and no probability lies above ``s_min``.
        """
        lo = np.maximum(self.edges[:-1], s_min)
        hi = self.edges[1:]
        mass = self.densities * np.clip(hi - lo, 0.0, None)
        total = mass.sum()
        if n == 0:
            return np.empty(0)
        if not total > 0:
            raise MCSimError(
                f"no summit heights above s = {s_min:g} (the histogram ends at s = {hi[-1]:g})"
            )
        cum = np.cumsum(mass) / total
        k = np.minimum(np.searchsorted(cum, rng.random(n), side="right"), mass.size - 1)
        # 1 − U lies in (0, 1]: draws in (lo, hi], strictly above s_min.
        return hi[k] - (hi[k] - lo[k]) * rng.random(n)

    def gw_integrals(
        self, g: LawIntegrand, h, breaks=None, upper: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """Partial expectations E[g(S − h); S > h] = Σ_k f_k ∫_{max(a_k, h)}^{b_k} g(s − h) ds.

        Each bin [a_k, b_k] with b_k > h is clipped to s > h and integrated in
        u = √(s − h) (ds = 2u du) with a composite Gauss–Legendre rule, so the
        δ^{3/2} branch point of the Hertz law at s = h is removed. ``scale`` is 1: the
        support is bounded and nothing underflows.

        With ``breaks`` (see :meth:`mcsim.model.distributions.HeightDistribution.gw_integrals`)
        the integral starts at Δ = breaks[:, 0] and every bin is further split at the
        breakpoints; each piece [Δ_k, Δ_k+1] is integrated in u = √(Δ − Δ_k) with the
        same rule, and ``g`` is called as ``g(delta, rows)``. With ``upper`` too (g zero
        above Δ = upper, a band's), the pieces that start above it are skipped: every node
        of one lies above, so it adds exactly 0.
        """
        h = np.atleast_1d(np.asarray(h, dtype=float))
        if breaks is not None:
            breaks = np.asarray(breaks, dtype=float).reshape(h.size, -1)
            top = np.full(h.size, np.inf) if upper is None else np.asarray(upper, dtype=float)
            return self._piecewise(g, h, breaks, top)
        a, b = self.edges[:-1], self.edges[1:]
        # Active (h, bin) pairs: the bin reaches above h and has probability.
        ih, ik = np.nonzero((b[None, :] > h[:, None]) & (self.densities[None, :] > 0))
        per_pair = []
        step = max(1, _CHUNK // _NODES.size)
        for start in range(0, ih.size, step):
            jh, jk = ih[start : start + step], ik[start : start + step]
            u_lo = np.sqrt(np.maximum(a[jk] - h[jh], 0.0))
            u_hi = np.sqrt(b[jk] - h[jh])
            span = (u_hi - u_lo)[:, None]
            u = u_lo[:, None] + span * _NODES
            weight = 2 * u * span * _WEIGHTS * self.densities[jk][:, None]
            values = np.asarray(g(u * u))
            per_pair.append(np.sum(values * weight, axis=-1))
        q = per_pair[0].shape[0] if per_pair else np.asarray(g(np.ones((1, 1)))).shape[0]
        integral = np.zeros((q, h.size))
        if per_pair:
            contributions = np.concatenate(per_pair, axis=-1)
            for i in range(q):
                integral[i] = np.bincount(ih, weights=contributions[i], minlength=h.size)
        return np.ones(h.size), integral

    def _piecewise(self, g: LawIntegrand, h: np.ndarray, breaks: np.ndarray, upper: np.ndarray):
        """:meth:`gw_integrals` with breakpoints: panels are bins ∩ break intervals, those
        that start above ``upper`` left out."""
        a, b = self.edges[:-1], self.edges[1:]
        lo = breaks[:, 0]
        hi = np.maximum(b[-1] - h, lo)
        cuts = panel_edges(breaks, lo, hi)  # (h, m + 2), in Δ
        # Active (h, bin, break interval) triples, each clipped to the bin and interval.
        above_lo = b[None, :] - h[:, None] > lo[:, None]
        below_upper = a[None, :] - h[:, None] <= upper[:, None]
        ih, ik = np.nonzero(above_lo & below_upper & (self.densities > 0))
        p_lo = np.maximum((a[ik] - h[ih])[:, None], cuts[ih, :-1])
        p_hi = np.minimum((b[ik] - h[ih])[:, None], cuts[ih, 1:])
        keep = (p_hi > p_lo) & (p_lo <= upper[ih][:, None])
        rows = np.broadcast_to(ih[:, None], keep.shape)[keep]
        density = np.broadcast_to(self.densities[ik][:, None], keep.shape)[keep]
        p_lo, p_hi = p_lo[keep], p_hi[keep]
        per_panel = []
        step = max(1, _CHUNK // _NODES.size)
        for start in range(0, rows.size, step):
            sl = slice(start, start + step)
            span = np.sqrt(p_hi[sl] - p_lo[sl])[:, None]
            u = span * _NODES
            weight = 2 * u * span * _WEIGHTS * density[sl][:, None]
            values = np.asarray(g(p_lo[sl][:, None] + u * u, rows[sl]))
            per_panel.append(np.sum(values * weight, axis=-1))
        q = np.asarray(g(np.zeros((1, 1)), np.zeros(1, dtype=np.int64))).shape[0]
        integral = np.zeros((q, h.size))
        if per_panel:
            contributions = np.concatenate(per_panel, axis=-1)
            for i in range(q):
                integral[i] = np.bincount(rows, weights=contributions[i], minlength=h.size)
        return np.ones(h.size), integral

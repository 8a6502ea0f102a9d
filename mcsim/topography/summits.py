"""Summit statistics (σ_s, R, η) of a measured height map, by two routes.

See docs/physics.md, section 'Summit statistics from a height map'.

The map ``z[i, j]`` has rows along y (pitch ``dy``) and columns along x (pitch
``dx``), heights in m (the :class:`~mcsim.topography.readers.HeightMap` convention). Steps:

1. **Levelling**: a least-squares polynomial of total degree ``order`` in x and y
   (default 1, a plane; 0 only removes the mean) is fitted to the finite pixels and
   subtracted, so heights are measured from the mean plane.
2. **NaN handling**: non-finite pixels are dropped from every average and counted;
   a pixel is a summit candidate only if it and its 8 neighbours are finite.
3. **Saturation**: if more than ``saturation_fraction`` of the pixels sit exactly at the
   map's minimum or maximum (detector or scanner range clipped), a
   :class:`SaturationWarning` is issued: clipped peaks bias every summit statistic.
4. **Direct route** (Greenwood & Williamson 1966): a summit is a pixel higher
   than its 8 neighbours. Border pixels are never summits, unless the map is periodic
   (``periodic=True``): then neighbours wrap across the edges and every pixel is a
   candidate. Plateaus (equal neighbours)
   are counted once: the pixel must be strictly higher than the 4 neighbours that come
   before it in raster order (up-left, up, up-right, left) and at least as high as the
   4 that come after (right, down-left, down, down-right), so of a connected flat top
   only its first pixel in raster order counts. Curvature κ = −(z_xx + z_yy)/2 by
   central differences; R = 1/⟨κ⟩ (not ⟨1/κ⟩); σ_s = population std of summit
   heights; η = count / area of the candidate pixels.
5. **Spectral route** (Nayak 1971; McCool 1986): m0 = ⟨z²⟩, m2 = ⟨z_x²⟩ (forward
   differences), m4 = ⟨z_xx²⟩ (central second differences), each the average of the
   x and y profiles (McCool's equivalent isotropic surface); α = m0 m4/m2²,
   η = m4/(6π√3 m2), R = 0.375 √(π/m4), σ_s = √(1 − 0.8968/α) √m0, mean summit
   height 4 √(m0/(πα)) above the mean plane.

Periodic maps
-------------
Synthetic maps often repeat, measured ones do not. :func:`periodic_edges` takes a map as
periodic when its opposite edges join: the rms height step across each pair of opposite
edges is less than :data:`EDGE_JOIN` times the rms step between neighbouring pixels along
that axis (for a periodic map the two are the same statistic; for a cut-out map the edge
step is of the order of the rms height). On a periodic map the spectral route's differences
wrap too; its natural levelling is the mean only (a fitted plane would remove the random
tilt of a map that has none and lower its rms).

Both routes depend strongly on the pixel size and the instrument bandwidth: always
report ``dx``, ``dy`` and ``order`` with the numbers (they are in the result).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from mcsim.model.counterface import summits_of
from mcsim.model.errors import ParameterError
from mcsim.model.params import RadiusByHeight


class SaturationWarning(UserWarning):
    """Many pixels sit at the map's extreme values: the scan was probably clipped."""


@dataclass(frozen=True)
class SummitStatistics:
    """Summit statistics of one route.

    Attributes
    ----------
    sigma_s : float
        Standard deviation of summit heights, m.
    R : float
        Summit radius of curvature, m (1/mean curvature).
    eta : float
        Areal density of summits, m⁻².
    mean_height : float
        Mean summit height above the mean plane, m.
    count : float
        Number of summits found (direct route) or expected on the map's area (spectral).
    """

    sigma_s: float
    R: float
    eta: float
    mean_height: float
    count: float


@dataclass(frozen=True)
class SpectralMoments:
    """Spectral moments of the levelled map (McCool 1986), averaged over x and y.

    Attributes
    ----------
    m0 : float
        ⟨z²⟩, m².
    m2 : float
        ⟨(∂z/∂x)²⟩, dimensionless.
    m4 : float
        ⟨(∂²z/∂x²)²⟩, m⁻².
    alpha : float
        Nayak's bandwidth parameter m0 m4 / m2² (dimensionless).
    """

    m0: float
    m2: float
    m4: float
    alpha: float


@dataclass(frozen=True)
class TopographyResult:
    """Summit statistics of a height map by both routes, with the sampling they depend on.

    Attributes
    ----------
    direct : SummitStatistics
        8-neighbour local maxima.
    spectral : SummitStatistics
        Nayak/McCool formulas from the spectral moments.
    moments : SpectralMoments
        The moments used by the spectral route.
    rms : float
        Rms height of the levelled map √m0, m.
    dx, dy : float
        Pixel size along x (columns) and y (rows), m.
    shape : tuple of int
        (rows, columns) of the map.
    order : int
        Degree of the levelling polynomial.
    n_nan : int
        Number of non-finite pixels dropped.
    periodic : bool
        Neighbours and differences wrapped across the map's edges.
    """

    direct: SummitStatistics
    spectral: SummitStatistics
    moments: SpectralMoments
    rms: float
    dx: float
    dy: float
    shape: tuple[int, int]
    order: int
    n_nan: int
    periodic: bool = False


#: A map is periodic when the rms step across opposite edges is below this many rms neighbour steps.
EDGE_JOIN = 1.5

#: Levelled heights this small relative to the raw ones are rounding noise of the fit.
_ROUNDING = 1e-12


def _check_map(z, dx: float, dy: float) -> np.ndarray:
    z = np.asarray(z, dtype=float)
    if z.ndim != 2 or min(z.shape) < 3:
        raise ParameterError(
            f"a height map must be 2-D with at least 3×3 pixels, got shape {z.shape}"
        )
    for name, value in (("dx", dx), ("dy", dy)):
        if not (math.isfinite(value) and value > 0):
            raise ParameterError(f"{name} = {value!r} m is out of range (allowed: > 0 m)")
    if np.count_nonzero(np.isfinite(z)) < 9:
        raise ParameterError("the height map has fewer than 9 finite pixels")
    return z


def level(z, order: int = 1) -> np.ndarray:
    """Subtract the least-squares polynomial of total degree ``order`` in x and y.

    Parameters
    ----------
    z : array_like
        Height map (rows along y, columns along x), any unit; NaN pixels are ignored
        by the fit and stay NaN.
    order : int
        0: subtract the mean; 1: a plane (default); n: all monomials x^p y^q, p+q ≤ n.

    Returns
    -------
    ndarray
        Levelled map, same unit, zero mean over its finite pixels.
    """
    if not (isinstance(order, int | np.integer) and order >= 0):
        raise ParameterError(f"`order` must be a non-negative integer, got {order!r}")
    z = np.asarray(z, dtype=float)
    ny, nx = z.shape
    y, x = np.meshgrid(np.linspace(-1, 1, ny), np.linspace(-1, 1, nx), indexing="ij")
    ok = np.isfinite(z)
    basis = np.stack(
        [x[ok] ** p * y[ok] ** q for p in range(order + 1) for q in range(order + 1 - p)], axis=1
    )
    coef, *_ = np.linalg.lstsq(basis, z[ok], rcond=None)
    out = np.full_like(z, np.nan)
    out[ok] = z[ok] - basis @ coef
    return out


def flipped(counter) -> np.ndarray:
    """A counter-surface's map, measured face up, turned over about the y axis to face a map:
    its columns reversed and its heights negated (heights upward in the facing map's frame).

    Parameters
    ----------
    counter : array_like
        Height map as measured (rows along y, columns along x), any unit; NaN kept.
    """
    return -np.asarray(counter, dtype=float)[:, ::-1]


def facing_gap(z, counter) -> np.ndarray:
    """The topography of the gap between map ``z`` and a counter-surface facing it,
    z − :func:`flipped` (counter): the one rough surface that, against a flat, has the same
    gaps (docs/physics.md, section 'Two rough surfaces'). Same shape and unit; NaN where either is.

    Parameters
    ----------
    z, counter : array_like
        Height maps of the same shape and pixel size, ``counter`` measured face up.
    """
    return np.asarray(z, dtype=float) - flipped(counter)


class Correlation(NamedTuple):
    """Two maps' levelled heights compared (:func:`height_correlation`).

    Attributes
    ----------
    rho : float
        Correlation coefficient, in [-1, 1].
    rms, other_rms : float
        Rms of each map's levelled heights about their mean over the common pixels, the
        maps' unit.
    """

    rho: float
    rms: float
    other_rms: float


def height_correlation(z, other, order: int = 1) -> Correlation:
    """Correlation ρ of two maps' heights, each levelled by :func:`level` (``order``), over the
    pixels finite in both: Σab/√(Σa² Σb²) of the levelled heights a, b about their means (so the
    rms of a − b is √(rms_a² + rms_b² − 2ρ rms_a rms_b), exactly).

    Parameters
    ----------
    z, other : array_like
        Height maps of the same shape, in one frame (a counter-surface :func:`flipped`).
    order : int
        Levelling degree of each map.
    """
    a, b = level(z, order), level(other, order)
    ok = np.isfinite(a) & np.isfinite(b)
    a, b = a[ok] - a[ok].mean(), b[ok] - b[ok].mean()
    saa, sbb = float(np.sum(a * a)), float(np.sum(b * b))
    rho = float(np.sum(a * b)) / math.sqrt(saa * sbb)
    return Correlation(rho, math.sqrt(saa / a.size), math.sqrt(sbb / b.size))


def _warn_saturation(z: np.ndarray, fraction: float) -> None:
    finite = z[np.isfinite(z)]
    lo, hi = finite.min(), finite.max()
    for where, value in (("minimum", lo), ("maximum", hi)):
        share = np.count_nonzero(finite == value) / finite.size
        if share > fraction and lo != hi:
            warnings.warn(
                f"{share:.1%} of the pixels sit at the map's {where} ({value:.4g}): "
                "the scan is probably saturated, and summit statistics are biased",
                SaturationWarning,
                stacklevel=3,
            )


def _peaks(z: np.ndarray, periodic: bool = False):
    """Candidate pixels ``c``, a neighbour accessor, the candidate mask and the summit mask.

    Non-periodic: the interior pixels, neighbours by slicing. Periodic: every pixel,
    neighbours by wrapping (``nb(di, dj)[i, j] = z[(i + di) mod ny, (j + dj) mod nx]``).
    """
    if periodic:
        c = z

        def nb(di: int, dj: int) -> np.ndarray:
            return np.roll(z, (-di, -dj), axis=(0, 1))

    else:
        c = z[1:-1, 1:-1]

        def nb(di: int, dj: int) -> np.ndarray:
            return z[1 + di : z.shape[0] - 1 + di, 1 + dj : z.shape[1] - 1 + dj]

    before = [(-1, -1), (-1, 0), (-1, 1), (0, -1)]
    after = [(0, 1), (1, -1), (1, 0), (1, 1)]
    finite = np.isfinite(c)
    for d in before + after:
        finite &= np.isfinite(nb(*d))
    with np.errstate(invalid="ignore"):
        peak = finite.copy()
        for d in before:
            peak &= c > nb(*d)
        for d in after:
            peak &= c >= nb(*d)
    return c, nb, finite, peak


def summit_heights(z, periodic: bool = False) -> np.ndarray:
    """Heights of the direct-route summits (8-neighbour maxima, module docstring).

    Parameters
    ----------
    z : array_like
        Levelled height map (see :func:`level`), any unit; NaN allowed.
    periodic : bool
        Neighbours wrap across the map's edges.

    Returns
    -------
    ndarray
        One height per summit, same unit, in raster order.
    """
    c, _, _, peak = _peaks(np.asarray(z, dtype=float), periodic)
    return c[peak]


def summit_curvatures(
    z: np.ndarray, dx: float, dy: float, periodic: bool = False
) -> tuple[np.ndarray, np.ndarray]:
    """Each direct-route summit's height and curvature (rule in the module docstring).

    Parameters
    ----------
    z : ndarray
        Levelled height map, m (NaN allowed).
    dx, dy : float
        Pixel size along columns and rows, m.
    periodic : bool
        Neighbours wrap across the map's edges (every pixel a candidate).

    Returns
    -------
    heights, kappa : ndarray
        Per summit in raster order: its height (m) and its mean curvature
        κ = −(z_xx + z_yy)/2 by central differences (1/m; its radius is 1/κ).
    """
    return _curvatures(z, dx, dy, periodic)[:2]


def radius_by_height(heights: np.ndarray, kappa: np.ndarray, edges) -> tuple[RadiusByHeight, float]:
    """A summit radius by height fitted to the summits' own curvatures, one factor per band.

    The curvature of a summit grows with its height (Nayak 1971; measured on a map by
    ``validation/radius_height.py``). A log-linear fit ln κ = a + b s over the summits with
    κ > 0 (s their standardized heights) gives κ(s) ∝ e^{b s}; scaled so that the summits'
    mean curvature stays 1/R (GW's radius), band k's radius is R times
    ρ_k = ⟨e^{b s_i}⟩ e^{−b c_k}, c_k its centre. A smooth fit, not each band's own mean: the
    top bands hold a few summits.

    Parameters
    ----------
    heights : ndarray
        The summits' standardized heights s_i (the histogram's s = (z − mean)/σ).
    kappa : ndarray
        Their mean curvatures, 1/m (:func:`summit_curvatures`).
    edges : array_like
        Band edges in s (the histogram's standardized bin edges).

    Returns
    -------
    RadiusByHeight, float
        The bands, and the slope b of ln κ against s.

    Raises
    ------
    ParameterError
        Fewer than three summits with κ > 0.
    """
    convex = kappa > 0
    if np.count_nonzero(convex) < 3:
        raise ParameterError(f"{np.count_nonzero(convex)} summits with a positive curvature: "
                             "too few to fit a radius by height")  # fmt: skip
    b = float(np.polyfit(heights[convex], np.log(kappa[convex]), 1)[0])
    edges = np.asarray(edges, dtype=float)
    centre = (edges[:-1] + edges[1:]) / 2
    factors = np.mean(np.exp(b * heights[convex])) * np.exp(-b * centre)
    return RadiusByHeight(tuple(edges), tuple(np.clip(factors, 1e-3, 1e3))), b


def _curvatures(z: np.ndarray, dx: float, dy: float, periodic: bool):
    """:func:`summit_curvatures`, and the number of candidate pixels (finite with their 8
    neighbours)."""
    c, nb, finite, peak = _peaks(z, periodic)
    with np.errstate(invalid="ignore"):
        z_xx = (nb(0, 1) - 2 * c + nb(0, -1)) / dx**2
        z_yy = (nb(1, 0) - 2 * c + nb(-1, 0)) / dy**2
    return c[peak], -(z_xx[peak] + z_yy[peak]) / 2, np.count_nonzero(finite)


def direct_summits(z: np.ndarray, dx: float, dy: float, periodic: bool = False) -> SummitStatistics:
    """Summits as 8-neighbour local maxima of a levelled map (rule in the module docstring).

    Parameters as :func:`summit_curvatures`.

    Returns
    -------
    SummitStatistics
        NaN fields where no summit is found.
    """
    heights, kappa, candidates = _curvatures(z, dx, dy, periodic)
    area = candidates * dx * dy
    if heights.size == 0:
        return SummitStatistics(math.nan, math.nan, 0.0, math.nan, 0)
    return SummitStatistics(
        sigma_s=float(np.std(heights)),
        R=float(1.0 / np.mean(kappa)),
        eta=heights.size / area,
        mean_height=float(np.mean(heights)),
        count=heights.size,
    )


def _differences(u: np.ndarray, n: int, axis: int, periodic: bool) -> np.ndarray:
    """``n``-th forward differences along ``axis`` (n = 1 or 2); wrapping when periodic."""
    if not periodic:
        return np.diff(u, n=n, axis=axis)
    ahead = np.roll(u, -1, axis=axis)
    return ahead - u if n == 1 else ahead - 2 * u + np.roll(u, 1, axis=axis)


def spectral_moments(
    z: np.ndarray, dx: float, dy: float, periodic: bool = False
) -> SpectralMoments:
    """m0, m2, m4 of a levelled map by finite differences, averaged over x and y (McCool 1986).

    Computed on the map divided by its largest |height| (the moments scale as its square),
    so that tiny or huge heights do not underflow or overflow on the way. On a periodic
    map (``periodic=True``) the differences wrap across the edges.

    Raises
    ------
    ParameterError
        If the levelled map is flat (no slope or curvature), or its moments in m are
        not positive normal floats (heights or pixel sizes far outside physical ones).
    """
    peak = float(np.nanmax(np.abs(z)))
    if not (peak > 0 and math.isfinite(peak)):
        raise ParameterError("the levelled height map is flat (all heights equal): no roughness")
    u = z / peak
    m0 = float(np.nanmean(u**2))
    slopes, curvatures = [], []
    for axis, step in ((1, dx), (0, dy)):
        slopes.append(np.nanmean((_differences(u, 1, axis, periodic) / step) ** 2))
        curvatures.append(np.nanmean((_differences(u, 2, axis, periodic) / step**2) ** 2))
    m2, m4 = float(np.mean(slopes)), float(np.mean(curvatures))
    if not (m2 > 0 and m4 > 0):
        raise ParameterError(
            "the levelled height map has no slope or curvature (flat within rounding): no roughness"
        )
    alpha = m0 * m4 / m2**2
    moments = [m0 * peak**2, m2 * peak**2, m4 * peak**2]
    if not all(np.finfo(float).tiny <= m < math.inf for m in moments) or not math.isfinite(alpha):
        raise ParameterError(
            f"the height map's spectral moments m0, m2, m4 = {moments[0]:.3g} m^2, {moments[1]:.3g}, "
            f"{moments[2]:.3g} m^-2 are outside the floating-point range: heights (largest "
            f"{peak:.3g} m) or pixel sizes ({dx:.3g} m, {dy:.3g} m) are not physical (wrong unit?)"
        )
    return SpectralMoments(m0=moments[0], m2=moments[1], m4=moments[2], alpha=alpha)


def spectral_summits(moments: SpectralMoments, area: float) -> SummitStatistics:
    """Nayak (1971) / McCool (1986) summit statistics from the spectral moments.

    η = m4/(6π√3 m2), R = 0.375 √(π/m4), σ_s = √(1 − 0.8968/α) √m0 and mean summit
    height 4 √(m0/(πα)) (McCool 1986, Eqs. for the equivalent isotropic surface;
    :func:`mcsim.model.counterface.summits_of`).

    Parameters
    ----------
    moments : SpectralMoments
        From :func:`spectral_moments`.
    area : float
        Area of the map, m², for the expected ``count``.
    """
    s = summits_of(moments.m0, moments.m2, moments.m4, moments.alpha)
    return SummitStatistics(
        sigma_s=s.sigma, R=s.R, eta=s.eta, mean_height=s.summit_offset, count=s.eta * area
    )


def summit_statistics(
    z,
    dx: float,
    dy: float | None = None,
    *,
    order: int = 1,
    saturation_fraction: float = 0.01,
    periodic: bool = False,
) -> TopographyResult:
    """Level a height map and compute its summit statistics by both routes.

    Parameters
    ----------
    z : array_like
        Height map, m; rows along y, columns along x. NaN pixels are dropped.
    dx : float
        Pixel size along x (between columns), m.
    dy : float, optional
        Pixel size along y (between rows), m; ``dx`` if omitted.
    order : int
        Degree of the levelling polynomial (1: plane).
    saturation_fraction : float
        Share of pixels at the minimum or maximum above which a
        :class:`SaturationWarning` is issued.
    periodic : bool
        The map repeats (see :func:`periodic_edges`): summit neighbours and the spectral
        differences wrap across its edges.

    Returns
    -------
    TopographyResult
    """
    dy = dx if dy is None else dy
    z = _check_map(z, dx, dy)
    n_nan = int(np.count_nonzero(~np.isfinite(z)))
    _warn_saturation(z, saturation_fraction)
    levelled = level(z, order)
    if np.nanmax(np.abs(levelled)) <= _ROUNDING * np.nanmax(np.abs(z)):
        raise ParameterError(
            "the height map is flat: after levelling only rounding noise is left (no roughness)"
        )
    moments = spectral_moments(levelled, dx, dy, periodic)
    area = (np.size(z) - n_nan) * dx * dy
    return TopographyResult(
        direct=direct_summits(levelled, dx, dy, periodic),
        spectral=spectral_summits(moments, area),
        moments=moments,
        rms=math.sqrt(moments.m0),
        dx=float(dx),
        dy=float(dy),
        shape=(int(z.shape[0]), int(z.shape[1])),
        order=int(order),
        n_nan=n_nan,
        periodic=bool(periodic),
    )


def edge_steps(z) -> tuple[float, float]:
    """Rms step across opposite edges over the rms step between neighbours, along y and along x.

    Parameters
    ----------
    z : array_like
        Height map, any unit; a NaN pixel makes the ratio of its axis NaN.

    Returns
    -------
    (float, float)
        The ratios for rows (top against bottom edge) and columns (left against right edge).
    """
    z = np.asarray(z, dtype=float)
    ratios = []
    for axis in (0, 1):
        inner = np.sqrt(np.mean(np.diff(z, axis=axis) ** 2))
        across = np.sqrt(np.mean((np.take(z, 0, axis=axis) - np.take(z, -1, axis=axis)) ** 2))
        ratios.append(float(across / inner) if inner > 0 else math.inf)
    return ratios[0], ratios[1]


def periodic_edges(z) -> tuple[bool, str]:
    """Whether a map repeats: both :func:`edge_steps` ratios below :data:`EDGE_JOIN`.

    Parameters
    ----------
    z : array_like
        Height map as read (before levelling: a tilt does not repeat), any unit.

    Returns
    -------
    periodic : bool
        Opposite edges join along both axes (False where a ratio is NaN).
    reason : str
        The two ratios and the decision, for the output.
    """
    steps = edge_steps(z)
    periodic = all(step < EDGE_JOIN for step in steps)
    return periodic, (
        f"edge steps {steps[0]:.2f}, {steps[1]:.2f} x the neighbour step "
        f"({'<' if periodic else 'not <'} {EDGE_JOIN:g}: "
        f"{'edges join' if periodic else 'edges do not join'})"
    )

"""The GW surface of a height map: its summits by both routes, their heights' histogram.

:func:`map_surface` takes a map read once (:func:`mcsim.topography.maps.read_map`) and returns
what ``mcsim ingest`` writes and ``mcsim contact`` puts beside the exact solve: the summit
statistics by both routes of :mod:`mcsim.topography.summits`, the measured histograms of the
summit heights and of the map's heights, and the GW :class:`~mcsim.model.params.Surface`
built from them (R and η from the chosen route, σ = its σ_s, the histogram's shape; ``rq`` and
``summit_offset`` about the map's mean plane; with ``radius_by_height``, a radius for each
band of summit heights). Summit statistics describe the surface *as sampled*: they depend on
the pixel size (docs/physics.md, section 'Summit statistics from a height map').
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mcsim.model.errors import MCSimError, ParameterError
from mcsim.model.params import Surface
from mcsim.topography.empirical import Empirical
from mcsim.topography.maps import LEVELS
from mcsim.topography.readers import HeightMap, ReaderError
from mcsim.topography.summits import (
    TopographyResult,
    summit_curvatures,
    summit_heights,
    summit_statistics,
)
from mcsim.topography.summits import radius_by_height as fit_radius

ROUTES = ("direct", "spectral")
HEIGHTS = ("summits", "map")
#: Largest number of bins of a written histogram (Freedman–Diaconis otherwise).
MAX_BINS = 256
#: Bins wider than this many σ (forced by the :data:`MAX_BINS` cap) are warned about.
COARSE_BIN = 0.25
#: Direct and spectral summit statistics further apart than this factor are warned about.
ROUTE_DISAGREEMENT = 3.0


@dataclass(frozen=True)
class MapSurface:
    """A map's GW surface and what it was built from (:func:`map_surface`).

    Attributes
    ----------
    surface : Surface
        The GW surface.
    topography : TopographyResult
        Summit statistics by both routes.
    peaks : ndarray
        Heights of the direct-route summits on the levelled map, m.
    edges, counts : ndarray
        The histogram of the surface's heights (summits' or the map's): bin edges, m, and counts.
    map_edges, map_counts : ndarray
        The histogram of the levelled map's heights: bin edges, m, and counts.
    warnings : tuple of str
        Non-square pixels, routes that disagree, bins made coarse by outliers, saturation.
    """

    surface: Surface
    topography: TopographyResult
    peaks: np.ndarray
    edges: np.ndarray
    counts: np.ndarray
    map_edges: np.ndarray
    map_counts: np.ndarray
    warnings: tuple[str, ...]


def histogram_bins(z: np.ndarray) -> np.ndarray:
    """Freedman–Diaconis bins, at most :data:`MAX_BINS`; warns when outliers make them coarse."""
    edges = np.histogram_bin_edges(z, bins="fd")
    if edges.size - 1 > MAX_BINS or edges.size < 3:
        capped = edges.size - 1 > MAX_BINS
        edges = np.histogram_bin_edges(z, bins=min(MAX_BINS, max(2, int(np.sqrt(z.size)))))
        width, sigma = edges[1] - edges[0], float(np.std(z))
        if capped and width > COARSE_BIN * sigma:
            warnings.warn(
                f"histogram bins are {width * 1e9:.3g} nm wide ({width / sigma:.2g} sigma): the "
                f"heights span {z.min() * 1e9:.4g} .. {z.max() * 1e9:.4g} nm "
                f"({(z.max() - z.min()) / sigma:.0f} sigma), so outliers (spikes?) force coarse "
                "bins and blur the distribution's shape; remove them from the map first",
                stacklevel=2,
            )
    return edges


def _warn_route_disagreement(topo: TopographyResult) -> None:
    """Warn where the direct and spectral routes differ by more than :data:`ROUTE_DISAGREEMENT`."""
    far = []
    for key, label, unit, scale in (("eta", "eta", "um^-2", 1e-12), ("R", "R", "um", 1e6),
                                    ("sigma_s", "sigma_s", "nm", 1e9)):  # fmt: skip
        a, b = getattr(topo.direct, key), getattr(topo.spectral, key)
        if a > 0 and b > 0 and max(a / b, b / a) > ROUTE_DISAGREEMENT:
            far.append(f"{label} {a * scale:.3g} vs {b * scale:.3g} {unit}")
    if far:
        warnings.warn(
            f"the direct and spectral routes disagree by more than a factor "
            f"{ROUTE_DISAGREEMENT:g} ({'; '.join(far)}): the map is not a Gaussian "
            "random surface at this sampling (features, noise or a coarse pixel size); "
            "the --route choice matters here",
            stacklevel=2,
        )


def default_name(hmap: HeightMap) -> str:
    """The file's stem, or ``<stem>-on-<counter stem>`` facing a counter-surface."""
    stem = Path(hmap.source).stem
    return stem if hmap.facing is None else f"{stem}-on-{Path(hmap.facing.source).stem}"


def map_surface(
    hmap: HeightMap,
    *,
    route: str = "direct",
    heights: str = "summits",
    radius_by_height: bool = False,
    name: str | None = None,
) -> MapSurface:
    """The GW surface of a map read and levelled by :func:`~mcsim.topography.maps.read_map`.

    Parameters
    ----------
    hmap : HeightMap
        Prepared: its ``level`` and ``periodic`` decided, its ``levelled`` heights (m).
    route : {"direct", "spectral"}
        Summit statistics the surface takes its σ_s, R and η from.
    heights : {"summits", "map"}
        Histogram of the direct-route summit heights (default) or of all pixels.
    radius_by_height : bool
        Give each band of summit heights its own radius, from a fit of the summits'
        curvatures against their heights (:func:`mcsim.topography.summits.radius_by_height`).
    name : str, optional
        Surface name; :func:`default_name` by default.

    Returns
    -------
    MapSurface

    Raises
    ------
    MCSimError
        A map with too few summits or none the route can use, as one message that starts
        with the file name.
    """
    path = hmap.source
    name = default_name(hmap) if name is None else name
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            if not math.isclose(hmap.dx, hmap.dy, rel_tol=1e-3):
                warnings.warn(
                    f"pixels are not square ({hmap.dx * 1e9:.4g} nm x {hmap.dy * 1e9:.4g} nm): the "
                    "8-neighbour summits and curvatures mix both pitches; resample to square "
                    "pixels for summit statistics you can compare",
                    stacklevel=2,
                )
            topo = summit_statistics(
                hmap.heights, hmap.dx, hmap.dy, order=LEVELS[hmap.level], periodic=hmap.periodic
            )
            _warn_route_disagreement(topo)
            levelled = hmap.levelled
            peaks = summit_heights(levelled, hmap.periodic)
            if peaks.size < 2:
                raise ParameterError(f"found {peaks.size} summit(s): too few for a distribution")
            pixels = levelled[np.isfinite(levelled)]
            sample = peaks if heights == "summits" else pixels
            edges = histogram_bins(sample)
            map_edges = histogram_bins(pixels)
        counts, _ = np.histogram(sample, bins=edges)
        shape = Empirical.from_histogram(edges, counts, source=f"{path} ({heights})")
        map_counts, _ = np.histogram(pixels, bins=map_edges)
        map_shape = Empirical.from_histogram(map_edges, map_counts, source=f"{path} (map)")
        stats = getattr(topo, route)
        if not (math.isfinite(stats.sigma_s) and stats.sigma_s > 0 and stats.R > 0):
            raise ParameterError(
                f"the {route} route gives sigma_s = {stats.sigma_s:.3g} m, R = {stats.R:.3g} m: "
                "not a summit population (try --route direct or another --level)"
            )
        plane = float(np.mean(pixels))
        bands = None
        if radius_by_height:
            z_peaks, kappa = summit_curvatures(levelled, hmap.dx, hmap.dy, hmap.periodic)
            bands = fit_radius((z_peaks - shape.mean) / shape.sigma, kappa, shape.edges)[0]
        surface = Surface(sigma=stats.sigma_s, R=stats.R, eta=stats.eta, heights=shape, name=name,
                          rq=float(np.sqrt(np.mean((pixels - plane) ** 2))),
                          summit_offset=float(np.mean(peaks)) - plane, map_heights=map_shape,
                          radius_by_height=bands)  # fmt: skip
    except ReaderError:
        raise
    except MCSimError as err:
        raise type(err)(f"{path}: {err}") from None
    return MapSurface(surface=surface, topography=topo, peaks=peaks,
                      edges=np.asarray(edges, dtype=float), counts=counts.astype(float),
                      map_edges=np.asarray(map_edges, dtype=float),
                      map_counts=map_counts.astype(float),
                      warnings=tuple(str(w.message) for w in caught))  # fmt: skip

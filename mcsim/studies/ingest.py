"""From a measured file to a surface file: ``mcsim ingest``.

:func:`ingest_file` reads a height map (any format of :mod:`mcsim.topography.readers`) or a text
histogram of heights, and returns an :class:`IngestResult`: what was read, the height
statistics, the summit statistics by both routes of :mod:`mcsim.topography.summits`, and the
GW :class:`~mcsim.model.params.Surface` built from them. :meth:`IngestResult.write_surface`
writes that surface as a TOML file that ``mcsim analytic --surface`` and ``mcsim
simulate --surface`` read (:mod:`mcsim.store.config`).

What the surface file holds
---------------------------
* ``R`` and ``eta`` from the chosen route (``direct``: 8-neighbour summits, default;
  ``spectral``: Nayak/McCool), and ``sigma`` = that route's σ_s.
* The *shape* of the summit-height distribution, as a measured histogram: the heights
  of the direct-route summits (default), or, with ``heights="map"``, of all pixels of
  the levelled map. It is written to a companion CSV file next to the TOML file,
  ``<stem>-heights.csv`` (three columns ``left [nm], right [nm], count``), and named
  by a path relative to the TOML file's folder (``[surface.heights] file = ...``), so
  the two files move together. The histogram is standardized when read; ``sigma``
  sets its scale (:mod:`mcsim.store.config`).
* For the environment (:mod:`mcsim.physics.environment`), measured: ``rq``, the rms of the
  levelled map about its mean plane; ``summit_offset``, the mean height of the
  direct-route summits above that plane; and the map's own height histogram, written to
  ``<stem>-map-heights.csv`` and named by ``[surface.map_heights] file = ...``.
* Comments with the provenance: source file and channel, creation time, mcsim
  version, command line, route, levelling, pixel size, both routes' numbers and the
  caveat that they depend on the sampling interval.

A text histogram as input (two or three columns, see :mod:`mcsim.topography.readers.histogram`)
carries no summit radius or density: the caller gives ``R`` and ``eta``, and
``sigma`` is the histogram's own. A text file with more than three numeric columns
(or a ``.asc``/``.xyz`` file) is a height map.

Periodic maps
-------------
A periodic map (a synthetic one, usually) is analysed as such: summit neighbours wrap across
its edges, and its default levelling removes only the mean, so its rms is left as it is (a
fitted plane would remove a random tilt the map does not have). Unless told
(``periodic=True/False``), a map is periodic when its opposite edges join
(:func:`mcsim.topography.summits.periodic_edges`, checked on the map as read); the decision
and its numbers are printed and recorded.

Summit statistics depend strongly on the pixel size and the instrument bandwidth
(docs/physics.md, section 'Summit statistics from a height map'): they describe the surface *as
sampled*; the pixel size is written next to them everywhere.
"""

from __future__ import annotations

import dataclasses
import math
import os
import re
import warnings
from pathlib import Path

import numpy as np

from mcsim.model.errors import MCSimError, ParameterError
from mcsim.model.params import Material, Surface
from mcsim.studies.ingested import LEVELS, ROUTES, FacingMap, HeightSummary, IngestResult
from mcsim.topography.empirical import Empirical
from mcsim.topography.readers import HeightMap, ReaderError, read_height_map, read_histogram
from mcsim.topography.readers import histogram as _histogram_format
from mcsim.topography.summits import (
    TopographyResult,
    facing_gap,
    flipped,
    height_correlation,
    periodic_edges,
    summit_curvatures,
    summit_heights,
    summit_statistics,
)
from mcsim.topography.summits import level as level_heights
from mcsim.topography.summits import radius_by_height as fit_radius

HEIGHTS = ("summits", "map")
#: Pixel sizes a map may have, m: from 1 pm (below an atom's spacing) to 1 m (above any
#: profilometer's field). Outside them the summit statistics' powers of heights and
#: slopes (curvatures ~ z/dx², moments ~ (z/dx²)²) overflow or underflow double precision.
PIXEL_SIZE_RANGE = (1e-12, 1.0)
#: Largest |height| of a map, m (1 m): a larger one is a unit mistake, and its squares
#: overflow the summit statistics.
MAX_HEIGHT = 1.0
#: Largest number of bins of a written histogram (Freedman–Diaconis otherwise).
MAX_BINS = 256
#: Bins wider than this many σ (forced by the :data:`MAX_BINS` cap) are warned about.
COARSE_BIN = 0.25
#: Direct and spectral summit statistics further apart than this factor are warned about.
ROUTE_DISAGREEMENT = 3.0
#: Peak memory of the analysis per map pixel, bytes (measured: float64 copies, FFT, masks).
BYTES_PER_PIXEL = 96
_FORMAT_NAMES = {
    ".gwy": "Gwyddion .gwy",
    ".ibw": "Igor binary wave .ibw",
    ".nid": "Nanosurf .nid",
    ".npy": "NumPy .npy",
    ".xyz": "XYZ text",
}
_SPLIT = re.compile(r"[,;\s]+")


def is_histogram_file(path: Path) -> bool:
    """A text histogram: ``.hist``/``.tsv``, or a text file with at most 3 numeric columns."""
    suffix = path.suffix.lower()
    if suffix in (".hist", ".tsv"):
        return True
    if suffix not in _HISTOGRAM_OR_MATRIX:
        return False
    try:
        text = path.read_bytes()[:65536].decode("utf-8", errors="replace")
    except OSError:
        return False  # the reader names the problem
    for line in text.splitlines():
        cells = [c for c in _SPLIT.split(line.strip()) if c]
        if not cells or line.lstrip().startswith("#"):
            continue
        try:
            [float(c) for c in cells]
        except ValueError:
            continue
        return len(cells) <= 3
    return True


_HISTOGRAM_OR_MATRIX = tuple(set(_histogram_format.EXTENSIONS) - {".hist", ".tsv"})


def _histogram_bins(z: np.ndarray) -> np.ndarray:
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


def _check_choice(name: str, value: str, allowed) -> None:
    if value not in allowed:
        raise ParameterError(f"`{name}` must be one of {', '.join(allowed)}, got {value!r}")


def ingest_file(
    path: str | Path,
    *,
    unit: str | None = None,
    pixel_size: float | tuple[float, float] | None = None,
    route: str = "direct",
    level: str | None = None,
    heights: str = "summits",
    R: float | None = None,
    eta: float | None = None,
    name: str | None = None,
    channel: str | None = None,
    periodic: bool | None = None,
    calibrate: Material | None = None,
    radius_by_height: bool | None = None,
    adhesion_w: float | None = None,
    adhesion_range: float | None = None,
    counter: str | Path | None = None,
    progress: bool = False,
) -> IngestResult:
    """Read a height map or a height histogram and derive a GW surface from it.

    Parameters
    ----------
    path : path-like
        Height map (``.gwy .ibw .nid .npy .xyz`` or a text matrix) or text histogram.
    unit : str, optional
        Height unit for files that store none (e.g. ``"nm"``).
    pixel_size : float or (float, float), optional
        Pixel size, m, for maps that store none.
    route : {"direct", "spectral"}
        Summit statistics written as ``sigma``, ``R``, ``eta`` (maps only).
    level : str, optional
        A key of :data:`LEVELS`: ``"plane"``, ``"none"`` (mean only), ``"poly2"`` ...
        ``"poly5"``; default :func:`default_level` (``"plane"``, ``"none"`` on a periodic map).
    heights : {"summits", "map"}
        Histogram of the direct-route summit heights (default) or of all pixels.
    R : float, optional
        Summit radius, m: required for a histogram input, refused for a map.
    eta : float, optional
        Summit density, m⁻²: required for a histogram input, refused for a map.
    name : str, optional
        Surface name; the file's stem by default.
    channel : str, optional
        Channel of a multi-channel map (see :func:`mcsim.topography.readers.read_height_map`).
    periodic : bool, optional
        Analyse the map as periodic (summit neighbours wrap) or not; None: periodic when its
        opposite edges join (:func:`mcsim.topography.summits.periodic_edges`). Maps only.
    calibrate : Material, optional
        Fit GW's summit-radius scale to exact elastic solves of the map with this material's
        E* (:func:`mcsim.studies.calibration.calibrate`); recorded in the surface file and
        used by every command that reads it. Maps only.
    radius_by_height : bool, optional
        Give each band of summit heights (each histogram bin) its own radius, from a fit of
        the summits' curvatures against their heights
        (:func:`mcsim.topography.summits.radius_by_height`): taller summits are sharper.
        None (default): with ``calibrate`` only. Maps with ``heights="summits"`` only.
    adhesion_w : float, optional
        With ``calibrate``: also calibrate GW's pull-off on exact adhesive cycles of the map
        with this work of adhesion, J/m², > 0
        (:func:`mcsim.studies.adhesioncalibration.calibrate_adhesion`); recorded, not applied.
    adhesion_range : float, optional
        The exponential law's range, m, > 0 (default the material's z0, else 1 nm).
    counter : path-like, optional
        A counter-surface's height map, measured face up, of the same size and pixel size
        (read with the same ``unit``, ``pixel_size`` and ``channel``): it is turned over to
        face the map (:func:`~mcsim.topography.summits.flipped`) and the map analysed is the
        gap's topography, map − flipped counter
        (:func:`~mcsim.topography.summits.facing_gap`); the correlation of the two levelled
        maps is measured (``IngestResult.facing``). Maps only; not with ``calibrate``.
    progress : bool
        Progress bars on stderr over the calibrations' exact solves.

    Returns
    -------
    IngestResult
        Its ``warnings`` include non-square pixels, direct and spectral routes more
        than :data:`ROUTE_DISAGREEMENT` apart, and bins made coarse by outliers.

    Raises
    ------
    MCSimError
        Every problem, as one message that starts with the file name; a map too
        large for the available memory is refused before its analysis, naming the
        size that fits.
    """
    _check_choice("route", route, ROUTES)
    if level is not None:
        _check_choice("level", level, tuple(LEVELS))
    _check_choice("heights", heights, HEIGHTS)
    if adhesion_w is not None or adhesion_range is not None:
        from mcsim.studies.adhesioncalibration import check_inputs

        if calibrate is None or adhesion_w is None:
            raise ParameterError("w: the adhesion calibration needs --calibrate and --w")
        check_inputs(adhesion_w, adhesion_range)
    path = Path(path)
    if not path.exists():
        raise ReaderError(f"{path}: no such file")
    if not path.is_file():
        raise ReaderError(f"{path}: not a file")
    if name is None:
        name = path.stem if counter is None else f"{path.stem}-on-{Path(counter).stem}"
    if counter is not None and calibrate is not None:
        raise ParameterError(f"{path}: --calibrate solves the map file itself: not with a "
                             "counter-surface (ingest the gap without --calibrate)")  # fmt: skip
    if counter is not None and is_histogram_file(path):
        raise ParameterError(f"{path}: a text histogram has no map: a counter-surface combines "
                             "two height maps")  # fmt: skip
    if is_histogram_file(path):
        if channel is not None:
            raise ParameterError(
                f"{path}: a text histogram has no channels: --channel does not apply"
            )
        if periodic is not None:
            raise ParameterError(
                f"{path}: a text histogram has no edges: --periodic does not apply"
            )
        if calibrate is not None:
            raise ParameterError(
                f"{path}: a text histogram has no map to solve: --calibrate needs a height map"
            )
        if radius_by_height:
            raise ParameterError(f"{path}: a text histogram has no summit curvatures: "
                                 "--radius-by-height needs a height map")  # fmt: skip
        return _ingest_histogram(path, unit, R, eta, name)
    by_height = calibrate is not None if radius_by_height is None else bool(radius_by_height)
    if by_height and heights != "summits":
        if radius_by_height:
            raise ParameterError(f"{path}: --radius-by-height needs the summits' histogram "
                                 "(--heights summits), not the map's")  # fmt: skip
        by_height = False
    if R is not None or eta is not None:
        raise ParameterError(
            f"{path}: R and eta come from the map's summits: give them only with a histogram file"
        )
    hmap = read_checked(path, unit=unit, pixel_size=pixel_size, channel=channel)
    alone, counter_map = hmap.heights, None
    if counter is not None:
        counter_map = read_counter_map(path, counter, hmap, unit=unit, pixel_size=pixel_size,
                                       channel=channel)  # fmt: skip
        hmap = dataclasses.replace(hmap, heights=facing_gap(alone, counter_map.heights))
    _check_memory(path, hmap.heights.shape)
    periodic, periodic_reason = decide_periodic(hmap.heights, periodic)
    level = default_level(periodic) if level is None else level
    facing = None
    if counter_map is not None:
        measured = height_correlation(alone, flipped(counter_map.heights), LEVELS[level])
        facing = FacingMap(Path(counter), *measured)
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
                hmap.heights, hmap.dx, hmap.dy, order=LEVELS[level], periodic=periodic
            )
            _warn_route_disagreement(topo)
            levelled = level_heights(hmap.heights, LEVELS[level])
            peaks = summit_heights(levelled, periodic)
            if peaks.size < 2:
                raise ParameterError(f"found {peaks.size} summit(s): too few for a distribution")
            pixels = levelled[np.isfinite(levelled)]
            sample = peaks if heights == "summits" else pixels
            edges = _histogram_bins(sample)
            map_edges = _histogram_bins(pixels)
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
        if by_height:
            z_peaks, kappa = summit_curvatures(levelled, hmap.dx, hmap.dy, periodic)
            bands = fit_radius((z_peaks - shape.mean) / shape.sigma, kappa, shape.edges)[0]
        surface = Surface(sigma=stats.sigma_s, R=stats.R, eta=stats.eta, heights=shape, name=name,
                          rq=float(np.sqrt(np.mean((pixels - plane) ** 2))),
                          summit_offset=float(np.mean(peaks)) - plane, map_heights=map_shape,
                          radius_by_height=bands)  # fmt: skip
    except ReaderError:
        raise
    except MCSimError as err:
        raise type(err)(f"{path}: {err}") from None
    calibration = None
    if calibrate is not None:
        from mcsim.studies.calibration import calibrate as fit

        calibration = fit(path, calibrate, unit=unit, pixel_size=pixel_size, channel=channel,
                          level=level, periodic=periodic, surface=surface,
                          progress=progress)  # fmt: skip
    adhesion = None
    if adhesion_w is not None:
        from mcsim.studies.adhesioncalibration import calibrate_adhesion

        try:
            adhesion = calibrate_adhesion(levelled, (hmap.dx, hmap.dy), calibrate,
                                          calibration.apply(surface), w=adhesion_w,
                                          range_=adhesion_range, periodic=periodic,
                                          progress=progress)  # fmt: skip
        except MCSimError as err:
            raise type(err)(f"{path}: adhesion calibration: {err}") from None
    return IngestResult(
        source=path,
        format=_FORMAT_NAMES.get(path.suffix.lower(), "text matrix"),
        channel=hmap.channel,
        reader_notes=hmap.notes,
        surface=surface,
        edges=np.asarray(edges, dtype=float),
        counts=counts.astype(float),
        map_edges=np.asarray(map_edges, dtype=float),
        map_counts=map_counts.astype(float),
        density=False,
        heights_from=(
            "direct-route summit heights"
            if heights == "summits"
            else "all heights of the levelled map"
        ),
        route=route,
        level=level,
        shape=hmap.shape,
        dx=hmap.dx,
        dy=hmap.dy,
        n_nan=topo.n_nan,
        map_heights=HeightSummary.of(levelled),
        summit_heights=HeightSummary.of(peaks),
        topography=topo,
        warnings=tuple(str(w.message) for w in caught),
        periodic=periodic,
        periodic_reason=periodic_reason,
        calibration=calibration,
        adhesion_calibration=adhesion,
        facing=facing,
    )


def check_scale(hmap: HeightMap) -> HeightMap:
    """``hmap`` if its pixel sizes lie in :data:`PIXEL_SIZE_RANGE` and its heights within
    ±:data:`MAX_HEIGHT`.

    Raises
    ------
    ReaderError
        Naming the file, the field, its value and the allowed range.
    """
    low, high = PIXEL_SIZE_RANGE
    for name, value in (("dx", hmap.dx), ("dy", hmap.dy)):
        if not low <= value <= high:
            raise ReaderError(f"{hmap.source}: pixel size {name} = {value:.4g} m is out of range "
                              f"(allowed: {low:g} m to {high:g} m; check --pixel-size)")  # fmt: skip
    largest = float(np.nanmax(np.abs(hmap.heights)))
    if not largest <= MAX_HEIGHT:
        raise ReaderError(f"{hmap.source}: heights up to {largest:.4g} m are out of range "
                          f"(allowed: |height| <= {MAX_HEIGHT:g} m; check --unit)")  # fmt: skip
    return hmap


def read_checked(path: str | Path, **options) -> HeightMap:
    """:func:`~mcsim.topography.readers.read_height_map`, then :func:`check_scale`."""
    return check_scale(read_height_map(path, **options))


def read_map(
    path: str | Path, *, unit=None, pixel_size=None, channel=None, counter: str | Path | None = None
) -> HeightMap:
    """The height map of ``path`` (:func:`read_checked`), or with a ``counter``-surface's map
    the gap's topography, map − turned-over counter
    (:func:`~mcsim.topography.summits.facing_gap`; :func:`read_counter_map` checks it)."""
    hmap = read_checked(path, unit=unit, pixel_size=pixel_size, channel=channel)
    if counter is None:
        return hmap
    other = read_counter_map(Path(path), counter, hmap, unit=unit, pixel_size=pixel_size,
                             channel=channel)  # fmt: skip
    return dataclasses.replace(hmap, heights=facing_gap(hmap.heights, other.heights))


def read_counter_map(
    path: Path, counter: str | Path, hmap: HeightMap, *, unit=None, pixel_size=None, channel=None
) -> HeightMap:
    """A counter-surface's height map for the map ``hmap`` read from ``path``: read as ``hmap``
    was, refused unless it is a map of the same size and pixel size.

    Raises
    ------
    MCSimError
        Naming the counter-surface and what differs.
    """
    from mcsim.model.presets import SURFACES

    counter = Path(counter)
    where = f"counter-surface {counter}"
    if str(counter) in SURFACES or counter.suffix == ".toml":
        raise ParameterError(f"{where}: a Gaussian GW surface does not combine with a measured "
                             "map (its histogram and radii have no spectral moments to add): "
                             "give the counter-surface's height map")  # fmt: skip
    if counter.is_file() and is_histogram_file(counter):
        raise ParameterError(f"{where}: a text histogram, not a height map: a counter-surface "
                             "combines two height maps")  # fmt: skip
    try:
        other = read_checked(counter, unit=unit, pixel_size=pixel_size, channel=channel)
    except MCSimError as err:
        raise type(err)(f"{where}: {err}") from None
    same_pixel = all(math.isclose(a, b, rel_tol=1e-6) for a, b in ((hmap.dx, other.dx),
                                                                 (hmap.dy, other.dy)))  # fmt: skip
    if other.heights.shape != hmap.heights.shape or not same_pixel:

        def size(m: HeightMap) -> str:
            rows, cols = m.heights.shape
            return f"{cols} x {rows} pixels of {m.dx * 1e9:.6g} x {m.dy * 1e9:.6g} nm"

        raise ParameterError(f"{where}: {size(other)}, {path}: {size(hmap)}: the two maps must "
                             "have the same size and pixel size to face each other pixel by "
                             "pixel (crop or resample one)")  # fmt: skip
    return other


def decide_periodic(z, periodic: bool | None) -> tuple[bool, str]:
    """A map's periodicity: as asked, or from its edges (:func:`~mcsim.topography.summits.periodic_edges`).

    Parameters
    ----------
    z : ndarray
        Height map as read, any unit.
    periodic : bool or None
        The user's choice; None decides by the edges.

    Returns
    -------
    (bool, str)
        The decision and why, for the output.
    """
    if periodic is None:
        return periodic_edges(z)
    return bool(periodic), "as asked"


def default_level(periodic: bool) -> str:
    """The levelling used unless asked: ``"plane"``, or ``"none"`` (the mean only) on a periodic map.

    A periodic map has no tilt: fitting a plane would remove its random one and lower its rms.
    """
    return "none" if periodic else "plane"


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


def available_memory() -> int:
    """Bytes of memory available to a new allocation (``MemAvailable``; else free pages)."""
    try:
        with open("/proc/meminfo", encoding="ascii") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return 1 << 62  # unknown: do not refuse


def _check_memory(path: Path, shape: tuple[int, int]) -> None:
    """Refuse a map whose analysis needs more memory than is available, naming what fits."""
    need, have = shape[0] * shape[1] * BYTES_PER_PIXEL, available_memory()
    if need > have:
        side = math.isqrt(have // BYTES_PER_PIXEL)
        raise ParameterError(
            f"{path}: a {shape[1]} x {shape[0]} map needs about {need / 1e9:.3g} GB to analyse, "
            f"{have / 1e9:.3g} GB are available: crop or downsample it to at most about "
            f"{side} x {side} pixels"
        )


def _histogram_summary(edges, weights, density: bool, sigma: float) -> HeightSummary:
    """Exact moments of the piecewise-uniform density of a histogram (as :mod:`mcsim.topography.empirical`)."""
    width = np.diff(edges)
    mass = weights * width if density else weights
    p = mass / mass.sum()
    c = (edges[:-1] + edges[1:]) / 2
    mean = float(np.sum(p * c))
    d = c - mean
    # moments of a uniform density on [c − w/2, c + w/2] about the mean
    m3 = np.sum(p * (d**3 + d * width**2 / 4))
    m4 = np.sum(p * (d**4 + d**2 * width**2 / 2 + width**4 / 80))
    occupied = np.flatnonzero(mass > 0)
    return HeightSummary(
        count=0 if density else round(float(mass.sum())),
        mean=mean,
        sigma=sigma,
        skewness=float(m3 / sigma**3),
        kurtosis=float(m4 / sigma**4),
        minimum=float(edges[occupied[0]]),
        maximum=float(edges[occupied[-1] + 1]),
    )


def _ingest_histogram(path: Path, unit, R, eta, name) -> IngestResult:
    hist = read_histogram(path, unit=unit)
    emp = hist.to_empirical()
    if R is None or eta is None:
        raise ParameterError(
            f"{path}: a height histogram carries no summit radius or density: pass --R and --eta"
        )
    try:
        surface = Surface(sigma=emp.sigma, R=R, eta=eta, heights=emp, name=name)
    except MCSimError as err:
        raise type(err)(f"{path}: {err}") from None
    summary = _histogram_summary(hist.edges, hist.weights, hist.density, emp.sigma)
    return IngestResult(
        source=path,
        format="text histogram",
        channel="",
        reader_notes=hist.notes,
        surface=surface,
        edges=hist.edges,
        counts=np.asarray(hist.weights, dtype=float),
        density=hist.density,
        heights_from=f"histogram read from {path.name}",
        route="user",
        level="",
        shape=None,
        dx=math.nan,
        dy=math.nan,
        n_nan=0,
        map_heights=None,
        summit_heights=summary,
        topography=None,
    )

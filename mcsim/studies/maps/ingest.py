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

import math
from pathlib import Path

import numpy as np

from mcsim.model.errors import MCSimError, ParameterError
from mcsim.model.params import Material, Surface
from mcsim.studies.maps.ingested import HeightSummary, IngestResult
from mcsim.topography.maps import LEVELS, is_histogram_file, read_map
from mcsim.topography.mapsurface import HEIGHTS, ROUTES, map_surface
from mcsim.topography.readers import ReaderError, read_histogram

_FORMAT_NAMES = {
    ".gwy": "Gwyddion .gwy",
    ".ibw": "Igor binary wave .ibw",
    ".nid": "Nanosurf .nid",
    ".npy": "NumPy .npy",
    ".xyz": "XYZ text",
}


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
        A key of :data:`~mcsim.topography.maps.LEVELS`: ``"plane"``, ``"none"`` (mean only),
        ``"poly2"`` ... ``"poly5"``; default :func:`~mcsim.topography.maps.default_level`
        (``"plane"``, ``"none"`` on a periodic map).
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
        E* (:func:`mcsim.studies.maps.calibration.calibrate`); recorded in the surface file and
        used by every command that reads it. Maps only.
    radius_by_height : bool, optional
        Give each band of summit heights (each histogram bin) its own radius, from a fit of
        the summits' curvatures against their heights
        (:func:`mcsim.topography.summits.radius_by_height`): taller summits are sharper.
        None (default): with ``calibrate`` only. Maps with ``heights="summits"`` only.
    adhesion_w : float, optional
        With ``calibrate``: also calibrate GW's pull-off on exact adhesive cycles of the map
        with this work of adhesion, J/m², > 0
        (:func:`mcsim.studies.maps.adhesioncalibration.calibrate_adhesion`); recorded, not applied.
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
        than :data:`~mcsim.topography.mapsurface.ROUTE_DISAGREEMENT` apart, and bins made coarse by outliers.

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
        from mcsim.studies.maps.adhesioncalibration import check_inputs

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
    hmap = read_map(path, unit=unit, pixel_size=pixel_size, channel=channel, counter=counter,
                    level=level, periodic=periodic)  # fmt: skip
    found = map_surface(hmap, route=route, heights=heights, radius_by_height=by_height, name=name)
    surface = found.surface
    calibration = None
    if calibrate is not None:
        from mcsim.studies.maps.calibration import calibrate as fit

        calibration = fit(hmap, calibrate, surface=surface, progress=progress)
    adhesion = None
    if adhesion_w is not None:
        from mcsim.studies.maps.adhesioncalibration import calibrate_adhesion

        try:
            adhesion = calibrate_adhesion(hmap.levelled, (hmap.dx, hmap.dy), calibrate,
                                          calibration.apply(surface), w=adhesion_w,
                                          range_=adhesion_range, periodic=hmap.periodic,
                                          progress=progress)  # fmt: skip
        except MCSimError as err:
            raise type(err)(f"{path}: adhesion calibration: {err}") from None
    return IngestResult(
        source=path,
        format=_FORMAT_NAMES.get(path.suffix.lower(), "text matrix"),
        channel=hmap.channel,
        reader_notes=hmap.notes,
        surface=surface,
        edges=found.edges,
        counts=found.counts,
        map_edges=found.map_edges,
        map_counts=found.map_counts,
        density=False,
        heights_from=(
            "direct-route summit heights"
            if heights == "summits"
            else "all heights of the levelled map"
        ),
        route=route,
        level=hmap.level,
        shape=hmap.shape,
        dx=hmap.dx,
        dy=hmap.dy,
        n_nan=found.topography.n_nan,
        map_heights=HeightSummary.of(hmap.levelled),
        summit_heights=HeightSummary.of(found.peaks),
        topography=found.topography,
        warnings=found.warnings,
        periodic=hmap.periodic,
        periodic_reason=hmap.periodic_reason,
        calibration=calibration,
        adhesion_calibration=adhesion,
        facing=hmap.facing,
        height_map=hmap,
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

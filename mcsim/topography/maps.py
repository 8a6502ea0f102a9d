"""A height map read once: checked, faced by a counter-surface, its periodicity decided, levelled.

:func:`read_map` is the one place a measured map is read for an analysis: every consumer
(summit statistics and the GW surface, :mod:`mcsim.topography.mapsurface`; the exact contact,
its calibration and the adhesive cycle in :mod:`mcsim.studies`) takes the
:class:`~mcsim.topography.readers.base.HeightMap` it returns, so a command that needs the map
several times reads its file once.

Periodic maps
-------------
Unless told, a map is periodic when its opposite edges join
(:func:`mcsim.topography.summits.periodic_edges`, checked on the map as read); a periodic map
is levelled by its mean only unless another levelling is asked for (a fitted plane would
remove a random tilt the map does not have).
"""

from __future__ import annotations

import dataclasses
import math
import os
import re
from pathlib import Path

import numpy as np

from mcsim.model.errors import MCSimError, ParameterError
from mcsim.topography.readers import HeightMap, ReaderError, read_height_map
from mcsim.topography.readers import histogram as _histogram_format
from mcsim.topography.readers.base import FacingMap
from mcsim.topography.summits import facing_gap, flipped, height_correlation, periodic_edges
from mcsim.topography.summits import level as level_heights

#: Levelling choices: name → degree of the subtracted polynomial (``none``: the mean only).
LEVELS = {"none": 0, "plane": 1, **{f"poly{n}": n for n in range(2, 6)}}
#: Pixel sizes a map may have, m: from 1 pm (below an atom's spacing) to 1 m (above any
#: profilometer's field). Outside them the summit statistics' powers of heights and
#: slopes (curvatures ~ z/dx², moments ~ (z/dx²)²) overflow or underflow double precision.
PIXEL_SIZE_RANGE = (1e-12, 1.0)
#: Largest |height| of a map, m (1 m): a larger one is a unit mistake, and its squares
#: overflow the summit statistics.
MAX_HEIGHT = 1.0
#: Peak memory of the analysis per map pixel, bytes (measured: float64 copies, FFT, masks).
BYTES_PER_PIXEL = 96
_SPLIT = re.compile(r"[,;\s]+")
_HISTOGRAM_OR_MATRIX = tuple(set(_histogram_format.EXTENSIONS) - {".hist", ".tsv"})


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


def check_level(level: str | None) -> None:
    """Refuse a levelling that is not a key of :data:`LEVELS` (None: the default)."""
    if level is not None and level not in LEVELS:
        raise ParameterError(f"`level` must be one of {', '.join(LEVELS)}, got {level!r}")


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


def check_memory(path: Path | str, shape: tuple[int, int]) -> None:
    """Refuse a map whose analysis needs more memory than is available, naming what fits."""
    need, have = shape[0] * shape[1] * BYTES_PER_PIXEL, available_memory()
    if need > have:
        side = math.isqrt(have // BYTES_PER_PIXEL)
        raise ParameterError(
            f"{path}: a {shape[1]} x {shape[0]} map needs about {need / 1e9:.3g} GB to analyse, "
            f"{have / 1e9:.3g} GB are available: crop or downsample it to at most about "
            f"{side} x {side} pixels"
        )


def read_map(
    path: str | Path,
    *,
    unit: str | None = None,
    pixel_size: float | tuple[float, float] | None = None,
    channel: str | None = None,
    counter: str | Path | None = None,
    level: str | None = None,
    periodic: bool | None = None,
) -> HeightMap:
    """The height map of ``path``, read once and prepared for every analysis.

    Parameters
    ----------
    path : path-like
        Height map, any format of :func:`~mcsim.topography.readers.read_height_map`.
    unit : str, optional
        Height unit for files that store none (e.g. ``"nm"``).
    pixel_size : float or (float, float), optional
        Pixel size, m, for maps that store none.
    channel : str, optional
        Channel of a multi-channel map.
    counter : path-like, optional
        A counter-surface's height map, measured face up, of the same size and pixel size
        (read with the same ``unit``, ``pixel_size`` and ``channel``, :func:`read_counter_map`):
        the map returned is the gap's topography, map − turned-over counter
        (:func:`~mcsim.topography.summits.facing_gap`), and its ``facing`` the correlation of
        the two levelled maps.
    level : str, optional
        A key of :data:`LEVELS`; default :func:`default_level`.
    periodic : bool, optional
        Analyse the map as periodic or not; None: periodic when its opposite edges join.

    Returns
    -------
    HeightMap
        Heights as read (the gap's with a counter-surface), m, with its ``level``,
        ``periodic``, ``periodic_reason``, ``levelled`` heights and ``facing``.

    Raises
    ------
    MCSimError
        A file that does not read, a map out of range or too large for the available memory
        (:func:`check_memory`), naming the file.
    """
    check_level(level)
    path = Path(path)
    hmap = read_checked(path, unit=unit, pixel_size=pixel_size, channel=channel)
    alone, counter_map = hmap.heights, None
    if counter is not None:
        counter_map = read_counter_map(path, counter, hmap, unit=unit, pixel_size=pixel_size,
                                       channel=channel)  # fmt: skip
        hmap = dataclasses.replace(hmap, heights=facing_gap(alone, counter_map.heights))
    check_memory(path, hmap.heights.shape)
    periodic, reason = decide_periodic(hmap.heights, periodic)
    level = default_level(periodic) if level is None else level
    facing = None
    if counter_map is not None:
        measured = height_correlation(alone, flipped(counter_map.heights), LEVELS[level])
        facing = FacingMap(Path(counter), *measured)
    return dataclasses.replace(hmap, level=level, periodic=periodic, periodic_reason=reason,
                               levelled=level_heights(hmap.heights, LEVELS[level]),
                               facing=facing)  # fmt: skip


def as_map(source: HeightMap | str | Path, what: str, **read) -> HeightMap:
    """A prepared map: ``source`` itself, or the map of that file read by :func:`read_map`.

    Parameters
    ----------
    source : HeightMap or path-like
        A map :func:`read_map` returned, or a height map file.
    what : str
        What the map is for, in the message refusing a text histogram
        (``"a height histogram has no map to {what}"``).
    **read
        Options of :func:`read_map` (``unit``, ``pixel_size``, ``channel``, ``counter``,
        ``level``, ``periodic``): for a file only; a map was read with its own.

    Raises
    ------
    ParameterError
        A map as a reader returns it (not prepared), read options given with a map, or a text
        histogram.
    """
    given = sorted(k for k, v in read.items() if v is not None)
    if isinstance(source, HeightMap):
        if source.levelled is None:
            raise ParameterError(f"{source.source}: a map as a reader returns it: read it with "
                                 "mcsim.topography.maps.read_map (levelled, its periodicity "
                                 "decided)")  # fmt: skip
        if given:
            raise ParameterError(f"{', '.join(given)}: {source.source} is read already: give "
                                 "them to mcsim.topography.maps.read_map")  # fmt: skip
        return source
    if is_histogram_file(Path(source)):
        raise ParameterError(
            f"{source}: a height histogram has no map to {what}: give a height map"
        )
    return read_map(source, **read)

"""Any format the optional ``SurfaceTopography`` package reads (the ``topography`` extra).

SurfaceTopography (ContactEngineering) reads some forty instrument formats (Bruker/DI
``.spm``, JPK ``.jpk``, Zygo, Keyence, x3p, ...), detecting the format from the file's
contents. :func:`mcsim.topography.readers.read_height_map` hands it the files whose extension no
built-in reader handles.

Conventions, as checked against mcsim's own readers on real files (tests/test_surfacetopography.py):

* ``Topography.heights()`` is indexed ``[x, y]``; it is transposed here to mcsim's
  ``[row = y, column = x]``.
* SurfaceTopography orients every format like Gwyddion's display (``imshow(heights().T)``
  shows the image as Gwyddion does): row 0 is the top row of the displayed image. For
  ``.gwy`` this is mcsim's own layout; for Igor ``.ibw`` it is the up-down mirror of
  :mod:`mcsim.topography.readers.ibw`, which keeps Igor's storage order. Summit statistics do not
  depend on it.
* Heights and physical sizes share one unit (``Topography.unit``), converted here with
  mcsim's unit table; masked (undefined) pixels become NaN.
"""

from __future__ import annotations

import importlib.util
import logging
import math
import warnings
from pathlib import Path

import numpy as np

from mcsim.topography.readers.base import (
    MAX_PIXELS,
    HeightMap,
    ReaderError,
    check_heights,
    length_factor,
    pixel_sizes,
)

#: What to install for this reader, as said in error messages.
INSTALL_HINT = "pip install 'mcsim[topography]'"

log = logging.getLogger(__name__)


def available() -> bool:
    """Whether SurfaceTopography is installed (found without importing it)."""
    return importlib.util.find_spec("SurfaceTopography") is not None


def _choose(path: Path, channels: list, channel: str | None):
    names = ", ".join(repr(c.name) for c in channels)
    if channel is not None:
        for info in channels:
            if info.name == channel:
                return info
        raise ReaderError(f"{path}: no channel {channel!r} (channels: {names})")
    heights = [c for c in channels if c.is_height_channel]
    named = [c for c in heights if "height" in c.name.lower() or "topo" in c.name.lower()]
    if not heights:
        raise ReaderError(f"{path}: no height channel found (channels: {names}); choose one")
    return (named or heights)[0]


def read(
    path: Path | str,
    channel: str | None = None,
    unit: str | None = None,
    pixel_size: float | tuple[float, float] | None = None,
) -> HeightMap:
    """Read a height channel with SurfaceTopography.

    Parameters
    ----------
    path : path-like
        The file, in any format SurfaceTopography detects.
    channel : str, optional
        Channel name; by default the first height channel whose name contains "height"
        or "topo" (case-insensitive), else the first height channel.
    unit : str, optional
        Height (and lateral) unit, only for files that store none, e.g. ``"nm"``.
    pixel_size : float or (float, float), optional
        Pixel size (dx, dy), m, only for files that store no physical size.

    Returns
    -------
    HeightMap
        Heights in m, rows along y, columns along x.

    Raises
    ------
    ReaderError
        SurfaceTopography is missing or cannot read the file, the channel is a line
        scan, a unit or pixel size is missing, or given where the file stores one.
    """
    path = Path(path)
    try:
        import SurfaceTopography
        from SurfaceTopography.Exceptions import CannotDetectFileFormat
    except ImportError:
        raise ReaderError(
            f"{path}: reading this format needs the 'SurfaceTopography' package ({INSTALL_HINT})"
        ) from None
    if not path.is_file():
        raise ReaderError(f"{path}: no such file")
    caught = warnings.catch_warnings(record=True)
    seen = caught.__enter__()  # its readers' own warnings, while probing formats and reading
    warnings.simplefilter("always")
    try:
        reader = SurfaceTopography.open_topography(str(path))
        info = _choose(path, reader.channels, channel)
        if info.dim != 2 or not info.is_uniform:
            raise ReaderError(
                f"{path}: channel {info.name!r} is a line scan or non-uniform "
                f"({info.dim}-D, {info.nb_grid_pts} points), not a height map on a grid"
            )
        if math.prod(info.nb_grid_pts) > MAX_PIXELS:
            raise ReaderError(
                f"{path}: the file declares {' × '.join(map(str, info.nb_grid_pts))} points, "
                f"more than the limit of {MAX_PIXELS}"
            )
        for given, stored, option in (
            (unit, info.unit, "unit"),
            (pixel_size, info.physical_sizes, "pixel-size"),
        ):
            if given is not None and stored is not None:
                raise ReaderError(f"{path}: the file stores its {option}; do not pass --{option}")
        # physical sizes missing from the file: a placeholder for SurfaceTopography, which
        # refuses to build a topography without one; dx, dy then come from `pixel_size`
        placeholder = tuple(map(float, info.nb_grid_pts)) if info.physical_sizes is None else None
        topography = info.topography(physical_sizes=placeholder)
        raw = topography.heights()
        z_unit = topography.unit or unit
    except ReaderError:
        raise
    except CannotDetectFileFormat:
        raise ReaderError(
            f"{path}: unknown file type {path.suffix.lower() or '(no extension)'!r} "
            "(nor a format SurfaceTopography recognises: damaged or unsupported)"
        ) from None
    except Exception as err:  # readers raise ValueError, KeyError, struct.error, MemoryError...
        first = str(err).strip().splitlines()[0] if str(err).strip() else ""
        raise ReaderError(
            f"{path}: SurfaceTopography cannot read it ({type(err).__name__}"
            f"{': ' + first if first else ''})"
        ) from None
    finally:
        caught.__exit__(None, None, None)
    if seen:  # read all the same: say so once, in words, instead of leaking them
        first = " ".join(str(seen[0].message).split())[:200]
        log.info("%s: SurfaceTopography warned %d time(s) while reading it (first: %s: %s)",
                 path, len(seen), seen[0].category.__name__, first)  # fmt: skip
    if not z_unit:
        raise ReaderError(f"{path}: missing height unit: pass --unit")
    factor = length_factor(z_unit, path, f"channel {info.name!r} unit")
    # heights() is indexed [x, y]: transpose to rows along y
    z = check_heights(path, np.ma.filled(np.ma.asarray(raw, dtype=float), np.nan).T) * factor
    if placeholder is None:
        nx, ny = info.nb_grid_pts
        dx, dy = (float(s) * factor / n for s, n in zip(topography.physical_sizes, (nx, ny)))
        origin = "pixel size from the file"
    else:
        dx, dy = pixel_sizes(path, pixel_size)
        origin = "pixel size from the caller"
    return HeightMap(
        z,
        dx,
        dy,
        str(path),
        channel=info.name,
        notes=(
            f"read by SurfaceTopography ({type(reader).__name__}), channel {info.name!r}",
            f"unit {z_unit!r} ({'file' if topography.unit else 'caller'}); {origin}",
        ),
    )

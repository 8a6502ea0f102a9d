"""File readers: measured height maps and height histograms, one module per format family.

:func:`read_height_map` and :func:`read_histogram` pick the reader from the file's
extension and check its magic bytes before parsing. Every reader returns SI values
(:class:`~mcsim.topography.readers.base.HeightMap`, :class:`~mcsim.topography.readers.histogram.Histogram`)
and raises :class:`ReaderError` naming the file and the problem. Readers of binary
instrument formats import their optional packages (``gwyfile``, ``igor2``: the
``afm`` extra) only when used.
"""

from __future__ import annotations

from pathlib import Path

from mcsim.topography.readers import ascii, gwy, histogram, ibw, nid, npy, surfacetopography
from mcsim.topography.readers.base import HeightMap, ReaderError
from mcsim.topography.readers.histogram import Histogram

__all__ = ["HeightMap", "Histogram", "ReaderError", "read_height_map", "read_histogram"]

_MAP_FORMATS = {
    **dict.fromkeys(ascii.EXTENSIONS, ("ASCII matrix", ascii.detect)),
    **dict.fromkeys(ascii.XYZ_EXTENSIONS, ("XYZ text", ascii.detect)),
    **dict.fromkeys(npy.EXTENSIONS, ("NumPy .npy", npy.detect)),
    **dict.fromkeys(gwy.EXTENSIONS, ("Gwyddion .gwy", gwy.detect)),
    **dict.fromkeys(ibw.EXTENSIONS, ("Igor binary wave", ibw.detect)),
    **dict.fromkeys(nid.EXTENSIONS, ("Nanosurf .nid", nid.detect)),
}


def _check_format(path: Path, formats: dict, hint: str = "") -> str:
    suffix = path.suffix.lower()
    if suffix not in formats:
        raise ReaderError(
            f"{path}: unknown file type {suffix or '(no extension)'!r} "
            f"(known: {', '.join(sorted(formats))}){hint}"
        )
    name, detect = formats[suffix]
    if not detect(path):
        raise ReaderError(f"{path}: does not look like a {name} file (wrong magic bytes)")
    return suffix


def read_height_map(
    path: str | Path,
    unit: str | None = None,
    pixel_size: float | tuple[float, float] | None = None,
    channel: str | None = None,
) -> HeightMap:
    """Read a height map, choosing the reader by extension and magic bytes.

    Parameters
    ----------
    path : path-like
        ``.txt .asc .dat .csv`` (matrix), ``.xyz``, ``.npy``, ``.gwy``, ``.ibw``, ``.nid``;
        any other extension goes to :mod:`~mcsim.topography.readers.surfacetopography` if installed.
    unit : str, optional
        Height unit for formats that do not store one (matrix, XYZ, .npy), e.g. ``"nm"``.
    pixel_size : float or (float, float), optional
        Pixel size, m, for formats that do not store one (matrix, .npy).
    channel : str, optional
        Channel of a multi-channel file (.gwy, .ibw, .nid, SurfaceTopography's
        formats); by default the file's height channel. Single-channel formats
        refuse it.

    Returns
    -------
    HeightMap
        Heights in m, rows along y, columns along x.
    """
    path = Path(path)
    if path.suffix.lower() not in _MAP_FORMATS and surfacetopography.available():
        return surfacetopography.read(path, unit=unit, pixel_size=pixel_size, channel=channel)
    hint = f"; for other formats: {surfacetopography.INSTALL_HINT}"
    suffix = _check_format(path, _MAP_FORMATS, hint)
    if channel is not None and suffix not in (*gwy.EXTENSIONS, *ibw.EXTENSIONS, *nid.EXTENSIONS):
        raise ReaderError(f"{path}: a {suffix} file holds one channel: --channel does not apply")
    if suffix in ascii.EXTENSIONS:
        return ascii.read(path, unit=unit, pixel_size=pixel_size)
    if suffix in ascii.XYZ_EXTENSIONS:
        return ascii.read_xyz(path, unit=unit)
    if suffix in npy.EXTENSIONS:
        return npy.read(path, unit=unit, pixel_size=pixel_size)
    if suffix in gwy.EXTENSIONS:
        return gwy.read(path, channel=channel)
    if suffix in ibw.EXTENSIONS:
        return ibw.read(path, channel=channel, unit=unit)
    return nid.read(path, channel=channel)


def read_histogram(path: str | Path, unit: str | None = None) -> Histogram:
    """Read a text histogram of heights (see :mod:`mcsim.topography.readers.histogram`).

    Parameters
    ----------
    path : path-like
        ``.csv .tsv .txt .dat .hist``.
    unit : str, optional
        Height unit if the header names none (or to override it).
    """
    path = Path(path)
    _check_format(path, dict.fromkeys(histogram.EXTENSIONS, ("text histogram", histogram.detect)))
    return histogram.read(path, unit=unit)

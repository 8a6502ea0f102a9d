"""Plain-text height maps: a matrix of heights, or XYZ triples on a regular grid.

* **Matrix** (``.txt``, ``.asc``, ``.dat``, ``.csv``): one image row per line,
  separated by whitespace, commas or semicolons; row 0 is the first line. Gwyddion's
  ASCII export header is understood: ``# Width: 5.000 µm``, ``# Height: 5.000 µm``
  (physical size, giving the pixel size) and ``# Value units: m``. Without it the
  caller gives ``unit`` and ``pixel_size`` (the caller's values win when both exist).
* **XYZ** (``.xyz``): three columns x, y, z, all in the caller's ``unit`` (the format
  has none); rows of the map are the distinct y in increasing order, columns the
  distinct x.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from mcsim.topography.readers.base import (
    HeightMap,
    ReaderError,
    check_heights,
    head,
    length_factor,
    pixel_sizes,
)

EXTENSIONS = (".txt", ".asc", ".dat", ".csv")
XYZ_EXTENSIONS = (".xyz",)
_SPLIT = re.compile(r"[,;\s]+")
_SIZE = re.compile(r"^#\s*(Width|Height)\s*:\s*([-+0-9.eE]++)\s*+(\S+)\s*$")  # possessive: linear
_UNITS = re.compile(r"^#\s*Value units\s*:\s*(\S+)\s*$")


def detect(path: Path) -> bool:
    """A text file: no NUL byte in its first 4 kB."""
    return b"\x00" not in head(path, 4096)


def _rows(path: Path) -> tuple[list[str], list[list[float]]]:
    comments, rows = [], []
    text = path.read_bytes().decode("utf-8", errors="replace")
    for number, line in enumerate(text.splitlines(), start=1):
        line = line.strip()
        if not line:
            continue
        if line.startswith("#"):
            comments.append(line)
            continue
        try:
            rows.append([float(c) for c in _SPLIT.split(line) if c])
        except ValueError:
            raise ReaderError(f"{path}: line {number}: non-numeric cell in {line[:40]!r}") from None
    if not rows:
        raise ReaderError(f"{path}: no data (empty file or comments only)")
    return comments, rows


def read(
    path: Path | str, unit: str | None = None, pixel_size: float | tuple[float, float] | None = None
) -> HeightMap:
    """Read a text matrix of heights (module docstring).

    Parameters
    ----------
    path : path-like
        The file.
    unit : str, optional
        Height unit; needed unless the header has ``# Value units``.
    pixel_size : float or (float, float), optional
        Pixel size, m, or (dx, dy); needed unless the header has Width and Height.
    """
    path = Path(path)
    head(path)
    comments, rows = _rows(path)
    widths = {len(r) for r in rows}
    if len(widths) != 1:
        raise ReaderError(f"{path}: rows have different lengths ({sorted(widths)})")
    z = check_heights(path, np.array(rows))
    sizes, notes = {}, []
    header_unit = None
    for line in comments:
        if m := _SIZE.match(line):
            try:
                value = float(m.group(2))
            except ValueError:
                raise ReaderError(f"{path}: cannot read {line[:60]!r}: not a number") from None
            sizes[m.group(1)] = value * length_factor(m.group(3), path, m.group(1))
        elif m := _UNITS.match(line):
            header_unit = m.group(1)
    chosen = unit or header_unit
    if chosen is None:
        raise ReaderError(f"{path}: missing height unit: pass --unit")
    notes.append(f"height unit {chosen!r} ({'caller' if unit else 'header'})")
    if pixel_size is None and len(sizes) == 2:
        dx, dy = sizes["Width"] / z.shape[1], sizes["Height"] / z.shape[0]
        notes.append("pixel size from the header's Width and Height")
    else:
        dx, dy = pixel_sizes(path, pixel_size)
    return HeightMap(
        z * length_factor(chosen, path, "height unit"), dx, dy, str(path), notes=tuple(notes)
    )


def read_xyz(path: Path | str, unit: str | None = None) -> HeightMap:
    """Read x, y, z triples on a regular grid (any order) as a height map.

    Parameters
    ----------
    path : path-like
        The file.
    unit : str
        Unit of all three columns, e.g. ``"m"`` or ``"nm"``; required.
    """
    path = Path(path)
    head(path)
    if unit is None:
        raise ReaderError(f"{path}: missing unit of the x, y, z columns: pass --unit")
    _, rows = _rows(path)
    if {len(r) for r in rows} != {3}:
        raise ReaderError(f"{path}: an XYZ file needs exactly 3 columns (x, y, z) on every line")
    x, y, z = np.array(rows).T * length_factor(unit, path, "unit")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        raise ReaderError(f"{path}: x and y must be finite")
    xs, ix = np.unique(x, return_inverse=True)
    ys, iy = np.unique(y, return_inverse=True)
    if xs.size * ys.size != x.size or xs.size < 3 or ys.size < 3:
        raise ReaderError(
            f"{path}: points are not a full regular grid ({xs.size} x values × {ys.size} y values "
            f"for {x.size} points)"
        )
    steps = [np.diff(v) for v in (xs, ys)]
    for name, step in zip("xy", steps):
        if np.ptp(step) > 1e-6 * step.mean():
            raise ReaderError(f"{path}: {name} values are not equally spaced")
    grid = np.full((ys.size, xs.size), np.nan)
    grid[iy, ix] = z
    filled = np.zeros(grid.shape, dtype=bool)
    filled[iy, ix] = True
    if np.count_nonzero(filled) != x.size:
        raise ReaderError(f"{path}: duplicate grid points")
    return HeightMap(
        check_heights(path, grid),
        float(steps[0].mean()),
        float(steps[1].mean()),
        str(path),
        notes=(f"unit {unit!r}", "rows: increasing y; columns: increasing x"),
    )

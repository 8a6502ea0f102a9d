"""NumPy ``.npy`` height maps: a 2-D array; unit and pixel size come from the caller."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .base import HeightMap, ReaderError, check_heights, head, length_factor, pixel_sizes

EXTENSIONS = (".npy",)
MAGIC = b"\x93NUMPY"


def detect(path: Path) -> bool:
    """The .npy magic string."""
    return head(path, len(MAGIC)) == MAGIC


def read(
    path: Path | str, unit: str | None = None, pixel_size: float | tuple[float, float] | None = None
) -> HeightMap:
    """Read a 2-D ``.npy`` array (rows along y, columns along x) as heights.

    Parameters
    ----------
    path : path-like
        The file (no pickles are loaded).
    unit : str
        Unit of the stored heights, e.g. ``"nm"``; required (the format has none).
    pixel_size : float or (float, float)
        Pixel size, m, or (dx, dy); required.
    """
    path = Path(path)
    if unit is None:
        raise ReaderError(f"{path}: missing height unit: pass --unit (.npy files carry none)")
    factor = length_factor(unit, path, "height unit")
    dx, dy = pixel_sizes(path, pixel_size)
    try:
        z = np.load(path, allow_pickle=False)
    except ValueError as err:
        raise ReaderError(f"{path}: not a readable .npy array ({err})") from None
    if not np.issubdtype(z.dtype, np.number):
        raise ReaderError(f"{path}: expected a numeric array, got dtype {z.dtype}")
    z = check_heights(path, z) * factor
    return HeightMap(z, dx, dy, str(path), notes=(f"height unit {unit!r} (caller)",))

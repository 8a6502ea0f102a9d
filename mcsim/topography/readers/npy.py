"""NumPy ``.npy`` height maps: a 2-D array; unit and pixel size come from the caller."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mcsim.topography.readers.base import (
    MAX_PIXELS,
    HeightMap,
    ReaderError,
    check_heights,
    head,
    length_factor,
    pixel_sizes,
)

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
    z = check_heights(path, _load(path)) * factor
    return HeightMap(z, dx, dy, str(path), notes=(f"height unit {unit!r} (caller)",))


def _load(path: Path) -> np.ndarray:
    """The array, after checking its header against the cap and the file's size."""
    head(path)
    size = path.stat().st_size
    with path.open("rb") as f:
        try:
            version = np.lib.format.read_magic(f)
            if version == (1, 0):
                shape, fortran, dtype = np.lib.format.read_array_header_1_0(f)
            elif version == (2, 0):
                shape, fortran, dtype = np.lib.format.read_array_header_2_0(f)
            else:
                raise ValueError(f"unsupported format version {version}")
        except Exception as err:  # numpy's header parser raises ValueError, TokenError, ...
            message = " ".join(str(err).split())
            raise ReaderError(f"{path}: not a readable .npy array ({message})") from None
        if dtype.hasobject or not np.issubdtype(dtype, np.number):
            raise ReaderError(f"{path}: expected a numeric array, got dtype {dtype}")
        if len(shape) != 2 or min(shape) < 0:
            raise ReaderError(f"{path}: a height map needs a 2-D array, got shape {shape}")
        count = shape[0] * shape[1]
        if count > MAX_PIXELS:
            raise ReaderError(
                f"{path}: the header declares {shape[0]} × {shape[1]} pixels, more than the "
                f"limit of {MAX_PIXELS} (mcsim.topography.readers.base.MAX_PIXELS)"
            )
        if f.tell() + count * dtype.itemsize > size:
            raise ReaderError(
                f"{path}: file is truncated: the header declares {count * dtype.itemsize} bytes "
                f"of data, the file has {size - f.tell()}"
            )
        data = np.frombuffer(f.read(count * dtype.itemsize), dtype=dtype, count=count)
    return data.reshape(shape, order="F" if fortran else "C")

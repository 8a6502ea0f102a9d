"""Igor binary waves ``.ibw`` (e.g. Asylum Research AFM), via the ``igor2`` package.

Igor stores an image as ``w[x, y]`` (x fastest, column-major), with one layer per
channel in a 3-D wave whose layer labels name the channels. Pixel spacing is the
wave scaling ``sfA`` (SI, from the wave's dimension units) and heights are in the
wave's data unit. The array is transposed to the rows-along-y layout.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .base import HeightMap, ReaderError, check_heights, head, length_factor

EXTENSIONS = (".ibw",)
#: Igor binary-wave versions; the file starts with the version as a 16-bit integer.
VERSIONS = (1, 2, 3, 5)


def detect(path: Path) -> bool:
    """The first two bytes are a known version number, in either byte order."""
    start = head(path, 2)
    return len(start) == 2 and (
        int.from_bytes(start, "little") in VERSIONS or int.from_bytes(start, "big") in VERSIONS
    )


def _text(value) -> str:
    if isinstance(value, bytes):
        return value.split(b"\x00")[0].decode("latin-1")
    if isinstance(value, np.ndarray):
        return b"".join(value.ravel().tolist()).split(b"\x00")[0].decode("latin-1")
    return str(value)


def read(path: Path | str, channel: str | None = None, unit: str | None = None) -> HeightMap:
    """Read a height layer of an Igor binary wave.

    Parameters
    ----------
    path : path-like
        The file.
    channel : str, optional
        Layer label; by default the first label starting with "Height", else layer 0.
    unit : str, optional
        Height unit if the wave has none.
    """
    path = Path(path)
    try:
        from igor2 import binarywave
    except ImportError:
        raise ReaderError(
            f"{path}: reading .ibw files needs the 'igor2' package (pip install mcsim[afm])"
        ) from None
    try:
        wave = binarywave.load(str(path))["wave"]
    except Exception as err:  # igor2 raises struct.error/ValueError/KeyError
        raise ReaderError(f"{path}: not a readable Igor binary wave ({err})") from None
    data = np.asarray(wave["wData"], dtype=float)
    header = wave["wave_header"]
    if data.ndim == 2:
        data = data[:, :, None]
    if data.ndim != 3:
        raise ReaderError(f"{path}: expected an image wave (2-D or 3-D), got {data.ndim}-D")
    labels = [_text(v) for v in (wave.get("labels") or [[], [], []])[2]][1:]
    labels += [f"layer {k}" for k in range(len(labels), data.shape[2])]
    if channel is None:
        index = next((k for k, name in enumerate(labels) if name.lower().startswith("height")), 0)
    elif channel in labels:
        index = labels.index(channel)
    else:
        raise ReaderError(f"{path}: no channel {channel!r} (channels: {', '.join(labels)})")
    z_unit = unit or _text(wave.get("data_units") or header.get("dataUnits", b""))
    if not z_unit:
        raise ReaderError(f"{path}: missing height unit: pass --unit")
    z = check_heights(path, data[:, :, index].T) * length_factor(z_unit, path, "height unit")
    sfa = np.asarray(header["sfA"], dtype=float)
    dx, dy = float(sfa[0]), float(sfa[1])
    if not (dx > 0 and dy > 0):
        raise ReaderError(f"{path}: missing pixel size (wave scaling {dx}, {dy})")
    return HeightMap(
        z, dx, dy, str(path), channel=labels[index], notes=(f"height unit {z_unit!r}",)
    )

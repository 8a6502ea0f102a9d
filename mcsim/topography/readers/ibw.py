"""Igor binary waves ``.ibw`` (e.g. Asylum Research AFM), via the ``igor2`` package.

Igor stores an image as ``w[x, y]`` (x fastest, column-major), with one layer per
channel in a 3-D wave whose layer labels name the channels. Pixel spacing is the
wave scaling ``sfA`` (SI, from the wave's dimension units) and heights are in the
wave's data unit. The array is transposed to the rows-along-y layout.
"""

from __future__ import annotations

import math
import struct
from pathlib import Path

import numpy as np

from mcsim.topography.readers.base import (
    MAX_PIXELS,
    HeightMap,
    ReaderError,
    check_heights,
    head,
    length_factor,
)

EXTENSIONS = (".ibw",)
#: Igor binary-wave versions; the file starts with the version as a 16-bit integer.
VERSIONS = (1, 2, 3, 5)
#: Per version: the BinHeader's layout after the version (struct codes; the section
#: sizes are the ``l`` fields) and where WaveHeader5 keeps ``nDim`` (version 5 only).
_BIN_HEADERS = {1: "lh", 2: "lllh", 3: "llllh", 5: "hllll4l4llll"}
_NDIM_OFFSET = 64 + 68


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
    _check_declared_sizes(path)
    try:
        wave = binarywave.load(str(path))["wave"]
    except Exception as err:  # igor2 raises struct.error/ValueError/KeyError
        raise ReaderError(f"{path}: not a readable Igor binary wave ({err})") from None
    data = wave["wData"]
    if not (isinstance(data, np.ndarray) and np.issubdtype(data.dtype, np.number)):
        raise ReaderError(f"{path}: not a numeric wave")
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
        raise ReaderError(
            f"{path}: no channel {channel!r} (channels: {', '.join(map(repr, labels))})"
        )
    z_unit = unit or _text(wave.get("data_units") or header.get("dataUnits", b""))
    origin = "caller" if unit else "wave"
    if not z_unit and _is_asylum(wave) and labels[index].lower().startswith(_ASYLUM_LENGTHS):
        z_unit, origin = "m", "Asylum Research files store SI; the wave names none"
    if not z_unit:
        raise ReaderError(f"{path}: missing height unit: pass --unit")
    z = check_heights(path, data[:, :, index].T) * length_factor(z_unit, path, "height unit")
    xy_units = [_text(u) for u in header["dimUnits"][:2]]
    sfa = np.asarray(header["sfA"], dtype=float)
    dx, dy = (
        float(sfa[k]) * length_factor(xy_units[k] or "m", path, "lateral unit") for k in (0, 1)
    )
    if not (0 < dx < math.inf and 0 < dy < math.inf):
        raise ReaderError(f"{path}: missing pixel size (wave scaling {dx}, {dy})")
    return HeightMap(
        z,
        dx,
        dy,
        str(path),
        channel=labels[index],
        notes=(f"height unit {z_unit!r} ({origin})", "pixel size from the wave scaling sfA"),
    )


#: Asylum channel labels that hold lengths (heights, Z sensor, amplitude).
_ASYLUM_LENGTHS = ("height", "zsensor", "amplitude")


def _is_asylum(wave) -> bool:
    """Asylum Research's wave note starts with its scan parameters."""
    note = wave.get("note") or b""
    return isinstance(note, bytes) and note.startswith(b"ScanSize:")


def _check_declared_sizes(path: Path) -> None:
    """Refuse section sizes beyond the file and images beyond the cap, before igor2 allocates."""
    start = head(path, 64 + 320)
    order = "<" if int.from_bytes(start[:2], "little") in VERSIONS else ">"
    version = struct.unpack_from(f"{order}h", start)[0]
    layout = order + _BIN_HEADERS[version]
    if len(start) < 2 + struct.calcsize(layout):
        raise ReaderError(f"{path}: not a readable Igor binary wave ({len(start)} bytes)")
    fields = struct.unpack_from(layout, start, 2)
    sizes = fields[1:-2] if version == 5 else fields[:-1]  # v5: after the checksum
    file_size = path.stat().st_size
    if min(sizes) < 0 or sum(sizes) > file_size:
        raise ReaderError(
            f"{path}: not a readable Igor binary wave (truncated: the header declares "
            f"sections of {sum(sizes)} bytes, the file has {file_size})"
        )
    if version == 5 and len(start) >= _NDIM_OFFSET + 16:
        dims = [n for n in struct.unpack_from(f"{order}4l", start, _NDIM_OFFSET) if n > 0]
        if math.prod(dims[:2]) > MAX_PIXELS:
            raise ReaderError(
                f"{path}: the wave declares {' × '.join(map(str, dims))} points, more than "
                f"the limit of {MAX_PIXELS} pixels per image (mcsim.topography.readers.base.MAX_PIXELS)"
            )

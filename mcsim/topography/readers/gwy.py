"""Gwyddion ``.gwy`` files, parsed here with every size checked against the file.

Gwyddion stores each channel as a GwyDataField with its physical size (``xreal``,
``yreal``) and SI units, row 0 at the top of the image; both are used as stored.
The serialization (``GWYP``, then objects: a name, a byte size and typed components)
is the one documented in Gwyddion's user guide, "Gwyddion Native File Format". It is
read by :func:`_parse`, not by the ``gwyfile`` package, whose parser trusts array
counts: a corrupt string-array count made it loop for hours.
"""

from __future__ import annotations

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

EXTENSIONS = (".gwy",)
MAGIC = b"GWYP"


def detect(path: Path) -> bool:
    """Gwyddion's magic bytes ``GWYP``."""
    return head(path, len(MAGIC)) == MAGIC


def _unit(field, key: str) -> str:
    unit = field.get(key) if isinstance(field, dict) else None
    return str(unit.get("unitstr", "")) if isinstance(unit, dict) else ""


def read(path: Path | str, channel: str | None = None) -> HeightMap:
    """Read a height channel of a Gwyddion file.

    Parameters
    ----------
    path : path-like
        The file.
    channel : str, optional
        Channel title; by default the first whose title contains "height" or "topo"
        (case-insensitive), else the first channel with heights in metres.

    Raises
    ------
    ReaderError
        A corrupt file, no such channel, or a channel not in length units.
    """
    path = Path(path)
    head(path)
    try:
        container = _parse(path.read_bytes())
        fields = {
            str(value): container[key[: -len("/title")]]
            for key, value in container.items()
            if key.endswith("/data/title")
            and isinstance(container.get(key[: -len("/title")]), dict)
        }
    except (ValueError, struct.error) as err:
        raise ReaderError(f"{path}: not a readable Gwyddion file ({err})") from None
    if not fields:
        raise ReaderError(f"{path}: no data channel in the file")
    if channel is None:
        names = [t for t in fields if "height" in t.lower() or "topo" in t.lower()]
        names += [t for t in fields if _unit(fields[t], "si_unit_z") == "m"]
        if not names:
            raise ReaderError(
                f"{path}: no height channel found (channels: {', '.join(map(repr, fields))}); choose one"
            )
        channel = names[0]
    elif channel not in fields:
        raise ReaderError(
            f"{path}: no channel {channel!r} (channels: {', '.join(map(repr, fields))})"
        )
    field = fields[channel]
    z_factor = length_factor(_unit(field, "si_unit_z") or "?", path, f"channel {channel!r}")
    xy_factor = length_factor(_unit(field, "si_unit_xy") or "?", path, "lateral unit")
    try:
        rows, cols = int(field["yres"]), int(field["xres"])
        data = np.asarray(field["data"], dtype=float).reshape(rows, cols)
        xreal, yreal = float(field["xreal"]), float(field["yreal"])
    except (KeyError, TypeError, ValueError, OverflowError):  # e.g. xres stored as inf
        raise ReaderError(f"{path}: channel {channel!r} is not a complete data field") from None
    z = check_heights(path, data) * z_factor
    dx = xreal * xy_factor / z.shape[1]
    dy = yreal * xy_factor / z.shape[0]
    return HeightMap(
        z, dx, dy, str(path), channel=channel, notes=(f"Gwyddion channel {channel!r}",)
    )


#: Fixed-size component types: struct code per Gwyddion type letter (little-endian).
_SCALARS = {"b": "<?", "c": "<c", "i": "<i", "q": "<q", "d": "<d"}
_ARRAYS = {"C": "<u1", "I": "<i4", "Q": "<i8", "D": "<f8"}
_MAX_DEPTH = 32


def _parse(raw: bytes) -> dict:
    """The top-level object of a .gwy file as nested dicts; raises ValueError if corrupt."""
    if raw[:4] != MAGIC:
        raise ValueError("no GWYP magic")
    _, obj, _ = _object(raw, 4, len(raw), 0)
    return obj


def _string(raw: bytes, pos: int, end: int) -> tuple[str, int]:
    stop = raw.find(b"\0", pos, end)
    if stop < 0:
        raise ValueError(f"unterminated string at byte {pos}")
    return raw[pos:stop].decode("utf-8", errors="replace"), stop + 1


def _object(raw: bytes, pos: int, end: int, depth: int) -> tuple[str, dict, int]:
    if depth > _MAX_DEPTH:
        raise ValueError("objects nested too deeply")
    name, pos = _string(raw, pos, end)
    (size,) = struct.unpack_from("<I", raw, pos)
    pos += 4
    stop = pos + size
    if stop > end:
        raise ValueError(f"object {name!r} declares {size} bytes beyond its container")
    components = {}
    while pos < stop:
        key, pos = _string(raw, pos, stop)
        if pos >= stop:
            raise ValueError(f"component {key!r} has no type")
        code = chr(raw[pos])
        pos += 1
        if code in _SCALARS:
            (value,) = struct.unpack_from(_SCALARS[code], raw, pos)
            pos += struct.calcsize(_SCALARS[code])
        elif code == "s":
            value, pos = _string(raw, pos, stop)
        elif code == "o":
            _, value, pos = _object(raw, pos, stop, depth + 1)
        elif code in _ARRAYS or code in "SO":
            (count,) = struct.unpack_from("<I", raw, pos)
            pos += 4
            itemsize = np.dtype(_ARRAYS[code]).itemsize if code in _ARRAYS else 1
            if count * itemsize > stop - pos or count > MAX_PIXELS:
                raise ValueError(f"array {key!r} declares {count} items beyond its object")
            if code in _ARRAYS:
                value = np.frombuffer(raw, dtype=_ARRAYS[code], count=count, offset=pos)
                pos += count * itemsize
            else:
                value = []
                for _ in range(count):
                    if code == "S":
                        item, pos = _string(raw, pos, stop)
                    else:
                        _, item, pos = _object(raw, pos, stop, depth + 1)
                    value.append(item)
        else:
            raise ValueError(f"unknown component type {code!r}")
        if pos > stop:
            raise ValueError(f"component {key!r} runs beyond its object")
        components[key] = value
    return name, components, stop

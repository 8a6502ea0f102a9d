"""Gwyddion ``.gwy`` files, via the ``gwyfile`` package (optional extra ``afm``).

Gwyddion stores each channel as a GwyDataField with its physical size (``xreal``,
``yreal``) and SI units, row 0 at the top of the image; both are used as stored.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .base import HeightMap, ReaderError, check_heights, head, length_factor

EXTENSIONS = (".gwy",)
MAGIC = b"GWYP"


def detect(path: Path) -> bool:
    """Gwyddion's magic bytes ``GWYP``."""
    return head(path, len(MAGIC)) == MAGIC


def _unit(field, key: str) -> str:
    unit = field.get(key)
    return "" if unit is None else str(unit.unitstr)


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
        No ``gwyfile`` package, no such channel, or a channel not in length units.
    """
    path = Path(path)
    try:
        import gwyfile
    except ImportError:
        raise ReaderError(
            f"{path}: reading .gwy files needs the 'gwyfile' package (pip install mcsim[afm])"
        ) from None
    try:
        fields = gwyfile.util.get_datafields(gwyfile.load(str(path)))
    except Exception as err:  # gwyfile raises bare ValueError/KeyError/struct.error
        raise ReaderError(f"{path}: not a readable Gwyddion file ({err})") from None
    if not fields:
        raise ReaderError(f"{path}: no data channel in the file")
    if channel is None:
        names = [t for t in fields if "height" in t.lower() or "topo" in t.lower()]
        names += [t for t in fields if _unit(fields[t], "si_unit_z") == "m"]
        if not names:
            raise ReaderError(
                f"{path}: no height channel found (channels: {', '.join(fields)}); choose one"
            )
        channel = names[0]
    elif channel not in fields:
        raise ReaderError(f"{path}: no channel {channel!r} (channels: {', '.join(fields)})")
    field = fields[channel]
    z_factor = length_factor(_unit(field, "si_unit_z") or "?", path, f"channel {channel!r}")
    xy_factor = length_factor(_unit(field, "si_unit_xy") or "?", path, "lateral unit")
    z = check_heights(path, np.array(field.data, dtype=float)) * z_factor
    dx = field.xreal * xy_factor / z.shape[1]
    dy = field.yreal * xy_factor / z.shape[0]
    return HeightMap(
        z, dx, dy, str(path), channel=channel, notes=(f"Gwyddion channel {channel!r}",)
    )

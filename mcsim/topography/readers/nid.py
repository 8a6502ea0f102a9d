"""Nanosurf ``.nid`` files: an INI-like text header, ``#!``, then binary channels.

Parsed here without a vendor package. The ``[DataSet]`` section lists the channels
(``Gr<g>-Ch<c>=DataSet-<g>:<c>``); their blocks follow the ``#!`` marker in that
order, each ``Points × Lines`` integers of ``SaveBits`` bits (``SaveOrder=Intel``:
little-endian). A raw integer r maps to (r + 2^(b−1))/2^b · Dim2Range + Dim2Min
in ``Dim2Unit``; the pixel size is Dim0Range/Points (x) and Dim1Range/Lines (y).
This is the scaling of Nanosurf's own reader (NSFopen), checked against it on its
sample files. Lines are kept in the stored order; the header's scan direction is
recorded in the notes.
"""

from __future__ import annotations

import math
import re
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

EXTENSIONS = (".nid",)
MAGIC = b"[DataSet]"
_SECTION = re.compile(r"^\[(.+)\]$")
_CHANNEL = re.compile(r"Gr([0-9]+)-Ch([0-9]+)")


def detect(path: Path) -> bool:
    """The header starts with the ``[DataSet]`` section."""
    return head(path, len(MAGIC)) == MAGIC


def _header(text: str) -> dict[str, dict[str, str]]:
    sections: dict[str, dict[str, str]] = {}
    current: dict[str, str] = {}
    for line in text.splitlines():
        line = line.strip()
        match = _SECTION.match(line)
        if match:
            current = sections.setdefault(match.group(1), {})
        elif "=" in line:
            key, value = line.split("=", 1)
            current[key] = value.strip()
    return sections


def read(path: Path | str, channel: str | None = None, frame: str = "Scan forward") -> HeightMap:
    """Read one image channel of a Nanosurf .nid file.

    Parameters
    ----------
    path : path-like
        The file.
    channel : str, optional
        ``Dim2Name`` of the channel, or ``"Frame/Dim2Name"`` (e.g. ``"Scan
        backward/Z-Axis"``); by default ``"Z-Axis"`` or, in files without it,
        ``"Topography"``. Spectra and curves (one line, or an x axis in Hz) are
        refused: they are not height maps.
    frame : str
        ``Frame`` of the channel, ``"Scan forward"`` by default.
    """
    path = Path(path)
    head(path)
    raw = path.read_bytes()
    marker = raw.find(b"#!")
    if marker < 0:
        raise ReaderError(f"{path}: no '#!' data marker: not a complete .nid file")
    sections = _header(raw[:marker].decode("latin-1"))
    try:
        dataset = sections["DataSet"]
        groups = _count(dataset, "GroupCount", path)
        listed = sorted(
            (int(m[1]), int(m[2]), key) for key in dataset if (m := _CHANNEL.fullmatch(key))
        )
        names = [
            dataset[key]
            for g, c, key in listed
            if g < groups and c < _count(dataset, f"Gr{g}-Count", path)
        ]
        blocks = [sections[n] for n in names]
    except KeyError as err:
        raise ReaderError(f"{path}: incomplete .nid header (no {err})") from None
    sizes = []
    for b in blocks:
        pixels = _count(b, "Points", path) * _count(b, "Lines", path)
        if pixels > MAX_PIXELS:
            raise ReaderError(
                f"{path}: a channel declares {pixels} pixels, more than the limit of "
                f"{MAX_PIXELS} (mcsim.topography.readers.base.MAX_PIXELS)"
            )
        sizes.append(pixels * _count(b, "SaveBits", path) // 8)
    labels = [f"{b.get('Frame')}/{b.get('Dim2Name')}" for b in blocks]
    images = [label for label, b in zip(labels, blocks) if _is_image(b)]
    if channel is None:
        stored = {b.get("Dim2Name") for b in blocks if b.get("Frame") == frame}
        channel = "Z-Axis" if "Z-Axis" in stored else "Topography"
        if f"{frame}/{channel}" not in labels:
            raise ReaderError(
                f"{path}: no {frame}/Z-Axis or {frame}/Topography height channel; "
                + (f"images: {', '.join(map(repr, images))} (choose one with --channel)" if images
                   else f"the file holds no image, only spectra or curves ({', '.join(map(repr, labels))})")
            )  # fmt: skip
    if "/" in channel:
        frame, channel = channel.rsplit("/", 1)
    found = [k for k, label in enumerate(labels) if label == f"{frame}/{channel}"]
    if not found:
        raise ReaderError(
            f"{path}: no channel {frame}/{channel} (channels: {', '.join(map(repr, labels))})"
        )
    if not _is_image(blocks[found[0]]):
        b = blocks[found[0]]
        raise ReaderError(
            f"{path}: channel {frame}/{channel} is not a height image ({b.get('Lines')} line(s) "
            f"of {b.get('Points')} points, axes in {b.get('Dim0Unit', '?')!r} and {b.get('Dim1Unit', '?')!r}); "
            f"images: {', '.join(map(repr, images)) or 'none'}"
        )
    block = blocks[found[0]]
    if block.get("SaveMode", "Binary") != "Binary" or block.get("SaveOrder", "Intel") != "Intel":
        raise ReaderError(f"{path}: only binary little-endian (Intel) .nid data is supported")
    bits = int(block["SaveBits"])
    if bits not in (16, 32):
        raise ReaderError(f"{path}: unsupported SaveBits={bits}")
    start = marker + 2 + sum(sizes[: found[0]])
    if marker + 2 + sum(sizes) > len(raw):
        raise ReaderError(f"{path}: file is truncated ({len(raw)} bytes)")
    points, lines = int(block["Points"]), int(block["Lines"])
    counts = np.frombuffer(raw, dtype=f"<i{bits // 8}", count=points * lines, offset=start)
    q = 2.0**bits
    values = (counts.astype(float) + q / 2) / q * _real(block, "Dim2Range", path) + _real(
        block, "Dim2Min", path
    )
    z_factor = length_factor(block.get("Dim2Unit", "?"), path, f"channel {channel!r} unit")
    z = check_heights(path, values.reshape(lines, points) * z_factor)
    dx = (
        _real(block, "Dim0Range", path)
        * length_factor(block.get("Dim0Unit", "?"), path, "x unit")
        / points
    )
    dy = (
        _real(block, "Dim1Range", path)
        * length_factor(block.get("Dim1Unit", "?"), path, "y unit")
        / lines
    )
    direction = sections.get("DataSet-Info", {}).get("Scan direction", "unknown")
    return HeightMap(
        z, dx, dy, str(path), channel=f"{frame}/{channel}", notes=(f"scan direction {direction}",)
    )


def _is_image(block: dict[str, str]) -> bool:
    """A map: at least 3 lines, both axes lengths (spectra have 1 line or an x axis in Hz)."""
    try:
        if int(block.get("Lines", 0)) < 3:
            return False
        for key in ("Dim0Unit", "Dim1Unit"):
            length_factor(block.get(key, "?"), "", key)
    except (ValueError, ReaderError):
        return False
    return True


def _count(section: dict[str, str], key: str, path: Path) -> int:
    """A non-negative integer header value."""
    try:
        value = int(section[key])
    except KeyError:
        raise ReaderError(f"{path}: incomplete .nid header (no {key!r})") from None
    except ValueError:
        raise ReaderError(
            f"{path}: .nid header: {key}={section[key]!r} is not an integer"
        ) from None
    if value < 0:
        raise ReaderError(f"{path}: .nid header: {key}={value} is negative")
    return value


def _real(section: dict[str, str], key: str, path: Path) -> float:
    """A finite real header value."""
    try:
        value = float(section[key])
    except KeyError:
        raise ReaderError(f"{path}: incomplete .nid header (no {key!r})") from None
    except ValueError:
        raise ReaderError(f"{path}: .nid header: {key}={section[key]!r} is not a number") from None
    if not math.isfinite(value):
        raise ReaderError(f"{path}: .nid header: {key}={value!r} is not finite")
    return value

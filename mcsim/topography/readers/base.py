"""What every reader shares: the :class:`HeightMap` it returns, its error, unit helpers.

Convention for every height map: ``heights[i, j]`` is row ``i`` (along y, pitch
``dy``) and column ``j`` (along x, pitch ``dx``), in the order the file stores its
rows: row 0 is the file's first row (Gwyddion, ASCII, .npy: the top row of the
image as displayed by the instrument software; Igor, whose waves are stored
x-fastest as ``w[x, y]``, is transposed to this layout). No reader flips rows, so
summit statistics (which do not depend on orientation) and round trips are exact.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mcsim.model.errors import MCSimError
from mcsim.model.units import parse_quantity, unit_factor

#: Largest map a reader accepts, in pixels (16384 × 16384, 2 GiB as float64): a header that
#: declares more is refused before anything is allocated.
MAX_PIXELS = 2**28


class ReaderError(MCSimError):
    """A file cannot be read as a height map or a histogram; the message names the file.

    The message is kept on one short line: line breaks and other control characters (from
    a file name or from text read out of the file) are shown escaped, e.g. ``\\r``, and a
    message longer than :data:`MAX_MESSAGE` (2000) characters (a parser quoting binary data) is
    cut, saying how much.
    """

    def __init__(self, message: str) -> None:
        text = _CONTROL.sub(lambda m: repr(m.group())[1:-1], str(message))
        if len(text) > MAX_MESSAGE:
            text = f"{text[:MAX_MESSAGE]}... ({len(text) - MAX_MESSAGE} characters cut)"
        super().__init__(text)


#: Longest reader message, in characters: a path and a reason fit (a channel list of a few
#: dozen names included), a quoted binary file does not.
MAX_MESSAGE = 2000
_CONTROL = re.compile("[\x00-\x1f\x7f-\x9f\u2028\u2029]")


@dataclass(frozen=True)
class FacingMap:
    """A counter-surface's map facing a map (``--counter-surface``): turned over (columns
    reversed, heights negated) and subtracted, so that the map analysed is the gap's
    topography.

    Attributes
    ----------
    source : Path
        The counter-surface's map file.
    correlation : float
        ρ of the two levelled maps' heights in the facing frame
        (:func:`mcsim.topography.summits.height_correlation`).
    rms, counter_rms : float
        Rms of the levelled map and of the turned-over counter map over their common
        pixels, m: the gap's rq is √(rms² + counter_rms² − 2ρ rms counter_rms).
    """

    source: Path
    correlation: float
    rms: float
    counter_rms: float

    def line(self) -> str:
        """One line, for the terminal and the surface file."""
        gap = (self.rms**2 + self.counter_rms**2
               - 2 * self.correlation * self.rms * self.counter_rms) ** 0.5  # fmt: skip
        return (f"{self.source} turned over to face the map (columns reversed, heights negated); "
                f"the map analysed is their gap, map - turned-over counter; correlation of the "
                f"levelled heights rho = {self.correlation:.4g}, rms {self.rms * 1e9:.4g} nm and "
                f"{self.counter_rms * 1e9:.4g} nm: the gap's rms sqrt(rms1^2 + rms2^2 - 2 rho "
                f"rms1 rms2) = {gap * 1e9:.4g} nm")  # fmt: skip


@dataclass(frozen=True)
class HeightMap:
    """A measured height map in SI units: as a reader returns it, or read once and prepared
    for every analysis (:func:`mcsim.topography.maps.read_map`: with a counter-surface the
    gap's, its periodicity decided and levelled).

    Attributes
    ----------
    heights : ndarray
        Heights, m, shape (rows along y, columns along x); NaN for missing pixels. As read
        (the gap's with a counter-surface), not levelled.
    dx, dy : float
        Pixel size along x (between columns) and y (between rows), m.
    source : str
        File the map was read from.
    channel : str
        Channel (data field) name inside the file.
    notes : tuple of str
        What the reader assumed or converted (units, scaling, chosen channel).
    level : str or None
        The levelling of :attr:`levelled` (a key of :data:`mcsim.topography.maps.LEVELS`);
        None as a reader returns it.
    periodic : bool or None
        The map is analysed as periodic (summit neighbours and solves wrap); None as a
        reader returns it.
    periodic_reason : str
        Why (asked, or the edge steps of :func:`mcsim.topography.summits.periodic_edges`).
    levelled : ndarray or None
        :attr:`heights` levelled by :attr:`level`, m.
    facing : FacingMap or None
        The counter-surface facing the map, if any.
    """

    heights: np.ndarray
    dx: float
    dy: float
    source: str
    channel: str = ""
    notes: tuple[str, ...] = field(default=())
    level: str | None = None
    periodic: bool | None = None
    periodic_reason: str = ""
    levelled: np.ndarray | None = field(default=None, repr=False)
    facing: FacingMap | None = None

    def __post_init__(self):
        for name in ("dx", "dy"):
            value = getattr(self, name)
            if not (isinstance(value, float) and math.isfinite(value) and value > 0):
                raise ReaderError(
                    f"{self.source}: pixel size {name} = {value!r} m: must be positive and finite"
                )

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, columns)."""
        return self.heights.shape

    @property
    def size(self) -> tuple[float, float]:
        """Physical size (x, y) = (columns·dx, rows·dy), m."""
        return self.heights.shape[1] * self.dx, self.heights.shape[0] * self.dy


def length_factor(unit: str, path: Path | str, what: str) -> float:
    """SI factor of a length unit read from a file or given by the caller."""
    try:
        return unit_factor(unit, "length")
    except MCSimError as err:
        raise ReaderError(f"{path}: {what}: {err}") from None


def pixel_sizes(
    path: Path | str, pixel_size: float | str | tuple[float | str, float | str] | None
) -> tuple[float, float]:
    """(dx, dy) in m from the caller's ``pixel_size`` (m, or a length with its unit such as
    ``"10 nm"``; one for both axes or a pair); raises if it is missing or bad."""
    if pixel_size is None:
        raise ReaderError(f"{path}: missing pixel size: pass --pixel-size")
    pair = (
        (pixel_size, pixel_size)
        if isinstance(pixel_size, str) or np.ndim(pixel_size) == 0
        else pixel_size
    )
    if len(pair) != 2:
        raise ReaderError(f"{path}: pixel size {pixel_size!r}: give one length or a pair (dx, dy)")
    sizes = []
    for value in pair:
        if isinstance(value, np.generic | np.ndarray) and np.ndim(value) == 0:
            value = value.item()  # a NumPy scalar: its Python number
        try:
            size = parse_quantity(value, "length", "pixel size")
        except MCSimError as err:
            raise ReaderError(f"{path}: {err}") from None
        if not (math.isfinite(size) and size > 0):
            raise ReaderError(f"{path}: pixel size must be positive and finite, got {size!r} m")
        sizes.append(size)
    return sizes[0], sizes[1]


def check_heights(path: Path | str, z: np.ndarray) -> np.ndarray:
    """A 2-D float array with at least 3×3 pixels and one finite value; ±inf become NaN."""
    if np.iscomplexobj(z):
        raise ReaderError(f"{path}: heights are complex numbers")
    try:
        z = np.asarray(z, dtype=float)
    except (TypeError, ValueError):
        raise ReaderError(f"{path}: heights are not numbers") from None
    if z.ndim != 2 or min(z.shape) < 3:
        raise ReaderError(f"{path}: a height map needs at least 3×3 pixels, got shape {z.shape}")
    if z.size > MAX_PIXELS:
        raise ReaderError(f"{path}: {z.size} pixels, more than the limit of {MAX_PIXELS}")
    finite = np.isfinite(z)
    if not np.any(finite):
        raise ReaderError(f"{path}: the height map has no finite value")
    return np.where(finite, z, np.nan)


def head(path: Path, n: int = 64) -> bytes:
    """The first ``n`` bytes of a file, for magic-byte checks."""
    try:
        with path.open("rb") as f:
            return f.read(n)
    except FileNotFoundError:
        raise ReaderError(f"{path}: no such file") from None
    except OSError as err:
        raise ReaderError(f"{path}: cannot read ({err.strerror})") from None
    except ValueError:  # a NUL byte in the name
        raise ReaderError(f"{path!r}: not a valid file name") from None

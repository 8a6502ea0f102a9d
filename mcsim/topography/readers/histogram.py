"""Text histograms of heights: CSV, TSV or whitespace columns, optional header.

Accepted layouts (one bin per line):

* two columns ``centre, weight`` (edges halfway between centres, the outer ones half
  a spacing out), e.g. Gwyddion's exported height distribution;
* three columns ``left, right, weight`` (contiguous bins).

Lines starting with ``#`` and blank lines are skipped; text lines before the first
numeric line form the header. The height unit is the first bracketed unit of the last
header line (``height (nm)``, ``z [nm]``, ``# z [µm]  ρ [1/µm]``), or the caller's
``unit`` (which wins when both are given). The weights are densities if the header
says so (``density``, ``pdf``, ``ρ`` or a unit ``1/...``), counts otherwise; for
equal bins the two read the same.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mcsim.model.errors import MCSimError
from mcsim.topography.empirical import Empirical
from mcsim.topography.readers.base import ReaderError, head, length_factor

EXTENSIONS = (".csv", ".tsv", ".txt", ".dat", ".hist")

_SPLIT = re.compile(r"[,;\t ]+")
_UNIT = re.compile(r"[\[(]([^\[\]()]+)[\])]")  # no nested brackets: linear time
_DENSITY = re.compile(r"density|pdf|ρ|\b1/", re.IGNORECASE)


@dataclass(frozen=True)
class Histogram:
    """A histogram of heights read from a file.

    Attributes
    ----------
    edges : ndarray
        Bin edges, m, strictly increasing.
    weights : ndarray
        Counts per bin, or densities (per unit height) if ``density``.
    density : bool
        Whether ``weights`` are densities.
    source : str
        File name.
    notes : tuple of str
        Unit and layout the reader used.
    """

    edges: np.ndarray
    weights: np.ndarray
    density: bool
    source: str
    notes: tuple[str, ...] = ()

    def to_empirical(self) -> Empirical:
        """The standardized :class:`~mcsim.topography.empirical.Empirical` distribution of this histogram."""
        try:
            return Empirical.from_histogram(
                self.edges, self.weights, density=self.density, source=self.source
            )
        except MCSimError as err:
            raise ReaderError(f"{self.source}: {err}") from None


def detect(path: Path) -> bool:
    """A text file: no NUL byte in its first 4 kB."""
    return b"\x00" not in head(path, 4096)


def _cells(line: str) -> list[str]:
    return [c for c in _SPLIT.split(line.strip()) if c]


def _is_numeric(cells: list[str]) -> bool:
    try:
        [float(c) for c in cells]
    except ValueError:
        return False
    return bool(cells)


def read(path: Path | str, unit: str | None = None) -> Histogram:
    """Read a text histogram (module docstring).

    Parameters
    ----------
    path : path-like
        The file.
    unit : str, optional
        Height unit (``"nm"``, ``"um"``, ...) if the header does not give one, or to
        override it.

    Returns
    -------
    Histogram
        Edges in m.

    Raises
    ------
    ReaderError
        Empty file, fewer than two bins, a non-numeric cell, a wrong number of
        columns, negative or all-zero weights, weights whose sum overflows, bins out
        of order, or no unit.
    """
    path = Path(path)
    head(path)  # existence and permission errors, with the file named
    text = path.read_bytes().decode("utf-8", errors="replace").replace("\ufffd", "?")
    header: list[str] = []
    rows: list[list[float]] = []
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line:
            continue
        if line.startswith("#"):
            if not rows:
                header.append(line.lstrip("#").strip())
            continue
        cells = _cells(line)
        if not rows and not _is_numeric(cells):
            header.append(line)
            continue
        if len(cells) not in (2, 3):
            raise ReaderError(
                f"{path}: line {number}: expected 2 columns (centre, weight) or 3 "
                f"(left, right, weight), got {len(cells)}"
            )
        try:
            rows.append([float(c) for c in cells])
        except ValueError:
            bad = next(c for c in cells if not _is_numeric([c]))
            raise ReaderError(f"{path}: line {number}: cannot read {bad!r} as a number") from None
        if rows and len(rows[-1]) != len(rows[0]):
            raise ReaderError(
                f"{path}: line {number}: {len(cells)} columns, the first row has {len(rows[0])}"
            )
    if not rows:
        raise ReaderError(f"{path}: no histogram data (empty file or header only)")
    if len(rows) < 2:
        raise ReaderError(f"{path}: a histogram needs at least two bins, found 1")
    data = np.array(rows)
    if not np.all(np.isfinite(data)):
        raise ReaderError(f"{path}: histogram values must be finite")
    weights = data[:, -1]
    if np.any(weights < 0):
        raise ReaderError(f"{path}: negative count in bin {int(np.argmax(weights < 0)) + 1}")
    if not np.any(weights > 0):
        raise ReaderError(f"{path}: all counts are zero")
    with np.errstate(over="ignore"):
        total = np.sum(weights)
    if not np.isfinite(total):
        raise ReaderError(f"{path}: the counts add up to more than the largest float (1.8e308)")
    if data.shape[1] == 2:
        centres = data[:, 0]
        with np.errstate(over="ignore", invalid="ignore"):  # huge centres: refused below
            increasing = np.all(np.diff(centres) > 0)
        if not increasing:
            raise ReaderError(f"{path}: bin centres must be strictly increasing")
        with np.errstate(over="ignore", invalid="ignore"):  # overflow is refused below
            mid = (centres[1:] + centres[:-1]) / 2
            edges = np.concatenate(
                [[centres[0] - (mid[0] - centres[0])], mid, [centres[-1] + (centres[-1] - mid[-1])]]
            )
        layout = "two columns: centre, weight"
    else:
        left, right = data[:, 0], data[:, 1]
        if np.any(right <= left):
            raise ReaderError(f"{path}: every bin needs right edge > left edge")
        gap = np.abs(left[1:] - right[:-1])
        if np.any(gap > 1e-9 * np.abs(right[:-1]).max()):
            raise ReaderError(f"{path}: bins must be contiguous (right edge = next left edge)")
        edges = np.concatenate([left, right[-1:]])
        layout = "three columns: left, right, weight"
    column_line = header[-1] if header else ""
    found = _UNIT.search(column_line)
    if unit is None and found is None:
        raise ReaderError(
            f"{path}: missing height unit: pass --unit (e.g. 'nm') or name it in the header"
        )
    chosen = unit if unit is not None else found.group(1)
    factor = length_factor(chosen, path, "height unit")
    edges = edges * factor
    with np.errstate(over="ignore", invalid="ignore"):
        span = np.diff(edges)
        total = edges[-1] - edges[0]
    if not (np.all(np.isfinite(edges)) and np.all(span > 0) and np.isfinite(total)):
        raise ReaderError(f"{path}: bin edges overflow or collapse (values too large or too close)")
    weight_header = column_line[found.end() :] if found else column_line
    density = bool(_DENSITY.search(weight_header))
    return Histogram(
        edges=edges,
        weights=weights,
        density=density,
        source=str(path),
        notes=(layout, f"height unit {chosen!r}", "densities" if density else "counts"),
    )

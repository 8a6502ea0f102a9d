"""What ``mcsim ingest`` found: height and summit statistics, the surface, and its files.

:class:`IngestResult` is returned by :func:`mcsim.studies.maps.ingest.ingest_file`; its
:meth:`~IngestResult.write_surface` writes the surface TOML file and the measured
height histogram beside it (the layout is described in :mod:`mcsim.studies.maps.ingest`).
"""

from __future__ import annotations

import datetime as dt
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from mcsim._version import __version__
from mcsim.model.errors import ParameterError
from mcsim.model.params import Surface
from mcsim.store.outputs import check_output, write_atomic
from mcsim.topography.empirical import Empirical
from mcsim.topography.maps import LEVELS
from mcsim.topography.mapsurface import ROUTES
from mcsim.topography.readers.base import FacingMap, HeightMap
from mcsim.topography.summits import TopographyResult

if TYPE_CHECKING:
    from mcsim.studies.maps.adhesioncalibration import AdhesionCalibration
    from mcsim.studies.maps.calibration import Calibration


@dataclass(frozen=True)
class HeightSummary:
    """Moments and range of a set of heights.

    Attributes
    ----------
    count : int
        Number of heights.
    mean, sigma : float
        Mean and population standard deviation, m.
    skewness : float
        Third standardized moment (0 for a Gaussian).
    kurtosis : float
        Fourth standardized moment, Pearson's (3 for a Gaussian).
    minimum, maximum : float
        Range, m.
    """

    count: int
    mean: float
    sigma: float
    skewness: float
    kurtosis: float
    minimum: float
    maximum: float

    @classmethod
    def of(cls, z) -> HeightSummary:
        """Summary of the finite values of ``z`` (m)."""
        z = np.asarray(z, dtype=float)
        z = z[np.isfinite(z)]
        mean, sigma = float(np.mean(z)), float(np.std(z))
        s = (z - mean) / sigma if sigma > 0 else np.zeros_like(z)
        return cls(
            count=int(z.size),
            mean=mean,
            sigma=sigma,
            skewness=float(np.mean(s**3)),
            kurtosis=float(np.mean(s**4)),
            minimum=float(z.min()),
            maximum=float(z.max()),
        )

    def line(self) -> str:
        """One line, heights in nm."""
        return (
            f"mean {self.mean * 1e9:.4g} nm, sigma {self.sigma * 1e9:.4g} nm, "
            f"skewness {self.skewness:.3g}, kurtosis {self.kurtosis:.3g} (Gaussian: 0, 3), "
            f"min {self.minimum * 1e9:.4g} nm, max {self.maximum * 1e9:.4g} nm"
        )


@dataclass(frozen=True)
class IngestResult:
    """What :func:`ingest_file` read and derived.

    Attributes
    ----------
    source : Path
        The input file.
    format : str
        File format as read.
    channel : str
        Channel read ("" for single-channel formats and histograms).
    reader_notes : tuple of str
        What the reader assumed (units, scaling).
    surface : Surface
        The GW surface written by :meth:`write_surface`.
    edges : ndarray
        Edges of the written histogram, m (heights above the mean plane).
    counts : ndarray
        Counts (or densities per m, if ``density``) of the written histogram.
    density : bool
        Whether ``counts`` are densities (only for a histogram read as densities).
    heights_from : str
        What the histogram describes (``"direct-route summit heights"``, ...).
    route : str
        Route of ``R``, ``eta`` and ``sigma`` (``direct``, ``spectral``, or ``user``
        for a histogram input).
    level : str
        Levelling applied to a map (a key of :data:`~mcsim.topography.maps.LEVELS`); "" for a histogram.
    shape : tuple of int or None
        (rows, columns) of a map.
    dx, dy : float
        Pixel size, m (NaN for a histogram).
    n_nan : int
        Non-finite pixels dropped.
    map_heights : HeightSummary or None
        Heights of the levelled map.
    summit_heights : HeightSummary or None
        Heights of the direct-route summits (or of the histogram input).
    topography : TopographyResult or None
        Both routes' summit statistics of a map.
    warnings : tuple of str
        Warnings raised while analysing (e.g. saturation).
    map_edges, map_counts : ndarray or None
        Histogram of all heights of the levelled map (edges in m, counts), for the
        environment (``surface.map_heights``); None for a histogram input.
    periodic : bool
        The map was analysed as periodic (summit neighbours wrap across its edges).
    periodic_reason : str
        Why: "as asked", or the edge check's numbers (:func:`~mcsim.topography.summits.periodic_edges`).
    calibration : Calibration or None
        GW's summit-radius scale fitted to exact solves (:mod:`mcsim.studies.maps.calibration`),
        written to the surface file's ``[surface.calibration]`` table; ``surface`` keeps the
        measured radius.
    adhesion_calibration : AdhesionCalibration or None
        GW's pull-off calibrated on exact adhesive cycles of the map
        (:mod:`mcsim.studies.maps.adhesioncalibration`), written to the surface file's
        ``[surface.adhesion_calibration]`` table; recorded, not applied.
    facing : FacingMap or None
        A counter-surface's map facing this one: the map analysed is their gap's topography.
    height_map : HeightMap or None
        The map as read once and analysed (:func:`mcsim.topography.maps.read_map`), for the
        studies that follow on it (``mcsim report``: its exact contact and stickiness); None
        for a histogram.
    """

    source: Path
    format: str
    channel: str
    reader_notes: tuple[str, ...]
    surface: Surface
    edges: np.ndarray
    counts: np.ndarray
    density: bool
    heights_from: str
    route: str
    level: str
    shape: tuple[int, int] | None
    dx: float
    dy: float
    n_nan: int
    map_heights: HeightSummary | None
    summit_heights: HeightSummary | None
    topography: TopographyResult | None
    warnings: tuple[str, ...] = ()
    map_edges: np.ndarray | None = None
    map_counts: np.ndarray | None = None
    periodic: bool = False
    periodic_reason: str = ""
    calibration: Calibration | None = None
    adhesion_calibration: AdhesionCalibration | None = None
    facing: FacingMap | None = None
    height_map: HeightMap | None = field(default=None, repr=False)

    @property
    def distribution(self) -> Empirical:
        """The measured height distribution (standardized, with its σ and mean in m)."""
        return self.surface.heights

    @property
    def gaussian_surface(self) -> Surface:
        """The same (σ, R, η) with Gaussian summit heights: the GW reference."""
        s = self.surface
        return Surface(sigma=s.sigma, R=s.R, eta=s.eta, name=f"{s.name} (Gaussian)")

    def summary_lines(self) -> list[str]:
        """What was read and derived, for a terminal (lengths in nm and µm)."""
        s = self.surface
        lines = [f"read       {self.source} ({self.format}{self._channel()})"]
        lines += [f"reader     {note}" for note in self.reader_notes]
        if self.facing is not None:
            lines.append(f"counter    {self.facing.line()}")
        if self.topography is not None:
            rows, cols = self.shape
            lines += [
                f"map        {cols} x {rows} pixels (x by y), {cols * self.dx * 1e6:.4g} um x "
                f"{rows * self.dy * 1e6:.4g} um, pixel size {self.dx * 1e9:.4g} nm x {self.dy * 1e9:.4g} nm",
                f"pixels     {self.n_nan} NaN of {rows * cols} dropped",
                f"periodic   {'yes (neighbours wrap)' if self.periodic else 'no'}: {self.periodic_reason}",
                f"levelling  {self.level}: least-squares polynomial of degree {LEVELS[self.level]} "
                "subtracted; heights from the mean plane",
                f"heights    levelled map: {self.map_heights.line()}",
                f"summits    direct route, {self.summit_heights.count} summits: "
                f"{self.summit_heights.line()}",
                "route        eta (um^-2)     R (um)  sigma_s (nm)  mean height (nm)   summits",
            ]
            for name in ROUTES:
                r = getattr(self.topography, name)
                lines.append(
                    f"  {name:<9}  {r.eta * 1e-12:11.5g}  {r.R * 1e6:9.4g}  {r.sigma_s * 1e9:12.4g}"
                    f"  {r.mean_height * 1e9:16.4g}  {r.count:8.6g}"
                )
            lines.append(
                f"caveat     summit statistics depend strongly on the sampling interval "
                f"(pixel size {self.dx * 1e9:.4g} nm) and the instrument bandwidth (tip, noise)"
            )
        else:
            lines.append(f"histogram  {self.edges.size - 1} bins: {self.summit_heights.line()}")
        if s.radius_by_height is not None:
            f = s.radius_by_height.factors
            lines.append(f"radius     by height: R x {f[0]:.3g} in the lowest band of summit heights "
                         f"to x {f[-1]:.3g} in the highest ({len(f)} bands, the histogram's bins; "
                         "ln curvature fitted linear in height)")  # fmt: skip
        if self.calibration is not None:
            lines += self.calibration.lines()
            lines += [f"warning    {w}" for w in self.calibration.warnings()]
        if self.adhesion_calibration is not None:
            lines += self.adhesion_calibration.lines()
            lines += [f"warning    {w}" for w in self.adhesion_calibration.warnings()]
        lines += [f"warning    {w}" for w in self.warnings]
        if s.rq is not None:
            lines.append(
                f"gaps       rq = {s.rq * 1e9:.4g} nm (levelled map about its mean plane), "
                f"summit_offset = {s.summit_offset * 1e9:.4g} nm (mean direct-route summit "
                f"height above it), map heights: {self.map_edges.size - 1} bins (measured; "
                "for the environment)"
            )
        lines.append(
            f"surface    sigma = {s.sigma * 1e9:.4g} nm, R = {s.R * 1e6:.4g} um, "
            f"eta = {s.eta * 1e-12:.5g} um^-2 (route {self.route}); heights: {self.heights_from}, "
            f"{self.edges.size - 1} bins"
        )
        return lines

    def _channel(self) -> str:
        return f", channel {self.channel!r}" if self.channel else ""

    @staticmethod
    def companion_paths(path: str | Path) -> dict[str, Path]:
        """Files written next to the surface file ``path``: histogram CSV and figures."""
        path = Path(path)
        return {
            "histogram": path.with_name(f"{path.stem}-heights.csv"),
            "map_histogram": path.with_name(f"{path.stem}-map-heights.csv"),
            "histogram_figure": path.with_name(f"{path.stem}-heights.png"),
            "comparison_figure": path.with_name(f"{path.stem}-gw.png"),
        }

    def write_surface(
        self, path: str | Path, *, overwrite: bool = False, command: str | None = None
    ) -> list[Path]:
        """Write the surface TOML file and its histogram CSV (module docstring).

        Parameters
        ----------
        path : path-like
            The ``.toml`` file; the histogram goes to ``<stem>-heights.csv`` beside it.
        overwrite : bool
            Replace existing files; otherwise an existing one is an error.
        command : str, optional
            Command line recorded in the comments.

        Returns
        -------
        list of Path
            The TOML file and the CSV file.

        Raises
        ------
        MCSimError
            Not a ``.toml`` path, a missing folder, an existing file without
            ``overwrite``, the input file itself, or not a regular file
            (:mod:`mcsim.store.outputs`).
        """
        path = Path(path)
        if path.suffix != ".toml":
            raise ParameterError(f"{path}: the surface file must end in .toml")
        companions = self.companion_paths(path)
        csv, map_csv = companions["histogram"], companions["map_histogram"]
        header = self._provenance(command)
        files = {csv: self._histogram_text(header)}
        if self.map_edges is not None:
            files[map_csv] = self._histogram_text(
                header, self.map_edges, self.map_counts, "all heights of the levelled map"
            )
        files[path] = self._toml_text(header, csv.name, map_csv.name)
        for p in files:  # all refused before any is written
            check_output(p, inputs=[self.source], overwrite=overwrite)
        for p, text in files.items():
            write_atomic(p, lambda tmp, text=text: tmp.write_text(text, encoding="utf-8"),
                         inputs=[self.source], overwrite=overwrite)  # fmt: skip
        return [path, *(p for p in files if p != path)]

    def _provenance(self, command: str | None) -> list[str]:
        now = dt.datetime.now(dt.UTC).isoformat(timespec="seconds")
        lines = [
            f"written by mcsim {__version__} (mcsim ingest) on {now}",
            f"source: {self.source.resolve()} ({self.format}{self._channel()})",
        ]
        if command:
            lines.append(f"command: {command}")
        if self.facing is not None:
            lines.append(f"counter-surface: {self.facing.line()}")
        if self.topography is not None:
            rows, cols = self.shape
            lines += [
                f"map: {cols} x {rows} pixels, pixel size {self.dx * 1e9:.6g} nm x {self.dy * 1e9:.6g} nm, "
                f"{self.n_nan} NaN pixels dropped, levelling {self.level} (degree {LEVELS[self.level]})",
                f"periodic: {'yes' if self.periodic else 'no'} ({self.periodic_reason})",
            ]
        return lines

    def _histogram_text(self, header: list[str], edges=None, counts=None, what=None) -> str:
        """The summit histogram as CSV text, or the one given (counts)."""
        density = self.density and counts is None
        edges = self.edges if edges is None else edges
        counts = self.counts if counts is None else counts
        weight = "density [1/nm]" if density else "count"
        out = [f"# {line}" for line in header]
        out += [
            f"# {what or self.heights_from}, heights above the mean plane",
            f"left [nm], right [nm], {weight}",
        ]
        values = counts * 1e-9 if density else counts
        for left, right, w in zip(edges[:-1] * 1e9, edges[1:] * 1e9, values):
            out.append(f"{float(left)!r}, {float(right)!r}, {_number(w)}")
        return "\n".join(out) + "\n"

    def _toml_text(self, header: list[str], csv_name: str, map_csv_name: str) -> str:
        s = self.surface
        out = [f"# {line}" for line in header]
        if self.topography is not None:
            out += [
                f"# route: {self.route} (R, eta and sigma below); both routes, with this sampling:",
                *(
                    f"#   {name:<8}: eta = {r.eta * 1e-12:.6g} um^-2, R = {r.R * 1e6:.6g} um, "
                    f"sigma_s = {r.sigma_s * 1e9:.6g} nm, {r.count:.6g} summits"
                    for name in ROUTES
                    for r in [getattr(self.topography, name)]
                ),
                "# Summit statistics depend strongly on the sampling interval (pixel size) and the",
                "# instrument bandwidth: they describe the surface as sampled, not the surface alone.",
            ]
        else:
            out.append("# R and eta: given by the user; sigma: the histogram's own")
        out += [
            f"# heights: {self.heights_from}, histogram in {csv_name} (path relative to this file)",
            "# Use: mcsim analytic --surface THIS.toml --h=4:-1:51  (material: --material, default silicon)",
            "",
            "[surface]",
            f"name = {json.dumps(s.name)}",
            f'sigma = "{s.sigma * 1e9:.12g} nm"',
            f'R = "{s.R * 1e6:.12g} um"',
            f'eta = "{s.eta * 1e-12:.12g} um^-2"',
            "",
            *(
                [
                    "# For the environment (van der Waals, capillary), measured on the levelled map:",
                    "# rq about its mean plane, the mean direct-route summit height above it, and",
                    f"# the map's height histogram in {map_csv_name}.",
                    f'rq = "{s.rq * 1e9:.12g} nm"',
                    f'summit_offset = "{s.summit_offset * 1e9:.12g} nm"',
                ]
                if s.rq is not None
                else []
            ),
            *self._radius_toml(),
            *self._calibration_toml(),
            *(self.adhesion_calibration.toml_lines() if self.adhesion_calibration else []),
            "",
            "[surface.heights]",
            f"file = {json.dumps(csv_name)}",
            'unit = "nm"',
            *(
                ["", "[surface.map_heights]", f"file = {json.dumps(map_csv_name)}", 'unit = "nm"']
                if s.map_heights is not None
                else []
            ),
        ]
        return "\n".join(out) + "\n"

    def _radius_toml(self) -> list[str]:
        """The ``[surface.radius_by_height]`` table, or nothing."""
        bands = self.surface.radius_by_height
        if bands is None:
            return []
        return [
            "",
            "# Summit radius by height (mcsim ingest --radius-by-height): the summits of each",
            "# band of heights have the radius R x factor (fitted to the summits' curvatures:",
            "# ln kappa linear in s). Band edges in s = (z - mean summit height)/sigma, the",
            "# histogram's bins; the outermost bands extend beyond them.",
            "[surface.radius_by_height]",
            "edges = [" + ", ".join(f"{e:.12g}" for e in bands.edges) + "]",
            "factors = [" + ", ".join(f"{f:.12g}" for f in bands.factors) + "]",
        ]

    def _calibration_toml(self) -> list[str]:
        """The ``[surface.calibration]`` table (:mod:`mcsim.studies.maps.calibration`), or nothing."""
        c = self.calibration
        if c is None:
            return []

        def numbers(values) -> str:
            return "[" + ", ".join(f"{float(v):.6g}" for v in values) + "]"

        return [
            "",
            "# GW calibrated on exact elastic solves of the map (mcsim ingest --calibrate): every",
            "# command that reads this file uses the summit radius R x radius_scale. It fits the",
            "# real contact area of non-adhesive contact over these loads, at this pixel size; it",
            "# does NOT fix the mean gap (both are below), nor adhesion.",
            "[surface.calibration]",
            f"radius_scale = {c.radius_scale:.12g}",
            f"material = {json.dumps(c.material)}",
            f'E_star = "{c.E_star / 1e9:.12g} GPa"',
            f'pixel_size = "{c.dx * 1e9:.12g} nm"',
            f"periodic = {'true' if c.periodic else 'false'}",
            f"load = {numbers(c.load)}  # p/E*",
            f"exact_area_fraction = {numbers(c.exact_area)}",
            f"gw_area_fraction = {numbers(c.gw_area)}  # calibrated",
            f"uncalibrated_area_fraction = {numbers(c.uncalibrated_area)}",
            f"exact_mean_gap_nm = {numbers(c.exact_gap * 1e9)}",
            f"gw_mean_gap_nm = {numbers(c.gw_gap * 1e9)}  # not calibrated",
            f"in_sample_worst_error = {c.in_sample_worst:.6g}  # largest |A_GW/A_exact - 1| "
            "at these loads",
            f"in_sample_rms_error = {c.in_sample_rms:.6g}",
            "# Out of sample: each load left out of the fit in turn (the scale fitted to the",
            "# others, GW's error A_GW/A_exact - 1 at the load left out), and one load above",
            "# the fitted range (exact and calibrated GW's area, the error). The warning judges",
            "# these.",
            f"loo_radius_scale = {numbers(c.loo_scale)}",
            f"loo_error = {numbers(c.loo_error)}",
            f"loo_worst_error = {c.loo_worst:.6g}",
            f"loo_rms_error = {c.loo_rms:.6g}",
            f"extrapolated_load = {c.extrapolated_load:.6g}  # p/E*",
            f"extrapolated_exact_area_fraction = {c.extrapolated_exact_area:.6g}",
            f"extrapolated_gw_area_fraction = {c.extrapolated_gw_area:.6g}",
            f"extrapolated_error = {c.extrapolated_error:.6g}",
        ]


def _number(w: float) -> str:
    return str(int(w)) if float(w).is_integer() else repr(float(w))

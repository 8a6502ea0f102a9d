"""Pads synthesised from a measured map's spectrum: ``mcsim ingest --synthesize``.

:func:`synthesize_pads` reads a height map as ``mcsim ingest`` does (any reader, its periodicity
decided from the edges unless told, levelled by its mean if periodic and by a plane
otherwise: :func:`mcsim.topography.synthesis.radial_psd`), takes its radial PSD and draws
``n`` periodic Gaussian pads of ``pixels`` × ``pixels`` pixels at the map's pixel size from
it (:func:`mcsim.topography.synthesis.synthesize`: each mode the mean periodogram of the
map's annulus it falls in). A pad smaller than the map holds only the wavelengths that fit
in it, so its mean square is below the map's (the map's longest wavelengths are missing);
:attr:`SynthesizedPads.mean_square` states both. Pad i comes from the i-th spawned child of
``np.random.default_rng(seed)``: the same seed gives bit-identical pads, and pad i does not
depend on ``n``.

:meth:`SynthesizedPads.write` writes them to HDF5, atomically, never over an existing file
unless asked (:func:`mcsim.store.outputs.check_output`). Layout (schema :data:`SCHEMA`):

    /                     attrs: pads_schema_version, mcsim_version, created, command, seed,
                          source, channel, periodic_source, method
    heights   (pad, y, x) float64, m: the pads (periodic), each of zero mean
    psd_q     (bin,)      float64, rad/m: the source map's annuli (mean |q|)
    psd_C     (bin,)      float64, m^4: their mean periodogram
    psd_modes (bin,)      int64: the modes averaged in each annulus
    attrs of heights:     pixel_size (m); attrs of psd_C: width (rad/m), area (m^2)

each dataset with CF ``units`` and ``long_name``. :func:`read_pads` reads it back.
"""

from __future__ import annotations

import datetime as _dt
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mcsim._version import __version__
from mcsim.model.errors import ParameterError
from mcsim.topography.synthesis import MIN_SIDE, RadialPSD, radial_psd, synthesize, wavevectors

#: HDF5 layout version of a pads file.
SCHEMA = 1


@dataclass(frozen=True)
class SynthesizedPads:
    """Pads drawn from a map's radial PSD (module docstring).

    Attributes
    ----------
    heights : ndarray
        Heights, m, shape (n, pixels, pixels); periodic, each of zero mean.
    pixel_size : float
        Pixel size, m (the map's).
    seed : int
        Root seed of ``np.random.default_rng``.
    source : str
        The map file.
    channel : str
        Its channel.
    periodic_source : bool
        The map was analysed as periodic (mean removed, no window) or not (plane, Hann window).
    psd : RadialPSD
        The map's radial PSD the pads were drawn from.
    """

    heights: np.ndarray
    pixel_size: float
    seed: int
    source: str
    channel: str
    periodic_source: bool
    psd: RadialPSD

    @property
    def mean_square(self) -> tuple[float, float]:
        """(expected mean square of a pad, the map's), m²: Σ_q C(|q|)/A over the pad's modes,
        and over the map's (:meth:`RadialPSD.mean_square`)."""
        q = wavevectors(self.heights.shape[1:], self.pixel_size)
        area = self.heights[0].size * self.pixel_size**2
        return float(np.sum(self.psd(q[q > 0])) / area), self.psd.mean_square()

    def write(self, path: str | Path, *, overwrite: bool = False, command: str = "") -> Path:
        """Write the pads to HDF5 atomically (module docstring); refuse an existing file
        unless ``overwrite`` and the source map always. Returns the path."""
        from mcsim.store.files import atomic_write
        from mcsim.store.outputs import check_output

        path = check_output(path, inputs=[self.source], overwrite=overwrite)

        def fill(f):
            f.attrs.update({
                "pads_schema_version": SCHEMA, "mcsim_version": __version__,
                "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
                "command": command, "seed": self.seed, "source": self.source,
                "channel": self.channel, "periodic_source": self.periodic_source,
                "method": "psd: the source's radial PSD, each mode its annulus' mean periodogram",
            })  # fmt: skip
            for name, data, units, long_name in (
                ("heights", self.heights, "m", "height above the pad's mean plane"),
                ("psd_q", self.psd.q, "rad/m", "mean wavevector |q| of the source's annulus"),
                ("psd_C", self.psd.C, "m^4", "radially averaged periodogram of the source"),
                ("psd_modes", self.psd.n_modes, "1", "modes averaged in the annulus"),
                ("psd_index", self.psd.index, "1", "annulus number k (centre k * width)"),
            ):
                ds = f.create_dataset(name, data=data)
                ds.attrs["units"] = units
                ds.attrs["long_name"] = long_name
            f["heights"].attrs["pixel_size"] = self.pixel_size
            f["psd_C"].attrs["width"] = self.psd.width
            f["psd_C"].attrs["area"] = self.psd.area

        atomic_write(path, fill)
        return path


def read_pads(path: str | Path) -> SynthesizedPads:
    """Read a pads file written by :meth:`SynthesizedPads.write`."""
    import h5py

    with h5py.File(path, "r") as f:
        if f.attrs.get("pads_schema_version") != SCHEMA:
            raise ParameterError(f"{path}: not an mcsim pads file of schema {SCHEMA}")
        c = f["psd_C"]
        psd = RadialPSD(q=f["psd_q"][()], C=c[()], n_modes=f["psd_modes"][()],
                        index=f["psd_index"][()], width=float(c.attrs["width"]),
                        area=float(c.attrs["area"]))  # fmt: skip
        return SynthesizedPads(
            heights=f["heights"][()], pixel_size=float(f["heights"].attrs["pixel_size"]),
            seed=int(f.attrs["seed"]), source=str(f.attrs["source"]),
            channel=str(f.attrs["channel"]), periodic_source=bool(f.attrs["periodic_source"]),
            psd=psd,
        )  # fmt: skip


def check_pads(n, pixels, seed=None, path=None) -> None:
    """Refuse a bad number of pads (≥ 1), pad side (≥ 8 pixels), seed (≥ 0) or a histogram
    file as the source (it has no spectrum), one line naming the field."""
    from mcsim.topography.maps import is_histogram_file

    if path is not None and is_histogram_file(Path(path)):
        raise ParameterError(
            f"`path` = {str(path)!r}: a histogram has no spectrum; give a height map"
        )
    fields = (("n", n, 1), ("pixels", pixels, MIN_SIDE)) + (
        () if seed is None else (("seed", seed, 0),)
    )
    for name, value, low in fields:
        if not (isinstance(value, int | np.integer) and not isinstance(value, bool)
                and value >= low):  # fmt: skip
            raise ParameterError(
                f"`{name}` = {value!r} is out of range (allowed: an integer >= {low})"
            )


def synthesize_pads(
    path: str | Path,
    n: int,
    pixels: int,
    seed: int | None = None,
    *,
    unit: str | None = None,
    pixel_size: float | tuple[float, float] | None = None,
    channel: str | None = None,
    periodic: bool | None = None,
) -> SynthesizedPads:
    """``n`` periodic pads of ``pixels`` × ``pixels`` from a height map's radial PSD.

    Parameters
    ----------
    path : path-like
        A height map (any format of :mod:`mcsim.topography.readers`); not a histogram.
    n : int
        Number of pads, ≥ 1.
    pixels : int
        Pixels along each side of a pad, ≥ 8.
    seed : int, optional
        Root seed (None: fresh entropy, recorded).
    unit, pixel_size, channel
        As for :func:`mcsim.studies.maps.ingest.ingest_file`; the pixels must be square.
    periodic : bool, optional
        Analyse the map as periodic; None decides from its edges.

    Returns
    -------
    SynthesizedPads

    Raises
    ------
    ParameterError
        A bad ``n`` or ``pixels``, a histogram file, a map with non-square pixels or NaN.
    """
    from mcsim.topography.maps import decide_periodic, read_checked

    check_pads(n, pixels, seed, path)
    path = Path(path)
    hmap = read_checked(path, unit=unit, pixel_size=pixel_size, channel=channel)
    if not np.isclose(hmap.dx, hmap.dy, rtol=1e-9):
        raise ParameterError(f"`pixel_size`: {hmap.dx:.4g} m x {hmap.dy:.4g} m; square pixels only")
    is_periodic, _ = decide_periodic(hmap.heights, periodic)
    psd = radial_psd(hmap.heights, hmap.dx, periodic=is_periodic)
    if seed is None:
        seed = int(np.random.SeedSequence().generate_state(1, np.uint32)[0])
    heights = synthesize((pixels, pixels), hmap.dx, psd, rng=int(seed), n=int(n))
    return SynthesizedPads(heights=heights, pixel_size=hmap.dx, seed=int(seed),
                           source=str(path), channel=hmap.channel,
                           periodic_source=is_periodic, psd=psd)  # fmt: skip

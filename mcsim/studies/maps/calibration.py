"""GW calibrated on the exact elastic contact of its map: ``mcsim ingest --calibrate``.

GW's real contact area on a measured map is not the exact one (``mcsim contact``,
docs/contact.md): its summits do not interact and its summit radius is a sampled curvature.
:func:`calibrate` solves the map's frictionless, non-adhesive contact exactly at
:data:`LOADS` (p/E* = 1e-4 … 1e-2, five loads spaced evenly in log) and fits **one
summit-radius scale** s so that GW's Hertz area with radius s·R follows the exact area: the s
that makes the worst ratio |ln(A_GW/A_exact)| over the loads smallest (a one-parameter
minimax fit; GW's area at a fixed pressure grows about as √R). The surface file records s
with the loads, both areas, the errors at the fitted loads (in sample) and out of sample
(below); every command that reads the file then uses the radius s·R. The surface ``ingest`` calibrates carries a radius by height by
default (:class:`~mcsim.model.params.RadiusByHeight`, each band of summit heights its own
radius): s scales every band's radius.

Out of sample
-------------
The errors at the five loads the scale was fitted to flatter it. Two checks judge it on
loads it was not fitted to:

* **Leave-one-out** over the loads: for each load k the scale is fitted again (the same
  minimax fit) on the other four, and GW's error at load k is recorded; the worst and rms
  over k, with each load's error and refitted scale. A minimax fit is set by the two loads
  where the error is largest and smallest: leaving out any other load leaves the scale
  unchanged, so its leave-one-out error is its in-sample one.
* **One load outside the fitted range**, p/E* = :data:`EXTRAPOLATED_LOAD` = 3e-2, half a
  decade above the top (the spacing of the fitted loads): the exact contact is solved there
  too, warm-started from the solve at 1e-2 (one solve more), and calibrated GW's error
  there recorded. The check goes up, not down: below 1e-4 the exact contact is a few
  pixels of a map, itself resolution-limited, while above the range is where a user who
  presses harder than the calibration goes; there the contact covers a good part of the map
  and GW's independent summits are stretched, which is what such a user meets.

:meth:`Calibration.warnings` judges the larger of the two, not the in-sample error, against
:data:`TARGET`.

What calibration does and does not fix
--------------------------------------
* It fixes the real contact area of non-adhesive contact over the fitted loads, at the map's
  pixel size, as well as one scale can: with one radius for every summit GW's area grows
  more slowly with load than the exact one (the taller summits are sharper), so one scale
  leaves an error that grows toward the ends of the range; a radius by height bends the
  curve (docs/contact.md: 4.6 % on the shipped map in sample, against 13.8 %). The errors
  in and out of sample are recorded; the out-of-sample one is warned about above
  :data:`TARGET`.
* It does **not** fix the mean gap: the radius moves GW's separation at a given load, but its
  mean gap stays off the exact one (GW deforms only the summits, and its gap turns negative
  under loads the exact gap does not), nearer on some maps and further on others; both mean
  gaps are recorded beside the areas. Nor is it checked for adhesive law sets, whose forces
  scale with R differently (JKR pull-off ∝ R).
* The ratio GW/exact at a given p/E* does not depend on E* (both areas scale with p/E*), so
  one scale serves every material; the material used is recorded.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface
from mcsim.physics import bem
from mcsim.studies.maps.contact import contact_map, gw_hertz
from mcsim.topography.readers import HeightMap

#: Calibration loads p/E*: five, evenly spaced in log from 1e-4 to 1e-2.
LOADS = np.logspace(-4, -2, 5)
#: Load p/E* of the extrapolation check, outside the fitted range (module docstring).
EXTRAPOLATED_LOAD = 3e-2
#: Worst out-of-sample relative area error above which the calibration is warned about.
TARGET = 0.10
#: Range searched for ln s (s from e^-5 to e^5).
LOG_SCALE_BOUND = 5.0


#: Keys of the surface file's ``[surface.calibration]`` table read back as they are, by the
#: :class:`Calibration` field each holds (``E_star``, ``pixel_size`` and the gaps carry units).
_FILE_KEYS = {"radius_scale": "radius_scale", "material": "material", "periodic": "periodic",
              "load": "load", "exact_area_fraction": "exact_area", "gw_area_fraction": "gw_area",
              "uncalibrated_area_fraction": "uncalibrated_area",
              "in_sample_worst_error": "in_sample_worst", "in_sample_rms_error": "in_sample_rms",
              "loo_radius_scale": "loo_scale", "loo_error": "loo_error",
              "loo_worst_error": "loo_worst", "loo_rms_error": "loo_rms",
              "extrapolated_load": "extrapolated_load",
              "extrapolated_exact_area_fraction": "extrapolated_exact_area",
              "extrapolated_gw_area_fraction": "extrapolated_gw_area",
              "extrapolated_error": "extrapolated_error"}  # fmt: skip


@dataclass(frozen=True)
class Calibration:
    """One summit-radius scale fitted to exact solves (module docstring).

    Attributes
    ----------
    radius_scale : float
        s: GW uses the radius s·R, dimensionless.
    material : str
        Name of the material of the solves.
    E_star : float
        Its contact modulus, Pa.
    load : ndarray
        The loads p/E*, dimensionless.
    exact_area, gw_area, uncalibrated_area : ndarray
        A_r/A_n at each load: exact, GW with s·R, GW with R.
    exact_gap, gw_gap : ndarray
        Mean gap at each load, m: exact, and GW's with s·R (not calibrated).
    in_sample_worst, in_sample_rms : float
        Largest and rms |A_GW/A_exact − 1| over the fitted loads after calibration
        (in sample: at the loads the scale was fitted to), dimensionless.
    loo_scale : ndarray
        At each load k, the radius scale fitted to the other loads (leave-one-out),
        dimensionless.
    loo_error : ndarray
        At each load k, A_GW/A_exact − 1 with the radius ``loo_scale[k]`` (out of sample:
        load k was left out of that fit), signed, dimensionless.
    loo_worst, loo_rms : float
        Largest and rms |``loo_error``| over the loads, dimensionless.
    extrapolated_load : float
        p/E* of the extrapolation check, :data:`EXTRAPOLATED_LOAD`, above the fitted loads.
    extrapolated_exact_area, extrapolated_gw_area : float
        A_r/A_n there: exact, and GW with s·R.
    extrapolated_error : float
        A_GW/A_exact − 1 there (out of sample: outside the fitted range), signed.
    dx : float
        Pixel size of the map, m: the exact areas belong to it.
    periodic : bool
        The map was solved as periodic.
    """

    radius_scale: float
    material: str
    E_star: float
    load: np.ndarray
    exact_area: np.ndarray
    gw_area: np.ndarray
    uncalibrated_area: np.ndarray
    exact_gap: np.ndarray
    gw_gap: np.ndarray
    in_sample_worst: float
    in_sample_rms: float
    loo_scale: np.ndarray
    loo_error: np.ndarray
    loo_worst: float
    loo_rms: float
    extrapolated_load: float
    extrapolated_exact_area: float
    extrapolated_gw_area: float
    extrapolated_error: float
    dx: float
    periodic: bool

    @property
    def out_of_sample_worst(self) -> float:
        """The larger of the worst leave-one-out error and the extrapolated one (absolute)."""
        return max(self.loo_worst, abs(self.extrapolated_error))

    @classmethod
    def from_file(cls, path: str | Path) -> Calibration:
        """The calibration a surface file records (``[surface.calibration]``, as ``ingest`` writes it).

        Numbers come back to the 6 significant digits they are written with (``radius_scale``
        to 12).

        Raises
        ------
        ParameterError
            No such table, or one written before the out-of-sample errors were recorded.
        """
        from mcsim.model.units import parse_quantity
        from mcsim.store.config import calibration_in_surface_file

        table = calibration_in_surface_file(path)
        if table is None:
            raise ParameterError(
                f"{path}: no [surface.calibration] table (mcsim ingest --calibrate)"
            )
        missing = sorted(set(_FILE_KEYS) - set(table))
        if missing:
            raise ParameterError(f"{path}: [surface.calibration] has no {', '.join(missing)} (written "
                                 "before the out-of-sample errors were recorded: ingest it again)")  # fmt: skip
        values = {field: (np.asarray(table[key], dtype=float) if isinstance(table[key], list)
                          else table[key]) for key, field in _FILE_KEYS.items()}  # fmt: skip
        return cls(**values, E_star=parse_quantity(table["E_star"], "pressure", "E_star"),
                   dx=parse_quantity(table["pixel_size"], "length", "pixel_size"),
                   exact_gap=np.asarray(table["exact_mean_gap_nm"], dtype=float) * 1e-9,
                   gw_gap=np.asarray(table["gw_mean_gap_nm"], dtype=float) * 1e-9)  # fmt: skip

    def apply(self, surface: Surface) -> Surface:
        """``surface`` with its summit radius multiplied by :attr:`radius_scale`."""
        return dataclasses.replace(surface, R=surface.R * self.radius_scale)

    def warnings(self) -> list[str]:
        """A line if the worst out-of-sample error is above :data:`TARGET` (else empty)."""
        worst = self.out_of_sample_worst
        if worst <= TARGET:
            return []
        which = ("leave-one-out over the fitted loads" if self.loo_worst >= abs(self.extrapolated_error)
                 else f"at p/E* = {short(self.extrapolated_load)}, outside the fitted range")  # fmt: skip
        ratios = ", ".join(f"{r:.3g}" for r in self.gw_area / self.exact_area)
        return [f"calibrated GW's area is off the exact one out of sample by up to {worst:.1%} "
                f"({which}), above {TARGET:.0%} (leave-one-out worst {self.loo_worst:.1%}; at "
                f"p/E* = {short(self.extrapolated_load)} {self.extrapolated_error:+.1%}; in sample "
                f"{self.in_sample_worst:.1%}, ratios {ratios} at p/E* = "
                f"{', '.join(f'{x:.3g}' for x in self.load)}): one radius scale cannot follow how "
                "the exact area grows with load on this map (with one radius for every summit, try "
                "--radius-by-height; outside the fitted loads, trust the area less)"]  # fmt: skip

    def lines(self) -> list[str]:
        """What was fitted, for a terminal."""
        return [
            f"calibrate  summit radius x {self.radius_scale:.4g} (R = "
            f"{self.radius_scale:.4g} x measured), fitted to exact solves (material "
            f"{self.material}, pixel size {self.dx * 1e9:.4g} nm) at p/E* = "
            f"{', '.join(f'{x:.3g}' for x in self.load)}",
            "calibrate  A_r/A_n exact " + ", ".join(f"{a:.4g}" for a in self.exact_area)
            + "; GW calibrated " + ", ".join(f"{a:.4g}" for a in self.gw_area)
            + "; GW measured R " + ", ".join(f"{a:.4g}" for a in self.uncalibrated_area),
            f"calibrate  in sample (at the fitted loads): worst area error "
            f"{self.in_sample_worst:.1%}, rms {self.in_sample_rms:.1%}",
            f"calibrate  out of sample: leave-one-out worst {self.loo_worst * 100:.1f} %, rms "
            f"{self.loo_rms * 100:.1f} %; at p/E* = {short(self.extrapolated_load)} (outside the "
            f"fitted range): {self.extrapolated_error * 100:+.1f} %",
            "calibrate  the mean gap is NOT calibrated: exact "
            + ", ".join(f"{g * 1e9:.4g}" for g in self.exact_gap) + " nm; GW calibrated "
            + ", ".join(f"{g * 1e9:.4g}" for g in self.gw_gap) + " nm",
        ]  # fmt: skip


def short(x: float) -> str:
    """``x`` in e-notation with one digit and no padded exponent: 0.03 -> ``3e-2``."""
    mantissa, exponent = f"{x:.0e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def _errors(surface: Surface, material: Material, pressure, exact, scale: float) -> np.ndarray:
    """ln(A_GW/A_exact) at each pressure for the radius scale ``scale``."""
    scaled = dataclasses.replace(surface, R=surface.R * scale)
    return np.log(gw_hertz(scaled, material, pressure)[1] / exact)


def _minimax_scale(errors, keep: np.ndarray, start: float) -> float:
    """ln s of the minimax fit over the loads ``keep``: max |e_k| smallest (module docstring).

    ``errors(x)`` gives e_k = ln(A_GW/A_exact) at every load for the scale e^x. Each e_k grows
    with x (GW's area at a fixed pressure grows with R), so max_k |e_k| = max(max e, −min e)
    is smallest where g(x) = max_k e_k + min_k e_k, which grows with x, crosses zero: that
    root, bracketed from ``start`` outward and found by Brent's method to 1e-10 in ln s (a
    bound of ±:data:`LOG_SCALE_BOUND` if it lies beyond).

    Parameters
    ----------
    errors : callable
        x ↦ ndarray of e_k at every load (cached by the caller: brackets share points).
    keep : ndarray of bool
        The loads fitted.
    start : float
        First guess of ln s.
    """
    from scipy import optimize

    def g(x: float) -> float:
        e = errors(x)[keep]
        return float(e.max() + e.min())

    g0 = g(start)
    if abs(g0) <= 1e-10:  # already the root (a load left out that did not set the fit)
        return start
    # e_k grows about as (1 − m/2)·x (area ∝ p^m, m ≈ 1): g by about one per unit of x
    step, a = -g0, start
    while True:
        b = min(max(a + step, -LOG_SCALE_BOUND), LOG_SCALE_BOUND)
        if (g(b) > 0) != (g0 > 0):
            break
        if b in (-LOG_SCALE_BOUND, LOG_SCALE_BOUND):
            return b
        a, step = b, 2 * step
    return optimize.brentq(g, min(a, b), max(a, b), xtol=1e-10)


def calibrate(
    source: HeightMap | str | Path,
    material: Material,
    *,
    unit: str | None = None,
    pixel_size: float | tuple[float, float] | None = None,
    channel: str | None = None,
    level: str | None = None,
    periodic: bool | None = None,
    tol: float = bem.TOL,
    surface: Surface | None = None,
    progress: bool = False,
) -> Calibration:
    """Fit GW's summit-radius scale to the exact contact of a map (module docstring).

    Parameters
    ----------
    source : HeightMap or path-like
        A map read once (:func:`mcsim.topography.maps.read_map`; ``mcsim ingest`` passes the
        map it analysed), or a height map file, any format ``mcsim ingest`` reads.
    material : Material
        Its contact modulus E* (Pa) sets the pressures p = (p/E*)·E* of :data:`LOADS`.
    unit, pixel_size, channel, level, periodic
        For a file: as for :func:`mcsim.studies.maps.contact.contact_map` (pixel size in m).
    tol : float
        Tolerance of the exact solves (:func:`mcsim.physics.bem.solve_contact`).
    surface : Surface, optional
        The GW surface whose radius is scaled (``mcsim ingest``'s, with its radius by
        height); default: the map's own GW surface (:func:`~mcsim.topography.mapsurface.map_surface`).
    progress : bool
        A progress bar over the exact solves (as ``mcsim contact``'s, on large maps).

    Returns
    -------
    Calibration

    Raises
    ------
    ParameterError
        No exact contact at the lowest load (the map too coarse for it).
    """
    from functools import cache

    loads = np.append(LOADS, EXTRAPOLATED_LOAD)  # ascending: the last solve warm-starts from 1e-2
    pressure = loads * material.E_star
    exact = contact_map(source, material, pressure, surface=surface, unit=unit,
                        pixel_size=pixel_size, channel=channel, level=level, periodic=periodic,
                        tol=tol, progress=progress)  # fmt: skip
    if not np.all(exact.area_fraction > 0):
        raise ParameterError(f"{exact.source}: no pixel in contact at p/E* = {LOADS[0]:g}: the map is too "
                             "coarse to calibrate on (refine it)")  # fmt: skip
    surface = exact.surface
    fitted = slice(0, LOADS.size)
    area = exact.area_fraction[fitted]

    @cache
    def errors(x: float) -> np.ndarray:
        return _errors(surface, material, pressure[fitted], area, math.exp(x))

    everyone = np.ones(LOADS.size, dtype=bool)
    x = _minimax_scale(errors, everyone, 0.0)
    loo_x = np.array([_minimax_scale(errors, everyone & (np.arange(LOADS.size) != k), x)
                      for k in range(LOADS.size)])  # fmt: skip
    loo_scale = np.exp(loo_x)
    loo_error = np.expm1([errors(float(xk))[k] for k, xk in enumerate(loo_x)])
    scale = math.exp(x)
    _, gw, gw_gap = gw_hertz(dataclasses.replace(surface, R=surface.R * scale), material, pressure)
    relative = gw / exact.area_fraction - 1
    return Calibration(
        radius_scale=scale, material=material.name, E_star=material.E_star, load=LOADS.copy(),
        exact_area=area, gw_area=gw[fitted],
        uncalibrated_area=gw_hertz(surface, material, pressure[fitted])[1],
        exact_gap=exact.mean_gap[fitted], gw_gap=gw_gap[fitted],
        in_sample_worst=float(np.max(np.abs(relative[fitted]))),
        in_sample_rms=float(np.sqrt(np.mean(relative[fitted] ** 2))),
        loo_scale=loo_scale, loo_error=loo_error, loo_worst=float(np.max(np.abs(loo_error))),
        loo_rms=float(np.sqrt(np.mean(loo_error**2))), extrapolated_load=EXTRAPOLATED_LOAD,
        extrapolated_exact_area=float(exact.area_fraction[-1]),
        extrapolated_gw_area=float(gw[-1]), extrapolated_error=float(relative[-1]),
        dx=exact.dx, periodic=exact.periodic,
    )  # fmt: skip

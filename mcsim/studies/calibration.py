"""GW calibrated on the exact elastic contact of its map: ``mcsim ingest --calibrate``.

GW's real contact area on a measured map is not the exact one (``mcsim contact``,
docs/contact.md): its summits do not interact and its summit radius is a sampled curvature.
:func:`calibrate` solves the map's frictionless, non-adhesive contact exactly at
:data:`LOADS` (p/E* = 1e-4 … 1e-2, five loads spaced evenly in log) and fits **one
summit-radius scale** s so that GW's Hertz area with radius s·R follows the exact area: the s
that makes the worst ratio |ln(A_GW/A_exact)| over the loads smallest (a one-parameter
minimax fit; GW's area at a fixed pressure grows about as √R). The surface file records s
with the loads, both areas and the worst and rms errors; every command that reads the file
then uses the radius s·R. The surface ``ingest`` calibrates carries a radius by height by
default (:class:`~mcsim.model.params.RadiusByHeight`, each band of summit heights its own
radius): s scales every band's radius.

What calibration does and does not fix
--------------------------------------
* It fixes the real contact area of non-adhesive contact over the fitted loads, at the map's
  pixel size, as well as one scale can: with one radius for every summit GW's area grows
  more slowly with load than the exact one (the taller summits are sharper), so one scale
  leaves an error that grows toward the ends of the range; a radius by height bends the
  curve (docs/contact.md: 4.6 % on the shipped map, against 13.8 %). The worst error is
  recorded and warned about above :data:`TARGET`.
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
from mcsim.studies.contact import contact_map, gw_hertz

#: Calibration loads p/E*: five, evenly spaced in log from 1e-4 to 1e-2.
LOADS = np.logspace(-4, -2, 5)
#: Worst relative area error above which the calibration is warned about.
TARGET = 0.10
#: Range searched for ln s (s from e^-5 to e^5).
LOG_SCALE_BOUND = 5.0


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
    worst, rms : float
        Largest and rms |A_GW/A_exact − 1| over the loads after calibration.
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
    worst: float
    rms: float
    dx: float
    periodic: bool

    def apply(self, surface: Surface) -> Surface:
        """``surface`` with its summit radius multiplied by :attr:`radius_scale`."""
        return dataclasses.replace(surface, R=surface.R * self.radius_scale)

    def warnings(self) -> list[str]:
        """A line if the worst error is above :data:`TARGET` (else empty)."""
        if self.worst <= TARGET:
            return []
        ratios = ", ".join(f"{r:.3g}" for r in self.gw_area / self.exact_area)
        return [f"calibrated GW's area is off the exact one by up to {self.worst:.1%} (> "
                f"{TARGET:.0%}; ratios {ratios} at p/E* = "
                f"{', '.join(f'{x:.3g}' for x in self.load)}): one radius scale cannot follow how "
                "the exact area grows with load on this map (with one radius for every summit, try "
                "--radius-by-height)"]  # fmt: skip

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
            f"calibrate  worst area error {self.worst:.1%}, rms {self.rms:.1%}",
            "calibrate  the mean gap is NOT calibrated: exact "
            + ", ".join(f"{g * 1e9:.4g}" for g in self.exact_gap) + " nm; GW calibrated "
            + ", ".join(f"{g * 1e9:.4g}" for g in self.gw_gap) + " nm",
        ]  # fmt: skip


def _errors(surface: Surface, material: Material, pressure, exact, scale: float) -> np.ndarray:
    """ln(A_GW/A_exact) at each pressure for the radius scale ``scale``."""
    scaled = dataclasses.replace(surface, R=surface.R * scale)
    return np.log(gw_hertz(scaled, material, pressure)[1] / exact)


def calibrate(
    path: str | Path,
    material: Material,
    *,
    unit: str | None = None,
    pixel_size: float | tuple[float, float] | None = None,
    channel: str | None = None,
    level: str | None = None,
    periodic: bool | None = None,
    tol: float = bem.TOL,
    surface: Surface | None = None,
) -> Calibration:
    """Fit GW's summit-radius scale to the exact contact of a map (module docstring).

    Parameters
    ----------
    path : path-like
        Height map, any format ``mcsim ingest`` reads.
    material : Material
        Its contact modulus E* (Pa) sets the pressures p = (p/E*)·E* of :data:`LOADS`.
    unit, pixel_size, channel, level, periodic
        As for :func:`mcsim.studies.contact.contact_map` (pixel size in m).
    tol : float
        Tolerance of the exact solves (:func:`mcsim.physics.bem.solve_contact`).
    surface : Surface, optional
        The GW surface whose radius is scaled (``mcsim ingest``'s, with its radius by
        height); default: the map's own GW surface (:func:`~mcsim.studies.contact.contact_map`).

    Returns
    -------
    Calibration

    Raises
    ------
    ParameterError
        No exact contact at the lowest load (the map too coarse for it).
    """
    from scipy import optimize

    pressure = LOADS * material.E_star
    exact = contact_map(path, material, pressure, unit=unit, pixel_size=pixel_size,
                        channel=channel, level=level, periodic=periodic, tol=tol)  # fmt: skip
    if not np.all(exact.area_fraction > 0):
        raise ParameterError(f"{path}: no pixel in contact at p/E* = {LOADS[0]:g}: the map is too "
                             "coarse to calibrate on (refine it)")  # fmt: skip
    surface = exact.surface if surface is None else surface
    area = exact.area_fraction
    best = optimize.minimize_scalar(
        lambda x: float(np.max(np.abs(_errors(surface, material, pressure, area, math.exp(x))))),
        bounds=(-LOG_SCALE_BOUND, LOG_SCALE_BOUND), method="bounded", options={"xatol": 1e-8},
    )  # fmt: skip
    scale = math.exp(best.x)
    _, gw, gw_gap = gw_hertz(dataclasses.replace(surface, R=surface.R * scale), material, pressure)
    relative = gw / area - 1
    return Calibration(
        radius_scale=scale, material=material.name, E_star=material.E_star, load=LOADS.copy(),
        exact_area=area, gw_area=gw, uncalibrated_area=gw_hertz(surface, material, pressure)[1],
        exact_gap=exact.mean_gap, gw_gap=gw_gap,
        worst=float(np.max(np.abs(relative))), rms=float(np.sqrt(np.mean(relative**2))),
        dx=exact.dx, periodic=exact.periodic,
    )  # fmt: skip

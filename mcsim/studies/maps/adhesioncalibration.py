"""GW's adhesion calibrated on the exact adhesive contact of its map: ``ingest --calibrate --w``.

:mod:`mcsim.studies.maps.calibration` fits GW's real contact area; this module then asks whether
GW's **pull-off** on the same (area-calibrated) surface follows the exact one, and fits at most
one adhesion parameter per law set so that it does.

The exact side
--------------
The map's exact adhesive approach and retraction (:mod:`mcsim.physics.adhesivebem`, the
machinery of :func:`mcsim.studies.maps.adhesivecontact.adhesive_contact`: the positions of
:func:`~mcsim.studies.maps.adhesivecontact.positions`, the pull-off located between the steps) is
solved with the exponential law φ = −w e^{−g/ρ} (work of adhesion w, range ρ) at each preload
p/E* of :data:`PRELOADS` (1e-4, 1e-3, 1e-2: the decades of the area calibration's loads; three,
not five, because one cycle costs seconds), in :data:`STEPS` steps, and once more at
:data:`EXTRAPOLATED_PRELOAD` = 3e-2 for the out-of-sample check. Its pull-off P_exact(p) is
the most tensile mean pressure of the retraction, Pa.

GW's side and the one parameter
-------------------------------
Each law set of :data:`~mcsim.studies.maps.adhesivecontact.GW_LAWS` (jkr, dmt, maugis-dugdale)
takes, as ``adhesive_contact`` gives it, the Dugdale range of the same law (z0 = ρ/0.97), is
pressed on its mean curve to the largest mean pressure of the exact approach (load control)
and retracted; its pull-off is the most tensile mean load of the retraction
(:func:`gw_pull_off`). The one parameter fitted per law set is an **effective work of
adhesion** w_GW = c·w, c the factor: the minimax fit over the preloads of
|ln(P_GW(c·w)/P_exact)| (the root of max plus min of the log errors, as for the radius scale; each law set's
pull-off grows with w). The
factor, not the range, because it is the one parameter every law set has (jkr has no range)
and it moves the pull-off of each in proportion (JKR's and DMT's are ∝ w per summit); a range
fitted instead would compare dmt and maugis-dugdale on one parameter and jkr on none.

The law set chosen is the one whose fitted worst error in sample is smallest (ties within
1e-3, the fit's resolution, go to the smaller out-of-sample error, then to the order jkr, dmt,
maugis-dugdale).

Out of sample
-------------
As for the area: **leave-one-out** over the preloads (c refitted without preload k, GW's error
at k) and **one preload outside the fitted range**, p/E* = 3e-2 (one exact cycle more). Both
are recorded for every law set; :meth:`AdhesionCalibration.warnings` judges the chosen law's
larger out-of-sample error against :data:`TARGET` (20 %) and says, with the numbers, when no
law set gets there.

What it does not do
-------------------
The factor is recorded in the surface file (``[surface.adhesion_calibration]``) but **not
applied**: ``mcsim analytic`` and ``adhesion`` on the file still use the material's w and
z0. Give ``--material`` a w of c·w and z0 of ρ/0.97 to use it. Only the pull-off is fitted,
not the work of separation or the hysteresis.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface
from mcsim.physics import adhesivebem
from mcsim.physics.interactions import Exponential
from mcsim.store.config import ADHESION_CALIBRATION_KEYS
from mcsim.studies.maps.adhesivecontact import GW_LAWS, H0_PER_Z0, exact_cycle
from mcsim.studies.maps.calibration import short

#: Preloads p/E* of the fit: the decades of the area calibration's loads.
PRELOADS = np.logspace(-4, -2, 3)
#: Preload p/E* of the extrapolation check, above the fitted range.
EXTRAPOLATED_PRELOAD = 3e-2
#: Worst out-of-sample relative pull-off error above which the calibration is warned about.
TARGET = 0.20
#: Positions of the flat on approach in each exact cycle (the retraction revisits them).
STEPS = 16
#: Default range of the exponential law without a z0 in the material, m.
DEFAULT_RANGE = 1e-9
#: Points of GW's mean curves on which the turn and the pull-off are bracketed.
GRID = 300
#: Points between the bracketing neighbours of :data:`GRID` in :func:`gw_pull_off`.
FINE = 100

#: Tolerance of the fitted ln c: 1e-4 relative in c, far below the errors judged (20 %),
#: and each GW evaluation costs about a second.
XTOL = 1e-4
#: Range searched for ln c (c from 1/100 to 100).
LOG_FACTOR_BOUND = math.log(100.0)

#: Keys of ``[surface.adhesion_calibration]`` (:meth:`AdhesionCalibration.toml_lines`).
FILE_KEYS = ADHESION_CALIBRATION_KEYS


@dataclass(frozen=True)
class LawFit:
    """One law set's effective work-of-adhesion factor fitted to the exact pull-offs.

    Attributes
    ----------
    law : str
        The law set.
    factor : float
        c: GW uses w_GW = c·w, dimensionless.
    gw_pull_off : ndarray
        GW's pull-off with c·w at each preload, Pa (tensile magnitude).
    in_sample_worst : float
        Largest |P_GW/P_exact − 1| over the fitted preloads, dimensionless.
    loo_factor : ndarray
        At each preload k, c fitted to the other preloads, dimensionless.
    loo_error : ndarray
        At each preload k, P_GW/P_exact − 1 with ``loo_factor[k]`` (out of sample), signed.
    extrapolated_gw_pull_off : float
        GW's pull-off with c·w at the extrapolated preload, Pa.
    extrapolated_error : float
        P_GW/P_exact − 1 there (out of sample: outside the fitted range), signed.
    """

    law: str
    factor: float
    gw_pull_off: np.ndarray
    in_sample_worst: float
    loo_factor: np.ndarray
    loo_error: np.ndarray
    extrapolated_gw_pull_off: float
    extrapolated_error: float

    @property
    def loo_worst(self) -> float:
        """Largest |``loo_error``|."""
        return float(np.max(np.abs(self.loo_error)))

    @property
    def out_of_sample_worst(self) -> float:
        """The larger of the worst leave-one-out error and the extrapolated one (absolute)."""
        return max(self.loo_worst, abs(self.extrapolated_error))

    def line(self) -> str:
        """One line for a terminal."""
        return (f"calibrate adhesion:   {self.law:<15} w x {self.factor:<7.3g} in sample "
                f"{self.in_sample_worst * 100:5.1f} %, leave-one-out {self.loo_worst * 100:5.1f} %, "
                f"extrapolated {self.extrapolated_error * 100:+6.1f} %")  # fmt: skip


@dataclass(frozen=True)
class AdhesionCalibration:
    """GW's pull-off calibrated on exact adhesive cycles of the map (module docstring).

    Attributes
    ----------
    law : str
        The law set chosen (smallest worst error in sample).
    w, range : float
        The exponential law of the exact cycles: work of adhesion, J/m², and range ρ, m.
    material : str
        Name of the material; ``E_star`` its contact modulus, Pa.
    preload : ndarray
        The fitted preloads p/E*, dimensionless.
    exact_pull_off : ndarray
        The exact pull-off at each, Pa (tensile magnitude).
    fits : tuple of LawFit
        Every law set's fit, in :data:`GW_LAWS` order.
    extrapolated_preload : float
        p/E* of the extrapolation check.
    extrapolated_exact_pull_off : float
        The exact pull-off there, Pa.
    dx : float
        Pixel size of the map, m; ``periodic`` whether it was solved as periodic; ``steps``
        the positions of each exact cycle.
    """

    law: str
    w: float
    range: float
    material: str
    E_star: float
    preload: np.ndarray
    exact_pull_off: np.ndarray
    fits: tuple[LawFit, ...]
    extrapolated_preload: float
    extrapolated_exact_pull_off: float
    dx: float
    periodic: bool
    steps: int

    @property
    def best(self) -> LawFit:
        """The chosen law set's fit."""
        return next(f for f in self.fits if f.law == self.law)

    def warnings(self) -> list[str]:
        """A line if the chosen law's out-of-sample error is above :data:`TARGET`."""
        b = self.best
        if b.out_of_sample_worst <= TARGET:
            return []
        others = [f for f in self.fits if f.out_of_sample_worst <= TARGET]
        which = (f"{', '.join(f.law for f in others)} would get there out of sample but fits "
                 "worse in sample" if others else "no law set gets there")  # fmt: skip
        ratios = ", ".join(f"{r:.3g}" for r in b.gw_pull_off / self.exact_pull_off)
        return [f"calibrated GW's pull-off ({b.law}, w x {b.factor:.3g}) is off the exact one out "
                f"of sample by up to {b.out_of_sample_worst:.1%}, above {TARGET:.0%} (leave-one-out "
                f"worst {b.loo_worst:.1%}; at p/E* = {short(self.extrapolated_preload)} "
                f"{b.extrapolated_error:+.1%}; in sample {b.in_sample_worst:.1%}, ratios {ratios} at "
                f"p/E* = {', '.join(f'{x:.3g}' for x in self.preload)}): {which}; one work-of-"
                "adhesion factor cannot follow how the exact pull-off changes with preload on "
                "this map"]  # fmt: skip

    def lines(self) -> list[str]:
        """What was fitted, for a terminal."""
        b = self.best
        return [
            f"calibrate adhesion: law {b.law}, w x {b.factor:.3g}; pull-off error in sample "
            f"{b.in_sample_worst * 100:.1f} %, leave-one-out {b.loo_worst * 100:.1f} %, at p/E* = "
            f"{short(self.extrapolated_preload)} {b.extrapolated_error * 100:+.1f} %",
            f"calibrate adhesion:   exact cycles (exponential, w = {self.w:.4g} J/m^2, range "
            f"{self.range * 1e9:.4g} nm, {self.steps} steps) at p/E* = "
            f"{', '.join(f'{x:.3g}' for x in self.preload)}, {short(self.extrapolated_preload)}: "
            "pull-off " + ", ".join(f"{p / 1e3:.4g}" for p in self.exact_pull_off)
            + f", {self.extrapolated_exact_pull_off / 1e3:.4g} kPa",
            *(f.line() for f in self.fits),
            "calibrate adhesion:   recorded, not applied: analytic and adhesion still use the "
            "material's w and z0",
        ]  # fmt: skip

    def toml_lines(self) -> list[str]:
        """The ``[surface.adhesion_calibration]`` table."""

        def numbers(values, scale=1.0) -> str:
            return "[" + ", ".join(f"{float(v) * scale:.6g}" for v in values) + "]"

        b = self.best
        return [
            "",
            "# GW's pull-off calibrated on exact adhesive cycles of the map (mcsim ingest",
            "# --calibrate --w): the law set and work-of-adhesion factor (w_GW = factor x w, z0 =",
            "# range/0.97) that bring GW's pull-off nearest the exact one; RECORDED, NOT APPLIED.",
            "# Per law set (in the order of laws): factor, GW's pull-off at each preload, errors",
            "# in sample, leave-one-out and at one preload above the fitted range.",
            "[surface.adhesion_calibration]",
            f'law = "{self.law}"',
            f"factor = {b.factor:.12g}",
            'interaction = "exponential"',
            f'w = "{self.w:.12g} J/m^2"',
            f'range = "{self.range * 1e9:.12g} nm"',
            f'material = "{self.material}"',
            f'E_star = "{self.E_star / 1e9:.12g} GPa"',
            f'pixel_size = "{self.dx * 1e9:.12g} nm"',
            f"periodic = {'true' if self.periodic else 'false'}",
            f"steps = {self.steps}",
            f"preload = {numbers(self.preload)}  # p/E*",
            f"exact_pull_off_kPa = {numbers(self.exact_pull_off, 1e-3)}",
            "laws = [" + ", ".join(f'"{f.law}"' for f in self.fits) + "]",
            "gw_pull_off_kPa = [" + ", ".join(numbers(f.gw_pull_off, 1e-3) for f in self.fits)
            + "]",
            f"factors = {numbers([f.factor for f in self.fits])}",
            f"in_sample_worst_error = {numbers([f.in_sample_worst for f in self.fits])}",
            "loo_factor = [" + ", ".join(numbers(f.loo_factor) for f in self.fits) + "]",
            "loo_error = [" + ", ".join(numbers(f.loo_error) for f in self.fits) + "]",
            f"loo_worst_error = {numbers([f.loo_worst for f in self.fits])}",
            f"extrapolated_preload = {self.extrapolated_preload:.6g}  # p/E*",
            f"extrapolated_exact_pull_off_kPa = {self.extrapolated_exact_pull_off / 1e3:.6g}",
            "extrapolated_gw_pull_off_kPa = "
            + numbers([f.extrapolated_gw_pull_off for f in self.fits], 1e-3),
            f"extrapolated_error = {numbers([f.extrapolated_error for f in self.fits])}",
        ]  # fmt: skip

    @classmethod
    def from_file(cls, path: str | Path) -> AdhesionCalibration:
        """The adhesion calibration a surface file records (6 significant digits; the chosen
        factor to 12).

        Raises
        ------
        ParameterError
            No ``[surface.adhesion_calibration]`` table, or one with keys missing.
        """
        from mcsim.model.units import parse_quantity
        from mcsim.store.config import adhesion_calibration_in_surface_file

        t = adhesion_calibration_in_surface_file(path)
        if t is None:
            raise ParameterError(f"{path}: no [surface.adhesion_calibration] table (mcsim "
                                 "ingest --calibrate --w)")  # fmt: skip
        missing = sorted(set(FILE_KEYS) - set(t))
        if missing:
            raise ParameterError(f"{path}: [surface.adhesion_calibration] has no "
                                 f"{', '.join(missing)}")  # fmt: skip
        fits = tuple(
            LawFit(
                law=law,
                factor=float(t["factors"][i]),
                gw_pull_off=np.asarray(t["gw_pull_off_kPa"][i], dtype=float) * 1e3,
                in_sample_worst=float(t["in_sample_worst_error"][i]),
                loo_factor=np.asarray(t["loo_factor"][i], dtype=float),
                loo_error=np.asarray(t["loo_error"][i], dtype=float),
                extrapolated_gw_pull_off=float(t["extrapolated_gw_pull_off_kPa"][i]) * 1e3,
                extrapolated_error=float(t["extrapolated_error"][i]),
            )
            for i, law in enumerate(t["laws"])
        )
        fits = tuple(dataclasses.replace(f, factor=float(t["factor"])) if f.law == t["law"]
                     else f for f in fits)  # fmt: skip
        return cls(law=t["law"], w=parse_quantity(t["w"], "energy_per_area", "w"),
                   range=parse_quantity(t["range"], "length", "range"), material=t["material"],
                   E_star=parse_quantity(t["E_star"], "pressure", "E_star"),
                   preload=np.asarray(t["preload"], dtype=float),
                   exact_pull_off=np.asarray(t["exact_pull_off_kPa"], dtype=float) * 1e3,
                   fits=fits, extrapolated_preload=float(t["extrapolated_preload"]),
                   extrapolated_exact_pull_off=float(t["extrapolated_exact_pull_off_kPa"]) * 1e3,
                   dx=parse_quantity(t["pixel_size"], "length", "pixel_size"),
                   periodic=bool(t["periodic"]), steps=int(t["steps"]))  # fmt: skip


#: Largest work of adhesion, J/m² (100): far above any solid pair's, 2γ ≲ 7 J/m² for the
#: metals of highest surface energy (Tyson & Miller 1977); a larger one is a unit mistake, and
#: its law's curvature w/ρ² overflows the exact solves.
MAX_W = 100.0


def check_inputs(w: float, range_: float | None) -> None:
    """Refuse a work of adhesion or a range that is not a finite number > 0, or a work above
    :data:`MAX_W` (one line naming it)."""
    for name, value, unit in (("w", w, "J/m^2"), ("range", range_, "m")):
        if value is None and name == "range":
            continue
        if not (isinstance(value, int | float) and math.isfinite(value) and value > 0):
            raise ParameterError(
                f"{name} = {value!r} {unit} is out of range (allowed: a number > 0)"
            )
    if w > MAX_W:
        raise ParameterError(f"w = {w!r} J/m^2 is out of range (allowed: 0 < w <= {MAX_W:g} "
                             "J/m^2)")  # fmt: skip


def exact_pull_off(z, pixels, E_star: float, law: Exponential, pressure: float, *,
                   periodic: bool, steps: int = STEPS, tol: float = adhesivebem.TOL,
                   max_iter: int = adhesivebem.MAX_ITER) -> tuple[float, float]:  # fmt: skip
    """The exact adhesive cycle of heights ``z`` (m, about their mean) to the depth where the
    non-adhesive contact carries ``pressure`` (Pa): its refined pull-off (Pa, tensile
    magnitude) and the largest mean pressure of its approach (Pa)."""
    cycle, pull_off, _ = exact_cycle(z, pixels, E_star, law, pressure, periodic=periodic,
                                     steps=steps, tol=tol, max_iter=max_iter)  # fmt: skip
    return pull_off, max(s.mean_pressure for s in cycle.approach)


def _top(surface: Surface, material: Material, law: str) -> float:
    """h above which no summit feels the law (dmt's tail: 50 z0 beyond the highest summit)."""
    from mcsim.physics.laws import get_law_set

    edges = get_law_set(law).edges_for(surface, material)
    heights = surface.heights
    highest = float(heights.edges[-1]) if hasattr(heights, "edges") else 8.0
    reach = min(edges.reach, edges.break_off, -50 * (material.z0 or 0.0) if law == "dmt" else 0.0)
    return highest - reach / surface.sigma


def _fine(lo: float, hi: float) -> np.ndarray:
    return np.linspace(lo, hi, FINE)


def gw_pull_off(surface: Surface, material: Material, law: str, pressures) -> np.ndarray:
    """GW's pull-off at each preload, Pa (tensile magnitude, 0 if never tensile), for the law
    set ``law`` with the material's w (``gamma``) and z0, pressed on its mean curve to each of
    ``pressures`` (Pa) and retracted.

    The turn: from the top down, the first separation on the approach branch whose mean load
    reaches the preload (load control), bracketed on :data:`GRID` points from the top to 6 σ
    below the lowest summit, then on :data:`FINE` points between the bracket, then linear
    between those. The pull-off: the most tensile mean load of the retraction from that turn,
    on :data:`GRID` points and again on :data:`FINE` points between the neighbours of the
    most tensile one (the spacing then ~1e-3 σ; the minimum may sit on a kink, where a jump
    ends, so no smooth refinement).
    """
    from mcsim.physics.analytic import analytic_curves

    def load(h, branch, turn=None):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return analytic_curves(surface, material, np.atleast_1d(h), law, branch=branch,
                             turn=turn).load * material.K  # fmt: skip

    top = _top(surface, material, law)
    heights = surface.heights
    bottom = (float(heights.edges[0]) if hasattr(heights, "edges") else -8.0) - 6.0
    h = np.linspace(top, bottom, GRID)  # downward, to 6 sigma below the lowest summit
    approach = load(h, "approach")
    out = []
    for pressure in np.atleast_1d(pressures):
        above = approach >= pressure
        if not above.any():
            raise ParameterError(f"law {law}: GW's approach never carries {pressure:g} Pa above "
                                 "6 sigma below its lowest summit")  # fmt: skip
        i = int(np.argmax(above))
        turn = h[0]
        if i > 0:
            fine = _fine(h[i - 1], h[i])
            f = load(fine, "approach") - pressure
            j = max(int(np.argmax(f >= 0)), 1)
            turn = fine[j - 1] + (fine[j] - fine[j - 1]) * f[j - 1] / (f[j - 1] - f[j])
        grid = np.linspace(turn, max(top, turn + 1e-6), GRID)
        values = load(grid, "retract", turn)
        k = int(np.argmin(values))
        if values[k] < 0:
            fine = _fine(grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)])
            values = np.append(values, load(fine, "retract", turn))
        out.append(max(-float(values.min()), 0.0))
    return np.array(out)


def _minimax(errors, keep: np.ndarray, start: float) -> float:
    """ln c of the minimax fit over the preloads ``keep``: the root of g = max e + min e.

    ``errors(x)`` gives e_k = ln(P_GW/P_exact) at every preload for c = e^x; each grows with x
    (more w, more pull-off), so max |e_k| is smallest where g, growing with x, crosses zero
    (as :func:`mcsim.studies.maps.calibration._minimax_scale`). The pull-off grows about as c^a
    with a between 1/2 and 1, so from ``start`` the root lies within −2 g: bracketed there
    (widened by doubling if not) and found by Brent's method to :data:`XTOL`.
    """
    from scipy import optimize

    def g(x: float) -> float:
        e = errors(x)[keep]
        return float(e.max() + e.min())

    g0 = g(start)
    if abs(g0) <= XTOL:
        return start
    step = -2 * g0
    while True:
        b = min(max(start + step, -LOG_FACTOR_BOUND), LOG_FACTOR_BOUND)
        if (g(b) > 0) != (g0 > 0):
            return optimize.brentq(g, min(start, b), max(start, b), xtol=XTOL)
        if abs(b) == LOG_FACTOR_BOUND:
            return b
        step *= 2


def _fit(gw, exact: np.ndarray, n: int) -> tuple[float, np.ndarray, np.ndarray]:
    """ln c of the minimax fit over the ``n`` fitted preloads, and the leave-one-out ln c and
    signed relative errors; ``gw(x)`` gives GW's pull-off at every preload for c = e^x."""
    from functools import cache

    @cache
    def errors(x: float) -> np.ndarray:
        return np.log(np.maximum(gw(x)[:n], 1e-300) / exact[:n])

    everyone = np.ones(n, dtype=bool)
    start = -float(np.mean(errors(0.0)))  # pull-off about ∝ w: one step to near the root
    x = _minimax(errors, everyone, start)
    loo_x = np.array([_minimax(errors, everyone & (np.arange(n) != k), x) for k in range(n)])
    loo_error = np.expm1([errors(float(xk))[k] for k, xk in enumerate(loo_x)])
    return x, loo_x, loo_error


def calibrate_adhesion(
    z: np.ndarray,
    pixels: tuple[float, float],
    material: Material,
    surface: Surface,
    *,
    w: float,
    range_: float | None = None,
    periodic: bool,
    preloads: np.ndarray = PRELOADS,
    extrapolated: float = EXTRAPOLATED_PRELOAD,
    steps: int = STEPS,
    progress: bool = False,
) -> AdhesionCalibration:
    """Fit GW's pull-off to exact adhesive cycles of a levelled map (module docstring).

    Parameters
    ----------
    z : ndarray
        The levelled heights, m (finite; their mean is removed here).
    pixels : (float, float)
        Pixel size (dx, dy), m.
    material : Material
        Its E* (Pa) sets the preloads p = (p/E*)·E*.
    surface : Surface
        The GW surface (``ingest``'s, area-calibrated).
    w : float
        Work of adhesion of the exponential law, J/m², > 0.
    range_ : float, optional
        Its range ρ, m, > 0 (default the material's z0, else :data:`DEFAULT_RANGE`).
    periodic : bool
        Solve the map as periodic.
    preloads : ndarray
        The fitted preloads p/E*, ascending, at least two.
    extrapolated : float
        The out-of-sample preload p/E*, above them.
    steps : int
        Positions of each exact cycle.
    progress : bool
        A progress bar over the exact cycles on stderr.

    Returns
    -------
    AdhesionCalibration

    Raises
    ------
    ParameterError
        Bad inputs (naming the field), a map with missing pixels, an exact retraction that is
        never tensile, or a solve that did not converge.
    """
    check_inputs(w, range_)
    range_ = range_ if range_ is not None else (material.z0 or DEFAULT_RANGE)
    preloads = np.asarray(preloads, dtype=float)
    if not (preloads.size >= 2 and np.all(np.diff(preloads) > 0) and extrapolated > preloads[-1]):
        raise ParameterError(f"preloads = {preloads!r} must be >= 2 ascending p/E* below the "
                             f"extrapolated one {extrapolated!r}")  # fmt: skip
    if not np.all(np.isfinite(z)):
        raise ParameterError("the map has missing pixels: fill or crop them for a contact solve")
    z = z - z.mean()
    law = Exponential(w, range_)
    adhesivebem.check_inputs(z, pixels, material.E_star, law)
    all_loads = np.append(preloads, extrapolated)
    exact, reached = np.empty(all_loads.size), np.empty(all_loads.size)
    cycles = enumerate(all_loads)
    if progress:
        import sys

        from tqdm import tqdm

        cycles = tqdm(cycles, total=all_loads.size, unit=" cycles", file=sys.stderr, leave=False)
    for k, p in cycles:
        exact[k], reached[k] = exact_pull_off(z, pixels, material.E_star, law,
                                              p * material.E_star, periodic=periodic, steps=steps)  # fmt: skip
    if not np.all(exact > 0):
        bad = ", ".join(f"{x:.3g}" for x in all_loads[exact <= 0])
        raise ParameterError(f"the exact retraction is never tensile at p/E* = {bad}: no "
                             "pull-off to calibrate GW's on")  # fmt: skip
    n = preloads.size
    fits = []
    for name in GW_LAWS:

        @functools.cache  # the fit's last step is one of its points: not solved again below
        def gw(x: float, name=name) -> np.ndarray:
            m = dataclasses.replace(material, gamma=math.exp(x) * w, z0=range_ / H0_PER_Z0)
            return gw_pull_off(surface, m, name, reached)

        x, loo_x, loo_error = _fit(gw, exact, n)
        pulls = gw(x)
        relative = pulls / exact - 1
        fits.append(LawFit(law=name, factor=math.exp(x), gw_pull_off=pulls[:n],
                           in_sample_worst=float(np.max(np.abs(relative[:n]))),
                           loo_factor=np.exp(loo_x), loo_error=loo_error,
                           extrapolated_gw_pull_off=float(pulls[-1]),
                           extrapolated_error=float(relative[-1])))  # fmt: skip
    # ties below the fit's resolution (XTOL, the grids: 1e-3) go to the smaller error out of
    # sample, then to the order of GW_LAWS
    best = min(fits, key=lambda f: (round(f.in_sample_worst, 3), round(f.out_of_sample_worst, 3)))
    return AdhesionCalibration(
        law=best.law, w=float(w), range=float(range_), material=material.name,
        E_star=material.E_star, preload=preloads.copy(), exact_pull_off=exact[:n],
        fits=tuple(fits), extrapolated_preload=float(extrapolated),
        extrapolated_exact_pull_off=float(exact[-1]), dx=float(pixels[0]),
        periodic=bool(periodic), steps=steps,
    )  # fmt: skip

"""Is GW's adhesion right on my map? The exact adhesive contact of a height map beside GW's.

:func:`adhesive_contact` reads a height map as ``mcsim contact`` does, presses it against a
rigid flat and pulls it off again under displacement control with a gap-dependent interaction
law (:mod:`mcsim.physics.adhesivebem`: FFT boundary elements, both branches, every jump), and
puts beside the exact answer GW's on the same map, for every adhesive law set.

The cycle
---------
The flat starts where nothing acts yet (the map's highest pixel plus :data:`START_RANGES`
ranges of the interaction), comes down in :data:`TAIL` steps to :data:`NEAR_RANGES` ranges
above it (where the attraction is still weak), and from there in equal steps (``steps`` in
all) to the position where the
non-adhesive contact carries ``pressure`` (:func:`mcsim.physics.bem.solve_contact`; the
adhesive contact there carries somewhat less, reported), then goes back up through the same
positions. Per step: the mean pressure (compressive positive), the real contact area and the
area within the law's range, the patches, the mean gap. Of the retraction: the **pull-off**
(the most tensile mean pressure, Pa, located between the steps by :data:`REFINE` more solves
between the neighbours of the most tensile step, warm-started on the retraction branch from
the step below it), the **work of separation** (the tensile part of the
mean pressure integrated over the retraction, J/m²), the **hysteresis** (the energy the
cycle dissipates, J/m²) and the jumps where a branch ends. Every step must converge: a solve
that does not is an error, never a number.

GW on the same map
------------------
The GW surface is ``mcsim ingest``'s (direct-route summits and their measured heights). Each
adhesive law set (jkr, dmt, maugis-dugdale) takes the interaction's work of adhesion w and, as
its range, the Dugdale range of the same largest traction: maugis-dugdale's h0 = 0.97 z0 set
to the law's range (so z0 = range/0.97, which dmt's tail uses too). GW is pressed on its mean
curve to the same largest mean pressure the exact approach reached (load control), retracted,
and its pull-off and work of separation (:func:`mcsim.physics.adhesion.adhesion_summary`)
stand beside the exact ones with their ratios.

Stickiness
----------
The map's stickiness diagnostics for the interaction (:func:`mcsim.physics.stickiness.stickiness`:
Pastewka–Robbins with its validity, Persson–Tosatti, Müser's Tabor parameter, the mesh
criterion) are reported, with a warning where the grid or the model cannot be trusted.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface
from mcsim.physics import adhesivebem, adhesivecycle, bem
from mcsim.physics.adhesivecycle import AdhesiveCycle
from mcsim.physics.interactions import Exponential, Interaction, MaugisDugdale
from mcsim.physics.stickiness import Stickiness, stickiness
from mcsim.topography.maps import as_map
from mcsim.topography.mapsurface import map_surface
from mcsim.topography.readers import HeightMap
from mcsim.topography.readers.base import FacingMap

#: Interaction laws by name (``--interaction``).
INTERACTIONS = {"exponential": Exponential, "maugis-dugdale": MaugisDugdale}
#: GW's adhesive law sets compared with the exact solution.
GW_LAWS = ("jkr", "dmt", "maugis-dugdale")
#: The approach starts this many ranges above the highest pixel (exponential: e^-20 of w) ...
START_RANGES = {"exponential": 20.0, "maugis-dugdale": 2.0}
#: ... comes down to this many ranges above it in :data:`TAIL` steps, geometric in the gap to
#: the highest pixel, and from there to the deepest position in equal steps.
NEAR_RANGES = {"exponential": 4.0, "maugis-dugdale": 1.0}
TAIL = 4
#: Maugis–Dugdale's h0 over z0 (:mod:`mcsim.physics.laws.maugis_dugdale`).
H0_PER_Z0 = 0.97
#: HDF5 layout version of ``mcsim contact --adhesion --out`` files.
SCHEMA = 1
#: Default number of positions of the flat on approach (and again on retraction).
STEPS = 30
#: Solves between the neighbours of the most tensile retraction step (module docstring).
REFINE = 12


@dataclass(frozen=True)
class GWAdhesion:
    """GW's adhesion on the map for one law set, pressed to the exact approach's largest load.

    Attributes
    ----------
    law : str
        The law set.
    turn : float
        Its closest approach h = d/σ.
    pull_off : float
        Pull-off pressure, Pa (> 0: tensile magnitude; 0 if it never pulls).
    work_of_separation : float
        The tensile part of its mean retraction load integrated from the turn outward,
        −∫ min(p, 0) dd, J/m²: the exact cycle's definition (not the adhesion summary's
        signed work, which also gives back the elastic energy of the preload).
    position, pressure : ndarray
        Its mean retraction curve: the flat's height above the map's mean plane (σh plus
        the summits' offset above that plane, m) and the mean pressure (Pa, compressive
        positive), from the turn to where no summit pulls.
    """

    law: str
    turn: float
    pull_off: float
    work_of_separation: float
    position: np.ndarray = field(repr=False, default_factory=lambda: np.empty(0))
    pressure: np.ndarray = field(repr=False, default_factory=lambda: np.empty(0))


@dataclass(frozen=True)
class AdhesiveContactResult:
    """The exact adhesive cycle of a map and GW's adhesion on it (module docstring).

    Attributes
    ----------
    source : Path
        The map file.
    channel, level : str
        Its channel and the levelling applied.
    dx, dy : float
        Pixel size, m: every exact number belongs to it.
    shape : (int, int)
        Map shape (rows, columns).
    periodic : bool
        Solved as periodic (else zero-padded).
    periodic_reason : str
        Why.
    E_star : float
        Contact modulus, Pa.
    interaction : MaugisDugdale or Exponential
        The law of the exact solve (w J/m², range m).
    pressure : float
        The non-adhesive pressure that set the deepest position, Pa.
    cycle : AdhesiveCycle
        The exact approach and retraction (:func:`mcsim.physics.adhesivecycle.cycle`).
    pull_off : float
        The most tensile mean pressure of the retraction, located between its steps (module
        docstring), Pa (> 0: tensile magnitude; 0 if never tensile).
    pull_off_position : float
        Where, m (NaN if never tensile).
    gw : tuple of GWAdhesion
        GW's answer per adhesive law set.
    surface : Surface
        The GW surface of the map.
    stickiness : Stickiness
        The map's stickiness diagnostics for the interaction.
    fields : dict or None
        ``"gap"``, ``"pressure"`` (m, Pa), each (steps, rows, columns) float32, approach then
        retraction; only when kept.
    facing : FacingMap or None
        A counter-surface's map facing this one, turned over: the map solved is their gap.
    subpixel : int
        Points k × k per pixel over which the interaction was integrated (1: the centres).
    """

    source: Path
    channel: str
    level: str
    dx: float
    dy: float
    shape: tuple[int, int]
    periodic: bool
    periodic_reason: str
    E_star: float
    interaction: Interaction
    pressure: float
    cycle: AdhesiveCycle
    pull_off: float
    pull_off_position: float
    gw: tuple[GWAdhesion, ...]
    surface: Surface
    stickiness: Stickiness
    fields: dict | None = field(default=None, repr=False)
    facing: FacingMap | None = None
    subpixel: int = 1

    def __repr__(self) -> str:
        """A few lines, as in a notebook: the map, the law, the exact and GW's pull-offs."""
        law, s = self.interaction, self.summary()
        gw = ", ".join(f"{g.law} {g.pull_off:.3g} Pa ({s['gw'][g.law]['pull_off_ratio']:.3g}x)"
                       for g in self.gw)  # fmt: skip
        return (f"AdhesiveContactResult({self.source.name}: {self.shape[1]} x {self.shape[0]} "
                f"pixels of {self.dx * 1e9:.4g} nm, {self.law_name} law w = {law.w:.4g} J/m^2, "
                f"range {law.range * 1e9:.4g} nm; {len(self.cycle.approach)} steps to "
                f"{self.max_pressure:.4g} Pa; exact pull-off {self.pull_off:.4g} Pa, work of "
                f"separation {s['work_of_separation']:.4g} J/m^2; GW: {gw})")  # fmt: skip

    @property
    def law_name(self) -> str:
        """The interaction's name (``exponential`` or ``maugis-dugdale``)."""
        return next(k for k, v in INTERACTIONS.items() if isinstance(self.interaction, v))

    @property
    def max_pressure(self) -> float:
        """The largest mean pressure of the exact approach, Pa (GW is pressed to it)."""
        return max(s.mean_pressure for s in self.cycle.approach)

    def columns(self) -> dict[str, np.ndarray]:
        """Per step, approach then retraction: ``branch`` and the exact numbers, SI."""
        steps = (*self.cycle.approach, *self.cycle.retraction)
        n = len(self.cycle.approach)
        return {
            "branch": np.array(["approach"] * n + ["retract"] * (len(steps) - n)),
            "position": np.array([s.position for s in steps]),
            "mean_gap": np.array([s.mean_gap for s in steps]),
            "pressure": np.array([s.mean_pressure for s in steps]),
            "area_fraction": np.array([s.contact_fraction for s in steps]),
            "attractive_fraction": np.array([s.attractive_fraction for s in steps]),
            "patches": np.array([s.patches for s in steps], dtype=int),
            "iterations": np.array([s.iterations for s in steps], dtype=int),
        }

    def summary(self) -> dict:
        """The cycle's numbers and GW's beside them (SI), as JSON-ready floats."""
        c = self.cycle
        exact_pull = self.pull_off
        out = {
            "pull_off": exact_pull,
            "pull_off_position": self.pull_off_position,
            "work_of_separation": c.work_of_separation,
            "approach_work": c.approach_work,
            "hysteresis": c.hysteresis,
            "max_pressure": self.max_pressure,
            "jumps": [dataclasses.asdict(j) for j in c.jumps],
            "gw": {},
        }
        for g in self.gw:
            out["gw"][g.law] = {
                "pull_off": g.pull_off,
                "work_of_separation": g.work_of_separation,
                "turn": g.turn,
                "pull_off_ratio": _ratio(g.pull_off, exact_pull),
                "work_ratio": _ratio(g.work_of_separation, c.work_of_separation),
            }
        return out

    def warnings(self) -> list[str]:
        """Where the grid, the model or the comparison cannot be trusted: one line each."""
        lines = list(self.stickiness.warnings())
        if not self.cycle.jumps:
            lines.append(
                "no jump between the steps: the branches may not end here (weak adhesion, "
                "no hysteresis), or the steps are too coarse to see where they do (more --steps)"
            )
        if self.summary()["pull_off"] == 0:
            lines.append("the exact retraction is never tensile: no pull-off to compare GW's with")
        return lines

    def write(self, path: str | Path, *, command: str = "", overwrite: bool = False) -> Path:
        """Write the steps, the summary and the kept fields to HDF5, atomically
        (:mod:`mcsim.store.outputs` rules; CF ``units`` and ``long_name`` on every dataset)."""
        import datetime as dt
        import json

        from mcsim._version import __version__
        from mcsim.store.files import atomic_write, storage
        from mcsim.store.outputs import check_output

        if self.fields is None:
            raise ParameterError("no fields kept: call adhesive_contact(..., keep_fields=True)")
        path = check_output(path, inputs=[self.source], overwrite=overwrite)
        units = {
            "position": ("m", "height of the flat above the map's mean plane"),
            "mean_gap": ("m", "mean gap (exact)"),
            "pressure": ("Pa", "mean pressure (exact; compressive positive)"),
            "area_fraction": ("1", "real over nominal contact area (exact)"),
            "attractive_fraction": ("1", "fraction of the map within the interaction's range"),
            "patches": ("1", "contact patches"),
            "iterations": ("1", "L-BFGS-B iterations"),
        }

        def fill(f):
            law = self.interaction
            f.attrs.update({
                "schema": SCHEMA, "mcsim_version": __version__,
                "created": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"),
                "command": command, "source": str(self.source), "channel": self.channel,
                "level": self.level, "dx": self.dx, "dy": self.dy, "periodic": self.periodic,
                "periodic_reason": self.periodic_reason, "E_star": self.E_star,
                "interaction": self.law_name, "w": law.w, "range": law.range,
                "subpixel": self.subpixel, "summary": json.dumps(self.summary()),
            })  # fmt: skip
            if self.facing is not None:
                f.attrs.update({"counter_surface": str(self.facing.source),
                                "correlation": self.facing.correlation})  # fmt: skip
            columns = self.columns()
            f.create_dataset("branch", data=columns["branch"].astype("S8"))
            for name, (unit, long_name) in units.items():
                ds = f.create_dataset(name, data=columns[name])
                ds.attrs.update({"units": unit, "long_name": long_name})
            for name, unit, long_name in (("gap", "m", "gap between the surface and the flat"),
                                          ("pressure", "Pa", "pressure, tensile negative")):  # fmt: skip
                data = self.fields[name]
                ds = f.create_dataset(f"{name}_field", data=data, **storage(data))
                ds.attrs.update({"units": unit, "long_name": long_name,
                                 "dimensions": "step, y, x"})  # fmt: skip

        atomic_write(path, fill)
        return path


def _ratio(gw: float, exact: float) -> float:
    return gw / exact if exact > 0 else math.nan


def interaction(name: str, w: float, range_: float) -> Interaction:
    """The interaction law ``name`` (:data:`INTERACTIONS`) of work of adhesion w (J/m²) and
    range (m)."""
    if name not in INTERACTIONS:
        raise ParameterError(f"interaction = {name!r} is not one of {', '.join(INTERACTIONS)}")
    return INTERACTIONS[name](w, range_)


def gw_adhesion(surface: Surface, material: Material, law: Interaction, pressure: float):
    """GW's pull-off and work of separation on ``surface`` for every law set of
    :data:`GW_LAWS`, pressed to ``pressure`` (Pa) on its mean curve (module docstring)."""
    from mcsim.physics.adhesion import adhesion_summary
    from mcsim.physics.loadcontrol import preload_turn

    gw_material = dataclasses.replace(material, gamma=law.w, z0=law.range / H0_PER_Z0)
    out = []
    for name in GW_LAWS:
        turn = preload_turn(surface, gw_material, max(pressure, 0.0), name)
        s = adhesion_summary(surface, gw_material, name, turn=turn)
        work, h, load = tensile_work(surface, gw_material, name, turn)
        offset = surface.summit_offset or 0.0
        out.append(GWAdhesion(name, float(turn), float(s.pull_off_pressure), work,
                              surface.sigma * h + offset, load * gw_material.K))  # fmt: skip
    return tuple(out)


#: Panels and Gauss–Legendre nodes of :func:`tensile_work` (its kinks cost ~1e-4 relative).
WORK_PANELS, WORK_NODES = 400, 8


def tensile_work(surface: Surface, material: Material, law: str, turn: float):
    """−∫ min(p̄, 0) dd of GW's mean retraction load from ``turn`` (h = d/σ) to where no
    summit feels the law, J/m² (dmt's tail: 50 z0 beyond the highest summit); with the
    separations h and the loads over A_n K it was integrated on."""
    from mcsim.physics.analytic import analytic_curves
    from mcsim.physics.laws import get_law_set

    edges = get_law_set(law).edges_for(surface, material)
    heights = surface.heights
    highest = float(heights.edges[-1]) if hasattr(heights, "edges") else 8.0
    reach = min(edges.reach, edges.break_off, -50 * (material.z0 or 0.0) if law == "dmt" else 0.0)
    top = max(highest - reach / surface.sigma, turn + 1e-6)
    x, w = np.polynomial.legendre.leggauss(WORK_NODES)
    cuts = np.linspace(turn, top, WORK_PANELS + 1)
    half = np.diff(cuts)[:, None] / 2
    h = ((cuts[:-1, None] + cuts[1:, None]) / 2 + half * x).ravel()
    load = analytic_curves(surface, material, h, law, branch="retract", turn=turn).load
    scale = material.K * surface.sigma  # load·K is force per nominal area; dd = σ dh
    return float(-scale * np.sum((half * w).ravel() * np.minimum(load, 0.0))), h, load


def _refined_pull_off(cycle, start, z, pixels, E_star, law, periodic, tol, max_iter, subpixel=1):
    """The most tensile retraction pressure (Pa, > 0; 0 if none) and its position (m), with
    :data:`REFINE` solves between the neighbours of the most tensile step, warm-started from
    the displacement ``start`` of the step below it (module docstring)."""
    steps = cycle.retraction
    p = np.array([s.mean_pressure for s in steps])
    k = int(np.argmin(p))
    if p[k] >= 0:
        return 0.0, math.nan
    best = (float(p[k]), steps[k].position)
    if 0 < k < len(steps) - 1 and start is not None:
        fine = np.linspace(steps[k - 1].position, steps[k + 1].position, REFINE + 2)[1:-1]
        for s in adhesivebem.follow(z, pixels, E_star, law, fine, periodic=periodic, tol=tol,
                                    max_iter=max_iter, initial=start, subpixel=subpixel):  # fmt: skip
            if not s.converged:
                raise ParameterError(f"the pull-off's refinement did not converge at d = "
                                     f"{s.position:.4g} m; no answer is given for it")  # fmt: skip
            best = min(best, (s.mean_pressure, s.position))
    return -best[0], float(best[1])


def _flat_height(solution, z, pixels, E_star: float, periodic: bool) -> float:
    """The flat's height above the mean plane of a non-adhesive solution, m: g = u − z + d,
    averaged over the map (u's mean is 0 on a periodic map)."""
    if periodic:
        return solution.mean_gap
    u = bem.displacement_operator(z.shape, pixels, E_star, False)(solution.pressure_field)
    return float(np.mean(solution.gap_field + z - u))


def positions(z: np.ndarray, law: Interaction, deepest: float, steps: int) -> np.ndarray:
    """The flat's heights on approach, m: from where nothing acts down to ``deepest``
    (module docstring)."""
    name = next(k for k, v in INTERACTIONS.items() if isinstance(law, v))
    highest = float(z.max())
    near = highest + NEAR_RANGES[name] * law.range
    if not deepest < near:
        raise ParameterError(f"the deepest position {deepest:.4g} m lies above the start "
                             f"{near:.4g} m: give a larger pressure")  # fmt: skip
    tail = highest + np.geomspace(START_RANGES[name], NEAR_RANGES[name], TAIL + 1) * law.range
    if steps <= TAIL + 1:
        return np.linspace(tail[0], deepest, steps)
    return np.concatenate([tail[:-1], np.linspace(near, deepest, steps - TAIL)])


def exact_cycle(z, pixels, E_star: float, law: Interaction, pressure: float, *,
                periodic: bool, steps: int = STEPS, tol: float = adhesivebem.TOL,
                max_iter: int = adhesivebem.MAX_ITER, subpixel: int = 1, on_step=None):  # fmt: skip
    """The exact adhesive cycle of heights ``z`` (m, about their mean) down to where the
    non-adhesive contact carries ``pressure`` (Pa) and back (module docstring); ``subpixel``
    points k × k per pixel integrate the interaction (:func:`mcsim.physics.adhesivebem.solve_gap`).

    Returns
    -------
    cycle : AdhesiveCycle
    pull_off : float
        The most tensile retraction pressure located between the steps, Pa (> 0; 0 if none).
    position : float
        Where, m (NaN if never tensile).

    Raises
    ------
    ParameterError
        A solve, of the cycle or of the pull-off's refinement, that did not converge.
    """
    deepest = bem.solve_contact(z, pixels, E_star, pressure, periodic=periodic)
    if not deepest.converged:
        raise ParameterError(f"pressure {pressure:g} Pa: the non-adhesive solve that sets the "
                             "deepest position did not converge")  # fmt: skip
    heights = positions(z, law, _flat_height(deepest, z, pixels, E_star, periodic), steps)
    below: list = [None, None]  # on retraction: the displacement below the most tensile step

    def track(branch, solution):
        if branch == "retraction":
            if below[1] is None or solution.mean_pressure < below[1][0]:
                below[1] = (solution.mean_pressure, below[0])
            below[0] = solution.displacement_field
        if on_step is not None:
            on_step(branch, solution)

    try:
        cycle = adhesivecycle.cycle(z, pixels, E_star, law, heights, periodic=periodic, tol=tol,
                                    max_iter=max_iter, on_step=track, subpixel=subpixel)  # fmt: skip
    except adhesivecycle.ConvergenceError as err:
        raise ParameterError(f"{err}; no answer is given for it") from None
    pull_off, where = _refined_pull_off(cycle, below[1][1], z, pixels, E_star, law, periodic,
                                        tol, max_iter, subpixel)  # fmt: skip
    return cycle, pull_off, where


def adhesive_contact(
    source: HeightMap | str | Path,
    material: Material,
    pressure: float,
    *,
    law: str = "exponential",
    w: float | None = None,
    range_: float | None = None,
    steps: int = STEPS,
    unit: str | None = None,
    pixel_size: float | tuple[float, float] | None = None,
    channel: str | None = None,
    level: str | None = None,
    periodic: bool | None = None,
    tol: float = adhesivebem.TOL,
    max_iter: int = adhesivebem.MAX_ITER,
    subpixel: int = 1,
    keep_fields: bool = False,
    progress: bool = False,
    counter: str | Path | None = None,
) -> AdhesiveContactResult:
    """The exact adhesive approach and retraction of a map, GW's adhesion beside it.

    Parameters
    ----------
    source : HeightMap or path-like
        A map read once (:func:`mcsim.topography.maps.read_map`), or a height map file, any
        format ``mcsim ingest`` reads.
    material : Material
        Its contact modulus E* (Pa); its w (J/m²) and z0 (m) are the defaults of ``w`` and
        ``range_``.
    pressure : float
        Nominal pressure, Pa, > 0, of the non-adhesive contact at the deepest position.
    law : {"exponential", "maugis-dugdale"}
        The interaction (:mod:`mcsim.physics.interactions`).
    w : float, optional
        Work of adhesion, J/m² (default the material's).
    range_ : float, optional
        The law's range, m (default the material's z0).
    steps : int
        Positions of the flat on approach (the retraction revisits them), >= 2.
    unit, pixel_size, channel, level, periodic
        For a file: as for :func:`mcsim.studies.maps.contact.contact_map`.
    subpixel : int, optional
        k: the interaction integrated over k × k points of each pixel (bilinear gap), which
        resolves a Dugdale zone narrower than a pixel (docs/contact.md); 1, the default, at
        the pixel centres.
    tol, max_iter : float, int
        Solver tolerance and most iterations of one solve
        (:func:`mcsim.physics.adhesivebem.solve_gap`).
    keep_fields : bool
        Keep the gap and pressure fields of every step (float32; memory grows with the steps).
    progress : bool
        A progress bar over the steps.
    counter : path-like, optional
        A counter-surface's height map, as for :func:`mcsim.studies.maps.contact.contact_map`.

    Returns
    -------
    AdhesiveContactResult

    Raises
    ------
    ParameterError
        Bad inputs (each naming its field), or a solve that did not converge.
    """
    w = material.gamma if w is None else w
    range_ = material.z0 if range_ is None else range_
    if range_ is None:
        raise ParameterError("range: give the interaction's range (--range), or z0 in the material")
    if not (isinstance(steps, int | np.integer) and steps >= 2):
        raise ParameterError(f"steps = {steps!r} must be a whole number >= 2")
    p = float(pressure)
    if not (math.isfinite(p) and 0 < p < material.E_star):
        raise ParameterError(f"pressure = {pressure!r} Pa is out of range (allowed: (0, E* = "
                             f"{material.E_star:g}) Pa)")  # fmt: skip
    law_ = interaction(law, w, range_)
    hmap = as_map(source, "press", unit=unit, pixel_size=pixel_size, channel=channel,
                  counter=counter, level=level, periodic=periodic)  # fmt: skip
    path, z, periodic = hmap.source, hmap.levelled, hmap.periodic
    if not np.all(np.isfinite(z)):
        raise ParameterError(
            f"{path}: the map has missing pixels: fill or crop them for a contact solve"
        )
    z = z - z.mean()  # heights about the mean plane, the positions' origin
    pixels = (hmap.dx, hmap.dy)
    adhesivebem.check_inputs(z, pixels, material.E_star, law_)
    diagnostics = stickiness(z, hmap.dx, material.E_star, law_.w, law_.range, periodic)
    surface = map_surface(hmap).surface
    kept: dict[str, list] = {"gap": [], "pressure": []}
    bar = None
    if progress:
        import sys

        from tqdm import tqdm

        bar = tqdm(total=2 * steps, unit=" steps", file=sys.stderr, leave=False)

    def on_step(branch, solution):
        if keep_fields:
            kept["gap"].append(solution.gap_field.astype(np.float32))
            kept["pressure"].append(solution.pressure_field.astype(np.float32))
        if bar is not None:
            bar.update()

    try:
        result, pull_off, where = exact_cycle(z, pixels, material.E_star, law_, p,
                                              periodic=periodic, steps=steps, tol=tol,
                                              max_iter=max_iter, subpixel=subpixel,
                                              on_step=on_step)  # fmt: skip
    except ParameterError as err:
        raise ParameterError(f"{path}: {err}") from None
    finally:
        if bar is not None:
            bar.close()
    gw = gw_adhesion(surface, material, law_, max(s.mean_pressure for s in result.approach))
    return AdhesiveContactResult(
        source=Path(path), channel=hmap.channel, level=hmap.level, dx=hmap.dx, dy=hmap.dy,
        shape=z.shape, periodic=periodic, periodic_reason=hmap.periodic_reason,
        E_star=material.E_star,
        interaction=law_, pressure=p, cycle=result, pull_off=pull_off,
        pull_off_position=where, gw=gw, surface=surface,
        stickiness=diagnostics,
        fields={k: np.stack(v) for k, v in kept.items()} if keep_fields else None,
        facing=hmap.facing, subpixel=subpixel,
    )  # fmt: skip

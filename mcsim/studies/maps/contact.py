"""How good is GW on a measured map: the exact elastic contact beside GW's, ``mcsim contact``.

:func:`contact_map` reads a height map as ``mcsim ingest`` does (same readers, units, channel
and levelling), solves its frictionless, non-adhesive contact against a rigid flat exactly
at each pressure (:mod:`mcsim.physics.bem`), and puts GW's answer on the same map beside it.

GW on the map
-------------
The GW surface is the one ``mcsim ingest`` writes (direct-route summits: σ_s, R, η and the
measured summit-height histogram). As the exact solve is non-adhesive, so is GW here: Hertz
summits (Greenwood & Williamson 1966; the paper's Eq. 2 summed), with h = d/σ the flat's
separation from the summits' mean plane in units of σ = σ_s and
F_n(h) = ∫ Δⁿ φ(h + Δ) dΔ over Δ > 0 (φ the summit-height density):

* nominal pressure p = η K R^½ σ^{3/2} F_{3/2}(h), K = (4/3) E*, solved for h;
* real contact area fraction A_r/A_n = π η R σ F_1(h) (each summit's Hertz area π R δ);
* mean gap: the flat's height above the map's mean plane, σ h + ``summit_offset`` (the
  summits' mean height above that plane). GW deforms the summits only, each locally, so this
  is its mean gap; it turns negative once the flat passes below the mean plane, which a
  real gap cannot.

The exact mean gap is the mean of the gap field over the map's pixels. On a periodic map the
mean displacement is zero, so it too is the flat's height above the mean plane; on a
non-periodic (zero-padded) map the half-space also sinks as a whole under the load.

Periodic or not
---------------
Synthetic maps often repeat, measured ones do not. Unless told, the map is taken as periodic
when its opposite edges join (:func:`mcsim.topography.summits.periodic_edges`, the rule
``mcsim ingest`` uses too), and a periodic map is levelled by its mean only unless another
levelling is asked for. The decision and its numbers are reported; GW's summits are then
found with neighbours that wrap, as ``mcsim ingest`` finds them.

The environment on the exact gaps
---------------------------------
With an :class:`~mcsim.physics.environment.Environment`, the van der Waals and capillary
attraction are summed over the elastic gap field g of each load, pixel by pixel (the sum
DelRio et al., Nature Materials 4, 629 (2005) and Appl. Phys. Lett. 90, 163104 (2007) made on
a measured topography, here on the deformed one instead of the rigid overlap), per nominal
area (:func:`gap_attraction`):

* van der Waals: p_vdW = (1/N) Σ p(g) over the pixels with g ≥ D0, p the retarded flat-flat
  pressure (:func:`~mcsim.physics.vanderwaals.vdw_flat_pressure`: Gregory 1981; A/(6π g³)
  without retardation, Israelachvili Eq. 13.11), in the Derjaguin approximation;
* capillary: p_cap = (γ_L/r_K) × the fraction of pixels with f ≤ g < g_K = 2 r_K cos θ + 2t
  (Laplace pressure on the area the liquid bridges between the adsorbed films t, above the wet
  floor f = max(D0, 2t): :mod:`mcsim.physics.films`);
* pixels with g < D0, the contacts among them, belong to the contact and are left out.

The attraction pulls the surfaces together without deforming them (DMT on the exact solve):
the contacts carry p, of which p_vdW + p_cap comes from the attraction, so the pressure applied
from outside is p − p_vdW − p_cap (``external_pressure``). This holds for stiff, weakly
adhesive contacts (small Tabor parameter); where the attraction would deform the surface
around the contacts, a full adhesive solve is needed. The van der Waals sum is dominated by
the smallest open gaps, so it too depends on the pixel size.

Every exact number depends on the map's resolution (the real contact area converges slowly
as the pixels shrink): the pixel size is reported beside them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface
from mcsim.physics import bem
from mcsim.physics.analytic import hertz_area_fraction
from mcsim.physics.environment import Environment, as_environment
from mcsim.physics.loadcontrol import balance
from mcsim.physics.vanderwaals import vdw_flat_pressure
from mcsim.topography.maps import as_map
from mcsim.topography.mapsurface import map_surface
from mcsim.topography.readers import HeightMap
from mcsim.topography.readers.base import FacingMap

#: Maps of more pixels than this show a progress bar over the loads.
PROGRESS_PIXELS = 128 * 128
#: HDF5 layout version of ``mcsim contact --out`` files (separate from the package version).
SCHEMA = 1


def gw_hertz(surface: Surface, material: Material, pressure: np.ndarray):
    """GW's non-adhesive contact at nominal pressures: separation, area fraction, mean gap.

    The separation balances the Hertz load of the summits, the seed law set's P̄ (Eq. 3),
    by :func:`mcsim.physics.loadcontrol.load_control`; the area is
    :func:`~mcsim.physics.analytic.hertz_area_fraction`.

    Parameters
    ----------
    surface : Surface
        GW surface (σ, R, η, summit heights; ``summit_offset`` in m, 0 if None).
    material : Material
        Its E* (the Hertz load uses K = 4E*/3 alone).
    pressure : ndarray
        Nominal pressures, Pa, > 0.

    Returns
    -------
    h, area_fraction, mean_gap : ndarray
        h = d/σ; A_r/A_n (dimensionless); mean gap, m (module docstring).
    """
    h = balance(surface, material, pressure, "seed").h
    offset = surface.summit_offset or 0.0
    return h, hertz_area_fraction(surface, h), surface.sigma * h + offset


def gap_attraction(gap: np.ndarray, environment: Environment) -> tuple[float, float]:
    """Van der Waals and capillary attraction over a gap field, per nominal area (module docstring).

    Parameters
    ----------
    gap : ndarray
        Gap between the deformed surface and the flat on each pixel, m.
    environment : Environment
        Its Hamaker constant (J), cutoff D0 (m), retardation b (m⁻¹), Laplace pressure
        γ_L/r_K (Pa), wet floor f = max(D0, 2t) and condensation gap g_K (m) are used.

    Returns
    -------
    (float, float)
        p_vdW = (1/N) Σ_{g ≥ D0} p(g) (:func:`~mcsim.physics.vanderwaals.vdw_flat_pressure`;
        A/(6π g³) non-retarded) and p_cap = (γ_L/r_K) #{f ≤ g < g_K}/N, Pa, positive when
        attractive; 0 for a term the environment does not have.
    """
    open_ = gap >= environment.cutoff
    vdw = 0.0
    if environment.has_vdw:
        pressure = vdw_flat_pressure(gap[open_], environment.hamaker, environment.retardation)
        vdw = float(np.sum(pressure)) / gap.size
    filled = np.count_nonzero((gap >= environment.wet_floor) & (gap < environment.condensation_gap))
    return vdw, environment.laplace_pressure * filled / gap.size


@dataclass(frozen=True)
class ContactResult:
    """The exact contact of a map and GW's on it, per pressure.

    Attributes
    ----------
    source : Path
        The map file.
    channel, level : str
        Its channel and the levelling applied.
    dx, dy : float
        Pixel size along x and y, m: every exact number belongs to it.
    shape : (int, int)
        Map shape (rows, columns).
    periodic : bool
        Solved as a periodic map (else zero-padded).
    periodic_reason : str
        Why: the option given, or the edge check's numbers.
    E_star : float
        Contact modulus, Pa.
    tol : float
        Solver tolerance (:func:`mcsim.physics.bem.solve_contact`).
    pressure : ndarray
        Nominal pressures, Pa.
    area_fraction, mean_gap, patches, iterations, residual : ndarray
        Exact: A_r/A_n, mean gap (m), contact patches, CG iterations, final residual.
    gw_h, gw_area_fraction, gw_mean_gap : ndarray
        GW on the same map: h = d/σ, A_r/A_n, mean gap (m) (module docstring).
    surface : Surface
        The GW surface.
    pressure_fields, gap_fields : ndarray or None
        Per pressure (first axis), Pa and m; kept only when asked for.
    environment : Environment or None
        The environment summed over the gaps (None: none).
    vdw_pressure, capillary_pressure : ndarray or None
        Its van der Waals and capillary attraction per nominal area at each load, Pa
        (> 0 attractive; :func:`gap_attraction`); None without an environment.
    facing : FacingMap or None
        A counter-surface's map facing this one, turned over: the map solved is their gap.
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
    tol: float
    pressure: np.ndarray
    area_fraction: np.ndarray
    mean_gap: np.ndarray
    patches: np.ndarray
    iterations: np.ndarray
    residual: np.ndarray
    gw_h: np.ndarray
    gw_area_fraction: np.ndarray
    gw_mean_gap: np.ndarray
    surface: Surface
    pressure_fields: np.ndarray | None = field(default=None, repr=False)
    gap_fields: np.ndarray | None = field(default=None, repr=False)
    environment: Environment | None = None
    vdw_pressure: np.ndarray | None = None
    capillary_pressure: np.ndarray | None = None
    facing: FacingMap | None = None

    def columns(self) -> dict[str, np.ndarray]:
        """The per-pressure numbers, SI (pressure Pa, gaps m), pixel size beside them."""
        n = self.pressure.size
        out = {"pressure": self.pressure, "area_fraction": self.area_fraction,
               "mean_gap": self.mean_gap, "patches": self.patches,
               "gw_area_fraction": self.gw_area_fraction, "gw_mean_gap": self.gw_mean_gap}  # fmt: skip
        if self.environment is not None:
            out |= {"vdw_pressure": self.vdw_pressure,
                    "capillary_pressure": self.capillary_pressure,
                    "external_pressure": self.pressure - self.vdw_pressure - self.capillary_pressure}  # fmt: skip
        return out | {"iterations": self.iterations, "pixel_size": np.full(n, self.dx)}

    def write(self, path: str | Path, *, command: str = "", overwrite: bool = False) -> Path:
        """Write the fields and the numbers to an HDF5 file, atomically (:mod:`mcsim.store.outputs` rules).

        Datasets carry CF ``units`` and ``long_name``; the fields are compressed
        (:func:`mcsim.store.files.storage`). Root attributes: schema version, mcsim version,
        creation time, command line, source, pixel size, periodicity, E*, tolerance; with a
        counter-surface its map (``counter_surface``) and the measured ``correlation``.
        """
        import dataclasses
        import datetime as dt
        import math

        from mcsim._version import __version__
        from mcsim.store.files import atomic_write, storage
        from mcsim.store.outputs import check_output

        if self.pressure_fields is None or self.gap_fields is None:
            raise ParameterError("no fields kept: call contact_map(..., keep_fields=True)")
        path = check_output(path, inputs=[self.source], overwrite=overwrite)
        units = {"pressure": ("Pa", "nominal pressure"),
                 "area_fraction": ("1", "real over nominal contact area (exact)"),
                 "mean_gap": ("m", "mean gap (exact)"), "patches": ("1", "contact patches"),
                 "iterations": ("1", "conjugate-gradient iterations"),
                 "gw_area_fraction": ("1", "real over nominal contact area (GW)"),
                 "gw_mean_gap": ("m", "mean gap (GW)"),
                 "vdw_pressure": ("Pa", "van der Waals attraction over the gaps per nominal area"),
                 "capillary_pressure": ("Pa", "capillary attraction over the gaps per nominal area"),
                 "external_pressure": ("Pa", "applied pressure: pressure - vdw - capillary")}  # fmt: skip

        def fill(f):
            f.attrs.update({"schema": SCHEMA, "mcsim_version": __version__,
                            "created": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"),
                            "command": command, "source": str(self.source), "channel": self.channel,
                            "level": self.level, "dx": self.dx, "dy": self.dy,
                            "periodic": self.periodic, "periodic_reason": self.periodic_reason,
                            "E_star": self.E_star, "tol": self.tol})  # fmt: skip
            if self.facing is not None:
                f.attrs.update({"counter_surface": str(self.facing.source),
                                "correlation": self.facing.correlation})  # fmt: skip
            columns = self.columns()
            if self.environment is not None:
                f.attrs.update({f"environment_{k}": (math.nan if v is None else v)
                                for k, v in dataclasses.asdict(self.environment).items()})  # fmt: skip
            for name, (unit, long_name) in units.items():
                if name not in columns:
                    continue
                ds = f.create_dataset(name, data=columns[name])
                ds.attrs.update({"units": unit, "long_name": long_name})
            for name, data, unit, long_name in (
                ("pressure_field", self.pressure_fields, "Pa", "contact pressure"),
                (
                    "gap_field",
                    self.gap_fields,
                    "m",
                    "gap between the deformed surface and the flat",
                ),
            ):
                ds = f.create_dataset(name, data=data, **storage(data))
                ds.attrs.update({"units": unit, "long_name": long_name,
                                 "dimensions": "pressure, y, x"})  # fmt: skip

        atomic_write(path, fill)
        return path


def contact_map(
    source: HeightMap | str | Path,
    material: Material,
    pressure,
    *,
    surface: Surface | None = None,
    unit: str | None = None,
    pixel_size: float | tuple[float, float] | None = None,
    channel: str | None = None,
    level: str | None = None,
    periodic: bool | None = None,
    tol: float = bem.TOL,
    keep_fields: bool = False,
    progress: bool = False,
    environment: Environment | None = None,
    counter: str | Path | None = None,
) -> ContactResult:
    """Exact elastic contact of a measured map against a flat, with GW's on the same map.

    Parameters
    ----------
    source : HeightMap or path-like
        A map read once (:func:`mcsim.topography.maps.read_map`), or a height map file, any
        format ``mcsim ingest`` reads (read here, with the options below).
    material : Material
        Its contact modulus ``E_star`` (Pa) is used.
    pressure : array_like or str
        Nominal pressures, Pa, > 0; or a string such as ``"1kPa:10MPa:5:log"``
        (:func:`mcsim.model.units.parse_values`). Solved in ascending order.
    surface : Surface, optional
        GW's surface on the map; default the map's own
        (:func:`mcsim.topography.mapsurface.map_surface`, as ``mcsim ingest`` finds it).
    unit, pixel_size, channel, level
        For a file: as for :func:`mcsim.studies.maps.ingest.ingest_file` (pixel size in m;
        levelling by default ``"plane"``, or ``"none"`` on a periodic map).
    periodic : bool, optional
        Solve the map as periodic or zero-padded; None: periodic when its opposite edges
        join (:func:`mcsim.topography.summits.periodic_edges`).
    tol : float
        Solver tolerance (:func:`mcsim.physics.bem.solve_contact`).
    keep_fields : bool
        Keep the pressure and gap fields of every load (memory grows with the loads).
    progress : bool
        A progress bar over the loads for maps above :data:`PROGRESS_PIXELS` pixels.
    environment : Environment or mapping, optional
        Van der Waals and capillary attraction summed over each load's gap field
        (:func:`gap_attraction`; a mapping as :func:`~mcsim.physics.environment.as_environment`
        reads it); None: none.
    counter : path-like, optional
        A counter-surface's height map, measured face up, of the same size and pixel size:
        the map solved (and GW's) is the gap's topography, map − turned-over counter
        (:func:`mcsim.topography.maps.read_map`; docs/physics.md, section 'Two rough surfaces').

    Returns
    -------
    ContactResult
    """
    from mcsim.model.units import parse_values

    environment = as_environment(environment)
    if isinstance(pressure, str):
        pressure = parse_values(pressure, "pressure", "pressure", limit=1000)
    p = np.sort(np.atleast_1d(np.asarray(pressure, dtype=float)))
    if p.ndim != 1 or p.size == 0 or not np.all(np.isfinite(p) & (p > 0)):
        raise ParameterError(
            f"pressure = {pressure!r}: give one or more positive, finite values, Pa"
        )
    if p[-1] >= material.E_star:  # linear elasticity (small strains) ends long before
        raise ParameterError(f"pressure = {p[-1]:g} Pa is out of range (allowed: below E* = "
                             f"{material.E_star:g} Pa, where small-strain elasticity holds)")  # fmt: skip
    hmap = as_map(source, "press", unit=unit, pixel_size=pixel_size, channel=channel,
                  counter=counter, level=level, periodic=periodic)  # fmt: skip
    path, z, periodic = hmap.source, hmap.levelled, hmap.periodic
    if surface is None:
        surface = map_surface(hmap).surface
    if not np.all(np.isfinite(z)):
        raise ParameterError(
            f"{path}: the map has missing pixels: fill or crop them for a contact solve"
        )
    solutions = bem.solve_loads(
        z, (hmap.dx, hmap.dy), material.E_star, p, periodic=periodic, tol=tol
    )
    if progress and z.size > PROGRESS_PIXELS:
        import sys

        from tqdm import tqdm

        solutions = tqdm(solutions, total=p.size, unit=" loads", file=sys.stderr, leave=False)
    rows, pressures, gaps, attraction = [], [], [], []
    for s in solutions:
        if not s.converged:
            raise ParameterError(f"pressure {s.pressure:g} Pa: the solver did not converge in "
                                 f"{s.iterations} iterations (residual {s.residual:.2g} > tol {tol:g})")  # fmt: skip
        rows.append((s.area_fraction, s.mean_gap, s.patches, s.iterations, s.residual))
        if environment is not None:
            attraction.append(gap_attraction(s.gap_field, environment))
        if keep_fields:
            pressures.append(s.pressure_field)
            gaps.append(s.gap_field)
    area, gap, patches, iterations, residual = (np.array(c) for c in zip(*rows, strict=True))
    gw_h, gw_area, gw_gap = gw_hertz(surface, material, p)
    return ContactResult(
        source=Path(path), channel=hmap.channel, level=hmap.level, dx=hmap.dx, dy=hmap.dy,
        shape=z.shape, periodic=periodic, periodic_reason=hmap.periodic_reason,
        E_star=material.E_star,
        tol=tol, pressure=p, area_fraction=area, mean_gap=gap, patches=patches.astype(int),
        iterations=iterations.astype(int), residual=residual, gw_h=gw_h,
        gw_area_fraction=gw_area, gw_mean_gap=gw_gap, surface=surface,
        pressure_fields=np.stack(pressures) if keep_fields else None,
        gap_fields=np.stack(gaps) if keep_fields else None, environment=environment,
        vdw_pressure=None if environment is None else np.array([a[0] for a in attraction]),
        capillary_pressure=None if environment is None else np.array([a[1] for a in attraction]),
        facing=hmap.facing,
    )  # fmt: skip

"""Results versus load: the separation that balances a nominal pressure (load control).

See docs/physics.md, section 'Load control'.

Under load control the surfaces sit where the analytic approach load equals the
applied one: p = load·K, with ``load`` = force/(A_n K) for the contact law sets and
the paper's external force P̄ = P/(A_n K) (Eq. 3) for the seed
(:mod:`mcsim.physics.analytic`). Each separation is root-solved by Brent's method to 1e-12 in
h = d/σ (bracketed on a grid of the approach curve).

Adhesion makes the approach load non-monotone in h: tensile as summits jump in, then
compressive. Several separations can carry the same load; the stable one is the
branch reached by changing the load quasi-statically from zero, starting from the
rest at zero load (the separation where the approach load turns from tensile to
compressive, or far away if it is never tensile). A compressive load follows the
curve downward from there, a tensile one upward. Where the load on the way passes a
local extremum the separation jumps (flag ``jump``); a tensile load beyond the most
tensile approach load (the pull-off under load control) has no equilibrium
(h = NaN, flag ``equilibrium`` False).

The roots are as accurate as h can be in floating point: the load at the returned h
matches p to 1e-10 relative or better on the paper's surfaces, but where the load is a small
difference of large attractive and repulsive terms (pressures of ~100 Pa near the
zero-load rest of the super-smooth surface) one ulp of h moves it by ~1e-9 relative.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy import optimize

from mcsim.model.errors import ParameterError
from mcsim.model.params import MAX_ABS_H, Material, Surface
from mcsim.model.presets import as_material, as_surface
from mcsim.model.units import parse_values
from mcsim.physics.adhesion import bottom_separation, top_separation
from mcsim.physics.analytic import AnalyticCurves, analytic_curves, hertz_area_fraction
from mcsim.physics.environment import Environment, as_environment
from mcsim.physics.laws import LawSet, get_law_set
from mcsim.physics.surfaceenvironment import contact_law

#: Points of the approach grid that brackets each root.
GRID = 801
#: Tolerance of the roots in h = d/σ.
XTOL = 1e-12
#: Most pressures one call takes (as the command line's separations).
MAX_PRESSURES = 10_000


def balanced_quantity(law: str | LawSet, environment: bool = False) -> str:
    """Name of the curve that the applied load balances: ``P`` (seed, Eq. 3) or ``load``
    (with an environment always ``load``, the net load of contact and environment)."""
    laws = get_law_set(law)
    if laws.name == "seed":
        return "load" if environment else "P"
    if "load" not in laws.names:
        raise ParameterError(f"law set {laws.name!r} has no 'load' output to balance a pressure")
    return "load"


@dataclass(frozen=True)
class LoadControl:
    """Separations and curves at given nominal pressures (approach branch).

    Attributes
    ----------
    pressure : ndarray
        Nominal pressures p = applied force/A_n, Pa (> 0 compressive).
    h : ndarray
        Balancing separations d/σ; NaN where there is no equilibrium.
    jump : ndarray of bool
        The load path from zero to p passes a local extremum of the load: the
        separation jumps on the way (it is not continuously connected to the rest).
    equilibrium : ndarray of bool
        False for a tensile load beyond the pull-off (no separation carries it).
    curves : AnalyticCurves
        The analytic curves at ``h`` (NaN rows where there is no equilibrium); for the
        seed also ``area``, the real contact area A_r/A_n of its Hertz summits
        (:func:`hertz_area_fraction`).
    quantity : str
        The balanced curve: ``P`` (seed) or ``load``; p = quantity · K.
    """

    pressure: np.ndarray
    h: np.ndarray
    jump: np.ndarray
    equilibrium: np.ndarray
    curves: AnalyticCurves
    quantity: str

    def columns(self) -> dict[str, np.ndarray]:
        """``pressure`` (Pa), ``h``, the curves (dimensionless), ``jump``, ``equilibrium``."""
        values = dict(self.curves.values)
        return {"pressure": self.pressure, "h": self.h, **values, "jump": self.jump,
                "equilibrium": self.equilibrium}  # fmt: skip


def solve_targets(
    load,
    grid: np.ndarray,
    targets: np.ndarray,
    xtol: float = XTOL,
    values: np.ndarray | None = None,
):
    """Stable roots of ``load(h) = target`` along a descending grid of h (pure, no physics).

    Parameters
    ----------
    load : callable
        Vectorised load as a function of h (approach branch).
    grid : ndarray
        Strictly decreasing h, from where the load vanishes (far away) downward.
    targets : ndarray
        Loads to balance, in the unit of ``load``.
    xtol : float
        Tolerance of the roots in h.
    values : ndarray, optional
        ``load(grid)``, where the caller has it already (not computed twice).

    Returns
    -------
    h, jump, equilibrium : ndarray
        Root per target (NaN without equilibrium), jump and equilibrium flags.
    """
    if values is None:
        values = load(grid)
    tensile = np.flatnonzero(values < 0)
    # Rest at zero load: first index at or after the first tensile point with load >= 0.
    rest = 0
    if tensile.size:
        after = np.flatnonzero((values >= 0) & (np.arange(grid.size) > tensile[0]))
        rest = after[0] if after.size else grid.size
    h = np.full(targets.shape, np.nan)
    jump = np.zeros(targets.shape, dtype=bool)
    found = np.zeros(targets.shape, dtype=bool)
    scale = np.max(np.abs(values)) * 1e-9
    for k, target in enumerate(targets):
        if target >= 0:
            path = np.arange(rest, grid.size)  # downward from the rest
            hit = path[values[path] >= target]
            if not hit.size or hit[0] == 0:
                continue
            j = hit[0]
            lo, hi = grid[j], grid[j - 1]
            before = values[rest:j]
        else:
            path = np.arange(rest - 1, -1, -1)  # upward from the rest
            hit = path[values[path] <= target]
            if not hit.size or hit[0] + 1 >= grid.size:
                continue
            j = hit[0]
            lo, hi = grid[j + 1], grid[j]
            before = -values[j + 1 : rest][::-1]
        # Passing a local extremum on the way: the load dips below its running maximum.
        if before.size > 1:
            jump[k] = bool(np.any(before < np.maximum.accumulate(before) - scale))
        h[k] = optimize.brentq(lambda x, t=target: float(load(np.array([x]))[0] - t), lo, hi,
                               xtol=xtol, rtol=4 * np.finfo(float).eps)  # fmt: skip
        found[k] = True
    return h, jump, found


def load_control(
    surface: Surface,
    material: Material,
    pressure,
    law: str | LawSet = "seed",
    environment: Environment | None = None,
) -> LoadControl:
    """Separations on the approach branch that balance nominal pressures, and the curves there.

    Parameters
    ----------
    surface, material : Surface or str, Material or str
        The inputs of :func:`mcsim.gw_curves` (objects or preset names).
    pressure : array_like or str
        Nominal pressures p, Pa (> 0 compressive); finite. Or a string as on the command
        line: ``"1kPa,1MPa"`` or ``"1kPa:10MPa:31:log"`` (:func:`mcsim.model.units.parse_values`). A tensile (negative) or zero
        pressure is allowed only for a law set whose approach load is tensile somewhere.
    law : str or LawSet
        Law set; for ``seed`` the balanced load is P̄ (Eq. 3), else ``load``.
    environment : Environment or mapping, optional
        An Environment, or its fields as a mapping (:func:`~mcsim.physics.environment.as_environment`).
        Van der Waals and capillary attraction (:func:`mcsim.gw_curves`): the pressure
        then balances the net ``load`` = contact − vdw − capillary, for every law set.

    Returns
    -------
    LoadControl

    Raises
    ------
    ParameterError
        Non-finite or empty pressures, p <= 0 without adhesion, or a pressure that
        no separation with |h| <= 1e6 reaches.
    """
    surface, material = as_surface(surface), as_material(material)
    return balance(surface, material, pressure, law, as_environment(environment))


def balance(
    surface: Surface,
    material: Material,
    pressure,
    law: str | LawSet = "seed",
    environment: Environment | None = None,
) -> LoadControl:
    """:func:`load_control` of inputs resolved already (a Surface, a Material, an Environment or
    None), as every module below the public boundary calls it; parameters, results and errors
    as :func:`load_control`'s."""
    laws = contact_law(get_law_set(law), environment)  # one interface: w less van der Waals
    quantity = balanced_quantity(laws, environment is not None)
    if isinstance(pressure, str):
        pressure = parse_values(pressure, "pressure", "pressure", limit=MAX_PRESSURES)
    try:
        p = np.atleast_1d(np.asarray(pressure, dtype=float))
    except (TypeError, ValueError):
        raise ParameterError(f"pressure = {pressure!r}: give numbers (Pa) or a string such as "
                             "'1kPa:10MPa:31:log'") from None  # fmt: skip
    if p.ndim != 1 or p.size == 0 or not np.all(np.isfinite(p)):
        raise ParameterError(f"pressure = {pressure!r}: give one or more finite values, Pa")
    targets = p / material.K

    def load(h):
        return analytic_curves(surface, material, h, laws, environment=environment).values[quantity]

    top, bottom = top_separation(surface, laws, material), bottom_separation(surface)
    while True:
        grid = np.linspace(top, bottom, GRID)
        values = load(grid)
        if values.max() >= targets.max():
            break
        if bottom < -MAX_ABS_H / 2:
            raise ParameterError(
                f"pressure = {p.max():g} Pa is out of range (allowed: up to "
                f"{values.max() * material.K:g} Pa, the load at h = {bottom:g})"
            )
        bottom = top - 2 * (top - bottom)
    if values.min() >= 0 and np.any(targets <= 0):
        raise ParameterError(
            f"pressure = {p.min():g} Pa is out of range (allowed: > 0; the approach load of "
            f"law set {laws.name!r} is nowhere tensile on this surface, so no finite "
            "separation carries p <= 0)"
        )
    h, jump, found = solve_targets(load, grid, targets, values=values)
    curves = analytic_curves(
        surface, material, np.where(found, h, 0.0), laws, environment=environment
    )
    values = dict(curves.values)
    if laws.name == "seed":  # the area a load buys: Hertz summits, as the seed's load P (Eq. 2)
        values["area"] = hertz_area_fraction(surface, np.where(found, h, 0.0))
    values = {k: np.where(found, v, np.nan) for k, v in values.items()}
    curves = AnalyticCurves(h, values, surface, material, laws.name, environment=environment)
    return LoadControl(p, h, jump, found, curves, quantity)


def preload_turn(
    surface: Surface, material: Material, pressure: float, law: str | LawSet, environment=None
) -> float:
    """Closest approach h_turn = d/σ reached under a preload on the mean curve.

    The separation on the approach branch that balances the nominal pressure ``pressure``
    (Pa, >= 0), as :func:`load_control` finds it: an actuator pressing the surfaces with
    P·A_n from far away stops there, and retraction starts from it. With an
    ``environment`` the net load (contact minus its attraction) balances P. A preload of 0
    is the surfaces resting under their own attraction
    (:func:`mcsim.physics.adhesion.zero_load_separation`).

    Raises
    ------
    ParameterError
        A pressure that is not finite and >= 0, or that no separation carries.
    """
    p = float(pressure)
    if not (np.isfinite(p) and p >= 0):
        raise ParameterError(f"preload = {pressure!r} Pa: allowed a finite pressure >= 0")
    if p == 0:
        from mcsim.physics.adhesion import zero_load_separation

        try:
            return zero_load_separation(surface, material, law, environment)
        except ParameterError as err:  # NoAdhesiveRest: nothing pulls the surfaces together
            raise ParameterError(f"preload = 0 Pa: {err}") from None
    try:
        return float(balance(surface, material, [p], law, environment).h[0])
    except ParameterError as err:  # a pressure no separation carries: name the field
        raise ParameterError(f"preload: {err}") from None


@dataclass(frozen=True)
class Preload:
    """A preload and the closest approach it reaches on the mean approach curve, found once
    (:func:`preload_of`) and passed on: ``simulate(preload=...)`` takes its turn as it is when
    the run's inputs are the very objects it was found for.

    Attributes
    ----------
    pressure : float
        Nominal pressure, Pa, >= 0.
    turn : float
        Closest approach h_turn = d/σ that balances it (:func:`preload_turn`).
    inputs : tuple
        The surface, material, law set and environment it was found for.
    """

    pressure: float
    turn: float
    inputs: tuple = field(repr=False)

    def is_for(self, surface: Surface, material: Material, law, environment) -> bool:
        """Whether ``turn`` was found for these inputs (the same objects, the same law set)."""
        mine = self.inputs
        return (mine[0] is surface and mine[1] is material and mine[2] == law
                and mine[3] is environment)  # fmt: skip


def preload_of(
    surface: Surface, material: Material, pressure: float, law: str, environment=None
) -> Preload:
    """:func:`preload_turn`, kept with its pressure and inputs to pass on (:class:`Preload`)."""
    turn = preload_turn(surface, material, pressure, law, environment)
    return Preload(float(pressure), turn, (surface, material, law, environment))

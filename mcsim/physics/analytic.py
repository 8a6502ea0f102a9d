"""Analytic Greenwood–Williamson curves (paper, Eqs. 1, 3, 5, 7, 8), for every law set.

See docs/physics.md, sections 'The seed model' and 'GW integrals'.

Each total force is N times the expectation of a per-summit law over the summit
heights. Divided by A_n·K (the normalisation that makes Eqs. 3, 5 and 7 consistent;
the paper implies it without stating it):

    X̄(h) = (η / K) ∫_h^∞ X_a(σ(s − h)) p(s) ds,     X ∈ {P, F, T},

with p the standardized height density (Gaussian in the paper). The paper prints the
dimensional load integral of Eq. 3 from 0; it must run from d (from Δ = 0 in its
dimensionless form), which is what is computed here. μ = T̄/(P̄ + F̄) (Eq. 8) and
N_c/N = ∫_h^∞ p(s) ds (Eq. 1).

Law sets beyond the seed (:mod:`mcsim.physics.laws`) are integrated the same way, over the
summits that carry force: s > threshold(h, h_turn)/σ (:meth:`mcsim.physics.laws.Edges.threshold`),
with δ = σ(s − h) and δ_max = δ on approach, σ(s − h_turn) on retraction. Their
outputs in N are divided by A_n K (``load``), in m² by A_n (``area`` = A_r/A_n);
N_c/N counts the summits in contact (:meth:`mcsim.physics.laws.Edges.in_contact`). The
integrals run panel by panel between the law's edges and breakpoints
(:meth:`mcsim.model.distributions.HeightDistribution.gw_integrals` with ``breaks``). With a
shear strength τ (Bowden–Tabor) friction = τ A_r/(A_n K) and μ = friction/load where
the load is compressive (> 0); elsewhere μ is undefined (NaN).

With an environment (:mod:`mcsim.physics.environment`: van der Waals across the gaps and
capillary condensation) the curves gain ``vdw`` and ``capillary``, each attraction per
nominal area divided by K (positive when attractive), and ``load`` becomes the net load
contact − vdw − capillary: for the seed a new column P − vdw − capillary (P, F, T and μ of
Eqs. 3–8 unchanged), for the other law sets the ``load`` column itself, with μ =
friction/net load. Both branches carry the same environment terms (equilibrium menisci).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface, check_range, check_separations
from mcsim.model.presets import as_material, as_surface
from mcsim.physics.environment import Environment, as_environment
from mcsim.physics.laws import Edges, LawSet, get_law_set
from mcsim.physics.surfaceenvironment import contact_law, environment_curves
from mcsim.physics.validity import area_warnings

#: Quantities of a GW curve, in output order, with their meaning.
QUANTITIES = {
    "contact_fraction": "N_c/N, fraction of summits in contact (Eq. 1)",
    "P": "Hertz load P/(A_n K) (Eq. 3)",
    "F": "JKR adhesion term F/(A_n K) (Eq. 5); not a pull-off force",
    "T": "adhesional friction T/(A_n K) (Eq. 7)",
    "mu": "friction coefficient T/(P + F) (Eq. 8); undefined where w = 0",
}


#: Quantities of the curves of a law set with named outputs (load, area), beyond the
#: law's own: what they mean, for column help.
CONTACT_QUANTITIES = {
    "contact_fraction": "N_c/N, fraction of summits in contact",
    "load": "net normal force/(A_n K), positive when compressive",
    "area": "real contact area A_r/A_n",
    "friction": "friction tau A_r/(A_n K) (Bowden-Tabor)",
    "mu": "friction/load where load > 0, else undefined",
}

#: Curves an environment adds (:func:`gw_curves` with ``environment``).
ENVIRONMENT_QUANTITIES = {
    "vdw": "van der Waals attraction across the gaps per nominal area/K, > 0 attractive",
    "capillary": "capillary (Laplace) attraction per nominal area/K, > 0 attractive",
    "load": "net load/(A_n K): contact minus vdw minus capillary, > 0 compressive",
}


def quantities(law: str | LawSet, material: Material, environment: bool = False) -> tuple[str, ...]:
    """Names of the curves of a law set, in column order (after ``h``).

    The seed: ``contact_fraction, P, F, T, mu``. Other sets: ``contact_fraction``,
    their outputs (``load, area``), and ``friction, mu`` if the set has Bowden–Tabor
    friction and the material gives τ. With an ``environment``: then ``vdw, capillary``
    (and, for the seed, the net ``load``).
    """
    laws = get_law_set(law)
    if laws.name == "seed":
        names = tuple(QUANTITIES)
    else:
        friction = ("friction", "mu") if laws.friction and material.tau is not None else ()
        names = ("contact_fraction", *laws.names, *friction)
    if environment:
        names += tuple(q for q in ENVIRONMENT_QUANTITIES if q not in names)
    return names


@dataclass(frozen=True)
class AnalyticCurves:
    """GW curves versus the dimensionless mean separation h = d/σ.

    Attributes
    ----------
    h : ndarray
        Separations d/σ.
    values : dict of str to ndarray
        Each curve by name, in column order (:func:`quantities`); also readable as
        attributes (``curves.load``). The seed: ``contact_fraction`` N_c/N (Eq. 1),
        ``P``, ``F``, ``T`` each divided by A_n·K (Eqs. 3, 5, 7) and ``mu`` T/(P + F)
        (Eq. 8), NaN where P + F = 0 and everywhere without adhesion (w = 0: the
        friction of Eq. 6 is adhesional, T = 0, and the model gives no μ). Other law sets: ``contact_fraction``, ``load``
        (force/(A_n K), signed, > 0 compressive), ``area`` (A_r/A_n), and with τ
        ``friction`` τA_r/(A_n K) and ``mu`` = friction/load, NaN (undefined) where
        load ≤ 0.
    surface, material : Surface, Material
        The inputs.
    law : str
        Law-set name.
    branch : str
        ``"approach"`` or ``"retract"``.
    turn : float or None
        Closest approach h_turn = d_turn/σ before retraction (None on approach).
    environment : Environment or None
        The environment whose ``vdw`` and ``capillary`` curves are included (None: none).
    """

    h: np.ndarray
    values: dict[str, np.ndarray]
    surface: Surface
    material: Material
    law: str
    branch: str = "approach"
    turn: float | None = None
    environment: Environment | None = None

    def __getattr__(self, name: str) -> np.ndarray:
        values = self.__dict__.get("values")
        if values is not None and name in values:
            return values[name]
        raise AttributeError(f"{type(self).__name__} of law set {self.__dict__.get('law')!r} "
                             f"has no curve {name!r}")  # fmt: skip

    def forces(self, area: float) -> dict[str, np.ndarray]:
        """Dimensional totals for a nominal area ``area`` (m², > 0).

        ``N_c`` (summits in contact) and every curve that is a force (× A_n K, N) or an
        area (× A_n, m²): the seed's P, F, T; ``load``, ``area``, ``friction``.
        """
        area = check_range("area", area, "m^2", low=0)
        scale = area * self.material.K
        out = {"N_c": self.surface.eta * area * self.contact_fraction}
        for q, v in self.values.items():
            if q in ("P", "F", "T", "load", "friction", "vdw", "capillary"):
                out[q] = v * scale
            elif q == "area":
                out[q] = v * area
        return out

    #: Column names of :meth:`table`: each quantity with its normalisation.
    LABELS: ClassVar[dict[str, str]] = {
        "h": "h = d/σ",
        "contact_fraction": "N_c/N",
        "P": "P/(A_n K)",
        "F": "F/(A_n K)",
        "T": "T/(A_n K)",
        "mu": "μ = T/(P + F)",
        "load": "load/(A_n K)",
        "area": "A_r/A_n",
        "friction": "τ A_r/(A_n K)",
        "vdw": "p_vdW/K",
        "capillary": "p_cap/K",
    }

    def columns(self) -> dict[str, np.ndarray]:
        """Arrays ``h`` and every curve (dimensionless), by short name, in order."""
        return {"h": self.h, **self.values}

    def table(self):
        """The curves as a :class:`pandas.DataFrame`, one row per separation.

        Columns, named with their normalisation (all dimensionless): ``h = d/σ``,
        ``N_c/N`` (Eq. 1), then the seed's ``P/(A_n K)``, ``F/(A_n K)``, ``T/(A_n K)``
        (Eqs. 3, 5, 7) and ``μ = T/(P + F)`` (Eq. 8), or a contact law set's
        ``load/(A_n K)``, ``A_r/A_n`` and, with τ, ``τ A_r/(A_n K)`` and
        ``μ = friction/load``.
        """
        import pandas as pd

        labels = self.LABELS if self.law == "seed" else {**self.LABELS, "mu": "μ = friction/load"}
        return pd.DataFrame({labels.get(c, c): v for c, v in self.columns().items()})

    def validity_warnings(self) -> list[str]:
        """Where these curves leave GW's independent summits (:mod:`mcsim.physics.validity`).

        The real contact area is the ``area`` curve; for a law set without one (the seed)
        that of its Hertz summits, π η R σ F_1(h) (Greenwood & Williamson 1966).

        Returns
        -------
        list of str
            One line if the area fraction passes the nominal area or
            :data:`~mcsim.physics.validity.INTERACTING_AREA` at some ``h``; else empty.
        """
        h = self.h[np.isfinite(self.h)]  # NaN rows: no equilibrium under load control
        if "area" in self.values:
            area = self.values["area"][np.isfinite(self.h)]
        else:
            area = hertz_area_fraction(self.surface, h)
        return area_warnings(area, h)

    def _summary(self) -> tuple[str, list[tuple[str, str]]]:
        from mcsim.model import display as _display

        rows = _display.inputs(self.surface, self.material, self.law, self.h)
        if self.turn is not None:
            rows.append(("branch", f"retract after the closest approach h_turn = {self.turn:g}"))
        return "GW analytic curves", rows

    def __repr__(self) -> str:
        from mcsim.model import display as _display

        return _display.text(*self._summary())

    def _repr_html_(self) -> str:
        from mcsim.model import display as _display

        return _display.table(*self._summary())


def _check_turn(laws: LawSet, branch: str, h: np.ndarray, turn) -> float | None:
    """The closest approach h_turn for ``branch``: None on approach, else <= min(h)."""
    laws.check_branch(branch)
    if branch == "approach":
        if turn is not None:
            raise ParameterError(
                f"turn = {turn!r} applies to branch='retract' only (the approach has no turn)"
            )
        return None
    if turn is None:
        return float(h.min())
    turn = check_range("turn", turn, "1")
    if turn > h.min():
        raise ParameterError(
            f"turn = {turn:g} is out of range (allowed: turn <= {h.min():g}, the lowest "
            "separation: retraction starts from the closest approach)"
        )
    return turn


def gw_curves(
    surface: Surface | str,
    material: Material | str,
    h,
    law: str | LawSet = "seed",
    branch: str = "approach",
    turn: float | None = None,
    environment: Environment | dict | None = None,
) -> AnalyticCurves:
    """GW curves of a surface and material at separations ``h`` (= d/σ), vectorised.

    Parameters
    ----------
    surface : Surface or str
        Summit population (σ, R, η and the height distribution), or a preset's name.
    material : Material or str
        Material pair (K, G, γ; z0, τ, H where the law set needs them), or a preset's name.
    h : array_like
        Dimensionless separations d/σ: finite, |h| <= 1e6
        (:data:`mcsim.model.params.MAX_ABS_H`); others raise a ParameterError.
    law : str or LawSet
        Per-summit law set, ``"seed"`` by default (the paper as written).
    branch : {"approach", "retract"}
        Approach from far away, or retraction after the closest approach ``turn``.
    turn : float, optional
        Closest approach h_turn = d_turn/σ, retraction only; default the lowest ``h``.
        It must not lie above any ``h`` (retraction starts there).
    environment : Environment or mapping, optional
        An Environment, or its fields as a mapping (:func:`~mcsim.physics.environment.as_environment`).
        Adds the curves ``vdw`` and ``capillary`` (attraction per nominal area over K,
        > 0 attractive; :func:`mcsim.physics.surfaceenvironment.environment_curves` at the
        mean-plane gap D = hσ + summit_offset of :func:`~mcsim.physics.gapheights.gap_heights`)
        and makes ``load`` the net load (see the module docstring). None (default): the
        contact curves alone, exactly as without this argument.

    Returns
    -------
    AnalyticCurves
        Dimensionless curves (see :class:`AnalyticCurves` for each one's scale).

    Raises
    ------
    ParameterError
        Unknown law set or branch, retraction of a law set without one, a ``turn``
        above the sweep or on approach, a material field the law set needs.
    """
    return analytic_curves(as_surface(surface), as_material(material), h, law, branch, turn,
                           as_environment(environment))  # fmt: skip


def analytic_curves(
    surface: Surface,
    material: Material,
    h,
    law: str | LawSet = "seed",
    branch: str = "approach",
    turn: float | None = None,
    environment: Environment | None = None,
) -> AnalyticCurves:
    """:func:`gw_curves` of inputs resolved already (a Surface, a Material, an Environment or
    None): what every module below the public boundary calls (docs: ARCHITECTURE.md, 'One
    simulate'); parameters and results as :func:`gw_curves`'s.
    """
    laws = contact_law(get_law_set(law), environment)  # one interface: w less van der Waals
    h = check_separations(h)
    turn = _check_turn(laws, branch, h, turn)
    if surface.radius_by_height is not None:
        return _mixture(surface, material, h, laws, branch, turn, environment)
    args = laws.arguments(surface, material)
    sigma = surface.sigma
    edges = laws.edges_for(surface, material)
    if laws.stateful or edges != Edges():
        curves = _contact_curves(surface, material, h, laws, args, edges, branch, turn)
        return curves if environment is None else _with_environment(curves, environment)

    def integrand(delta: np.ndarray) -> np.ndarray:
        return np.stack([f(sigma * delta, *a) for f, a in zip(laws.laws, args)])

    scale, integral = surface.heights.gw_integrals(integrand, h)
    values = {"contact_fraction": np.asarray(surface.heights.sf(h), dtype=float)}
    values |= _normalised(laws, surface, material, scale, integral)
    if laws.name == "seed":  # Eq. 8; undefined without adhesion (Eq. 6: T = 0 at w = 0)
        denominator = (integral[0] + integral[1]) * (material.gamma > 0)
        with np.errstate(invalid="ignore", divide="ignore"):
            values["mu"] = np.where(denominator > 0, integral[2] / denominator, np.nan)
    else:
        values = {**values, **_friction(laws, material, values)}
    curves = AnalyticCurves(h, values, surface, material, laws.name, branch, turn)
    return curves if environment is None else _with_environment(curves, environment)


def _mixture(surface, material, h, laws, branch, turn, environment) -> AnalyticCurves:
    """Curves of a surface whose radius depends on height: the sums of its bands' curves
    (:meth:`~mcsim.model.params.Surface.components`), μ from the sums."""
    parts = [analytic_curves(c, material, h, laws, branch, turn).values
             for c in surface.components()]  # fmt: skip
    values = {k: np.sum([p[k] for p in parts], axis=0) for k in parts[0] if k != "mu"}
    if laws.name == "seed":  # Eq. 8, as for one radius
        denominator = (values["P"] + values["F"]) * (material.gamma > 0)
        with np.errstate(invalid="ignore", divide="ignore"):
            values["mu"] = np.where(denominator > 0, values["T"] / denominator, np.nan)
    else:
        values |= _friction(laws, material, values)
    curves = AnalyticCurves(h, values, surface, material, laws.name, branch, turn)
    return curves if environment is None else _with_environment(curves, environment)


def _with_environment(curves: AnalyticCurves, environment: Environment) -> AnalyticCurves:
    """The curves with ``vdw``, ``capillary`` (Pa/K) and the net ``load`` (and μ on it)."""
    surface, material = curves.surface, curves.material
    pressures = environment_curves(curves.h, surface, environment)
    vdw, capillary = pressures["vdw"] / material.K, pressures["capillary"] / material.K
    values = dict(curves.values)
    contact = values["P"] if curves.law == "seed" else values["load"]
    values |= {"vdw": vdw, "capillary": capillary, "load": contact - vdw - capillary}
    if curves.law != "seed" and "friction" in values:
        with np.errstate(invalid="ignore", divide="ignore"):
            values["mu"] = np.where(values["load"] > 0, values["friction"] / values["load"], np.nan)
    return dataclasses.replace(curves, values=values, environment=environment)


def _normalised(laws, surface, material, scale, integral) -> dict[str, np.ndarray]:
    """Per-summit expectations to curves: forces (N) per A_n K, areas (m²) per A_n."""
    out = {}
    for o, row in zip(laws.outputs, integral):
        factor = surface.eta / material.K if o.unit == "N" else surface.eta
        out[o.name] = factor * scale * row
    return out


def _friction(laws: LawSet, material: Material, values: dict) -> dict[str, np.ndarray]:
    """Bowden–Tabor friction τA_r/(A_n K) and μ = friction/load (load > 0), if τ is given."""
    if not (laws.friction and material.tau is not None):
        return {}
    friction = material.tau / material.K * values["area"]
    load = values["load"]
    with np.errstate(invalid="ignore", divide="ignore"):
        mu = np.where(load > 0, friction / load, np.nan)
    return {"friction": friction, "mu": mu}


def _contact_curves(surface, material, h, laws, args, edges, branch, turn) -> AnalyticCurves:
    """Curves of a law set with edges or branches: piecewise quadrature between breakpoints."""
    sigma = surface.sigma
    # δ_max − δ = d − d_turn, per h, over σ (0 on approach; and for a law set
    # without history, whose retraction is its approach, bit for bit).
    lag = np.zeros_like(h) if turn is None or not laws.stateful else h - turn
    stateful = [o.stateful for o in laws.outputs]

    def integrand(delta: np.ndarray, rows: np.ndarray) -> np.ndarray:
        d = sigma * delta
        d_max = sigma * (delta + lag[rows][:, None])
        return np.stack(
            [f(d, d_max, *a) if st else f(d, *a) for f, a, st in zip(laws.laws, args, stateful)]
        )

    scale, integral = surface.heights.gw_integrals(integrand, h, _breaks(edges, sigma, lag))
    values = _normalised(laws, surface, material, scale, integral)
    # In contact: δ_max > jump_in and δ > break_off, i.e. s above both.
    lowest = np.maximum(edges.jump_in / sigma - lag, edges.break_off / sigma)
    values = {
        "contact_fraction": np.asarray(surface.heights.sf(h + lowest), dtype=float),
        **values,
    }
    values |= _friction(laws, material, values)
    if laws.name == "seed":  # the seed with an environment's caps: its μ (Eq. 8) as above
        denominator = values["P"] + values["F"]
        with np.errstate(invalid="ignore", divide="ignore"):
            values["mu"] = np.where(denominator > 0, values["T"] / denominator, np.nan)
    return AnalyticCurves(h, values, surface, material, laws.name, branch, turn)


def _breaks(edges: Edges, sigma: float, lag: np.ndarray) -> np.ndarray:
    """Lower limit and breakpoints of the integrals in Δ = s − h, shape ``(len(h), m)``.

    The lower limit is threshold(d, d_turn) − d over σ; breakpoints are the reach,
    break-off and δ = 0 in δ, the jump-in and each declared breakpoint both in δ and
    in δ_max (= δ + σ·lag).
    """
    lower = np.minimum(edges.reach, np.maximum(edges.jump_in - sigma * lag, edges.break_off))
    in_delta = sorted({0.0, edges.reach, edges.break_off, edges.jump_in, *edges.breakpoints})
    in_max = sorted({edges.jump_in, *edges.breakpoints}) if np.any(lag != 0) else []
    columns = [lower / sigma]
    columns += [np.full_like(lag, b / sigma) for b in in_delta]
    columns += [b / sigma - lag for b in in_max]
    return np.stack(columns, axis=1)


def hertz_area_fraction(surface: Surface, h) -> np.ndarray:
    """GW real contact area of Hertz summits, A_r/A_n = π η R σ F_1(h) (GW 1966, Eq. 9)."""
    h = np.atleast_1d(np.asarray(h, dtype=float))
    out = np.zeros_like(h)
    for part in surface.components():  # a radius by height: the sum over its bands
        scale, integral = part.heights.gw_integrals(lambda d: d[None], h)
        out += math.pi * part.eta * part.R * part.sigma * scale * integral[0]
    return out

"""Adhesion summary of a rough contact: pull-off force, work of separation, regime numbers.

See docs/physics.md, section 'Adhesion summaries and regime numbers'.

From the analytic GW curves of a contact law set (:func:`mcsim.gw_curves`) on approach
and on retraction after a closest approach h_turn:

* **pull-off force**: the most tensile net load on retraction, min over h ≥ h_turn
  of the load, located by a bounded minimisation (to 1e-7 in h, :data:`H_TOLERANCE`) around the lowest
  point of a grid; reported as a magnitude, force/(A_n K) and as a pressure (Pa);
* **work of separation**: ∫ max(−load, 0) dd on retraction from d_turn, J/m² of
  nominal area (d = σh, force per area = load·K);
* **hysteresis**: ∫ (load_approach − load_retract) dd over the same range, J/m²: the
  energy lost in one approach–retraction cycle;
* **regime numbers** of one summit: Tabor's μ_T = (R w²/(E*² z0³))^{1/3} (Tabor 1977),
  Maugis' λ = 2σ0 (R/(π w K²))^{1/3} with σ0 = w/h0, h0 = 0.97 z0 and K = 4E*/3
  (Maugis 1992; Johnson & Greenwood 1997), so λ = 1.162 μ_T; the Fuller–Tabor
  adhesion parameter θ = E* σ^{3/2}/(R^{1/2} w) (see :func:`adhesion_parameter`); the
  plasticity index ψ = (E*/H)√(σ/R) (Greenwood & Williamson 1966).

With an environment (:mod:`mcsim.physics.environment`) the net load on both branches is
the contact load minus the van der Waals and capillary attraction (:func:`mcsim.gw_curves`):
the turn is where the net approach load is zero, the pull-off is the most tensile net
retraction load (searched also above the summits, where the attraction alone acts), and the
work of separation is the integral of the net retraction force from the turn to infinity,
−∫ F_net dd per nominal area (signed: a compressive part, the elastic energy the pressed
summits give back, counts against it): the contact part −∫ load dd plus the works of the two
attractions (:func:`mcsim.physics.surfaceenvironment.environment_works`, each the integral of its
own pressure). The dry work is that contact part alone; at the zero-load turn its retraction
load is nowhere compressive. Hysteresis is unchanged in form: the equilibrium menisci and van der
Waals act alike on both branches.

Which law set fits is read off the Johnson–Greenwood (1997) adhesion map at the low
loads that decide pull-off: DMT for λ < 0.1, JKR for λ > 5, Maugis–Dugdale between
(:data:`DMT_BELOW`, :data:`JKR_ABOVE`). A law set used outside its zone, or an elastic
law set at ψ > 1 (mostly plastic summits), gives a :class:`RegimeWarning`.

References: K.N.G. Fuller & D. Tabor, Proc. R. Soc. Lond. A 345 (1975) 327–342;
D. Tabor, J. Colloid Interface Sci. 58 (1977) 2–13; D. Maugis, J. Colloid Interface
Sci. 150 (1992) 243–269; K.L. Johnson & J.A. Greenwood, J. Colloid Interface Sci. 192
(1997) 326–333; J.A. Greenwood & J.B.P. Williamson, Proc. R. Soc. Lond. A 295 (1966)
300–319.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import asdict, dataclass

import numpy as np

from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface, check_range, plasticity_index
from mcsim.physics.analytic import analytic_curves
from mcsim.physics.environment import Environment, as_environment
from mcsim.physics.gapheights import gap_heights
from mcsim.physics.laws import LawSet, get_law_set
from mcsim.physics.surfaceenvironment import (
    band_edge,
    contact_law,
    environment_curves,
    environment_works,
)
from mcsim.physics.validity import work_warnings

#: Johnson–Greenwood (1997) map at low load: DMT below this Maugis λ.
DMT_BELOW = 0.1
#: Johnson–Greenwood (1997) map at low load: JKR above this Maugis λ.
JKR_ABOVE = 5.0
#: Dugdale range over the equilibrium spacing, h0/z0 (Maugis' match to Lennard-Jones).
H0_OVER_Z0 = 0.97
#: Points of the grid on which the zero of the approach load is bracketed.
GRID = 200
#: Panels on [turn, top] for the work and hysteresis integrals, and their
#: Gauss–Legendre nodes; the pull-off is bracketed on the same points.
PANELS = 64
NODES = 8
#: Absolute tolerance of the pull-off separation, in h.
H_TOLERANCE = 1e-7
#: Gaussian heights: standardized height above which the quadrature sees no summit
#: (the weight is below e^-41 of its peak there, as in :mod:`mcsim.model.distributions`).
GAUSSIAN_TOP = math.sqrt(82.0)


class NoAdhesiveRest(ParameterError):
    """The approach load is never tensile: under no external load the surfaces rest apart."""


class RegimeWarning(UserWarning):
    """A law set used outside its regime (adhesion map, plasticity index)."""


class ValidityWarning(RegimeWarning):
    """GW's independent summits used where they do not hold (:mod:`mcsim.physics.validity`)."""


def tabor_parameter(surface: Surface, material: Material) -> float | None:
    """Tabor's μ_T = (R w²/(E*² z0³))^{1/3} of one summit, or None without z0 (Tabor 1977)."""
    if material.z0 is None:
        return None
    w = material.gamma
    return (surface.R * w**2 / (material.E_star**2 * material.z0**3)) ** (1 / 3)


def maugis_parameter(surface: Surface, material: Material) -> float | None:
    """Maugis' λ = 2σ0 (R/(π w K²))^{1/3}, σ0 = w/(0.97 z0), K = 4E*/3; None without z0.

    Maugis (1992) in the notation of Johnson & Greenwood (1997); λ = 1.162 μ_T
    (λ ∝ w^{2/3}: 0 for w = 0).
    """
    if material.z0 is None:
        return None
    w = material.gamma
    sigma0 = w / (H0_OVER_Z0 * material.z0)
    return 2 * sigma0 * (surface.R / (math.pi * w * material.K**2)) ** (1 / 3) if w > 0 else 0.0


def adhesion_parameter(surface: Surface, material: Material) -> float:
    """Fuller–Tabor adhesion parameter θ = E* σ^{3/2}/(R^{1/2} w) (inf for w = 0).

    θ = (σ/ℓ)^{3/2} with ℓ = (R w²/E*²)^{1/3} the JKR length of one summit: the
    ratio of the roughness to the distance over which a summit's adhesion acts.
    Fuller & Tabor (1975) plot pull-off against the inverse of Δ_c = |δ_c|/σ,
    δ_c = ¾(π² w² R/E*²)^{1/3} the JKR break-off under fixed grips, i.e. against
    σ/|δ_c| = θ^{2/3}/(¾ π^{2/3}) = 0.6216 θ^{2/3}: the same group up to a power and
    a constant. Pull-off falls to almost nothing for θ ≳ 10.
    """
    w = material.gamma
    if w == 0:
        return math.inf
    return material.E_star * surface.sigma**1.5 / (math.sqrt(surface.R) * w)


def choose_law(surface: Surface, material: Material) -> tuple[str, str]:
    """The law set the Johnson–Greenwood adhesion map picks, and why (one line).

    DMT for λ < 0.1, JKR for λ > 5, Maugis–Dugdale between (at the low loads that
    decide pull-off). Needs z0.

    Raises
    ------
    ParameterError
        Without z0 (λ is unknown).
    """
    lam = maugis_parameter(surface, material)
    if lam is None:
        raise ParameterError(
            "law = 'auto' needs the material's z0 (equilibrium spacing, m) to place the "
            "contact on the Johnson-Greenwood adhesion map"
        )
    if lam < DMT_BELOW:
        name, zone = "dmt", f"< {DMT_BELOW:g}: DMT zone"
    elif lam > JKR_ABOVE:
        name, zone = "jkr", f"> {JKR_ABOVE:g}: JKR zone"
    else:
        name, zone = (
            "maugis-dugdale",
            f"between {DMT_BELOW:g} and {JKR_ABOVE:g}: JKR-DMT transition",
        )
    return name, (
        f"law auto: {name} (Maugis lambda = {lam:.3g} {zone} of the Johnson-Greenwood 1997 "
        "adhesion map)"
    )


def regime_warnings(surface: Surface, material: Material, law: str | LawSet) -> list[str]:
    """One line per reason the law set is outside its regime (empty if none).

    ``jkr`` at λ < 5, ``dmt`` at λ > 0.1 (Johnson & Greenwood 1997), except without
    adhesion (w = 0: every adhesive law set is Hertz, in no zone of the map); any elastic
    law set (one that does not take the hardness H) at ψ > 1. The seed law set, the
    paper's model as written, is never flagged here.
    """
    laws = get_law_set(law)
    if laws.name == "seed":
        return []
    out = []
    lam = maugis_parameter(surface, material) if material.gamma > 0 else None
    if lam is not None and laws.name == "jkr" and lam < JKR_ABOVE:
        out.append(f"law jkr used at Maugis lambda = {lam:.3g} < {JKR_ABOVE:g}, outside the JKR "
                   "zone of the Johnson-Greenwood adhesion map (use maugis-dugdale or --law auto)")  # fmt: skip
    if lam is not None and laws.name == "dmt" and lam > DMT_BELOW:
        out.append(f"law dmt used at Maugis lambda = {lam:.3g} > {DMT_BELOW:g}, outside the DMT "
                   "zone of the Johnson-Greenwood adhesion map (use maugis-dugdale or --law auto)")  # fmt: skip
    psi = plasticity_index(surface, material)
    if psi is not None and psi > 1 and "H" not in laws.requires:
        out.append(f"plasticity index psi = {psi:.3g} > 1: most summits yield, which the elastic "
                   f"law set {laws.name} ignores")  # fmt: skip
    return out


@dataclass(frozen=True)
class AdhesionSummary:
    """Pull-off, work of separation, hysteresis and regime numbers of a rough contact.

    Attributes
    ----------
    law : str
        Law set.
    turn : float
        Closest approach h_turn = d_turn/σ before retraction.
    turn_from : str
        How ``turn`` was chosen: ``"zero load on approach"``, ``"given"``, or (no
        tensile approach load, so no adhesive rest) ``"none: ..."``.
    pull_off : float
        Magnitude of the most tensile net load on retraction, force/(A_n K); 0 if the
        load never turns tensile.
    h_pull_off : float
        Separation d/σ of the pull-off; NaN (undefined) when ``pull_off`` is 0.
    pull_off_pressure : float
        ``pull_off`` × K: the pull-off force per nominal area, Pa.
    work_of_separation : float
        ∫ tensile load dd on retraction from the turn, J/m² of nominal area.
    hysteresis : float
        ∫ (load_approach − load_retract) dd from the turn, J/m².
    tabor, maugis_lambda : float or None
        μ_T and λ of one summit (None without z0).
    adhesion_parameter : float
        Fuller–Tabor θ = E* σ^{3/2}/(R^{1/2} w).
    plasticity_index : float or None
        ψ = (E*/H)√(σ/R) (None without H).
    warnings : tuple of str
        Regime warnings (:func:`regime_warnings`).
    validity : tuple of str
        Where GW itself does not hold (:mod:`mcsim.physics.validity`): a real contact area at
        the turn beyond the nominal area or where summits interact, a work of separation of
        the contact above w.
    work_of_separation_contact, work_of_separation_vdw, work_of_separation_capillary : float or None
        With an environment: the parts of ``work_of_separation`` (J/m²): the contact
        integral, and the van der Waals and capillary works from the turn to infinity;
        None without.
    kelvin_radius : float or None
        Kelvin radius r_K of the environment, m (0 when dry); None without.
    rq, summit_offset : float or None
        Rms height and mean summit height above the mean plane used by the environment,
        m (:func:`mcsim.physics.gapheights.gap_heights`); None without.
    heights_source : str or None
        Where ``rq`` and ``summit_offset`` come from: ``"given"`` or the Nayak estimate.
    """

    law: str
    turn: float
    turn_from: str
    pull_off: float
    h_pull_off: float
    pull_off_pressure: float
    work_of_separation: float
    hysteresis: float
    tabor: float | None
    maugis_lambda: float | None
    adhesion_parameter: float
    plasticity_index: float | None
    warnings: tuple[str, ...] = ()
    validity: tuple[str, ...] = ()
    work_of_separation_contact: float | None = None
    work_of_separation_vdw: float | None = None
    work_of_separation_capillary: float | None = None
    kelvin_radius: float | None = None
    rq: float | None = None
    summit_offset: float | None = None
    heights_source: str | None = None

    def to_dict(self) -> dict:
        """Plain dict (JSON-ready apart from NaN/inf, which the CLI writes as null)."""
        return asdict(self)


def top_separation(surface: Surface, laws: LawSet, material: Material) -> float:
    """Separation h above which no summit carries force on either branch."""
    heights = surface.heights
    top = float(heights.edges[-1]) if hasattr(heights, "edges") else GAUSSIAN_TOP
    lowest = min(min(e.reach, e.break_off, 0.0) for e in _edges(surface, laws, material))
    return top - lowest / surface.sigma


def _edges(surface: Surface, laws: LawSet, material: Material) -> list:
    """The law set's edges for each of the surface's radii (one, or one per band of heights)."""
    return [laws.edges_for(part, material) for part in surface.components()]


def bottom_separation(surface: Surface) -> float:
    heights = surface.heights
    return float(heights.edges[0]) if hasattr(heights, "edges") else -GAUSSIAN_TOP


def _kinks(surface, material, laws, turn: float, top: float) -> np.ndarray:
    """Separations in (turn, top) where the retraction load may have a kink.

    Where an edge in δ (reach, break-off, 0, jump-in, breakpoints) meets an edge in
    δ_max (jump-in, breakpoints), and, for a histogram, where an edge in δ crosses a
    bin edge (the density jumps there), or a band edge of a radius by height (the radius
    does); for each of the surface's radii.
    """
    sigma, h = surface.sigma, []
    jumps = [surface.heights.edges] if hasattr(surface.heights, "edges") else []
    if surface.radius_by_height is not None:
        jumps.append(np.asarray(surface.radius_by_height.edges))
    for edges in _edges(surface, laws, material):
        in_delta = np.array([0.0, edges.reach, edges.break_off, edges.jump_in, *edges.breakpoints])
        in_max = np.array([edges.jump_in, *edges.breakpoints])
        h.append(turn + (in_max[:, None] - in_delta[None, :]).ravel() / sigma)
        h += [(s[:, None] - in_delta[None, :] / sigma).ravel() for s in jumps]
    h = np.concatenate(h)
    return np.unique(h[(h > turn) & (h < top)])


def zero_load_separation(
    surface: Surface, material: Material, law: str | LawSet, environment: Environment | None = None
) -> float:
    """Separation h where the approach load first turns compressive, coming from far away.

    The surfaces rest there under no external load (the stable zero of the load:
    tensile above, compressive below). Bracketed on a grid from where no summit
    reaches down to the lowest summit (further down if the load is still tensile
    there, as for summits much rougher in adhesion than in height), then solved by
    Brent's method to 1e-12 in h.

    Raises
    ------
    NoAdhesiveRest
        If the approach load is never tensile where the quadrature sees summits (no
        adhesion, or too little for the roughness): the surfaces rest out of contact.
    ParameterError
        If the load is still tensile at h = -1e6.
    """
    from scipy import optimize  # here, not at import: a sweep's fast path does without it

    laws = get_law_set(law)
    top, bottom = top_separation(surface, laws, material), bottom_separation(surface)
    # Below the lowest summit every summit is pressed in: extend the scan downwards
    # (doubling its span) until the load turns compressive, or up to |h| = 1e6.
    while True:
        h = np.linspace(top, bottom, GRID)
        load = analytic_curves(surface, material, h, laws, environment=environment).load
        tensile = np.flatnonzero(load < 0)
        if tensile.size == 0:
            raise NoAdhesiveRest(
                f"law set {laws.name!r}: the approach load is never tensile, so there is no "
                "separation of zero external load; give turn (--turn=H)"
            )
        after = np.flatnonzero((load > 0) & (np.arange(h.size) > tensile[0]))
        if after.size or bottom < -1e6:
            break
        bottom = top - 2 * (top - bottom)
    if after.size == 0:
        raise ParameterError(
            f"law set {laws.name!r}: the approach load stays tensile down to h = {h[-1]:g}; "
            "give turn (--turn=H)"
        )
    i = after[0]

    def f(x: float) -> float:
        return float(analytic_curves(surface, material, [x], laws, environment=environment).load[0])

    return float(optimize.brentq(f, h[i], h[i - 1], xtol=1e-12, rtol=4 * np.finfo(float).eps))


def adhesion_summary(
    surface: Surface,
    material: Material,
    law: str | LawSet,
    turn: float | None = None,
    environment: Environment | None = None,
) -> AdhesionSummary:
    """Adhesion summary from the analytic curves (see the module docstring).

    Parameters
    ----------
    surface, material : Surface, Material
        The contact.
    law : str or LawSet
        A law set with a ``load`` output and a retraction branch.
    turn : float, optional
        Closest approach h_turn = d_turn/σ; default the separation of zero load on
        approach (:func:`zero_load_separation`). Where the approach load is never
        tensile (no adhesion, or too little for the roughness) the surfaces rest apart
        under no load: the summary then has pull-off, work of separation and
        hysteresis 0, ``turn`` the top of the summit population and ``turn_from``
        saying so.
    environment : Environment or mapping, optional
        An Environment, or its fields as a mapping (:func:`~mcsim.physics.environment.as_environment`).
        Van der Waals and capillary attraction across the gaps (see the module
        docstring); None (default): the contact alone, exactly as without it.

    Returns
    -------
    AdhesionSummary
        Regime warnings are also issued as :class:`RegimeWarning`, and GW's validity
        warnings (its ``validity``) as :class:`~mcsim.physics.validity.ValidityWarning`.

    Raises
    ------
    ParameterError
        A law set without a ``load`` or a retraction branch, or a missing material field.
    """
    environment = as_environment(environment)
    from scipy import optimize

    laws = contact_law(get_law_set(law), environment)  # one interface: w less van der Waals
    if "load" not in laws.names:
        raise ParameterError(
            f"law set {laws.name!r} has no net load (the seed's Eq. 4 term is not a tensile "
            "force): use a contact law set (jkr, dmt, maugis-dugdale) or law auto"
        )
    laws.check_branch("retract")
    if turn is None:
        try:
            turn = zero_load_separation(surface, material, laws, environment)
            turn_from = "zero load on approach"
        except NoAdhesiveRest:
            # Under no external load the surfaces never come together: nothing to pull off.
            top = top_separation(surface, laws, material)
            return _summary(surface, material, laws, top,
                            "none: the mean approach load is never tensile, so the mean curve of an "
                            "infinite surface rests apart",
                            0.0, math.nan, 0.0, 0.0,
                            _environment_parts(surface, top, environment, 0.0, zero=True))  # fmt: skip
    else:
        turn, turn_from = check_range("turn", turn, "1"), "given"
    top = max(top_separation(surface, laws, material), turn)

    def load(x, branch: str) -> np.ndarray:
        return analytic_curves(surface, material, np.atleast_1d(x), laws, branch=branch,
                         turn=turn if branch == "retract" else None).load  # fmt: skip

    # Panels on [turn, top], split where the retraction load changes sign (a kink of
    # max(−load, 0)); Gauss–Legendre nodes on each, both branches in one call each.
    coarse = np.linspace(turn, top, PANELS + 1)
    on_coarse = load(coarse, "retract")
    change = np.flatnonzero(np.sign(on_coarse[:-1]) * np.sign(on_coarse[1:]) < 0)
    roots = [
        optimize.brentq(lambda x: load(x, "retract")[0], coarse[j], coarse[j + 1], xtol=1e-13)
        for j in change
        # At the zero-load turn the load is 0 to rounding, and its sign can differ between
        # this one-point evaluation and the grid's: no root inside the panel then.
        if load(coarse[j], "retract")[0] * load(coarse[j + 1], "retract")[0] < 0
    ]
    cuts = np.unique(np.concatenate([coarse, roots, _kinks(surface, material, laws, turn, top)]))
    x, w = np.polynomial.legendre.leggauss(NODES)
    half = np.diff(cuts)[:, None] / 2
    nodes = ((cuts[:-1, None] + cuts[1:, None]) / 2 + half * x).ravel()
    weights = (half * w).ravel()
    retract = load(nodes, "retract")
    approach = load(nodes, "approach")
    scale = material.K * surface.sigma  # load·K is force per nominal area; dd = σ dh
    work = -scale * float(np.sum(weights * retract))  # −∫ F dd: signed (module docstring)
    hysteresis = scale * float(np.sum(weights * (approach - retract)))
    # Pull-off: bounded minimisation around the lowest of the nodes and panel edges (and,
    # with an environment, of a grid above the summits, where the attraction alone acts).
    grid = np.concatenate([cuts, nodes])
    values = np.concatenate([load(cuts, "retract"), retract])
    if environment is not None:
        grid = np.concatenate([grid, np.linspace(top, environment_top_separation(surface, environment),
                                                 PANELS + 1)[1:]])  # fmt: skip
        values = np.concatenate([values, load(grid[values.size :], "retract")])
        values = values - _attraction(surface, material, environment, grid)
        contact_load = load

        def load(x, branch: str) -> np.ndarray:  # the net load
            return contact_load(x, branch) - _attraction(surface, material, environment, x)

    order = np.argsort(grid)
    grid, values = grid[order], values[order]
    i = int(np.argmin(values))
    pull_off, h_pull_off = 0.0, math.nan
    if values[i] < 0:
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
        best = optimize.minimize_scalar(
            lambda x: load(x, "retract")[0], bounds=(lo, hi), method="bounded",
            options={"xatol": H_TOLERANCE},
        )  # fmt: skip
        x, value = (best.x, best.fun) if best.fun <= values[i] else (grid[i], values[i])
        pull_off, h_pull_off = -float(value), float(x)
    parts = _environment_parts(surface, turn, environment, work)
    if parts:
        work = parts["work_of_separation_contact"] + parts["work_of_separation_vdw"]
        work += parts["work_of_separation_capillary"]
    return _summary(surface, material, laws, turn, turn_from, pull_off, h_pull_off, work,
                    hysteresis, parts)  # fmt: skip


def _attraction(surface: Surface, material: Material, environment: Environment, h) -> np.ndarray:
    """Van der Waals plus capillary attraction per nominal area over K at separations h."""
    p = environment_curves(np.asarray(h, dtype=float), surface, environment)
    return (p["vdw"] + p["capillary"]) / material.K


def environment_top_separation(surface: Surface, environment: Environment) -> float:
    """Separation h above which every gap is open and wider than the condensation gap:
    there the attraction only falls with h (beyond the highest heights, ~9 rq)."""
    gap = gap_heights(surface)
    heights = gap.heights
    highest = float(heights.sigma * heights.edges[-1]) if hasattr(heights, "edges") else (
        GAUSSIAN_TOP * gap.rq)  # fmt: skip
    sharpest = min(part.R for part in surface.components())  # the deepest band edge
    widest = max(environment.condensation_gap, band_edge(sharpest, surface.eta, environment))
    return (highest + widest - gap.summit_offset) / surface.sigma


def _environment_parts(surface, turn, environment, contact_work, zero=False) -> dict:
    """The environment's fields of the summary at the turn (empty without an environment);
    ``zero``: the surfaces rest apart, no work."""
    if environment is None:
        return {}
    gap = gap_heights(surface)
    works = environment_works(np.float64(turn), surface, environment)
    return {
        "work_of_separation_contact": float(contact_work),
        "work_of_separation_vdw": 0.0 if zero else float(works["vdw"]),
        "work_of_separation_capillary": 0.0 if zero else float(works["capillary"]),
        "kelvin_radius": environment.kelvin_radius,
        "rq": gap.rq,
        "summit_offset": gap.summit_offset,
        "heights_source": gap.source,
    }


def _summary(surface, material, laws, turn, turn_from, pull_off, h_pull_off, work, hysteresis,
             parts=None):  # fmt: skip
    notes = tuple(regime_warnings(surface, material, laws))
    for note in notes:
        warnings.warn(note, RegimeWarning, stacklevel=3)
    contact_work = (parts or {}).get("work_of_separation_contact", work)
    validity = tuple(analytic_curves(surface, material, [turn], laws).validity_warnings()
                     + work_warnings(contact_work, material.w))  # fmt: skip
    for note in validity:
        warnings.warn(note, ValidityWarning, stacklevel=3)
    return AdhesionSummary(
        law=laws.name,
        turn=float(turn),
        turn_from=turn_from,
        pull_off=pull_off,
        h_pull_off=h_pull_off,
        pull_off_pressure=pull_off * material.K,
        work_of_separation=work,
        hysteresis=hysteresis,
        tabor=tabor_parameter(surface, material),
        maugis_lambda=maugis_parameter(surface, material),
        adhesion_parameter=adhesion_parameter(surface, material),
        plasticity_index=plasticity_index(surface, material),
        warnings=notes,
        validity=validity,
        **(parts or {}),
    )

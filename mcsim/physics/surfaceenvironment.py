"""The environment over a GW surface: each summit's cap, and the open gaps between the caps.

See docs/physics.md, sections 'The environment: summits and open gaps' and 'The environment
covers the surface once'.

The whole surface's attraction is the proximity model of :mod:`mcsim.physics.environment`
over the surface's own heights about its mean plane (:func:`proximity_pressures`: every
local gap g ≥ D0 once, the rest contact). It is shared in two parts: each GW summit's
**cap** owns the local gaps D0 ≤ u < u_c near it (per-summit laws,
:mod:`mcsim.physics.laws.attraction`, appended to the law set by :func:`with_environment`,
:func:`band_edge`), and the **open gaps** carry the rest, the whole surface's attraction less
the caps' expectation over the summit heights (:func:`open_gap_pressures`). On average over
the summits the two cover the surface's own gaps exactly once at every separation; a pad's
caps carry its summits' fluctuations about that average. :func:`environment_curves` and
:func:`environment_works` give both.

**One interface, one law** (:func:`vdw_share`, :func:`contact_law`): the solids' van der Waals
attraction is part of their interface's work of adhesion w, not an addition to it. Its share
w_vdW = A/(12π D0²)·1/(1 + b D0) (the retarded flat–flat van der Waals energy at contact,
:func:`mcsim.physics.vanderwaals.vdw_flat_energy`) acts through the caps and
the open gaps, and the contact law carries the rest, w − w_vdW (the short-range part), so a
touching summit's adhesion sums to w once (docs/physics.md); :func:`interface_notes` says how
w is shared.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from mcsim.model.errors import ParameterError
from mcsim.physics.capillary import capillary_pressure, capillary_work
from mcsim.physics.environment import Environment
from mcsim.physics.gapheights import gap_heights
from mcsim.physics.laws import Edges, LawSet, Output, attraction
from mcsim.physics.vanderwaals import vdw_flat_energy, vdw_pressure, vdw_work


def band_edge(R: float, eta: float, env: Environment) -> float:
    """Band edge u_c, m: the deepest local gap a summit's cap owns (docs/physics.md,
    section 'The environment: summits and open gaps').

    u_c = D0 + 1/(2πRη): a paraboloid of radius R has area 2πR per unit depth of local gap,
    so its open part D0 ≤ u < u_c has area 1/η, its summit's share of the nominal area
    (GW's picture of a summit). Local gaps u ≥ u_c are the open gaps between the caps.

    Parameters
    ----------
    R : float
        Summit radius, m.
    eta : float
        Summit density η, m⁻².
    env : Environment
    """
    return env.cutoff + 1 / (2 * math.pi * R * eta)


def summit_parameters(surface, env: Environment) -> dict[str, float]:
    """Parameters of the per-summit laws of :mod:`mcsim.physics.laws.attraction` (SI):
    ``hamaker`` (0 without van der Waals), ``cutoff`` (D0), ``band`` (u_c), ``retardation``
    (b = 5.32/λ, m⁻¹; 0 non-retarded), ``laplace``
    (γ_L/r_K, 0 without condensation), ``gap_k``, the cap's condensation gap min(g_K, u_c)
    (D0 without condensation): the rest of the condensate lies in the open gaps, and
    ``wet_floor``, the cap's wet floor min(max(D0, 2t), its gap_k) (D0 without condensation)."""
    u_c = band_edge(surface.R, surface.eta, env)
    gap_k = max(min(env.condensation_gap, u_c), env.cutoff) if env.has_capillary else env.cutoff
    return {
        "hamaker": env.hamaker or 0.0,
        "cutoff": env.cutoff,
        "band": u_c,
        "retardation": env.retardation,
        "laplace": env.laplace_pressure,
        "gap_k": gap_k,
        "wet_floor": min(env.wet_floor, gap_k),
    }


def active_terms(env: Environment) -> tuple[str, ...]:
    """``"vdw"`` and/or ``"capillary"``: the environment's terms that act."""
    return tuple(t for t, on in (("vdw", env.has_vdw), ("capillary", env.has_capillary)) if on)


#: The per-summit outputs of the environment (:func:`with_environment`).
SUMMIT_OUTPUTS = {
    "vdw": Output("vdw", "N", attraction.vdw_summit,
                  "van der Waals attraction of the summit's open cap (> 0 attractive)"),
    "capillary": Output("capillary", "N", attraction.capillary_summit,
                        "capillary attraction of the summit's meniscus (> 0 attractive)"),
}  # fmt: skip


def vdw_share(w: float, env: Environment | None) -> float:
    """The van der Waals part w_vdW of the interface's work of adhesion w, J/m².

    w_vdW = A/(12π D0²)·1/(1 + b D0), the retarded energy per unit area of two flats at the
    cutoff gap D0 (:func:`mcsim.physics.vanderwaals.vdw_flat_energy`: Gregory 1981; b = 0,
    Israelachvili, *Intermolecular and Surface Forces*, 3rd ed., Eq. 13.11): the caps carry
    it as a sphere–flat pull of up to 2πR·w_vdW (Derjaguin), the open gaps as the flat–flat
    pressure. The contact law then carries w − w_vdW (:func:`contact_law`). With w = 0 (a
    contact law without adhesion) the van der Waals attraction is the interface's whole
    adhesion. 0 without van der Waals.

    Parameters
    ----------
    w : float
        The interface's work of adhesion (the material's w), J/m².
    env : Environment or None

    Raises
    ------
    ParameterError
        w_vdW > w > 0: one interface's van der Waals part cannot exceed its work of adhesion.
    """
    if env is None or not env.has_vdw:
        return 0.0
    share = float(vdw_flat_energy(env.cutoff, env.hamaker, env.retardation))
    if 0 < w < share:
        raise ParameterError(
            f"the van der Waals part of the interface's adhesion, {_SHARE} = {share:.4g} "
            f"J/m^2 (A = {env.hamaker:.4g} J, D0 = cutoff = {env.cutoff * 1e9:.4g} nm, "
            f"{env.retardation_label}), exceeds its work of adhesion w = {w:.4g} J/m^2: one "
            f"interface has one adhesion; give w >= {share:.4g} J/m^2, a smaller hamaker or "
            f"cutoff >= {_least_cutoff(w, env) * 1e9:.4g} nm"
        )
    return share


#: The van der Waals share's formula, as messages write it (b = 5.32/λ).
_SHARE = "A/(12 pi D0^2 (1 + b D0))"


def _least_cutoff(w: float, env: Environment) -> float:
    """The cutoff D0 (m) at which the van der Waals share equals ``w``: the positive root of
    b D0³ + D0² = A/(12π w), whose left side rises with D0."""
    c = env.hamaker / (12 * math.pi * w)
    roots = np.roots([env.retardation, 1.0, 0.0, -c])
    return float(max(r.real for r in roots if abs(r.imag) <= 1e-9 * abs(r)))


def contact_adhesion(w: float, env: Environment | None) -> float:
    """The work of adhesion the contact law carries, J/m²: w − :func:`vdw_share` (0 for w = 0)."""
    share = vdw_share(w, env)
    return w - share if w > 0 else 0.0


def contact_law(law: LawSet, env: Environment | None) -> LawSet:
    """Law set ``law`` carrying the interface's adhesion less its van der Waals share.

    Its parameters take the work of adhesion :func:`contact_adhesion` (``gamma``, and every
    constant the law set derives from it), so that with the environment's van der Waals
    attraction the interface's adhesion is counted once. ``law`` itself (the same object)
    without van der Waals, for the seed (its net load is P − vdw − capillary: Eq. 4's
    adhesion term F is not in it, and its F, T and μ stay the paper's Eqs. 4–8), and a law
    set already so made.
    """
    if env is None or not env.has_vdw or "load" not in law.names:
        return law
    if getattr(law.constants, "interface", None) is not None:
        return law

    def constants(s, m) -> dict:
        contact = dataclasses.replace(m, gamma=contact_adhesion(m.gamma, env))
        return {**law.constants(s, contact), "gamma": contact.gamma}

    constants.interface = env  # marks the split as made (a law set is frozen; its parts are not)
    return dataclasses.replace(law, constants=constants)


def with_environment(law: LawSet, env: Environment | None) -> LawSet:
    """Law set ``law`` with the environment's per-summit outputs ``vdw`` and ``capillary``
    (N, > 0 attractive; the active ones) appended, acting down to δ = −u_c, its own
    adhesion less the van der Waals share (:func:`contact_law`).

    The outputs are the summits' caps (:mod:`mcsim.physics.laws.attraction`); the open gaps
    between them are :func:`open_gap_pressures`, which are not per summit. Their parameters
    (:func:`summit_parameters`) are the surface's the law set is asked for: one band of a
    radius by height gets its own. Without an active environment, ``law`` itself (the same
    object: nothing changes).
    """
    if env is None or not env.active:
        return law
    terms = active_terms(env)
    contact = contact_law(law, env)

    def edges(params) -> Edges:
        # Down to the band edge whichever terms act: the summits drawn, hence a pad's, are
        # then the same at every humidity and Hamaker constant (common random numbers).
        base = law.edges(params)
        cuts = {-params["cutoff"], -params["wet_floor"], -params["gap_k"], -params["band"]}
        return Edges(min(base.reach, -params["band"]), base.jump_in, base.break_off,
                     tuple(sorted({*base.breakpoints, *cuts})))  # fmt: skip

    def constants(s, m) -> dict:
        return {**contact.constants(s, m), **summit_parameters(s, env)}

    constants.interface = env
    outputs = (*law.outputs, *(SUMMIT_OUTPUTS[t] for t in terms))
    return dataclasses.replace(law, outputs=outputs, edges=edges, constants=constants)


#: Panels of the caps' integrals between D0 and u_c, in geometric steps of local gap (the
#: van der Waals force of a cap varies as u⁻²): 16 give 1e-11 relative on the four presets.
_CAP_PANELS = 16


def _summit_expectation(h, surface, env: Environment, work: bool) -> dict[str, np.ndarray]:
    """η E[F] (Pa) or η E[W] (J/m²) of the summits' caps at separations ``h`` (= d/σ),
    over the surface's summit heights (Gaussian or measured), panel by panel; with a radius by
    height, the sum over its bands, each with its own radius and band edge."""
    parts = surface.components()
    if len(parts) > 1:
        out = [_summit_expectation(h, part, env, work) for part in parts]
        return {term: np.sum([o[term] for o in out], axis=0) for term in out[0]}
    h = np.atleast_1d(np.asarray(h, dtype=float))
    sigma, p = surface.sigma, summit_parameters(surface, env)
    R, D0, u_c, g_k, floor = surface.R, p["cutoff"], p["band"], p["gap_k"], p["wet_floor"]
    vdw = attraction.vdw_summit_work if work else attraction.vdw_summit
    cap = attraction.capillary_summit_work if work else attraction.capillary_summit

    def integrand(delta, rows):
        d = sigma * delta
        return np.stack([vdw(d, p["hamaker"], R, D0, u_c, p["retardation"]),
                         cap(d, p["laplace"], R, floor, g_k)])  # fmt: skip

    # Below δ = −u_c a cap's forces and works are 0; between the edges they are smooth, the
    # van der Waals ones varying as u⁻² over D0 ≤ u < u_c: panels in geometric steps there.
    steps = D0 * (u_c / D0) ** (np.arange(1, _CAP_PANELS) / _CAP_PANELS)
    columns = [-u_c / sigma, *sorted(-np.array([u_c, g_k, floor, D0, *steps]) / sigma), 0.0]
    breaks = np.tile(np.asarray(columns), (h.size, 1))
    scale, integral = surface.heights.gw_integrals(integrand, h, breaks)
    out = surface.eta * scale * integral
    return {"vdw": out[0], "capillary": out[1]}


def _gaps(h, surface):
    """Mean-plane gaps D = hσ + y_s (m) and the heights about the mean plane."""
    gap = gap_heights(surface)
    return np.asarray(h, dtype=float) * surface.sigma + gap.summit_offset, gap.heights


def proximity_pressures(h, surface, env: Environment) -> dict[str, np.ndarray]:
    """The environment's attraction over the whole surface, Pa (> 0 attractive): the
    proximity model over the surface's own heights about its mean plane, every local gap
    g = D − z ≥ D0 once (:func:`vdw_pressure`, :func:`capillary_pressure` with the cutoff D0).

    This is the expected attraction of the summits' caps and the open gaps together
    (:func:`environment_curves`): its areas are those of the surface itself (docs/physics.md,
    section 'The environment covers the surface once').

    Parameters
    ----------
    h : array_like
        Separations d/σ from the mean summit plane (D = hσ + y_s).
    surface : Surface
    env : Environment

    Returns
    -------
    dict
        ``"vdw"``, ``"capillary"``, Pa (zeros where off).
    """
    D, heights = _gaps(h, surface)
    zero = np.zeros(np.shape(D))
    args = env.cutoff, env.surface_tension, env.kelvin_radius, env.contact_angle, env.film
    return {
        "vdw": vdw_pressure(D, heights, env.hamaker, env.cutoff, env.retardation)
        if env.has_vdw
        else zero,
        "capillary": capillary_pressure(D, heights, *args) if env.has_capillary else zero,
    }


def proximity_works(h_t, surface, env: Environment) -> dict[str, np.ndarray]:
    """Works of :func:`proximity_pressures` from ``h_t`` (= d_t/σ) outward, J/m²:
    :func:`vdw_work` and :func:`capillary_work` with the cutoff D0."""
    D, heights = _gaps(h_t, surface)
    zero = np.zeros(np.shape(D))
    args = env.cutoff, env.surface_tension, env.kelvin_radius, env.contact_angle, env.film
    return {
        "vdw": vdw_work(D, heights, env.hamaker, env.cutoff, env.retardation)
        if env.has_vdw
        else zero,
        "capillary": capillary_work(D, heights, *args) if env.has_capillary else zero,
    }


def _rest(whole: dict, caps: dict, env: Environment) -> dict[str, np.ndarray]:
    """``whole`` less the caps' expectation, term by term (the caps' zero where off)."""
    terms = active_terms(env)
    return {t: whole[t] - (caps[t].reshape(np.shape(whole[t])) if t in terms else 0.0)
            for t in ("vdw", "capillary")}  # fmt: skip


def open_gap_pressures(h, surface, env: Environment) -> dict[str, np.ndarray]:
    """Attraction of the surface outside the summits' caps, Pa (> 0 attractive).

    The whole surface's attraction (:func:`proximity_pressures`) less the caps' expectation
    over the summit heights: the caps (:mod:`mcsim.physics.laws.attraction`, per summit)
    then carry their own fluctuations, and caps plus open gaps cover the surface's own gaps
    exactly once at every separation, on average over the summits. Where the caps' rigid
    paraboloids claim more of some gap than the surface has (deep in contact), this rest is
    negative: it takes back what the caps over-count (docs/physics.md).

    Parameters
    ----------
    h : array_like
        Separations d/σ from the mean summit plane.
    surface : Surface
    env : Environment

    Returns
    -------
    dict
        ``"vdw"``, ``"capillary"``, Pa (zeros where off).
    """
    caps = _summit_expectation(h, surface, env, work=False)
    return _rest(proximity_pressures(h, surface, env), caps, env)


def open_gap_works(h_t, surface, env: Environment) -> dict[str, np.ndarray]:
    """Works of :func:`open_gap_pressures` from ``h_t`` (= d_t/σ) outward, J/m²: the whole
    surface's (:func:`proximity_works`) less the caps' expected works."""
    caps = _summit_expectation(h_t, surface, env, work=True)
    return _rest(proximity_works(h_t, surface, env), caps, env)


def _split(whole: dict, caps: dict, env: Environment, shape) -> dict[str, np.ndarray]:
    out = {}
    for term in ("vdw", "capillary"):
        on = term in active_terms(env)
        cap = caps[term].reshape(shape) if on else np.zeros(shape)
        out |= {term: whole[term], f"{term}_caps": cap, f"{term}_gaps": whole[term] - cap}
    return out


def environment_curves(h, surface, env: Environment) -> dict[str, np.ndarray]:
    """The environment's attraction per nominal area over a GW separation grid, Pa.

    The whole surface's (:func:`proximity_pressures`: the proximity model over the
    surface's own heights, each local gap once), shared between the summits' caps
    (:mod:`mcsim.physics.laws.attraction`, expected over the summit heights) and the open
    gaps, the rest (:func:`open_gap_pressures`; docs/physics.md, section 'The environment
    covers the surface once').

    Parameters
    ----------
    h : array_like
        Dimensionless separations d/σ (d from the mean summit plane).
    surface : Surface
        Summits (σ, R, η, heights) and the heights about the mean plane
        (:func:`mcsim.physics.gapheights.gap_heights`).
    env : Environment

    Returns
    -------
    dict
        ``"vdw"``, ``"capillary"`` (totals), and their parts ``"vdw_caps"``, ``"vdw_gaps"``,
        ``"capillary_caps"``, ``"capillary_gaps"``; Pa, > 0 attractive, zeros where off.
    """
    caps = _summit_expectation(h, surface, env, work=False)
    return _split(proximity_pressures(h, surface, env), caps, env, np.shape(h))


def environment_works(h_t, surface, env: Environment) -> dict[str, np.ndarray]:
    """Works of the attractions of :func:`environment_curves` from ``h_t`` (= d_t/σ) to far
    away, J/m² (same keys): each the integral of its own pressure over d (the attractions
    have no history)."""
    caps = _summit_expectation(h_t, surface, env, work=True)
    return _split(proximity_works(h_t, surface, env), caps, env, np.shape(h_t))


def interface_notes(surface, material, env: Environment | None) -> list[str]:
    """How the interface's adhesion is shared (text lines; empty without van der Waals).

    One line: the van der Waals share A/(12π D0²)/(1 + b D0) of the work of adhesion w, which the caps
    and the open gaps carry, and the rest, which the contact law carries
    (:func:`vdw_share`); with w = 0, that the van der Waals attraction is the interface's
    whole adhesion. Inputs whose share exceeds w are refused by :func:`vdw_share`.
    """
    if env is None or not env.has_vdw:
        return []
    share = vdw_share(material.gamma, env)
    if material.gamma == 0:
        return [
            f"w = 0: the van der Waals attraction, {_SHARE} = {share:.3g} J/m^2 at contact "
            f"({env.retardation_label}), is the interface's whole adhesion (the contact law "
            "carries none)"
        ]
    return [
        f"one interface: of w = {material.gamma:.3g} J/m^2 the van der Waals part "
        f"{_SHARE} = {share:.3g} J/m^2 ({env.retardation_label}) acts on the summits' caps "
        f"and across the open gaps, and the contact law carries the rest, "
        f"{material.gamma - share:.3g} J/m^2"
    ]


def environment_warnings(surface, env: Environment | None) -> list[str]:
    """Where the environment's model leaves its ground on ``surface`` (text lines; empty
    without an environment; docs/physics.md, section 'The environment covers the surface
    once'):

    * the caps reach deeper than the summits' spread, u_c − D0 = 1/(2πRη) > 3σ: one summit's
      paraboloid then claims gaps its neighbours' heights also own, and the open gaps take
      back the excess (a mean-field correction: a pad's caps overstate its fluctuations);
    * menisci wider than a cap, g_K > u_c: neighbouring summits' menisci merge into one film
      over the open gaps (the caps carry theirs up to u_c, the open gaps the rest).

    With condensation, :data:`EQUILIBRIUM_NOTE` goes beside them as a note.
    """
    if env is None or not env.active:
        return []
    out = []
    for part in surface.components():
        depth = 1 / (2 * math.pi * part.R * part.eta)
        if depth > 3 * surface.sigma:
            out.append(
                f"the summits' caps reach u_c - D0 = 1/(2 pi R eta) = {depth * 1e9:.3g} nm below "
                f"their tips, deeper than 3 sigma = {3 * surface.sigma * 1e9:.3g} nm of the summit "
                "heights: neighbouring caps claim the same gaps and the open gaps take back the "
                "excess (the mean is the surface's own; a pad's fluctuations are overstated)"
            )
            break
    if env.has_capillary:
        u_c = band_edge(surface.R, surface.eta, env)
        if env.condensation_gap > u_c:
            out.append(
                f"menisci merge: the condensation gap g_K = {env.condensation_gap * 1e9:.3g} nm "
                f"exceeds a summit's cap, u_c = {u_c * 1e9:.3g} nm; the water is one film over "
                "the open gaps, carried by the surface's own gaps rather than by summits"
            )
    return out


#: The note beside every result with condensation (:func:`environment_warnings`).
EQUILIBRIUM_NOTE = ("menisci are in equilibrium with the vapour throughout (a slow separation); "
                    "a fast pull-off conserves their volume and pulls less (not modelled)")  # fmt: skip

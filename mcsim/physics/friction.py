"""Static friction of one summit and its GW expectation: the seed's other half for every law set.

See docs/physics.md, section 'Friction of pads'.

Which per-summit law applies (:func:`friction_rule`):

* **Bowden–Tabor** (``"shear"``), T_a = τ·A_a: a law set with ``friction`` (jkr, dmt,
  maugis-dugdale, elastic-plastic) when the material gives a shear strength τ, as the
  ``friction`` curve of :func:`mcsim.gw_curves` already is.
* **Savkoor–Briggs** (``"savkoor-briggs"``), the seed's Eq. 6,
  T_a = 4 √(G/K) √(2πwR P_a + 3(πwR)²), the tangential force at which a JKR contact of
  normal load P_a peels: the seed and jkr summits without τ. For the jkr law set P_a is the
  summit's own JKR load (net, tensile down to its pull-off −(3/2)πwR, where T_a falls to 0),
  not the seed's Hertz load of its interference; w is the contact law's work of adhesion
  (with an environment, the interface's w less its van der Waals share,
  :func:`mcsim.physics.surfaceenvironment.contact_law`).
* Any other combination has no friction: :func:`friction_rule` raises, naming the law sets
  that have it.

The functions here are pure and vectorised; :mod:`mcsim.engine.pads.friction` sums them over a
pad's summits at its turn.
"""

from __future__ import annotations

import numpy as np

from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface
from mcsim.physics.environment import Environment
from mcsim.physics.laws import LawSet, get_law_set

#: Per-summit friction laws, by name.
RULES = ("savkoor-briggs", "shear")

#: Law sets whose summits peel as JKR contacts do (Savkoor–Briggs without τ).
SAVKOOR_BRIGGS = ("seed", "jkr")


def savkoor_briggs(load, R: float, K: float, G: float, w: float):
    """Savkoor–Briggs friction of one summit, T_a = 4 √(G/K) √(2πwR P_a + 3(πwR)²), N.

    The seed's Eq. 6 (Savkoor & Briggs 1977): the tangential force at which a JKR contact
    under the normal load P_a peels. 0 where the radicand is negative (P_a below the JKR
    pull-off −(3/2)πwR: no contact to peel).

    Parameters
    ----------
    load : float or ndarray
        Normal load P_a of the summit, N (compressive positive).
    R : float
        Summit radius, m.
    K, G : float
        Elastic constant and combined shear modulus (seed, Eq. 7), Pa.
    w : float
        Work of adhesion, J/m².
    """
    c = np.pi * w * R
    return 4.0 * np.sqrt(G / K) * np.sqrt(np.maximum(2.0 * c * np.asarray(load) + 3.0 * c * c, 0.0))


def has_friction(law: LawSet | str, material: Material) -> bool:
    """Whether :func:`friction_rule` gives ``law`` a friction with ``material``."""
    laws = get_law_set(law)
    return (laws.friction and material.tau is not None) or laws.name in SAVKOOR_BRIGGS


def friction_rule(law: LawSet | str, material: Material) -> str:
    """The per-summit friction of ``law`` with ``material``: one of :data:`RULES` (module
    docstring).

    Raises
    ------
    ParameterError
        A law set without friction: one line naming the law sets that have it.
    """
    laws = get_law_set(law)
    if laws.friction and material.tau is not None:
        return "shear"
    if laws.name in SAVKOOR_BRIGGS:
        return "savkoor-briggs"
    from mcsim.physics.laws import LAW_SETS

    shear = ", ".join(n for n, s in LAW_SETS.items() if s.friction)
    why = "without a shear strength tau" if laws.friction else "at all"
    raise ParameterError(f"law {laws.name!r} has no friction {why}: law sets with friction are "
                         f"{', '.join(SAVKOOR_BRIGGS)} (Savkoor-Briggs, Eq. 6) and, with the "
                         f"material's tau, {shear} (tau x contact area)")  # fmt: skip


def summit_friction(law: LawSet, params: dict, delta, rule: str) -> np.ndarray:
    """Static friction (N) of summits at interference ``delta`` (m) on approach.

    Parameters
    ----------
    law : LawSet
        The contact law (with an environment, its contact part).
    params : dict
        Its named parameters (:meth:`~mcsim.physics.laws.LawSet.parameters`).
    delta : ndarray
        Interference of each summit, m; only those in contact (δ > jump-in) carry friction.
    rule : str
        One of :data:`RULES` (:func:`friction_rule`).
    """
    delta = np.asarray(delta, dtype=float)
    touching = delta > law.edges(params).jump_in
    d = delta[touching]
    out = np.zeros(delta.shape)
    if rule == "shear":
        out[touching] = params["tau"] * _output(law, "area", params, d)
    elif "T" in law.names:  # the seed: its own Eq. 6, of its Hertz load
        out[touching] = _output(law, "T", params, d)
    else:
        load = _output(law, "load", params, d)
        out[touching] = savkoor_briggs(load, params["R"], params["K"], params["G"], params["gamma"])
    return out


def _output(law: LawSet, name: str, params: dict, delta: np.ndarray) -> np.ndarray:
    """Output ``name`` of ``law`` at ``delta`` (m) on approach (δ_max = δ)."""
    o = law.outputs[law.names.index(name)]
    args = tuple(params[p] for p in o.parameter_names)
    return np.asarray(o.law(delta, delta, *args) if o.stateful else o.law(delta, *args), float)


def gw_static_friction(surface: Surface, material: Material, h, law: LawSet | str,
                       environment: Environment | None = None) -> np.ndarray:  # fmt: skip
    """GW static friction per nominal area over K at separations ``h`` (= d/σ) on approach:
    (η/K) ∫ T_a(σ(s − h)) p(s) ds, T_a of :func:`summit_friction` (dimensionless, the
    normalisation of the ``friction`` curves; a sum over the bands of a radius by height).

    Raises
    ------
    ParameterError
        A law set without friction (:func:`friction_rule`).
    """
    from mcsim.physics.surfaceenvironment import contact_law

    laws = contact_law(get_law_set(law), environment)
    rule = friction_rule(laws, material)
    h = np.atleast_1d(np.asarray(h, dtype=float))
    total = np.zeros(h.shape)
    for part in surface.components():
        params = laws.parameters(part, material)
        sigma, e = part.sigma, laws.edges(params)

        def integrand(delta, rows, params=params, sigma=sigma):
            return summit_friction(laws, params, sigma * delta, rule)[None]

        cuts = np.array([e.jump_in, *sorted({0.0, *e.breakpoints})]) / sigma
        breaks = np.broadcast_to(cuts, (h.size, cuts.size))
        scale, integral = part.heights.gw_integrals(integrand, h, breaks)
        total += part.eta / material.K * scale * integral[0]
    return total

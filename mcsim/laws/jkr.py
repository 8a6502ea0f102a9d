"""Exact JKR under fixed penetration, with approach and retraction (Fuller & Tabor 1975).

A summit at interference δ = z − d (m) with contact radius a obeys (Johnson, Kendall
& Roberts 1971, in the form used by Fuller & Tabor 1975; Johnson 1985, *Contact
Mechanics*, §5.5)::

    δ = a²/R − √(2πwa/E*),        P = 4E*a³/(3R) − √(8πwE*a³),        A = πa²

with w the work of adhesion (the paper's γ, parameter ``gamma``) and E* the contact
modulus. Under fixed penetration (the Greenwood–Williamson separation d is imposed)
the summit follows the stable, larger-a branch of δ(a):

* **approach**: out of contact for δ ≤ 0; for δ > 0 the summit has jumped into
  contact, with a³ = 2πwR²/E* and P = −(4/3)πwR at δ → 0⁺ (Greenwood 1997);
* **retraction**: a summit that touched at the turn (δ_max > 0) stays on the branch
  down to the fold of δ(a), δ_c = −¾ (π²w²R/E*²)^{1/3}, where a³ = πwR²/(8E*) and
  P = −(5/6)πwR (the pull-off under fixed grips; Maugis 2000, *Contact, Adhesion and
  Rupture of Elastic Solids*), and breaks off there.

Inverting δ → a: with u = √a the first relation is the quartic u⁴ − cRu − δR = 0,
c = √(2πw/E*); for δ ≥ δ_c its largest positive root (the stable branch) is found in
closed form (Ferrari's resolvent cubic m³ + δR m − c²R²/8 = 0, solved by Cardano
without cancellation; it has one positive root and a non-negative discriminant for
δ ≥ δ_c), then polished by one Newton step. Measured against 50-digit arithmetic
(R of the smooth and rough surfaces, silicon): load and area within 3e-14 relative
for a > 1.01 a_c, 5e-12 for a > 1.0001 a_c, 5e-10 for a > 1.000001 a_c, a_c the
contact radius at δ_c: next to the fold a(δ) is ill-conditioned (da/dδ → ∞).
δ is clamped to [δ_c, 10⁶⁰ m²/R] before inverting so the values stay finite for
every finite input; the result is multiplied by the in-contact indicator
(δ_max > 0)·(δ > δ_c). w = 0 gives Hertz.

Each output function writes the inversion out in full, so that each compiles on its
own in the Monte Carlo kernel (see :mod:`mcsim.laws`).

References: Johnson, Kendall & Roberts, Proc. R. Soc. Lond. A 324, 301 (1971); Fuller &
Tabor, Proc. R. Soc. Lond. A 345, 327 (1975); Greenwood, Proc. R. Soc. Lond. A 453,
1277 (1997).
"""

import numpy as np

from . import Edges, LawSet, Output


def jkr_load(delta, delta_max, R, E_star, gamma, delta_c):
    """Net normal force of one JKR summit, P = 4E*a³/(3R) − √(8πwE*a³) (Fuller & Tabor 1975).

    Parameters
    ----------
    delta : float or ndarray
        Interference δ = z − d, m.
    delta_max : float or ndarray
        Largest interference reached so far, m (δ itself on approach).
    R : float
        Summit radius, m.
    E_star : float
        Contact modulus E*, Pa.
    gamma : float
        Work of adhesion w, J/m².
    delta_c : float
        Break-off interference δ_c = −¾ (π²w²R/E*²)^{1/3}, m (:func:`break_off`,
        computed once per contact by the law set's ``constants``).

    Returns
    -------
    float or ndarray
        Load, N, compressive positive; zero out of contact (δ_max ≤ 0 or δ ≤ δ_c).
    """
    cR = np.sqrt(2.0 * np.pi * gamma / E_star) * R
    p = np.minimum(np.maximum(delta, delta_c) * R, 1e60)
    q = 0.125 * cR * cR
    disc = np.maximum(0.25 * q * q + p * p * p / 27.0, 0.0)
    A = np.cbrt(0.5 * q + np.sqrt(disc))
    B = p / (3.0 * np.maximum(A, 1e-300))
    # resolvent root m = A − B = q/Q with Q = A² + AB + B² (no cancellation)
    Q = np.maximum(A * A + p / 3.0 + B * B, 1e-300)
    # s = √(2m); largest root u = (s + √(2cR/s − s²))/2, and 2cR/s = 4√Q
    s = cR / (2.0 * np.sqrt(Q))
    u = 0.5 * (s + np.sqrt(np.maximum(4.0 * np.sqrt(Q) - s * s, 0.0)))
    g = u * u * u * u - cR * u - p
    gp = np.maximum(4.0 * u * u * u - cR, 4e-6 * u * u * u) + 1e-300
    u = u - g / gp
    u3 = u * u * u
    load = 4.0 * E_star * u3 * u3 / (3.0 * R) - np.sqrt(8.0 * np.pi * gamma * E_star) * u3
    return (delta_max > 0) * (delta > delta_c) * load


def jkr_area(delta, delta_max, R, E_star, gamma, delta_c):
    """Real contact area of one JKR summit, A = πa² (Fuller & Tabor 1975).

    Parameters
    ----------
    delta : float or ndarray
        Interference δ = z − d, m.
    delta_max : float or ndarray
        Largest interference reached so far, m (δ itself on approach).
    R : float
        Summit radius, m.
    E_star : float
        Contact modulus E*, Pa.
    gamma : float
        Work of adhesion w, J/m².
    delta_c : float
        Break-off interference δ_c = −¾ (π²w²R/E*²)^{1/3}, m (:func:`break_off`,
        computed once per contact by the law set's ``constants``).

    Returns
    -------
    float or ndarray
        Area, m²; zero out of contact (δ_max ≤ 0 or δ ≤ δ_c).
    """
    cR = np.sqrt(2.0 * np.pi * gamma / E_star) * R
    p = np.minimum(np.maximum(delta, delta_c) * R, 1e60)
    q = 0.125 * cR * cR
    disc = np.maximum(0.25 * q * q + p * p * p / 27.0, 0.0)
    A = np.cbrt(0.5 * q + np.sqrt(disc))
    B = p / (3.0 * np.maximum(A, 1e-300))
    # resolvent root m = A − B = q/Q with Q = A² + AB + B² (no cancellation)
    Q = np.maximum(A * A + p / 3.0 + B * B, 1e-300)
    # s = √(2m); largest root u = (s + √(2cR/s − s²))/2, and 2cR/s = 4√Q
    s = cR / (2.0 * np.sqrt(Q))
    u = 0.5 * (s + np.sqrt(np.maximum(4.0 * np.sqrt(Q) - s * s, 0.0)))
    g = u * u * u * u - cR * u - p
    gp = np.maximum(4.0 * u * u * u - cR, 4e-6 * u * u * u) + 1e-300
    u = u - g / gp
    return (delta_max > 0) * (delta > delta_c) * (np.pi * u * u * u * u)


def break_off(R: float, E_star: float, gamma: float) -> float:
    """Fold of δ(a), the break-off interference δ_c = −¾ (π²w²R/E*²)^{1/3}, m.

    The law functions take it as a parameter (its cube root is not recomputed per
    summit), and the edges use the same number, so both agree to the last bit.
    """
    return -0.75 * float(np.cbrt(np.pi * np.pi * gamma * gamma * R / (E_star * E_star)))


def _constants(surface, material) -> dict:
    return {"delta_c": break_off(surface.R, material.E_star, material.gamma)}


def _edges(params) -> Edges:
    return Edges(reach=0.0, jump_in=0.0, break_off=params["delta_c"])


LAW_SET = LawSet(
    name="jkr",
    description="exact JKR under fixed penetration (Fuller & Tabor 1975): jump-in at 0, break-off at delta_c",
    outputs=(
        Output("load", "N", jkr_load, "net normal force, compressive positive"),
        Output("area", "m^2", jkr_area, "real contact area pi a^2"),
    ),
    edges=_edges,
    constants=_constants,
    friction=True,
)

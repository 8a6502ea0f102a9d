"""Exact JKR under fixed penetration, with approach and retraction (Fuller & Tabor 1975).

See docs/physics.md, section 'JKR law set'.

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

Inverting δ → a, in reduced form: with u = √a, s = (cR)^{1/3}, c = √(2πw/E*) and
t = u/s, the first relation is the quartic t⁴ − t = x, x = δR/s⁴, whose fold is at
4t³ = 1, t_c = 4^{-1/3}, x_c = −¾·4^{-1/3} (δ = δ_c). With v = t − t_c ≥ 0 on the stable
branch and X = (δ − δ_c)R/s⁴ = x − x_c ≥ 0 it reads, expanded about the fold,

    G(v) = v² (v² + 4t_c v + 6t_c²) − X = 0,

one root v ≥ 0 for every X ≥ 0. s, R/s⁴ and the scales of the outputs are per-run
constants (:func:`reduced_constants`), so a summit costs two square roots and two
divisions, no cube root and no data-dependent loop (the Monte Carlo kernel vectorises
it): with r = √X, ρ = √r and y = (t_c² − r)/(t_c² + r) ∈ [−1, 1], a starting value
v₀ = (1 − y)(ρ K₁(y) + t_c K₂(y)), K₁ and K₂ degree-6 polynomials fitted (least squares in
the relative error) to within 5e-6 relative of v uniformly from the fold to X → ∞ (the
form follows v: analytic in r at the fold, ρ·f(1/r) + g(1/r) as r → ∞; without
adhesion y = −1 and v₀ = 2K₁(−1)ρ ≈ ρ), then one Halley step on G (cubic
convergence: 1e-16). Then A = π s⁴ t⁴, P = 4E* s⁶ t⁶/(3R) − √(8πwE*) s³ t³. Measured
against 50-digit arithmetic (R of the smooth and rough surfaces, silicon): load and
area within 4e-14 relative for a ≥ 1.01 a_c, 4e-12 for a ≥ 1.0001 a_c, 4e-10 for
a ≥ 1.000001 a_c, a_c the contact radius at δ_c: next to the fold a(δ) is
ill-conditioned (da/dδ → ∞). δ − δ_c is clamped to [0, 1e30 m] and 1e-150 added to X
(against underflow in the Halley step), so the values stay finite for every finite
input; the result is multiplied by the in-contact indicator (δ_max > 0)·(δ > δ_c).
w = 0 gives Hertz (t_c = 0 and s⁴ = R², so t⁴ = δ/R).

The inversion is written once, in the helper :func:`reduced_root` that both outputs call
(:mod:`mcsim.physics.laws`); in the Monte Carlo kernel both are inlined with the same
parameters and LLVM computes the inversion once for both.

References: Johnson, Kendall & Roberts, Proc. R. Soc. Lond. A 324, 301 (1971); Fuller &
Tabor, Proc. R. Soc. Lond. A 345, 327 (1975); Greenwood, Proc. R. Soc. Lond. A 453,
1277 (1997).
"""

import numpy as np

from mcsim.physics.laws import Edges, LawSet, Output


def reduced_root(delta, delta_c, jkr_kappa, jkr_t_c):
    """Reduced root t = √a/s of the stable JKR branch at interference δ (module docstring).

    The root of t⁴ − t = δR/s⁴ with t ≥ t_c: a starting value from the fitted K₁ and K₂
    and one Halley step on G(v) = v²(v² + 4t_c v + 6t_c²) − X, X = (δ − δ_c)R/s⁴, v = t − t_c.

    Parameters
    ----------
    delta : float or ndarray
        Interference δ = z − d, m.
    delta_c : float
        Break-off interference δ_c = −¾ (π²w²R/E*²)^{1/3}, m (:func:`break_off`).
    jkr_kappa : float
        R/s⁴, 1/m (:func:`reduced_constants`).
    jkr_t_c : float
        Reduced fold t_c = 4^{-1/3} (0 without adhesion).

    Returns
    -------
    float or ndarray
        t, dimensionless (a = s²t², m); finite for every finite δ, t_c (to rounding)
        at and below δ_c.
    """
    X = np.minimum(np.maximum(delta - delta_c, 0.0), 1e30) * jkr_kappa + 1e-150
    r = np.sqrt(X)
    rho = np.sqrt(r)
    inv = 1.0 / (jkr_t_c * jkr_t_c + r)  # independent of ρ: a short dependency chain
    y = (jkr_t_c * jkr_t_c - r) * inv
    y2 = y * y
    y4 = y2 * y2
    # K₁(y) and K₂(y), degree 6, in Estrin's scheme
    pa = (0.3800565 - 0.4921 * y) + y2 * (-0.1997725 + 0.3058172 * y)
    pa = pa + y4 * ((0.0787893 - 0.06367068 * y) - 0.009026963 * y2)
    pb = (-0.01694183 + 0.5828661 * y) + y2 * (-0.2408734 - 0.2788102 * y)
    pb = pb + y4 * ((0.1251011 + 0.04789251 * y) - 0.01511029 * y2)
    v = 2.0 * r * inv * (rho * pa + jkr_t_c * pb)
    # one Halley step on G(v) = v²(v² + 4t_c v + 6t_c²) − X
    t = v + jkr_t_c
    g = v * v * (v * v + 4.0 * jkr_t_c * v + 6.0 * jkr_t_c * jkr_t_c) - X
    g1 = 4.0 * v * (v * v + 3.0 * jkr_t_c * t)
    return t - 2.0 * g * g1 / (2.0 * g1 * g1 - 12.0 * g * t * t)


def jkr_load(delta, delta_max, delta_c, jkr_kappa, jkr_t_c, jkr_hertz, jkr_adhesion):
    """Net normal force of one JKR summit, P = 4E*a³/(3R) − √(8πwE*a³) (Fuller & Tabor 1975).

    Parameters
    ----------
    delta : float or ndarray
        Interference δ = z − d, m.
    delta_max : float or ndarray
        Largest interference reached so far, m (δ itself on approach).
    delta_c : float
        Break-off interference δ_c = −¾ (π²w²R/E*²)^{1/3}, m (:func:`break_off`).
    jkr_kappa : float
        R/s⁴, 1/m: X = (δ − δ_c) R/s⁴ (:func:`reduced_constants`, as the next three).
    jkr_t_c : float
        Reduced fold t_c = 4^{-1/3} (0 without adhesion).
    jkr_hertz : float
        4E* s⁶/(3R), N.
    jkr_adhesion : float
        √(8πwE*) s³, N.

    Returns
    -------
    float or ndarray
        Load, N, compressive positive; zero out of contact (δ_max ≤ 0 or δ ≤ δ_c).
    """
    t = reduced_root(delta, delta_c, jkr_kappa, jkr_t_c)
    t3 = t * t * t
    return (delta_max > 0) * (delta > delta_c) * ((jkr_hertz * t3 - jkr_adhesion) * t3)


def jkr_area(delta, delta_max, delta_c, jkr_kappa, jkr_t_c, jkr_area_unit):
    """Real contact area of one JKR summit, A = πa² (Fuller & Tabor 1975).

    Parameters
    ----------
    delta : float or ndarray
        Interference δ = z − d, m.
    delta_max : float or ndarray
        Largest interference reached so far, m (δ itself on approach).
    delta_c : float
        Break-off interference δ_c = −¾ (π²w²R/E*²)^{1/3}, m (:func:`break_off`).
    jkr_kappa : float
        R/s⁴, 1/m: X = (δ − δ_c) R/s⁴ (:func:`reduced_constants`, as the next three).
    jkr_t_c : float
        Reduced fold t_c = 4^{-1/3} (0 without adhesion).
    jkr_area_unit : float
        π s⁴, m².

    Returns
    -------
    float or ndarray
        Area, m²; zero out of contact (δ_max ≤ 0 or δ ≤ δ_c).
    """
    t = reduced_root(delta, delta_c, jkr_kappa, jkr_t_c)
    t2 = t * t
    return (delta_max > 0) * (delta > delta_c) * (jkr_area_unit * t2 * t2)


def break_off(R: float, E_star: float, gamma: float) -> float:
    """Fold of δ(a), the break-off interference δ_c = −¾ (π²w²R/E*²)^{1/3}, m.

    The law functions take it as a parameter (its cube root is not recomputed per
    summit), and the edges use the same number, so both agree to the last bit.
    """
    return -0.75 * float(np.cbrt(np.pi * np.pi * gamma * gamma * R / (E_star * E_star)))


def reduced_constants(R: float, E_star: float, gamma: float) -> dict[str, float]:
    """Per-run constants of the reduced inversion (module docstring), SI.

    Parameters
    ----------
    R : float
        Summit radius, m.
    E_star : float
        Contact modulus E*, Pa.
    gamma : float
        Work of adhesion w, J/m².

    Returns
    -------
    dict
        ``delta_c`` (m), ``jkr_kappa`` = R/s⁴ (1/m), ``jkr_t_c``, ``jkr_hertz`` =
        4E*s⁶/(3R) (N), ``jkr_adhesion`` = √(8πwE*) s³ (N), ``jkr_area_unit`` = πs⁴
        (m²), with s = (cR)^{1/3}, c = √(2πw/E*); without adhesion s⁴ = R² and t_c = 0.
    """
    if gamma > 0:
        s3 = float(np.sqrt(2.0 * np.pi * gamma / E_star)) * R
        s = float(np.cbrt(s3))
        s4, s6, t_c = s3 * s, s3 * s3, float(np.cbrt(0.25))
    else:
        s3, s4, s6, t_c = 0.0, R * R, R**3, 0.0
    return {
        "delta_c": break_off(R, E_star, gamma),
        "jkr_kappa": R / s4,
        "jkr_t_c": t_c,
        "jkr_hertz": 4.0 * E_star * s6 / (3.0 * R),
        "jkr_adhesion": float(np.sqrt(8.0 * np.pi * gamma * E_star)) * s3,
        "jkr_area_unit": np.pi * s4,
    }


def _constants(surface, material) -> dict:
    return reduced_constants(surface.R, material.E_star, material.gamma)


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

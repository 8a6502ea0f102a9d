"""The environment's attraction on one summit: its meniscus and its van der Waals pull.

See docs/physics.md, section 'The environment: summits and open gaps'.

The proximity (Derjaguin) model of :mod:`mcsim.physics.environment` applied to one
spherical cap of radius R whose tip is at gap g = −δ from the flat (Israelachvili,
*Intermolecular and Surface Forces*, 3rd ed., ch. 13 and 17). Around the tip the local gap
is u = g + r²/2R, so the cap's area at local gaps in [u, u + du] is 2πR du, the same at
every u. A pressed summit (g < 0) keeps this rigid profile outside its contact: no
elastic deformation of the open gaps, as in the proximity model. The summit owns the
local gaps u < u_c (its **cap**, u_c the band edge of
:func:`mcsim.physics.surfaceenvironment.band_edge`); every gap u < D0 (the cutoff) is contact,
which belongs to the contact law and is charged nothing here. Per summit, attractive
positive (N):

* van der Waals, the retarded flat–flat pressure p(u) = −dW/du over the open part of the
  cap, D0 ≤ u < u_c, W(u) = A/(12π u²)·1/(1 + b u) the flats' energy (Gregory, J. Colloid
  Interface Sci. 83, 138, 1981; b = 5.32/λ, :func:`mcsim.physics.vanderwaals.vdw_flat_energy`):
  F_vdW = 2πR [W(m) − W(u_c)] = (A R/6)[k(m) − k(u_c)], k(u) = 1/(u²(1 + b u)),
  m = min(max(g, D0), u_c); b = 0 gives the non-retarded (A R/6)(m⁻² − u_c⁻²).
  u_c → ∞ with g ≥ D0 gives the sphere–flat A R/(6 g²)·1/(1 + b g) (Derjaguin;
  non-retarded: Israelachvili Eq. 13.11 and Table 13.1), whose energy is Gregory's retarded
  sphere–plate −(A R/6g)[1 − b g ln(1 + 1/(b g))];
* the meniscus: a liquid bridge joins the adsorbed films (thickness t on each face) where
  u < g_K = 2 r_K cos θ + 2t (Kelvin), and its Laplace pressure γ_L/r_K acts on the annulus
  f ≤ u < g_K above the wet floor f = max(D0, 2t) (below it the films are pressed into each
  other), of area 2πR(g_K − max(g, f))⁺: F_cap = 2πR (γ_L/r_K)(g_K − m)⁺,
  m = min(max(g, f), g_K); for f ≤ g < g_K this is 4πRγ_L cos θ (g_K − g)/(g_K − 2t), the
  classic sphere–flat meniscus (Israelachvili Eq. 17.21, t = 0) rising at touch to
  2πR(γ_L/r_K)(g_K − f) = 4πRγ_L cos θ once 2t ≥ D0, and a pressed summit keeps that
  value: its wetted annulus surrounds its contact.

Both are continuous in δ, constant once the tip is below D0 (the meniscus below f), zero
beyond their range (u_c, g_K), and −dW/dd = F with the works of :func:`vdw_summit_work` and
:func:`capillary_summit_work`. The functions are written in the law vocabulary
(:mod:`mcsim.physics.laws`), so the Monte Carlo kernel compiles them like any law.
"""

import numpy as np


def vdw_summit(delta, hamaker, R, cutoff, band, retardation):
    """Van der Waals attraction of one summit across its open cap, N (> 0 attractive):
    (A R/6)[k(m) − k(u_c)], k(u) = 1/(u²(1 + b u)), m = min(max(g, D0), u_c) (module
    docstring; Gregory 1981 by Derjaguin).

    Parameters
    ----------
    delta : array_like
        Interference δ = z − d, m (the tip's gap is g = −δ).
    hamaker : float
        Hamaker constant A, J.
    R : float
        Summit radius, m.
    cutoff : float
        Cutoff gap D0, m: smaller gaps are contact.
    band : float
        Band edge u_c, m (> D0): the cap's deepest local gap.
    retardation : float
        b = 5.32/λ, m⁻¹ (:func:`mcsim.physics.environment.retardation`); 0: non-retarded.
    """
    m = np.minimum(np.maximum(-delta, cutoff), band)
    return hamaker * R / 6 * (1 / (m * m * (1 + retardation * m))
                              - 1 / (band * band * (1 + retardation * band)))  # fmt: skip


def capillary_summit(delta, laplace, R, wet_floor, gap_k):
    """Capillary attraction of one summit's meniscus, N (> 0 attractive).

    Parameters
    ----------
    delta : array_like
        Interference δ = z − d, m.
    laplace : float
        Laplace pressure γ_L/r_K, Pa (0 without condensation).
    R : float
        Summit radius, m.
    wet_floor : float
        Wet floor f = max(D0, 2t), m (<= ``gap_k``): the smallest local gap the bridge
        pulls across.
    gap_k : float
        Condensation gap g_K = 2 r_K cos θ + 2t, m (>= f; = f without condensation).
    """
    m = np.minimum(np.maximum(-delta, wet_floor), gap_k)
    return 2 * np.pi * R * laplace * (gap_k - m)


def vdw_summit_work(delta_t, hamaker, R, cutoff, band, retardation):
    """Work of :func:`vdw_summit` from interference ``delta_t`` to far away, J:
    ∫ F dd from d_t = z − δ_t outward (NumPy only, not a kernel law).

    (A R/6) {∫_m^{u_c} [k(u) − k(u_c)] du + (D0 − g)⁺ [k(D0) − k(u_c)]}, with
    ∫ k du = −1/u + b ln((1 + b u)/u), so ∫_m^{u_c} k du = 1/m − 1/u_c
    − b ln(1 + (u_c − m)/(m (1 + b u_c))); b = 0: 1/m − 1/u_c.
    """
    g = np.asarray(-delta_t, dtype=float)
    m = np.minimum(np.maximum(g, cutoff), band)
    b = retardation
    # Open part: ∫_m^{u_c} (k(u) − k(u_c)) du; pressed part: the constant force over D0 − g.
    edge = 1 / (band**2 * (1 + b * band))
    open_part = (
        1 / m - 1 / band - b * np.log1p((band - m) / (m * (1 + b * band))) - (band - m) * edge
    )
    pressed = np.maximum(cutoff - g, 0) * (1 / (cutoff**2 * (1 + b * cutoff)) - edge)
    return hamaker * R / 6 * (open_part + pressed)


def capillary_summit_work(delta_t, laplace, R, wet_floor, gap_k):
    """Work of :func:`capillary_summit` from interference ``delta_t`` to far away, J
    (NumPy only): πR(γ_L/r_K)[(g_K − m)² + 2(g_K − f)(f − g)⁺]."""
    g = np.asarray(-delta_t, dtype=float)
    m = np.minimum(np.maximum(g, wet_floor), gap_k)
    pressed = np.maximum(wet_floor - g, 0) * 2 * (gap_k - wet_floor)
    return np.pi * R * laplace * ((gap_k - m) ** 2 + pressed)

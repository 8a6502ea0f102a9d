"""DMT with a van der Waals attraction outside contact (Derjaguin, Muller & Toporov 1975).

See docs/physics.md, section 'DMT law set'.

One summit at interference δ = z − d (m):

* in contact (δ > 0): the Hertz load minus the DMT attraction,
  P = K R^½ δ^{3/2} − 2πwR with K = 4E*/3 (Hertz 1882; Derjaguin, Muller & Toporov
  1975), and the Hertz area A = πRδ;
* out of contact (δ ≤ 0): the Derjaguin force on a sphere at gap D = z0 − δ from a
  flat, F = 2πR W(D) (Derjaguin 1934), for the van der Waals interaction energy per
  unit area W(D) = −w (z0/D)² (non-retarded, W = −A_H/(12πD²) with w = A_H/(12πz0²);
  Israelachvili, *Intermolecular and Surface Forces*, 3rd ed. 2011, chs. 11 and 13):
  P = −2πwR (z0/D)², area zero. At δ = 0 (D = z0) it equals the in-contact −2πwR, so
  the load is continuous there. This is the Chang, Etsion & Bogy (1988) picture of
  DMT: Hertz stresses inside the contact, the surface force outside.

w is the work of adhesion (parameter ``gamma``), z0 the equilibrium spacing
(material field ``z0``; the silicon preset uses 0.3 nm). There is no hysteresis: the
outputs depend on δ alone, the same on approach and retraction.

**Cutoff.** The 1/D² tail decays slowly: the work the attraction does on one summit
brought in from infinity, ∫ 2πwR (z0/D)² dD over D > z0, is 2πwRz0, and the part
from gaps beyond D_cut is the fraction z0/D_cut of it. The attraction is therefore
truncated at the gap D_cut = ``cutoff`` · z0 (default 10 z0, so summits farther than
3 nm feel nothing with z0 = 0.3 nm): the law set's ``reach`` is δ = z0 − D_cut, and
the same truncated law is used by the Monte Carlo kernel and the analytic integrals.
The force jumps from −2πwR/cutoff² (−0.02πwR by default) to zero there.
:func:`truncated_fraction` reports how much of a rough surface's attraction that
drops.

References: Derjaguin, Muller & Toporov, J. Colloid Interface Sci. 53, 314 (1975);
Chang, Etsion & Bogy, J. Tribol. 110, 50 (1988).
"""

from __future__ import annotations

import math

import numpy as np

from mcsim.model.errors import ParameterError
from mcsim.physics.laws import Edges, LawSet, Output

#: Default tail cutoff, in units of z0 (the gap beyond which the attraction is dropped).
DEFAULT_CUTOFF = 10.0


def dmt_load(delta, R, K, gamma, z0, gap_cut):
    """Net normal force of one DMT summit (Derjaguin, Muller & Toporov 1975).

    P = K R^½ δ^{3/2} − 2πwR in contact (δ > 0); −2πwR (z0/(z0 − δ))² out of contact
    down to the cutoff gap (δ > z0 − D_cut); zero beyond.

    Parameters
    ----------
    delta : float or ndarray
        Interference δ = z − d, m.
    R : float
        Summit radius, m.
    K : float
        Elastic constant K = 4E*/3, Pa.
    gamma : float
        Work of adhesion w, J/m².
    z0 : float
        Equilibrium spacing, m.
    gap_cut : float
        Gap D_cut beyond which the attraction is dropped, m (≥ z0).

    Returns
    -------
    float or ndarray
        Load, N, compressive positive (negative: attraction).
    """
    d = np.maximum(delta, 0.0)
    gap = z0 - np.minimum(delta, 0.0)
    ratio = z0 / gap
    return K * np.sqrt(R) * d * np.sqrt(d) - (delta > z0 - gap_cut) * (
        2.0 * np.pi * gamma * R * ratio * ratio
    )


def dmt_area(delta, R):
    """Real contact area of one DMT summit, the Hertz area A = πRδ (Hertz 1882).

    Parameters
    ----------
    delta : float or ndarray
        Interference δ = z − d, m.
    R : float
        Summit radius, m.

    Returns
    -------
    float or ndarray
        Area, m²; zero for δ ≤ 0.
    """
    return np.pi * R * np.maximum(delta, 0.0)


def dmt_law_set(cutoff: float = DEFAULT_CUTOFF) -> LawSet:
    """The ``dmt`` law set with the attraction truncated at the gap ``cutoff`` · z0.

    Parameters
    ----------
    cutoff : float
        Cutoff gap in units of the equilibrium spacing z0, ≥ 1 (1: no attraction
        outside contact). Default 10.

    Returns
    -------
    LawSet
        Outputs ``load`` (N) and ``area`` (m²); needs the material's ``z0`` unless
        w = 0 (then Hertz: P = K R^½ δ^{3/2}, area πRδ, nothing out of contact). Named
        ``dmt`` whatever the cutoff: the cutoff is in its description and enters the
        law functions as the parameter ``gap_cut`` (m), so the compiled kernel is
        the same for every cutoff.
    """
    try:
        cutoff = float(cutoff)
    except (TypeError, ValueError):
        raise ParameterError(f"cutoff must be a number, got {cutoff!r}") from None
    if not (math.isfinite(cutoff) and cutoff >= 1.0):
        raise ParameterError(
            f"cutoff = {cutoff!r} (in units of z0) is out of range (allowed: finite, >= 1)"
        )

    def constants(surface, material) -> dict:
        if material.gamma == 0:  # no attraction, no tail to cut: Hertz, whatever z0 is
            z0 = surface.R if material.z0 is None else material.z0  # any length > 0
            return {"z0": z0, "gap_cut": z0}
        return {"gap_cut": cutoff * material.z0}

    def edges(params) -> Edges:
        return Edges(reach=params["z0"] - params["gap_cut"], jump_in=0.0, break_off=0.0)

    return LawSet(
        name="dmt",
        description=(
            "DMT: Hertz - 2 pi w R in contact, van der Waals -2 pi w R (z0/D)^2 outside, "
            f"cut off at the gap {cutoff:g} z0"
        ),
        outputs=(
            Output("load", "N", dmt_load, "net normal force, compressive positive"),
            Output("area", "m^2", dmt_area, "real contact area pi R delta"),
        ),
        edges=edges,
        constants=constants,
        requires=("z0",),
        friction=True,
    )


LAW_SET = dmt_law_set()


def truncated_fraction(surface, material, h, cutoff: float = DEFAULT_CUTOFF) -> np.ndarray:
    """Fraction of a rough surface's DMT attraction that the tail cutoff drops.

    At the separation d = hσ every summit attracts: 2πwR if it touches (s > h), the
    van der Waals 2πwR (z0/D)² at the gap D = z0 + σ(h − s) if not. The fraction is

        ∫_{D > D_cut} 2πwR (z0/D)² φ(s) ds  /  [ ∫_{s > h} 2πwR φ(s) ds + ∫_{s ≤ h} 2πwR (z0/D)² φ(s) ds ],

    the attraction of the summits beyond the cutoff gap (which :data:`LAW_SET` leaves
    out) relative to the whole untruncated attraction, φ the surface's summit-height
    density. The net load of the law set is short of the untruncated one by this
    fraction of the total attraction (in N: times 2πwR·N·[...]). For one summit, the
    work of the attraction dropped on approach is the fraction 1/cutoff.

    Parameters
    ----------
    surface : Surface
        The rough surface (σ, R and the height distribution; η cancels).
    material : Material
        The materials; needs ``z0`` (w cancels).
    h : float or array_like
        Separations d/σ.
    cutoff : float
        Cutoff gap in units of z0 (see :func:`dmt_law_set`).

    Returns
    -------
    ndarray
        The truncated fraction at each h, in [0, 1).
    """
    from scipy import integrate

    if material.z0 is None:
        raise ParameterError(
            "the dmt truncated fraction needs material field 'z0', which is not given"
        )
    dmt_law_set(cutoff)  # validates cutoff
    z0 = material.z0 / surface.sigma  # lengths in units of σ
    heights = surface.heights
    edges = getattr(heights, "edges", None)
    lo = -40.0 if edges is None else float(edges[0])

    def tail(s, h):
        return (z0 / (z0 + h - s)) ** 2 * heights.pdf(np.asarray(s, dtype=float))

    def integral(a, b, h):
        if b <= a:
            return 0.0
        inside = () if edges is None else [e for e in edges if a < e < b]
        return integrate.quad(tail, a, b, args=(h,), points=inside or None,
                              limit=500 + 2 * len(inside), epsabs=0.0, epsrel=1e-10)[0]  # fmt: skip

    out = []
    for hj in np.atleast_1d(np.asarray(h, dtype=float)):
        s_cut = hj - (cutoff - 1.0) * z0
        dropped = integral(lo, s_cut, hj)
        total = float(heights.sf(hj)) + dropped + integral(max(lo, s_cut), hj, hj)
        out.append(dropped / total if total > 0 else 0.0)
    return np.asarray(out)

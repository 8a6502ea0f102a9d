"""Maugis–Dugdale adhesive elastic sphere, under fixed penetration, tabulated once per run.

See docs/physics.md, section 'Maugis-Dugdale law set'.

Maugis (1992) replaced the surface forces by a Dugdale law: a constant tension σ0 while
the gap is below h0, nothing beyond, so that the work of adhesion is w = σ0 h0. We take
h0 = 0.97 z0 (Maugis' match of the Dugdale law to a Lennard-Jones law of equilibrium
spacing z0), i.e. σ0 = w/h0.

Notation of Johnson & Greenwood (1997, J. Colloid Interface Sci. 192, 326), with
K = 4E*/3, a the contact radius and c the outer radius of the Dugdale zone:

    λ = 2σ0 (R / (π w K²))^{1/3}                       (Maugis parameter, ≈ 1.16 μ_T)
    A = a / (π w R²/K)^{1/3},  P̄ = P / (π w R),  Δ = δ / (π² w² R / K²)^{1/3},  m = c/a

    (λA²/2)[√(m²−1) + (m²−2) arccos(1/m)] + (4λ²A/3)[√(m²−1) arccos(1/m) − m + 1] = 1
    P̄ = A³ − λA² [√(m²−1) + m² arccos(1/m)]
    Δ = A² − (4/3) λ A √(m²−1)

(Maugis 1992, J. Colloid Interface Sci. 150, 243, §6, eq. 6.17 for m, in these
units.) P is positive when compressive, δ positive for interference.

**Parametrisation used here.** With ψ = arccos(1/m) ∈ (0, π/2] and C = mA (the Dugdale
radius c in units of (πwR²/K)^{1/3}) the first equation is a quadratic in C,

    (λ/2) C² [½ sin 2ψ − ψ cos 2ψ] + (4λ²/3) C [ψ sin ψ − (1 − cos ψ)] = 1,

and A = C cos ψ, P̄ = A³ − λC²(sin ψ cos ψ + ψ), Δ = A² − (4/3)λ C sin ψ, all regular on
the closed interval: ψ → 0 is A → ∞ (the JKR limit of a thin zone), ψ = π/2 is A = 0
(the zone touches down at its centre).

**Out of contact** (the same Dugdale law, the gap nowhere closed): a uniform tension σ0
over r < c on the elastic half-spaces. The surfaces move together by 2σ0c/E* at the
centre and by 4σ0c/(πE*) at r = c (Johnson 1985, *Contact Mechanics*, §3.4), so the gap
h(c) = h0 gives, in the units above,

    P̄ = −(π/2) λ C²,   Δ = −h̄0 + C²/2 − (8/(3π)) λ C,   h̄0 = h0/(π²w²R/K²)^{1/3} = 2/(πλ),

which joins the contact solution continuously at ψ = π/2 and reduces to the Dugdale
attraction of a rigid sphere, F = −2πRσ0(h0 − g) at gap g = −δ, as λ → 0 (then
C²/2 = Δ + h̄0).

**Branches under fixed penetration.** The curve (Δ, P̄) has one turning point Δ_b, its
minimum in Δ: for λ ≤ λ_c = (9π/(16(π−1)))^{1/3} ≈ 0.938 it lies out of contact, at
C = 8λ/(3π), Δ_b = −h̄0 − ½(8λ/(3π))²; for λ > λ_c it lies in contact (the JKR-like
turning point, Δ_b = −0.9086 and P̄ = −5/6 as λ → ∞). The stable branch is the part of
the curve beyond it, single-valued in Δ for Δ > Δ_b. On approach no force acts until the
gap at the tip of the sphere falls to h0 (δ = −h0, where the force-free state ends; the
`jump_in`), where the summit jumps onto the stable branch. On retraction a summit that
jumped in stays on the stable branch down to Δ_b (`break_off`), then jumps out to zero
force. For λ → 0 this is DMT (pull-off 2πwR, no jump); for λ → ∞ JKR (jump-in at δ = 0,
break-off at δ_c with P = −(5/6)πwR; load-controlled pull-off 1.5πwR).

**The table.** All summits share R, so the stable contact branch (Δ ≥ Δ_lo, Δ_lo = Δ at
ψ = π/2 for λ ≤ λ_c, the turning point otherwise) is solved once per λ at the nodes of a
geometric grid in y = Δ − Δ_lo, 2^6 intervals per octave from y = 2^-70 to 2^100 (the
doubles whose bits are multiples of 2^46: :func:`nodes`), and P̄ and A² are a
not-a-knot cubic spline in y through them. A law function finds a summit's interval and
its place in it from the bits of y (:mod:`mcsim.physics.laws.ieee`: the exponent and the first
six fraction bits are the interval, the other fraction bits the place), with no root,
logarithm or division: on a CPU without fast gathers (AVX2) LLVM computes everything a
table address depends on one lane at a time, and the fourth root an earlier grid needed
there made this law set cost 2.5–3.3 times the seed's per pair. On a geometric grid a
power law y^α has the same relative interpolation error in every interval, so the grid
resolves the branch at every scale: P̄ − P̄_lo and A − A_lo ∝ y^{1/2} at a turning point,
A ∝ y^{1/3} at λ = λ_c (the turning point at touch-down), P̄ → Δ^{3/2} and A² → Δ as
Δ → ∞. Below 2^-70 a value is read at 2^-70 (an error of order √(2^-70) ≈ 3e-11).
Relative to max(|P̄|, 1) and max(A², 1) (P̄ changes sign and A → 0 at touch-down), the
table reproduces the direct solution of Maugis' equations (as in the tests) to 7e-10 for
λ = 1e-3 … 10, to 3e-9 at λ = λ_c − 1e-7, and to 1.2e-10 in the tail out to A = 1e6;
the tests check the bound 1e-8 for λ = 0.1 … 10. (For λ ≥ 100 the direct solution
itself, a root in m → 1, limits the comparison within y ≈ 1e-9 of the turning point.)
The out-of-contact part of the stable branch is evaluated in closed form. Δ is clamped
to ±1e30 (so y < 2^100), and the values are finite for every finite δ.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface
from mcsim.physics.laws import Edges, LawSet, Output
from mcsim.physics.laws.ieee import bits_float, float_bits

#: Dugdale range per equilibrium spacing, h0 = 0.97 z0 (Maugis 1992).
H0_PER_Z0 = 0.97
#: Maugis parameter where the turning point moves from out of contact into contact.
LAMBDA_C = (9.0 * np.pi / (16.0 * (np.pi - 1.0))) ** (1.0 / 3.0)
#: The table's grid (module docstring): 2**GRID_BITS intervals per octave of
#: y = Δ − Δ_lo, from 2**Y_EXPONENTS[0] to 2**Y_EXPONENTS[1].
GRID_BITS = 6
Y_EXPONENTS = (-70, 100)
#: Intervals of the table.
N_TABLE = (Y_EXPONENTS[1] - Y_EXPONENTS[0]) << GRID_BITS
#: Lowest node of the grid; a smaller y is read as Y_MIN.
Y_MIN = 2.0 ** Y_EXPONENTS[0]
# IEEE 754 binary64: y = 2**(e − 1023) (1 + f/2**52) has the bits e·2**52 + f.
_SHIFT = 52 - GRID_BITS  # bits >> _SHIFT = e·2**GRID_BITS + the first GRID_BITS bits of f
_FIRST = (1023 + Y_EXPONENTS[0]) << GRID_BITS  # bits >> _SHIFT of Y_MIN
_FRACTION = (1 << 52) - 1
_ONE = 1023 << 52  # the bits of 1.0
#: Range of λ the table is built and tested for.
LAMBDA_RANGE = (1e-3, 1e3)


def maugis_lambda(R: float, K: float, gamma: float, z0: float) -> float:
    """Maugis parameter λ = 2σ0 (R/(πwK²))^{1/3} with σ0 = w/h0, h0 = 0.97 z0.

    Parameters
    ----------
    R : float
        Summit radius, m.
    K : float
        Elastic constant K = 4E*/3, Pa.
    gamma : float
        Work of adhesion w, J/m².
    z0 : float
        Equilibrium spacing, m.

    Returns
    -------
    float
        λ, dimensionless.
    """
    sigma0 = gamma / (H0_PER_Z0 * z0)
    return 2.0 * sigma0 * np.cbrt(R / (np.pi * gamma * K * K))


def units(R: float, K: float, gamma: float) -> tuple[float, float, float]:
    """Scales of A, Δ and P̄ (Johnson & Greenwood 1997).

    Returns
    -------
    tuple of float
        (πwR²/K)^{1/3} (m), (π²w²R/K²)^{1/3} (m), πwR (N).
    """
    return (
        float(np.cbrt(np.pi * gamma * R * R / K)),
        float(np.cbrt((np.pi * gamma) ** 2 * R / K**2)),
        float(np.pi * gamma * R),
    )


def _sin_minus_u_cos(u: np.ndarray) -> np.ndarray:
    """sin u − u cos u without cancellation at small u (Taylor series below u = 1).

    Each element takes one branch: the series is summed only where u < 1, the closed form
    only elsewhere (the bisection of :func:`_solve_branch` calls this 64 times per table).
    The series stops after 9 terms: for u < 1 the 10th and every later one is below
    60 u^18/21! < 1.2e-18 of the first, and the sum is at least 0.9 of the first, so adding
    them would not change a bit of it (each is below half the spacing of doubles there,
    2^-54 of the sum; checked to the bit on 1.7e6 values in the tests).
    """
    u = np.asarray(u, dtype=float)
    out = np.empty_like(u)
    below = u < 1.0
    small = u[below]
    term, total = small**3 / 3.0, np.zeros_like(small)
    for k in range(1, 10):  # |term_k| = 2k u^{2k+1}/(2k+1)!, of sign (−1)^{k+1}, in place
        if k % 2:
            total += term
        else:
            total -= term
        term *= small
        term *= small
        term *= k + 1
        term /= k * (2 * k + 2) * (2 * k + 3)
    out[below] = total
    large = u[~below]
    out[~below] = np.sin(large) - large * np.cos(large)
    return out


def contact_curve(psi, lam: float):
    """Maugis' contact solution along ψ = arccos(1/m) (see the module docstring).

    Parameters
    ----------
    psi : array_like
        ψ ∈ (0, π/2]; π/2 is touch-down (A = 0), ψ → 0 is A → ∞.
    lam : float
        Maugis parameter λ.

    Returns
    -------
    A, P, Delta, C : ndarray
        Contact radius A, load P̄, penetration Δ and Dugdale radius C = mA, all in the
        units of the module docstring.
    """
    psi = np.asarray(psi, dtype=float)
    C = _zone(psi, lam)
    A = C * np.cos(psi)
    P = A**3 - lam * C * C * (np.sin(psi) * np.cos(psi) + psi)
    Delta = A * A - 4.0 / 3.0 * lam * C * np.sin(psi)
    return A, P, Delta, C


def _zone(psi: np.ndarray, lam: float) -> np.ndarray:
    """The Dugdale radius C at ψ: the positive root of the quadratic in C (module
    docstring)."""
    quad = 0.5 * _sin_minus_u_cos(2.0 * psi)  # ½ sin 2ψ − ψ cos 2ψ
    lin = psi * np.sin(psi) - 2.0 * np.sin(0.5 * psi) ** 2  # ψ sin ψ − (1 − cos ψ)
    k1 = 4.0 * lam * lam / 3.0 * lin
    return 2.0 / (k1 + np.sqrt(k1 * k1 + 2.0 * lam * quad))


def _penetration(psi: np.ndarray, lam: float) -> np.ndarray:
    """Δ of :func:`contact_curve` alone, by the same operations (the bisection's one need)."""
    C = _zone(psi, lam)
    A = C * np.cos(psi)
    return A * A - 4.0 / 3.0 * lam * C * np.sin(psi)


def _slopes(psi: float, lam: float) -> tuple[float, float]:
    """dΔ/dψ and dP̄/dψ along the contact curve (implicit differentiation of the
    quadratic in C, with d/dψ[½ sin 2ψ − ψ cos 2ψ] = 2ψ sin 2ψ, d/dψ[ψ sin ψ − 1 + cos ψ]
    = ψ cos ψ)."""
    A, _, _, C = contact_curve(psi, lam)
    s, c = np.sin(psi), np.cos(psi)
    quad = 0.5 * _sin_minus_u_cos(2.0 * psi)
    lin = psi * s - 2.0 * np.sin(0.5 * psi) ** 2
    dC = -(0.5 * lam * C * C * 2.0 * psi * np.sin(2.0 * psi) + 4.0 / 3.0 * lam**2 * C * psi * c)
    dC = dC / (lam * C * quad + 4.0 / 3.0 * lam**2 * lin)
    dA = dC * c - C * s
    dDelta = 2.0 * A * dA - 4.0 / 3.0 * lam * (dC * s + C * c)
    dP = 3.0 * A * A * dA - lam * (2.0 * C * dC * (s * c + psi) + C * C * (np.cos(2.0 * psi) + 1.0))
    return float(dDelta), float(dP)


@dataclass(frozen=True)
class Table:
    """The stable branch of the Maugis–Dugdale curve for one λ (units of the module
    docstring).

    Attributes
    ----------
    lam : float
        Maugis parameter λ.
    h0 : float
        Dugdale range h̄0 = 2/(πλ); jump-in at Δ = −h̄0.
    b : float
        8λ/(3π): the out-of-contact zone radius is C = b + √(b² + 2(Δ + h̄0)).
    psi_lo : float
        ψ at the lower end of the tabulated contact branch (π/2: touch-down, or the
        turning point).
    delta_lo : float
        Δ there.
    delta_touch : float
        Δ below which the out-of-contact formula applies (touch-down for λ ≤ λ_c; for
        λ > λ_c one unit below the turning point, where no summit is in contact).
    delta_break : float
        Break-off: the turning point of the curve in Δ.
    coefficients : ndarray, shape (8 N_TABLE,), read-only
        Eight numbers per interval k of :func:`nodes`: the cubic coefficients of P̄, then
        those of A², in the local coordinate s = (y − y_k)/(y_{k+1} − y_k) ∈ [0, 1), so
        that :func:`load` and :func:`area` read one interval's 64 adjacent bytes.
    """

    lam: float
    h0: float
    b: float
    psi_lo: float
    delta_lo: float
    delta_touch: float
    delta_break: float
    coefficients: np.ndarray


def _solve_branch(targets: np.ndarray, psi_lo: float, lam: float) -> np.ndarray:
    """ψ on the stable branch (0, ψ_lo] with Δ(ψ) = target, by bisection in ln ψ (Δ
    decreases monotonically there, from +∞).

    All targets start from the same interval, so the first steps share few midpoints (at
    most 2^k at step k): while they are fewer than a tenth of the targets, Δ is computed
    once per distinct midpoint.
    """
    lo = np.full(targets.shape, np.log(1e-30))
    hi = np.full(targets.shape, np.log(psi_lo))
    for k in range(64):
        mid = 0.5 * (lo + hi)
        if 2**k < targets.size // 10:
            distinct, where = np.unique(mid, return_inverse=True)
            above = _penetration(np.exp(distinct), lam)[where] > targets
        else:
            above = _penetration(np.exp(mid), lam) > targets
        lo = np.where(above, mid, lo)
        hi = np.where(above, hi, mid)
    return np.exp(0.5 * (lo + hi))


def _coefficients(y: np.ndarray, *f: np.ndarray) -> np.ndarray:
    """Not-a-knot cubic splines through (y, f) for each f, as local cubics in s ∈ [0, 1)
    per interval, interleaved: interval 0's [c0, c1, c2, c3] of each f, then interval 1's,
    ..."""
    from scipy.interpolate import (
        CubicSpline,  # on first use: keeps `import mcsim.physics.laws` light
    )

    h = np.diff(y)
    local = []
    for values in f:
        c = CubicSpline(y, values).c  # c[3 − j] multiplies (y − y_k)^j
        local += [c[3 - j] * h**j for j in range(4)]
    out = np.ascontiguousarray(np.stack(local, axis=1).ravel())
    out.flags.writeable = False
    return out


def nodes() -> np.ndarray:
    """The grid of the table in y = Δ − Δ_lo: the N_TABLE + 1 binary64 numbers whose bits
    are multiples of 2**(52 − GRID_BITS), from Y_MIN to 2**Y_EXPONENTS[1] (module
    docstring)."""
    bits = (np.arange(N_TABLE + 1, dtype=np.int64) + _FIRST) << _SHIFT
    return bits.view(np.float64)


@functools.lru_cache(maxsize=64)  # 0.7 MB each; a surface of bands needs one per band and w
def table(lam: float) -> Table:
    """Solve and tabulate the stable branch for one Maugis parameter (cached).

    Parameters
    ----------
    lam : float
        Maugis parameter λ, within :data:`LAMBDA_RANGE`.

    Returns
    -------
    Table
    """
    from scipy.optimize import brentq

    h0 = 2.0 / (np.pi * lam)
    b = 8.0 * lam / (3.0 * np.pi)
    half_pi = 0.5 * np.pi
    delta_touch = float(contact_curve(half_pi, lam)[2])
    psi_lo = half_pi
    if lam > LAMBDA_C and _slopes(half_pi, lam)[0] > 0.0:
        # the turning point is in contact: dΔ/dψ changes sign once on (0, π/2)
        psi_lo = brentq(lambda p: _slopes(p, lam)[0], 1e-6, half_pi, xtol=1e-15, rtol=1e-15)
    delta_lo = float(contact_curve(psi_lo, lam)[2])
    if lam > LAMBDA_C:
        delta_break, delta_touch = delta_lo, delta_lo - 1.0
    else:
        delta_break = -h0 - 0.5 * b * b
    y = nodes()
    target = delta_lo + y
    psi = np.where(target > delta_lo, _solve_branch(target, psi_lo, lam), psi_lo)
    A, P, _, _ = contact_curve(psi, lam)
    return Table(
        lam=lam,
        h0=h0,
        b=b,
        psi_lo=psi_lo,
        delta_lo=delta_lo,
        delta_touch=delta_touch,
        delta_break=delta_break,
        coefficients=_coefficients(y, P, A * A),
    )


def pull_off(lam: float) -> tuple[float, float]:
    """Load-controlled pull-off: the most tensile load on the whole curve, P̄ and Δ there.

    Under load control the sphere separates where dP̄ = 0 (Maugis 1992; Johnson &
    Greenwood 1997, fig. 3): 2 for λ → 0 (DMT), 1.5 for λ → ∞ (JKR). The minimum lies in
    contact, since out of contact P̄ = −(π/2)λC² falls as the zone grows to touch-down.

    Parameters
    ----------
    lam : float
        Maugis parameter λ.

    Returns
    -------
    P, Delta : float
        P̄ (negative; its magnitude is the pull-off force in units of πwR) and Δ.
    """
    from scipy.optimize import brentq

    half_pi = 0.5 * np.pi
    psi = half_pi
    if _slopes(half_pi, lam)[1] > 0.0:  # P̄ still falls as the contact grows from A = 0
        psi = brentq(lambda p: _slopes(p, lam)[1], 1e-6, half_pi, xtol=1e-15, rtol=1e-15)
    _, P, Delta, _ = contact_curve(psi, lam)
    return float(P), float(Delta)


def load(
    delta,
    delta_max,
    md_jump_in,
    md_break_off,
    md_per_delta_unit,
    md_force_unit,
    md_lambda,
    md_h0,
    md_b,
    md_delta_lo,
    md_delta_touch,
    md_table,
):
    """Net normal force on one summit, Maugis–Dugdale (module docstring), N.

    Parameters
    ----------
    delta : float or ndarray
        Interference δ = z − d, m.
    delta_max : float or ndarray
        Largest interference reached (δ on approach), m.
    md_jump_in, md_break_off : float
        Edges of the contact branch, m.
    md_per_delta_unit : float
        1/(π²w²R/K²)^{1/3}, 1/m (1/R without adhesion, :func:`hertz_table`).
    md_force_unit : float
        πwR, N (K R² without adhesion).
    md_lambda, md_h0, md_b, md_delta_lo, md_delta_touch : float
        λ and the dimensionless constants of :class:`Table`.
    md_table : ndarray
        :attr:`Table.coefficients` (load at offsets 0–3 of each interval's eight).

    Returns
    -------
    float or ndarray
        Load, N, positive when compressive; zero out of contact.
    """
    # The interval and the position in it are read off the bits of y (module docstring):
    # on an AVX2 CPU without fast gathers LLVM computes everything a table address
    # depends on one lane at a time, so that path holds no root and no division.
    big = 1e30 / md_per_delta_unit  # |Δ| ≤ 1e30: finite values for every finite δ
    D = np.minimum(np.maximum(delta, -big), big) * md_per_delta_unit
    on = (delta_max > md_jump_in) * (delta > md_break_off)
    zone = md_b + np.sqrt(np.maximum(md_b * md_b + 2.0 * (D + md_h0), 0.0))
    apart = -0.5 * np.pi * md_lambda * zone * zone
    bits = float_bits(np.maximum(D - md_delta_lo, Y_MIN))
    k = 8 * np.minimum((bits >> _SHIFT) - _FIRST, N_TABLE - 1)
    s = bits_float(((bits << GRID_BITS) & _FRACTION) | _ONE) - 1.0
    t = md_table
    touching = t[k] + s * (t[k + 1] + s * (t[k + 2] + s * t[k + 3]))
    inside = D >= md_delta_touch
    return on * (inside * touching + (1.0 - inside) * apart) * md_force_unit + 0.0  # no -0.0


def area(
    delta,
    delta_max,
    md_jump_in,
    md_break_off,
    md_per_delta_unit,
    md_area_unit,
    md_delta_lo,
    md_delta_touch,
    md_table,
):
    """Real contact area πa² of one summit, Maugis–Dugdale (module docstring), m².

    Parameters
    ----------
    delta : float or ndarray
        Interference δ = z − d, m.
    delta_max : float or ndarray
        Largest interference reached (δ on approach), m.
    md_jump_in, md_break_off : float
        Edges of the contact branch, m.
    md_per_delta_unit : float
        1/(π²w²R/K²)^{1/3}, 1/m (1/R without adhesion, :func:`hertz_table`).
    md_area_unit : float
        π (πwR²/K)^{2/3}, m² (πR² without adhesion).
    md_delta_lo, md_delta_touch : float
        Dimensionless constants of :class:`Table`.
    md_table : ndarray
        :attr:`Table.coefficients` (area at offsets 4–7 of each interval's eight).

    Returns
    -------
    float or ndarray
        Area, m²; zero out of contact, and inside the Dugdale zone before touch-down.
    """
    big = 1e30 / md_per_delta_unit  # |Δ| ≤ 1e30: finite values for every finite δ
    D = np.minimum(np.maximum(delta, -big), big) * md_per_delta_unit
    on = (delta_max > md_jump_in) * (delta > md_break_off)
    bits = float_bits(np.maximum(D - md_delta_lo, Y_MIN))
    k = 8 * np.minimum((bits >> _SHIFT) - _FIRST, N_TABLE - 1)
    s = bits_float(((bits << GRID_BITS) & _FRACTION) | _ONE) - 1.0
    t = md_table
    touching = t[k + 4] + s * (t[k + 5] + s * (t[k + 6] + s * t[k + 7]))
    return on * (D >= md_delta_touch) * touching * md_area_unit + 0.0


@functools.lru_cache(maxsize=1)
def hertz_table() -> Table:
    """The table of Hertz's sphere, the Maugis–Dugdale curve without adhesion (w = 0):
    P̄ = Δ^{3/2}, A² = Δ in units of any length L (δ = LΔ, P = K R^½ L^{3/2} P̄,
    πa² = πRL A²; Hertz 1882, Johnson 1985 §4.2), touching from Δ = 0 with no jump."""
    y = nodes()
    return Table(lam=0.0, h0=0.0, b=0.0, psi_lo=0.5 * np.pi, delta_lo=0.0, delta_touch=0.0,
                 delta_break=0.0, coefficients=_coefficients(y, y**1.5, y))  # fmt: skip


def _hertz_constants(R: float, K: float) -> dict:
    """:func:`constants` without adhesion: :func:`hertz_table` in units of L = R (λ = 0,
    so the out-of-contact term of :func:`load` is 0)."""
    tab = hertz_table()
    return {"md_lambda": 0.0, "md_jump_in": 0.0, "md_break_off": 0.0, "md_touch_down": 0.0,
            "md_per_delta_unit": 1.0 / R, "md_force_unit": K * R * R, "md_area_unit": np.pi * R * R,
            "md_h0": 0.0, "md_b": 0.0, "md_delta_lo": 0.0, "md_delta_touch": 0.0,
            "md_table": tab.coefficients}  # fmt: skip


def constants(surface: Surface, material: Material) -> dict:
    """The run's λ, units and table (named parameters of :func:`load` and :func:`area`).

    Without adhesion (w = 0) the curve is Hertz's (:func:`hertz_table`), with or
    without z0.

    Raises
    ------
    ParameterError
        With λ outside :data:`LAMBDA_RANGE` (a missing ``z0`` with w > 0 is caught by
        :meth:`LawSet.parameters`, from ``requires``).
    """
    if material.gamma == 0:
        return _hertz_constants(surface.R, material.K)
    R, K, w = surface.R, material.K, material.gamma
    lam = float(maugis_lambda(R, K, w, material.z0))
    lo, hi = LAMBDA_RANGE
    if not lo <= lam <= hi:
        raise ParameterError(
            f"Maugis parameter lambda = {lam:.4g} (from R, E*, gamma, z0) is outside "
            f"[{lo:g}, {hi:g}], the range tabulated for 'maugis-dugdale'; use --law dmt "
            "(small lambda) or jkr (large lambda)"
        )
    tab = table(lam)
    a_unit, delta_unit, force_unit = units(R, K, w)
    return {
        "md_lambda": lam,
        "md_jump_in": -H0_PER_Z0 * material.z0,
        "md_break_off": tab.delta_break * delta_unit,
        "md_touch_down": tab.delta_touch * delta_unit,
        "md_per_delta_unit": 1.0 / delta_unit,
        "md_force_unit": force_unit,
        "md_area_unit": np.pi * a_unit * a_unit,
        "md_h0": tab.h0,
        "md_b": tab.b,
        "md_delta_lo": tab.delta_lo,
        "md_delta_touch": tab.delta_touch,
        "md_table": tab.coefficients,
    }


def edges(params: Mapping) -> Edges:
    """Jump-in at δ = −h0, break-off at the turning point; touch-down as a breakpoint, m."""
    touch = params["md_touch_down"]
    breakpoints = (touch,) if touch > params["md_break_off"] else ()
    return Edges(
        reach=params["md_jump_in"],
        jump_in=params["md_jump_in"],
        break_off=params["md_break_off"],
        breakpoints=breakpoints,
    )


LAW_SET = LawSet(
    name="maugis-dugdale",
    description="Maugis-Dugdale adhesive sphere (Maugis 1992), fixed penetration, tabulated",
    outputs=(
        Output("load", "N", load, "net normal force, compressive positive"),
        Output("area", "m^2", area, "real contact area pi a^2"),
    ),
    edges=edges,
    constants=constants,
    requires=("z0",),
    friction=True,
)

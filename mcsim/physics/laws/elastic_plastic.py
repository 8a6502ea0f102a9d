"""Elastic–plastic summits on approach (Kogut & Etsion 2002), no adhesion.

See docs/physics.md, section 'Elastic-plastic law set'.

Kogut & Etsion (2002, J. Appl. Mech. 69, 657–662, doi:10.1115/1.1490373) fitted
finite-element results for a deformable sphere pressed by a rigid flat. With the
critical interference at the onset of yield (Chang, Etsion & Bogy 1987, with Kogut &
Etsion's hardness coefficient)::

    ω_c = (πkH/(2E*))² R,   k = 0.454 + 0.41ν,   P_c = (2/3)πkHRω_c,   A_c = πRω_c

(P_c and A_c are the Hertz load and area at ω_c, where the Hertz peak pressure is
kH), and x = δ/ω_c:

========================  ========================  ==========================
range                     P/P_c                     A/A_c
========================  ========================  ==========================
0 < x < 1 (elastic)       x^1.5 (Hertz)             x (Hertz)
1 ≤ x < 6                 1.03 x^1.425              0.93 x^1.136
6 ≤ x < 110               1.40 x^1.263              0.94 x^1.146
x ≥ 110 (fully plastic)   3x/k  (P = HA)            2x  (A = 2πRδ)
========================  ========================  ==========================

H is the hardness of the softer solid (material ``H``), ν its Poisson's ratio
(``Material.nu``), E* the contact modulus. The critical values and the load fits
(1.03, 1.425; 1.40, 1.263; 3/k in the plastic range) were checked against an
independent public implementation of the model (a MATLAB GW–KE code); the area fits (0.93, 1.136;
0.94, 1.146) are those issue 10 quotes from the paper, whose text was not available
here to check them.

The powers x^e are computed without the C library's exp and log (calls the Monte Carlo
kernel cannot vectorise): x = 2^j m with √½ ≤ m < √2, ln m by the atanh series,
exp(e ln m) by its [6/6] Padé approximant, times (2^e)^j; within 1.1e-15 relative of
``x**e`` for 1 ≤ x ≤ 110. Load and area call the one helper :func:`fit_power`
(:mod:`mcsim.physics.laws`).

The fits are not continuous at the range ends (they are the paper's separate fits):
going up through x = 1 the load jumps by +3.0 % and the area by −7.0 %, through x = 6
by +1.7 % and +2.9 %, through x = 110 by +14.4 % (ν = 0.22; the plastic 3x/k depends
on ν) and +7.1 %. The law set lists ω_c, 6ω_c and 110ω_c as breakpoints for the
quadrature.

Loading only: unloading leaves a residual deformation that depends on the largest
interference (Etsion, Kligerman & Kadin 2005), which this law set does not model;
the retraction branch is refused.
"""

import numpy as np

from mcsim.physics.laws import Edges, LawSet, Output


def fit_power(x, c, e, two_e):
    """One range of the fits, c·x^e, for x clamped to [1, 110] (module docstring).

    x = 2^j m with √½ ≤ m < √2, j = 4c + 2b + a found by halving, x^e = (2^e)^j m^e, and
    m^e = exp(e ln m), ln m = 2 atanh((m − 1)/(m + 1)) by its series: no libm calls (they
    keep the kernel from vectorising); within 1.1e-15 relative of ``c * x**e``.

    Parameters
    ----------
    x : float or ndarray
        Reduced interference δ/ω_c.
    c, e : float or ndarray
        Coefficient and exponent of the fit, |e| < 1.44 (then |e ln m| < 0.5, where the
        Padé approximant holds).
    two_e : float or ndarray
        2^e, computed once by the caller.

    Returns
    -------
    float or ndarray
        c·x^e in the unit of ``c``.
    """
    xc = np.minimum(np.maximum(x, 1.0), 110.0)
    c8 = xc >= 11.313708498984761  # √2·2³
    x1 = xc * (1.0 - 0.9375 * c8)
    b = x1 >= 2.8284271247461903  # √2·2
    x2 = x1 * (1.0 - 0.75 * b)
    a = x2 >= 1.4142135623730951  # √2
    m = x2 * (1.0 - 0.5 * a)
    u = (m - 1.0) / (m + 1.0)
    u2 = u * u
    u4 = u2 * u2
    u8 = u4 * u4
    series = (1.0 + 0.3333333333333333 * u2) + u4 * (0.2 + 0.14285714285714285 * u2)
    series = series + u8 * (
        (0.1111111111111111 + 0.09090909090909091 * u2)
        + u4 * (0.07692307692307693 + 0.06666666666666667 * u2)
        + u8 * ((0.058823529411764705 + 0.05263157894736842 * u2) + u4 * 0.047619047619047616)
    )
    y = e * (2.0 * u * series)  # e ln m, |y| < 0.5
    # exp y by its [6/6] Padé approximant N(y)/N(−y) (error < 1e-16 for |y| < 0.5)
    y2 = y * y
    even = 1.0 + y2 * (
        0.11363636363636363 + y2 * (0.0012626262626262627 + y2 * 1.503126503126503e-06)
    )
    odd = y * (0.5 + y2 * (0.015151515151515152 + y2 * 6.313131313131313e-05))
    em = (even + odd) / (even - odd)
    q2 = two_e * two_e
    scale = (1.0 + a * (two_e - 1.0)) * (1.0 + b * (q2 - 1.0)) * (1.0 + c8 * (q2 * q2 - 1.0))
    return c * em * scale


def elastic_plastic_load(delta, R, E_star, H, nu):
    """Normal load of one elastic–plastic summit (Kogut & Etsion 2002).

    Parameters
    ----------
    delta : float or ndarray
        Interference δ = z − d, m.
    R : float
        Summit radius, m.
    E_star : float
        Contact modulus E*, Pa.
    H : float
        Hardness of the softer solid, Pa.
    nu : float
        Poisson's ratio of the softer solid.

    Returns
    -------
    float or ndarray
        Load, N; zero for δ ≤ 0.
    """
    k = 0.454 + 0.41 * nu
    w_c = (np.pi * k * H / (2.0 * E_star)) ** 2 * R
    p_c = 2.0 / 3.0 * np.pi * k * H * R * w_c
    x = np.maximum(delta, 0.0) / w_c
    x0 = np.minimum(x, 1.0)
    low, high = x < 6.0, x >= 6.0
    # one power for both elastic-plastic ranges: 1.03 x^1.425 and 1.40 x^1.263
    power = fit_power(x, low * 1.03 + high * 1.40, low * 1.425 + high * 1.263,
                      low * 2.685145005560527 + high * 2.399942764746431)  # fmt: skip
    ratio = (x < 1.0) * (x0 * np.sqrt(x0)) + (x >= 1.0) * (x < 110.0) * power
    # fully plastic P = HA = 2πHRδ (= P_c 3x/k), with no division: under the kernel's
    # fast-math flags LLVM turns (3/k)·x into a division per summit
    return p_c * ratio + (x >= 110.0) * (2.0 * np.pi * H * R * np.maximum(delta, 0.0))


def elastic_plastic_area(delta, R, E_star, H, nu):
    """Real contact area of one elastic–plastic summit (Kogut & Etsion 2002).

    Parameters
    ----------
    delta : float or ndarray
        Interference δ = z − d, m.
    R : float
        Summit radius, m.
    E_star : float
        Contact modulus E*, Pa.
    H : float
        Hardness of the softer solid, Pa.
    nu : float
        Poisson's ratio of the softer solid.

    Returns
    -------
    float or ndarray
        Area, m²; zero for δ ≤ 0.
    """
    k = 0.454 + 0.41 * nu
    w_c = (np.pi * k * H / (2.0 * E_star)) ** 2 * R
    a_c = np.pi * R * w_c
    x = np.maximum(delta, 0.0) / w_c
    low, high = x < 6.0, x >= 6.0
    # one power for both elastic-plastic ranges: 0.93 x^1.136 and 0.94 x^1.146
    power = fit_power(x, low * 0.93 + high * 0.94, low * 1.136 + high * 1.146,
                      low * 2.1977084351537592 + high * 2.2129947061845443)  # fmt: skip
    ratio = (x < 1.0) * x + (x >= 1.0) * (x < 110.0) * power + (x >= 110.0) * (2.0 * x)
    return a_c * ratio


def critical_interference(R: float, E_star: float, H: float, nu: float) -> float:
    """Interference at the onset of yield, ω_c = (πkH/(2E*))² R, k = 0.454 + 0.41ν, m."""
    return (np.pi * (0.454 + 0.41 * nu) * H / (2.0 * E_star)) ** 2 * R


def _edges(params) -> Edges:
    w_c = critical_interference(params["R"], params["E_star"], params["H"], params["nu"])
    return Edges(breakpoints=(w_c, 6.0 * w_c, 110.0 * w_c))


LAW_SET = LawSet(
    name="elastic-plastic",
    description="Kogut & Etsion (2002) elastic-plastic sphere, no adhesion, loading only",
    outputs=(
        Output("load", "N", elastic_plastic_load, "normal force"),
        Output("area", "m^2", elastic_plastic_area, "real contact area"),
    ),
    edges=_edges,
    requires=("H",),
    retract=False,
    friction=True,
)

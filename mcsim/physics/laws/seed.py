"""The paper's law set, as written: Hertz load, Johnson adhesion, Savkoor–Briggs friction.

See docs/physics.md, sections 'Seed law set' and 'The seed model'.

Pure, vectorised functions of the interference δ = z − d (m), SI in and out, zero
for δ ≤ 0. They are plain arithmetic so that the Monte Carlo kernel compiles these
very functions (see :mod:`mcsim.engine.kernels`); each writes the Hertz load out in δ, as the
second lines of Eqs. 4 and 6 do, rather than calling :func:`hertz_load`, so that each
compiles on its own. K, G and γ are the paper's: see :class:`mcsim.model.params.Material`.
"""

import numpy as np


def hertz_load(delta, R, K):
    """Hertz load of one summit, P_a = K R^½ δ^{3/2} (Eq. 2).

    Parameters
    ----------
    delta : float or ndarray
        Interference δ = z − d, m.
    R : float
        Summit radius, m.
    K : float
        Elastic constant 1/K = ¾ Σ(1−ν²)/E, Pa.

    Returns
    -------
    float or ndarray
        Load, N; zero for δ ≤ 0.
    """
    d = np.maximum(delta, 0.0)
    return K * np.sqrt(R) * d * np.sqrt(d)


def johnson_adhesion(delta, R, K, gamma):
    """JKR adhesion term of one summit, F_a = 3πγR + √(6πγR P_a + (3πγR)²) (Eq. 4).

    This is the paper's "adhesive force": the JKR increase of the apparent Hertz
    load, P1 − P_a (Johnson, Kendall & Roberts 1971). It is always positive, equals
    6πγR at P_a → 0 (four times the JKR pull-off magnitude 1.5πγR) and is *not* an
    attractive or pull-off force.

    Parameters
    ----------
    delta : float or ndarray
        Interference δ, m.
    R : float
        Summit radius, m.
    K : float
        Elastic constant, Pa.
    gamma : float
        Work of adhesion, J/m².

    Returns
    -------
    float or ndarray
        Force, N; zero for δ ≤ 0 (out of contact).
    """
    d = np.maximum(delta, 0.0)
    c = 3.0 * np.pi * gamma * R
    load = K * np.sqrt(R) * d * np.sqrt(d)
    return (delta > 0) * (c + np.sqrt(2.0 * c * load + c * c))


def savkoor_briggs_friction(delta, R, K, G, gamma):
    """Adhesional friction of one summit, T_a = 4 √(G/K) √(2πγR P_a + 3(πγR)²) (Eq. 6).

    Savkoor & Briggs (1977): the tangential force at which the JKR contact peels
    under shear, with the paper's G (Eq. 7).

    Parameters
    ----------
    delta : float or ndarray
        Interference δ, m.
    R : float
        Summit radius, m.
    K : float
        Elastic constant, Pa.
    G : float
        Combined shear modulus 1/G = Σ(2−ν)/G_i, Pa.
    gamma : float
        Work of adhesion, J/m².

    Returns
    -------
    float or ndarray
        Force, N; zero for δ ≤ 0 (out of contact).
    """
    d = np.maximum(delta, 0.0)
    a = np.pi * gamma * R
    load = K * np.sqrt(R) * d * np.sqrt(d)
    return (delta > 0) * (4.0 * np.sqrt(G / K) * np.sqrt(2.0 * a * load + 3.0 * a * a))

"""A model of the probability that a pad sticks, from the per-summit statistics (rare events).

A pad of area A holds N ~ Poisson(λ = ηA) summits with iid heights s (in σ); see
docs/physics.md, section 'The stiction model'. To first order its pull-off X at a
separation h (d/σ) after the mean-field turn h̄ is a compound-Poisson sum:

* Force control: the pad turns at h_t ≈ h̄ + (P·A − F_a(h̄))/F̄_a′(h̄), so its retraction
  load at h is F_r(h; h_t) ≈ Σ g(s_i) + c·P·A with g(s) = f_r(s − h; s − h̄) − c·f_a(s − h̄)
  and c = ∂_{h_t}E[F_r(h; h_t)] / ∂_{h_t}E[F_a(h_t)] at h̄ (mean-field derivatives, by
  central differences of the quadrature). Without a preload the turn is common: c = 0.
* Y = Σ_{i≤N} g(s_i) has the cumulant generating function K(t) = λ(E[e^{tg}] − 1)
  (compound Poisson), and p(h) = P(−Y − c·P·A > F_r) = P(Y < y0) is its lower tail at
  y0 = −F_r − c·P·A, from the **Lugannani–Rice saddlepoint approximation** (Lugannani &
  Rice 1980; Daniels 1987, Eq. 2.6): K′(t̂) = y0, w = sgn(t̂)√(2(t̂y0 − K(t̂))),
  u = t̂√K″(t̂), P(Y ≤ y0) ≈ Φ(w) + φ(w)(1/w − 1/u). Chosen over a normal approximation
  with a skewness (Edgeworth) correction because its error is *relative* and uniform far
  into the tail (O(1/λ) for a compound-Poisson sum, Jensen 1995, Sect. 2.3), where the
  Edgeworth series' absolute error of O(λ^{-1}) exceeds the probabilities 1e-4 … 1e-6 of
  interest. Near the mean (|t̂| → 0) it has the limit 1/2 + κ₃/(6√(2π)κ₂^{3/2}).
* The pull-off is the extremum of each pad's own curve, min over h, not its value at the
  mean curve's h*: p_stick = P(∪_k A_k), A_k = {X(h_k) > F_r} over the grid h_k = h* +
  :data:`OFFSETS`, which max_k P(A_k) only bounds from below (measured: 0.69 against a
  brute-force 0.84 without a preload at 255 contacting summits). The joint law of the
  X(h_k) is taken as a **Gaussian copula** of the saddlepoint marginals p_k = P(A_k): the
  correlations are those of the compound-Poisson sums, ρ_kl = E[g_k g_l]/√(E[g_k²]E[g_l²])
  (Campbell's theorem), and b_k = Φ⁻¹(p_k). Where P(∪A_k) = 1 − Φ_K(−b; ρ) is at least
  :data:`JOINT_FLOOR` it is evaluated by Genz's algorithm (``scipy.stats.multivariate_normal``,
  fixed seed, absolute error below 1e-6); below, in the rare-event tail where that
  absolute error would swamp it, by Hunter's chain bound Σ p_k − Σ P(A_k ∩ A_{k+1})
  (Hunter 1976; bivariate normal), which is exact when each pad's excursion above F_r is
  one interval of h, as it is when sticking is rare. What remains is the part of the
  extremum between grid points (jumps at break-off), measured against brute force in
  ``validation/stiction_model.py``.

E[·] over s are trapezoid sums of the height density on :data:`NODES` nodes between the
lowest height that touches and s̄ + 8 (beyond, the density is below 1e-14 of its peak
for the Gaussian).
"""

from __future__ import annotations

import math

import numpy as np

from mcsim.engine.kernels import block_sums, sum_columns

#: Height nodes of the quadrature over s.
NODES = 4000
#: Separations (d/σ) around the mean curve's pull-off over which the tail is maximised.
OFFSETS = np.linspace(-0.3, 0.3, 13)
#: Largest exponent of the tilted weights (exp(700) ≈ 1e304, below float64's overflow).
_EXP_CAP = 700.0
#: Below this union probability the chain bound replaces Genz's algorithm (module docstring).
JOINT_FLOOR = 1e-3
#: Step (in h) of the central differences of the mean loads: several quadrature nodes wide (the
#: retraction load changes with the turn through the summits that touch, a step in s).
STEP = 0.01


def _per_summit(spec, s, h, h_turn) -> np.ndarray:
    """Load (N) of one summit of height s (σ) at separation h after the closest approach h_turn.

    One summit at z = 0 and the rows d = −δ: the kernel's sum is the per-summit law.
    """
    sigma = spec.surface.sigma
    d, d_turn = -(s - h) * sigma, -(s - h_turn) * sigma
    column = sum_columns(spec.law_set).index("load")
    return block_sums(np.zeros(1), d, spec.law_set, spec.arguments, d_turn=d_turn,
                      edges=spec.edges)[:, column]  # fmt: skip


def _quadrature(spec, low: float) -> tuple[np.ndarray, np.ndarray]:
    """Nodes s (σ) and trapezoid weights of the height density, λ included, from ``low``."""
    heights = spec.surface.heights
    s = np.linspace(low, 8.0, NODES)
    w = np.full(NODES, s[1] - s[0])
    w[[0, -1]] /= 2
    return s, w * heights.pdf(s) * spec.surface.eta * spec.area


def _lugannani_rice(g: np.ndarray, w: np.ndarray, y0: float) -> float:
    """P(Y ≤ y0) of the compound-Poisson Y = Σ g(s_i) with intensity weights w (module docstring)."""
    from scipy.optimize import brentq
    from scipy.special import ndtr

    def moments(t):
        # Capped below exp's overflow: the cap only bends K where y0 lies beyond every
        # reachable value, which the bracketing below reports as a tail of 0 or 1.
        e = w * np.exp(np.minimum(t * g, _EXP_CAP))
        return np.sum(e) - np.sum(w), np.sum(e * g), np.sum(e * g * g)

    k1, k2 = float(np.sum(w * g)), float(np.sum(w * g * g))
    if k2 == 0:
        return float(y0 >= 0)
    scale = 1 / math.sqrt(k2)
    if abs(y0 - k1) < 1e-6 * math.sqrt(k2):
        k3 = float(np.sum(w * g**3))  # clipped: a skewness past ±3√(2π) leaves [0, 1]
        return min(1.0, max(0.0, 0.5 + k3 / (6 * math.sqrt(2 * math.pi) * k2**1.5)))
    lo, hi = (-scale, 0.0) if y0 < k1 else (0.0, scale)
    while (moments(lo)[1] - y0) > 0:
        if lo < -1e6 * scale:
            return 0.0  # below every reachable value
        lo *= 2
    while (moments(hi)[1] - y0) < 0:
        if hi > 1e6 * scale:
            return 1.0
        hi *= 2
    t = brentq(lambda x: moments(x)[1] - y0, lo, hi, xtol=1e-14 * scale, rtol=1e-12)
    k, _, kpp = moments(t)
    with np.errstate(over="ignore"):  # t y0 past any float (a huge F_r): w -> inf, the tail's 1
        wv = math.copysign(math.sqrt(max(2 * (t * y0 - k), 0.0)), t)
    u = t * math.sqrt(kpp)
    return float(min(1.0, max(0.0, ndtr(wv) + _norm_pdf(wv) * (1 / wv - 1 / u))))


def _norm_pdf(x: float) -> float:
    """``scipy.stats.norm.pdf(x)`` without importing scipy.stats (≈0.5 s of a command's
    start), computed as it does: on a 1-element array (NumPy's exp of an array may differ in
    the last bit from its exp of a scalar); ``norm.cdf`` is scipy.special's ``ndtr``."""
    return float((np.exp(-(np.array([x], dtype=float) ** 2) / 2.0) / np.sqrt(2 * np.pi))[0])


def p_stick_model(spec, restoring_force: float, *, turn: float, h_pull_off: float,
                  preload: float | None = None) -> float:  # fmt: skip
    """Model estimate of p_stick = P(pull-off > F_r) for the pads of ``spec`` (module docstring).

    Parameters
    ----------
    spec : MonteCarloSpec
        The pads (surface, material, law set, area; Poisson summit count).
    restoring_force : float
        F_r, N.
    turn : float
        Mean-field turn h̄ = d/σ (under a preload, the one that balances it).
    h_pull_off : float
        Separation d/σ of the mean curve's pull-off after ``turn``.
    preload : float, optional
        Nominal pressure P, Pa: force control (else a common turn, c = 0).

    Returns
    -------
    float
        P(pull-off > F_r): the Lugannani–Rice tails at h* + :data:`OFFSETS`, joined over
        the offsets by their Gaussian copula (module docstring). NaN for pads with an
        environment (``spec.environment``) or a radius by height
        (``spec.surface.radius_by_height``): the model has not been checked against their
        pads there (nor written for several radii), whose own estimate is the answer.
    """
    if spec.environment is not None or spec.surface.radius_by_height is not None:
        return math.nan
    low = turn - 1.0
    s, w = _quadrature(spec, low)
    f_a = _per_summit(spec, s, turn, turn)
    gs, tails = [], []
    for h in h_pull_off + OFFSETS:
        if h < turn + STEP:
            continue
        f_r = _per_summit(spec, s, h, turn)
        c, applied = 0.0, 0.0
        if preload is not None:
            up, down = _per_summit(spec, s, h, turn + STEP), _per_summit(spec, s, h, turn - STEP)
            slope_r = np.sum(w * (up - down)) / (2 * STEP)
            a_up = _per_summit(spec, s, turn + STEP, turn + STEP)
            a_down = _per_summit(spec, s, turn - STEP, turn - STEP)
            c, applied = slope_r / (np.sum(w * (a_up - a_down)) / (2 * STEP)), preload * spec.area
        gs.append(f_r - c * f_a)
        tails.append(_lugannani_rice(gs[-1], w, -restoring_force - c * applied))
    return _union(np.array(gs), w, np.array(tails))


def _union(g: np.ndarray, w: np.ndarray, p: np.ndarray) -> float:
    """P(∪_k A_k) from the marginals ``p`` (K,) and the per-summit loads ``g`` (K, nodes) with
    intensity weights ``w``: Gaussian copula, Genz or Hunter's chain bound (module docstring)."""
    if p.size == 0:
        return 0.0
    top = float(p.max())
    if p.size == 1 or top >= 1 - 1e-12 or top <= 0:
        return top
    second = (g * w) @ g.T  # E[Σ g_k Σ g_l] − E[Σ g_k]E[Σ g_l] = λE[g_k g_l] (Campbell)
    scale = np.sqrt(np.diag(second))
    if np.any(scale == 0):
        return top
    from scipy.stats import multivariate_normal, norm  # here: ≈0.5 s, for the copula only

    rho = np.clip(second / np.outer(scale, scale), -1.0, 1.0)
    b = norm.ppf(np.clip(p, 1e-300, 1.0))
    pair = np.clip(np.diagonal(rho, 1), -1 + 1e-12, 1 - 1e-12)  # neighbours' correlations
    chain = p.sum() - sum(
        multivariate_normal([0.0, 0.0], [[1.0, r], [r, 1.0]], allow_singular=True).cdf(b[k : k + 2])
        for k, r in enumerate(pair)
    )
    if chain < JOINT_FLOOR:
        return float(min(max(chain, top), 1.0))
    joint = multivariate_normal(np.zeros(p.size), rho, allow_singular=True, seed=0,
                                maxpts=50_000 * p.size, abseps=1e-6, releps=1e-4)  # fmt: skip
    return float(min(max(1.0 - joint.cdf(-b), top), 1.0))

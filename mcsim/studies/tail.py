"""p_stick far in the tail (1e-2 … 1e-6) by importance sampling of pads.

No affordable number of plain pads resolves p_stick = P(pull-off > F_r) of 1e-4 … 1e-6, and
the saddlepoint model (:mod:`mcsim.studies.stiction`) fails where few summits touch.
Importance sampling is exact at any summit count (Owen, *Monte Carlo theory, methods and
examples*, 2013, ch. 9): pads are drawn from a tilted law q and each is weighted by its
likelihood ratio L = dP/dQ, so that p̂ = mean(L·1{event}) is unbiased for any q that covers
the event; q only sets the variance.

* **The pads' law.** A pad's summits above s_min (the only ones a run draws, and the only
  ones that can touch) are a Poisson process of intensity λ φ(s) (λ = ηA, φ the height
  density, s = z/σ). It is split at the cut s_c = max(s_min, h̄ − :data:`CUT`) below the
  mean-field turn h̄: the summits below the cut keep the nominal law (drawn as a run draws
  them, thinned to s ≤ s_c), the summits above it, those that decide the pad, are drawn
  from the tilted process: count N ~ Poisson(λ'), heights from a normal N(μ, τ²) truncated
  to s > s_c (:class:`Tilt`). With g that truncated density, the likelihood ratio of the
  two Poisson processes is (Owen, Eq. 9.15 for each summit; Kingman, *Poisson processes*,
  1993, Sect. 3.2 for the count)

      L = exp(λ' − λ S(s_c)) · Π_i λ φ(s_i) / (λ' g(s_i)),

  the product over the summits above the cut, S the survival function. It equals
  e^{λ'−λ_c}(λ_c/λ')^N Π φ_c(s_i)/g(s_i) with λ_c = λ S(s_c) and φ_c = φ/S(s_c) the nominal
  count and density above the cut.
* **The tilt, by the cross-entropy method** (Rubinstein & Kroese, *The cross-entropy
  method*, 2004, Algorithm 3.4.1). Under force control the pull-off is not monotone in the
  heights (a taller summit turns the pad higher and weakens it), so the tilt is found, not
  assumed: stage 0 draws pads from the nominal law (or takes the plain pads already
  evaluated), each stage keeps its elite, the :data:`RHO` fraction of pads nearest the
  event (all pads in the event once they are that many), and fits λ', μ, τ to the elite's
  summits above the cut by weighted maximum likelihood (weights L: the count's mean, and the
  truncated normal's μ, τ numerically), smoothed by :data:`SMOOTHING` (Rubinstein & Kroese,
  Remark 3.4.2). At most :data:`STAGES` stages.
* **The estimate.** ``pads`` pads drawn from the last tilt: p̂ = mean(L·1{event}) with the
  standard error of that mean (sample standard deviation, ddof = 1, over √n) and the normal
  95 % interval p̂ ± 1.96 se clipped to [0, 1]; the effective sample size of the weights in
  the event, (Σ L·1)²/Σ (L·1)² (Kish; Owen, Sect. 9.3): the pads outside the event do not
  enter p̂, and their weights, large or not, say nothing of its precision. The event is
  sticking when sticking is rare, and not sticking (p = 1 − P(not sticking)) when that is
  the rarer one.

Each pad is evaluated by :func:`mcsim.engine.padcurves.force_turn` and
:func:`~mcsim.engine.padcurves.pull_off` with the run's spec, as plain pads are, so every
law set (and its environment) of the spec applies unchanged. Stage k draws from its own
stream ``SeedSequence(spec.entropy, spawn_key=(STREAM, k))``, apart from the plain pads'
(realization r: keys (r, 0), (r, 1 + b)); all of a stage is drawn before any pad is
evaluated, so the estimate is bit-identical for any ``workers``.
"""

from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np

from mcsim.model.errors import ParameterError

#: Elite fraction of each cross-entropy stage (Rubinstein & Kroese 2004 use 0.01 … 0.1).
RHO = 0.1
#: Largest number of cross-entropy stages after stage 0.
STAGES = 8
#: Smoothing of the fitted tilt: new = SMOOTHING · fit + (1 − SMOOTHING) · previous.
SMOOTHING = 0.7
#: Depth of the cut below the mean-field turn, in σ: the summits above it are tilted.
CUT = 1.0
#: Smallest width τ of the tilted heights, in σ (keeps the tilted law covering the event).
SCALE_FLOOR = 0.1
#: First element of the tail's stream keys (module docstring): above any realization index.
STREAM = 2**63
#: Two-sided 95 % normal quantile of the interval.
Z95 = 1.959963984540054


@dataclass(frozen=True)
class Tilt:
    """The tilted law of a pad's summits above the cut (module docstring).

    Attributes
    ----------
    rate : float
        λ', expected number of summits above the cut (dimensionless).
    mean, scale : float
        μ and τ of their heights' normal before truncation to s > s_c, in σ.
    """

    rate: float
    mean: float
    scale: float


@dataclass(frozen=True)
class TailEstimate:
    """p_stick by importance sampling (module docstring).

    Attributes
    ----------
    p_stick, se : float
        The estimate of P(pull-off > F_r) and its standard error (dimensionless).
    low, high : float
        Its 95 % normal interval, clipped to [0, 1].
    ess : float
        Effective number of final pads in the event: (Σ L·1)²/Σ (L·1)² over the pads, 1 the
        event's indicator (Kish's effective sample size of the weights that make p̂).
    hits : int
        Final pads in the event (sticking, or not sticking where that is the rare side).
    pads : int
        Final pads drawn from the last tilt.
    evaluations : int
        Pads evaluated in all, pilot stages included (a stage 0 of given plain pads not).
    stages : int
        Cross-entropy stages after stage 0.
    reached : bool
        Whether the last stage's elite lay in the event (else the tilt stopped short of
        F_r after :data:`STAGES` stages: the estimate is unbiased still, its variance larger).
    event : str
        ``"stick"`` or ``"release"``: which side was sampled.
    tilt : Tilt
        The last tilt.
    cut : float
        The cut s_c, in σ.
    """

    p_stick: float
    se: float
    low: float
    high: float
    ess: float
    hits: int
    pads: int
    evaluations: int
    stages: int
    reached: bool
    event: str
    tilt: Tilt
    cut: float


def cut(spec, turn: float) -> float:
    """The cut s_c = max(s_min, h̄ − :data:`CUT`) (σ) above which summits are tilted."""
    return max(spec.s_min, turn - CUT)


class _Law:
    """The nominal and tilted laws of a pad's summits (heights in σ) and the likelihood ratio."""

    def __init__(self, spec, cut: float):
        self.spec, self.cut = spec, cut
        self.heights = spec.surface.heights
        self.lam = spec.surface.eta * spec.area
        self.below = self.lam * float(self.heights.sf(spec.s_min))  # Poisson mean above s_min
        self.above = self.lam * float(self.heights.sf(cut))  # λ_c

    def draw(self, tilt: Tilt | None, rng) -> tuple[np.ndarray, np.ndarray]:
        """One pad: its heights above s_min (σ), and those above the cut (from ``tilt``)."""
        from mcsim.model.distributions import Gaussian

        low = self.heights.sample_above(int(rng.poisson(self.below)), self.spec.s_min, rng)
        low = low[low <= self.cut]
        if tilt is None:
            high = self.heights.sample_above(int(rng.poisson(self.above)), self.cut, rng)
        else:
            n = int(rng.poisson(tilt.rate))
            a = (self.cut - tilt.mean) / tilt.scale
            high = tilt.mean + tilt.scale * Gaussian().sample_above(n, a, rng)
        return np.concatenate([low, high]), high

    def log_ratio(self, tilt: Tilt | None, high: np.ndarray) -> float:
        """log L of a pad whose summits above the cut are ``high`` (module docstring)."""
        if tilt is None:
            return 0.0
        from scipy.special import log_ndtr

        u = (high - tilt.mean) / tilt.scale
        log_g = (-0.5 * u * u - math.log(tilt.scale * math.sqrt(2 * math.pi))
                 - log_ndtr((tilt.mean - self.cut) / tilt.scale))  # fmt: skip
        with np.errstate(divide="ignore"):
            log_f = np.log(self.lam * self.heights.pdf(high))
        return float(tilt.rate - self.above + np.sum(log_f - math.log(tilt.rate) - log_g))


def _fit(law: _Law, previous: Tilt, highs: list, weights: np.ndarray) -> Tilt:
    """The smoothed cross-entropy tilt from elite pads' summits above the cut and their weights."""
    from scipy.optimize import minimize
    from scipy.special import log_ndtr

    total = float(np.sum(weights))
    counts = np.array([h.size for h in highs], dtype=float)
    rate = float(np.sum(weights * counts)) / total
    s = np.concatenate(highs) if highs else np.empty(0)
    mean, scale = previous.mean, previous.scale
    if s.size:
        w = np.repeat(weights, counts.astype(int)) / total
        m0 = float(np.sum(w * s) / np.sum(w))
        v0 = float(np.sum(w * (s - m0) ** 2) / np.sum(w))

        def nll(x):  # weighted negative log-likelihood of the truncated normal
            mu, tau = x[0], math.exp(x[1])
            u = (s - mu) / tau
            return float(np.sum(w * (0.5 * u * u + x[1] + log_ndtr((mu - law.cut) / tau))))

        x0 = [m0, 0.5 * math.log(max(v0, SCALE_FLOOR**2))]
        x = minimize(nll, x0, method="Nelder-Mead", options={"xatol": 1e-6, "fatol": 1e-12}).x
        mean, scale = float(x[0]), max(float(math.exp(x[1])), SCALE_FLOOR)
    a = SMOOTHING
    rate = max(a * rate + (1 - a) * previous.rate, 1e-6 * law.above)
    return Tilt(rate, a * mean + (1 - a) * previous.mean, a * scale + (1 - a) * previous.scale)


def pad_pull_off(spec, s: np.ndarray, *, turn: float, preload: float | None) -> float:
    """One pad's pull-off (N) from its summit heights ``s`` (σ), as plain pads evaluate it.

    Under a ``preload`` (Pa) the pad turns where its own approach load reaches P·A
    (:func:`mcsim.engine.padcurves.force_turn`), else at ``turn`` (d/σ); its pull-off is
    :func:`mcsim.engine.padcurves.pull_off` after that turn.
    """
    from mcsim.engine import padcurves

    z = s * spec.surface.sigma
    d_turn = turn * spec.surface.sigma
    if preload is not None:
        d_turn, _ = padcurves.force_turn(spec, z, preload * spec.area)
    return padcurves.pull_off(spec, z, d_turn)[0]


def _stage(law: _Law, tilt: Tilt | None, n: int, key: int, evaluate, workers: int):
    """``n`` pads drawn from ``tilt`` (nominal: None) on stream ``key``: their summits above
    the cut, log L and pull-off (N)."""
    rng = np.random.default_rng(np.random.SeedSequence(law.spec.entropy, spawn_key=(STREAM, key)))
    pads = [law.draw(tilt, rng) for _ in range(n)]  # all drawn before any is evaluated
    log_l = np.array([law.log_ratio(tilt, high) for _, high in pads])
    if workers > 1:
        with ThreadPoolExecutor(workers) as pool:
            force = np.array(list(pool.map(evaluate, [s for s, _ in pads])))
    else:
        force = np.array([evaluate(s) for s, _ in pads])
    return [high for _, high in pads], log_l, force


def importance_p_stick(spec, restoring_force: float, *, turn: float, preload: float | None = None,
                       pads: int, pilot: int, event: str = "stick", start=None,
                       workers: int = 1, score=None) -> TailEstimate:  # fmt: skip
    """P(pull-off > F_r) of the pads of ``spec`` by importance sampling (module docstring).

    Parameters
    ----------
    spec : MonteCarloSpec
        The pads (surface, material, law set, area, Poisson summit count, seed); its lowest
        separation bounds the turns.
    restoring_force : float
        F_r, N: a pad sticks when its pull-off exceeds it.
    turn : float
        The mean-field turn h̄ (d/σ): the common turn without a preload, and where the cut lies.
    preload : float, optional
        Nominal pressure P, Pa: force control (each pad turns under P·A).
    pads : int
        Final pads drawn from the last tilt (≥ 2).
    pilot : int
        Pads per cross-entropy stage (≥ 1/:data:`RHO`).
    event : {"stick", "release"}
        The rare side to sample: sticking, or not sticking (p̂ = 1 − its probability).
    start : tuple of (list of ndarray, ndarray), optional
        Stage 0 already evaluated on the nominal law, e.g. the plain pads: each pad's summit
        heights above :func:`cut` (σ) and its pull-off (N); else stage 0 draws ``pilot`` pads.
    workers : int
        Threads evaluating the pads of a stage (the result does not depend on it).
    score : callable, optional
        What is compared with ``restoring_force``, as a function of a pad's summit heights
        above s_min (σ); default its pull-off (:func:`pad_pull_off`). Another score gives
        the probability of another event of the same pads (the tests' exact cases).

    Returns
    -------
    TailEstimate

    Raises
    ------
    ParameterError
        A fixed summit count, too few pads or pilot pads, an unknown event, or a pad whose
        approach load stays below P·A down to the lowest separation.
    """
    if spec.count != "poisson":
        raise ParameterError(f"count = {spec.count!r}: importance sampling of pads needs a "
                             "Poisson summit count")  # fmt: skip
    if event not in ("stick", "release"):
        raise ParameterError(f"event = {event!r}: allowed stick, release")
    if pads < 2 or pilot * RHO < 1:
        raise ParameterError(f"pads = {pads!r}, pilot = {pilot!r}: importance sampling needs "
                             f"pads >= 2 and pilot >= {math.ceil(1 / RHO)}")  # fmt: skip
    law = _Law(spec, cut(spec, turn))
    fr = float(restoring_force)
    sign = 1.0 if event == "stick" else -1.0

    def evaluate(s):
        return pad_pull_off(spec, s, turn=turn, preload=preload)

    evaluate = evaluate if score is None else score

    def hit(force):  # the event: sticking, or its complement
        return (force > fr) if event == "stick" else ~(force > fr)

    tilt, evaluations = None, 0
    if start is None:
        highs, log_l, force = _stage(law, None, pilot, 0, evaluate, workers)
        evaluations += pilot
    else:
        highs, force = start
        log_l = np.zeros(len(highs))
    fitted = Tilt(law.above, 0.0, 1.0)  # the nominal count above the cut, standard heights
    reached, stage = False, 0
    while True:
        margin = sign * (force - fr)
        hits = hit(force)
        elite_size = math.ceil(RHO * margin.size)
        reached = int(np.count_nonzero(hits)) >= elite_size
        if reached:
            elite = hits
        else:
            level = np.sort(margin)[-elite_size]
            elite = margin >= level
        weights = np.exp(log_l[elite] - np.max(log_l[elite]))  # L up to a common factor
        fitted = _fit(law, fitted, [h for h, e in zip(highs, elite) if e], weights)
        tilt = fitted
        if reached or stage == STAGES:
            break
        stage += 1
        highs, log_l, force = _stage(law, tilt, pilot, stage, evaluate, workers)
        evaluations += pilot
    _, log_l, force = _stage(law, tilt, pads, STAGES + 1, evaluate, workers)
    evaluations += pads
    weight = np.exp(log_l)
    y = weight * hit(force)
    q, se = float(np.mean(y)), float(np.std(y, ddof=1) / math.sqrt(pads))
    low, high = max(0.0, q - Z95 * se), min(1.0, q + Z95 * se)
    if event == "release":
        q, low, high = 1.0 - q, 1.0 - high, 1.0 - low
    ess = float(np.sum(y) ** 2 / np.sum(y**2)) if np.any(y) else 0.0
    return TailEstimate(min(max(q, 0.0), 1.0), se, max(low, 0.0), min(high, 1.0), ess,
                        int(np.count_nonzero(y)), pads, evaluations, stage, reached, event,
                        tilt, law.cut)  # fmt: skip

"""p_stick far in the tail (1e-2 … 1e-6) by importance sampling of pads.

No affordable number of plain pads resolves p_stick = P(pull-off > F_r) of 1e-4 … 1e-6, and
the saddlepoint model (:mod:`mcsim.studies.stiction`) fails where few summits touch.
Importance sampling is exact at any summit count (Owen, *Monte Carlo theory, methods and
examples*, 2013, ch. 9): pads are drawn from a tilted law q and each is weighted by its
likelihood ratio L = dP/dQ, so that p̂ = mean(L·1{event}) is unbiased for any q that covers
the event; q only sets the variance.

* **The pads' law.** A pad's summits above s_min (the only ones a run draws, and the only
  ones that can touch) are a Poisson process of intensity λ φ(s) (λ = ηA, φ the height
  density, s = z/σ). It is split at the cut s_c = max(s_min, h̄ − :data:`~mcsim.studies.tiltlaw.CUT`) below the
  mean-field turn h̄: the summits below the cut keep the nominal law (drawn as a run draws
  them, thinned to s ≤ s_c); the summits above it, those that decide the pad, are drawn
  from a tilted Poisson process of intensity r_k λ φ(s) in height bin k (:data:`~mcsim.studies.tiltlaw.BINS` bins
  of :data:`~mcsim.studies.tiltlaw.BIN` σ from the cut, the last one open; :class:`~mcsim.studies.tiltlaw.Tilt`): in each bin a
  Poisson(r_k m_k) count, m_k = λ P(bin k) the nominal one, of heights from φ restricted to
  the bin. The likelihood ratio of the two Poisson processes (the ratio of their densities:
  Poisson counts per bin, the same heights within a bin; Owen, ch. 9) is

      L = exp(Σ_k m_k (r_k − 1)) · Π_k r_k^(−n_k),

  n_k the pad's summits in bin k: the general e^{λ'−λ}(λ/λ')^N Π φ(s_i)/φ_q(s_i) for this
  q. Piecewise constant, the tilt takes any shape the event asks for: more summits just
  above the turn and none far above it (a sticking pad under force control), or one tall
  summit that carries the preload (a pad that does not stick); a shifted normal for every
  summit could not do both (measured at p ≈ 6e-6, σ = 3 nm, 2000 pads: relative standard
  error 12 % against 19 %).
* **The tilts, by the cross-entropy method** (Rubinstein & Kroese, *The cross-entropy
  method*, 2004, ch. 3, the multilevel algorithm for rare events). Under force control the
  pull-off is not monotone in the heights (a taller summit turns the pad higher and weakens
  it), so the tilt is found, not assumed, by :data:`CHAINS` independent chains: each starts
  from its own stage 0 from the nominal law (its own ``pilot`` pads, or its share of the
  plain pads already evaluated, dealt in turn), and each stage sets a level, the margin to
  F_r of the :data:`RHO` fraction of the stage's new pads nearest the event (the event itself
  once that many are in it), and fits r_k to the elite: every pad of *all* the chain's stages
  at or above the level, r_k its weighted mean count in bin k over m_k (the
  maximum-likelihood intensity of a Poisson process), each pad weighted by the balance
  heuristic over the laws the chain has drawn from (below; stage 0's nominal law among
  them), smoothed by :data:`~mcsim.studies.tiltlaw.SMOOTHING` (Rubinstein & Kroese's smoothed updating) and kept
  above :data:`~mcsim.studies.tiltlaw.RATIO_FLOOR`. At most :data:`STAGES` stages. Reusing the stages' pads gives
  each fit the elite of every stage, not only the last one's thirty.
* **The estimate: a defensive mixture** (Hesterberg, *Technometrics* 37, 185, 1995; Owen,
  ch. 9.11). The last tilt alone gives every pad in the event the weight L, unbounded: a
  sticking pad with a summit in a bin the tilt thins to r_k = 0.03 weighs ×33 per summit, and
  on the few-summit case at p ≈ 1e-2 such pads (3 % of the event) carried 95–99.7 % of
  E_q[L²·1], a relative standard deviation per pad of 13–48 against 9.9 for plain pads, which
  a run of 1000 pads seldom sees: its p̂ lies low, its standard error too small, and its
  interval covered brute force in 23 of 28 runs (validation/README.md). So the
  ``pads`` final pads are drawn from 1 + 2 :data:`CHAINS` laws: n₀ = ⌈:data:`DEFENSIVE` ·
  pads⌉ from the nominal law q₀ = p and, for each chain, ⌈:data:`HALF_WAY` · pads/CHAINS⌉
  from its tilt half-way (ratios √r_k, :func:`~mcsim.studies.tiltlaw.half`: between the two in log) and the rest of
  its share from its last tilt (:func:`mixture`), and every pad, whichever law drew it, is
  weighted by the balance heuristic of the mixture (Veach & Guibas, SIGGRAPH 1995; Owen,
  ch. 9.12),

      w = p/Σ_j c_j q_j = 1/Σ_j (c_j/L_j),   c_j = n_j/pads,   L_j = p/q_j,

  L_j the ratio above for law j (L₀ = 1). Unbiased for this fixed allocation: the pads of
  law j contribute (n_j/pads)·E_j[w·1] = ∫ 1·p·c_j q_j/Σ_i c_i q_i, and these sum to
  ∫ 1·p = P(event), whatever the tilt (q > 0 wherever p > 0 is not needed: the nominal part
  covers it). Every weight is at most 1/c₀ ≤ 1/DEFENSIVE and at most L_j/c_j for each j, so
  the second moment per pad, Σ_j c_j E_j[(w·1)²] = E_p[w·1], is at most P(event)/c₀ (plain
  pads: P(event)) and at most E_{q_j}[(L_j·1)²]/c_j (one law alone; Hesterberg 1995, Owen &
  Zhou, *JASA* 95, 135, 2000). The half-way law fills the gap between the two others where
  the tilt thins the bins a pad of the event still uses (its weights then stay near
  1/c₁·L₁ instead of 1/c₀). **The chains' stages join the final pads** (adaptive multiple
  importance sampling: Cornuet, Marin, Mira & Robert, *Scand. J. Stat.* 39, 798, 2012): the
  sum runs over every pad evaluated, the stages 0 among the nominal ones, and the mixture
  over every law drawn from, c_j = n_j/(all pads); the stages' laws, between the nominal
  law and the tilts, lighten the weights of the pads the tilts make rare (p ≈ 1e-4 as
  ``sweep --pads 2000`` runs it: relative half-widths ≤ 0.30 in 9 of 10 seeds against a
  few above 0.4; validation/README.md). A stage's law depends on the earlier stages' pads,
  so this estimate is consistent rather than exactly unbiased (Cornuet et al.); the
  coverage checks on exact events measure it. **The pooled tilt.** A product tilt cannot follow
  two ways into the event at once, and at p ≈ 5e-6 a few final pads that the tilts make rare
  (sticking through more summits further below the turn, with one above it) carried 90 % of
  Σ(w·1)² in half the seeds. So, after the final pads, :data:`FITTED` · ``pads`` more are drawn
  from one tilt fitted, unsmoothed, to every pad in the event so far (both chains' stages and
  the final pads, each weighted by the deterministic mixture of every law drawn: the
  cross-entropy fit of the pooled pads), and join the sum and the mixture as one more law
  (AMIS's next step, Cornuet et al.); where no pad lies in the event none are drawn. The reach
  point's half-width stayed within 0.2 on 20 of 20 seeds from 14 000 evaluations, against 15
  of 20 from 15 000 without it; a mixture of two such tilts fitted by weighted EM reached 10 of 10,
  but lowered p̂ by 3.4 % on an exact event (the components fit the few heavy pads they then
  reweight) and its intervals held p in 85 of 100 runs: not used (validation/README.md).
  p̂ = mean(w·1{event}); its standard error is the pooled
  sample standard deviation of w·1 (ddof = 1) over √pads, which for the fixed allocation
  overstates the variance by the spread of the two laws' means (Owen, ch. 9.12):
  conservative. **One effective sample size**, n* = p̂(1 − p̂)/se² (the plain pads that would
  give the same standard error); the reported ``ess`` is n*·p̂, the effective number of pads
  in the event (for plain pads exactly their count of events), which
  :func:`mcsim.studies.pads.rare_event` gates on and the interval takes: Clopper–Pearson's
  of x* = n*·p̂ events in n* trials (Korn & Graubard, *Survey Methodology* 24, 193, 1998; not
  capped at ``pads``, since importance sampling beats plain pads), skewed upwards as the sum
  of a few large weights is, where the normal interval p̂ ± 1.96 se covered in fewer runs
  (41 against 43 of 48 runs of the two-part mixture of 1000 pads; validation/README.md).
  Where n* is undefined (no pad in the event, or all weights alike) the interval is
  Clopper–Pearson's of the n₀ nominal pads alone (the final ⌈DEFENSIVE · pads⌉ and the
  stages 0): they are plain pads, so it holds whatever the tilts drew; with none in the
  event [0, 1 − 0.025^(1/n₀)] ≈ [0, 3.7/n₀]
  (:func:`~mcsim.studies.intervals.effective_clopper_pearson`). The event is sticking when
  sticking is rare, and not sticking (p = 1 − P(not sticking)) when that is the rarer one.
* **The chains' check.** Each chain also estimates p from its own stages, half-way and
  tilted pads and its half of the final nominal ones (the balance heuristic of those three laws), independently
  of the other; where they differ by more than :data:`AGREE` = 3.29 of their combined
  standard error √(se₁² + se₂²) (for two correct normal estimates a chance of 0.1 %) the
  tilts have found different ways into the event and ``agree`` is False:
  :func:`mcsim.studies.rareevent.rare_event` then keeps the plain fraction. So is it where
  either chain's own estimate rests on fewer than :data:`CONFIRM` = 5 effective events (its
  interval spans more than a factor of 7 and would "agree" with anything): a chain that
  found no way in cannot confirm the other's. The pooled mixture holds both tilts, so a way
  in that one chain finds and the other misses is in the estimate; a way in that both miss is
  not detected (docs/physics.md).
  **The tall way in.** Two free chains follow the same way where the score's intermediate
  levels all lead there; under force control a pad sticks with many summits just below the
  turn and none above it, so a first tilt that raises the summits above the turn (r_k > 1 in
  a bin at or above h̄) has found another way, through tall summits. For a rare sticking
  under force control (a ``preload``; at a common turn more summits above it are the usual
  way, and the second chain stays free) the second chain then fits under r_k ≤ 1 in those bins (the cross-entropy fit restricted to
  that family: each bin's Poisson likelihood is concave, so its maximum under the bound is
  the clipped one) and looks for the way below the turn. On an exact event with both ways
  (validation/tail_benchmark.py's ``TwoWays``), where the score hides the way below the turn
  until a pad is almost in it, the second chain found it in none of 30 runs: it ended with
  0–2.5 effective events, and every run says it cannot tell (before :data:`CONFIRM`, 6 of
  the 30 agreed at 0.25–0.72 p; with two free chains 0 of 10 held p or disagreed;
  tests/studies/test_tail.py). Where the first tilt keeps the
  summits above the turn at or below nominal, as sticking pads' tilts do, the second chain
  is free; a rare release is not restricted.

* **The floor.** A caller that needs p only down to a resolution gives a ``floor``
  (``mcsim report``: 0.01 devices of its lot, :data:`mcsim.studies.report.RESOLUTION`). At
  each stage k ≥ 1 that has not reached the event, a chain estimates, from all its pads and
  their balance-heuristic weights as the estimate does, P(margin ≥ ℓ_{k−1}): the previous
  stage's level, fixed before stage k's pads, drawn to reach it, were drawn. The event lies
  within that level (ℓ ≤ 0 until the event is reached), so the upper end of its interval
  bounds P(event). Where it lies below the floor, at an effective sample size of at least
  :data:`MIN_ESS`, the chain stops; where every chain stops so, no final pads are drawn,
  p_stick is 0 and its interval [0, the chains' largest upper end] (for a release 1 and
  [1 − it, 1]), and ``bounded`` is True. Each chain bounds the level with its own tilts, and
  the larger bound is taken, as the chains' check guards the estimate. On exact events at
  p ≈ 2.5e-10 with a floor of 1e-4 the bound held p in 12 of 12 seeds after 3000–3600 pads
  against 5600–6200 for the estimate (tests/studies/test_tail.py); a floor below p leaves
  the estimate bit-identical (the check draws nothing).

Each pad is evaluated by :func:`mcsim.engine.pads.curves.force_turn` and
:func:`~mcsim.engine.pads.curves.pull_off` with the run's spec, as plain pads are, so every
law set (and its environment) of the spec applies unchanged. Stage k of chain c draws from
its own stream ``SeedSequence(spec.entropy, spawn_key=(STREAM, c, k))``, apart from the plain
pads' (realization r: keys (r, 0), (r, 1 + b)), the final pads of law j (:func:`mixture`'s
order) on keys (STREAM, CHAINS, j); all of a stage is drawn before any pad is evaluated, and
each pad is scored by the same function of its heights in this process or on a worker process
(:mod:`mcsim.studies.padpool`: contiguous chunks, joined in order), so the estimate is
bit-identical for any ``workers``.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from mcsim.engine import interrupt
from mcsim.model.errors import ParameterError
from mcsim.studies.intervals import effective_sample_size, weighted_estimate
from mcsim.studies.padpool import PadPool, chunks, opened, portable
from mcsim.studies.tiltlaw import BINS, Law, Tilt, cut, fit, half

#: Elite fraction of each cross-entropy stage (Rubinstein & Kroese 2004 use 0.01 … 0.1).
RHO = 0.1
#: Largest number of cross-entropy stages after stage 0.
STAGES = 8
#: Share of the final pads drawn from the nominal law (the defensive mixture, module
#: docstring): every weight is at most 1/DEFENSIVE = 5. Hesterberg (1995) takes 0.1 … 0.5; at
#: 0.2 the relative standard deviation per pad on the few-summit case at p ≈ 1e-2 is 3.9 (0.1:
#: 4.1, 0.3: 3.9; exact over the 2013 sticking pads of 2·10⁵ brute-force ones, the tilts of
#: 28 runs), and the final pads at p ≈ 1e-6 lose a fifth to the nominal law.
DEFENSIVE = 0.2
#: Share of the final pads drawn from the tilt half-way (ratios √r_k, module docstring): at
#: 0.3 (and 0.5 from the tilt) the intervals held brute force in 63 of 64 runs at p ≈ 1e-2,
#: against 60 of 64 with the two-part mixture on the same seeds (validation/README.md).
HALF_WAY = 0.3
#: Independent cross-entropy chains, each with its own tilt in the final mixture: where their
#: own estimates differ by more than AGREE standard errors, or one of them rests on fewer than
#: CONFIRM effective events, the event may have a way in that one tilt misses (module
#: docstring), and the estimate is not trusted.
CHAINS = 2
#: Largest |z| = |p̂₁ − p̂₂|/√(se₁² + se₂²) of the chains' own estimates that agree: the two-sided
#: normal 0.1 % point, so two correct chains disagree by chance in about one run of 1000.
AGREE = 3.29
#: Fewest effective events (:func:`~mcsim.studies.intervals.effective_sample_size`) each
#: chain's own estimate must rest on for the chains' check to count as a confirmation: with 5
#: its 95 % interval spans a factor of 7 (Clopper–Pearson of 5 events: [1.6, 11.7]), with 2 a
#: factor of 30, wide enough to "agree" with anything. Measured (validation/README.md): 9.9–114
#: on 40 chains of real pads at p ≈ 1e-4 and 5e-6; 0–2.5 on the second chain of all 30 runs of
#: an event with a second way in that it did not find (``TwoWays``), 6 of which agreed before.
CONFIRM = 5.0
#: Pads drawn from the pooled tilt after the final ones, per final pad (module docstring): at
#: 0.25 (5600 + 1400 final pads) the reach point's relative half-width stayed within 0.2 on 20
#: of 20 seeds, against 15 of 20 with 8000 final pads alone (validation/README.md).
FITTED = 0.25
#: First element of the tail's stream keys (module docstring): above any realization index.
STREAM = 2**63
#: Smallest effective sample size of an estimate that is used (the final one, by
#: :func:`mcsim.studies.rareevent.rare_event`, or a level's at the floor): below it a few
#: heavy weights decide p̂ and its interval does not cover (measured: 100 pads of σ = 1.5 nm
#: gave 1 − p̂ = 0.003 [0.0006, 0.0054] at an ESS of 5.9, against a brute-force 18 of 2000 =
#: 0.009 and 0.010–0.013 from 1000 pads at an ESS of ~50).
MIN_ESS = 30


@dataclass(frozen=True)
class TailEstimate:
    """p_stick by importance sampling (module docstring).

    Attributes
    ----------
    p_stick, se : float
        The estimate of P(pull-off > F_r) and its standard error (dimensionless).
    low, high : float
        Its 95 % interval (:func:`~mcsim.studies.intervals.effective_clopper_pearson`), in [0, 1].
    ess : float
        Effective number of pads in the sampled event, n*·p̂ with n* = p̂(1 − p̂)/se²
        (p̂ of the sampled side): the one effective sample size, which the interval takes
        (module docstring); 0 where n* is undefined.
    hits : int
        Pads in the event (sticking, or not sticking where that is the rare side), the
        stages' included: those the estimate sums.
    pads : int
        Final pads, from the nominal law, the half-way tilt and the last tilt
        (:func:`mixture`).
    evaluations : int
        Pads evaluated in all, pilot stages included (a stage 0 of given plain pads not).
    stages : int
        Cross-entropy stages after stage 0.
    reached : bool
        Whether every chain's last stage's elite lay in the event (else a tilt stopped short
        of F_r after :data:`STAGES` stages, or a later chain stalled: the estimate is
        unbiased still, its variance larger).
    event : str
        ``"stick"`` or ``"release"``: which side was sampled.
    tilts, cut : tuple of Tilt, float
        Each chain's last tilt; the cut s_c, in σ.
    agree : bool
        Whether the chains' own estimates agree within :data:`AGREE` combined standard errors,
        each resting on at least :data:`CONFIRM` effective events (module docstring); True
        where no final pads were drawn.
    chains : tuple of tuple of float
        Each chain's own estimate and 95 % interval (p, low, high) of the sampled side (the
        event, before ``"release"`` takes the complement), from its tilts' pads and its share
        of the nominal pads; where ``bounded``, its level's.
    bounded : bool
        Whether every chain stopped at the ``floor`` of :func:`importance_p_stick`: p_stick is
        0 (1 for ``"release"``) and the interval reaches the largest upper end of the chains'
        levels (1 minus it); ``se`` and ``ess`` are the levels' (largest, smallest).
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
    tilts: tuple[Tilt, ...]
    cut: float
    agree: bool
    chains: tuple[tuple[float, float, float], ...] = ()
    bounded: bool = False


def pad_pull_off(spec, s: np.ndarray, *, turn: float, preload: float | None) -> float:
    """One pad's pull-off (N) from its summit heights ``s`` (σ), as plain pads evaluate it:
    :func:`mcsim.engine.pads.curves.pull_off` after its turn
    (:func:`~mcsim.engine.pads.curves.pad_turn`; ``turn`` d/σ, ``preload`` Pa or None)."""
    from mcsim.engine.pads import curves as padcurves

    z = s * spec.surface.sigma
    return padcurves.pull_off(spec, z, padcurves.pad_turn(spec, z, turn, preload))[0]


def _scores(evaluate, pads: list) -> np.ndarray:
    """Each pad's score, ``evaluate`` of its summit heights, in order; a signal ends them
    between pads (:func:`mcsim.engine.interrupt.check`, in a sweep's worker thread too; a
    worker process leaves it to this one)."""
    out = []
    for s in pads:
        interrupt.check()
        out.append(evaluate(s))
    return np.array(out)


def _scorer(evaluate, pool: PadPool):
    """``scores(pads)``: :func:`_scores` of ``pads`` on ``pool``, in contiguous chunks joined
    in order; on its worker processes where they can call ``evaluate``, else on threads."""
    processes = pool.workers > 1 and portable(evaluate)

    def scores(pads: list) -> np.ndarray:
        calls = [(evaluate, pads[c]) for c in chunks(len(pads), pool.workers)]
        return np.concatenate(pool.map(_scores, calls, processes=processes))

    return scores


def _stage(law: Law, tilt: Tilt | None, n: int, key: tuple, scores):
    """``n`` pads drawn from ``tilt`` (nominal: None) on stream ``key``: their summits per bin
    above the cut and their ``scores`` (pull-off, N; :func:`_scorer`)."""
    seed = np.random.SeedSequence(law.spec.entropy, spawn_key=(STREAM, *key))
    pads, highs = law.draw(
        tilt, n, np.random.default_rng(seed)
    )  # all drawn before any is evaluated
    return law.bins(highs), scores(pads)


@dataclass(frozen=True)
class _Chain:
    """One chain's cross-entropy stages: its tilt, stages after stage 0, pads evaluated,
    whether its last stage reached the event, every stage's law (None: nominal), number of
    pads, their summits per bin above the cut and their scores (stage 0 first), and where the
    stages stopped at the floor, the estimate (p̂, se, low, high) of the level below it."""

    tilt: Tilt
    stages: int
    evaluations: int
    reached: bool
    laws: tuple = ()
    sizes: tuple = ()
    counts: np.ndarray | None = None
    force: np.ndarray | None = None
    bound: tuple | None = None


def _cross_entropy(law, c, counts, force, *, pilot, margin, hit, scores, give_up,
                   floor=0.0, cap=math.inf):  # fmt: skip
    """Chain ``c``'s tilt from its stage 0 (summits per bin, scores) by the multilevel
    cross-entropy method, every stage's pads reused in every fit (module docstring); it stops
    where its previous level's interval shows the event below ``floor`` (the floor)."""
    laws, sizes, new = [None], [len(force)], force
    fitted, previous, stage, evaluations = Tilt((1.0,) * BINS), -math.inf, 0, 0
    bound = None
    while True:
        elite_size = math.ceil(RHO * new.size)
        reached = int(np.count_nonzero(hit(new))) >= elite_size
        if reached:
            elite = hit(force)
        else:
            if floor > 0 and stage > 0:  # the event lies within the previous level
                y = (margin(force) >= previous) * law.weight(laws, sizes, counts)
                bound = weighted_estimate(y, sizes[0])
                if bound[3] < floor and effective_sample_size(*bound[:2]) >= MIN_ESS:
                    break
                bound = None
            level = np.sort(margin(new))[-elite_size]
            # stalled, or too slow to reach F_r in the stages left at its latest pace
            # (Rubinstein & Kroese 2004, ch. 3: a level that stops rising ends the method)
            if give_up and (level <= previous or -level > (level - previous) * (STAGES - stage)):
                break
            previous, elite = level, margin(force) >= level
        weights = law.weight(laws, sizes, counts[elite])
        fitted = fit(law, fitted, counts[elite], weights, cap)
        if reached or stage == STAGES:
            break
        stage += 1
        more, new = _stage(law, fitted, pilot, (c, stage), scores)
        laws.append(fitted), sizes.append(pilot)
        counts, force = np.vstack([counts, more]), np.concatenate([force, new])
        evaluations += pilot
    return _Chain(fitted, stage, evaluations, reached, tuple(laws), tuple(sizes), counts, force,
                  bound)  # fmt: skip


def importance_p_stick(spec, restoring_force: float, *, turn: float, preload: float | None = None,
                       pads: int, pilot: int, event: str = "stick", start=None,
                       workers: int | PadPool = 1, score=None, give_up: bool = False,
                       floor: float = 0.0) -> TailEstimate:  # fmt: skip
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
        Final pads (≥ 2), from the nominal law, the half-way tilt and the last tilt
        (:func:`mixture`).
    pilot : int
        Pads per cross-entropy stage (≥ 1/:data:`RHO`).
    event : {"stick", "release"}
        The rare side to sample: sticking, or not sticking (p̂ = 1 − its probability).
    start : tuple of (list of ndarray, ndarray), optional
        Stage 0 already evaluated on the nominal law, e.g. the plain pads: each pad's summit
        heights above :func:`cut` (σ) and its pull-off (N); else stage 0 draws ``pilot`` pads.
    workers : int or PadPool
        Worker processes evaluating each stage's pads, in contiguous chunks (one pool for the
        whole call, :class:`~mcsim.studies.padpool.PadPool`; the result does not depend on
        it); 1: every pad in this process, no pool started; or a caller's open pool, shared.
    score : callable, optional
        What is compared with ``restoring_force``, as a function of a pad's summit heights
        above s_min (σ); default its pull-off (:func:`pad_pull_off`). Another score gives
        the probability of another event of the same pads (the tests' exact cases); a
        ``preload`` then only marks the event as one of force-controlled pads (the tall way
        in, module docstring). With ``workers`` > 1 it runs on the worker processes where
        they can call it (it pickles, and is not defined in ``__main__``:
        :func:`~mcsim.studies.padpool.portable`), else, a lambda, a closure, a script's or
        a notebook's function, on as many threads of this process, as it always could.
    give_up : bool
        Stop the stages where their level (the elite's margin to F_r) does not rise from one
        stage to the next, or rises too slowly to reach F_r in the stages left at its latest
        pace, and draw no final pads where the first chain's stages did not reach the
        event (the next chain is then not run): then p_stick is NaN and the effective
        sample size 0 (the automatic switch's way out where F_r lies far beyond any pad:
        without it, every such point of a sweep spends all the stages and the final pads to
        find no pad in the event). A later chain that
        stalls ends its own stages only: the first one found a way into the event, and the
        later one, kept off that way under force control, found no other; its last tilt
        joins the mixture as it is (any law does, the defensive part bounds the weights).
    floor : float
        Resolve P(event) only down to it: a chain stops where its previous level's interval
        shows the event below ``floor``, and where every chain does the estimate is that
        bound (``bounded``; module docstring). 0: always to the estimate.

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
    if pads < 4 * CHAINS or pilot * RHO < 1:
        raise ParameterError(f"pads = {pads!r}, pilot = {pilot!r}: importance sampling needs "
                             f"pads >= {4 * CHAINS} and pilot >= {math.ceil(1 / RHO)}")  # fmt: skip
    if score is None:
        score = functools.partial(pad_pull_off, spec, turn=turn, preload=preload)
    with opened(workers) as pool:
        return _sample(Law(spec, cut(spec, turn)), float(restoring_force), turn=turn,
                       preload=preload, pads=pads, pilot=pilot, event=event, start=start,
                       scores=_scorer(score, pool), give_up=give_up, floor=floor)  # fmt: skip


def _sample(law: Law, fr: float, *, turn: float, preload: float | None, pads: int, pilot: int,
            event: str, start, scores, give_up: bool, floor: float) -> TailEstimate:  # fmt: skip
    """:func:`importance_p_stick` of ``law``'s pads, scored by ``scores`` (:func:`_scorer`)."""
    sign = 1.0 if event == "stick" else -1.0

    def hit(force):  # the event: sticking, or its complement
        return (force > fr) if event == "stick" else ~(force > fr)

    def margin(force):  # how far into the event
        return sign * (force - fr)

    if start is not None:  # the given pads, dealt to the chains in turn
        given = law.bins(start[0]), np.asarray(start[1], dtype=float)

    def zero(c):  # chain c's stage 0: its own pads from the nominal law, or its share
        if start is None:
            return _stage(law, None, pilot, (c, 0), scores)
        return given[0][c::CHAINS], given[1][c::CHAINS]

    options = dict(pilot=pilot, margin=margin, hit=hit, scores=scores, give_up=give_up,
                   floor=floor)  # fmt: skip
    chains = []
    for c in range(CHAINS):
        # the second chain may not raise the summits above the turn where the first one
        # raised them into a sticking (module docstring: the tall way in)
        cap = math.inf
        if c and event == "stick" and preload is not None:
            above = (law.edges[:-1] >= turn) & (np.asarray(chains[0].tilt.ratio) > 1)
            cap = np.where(above, 1.0, math.inf)
        chains.append(_cross_entropy(law, c, *zero(c), **options, cap=cap))
        stalled = give_up and not chains[0].reached and chains[0].bound is None
        if stalled:
            break  # the first chain cannot reach the event: no estimate
    evaluations = sum(c.evaluations for c in chains) + (len(chains) * pilot if start is None else 0)
    tilts, stages = tuple(c.tilt for c in chains), max(c.stages for c in chains)
    reached = len(chains) == CHAINS and all(c.reached for c in chains)
    if all(c.bound is not None for c in chains):  # every chain shows the event below the floor
        high = max(c.bound[3] for c in chains)
        p, low, high = (0.0, 0.0, high) if event == "stick" else (1.0, 1.0 - high, 1.0)
        return TailEstimate(p, max(c.bound[1] for c in chains), low, high,
                            min(effective_sample_size(*c.bound[:2]) for c in chains), 0, 0,
                            evaluations, stages, False, event, tilts, law.cut, True,
                            tuple((c.bound[0], *c.bound[2:]) for c in chains), bounded=True)  # fmt: skip
    if stalled:
        return TailEstimate(math.nan, math.nan, 0.0, 1.0, 0.0, 0, 0, evaluations, stages, False,
                            event, tilts, law.cut, True)  # fmt: skip
    sizes = mixture(pads)
    laws = (None, *(q for t in tilts for q in (half(t), t)))
    parts = [_stage(law, q, n, (CHAINS, j), scores)
             for j, (q, n) in enumerate(zip(laws, sizes, strict=True))]  # fmt: skip
    evaluations += pads

    def pooled(final: list, mine: list) -> tuple:
        """Every pad of the final parts ``final`` (indices into ``parts``; the nominal one
        first) and of the stages of ``mine`` (chains): its weight w·1{event} by the
        deterministic mixture, its summits per bin, and how many are nominal."""
        nominal = [parts[final[0]]] + [(c.counts[: c.sizes[0]], c.force[: c.sizes[0]])
                                       for c in mine]  # fmt: skip
        drawn = nominal + [parts[j] for j in final[1:]]
        drawn += [(c.counts[c.sizes[0] :], c.force[c.sizes[0] :]) for c in mine]
        q_all = [None] * len(nominal) + [laws[j] for j in final[1:]]
        q_all += [q for c in mine for q in c.laws[1:]]
        n_all = [len(part[1]) for part in drawn[: len(nominal)]] + [sizes[j] for j in final[1:]]
        n_all += [n for c in mine for n in c.sizes[1:]]
        counts = np.vstack([part[0] for part in drawn])
        y = hit(np.concatenate([part[1] for part in drawn])) * law.weight(q_all, n_all, counts)
        return y, counts, sum(n_all[: len(nominal)])

    def recycled(final: list, mine: list) -> tuple:
        """The deterministic mixture's estimate from ``final`` and ``mine`` (:func:`pooled`):
        p̂, se, low, high, hits."""
        y, _, n0 = pooled(final, mine)
        return (*weighted_estimate(y, n0), int(np.count_nonzero(y)))

    # the pooled tilt: fitted to every pad in the event so far, both chains' and the final
    # ones, each weighted by the mixture of every law drawn (module docstring)
    y, counts, _ = pooled(list(range(len(laws))), chains)
    if np.any(y > 0):
        refit = fit(law, Tilt((1.0,) * BINS), counts[y > 0], y[y > 0], smoothing=1.0)
        n = math.ceil(FITTED * pads)
        parts.append(_stage(law, refit, n, (CHAINS, len(laws)), scores))
        laws, sizes, evaluations = (*laws, refit), (*sizes, n), evaluations + n

    q, se, low, high, hits = recycled(list(range(len(parts))), chains)
    # each chain's own estimate from its stages, its tilts' final pads and its share of the
    # nominal ones (independent of the other chain's): they agree within AGREE standard
    # errors unless the tilts found different ways into the event
    own = []
    for c in range(CHAINS):
        share = slice(c * sizes[0] // CHAINS, (c + 1) * sizes[0] // CHAINS)
        parts.append((parts[0][0][share], parts[0][1][share]))
        own.append(recycled([len(parts) - 1, 1 + 2 * c, 2 + 2 * c], [chains[c]]))
    chain = tuple((o[0], o[2], o[3]) for o in own)
    (qa, sa, *_), (qb, sb, *_) = own
    resolved = min(effective_sample_size(o[0], o[1]) for o in own) >= CONFIRM
    agree = resolved and abs(qa - qb) <= AGREE * math.hypot(sa, sb)
    ess = effective_sample_size(q, se)
    if event == "release":
        q, low, high = 1.0 - q, 1.0 - high, 1.0 - low
    return TailEstimate(min(max(q, 0.0), 1.0), se, max(low, 0.0), min(high, 1.0), ess,
                        hits, pads, evaluations, stages, reached, event,
                        tilts, law.cut, agree, chain)  # fmt: skip


def mixture(pads: int) -> tuple[int, ...]:
    """Final pads from the nominal law, then from each chain's half-way tilt and its tilt
    (module docstring)."""
    n0 = math.ceil(DEFENSIVE * pads)
    n1 = math.ceil(HALF_WAY * pads / CHAINS)
    n2 = (pads - n0 - CHAINS * n1) // CHAINS
    out = [n0, *(n1, n2) * CHAINS]
    out[-1] += pads - sum(out)
    return tuple(out)

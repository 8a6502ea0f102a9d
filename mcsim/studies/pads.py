"""Stiction statistics of finite pads: the spread of pull-off force from pad to pad.

A contact pad of area A holds N ~ ηA summits (tens to thousands for 1–100 µm²), so its
pull-off force varies from device to device. Given the pull-off force of each of n
pads (one realization of a ``--cycle`` Monte Carlo run each, :meth:`mcsim.store.results.Run.pull_off`),
:func:`pad_statistics` reports

* the mean and its standard error s/√n, the sample standard deviation s (ddof = 1);
* the 5 %, 50 % and 95 % quantiles (linear interpolation between order statistics,
  NumPy's default ``method="linear"``, Hyndman & Fan 1996 type 7);
* with a restoring force F_r (a spring pulling the pad off), the probability that a
  pad sticks, p = P(pull-off > F_r), estimated by k/n, with a 95 % interval: by
  default the **Clopper–Pearson** exact interval (Clopper & Pearson 1934): the α/2
  and 1 − α/2 quantiles of Beta(k, n − k + 1) and Beta(k + 1, n − k), with 0 and 1 at
  k = 0 and k = n. It is the default because its coverage is never below 95 % for
  any p and n, which matters in the tails where stiction probabilities of interest
  lie (a few sticking pads out of hundreds). On request the **Wilson** score interval
  (Wilson 1927, :func:`wilson`): shorter, with coverage close to 95 % on average but
  below it for some p and n.

:func:`analytic_pad_pull_off` gives the GW prediction of the mean for comparison:
the analytic pull-off per nominal area (:func:`mcsim.physics.adhesion.adhesion_summary`,
force/(A K)) times K A. It is the most tensile value of the *mean* retraction load,
located to 1e-7 in h; a pad's pull-off is the most tensile value of its *own* load
curve, also in continuous h (its summits drawn again from the run's seed,
:mod:`mcsim.engine.pads.curves`), whatever the run's grid. The two differ: the minimum of
a noisy curve lies below the minimum of its mean (E[max] ≥ max E, so small pads pull
off harder on average than the analytic value, by a relative amount of order N^(-1/2)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mcsim.engine import interrupt
from mcsim.model.errors import ParameterError
from mcsim.studies.intervals import INTERVALS, clopper_pearson, wilson
from mcsim.studies.padpool import PadPool, chunks, opened
from mcsim.studies.rareevent import rare_event

#: Quantiles reported, as fractions.
QUANTILES = (0.05, 0.5, 0.95)


@dataclass(frozen=True)
class PadStatistics:
    """Per-pad pull-off statistics (forces in N).

    Attributes
    ----------
    pads : int
        Number of pads n.
    mean, se, std : float
        Sample mean, its standard error std/√n and the standard deviation (ddof = 1;
        NaN for one pad).
    q05, q50, q95 : float
        5 %, 50 % and 95 % quantiles.
    restoring_force : float or None
        F_r, N.
    p_stick : float or None
        Fraction of pads whose pull-off exceeds F_r.
    p_stick_ci : tuple of float or None
        95 % interval of the probability of sticking.
    interval : str
        Its kind, one of :data:`INTERVALS`.
    """

    pads: int
    mean: float
    se: float
    std: float
    q05: float
    q50: float
    q95: float
    restoring_force: float | None = None
    p_stick: float | None = None
    p_stick_ci: tuple[float, float] | None = None
    interval: str = "clopper-pearson"

    def to_dict(self) -> dict:
        """Keys ``pads, mean, se, std, q05, q50, q95`` and, with F_r, ``p_stick, p_stick_ci``."""
        out = {k: getattr(self, k) for k in ("pads", "mean", "se", "std", "q05", "q50", "q95")}
        if self.restoring_force is not None:
            out |= {"p_stick": self.p_stick, "p_stick_ci": list(self.p_stick_ci)}
        return out


def pad_statistics(
    force, restoring_force: float | None = None, interval: str = "clopper-pearson"
) -> PadStatistics:
    """Statistics of per-pad pull-off forces (module docstring).

    Parameters
    ----------
    force : array_like, shape (n,)
        Pull-off force of each pad (a magnitude, N), n ≥ 1, finite and ≥ 0.
    restoring_force : float, optional
        F_r (N, ≥ 0): a pad sticks when its pull-off exceeds it.
    interval : {"clopper-pearson", "wilson"}
        Interval of the probability of sticking (:func:`clopper_pearson`, :func:`wilson`).

    Returns
    -------
    PadStatistics

    Raises
    ------
    ParameterError
        An empty, non-finite or negative force, a negative or non-finite F_r, or an
        unknown interval.
    """
    if interval not in INTERVALS:
        raise ParameterError(f"interval = {interval!r}: allowed {', '.join(INTERVALS)}")
    f = np.asarray(force, dtype=float).ravel()
    if f.size == 0:
        raise ParameterError("pull-off forces: no pads (need at least one)")
    if not np.all(np.isfinite(f)) or np.any(f < 0):
        raise ParameterError("pull-off forces: must be finite and >= 0 (magnitudes, N)")
    n = f.size
    std = float(np.std(f, ddof=1)) if n > 1 else math.nan
    q = np.quantile(f, QUANTILES)
    stick = {}
    if restoring_force is not None:
        from mcsim.model.params import check_range

        # a number (N) or a string with its unit ("300 uN"), as the command line takes it
        fr = check_range("restoring_force", restoring_force, "N", low=0, low_open=False)
        k = int(np.count_nonzero(f > fr))
        ci = (wilson if interval == "wilson" else clopper_pearson)(k, n)
        stick = {"restoring_force": fr, "p_stick": k / n, "p_stick_ci": ci}
    return PadStatistics(pads=n, mean=float(np.mean(f)), se=std / math.sqrt(n), std=std,
                         q05=float(q[0]), q50=float(q[1]), q95=float(q[2]), interval=interval, **stick)  # fmt: skip


def analytic_pad_pull_off(spec, turn: float | None = None, summary=None) -> float:
    """GW mean pull-off of one pad of a cycle run's inputs, N (see the module docstring).

    The analytic pull-off force/(A K) after the closest approach ``turn`` (d/σ; default the
    run's, ``spec.turn``; under a preload its mean-field turn) times A K, times round(ηA)/(ηA) for a fixed summit count. The minimum of the mean
    curve (continuous in h), not the mean of the per-pad minima on the run's grid.
    ``summary``: that :func:`~mcsim.physics.adhesion.adhesion_summary` (of the spec's surface,
    material, law set and environment at ``turn``) where the caller has it already.
    """
    import warnings

    from mcsim.physics.adhesion import RegimeWarning, adhesion_summary

    s = summary
    if s is None:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RegimeWarning)
            s = adhesion_summary(spec.surface, spec.material, spec.law,
                                 turn=spec.turn if turn is None else turn,
                                 environment=spec.environment)  # fmt: skip
    bias = spec.expected_summits / (spec.surface.eta * spec.area)
    return s.pull_off * spec.material.K * spec.area * bias


def moment_std(run) -> float:
    """Across-pad standard deviation of pull-off predicted from the summit-level moments, N.

    To first order a pad's pull-off is minus its total load at the row h* of the
    retraction branch where the ensemble's mean load is most tensile; the variance of a
    sum over summits is ηA E[x²] for a Poisson count and N Var(x) for a fixed one
    (:mod:`mcsim.engine.statistics`), estimated by the mean over pads of Σx² (fixed:
    Σx² − (Σx)²/N). Valid when many summits carry the pull-off (≳ 100); NaN when the
    mean load is never tensile.
    """
    from mcsim.engine.kernels import sum_columns

    spec = run.spec
    if not spec.cycle or "load" not in spec.law_set.names:
        raise ParameterError(f"moment_std needs a cycle run of a law set with a load; law = "
                             f"{spec.law!r}, cycle = {spec.cycle}")  # fmt: skip
    cols = sum_columns(spec.law_set)
    retract = run.sums[:, spec.h.size :, :]
    first, second = retract[..., cols.index("load")], retract[..., cols.index("loadload")]
    if spec.count == "fixed":
        second = second - first**2 / run.n_summits[:, None]
    j = int(np.argmin(first.mean(axis=0)))
    return float(np.sqrt(second[:, j].mean())) if first[:, j].mean() < 0 else math.nan


#: Expected contacting summits per pad below which the Monte Carlo alone decides (docs/physics.md,
#: section 'Finite pads': the pad is then decided by its tallest summits).
FEW_CONTACTS = 10


#: Fewest plain pads that :func:`finite_pads` evaluates on worker processes: fewer take less
#: time than the workers' start (about 1 CPU s each: their imports and compiled kernels,
#: against 1.5–2 ms a pad).
PROCESS_PADS = 1000


def finite_pads(spec, restoring_force: float | None, *, preload: float | None = None, turn: float,
                h_pull_off: float, tail: bool | None = None, friction: bool = False,
                tangential_force: float | None = None, floor: float = 0.0,
                workers: int = 1, summary=None) -> dict:  # fmt: skip
    """Pull-off statistics of the ``spec.realizations`` pads of a cycle spec, as sweep variables.

    Each pad's summits are drawn from ``spec``'s seed as a ``--cycle`` run of the same spec
    draws them (:func:`mcsim.engine.pads.load.patch_heights`), so ``mcsim simulate --cycle``
    with that seed followed by ``mcsim pads`` gives the same pads.

    Parameters
    ----------
    spec : MonteCarloSpec
        A cycle spec: its realizations are the pads, its lowest separation bounds the turns.
    restoring_force : float or None
        F_r, N: a pad sticks when its pull-off exceeds it (None: no p_stick, with ``friction``).
    preload : float, optional
        Nominal pressure P, Pa: each pad turns under force control where its own approach
        load reaches P·A (:func:`mcsim.engine.pads.curves.force_turn`). Without it every pad
        turns at ``turn``.
    turn : float
        The mean-field turn d/σ (under a preload, the one that balances P on the mean
        curve); the analytic mean and the contacting summits are evaluated there.
    h_pull_off : float
        Separation d/σ of the mean curve's pull-off after ``turn`` (NaN: none), for the
        model estimate ``p_stick_model`` (:func:`mcsim.studies.stiction.p_stick_model`).
    tail : bool, optional
        p_stick (and p_slip) by importance sampling (:func:`tail_p_stick`): True always, None
        where the pads see fewer than :data:`~mcsim.studies.rareevent.SWITCH` on the rarer side, False never.
    friction : bool
        Also each pad's static friction at its turn and μ_s (:mod:`mcsim.studies.padfriction`):
        the keys of :data:`mcsim.store.sweepvariables.FRICTION`.
    tangential_force : float, optional
        F, N (implies ``friction``): also p_slip = P(T_s < F), the keys of
        :data:`~mcsim.store.sweepvariables.SLIP` and ``p_slip_method``.
    floor : float
        As for :func:`tail_p_stick` (p_stick and p_slip).
    workers : int
        Worker processes sharing one pool (:class:`~mcsim.studies.padpool.PadPool`): the
        plain pads in contiguous chunks where there are at least :data:`PROCESS_PADS`, and
        importance sampling's stages; 1: all in this process. The values do not depend on it.
    summary : AdhesionSummary, optional
        The mean curve's :func:`~mcsim.physics.adhesion.adhesion_summary` at ``turn`` (of the
        spec's surface, material, law set and environment), where the caller has it already:
        :func:`analytic_pad_pull_off` then does not compute it again.

    Returns
    -------
    dict
        The keys of :data:`mcsim.store.sweepvariables.PADS` (floats, SI) and ``p_stick_method``
        (one of :data:`~mcsim.studies.rareevent.METHODS`; those of p_stick only with a restoring force), and the
        friction's.

    Raises
    ------
    ParameterError
        A turn below the spec's lowest separation (no summit below it is drawn), or a pad
        whose approach load stays below P·A down to it.
    """
    from mcsim.engine.pads import friction as padfriction
    from mcsim.studies import padfriction as friction_study
    from mcsim.studies.stiction import p_stick_model

    if turn < spec.turn:
        raise ParameterError(f"pads turn at h = {turn:.4g}, below the lowest separation h = "
                             f"{spec.turn:g}; extend the separations (--h) down")  # fmt: skip
    friction = friction or tangential_force is not None
    if friction:
        padfriction.check_friction(spec)
    with opened(workers) as pool:
        force, work, highs, static, normal = _plain_pads(spec, pool, turn, preload, friction)
        s, out = pad_statistics(force, restoring_force), {}
        if friction:
            f = friction_study.friction_statistics(static, normal, tangential_force)
            out |= friction_study.variables(f)
            if tangential_force is not None:
                out |= friction_study.tail_p_slip(spec, f, turn=turn, preload=preload, tail=tail,
                                                  start=(highs, static), floor=floor,
                                                  workers=pool)  # fmt: skip
        if restoring_force is not None:
            out |= tail_p_stick(spec, s, restoring_force, turn=turn, preload=preload, tail=tail,
                                start=(highs, force), floor=floor, workers=pool)  # fmt: skip
    q05, q50, q95 = np.quantile(work, QUANTILES)  # signed (J/m²): not pad_statistics' forces
    if restoring_force is not None:
        model = (p_stick_model(spec, restoring_force, turn=turn, h_pull_off=h_pull_off,
                               preload=preload) if math.isfinite(h_pull_off) else 0.0)  # fmt: skip
        out["p_stick_model"] = min(max(model, 0.0), 1.0)
    lam = spec.surface.eta * spec.area
    return out | {
            "pull_off_mean": s.mean, "pull_off_std": s.std, "pull_off_q05": s.q05,
            "pull_off_q50": s.q50, "pull_off_q95": s.q95,
            "work_of_separation_mean": float(work.mean()),
            "work_of_separation_std": float(work.std(ddof=1)) if work.size > 1 else math.nan,
            "work_of_separation_q05": float(q05), "work_of_separation_q50": float(q50),
            "work_of_separation_q95": float(q95),
            "pull_off_analytic": analytic_pad_pull_off(spec, turn, summary),
            "contacting_summits": lam * float(spec.surface.heights.sf(turn))}  # fmt: skip


def _plain_pads(spec, pool: PadPool, turn: float, preload: float | None, friction: bool) -> tuple:
    """The ``spec.realizations`` plain pads of :func:`finite_pads`, in this process or, from
    :data:`PROCESS_PADS` pads, on ``pool`` in contiguous chunks joined in order
    (:func:`_pad_range`): each pad's pull-off (N), work of separation (J/m²), summits above
    the tail's cut (σ) and, with ``friction``, its static friction and normal load (N)."""
    from mcsim.studies.tail import cut

    n, s_c = spec.realizations, cut(spec, turn)
    if n < PROCESS_PADS:  # a few pads: the workers' start would take longer than they do
        parts = [_pad_range(spec, 0, n, turn, preload, s_c, friction)]
    else:
        parts = pool.map(_pad_range, [(spec, c.start, c.stop, turn, preload, s_c, friction)
                                      for c in chunks(n, pool.workers)])  # fmt: skip
    force, work, static, normal = (np.concatenate([p[k] for p in parts]) for k in (0, 1, 3, 4))
    return force, work, [h for p in parts for h in p[2]], static, normal


def _pad_range(
    spec, lo: int, hi: int, turn: float, preload: float | None, cut: float, friction: bool
) -> tuple:
    """Plain pads ``lo`` … ``hi`` − 1 of ``spec`` (:func:`_plain_pads`; the static friction
    and normal load NaN without ``friction``)."""
    from mcsim.engine.pads import curves as padcurves
    from mcsim.engine.pads import friction as padfriction
    from mcsim.engine.pads import load as padload

    sigma, n = spec.surface.sigma, hi - lo
    force, work, static, normal = np.empty(n), np.empty(n), np.full(n, np.nan), np.full(n, np.nan)
    highs = []
    for i, r in enumerate(range(lo, hi)):
        interrupt.check()  # a signal ends the pads between two, in a sweep's worker thread too
        z = padload.patch_heights(spec, r)
        d_turn = padcurves.pad_turn(spec, z, turn, preload)
        force[i] = padcurves.pull_off(spec, z, d_turn)[0]
        work[i] = padcurves.pad_work(spec, z, d_turn)
        highs.append(z[z > cut * sigma] / sigma)
        if friction:
            applied = None if preload is None else preload * spec.area
            static[i] = padfriction.static_friction(spec, z, d_turn)
            normal[i] = padfriction.normal_load(spec, z, d_turn, applied)
    return force, work, highs, static, normal


def tail_p_stick(spec, statistics: PadStatistics, restoring_force: float, *, turn: float,
                 preload: float | None, tail: bool | None, start=None, floor: float = 0.0,
                 workers: int | PadPool = 1) -> dict:  # fmt: skip
    """p_stick of the pads of ``spec``: the plain pads' fraction, or importance sampling.

    Importance sampling (:func:`mcsim.studies.tail.importance_p_stick`, max(n,
    :data:`~mcsim.studies.rareevent.TAIL_PADS`) final pads, cross-entropy stages of max(:data:`~mcsim.studies.rareevent.TAIL_PILOT`, n/10)
    pads after the n plain pads as stage 0, or its own with fewer than TAIL_PILOT) replaces the
    fraction where the plain pads see fewer than :data:`~mcsim.studies.rareevent.SWITCH` pads on the rarer side
    (``tail`` None) or always (``tail`` True), not
    with fewer than :data:`~mcsim.studies.rareevent.MIN_TAIL_PADS` pads or a fixed summit count (``tail`` None: the
    fraction stays; True: an error), nor where its effective sample size stays below
    :data:`~mcsim.studies.rareevent.MIN_ESS` or its two chains' estimates disagree (the fraction stays: it cannot tell).

    Parameters
    ----------
    spec : MonteCarloSpec
        The pads (:func:`finite_pads`).
    statistics : PadStatistics
        The plain pads' statistics, with F_r.
    restoring_force : float
        F_r, N.
    turn, preload : float
        Mean-field turn (d/σ) and the nominal pressure (Pa, or None), as :func:`finite_pads`.
    tail : bool or None
        None: automatic (importance sampling where the plain pads see fewer than
        :data:`~mcsim.studies.rareevent.SWITCH` on the rarer side); True: importance sampling; False: the plain fraction.
    start : tuple, optional
        The plain pads as stage 0: their heights above :func:`mcsim.studies.tail.cut` (σ)
        and pull-off (N); else the tail draws its own.
    floor : float
        Importance sampling resolves the probability only down to it: where its stages show
        the rarer side below ``floor`` it stops and gives that bound
        (:func:`mcsim.studies.tail.importance_p_stick`); 0: to the estimate.
    workers : int or PadPool
        Worker processes of importance sampling, or an open pool
        (:func:`mcsim.studies.tail.importance_p_stick`); 1: in this process.

    Returns
    -------
    dict
        ``p_stick``, ``p_stick_low``, ``p_stick_high`` (95 %), ``p_stick_ess`` (the effective
        number of pads on the rarer side, n*·p̂ with n* = p̂(1 − p̂)/se², the one its interval
        takes, :attr:`mcsim.studies.tail.TailEstimate.ess`; for plain pads their count) and
        ``p_stick_method`` (one of :data:`~mcsim.studies.rareevent.METHODS`).

    Raises
    ------
    ParameterError
        ``tail`` True with fewer than :data:`~mcsim.studies.rareevent.MIN_TAIL_PADS` pads or a fixed summit count.
    """
    return rare_event(spec, "p_stick", statistics.pads, statistics.p_stick,
                      statistics.p_stick_ci, restoring_force, turn=turn, preload=preload,
                      tail=tail, start=start, floor=floor, workers=workers)  # fmt: skip


@dataclass(frozen=True)
class PadReport:
    """The pads of a cycle run, as ``mcsim pads`` reports them (forces in N).

    Attributes
    ----------
    pull_off : mcsim.store.results.PullOff
        Each pad's pull-off (:meth:`mcsim.store.results.Run.pull_off`).
    statistics : PadStatistics
        Their statistics and, with a restoring force, the probability of sticking.
    analytic_mean : float
        GW mean pull-off of one pad after the mean-field turn (:func:`analytic_pad_pull_off`), N.
    contacts : float
        Expected contacting summits of a pad at the mean-field turn, ηA Φ(turn) (dimensionless):
        below :data:`FEW_CONTACTS` a pad's tallest summits decide it, and ``p_stick_model``
        is not to be trusted.
    p_stick_model : float or None
        With a restoring force: the rare-event model's probability of sticking
        (:func:`mcsim.studies.stiction.p_stick_model`; 0 where the mean curve never pulls off).
    stick : dict or None
        With a restoring force: p_stick, its interval, ``p_stick_ess`` and ``p_stick_method``
        (:func:`tail_p_stick`: the fraction of ``statistics``, or importance sampling).
    turns : dict
        Under a preload: ``preload`` (Pa), the mean-field turn ``h_turn_mean_field`` and the
        pads' own turns ``h_turn_min``, ``h_turn_q50``, ``h_turn_max`` (d/σ); else empty.
    friction : mcsim.studies.padfriction.FrictionStatistics or None
        With ``friction`` or a tangential force: the pads' static friction T_s and μ_s at their
        turns (each pad's in ``pull_off.static_friction``, ``pull_off.mu_static``) and p_slip.
    slip : dict or None
        With a tangential force: p_slip, its interval, ``p_slip_ess`` and ``p_slip_method``
        (:func:`mcsim.studies.padfriction.tail_p_slip`).
    """

    pull_off: object
    statistics: PadStatistics
    analytic_mean: float
    contacts: float
    p_stick_model: float | None
    turns: dict
    stick: dict | None = None
    friction: object = None
    slip: dict | None = None

    def quantities(self) -> dict[str, tuple[float, str]]:
        """Every reported quantity with its unit (``"N"``, ``"Pa"``, ``"1"``), in report order."""
        out = self.statistics.to_dict()
        fields = {
            k: (out[k], "1" if k == "pads" else "N")
            for k in ("pads", "mean", "se", "std", "q05", "q50", "q95")
        }
        if self.statistics.restoring_force is not None:
            s = self.stick
            fields |= {"restoring_force": (self.statistics.restoring_force, "N"),
                       "p_stick": (s["p_stick"], "1"), "p_stick_ci_low": (s["p_stick_low"], "1"),
                       "p_stick_ci_high": (s["p_stick_high"], "1"), "p_stick_model": (self.p_stick_model, "1"),
                       "p_stick_ess": (s["p_stick_ess"], "1")}  # fmt: skip
        fields["analytic_mean"] = (self.analytic_mean, "N")
        fields |= {k: (v, "Pa" if k == "preload" else "1") for k, v in self.turns.items()}
        if self.friction is not None:
            f = self.friction
            fields |= {f"static_friction_{k}": (v, "N") for k, v in f.static_friction.items()}
            fields |= {f"mu_static_{k}": (v, "1") for k, v in f.mu_static.items()}
            fields["mu_static_pads"] = (f.mu_pads, "1")
        if self.slip is not None:
            s = self.slip
            fields |= {"tangential_force": (self.friction.tangential_force, "N"),
                       "p_slip": (s["p_slip"], "1"), "p_slip_ci_low": (s["p_slip_low"], "1"),
                       "p_slip_ci_high": (s["p_slip_high"], "1"), "p_slip_ess": (s["p_slip_ess"], "1")}  # fmt: skip
        return fields


def pad_report(
    run, restoring_force: float | None = None, interval: str = "clopper-pearson",
    tail: bool | None = None, *, friction: bool = False, tangential_force: float | None = None,
    progress: bool = False, workers: int = 1,
) -> PadReport:  # fmt: skip
    """Pull-off statistics of the pads of a cycle run (one pad per realization), as ``mcsim pads``.

    Parameters
    ----------
    run : mcsim.Run
        A ``cycle`` run of a law set with a signed load (complete, or a checkpoint's
        completed pads).
    restoring_force : float, optional
        F_r, N (≥ 0): a pad sticks when its pull-off exceeds it; adds the probability of
        sticking, its interval and the model's estimate.
    interval : {"clopper-pearson", "wilson"}
        Interval of the probability of sticking (:func:`pad_statistics`).
    tail : bool, optional
        With F_r: p_stick by importance sampling (:func:`tail_p_stick`, with pads of its own
        streams of the run's seed): True always, None where the pads see fewer than
        :data:`~mcsim.studies.rareevent.SWITCH` on the rarer side, False never. The same for p_slip with F.
    friction : bool
        Also the pads' static friction T_s at their turns and μ_s
        (:mod:`mcsim.studies.padfriction`).
    tangential_force : float or str, optional
        F, N (≥ 0, finite; or with a unit; implies ``friction``): a pad slips when T_s < F;
        adds p_slip and its interval.
    progress : bool
        A progress bar over the pads on stderr (:meth:`mcsim.Run.pull_off`).
    workers : int
        Worker processes sharing one pool: the run's own pads where there are at least
        :data:`PROCESS_PADS` (:meth:`mcsim.Run.pull_off`), and importance sampling's stages
        for p_stick and p_slip (:func:`tail_p_stick`); 1: all in this process. The values do
        not depend on it.

    Returns
    -------
    PadReport

    Raises
    ------
    ParameterError
        Not a cycle run of a law set with a signed load, a bad F_r, F or interval, ``tail``
        True with too few pads, or ``friction`` for a law set without friction.
    """
    from mcsim.studies import padfriction

    if tangential_force is not None:
        tangential_force = padfriction.check_tangential_force(tangential_force)
    friction = friction or tangential_force is not None
    model = stick = fs = slip = None
    with opened(workers) as pool:
        many = run.sums.shape[0] >= PROCESS_PADS  # fewer: the workers' start would cost more
        pull_off = run.pull_off(friction=friction, progress=progress, pool=pool if many else None)
        statistics = pad_statistics(pull_off.force, restoring_force, interval)
        spec, turns, turn = run.spec, {}, None
        if pull_off.preload is not None:  # the analytic mean after the mean-field turn
            t, turn = pull_off.h_turn, run.attrs.get("preload_turn_mean_field")
            turns = {"preload": pull_off.preload, "h_turn_mean_field": turn,
                     "h_turn_min": float(np.min(t)), "h_turn_q50": float(np.median(t)),
                     "h_turn_max": float(np.max(t))}  # fmt: skip
        turn = spec.turn if turn is None else float(turn)
        contacts = spec.surface.eta * spec.area * float(spec.surface.heights.sf(turn))
        if restoring_force is not None:
            fr = statistics.restoring_force
            model = min(max(_p_stick_model(spec, fr, pull_off.preload, turn), 0.0), 1.0)
            stick = tail_p_stick(spec, statistics, fr, turn=turn, preload=pull_off.preload,
                                 tail=tail, workers=pool)  # fmt: skip
        if friction:
            fs = padfriction.friction_statistics(pull_off.static_friction, pull_off.normal_load,
                                                 tangential_force, interval)  # fmt: skip
            if tangential_force is not None:
                slip = padfriction.tail_p_slip(spec, fs, turn=turn, preload=pull_off.preload,
                                               tail=tail, workers=pool)  # fmt: skip
    return PadReport(pull_off, statistics, analytic_pad_pull_off(spec, turn), contacts, model,
                     turns, stick, fs, slip)  # fmt: skip


def _p_stick_model(spec, fr: float, preload: float | None, turn: float) -> float:
    """p_stick_model after the mean-field ``turn`` (0 where the mean curve never pulls off)."""
    import warnings

    from mcsim.physics.adhesion import RegimeWarning, adhesion_summary
    from mcsim.studies.stiction import p_stick_model

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RegimeWarning)
        h_off = adhesion_summary(
            spec.surface, spec.material, spec.law, turn=turn, environment=spec.environment
        ).h_pull_off
    if not math.isfinite(h_off):
        return 0.0
    return p_stick_model(spec, fr, turn=turn, h_pull_off=h_off, preload=preload)

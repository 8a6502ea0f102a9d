"""Which estimate answers a rare event of the pads (p_stick, p_slip): the plain fraction of
the pads with its interval, or importance sampling far in the tail
(:func:`mcsim.studies.tail.importance_p_stick`), and the rules that choose between them. Their
measurements are in validation/README.md ("Importance sampling of pads")."""

from __future__ import annotations

from mcsim.model.errors import ParameterError
from mcsim.studies.padpool import PadPool
from mcsim.studies.tail import MIN_ESS, importance_p_stick

#: Fewer pads than this on the rarer side (sticking or not) switch p_stick to importance
#: sampling by itself (``tail=None``): on the few-summit pads of issue 31 its intervals (the
#: three-part defensive mixture, 2000 final pads) held brute force in 30 of 30 runs of
#: validation/tail_benchmark.py at p ≈ 1e-2 (Clopper–Pearson 95 %: 0.88–1) and in 63 of 64
#: runs on other seeds.
SWITCH = 10
#: Fewest plain pads with which importance sampling runs: fewer than SWITCH of fewer pads on
#: one side does not say that side is rare (its own stages hold TAIL_PILOT pads).
MIN_TAIL_PADS = 100

#: Fewest final pads of importance sampling (more where more plain pads were simulated): at
#: 100 its effective sample size stays below MIN_ESS (measured: 6 to 12 in four cases); at
#: 1000 the two-part mixture's intervals held brute force in 43 of 48 runs on the few-summit
#: pads at p ≈ 1e-2, at 2000 the three-part one's in 30 of 30 (validation/README.md).
TAIL_PADS = 2000

#: Fewest pads of a cross-entropy stage (more where more plain pads were simulated): 30 elite
#: pads fit the tilt's 16 bins.
TAIL_PILOT = 300

#: How p_stick was estimated: the fraction of plain pads, or importance sampling.
METHODS = ("pads", "importance")


def rare_event(spec, name: str, n: int, p: float, ci, threshold: float, *, turn: float,
               preload: float | None, tail: bool | None, start=None, score=None,
               floor: float = 0.0, workers: int | PadPool = 1) -> dict:  # fmt: skip
    """The probability ``name`` (``p_stick``, ``p_slip``) of the pads of ``spec`` whose score
    (their pull-off, or ``score``) exceeds ``threshold``: the plain fraction ``p`` of ``n`` pads
    with its interval ``ci``, or importance sampling, by the rules of :func:`mcsim.studies.pads.tail_p_stick`,
    on ``workers`` processes or an open :class:`~mcsim.studies.padpool.PadPool`
    (:func:`~mcsim.studies.tail.importance_p_stick`).

    Returns
    -------
    dict
        ``name``, ``name_low``, ``name_high`` (95 %), ``name_ess`` and ``name_method``.
    """
    k = round(p * n)
    rare = min(k, n - k)
    plain = {name: p, f"{name}_low": ci[0], f"{name}_high": ci[1], f"{name}_ess": float(rare),
             f"{name}_method": "pads"}  # fmt: skip
    if tail is True and n < MIN_TAIL_PADS:
        raise ParameterError(f"pads = {n}: importance sampling (tail) needs at least "
                             f"{MIN_TAIL_PADS} pads")  # fmt: skip
    if tail is False or (
        tail is None and (rare >= SWITCH or n < MIN_TAIL_PADS or spec.count != "poisson")
    ):
        return plain
    estimate = importance_p_stick(spec, threshold, turn=turn, preload=preload,
                                  pads=max(n, TAIL_PADS), pilot=max(TAIL_PILOT, n // 10),
                                  start=start if n >= TAIL_PILOT else None,
                                  event="stick" if k <= n - k else "release",
                                  give_up=tail is None, score=score, floor=floor,
                                  workers=workers)  # fmt: skip
    if estimate.ess < MIN_ESS or not estimate.agree:
        return plain
    return {name: estimate.p_stick, f"{name}_low": estimate.low, f"{name}_high": estimate.high,
            f"{name}_ess": estimate.ess, f"{name}_method": "importance"}  # fmt: skip

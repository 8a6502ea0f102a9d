"""Static friction of finite pads: its statistics, and the probability that a pad slips.

See docs/physics.md, section 'Friction of pads'.

Each pad's static friction T_s at its own turn and the normal load W of its μ_s = T_s/W come
from :mod:`mcsim.engine.pads.friction`. Over n pads :func:`friction_statistics` reports, for T_s
(N) and μ_s, the mean, its standard error s/√n, the standard deviation (ddof = 1) and the
5/50/95 % quantiles (as :func:`mcsim.studies.pads.pad_statistics` does for the pull-off; μ_s
over the pads where it is defined), and with a tangential force F the probability that a pad
slips, p_slip = P(T_s < F), estimated by k/n with its 95 % Clopper–Pearson (or Wilson)
interval. Where fewer than :data:`mcsim.studies.pads.SWITCH` pads lie on the rarer side
(slipping or holding), :func:`tail_p_slip` estimates it by importance sampling
(:func:`mcsim.studies.tail.importance_p_stick` with the pad's T_s as its score: the same
tilted pads, cross-entropy stages and defensive mixture as p_stick).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from mcsim.model.errors import ParameterError
from mcsim.studies.padpool import PadPool

#: Statistics reported of T_s and of μ_s, in order.
STATISTICS = ("mean", "se", "std", "q05", "q50", "q95")


@dataclass(frozen=True)
class FrictionStatistics:
    """Static friction of n pads (forces in N).

    Attributes
    ----------
    pads : int
        Number of pads n.
    static_friction : dict
        T_s: ``mean``, ``se``, ``std``, ``q05``, ``q50``, ``q95`` (N; :data:`STATISTICS`).
    mu_static : dict
        μ_s = T_s/W over the pads where W is defined, the same keys (dimensionless; NaN where
        it is defined for none).
    mu_pads : int
        Pads whose μ_s is defined.
    tangential_force : float or None
        F, N.
    p_slip : float or None
        Fraction of pads whose T_s is below F.
    p_slip_ci : tuple of float or None
        Its 95 % interval.
    interval : str
        ``"clopper-pearson"`` or ``"wilson"``.
    """

    pads: int
    static_friction: dict
    mu_static: dict
    mu_pads: int
    tangential_force: float | None = None
    p_slip: float | None = None
    p_slip_ci: tuple[float, float] | None = None
    interval: str = "clopper-pearson"


def check_tangential_force(value, field: str = "tangential_force") -> float:
    """F (N) from a number (SI) or a quantity string ("5 uN"): finite and ≥ 0, else a
    ParameterError naming ``field``."""
    from mcsim.model.params import check_range

    return check_range(field, value, "N", low=0, low_open=False)


def _summary(x: np.ndarray) -> dict:
    """:data:`STATISTICS` of the finite values of ``x`` (NaN where there are none)."""
    x = x[np.isfinite(x)]
    if x.size == 0:
        return dict.fromkeys(STATISTICS, math.nan)
    std = float(np.std(x, ddof=1)) if x.size > 1 else math.nan
    q = np.quantile(x, (0.05, 0.5, 0.95))
    return {"mean": float(np.mean(x)), "se": std / math.sqrt(x.size), "std": std,
            "q05": float(q[0]), "q50": float(q[1]), "q95": float(q[2])}  # fmt: skip


def friction_statistics(static_friction, normal_load, tangential_force=None,
                        interval: str = "clopper-pearson") -> FrictionStatistics:  # fmt: skip
    """Statistics of the pads' static friction and μ_s, and p_slip with a tangential force.

    Parameters
    ----------
    static_friction : array_like, shape (n,)
        T_s of each pad, N (finite, ≥ 0).
    normal_load : array_like, shape (n,)
        W of each pad, N (NaN where undefined: its μ_s is left out).
    tangential_force : float or str, optional
        F (N, ≥ 0, finite; or with a unit): a pad slips when T_s < F.
    interval : {"clopper-pearson", "wilson"}
        Interval of p_slip.

    Raises
    ------
    ParameterError
        No pads, a non-finite or negative T_s, a bad F or interval.
    """
    from mcsim.studies.intervals import INTERVALS, clopper_pearson, wilson

    if interval not in INTERVALS:
        raise ParameterError(f"interval = {interval!r}: allowed {', '.join(INTERVALS)}")
    t = np.asarray(static_friction, dtype=float).ravel()
    w = np.asarray(normal_load, dtype=float).ravel()
    if t.size == 0 or t.shape != w.shape:
        raise ParameterError("static friction: no pads, or not one normal load per pad")
    if not np.all(np.isfinite(t)) or np.any(t < 0):
        raise ParameterError("static friction: must be finite and >= 0 (N)")
    with np.errstate(invalid="ignore", divide="ignore"):
        mu = np.where(w > 0, t / w, np.nan)
    slip = {}
    if tangential_force is not None:
        f = check_tangential_force(tangential_force)
        k = int(np.count_nonzero(t < f))
        ci = (wilson if interval == "wilson" else clopper_pearson)(k, t.size)
        slip = {"tangential_force": f, "p_slip": k / t.size, "p_slip_ci": ci}
    return FrictionStatistics(t.size, _summary(t), _summary(mu), int(np.count_nonzero(np.isfinite(mu))),
                              interval=interval, **slip)  # fmt: skip


def variables(statistics: FrictionStatistics) -> dict:
    """The sweep variables of :data:`mcsim.store.sweepvariables.FRICTION` (no ``_se``)."""
    keep = [k for k in STATISTICS if k != "se"]
    return ({f"static_friction_{k}": statistics.static_friction[k] for k in keep}
            | {f"mu_static_{k}": statistics.mu_static[k] for k in keep})  # fmt: skip


def pad_static_friction(spec, s: np.ndarray, *, turn: float, preload: float | None) -> float:
    """One pad's T_s (N) from its summit heights ``s`` (σ), at its turn as plain pads take it:
    under a ``preload`` (Pa) its own (:func:`mcsim.engine.pads.curves.force_turn`), else ``turn``
    (d/σ)."""
    from mcsim.engine.pads import curves as padcurves
    from mcsim.engine.pads import friction as padfriction

    z = s * spec.surface.sigma
    return padfriction.static_friction(spec, z, padcurves.pad_turn(spec, z, turn, preload))


def _slip_score(spec, s: np.ndarray, *, turn: float, preload: float | None) -> float:
    """−T_s (N) of one pad (:func:`pad_static_friction`): a pad slips when it exceeds −F."""
    return -pad_static_friction(spec, s, turn=turn, preload=preload)


def tail_p_slip(spec, statistics: FrictionStatistics, *, turn: float, preload: float | None,
                tail: bool | None, start=None, floor: float = 0.0,
                workers: int | PadPool = 1) -> dict:  # fmt: skip
    """p_slip of the pads of ``spec``: the plain pads' fraction, or importance sampling.

    As :func:`mcsim.studies.pads.tail_p_stick` for p_stick, with T_s in place of the
    pull-off: a pad slips when its score −T_s exceeds −F, so that
    :func:`mcsim.studies.tail.importance_p_stick` samples slipping pads (``event`` "stick")
    where slipping is rare and holding ones ("release") where holding is.

    Parameters
    ----------
    spec : MonteCarloSpec
        The pads.
    statistics : FrictionStatistics
        The plain pads' statistics, with F.
    turn, preload : float
        Mean-field turn (d/σ) and the nominal pressure (Pa, or None).
    tail : bool or None
        None: importance sampling where the plain pads see fewer than SWITCH on the rarer
        side; True: always; False: never.
    start : tuple, optional
        The plain pads as stage 0: their heights above :func:`mcsim.studies.tail.cut` (σ)
        and T_s (N).
    floor : float
        As for :func:`mcsim.studies.pads.tail_p_stick`.
    workers : int or PadPool
        As for :func:`mcsim.studies.pads.tail_p_stick` (the score runs on its processes).

    Returns
    -------
    dict
        ``p_slip``, ``p_slip_low``, ``p_slip_high`` (95 %), ``p_slip_ess`` and
        ``p_slip_method`` (``pads`` or ``importance``).

    Raises
    ------
    ParameterError
        ``tail`` True with fewer than MIN_TAIL_PADS pads or a fixed summit count.
    """
    from mcsim.studies.rareevent import rare_event

    score = functools.partial(_slip_score, spec, turn=turn, preload=preload)
    if start is not None:
        start = (start[0], -np.asarray(start[1]))
    return rare_event(spec, "p_slip", statistics.pads, statistics.p_slip,
                      statistics.p_slip_ci, -statistics.tangential_force, turn=turn,
                      preload=preload, tail=tail, start=start, score=score,
                      floor=floor, workers=workers)  # fmt: skip

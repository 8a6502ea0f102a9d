"""Estimates and standard errors of the Monte Carlo curves, and the comparison with GW.

Per realization r (a patch of area A with N_r summits) the dimensionless totals are
X̄_r = ΣX/(A K) for X ∈ {P, F, T} (as Eqs. 3, 5, 7) and the ratios N_c/N (Eq. 1) and
μ = ΣT/(ΣP + ΣF) (Eq. 8). The ensemble estimates are

* P, F, T: the mean over realizations;
* contact_fraction and μ: pooled ratios over all realizations, ΣN_c/ΣN and
  ΣT/(ΣP + ΣF), which estimate the analytic N_c/N and μ without the O(1/N) bias of a
  mean of per-patch ratios.

Standard errors use the summit-level second moments, since every total is a sum of
i.i.d. per-summit terms (non-contacting summits add zero):

* Poisson N: Var(ΣX) = ηA E[x²], estimated by Σx²; fixed N: N Var(x), estimated by
  Σx² − (ΣX)²/N;
* N_c/N given N: binomial, p(1 − p)/ΣN;
* μ: delta method, SE² = Σ(t − μ̂ s)²/(Σs)² with s = p + f, the same for fixed and
  Poisson N (PHYSICS.md).

These have the number of contacting summits as degrees of freedom, so z-scores are
close to normal even with few realizations. The spread across realizations
(``std``, ``se_between``) is reported too. Where the expected number of contacting
summits in the whole ensemble is below :data:`MIN_CONTACTS`, z is not reported: the
sums are then too skewed for a normal approximation.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .analytic import QUANTITIES, AnalyticCurves
from .kernels import SUM_COLUMNS
from .montecarlo import EnsembleSums

#: Expected contacting summits (whole ensemble) below which no z-score is given.
MIN_CONTACTS = 100

_COL = {name: i for i, name in enumerate(SUM_COLUMNS)}


def per_realization(ens: EnsembleSums) -> dict[str, np.ndarray]:
    """Dimensionless curves of each realization, arrays of shape (R, M).

    μ is NaN where a patch has no contact (P + F = 0): undefined, not zero.
    """
    scale = ens.spec.area * ens.spec.material.K
    s = ens.sums
    with np.errstate(invalid="ignore", divide="ignore"):
        cf = s[..., _COL["n_contact"]] / ens.n_summits[:, None]
        load = s[..., _COL["P"]] + s[..., _COL["F"]]
        mu = np.where(load > 0, s[..., _COL["T"]] / load, np.nan)
    return {
        "contact_fraction": cf,
        "P": s[..., _COL["P"]] / scale,
        "F": s[..., _COL["F"]] / scale,
        "T": s[..., _COL["T"]] / scale,
        "mu": mu,
    }


@dataclass(frozen=True)
class Summary:
    """Ensemble estimates per quantity (keys of :data:`mcsim.analytic.QUANTITIES`).

    Attributes
    ----------
    mean : dict of ndarray
        Estimate per separation (see the module docstring).
    se : dict of ndarray
        Standard error from the summit-level moments.
    std : dict of ndarray
        Standard deviation across realizations (NaN for one realization).
    se_between : dict of ndarray
        ``std/√R``, the across-realization standard error.
    expected_contacts : ndarray
        Expected contacting summits over the whole ensemble, R·E[N]·S(h).
    """

    mean: dict[str, np.ndarray]
    se: dict[str, np.ndarray]
    std: dict[str, np.ndarray]
    se_between: dict[str, np.ndarray]
    expected_contacts: np.ndarray


def force_estimate(
    spec, n_summits: np.ndarray, sums: np.ndarray, weights
) -> tuple[np.ndarray, np.ndarray]:
    """Mean over realizations of (a P + b F + c T)/(A K) and its summit-level standard error.

    ``weights`` = (a, b, c); e.g. (1, 1, 0) gives the total force of Fig. 4. The
    variance of one patch is Σx² (Poisson N) or Σx² − (Σx)²/N (fixed N) with
    x = a p + b f + c t per summit, from the moment columns of ``sums``.
    """
    a, b, c = weights
    col = {k: sums[..., i] for k, i in _COL.items()}
    total = a * col["P"] + b * col["F"] + c * col["T"]
    square = (a * a * col["PP"] + b * b * col["FF"] + c * c * col["TT"]
              + 2 * (a * b * col["PF"] + a * c * col["PT"] + b * c * col["FT"]))  # fmt: skip
    if spec.count == "fixed":
        square = square - total**2 / n_summits[:, None]
    R = total.shape[0]
    scale = R * spec.area * spec.material.K
    return total.sum(axis=0) / scale, np.sqrt(np.maximum(square.sum(axis=0), 0.0)) / scale


def summarize(ens: EnsembleSums) -> Summary:
    """Estimates and standard errors of a run (formulas in the module docstring)."""
    spec = ens.spec
    R = spec.realizations
    tot = ens.sums.sum(axis=0)  # (M, 10), pooled over realizations
    c = {k: tot[:, i] for k, i in _COL.items()}
    n_total = float(ens.n_summits.sum())
    mean, se = {}, {}
    with np.errstate(invalid="ignore", divide="ignore"):
        p = c["n_contact"] / n_total
        mean["contact_fraction"] = p
        se["contact_fraction"] = np.sqrt(p * (1 - p) / n_total)
        for q, weights in (("P", (1, 0, 0)), ("F", (0, 1, 0)), ("T", (0, 0, 1))):
            mean[q], se[q] = force_estimate(ens.spec, ens.n_summits, ens.sums, weights)
        s = c["P"] + c["F"]
        mu = np.where(s > 0, c["T"] / s, np.nan)
        ss = c["PP"] + 2 * c["PF"] + c["FF"]
        ts = c["PT"] + c["FT"]
        var = np.maximum(c["TT"] - 2 * mu * ts + mu**2 * ss, 0.0)
        mean["mu"] = mu
        se["mu"] = np.where(s > 0, np.sqrt(var) / s, np.nan)
    per = per_realization(ens)
    with warnings.catch_warnings():  # μ of a patch without contact is NaN and skipped
        warnings.simplefilter("ignore", RuntimeWarning)
        std = {q: np.nanstd(v, axis=0, ddof=1) for q, v in per.items()}
    se_between = {q: v / np.sqrt(R) for q, v in std.items()}
    expected = R * spec.expected_summits * np.asarray(spec.surface.heights.sf(spec.h))
    return Summary(mean, se, std, se_between, expected)


def expected_values(spec, curves: AnalyticCurves) -> dict[str, np.ndarray]:
    """What the estimators of :func:`summarize` converge to.

    The analytic curves are per unit of η·A; a fixed count N = round(ηA) scales the
    totals by round(ηA)/(ηA).
    """
    bias = spec.expected_summits / (spec.surface.eta * spec.area)
    return {q: getattr(curves, q) * (bias if q in ("P", "F", "T") else 1.0) for q in QUANTITIES}


def compare_table(summary: Summary, expected: dict[str, np.ndarray], h: np.ndarray) -> list[dict]:
    """Rows ``h, quantity, mc_mean, mc_se, analytic, z, note`` for every h and quantity.

    z = (mc − analytic)/se; NaN, with a note, where the expected number of contacts
    is below :data:`MIN_CONTACTS` or the estimate is undefined.
    """
    rows = []
    for j, hj in enumerate(h):
        few = summary.expected_contacts[j] < MIN_CONTACTS
        for q in QUANTITIES:
            m, e, a = summary.mean[q][j], summary.se[q][j], expected[q][j]
            note = ""
            if few:
                note = f"few contacts (expected {summary.expected_contacts[j]:.3g} < {MIN_CONTACTS}): no normal approximation"
            elif not np.isfinite(m):
                note = "undefined: no contact in the ensemble"
            elif e == 0:
                note = "zero standard error"
            z = (m - a) / e if not note else np.nan
            rows.append({"h": float(hj), "quantity": q, "mc_mean": float(m), "mc_se": float(e),
                         "analytic": float(a), "z": float(z), "note": note})  # fmt: skip
    return rows

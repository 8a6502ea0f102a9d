"""Estimates and standard errors of the Monte Carlo curves, and the comparison with GW.

See docs/physics.md, section 'Monte Carlo statistics'.

Per realization r (a patch of area A with N_r summits) the dimensionless totals are
X̄_r = ΣX/(A K) for every force output X of the law set (the seed: P, F, T, as Eqs.
3, 5, 7; the new sets: the signed ``load``), ΣX/A for an area output (A_r/A_n), and
the ratios N_c/N (Eq. 1) and μ. The seed's μ is ΣT/(ΣP + ΣF) (Eq. 8), undefined (NaN)
without adhesion (w = 0: its friction T is adhesional, Eq. 6, and 0); a law set
with Bowden–Tabor friction (``law.friction``, material τ given) reports
``friction`` = τ·Σarea/(A K) and μ = friction/load, defined only where the load is
compressive (> 0). The ensemble estimates are

* totals: the mean over realizations;
* contact_fraction and μ: pooled ratios over all realizations, ΣN_c/ΣN and
  Σt/Σs, which estimate the analytic N_c/N and μ without the O(1/N) bias of a
  mean of per-patch ratios.

Standard errors use the summit-level second moments, since every total is a sum of
i.i.d. per-summit terms (non-contacting summits add zero):

* Poisson N: Var(ΣX) = ηA E[x²], estimated by Σx²; fixed N: N Var(x), estimated by
  Σx² − (ΣX)²/N;
* N_c/N given N: binomial, p(1 − p)/ΣN;
* μ = Σt/Σs: delta method, SE² = Σ(t − μ̂ s)²/(Σs)², the same for fixed and
  Poisson N.

These have the number of contacting summits as degrees of freedom, so z-scores are
close to normal even with few realizations. The spread across realizations
(``std``, ``se_between``) is reported too. Where the expected number of summits
carrying force in the whole ensemble is below :data:`MIN_CONTACTS`, z is not
reported: the sums are then too skewed for a normal approximation.

Every curve has one value per row of the run (:meth:`mcsim.engine.spec.MonteCarloSpec.rows`):
the separations of ``h`` on approach, then on retraction for a cycle.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from mcsim.engine.kernels import sum_columns
from mcsim.engine.montecarlo import EnsembleSums
from mcsim.physics.laws import LawSet

#: Expected summits carrying force (whole ensemble) below which no z-score is given.
MIN_CONTACTS = 100

#: Per-summit units that a total of an output is normalised by: force/(A K), area/A.
_PER_UNIT = {"N": "(A K)", "m^2": "A"}


@dataclass(frozen=True)
class Quantity:
    """One estimated curve: a normalised total Σ(w·x)/scale, or a ratio of two totals.

    Attributes
    ----------
    name : str
        ``contact_fraction``, an output name, ``friction`` or ``mu``.
    normalisation : str
        How it is made dimensionless (``"load/(A K)"``, ``"T/(P + F)"``, ...).
    weights : tuple of float
        Per output, the linear combination summed (totals and ratio numerators).
    per_area_only : bool
        Divided by A only (area outputs), else by A K.
    denominator : tuple of float or None
        For a ratio: the weights of its denominator (defined where it is > 0).
    defined : bool
        False: undefined at every separation, NaN (the seed's μ without adhesion).
    total : bool
        Whether it is a total (scales with the summit count), not a ratio.
    """

    name: str
    normalisation: str
    weights: tuple[float, ...] = ()
    per_area_only: bool = False
    denominator: tuple[float, ...] | None = None
    defined: bool = True

    @property
    def total(self) -> bool:
        return self.name != "contact_fraction" and self.denominator is None


def quantities(law: LawSet, material) -> dict[str, Quantity]:
    """The curves a run of ``law`` reports, in output order.

    ``contact_fraction``; each output normalised by A K (forces) or A (areas); μ of the
    seed (Eq. 8: T/(P + F), when the outputs are P, F, T); for a law set with
    Bowden–Tabor friction and a material τ, ``friction`` = τ·area/(A K) and
    μ = friction/load.
    """
    names = law.names
    k = len(names)

    def unit(i: int) -> tuple[float, ...]:
        return tuple(1.0 if j == i else 0.0 for j in range(k))

    out = {"contact_fraction": Quantity("contact_fraction", "N_c/N")}
    for i, o in enumerate(law.outputs):
        if o.unit not in _PER_UNIT:
            raise ValueError(f"output {o.name!r} of law set {law.name!r} has unit {o.unit!r}")
        out[o.name] = Quantity(o.name, f"{o.name}/{_PER_UNIT[o.unit]}", unit(i), o.unit == "m^2")
    if {"P", "F", "T"} <= set(names):  # the seed: Savkoor-Briggs friction, Eq. 8
        p, f = unit(names.index("P")), unit(names.index("F"))
        # Its friction is adhesional (Eq. 6): without adhesion (w = 0) T is 0 and the
        # model says nothing of friction, so μ is undefined, not 0.
        out["mu"] = Quantity("mu", "T/(P + F)", unit(names.index("T")),
                             denominator=tuple(a + b for a, b in zip(p, f)),
                             defined=material.gamma > 0)  # fmt: skip
    elif law.friction and material.tau is not None and {"load", "area"} <= set(names):
        tau = float(material.tau)
        friction = tuple(tau * w for w in unit(names.index("area")))
        out["friction"] = Quantity("friction", "tau area/(A K)", friction)
        out["mu"] = Quantity("mu", "friction/load", friction, denominator=unit(names.index("load")))
    return out


def _columns(law: LawSet, sums: np.ndarray):
    """First moments (list per output) and second moments ((i, j) → array) of ``sums``."""
    cols = sum_columns(law)
    names = law.names
    at = {c: sums[..., i] for i, c in enumerate(cols)}
    first = [at[n] for n in names]
    second = {
        (i, j): at[names[i] + names[j]] for i in range(len(names)) for j in range(i, len(names))
    }
    return at["n_contact"], first, second


def _linear(first, weights):
    """Σ w_i S_i over the non-zero weights, in output order."""
    total = None
    for w, col in zip(weights, first):
        if w != 0:
            total = w * col if total is None else total + w * col
    return np.zeros_like(first[0]) if total is None else total


def _square(second, weights):
    """Σ_i w_i² S_ii + 2 Σ_{i<j} w_i w_j S_ij (the moment of the combination squared)."""
    k = len(weights)
    diag = _linear([second[i, i] for i in range(k)], [w * w for w in weights])
    pairs = [(i, j) for i in range(k) for j in range(i + 1, k) if weights[i] and weights[j]]
    if not pairs:
        return diag
    cross = _linear([second[i, j] for i, j in pairs], [weights[i] * weights[j] for i, j in pairs])
    return diag + 2 * cross


def _bilinear(second, a, b):
    """Σ_ij a_i b_j S_ij, over the non-zero weights: i in order, then j in order."""
    terms = [(a[i] * b[j], second[min(i, j), max(i, j)])
             for i in range(len(a)) if a[i] for j in range(len(b)) if b[j]]  # fmt: skip
    return _linear([t for _, t in terms], [w for w, _ in terms])


def _quadratic(second, b):
    """bᵀ S b over the pairs i ≤ j in lexicographic order (2 S_ij off the diagonal)."""
    k = len(b)
    terms = [((1 if i == j else 2) * b[i] * b[j], second[i, j])
             for i in range(k) for j in range(i, k) if b[i] and b[j]]  # fmt: skip
    return _linear([t for _, t in terms], [w for w, _ in terms])


def _ratio(first, second, q: Quantity):
    """Pooled ratio Σt/Σs and its delta-method standard error (NaN where Σs ≤ 0, and
    everywhere if ``q`` is not defined)."""
    num, den = _linear(first, q.weights), _linear(first, q.denominator)
    den = den if q.defined else np.zeros_like(den)
    with np.errstate(invalid="ignore", divide="ignore"):
        mu = np.where(den > 0, num / den, np.nan)
        var = np.maximum(
            _quadratic(second, q.weights) - 2 * mu * _bilinear(second, q.weights, q.denominator)
            + mu**2 * _quadratic(second, q.denominator),
            0.0,
        )  # fmt: skip
        return mu, np.where(den > 0, np.sqrt(var) / den, np.nan)


def _scale(spec, q: Quantity) -> float:
    return spec.area if q.per_area_only else spec.area * spec.material.K


def per_realization(ens: EnsembleSums) -> dict[str, np.ndarray]:
    """Dimensionless curves of each realization, arrays of shape (R, rows).

    μ is NaN where a patch has no compressive load (for the seed, no contact, and
    everywhere without adhesion, w = 0): undefined, not zero.
    """
    spec = ens.spec
    n_contact, first, _ = _columns(spec.law_set, ens.sums)
    out = {}
    with np.errstate(invalid="ignore", divide="ignore"):
        for name, q in quantities(spec.law_set, spec.material).items():
            if name == "contact_fraction":
                out[name] = n_contact / ens.n_summits[:, None]
            elif q.denominator is not None:
                den = _linear(first, q.denominator) if q.defined else np.zeros_like(n_contact)
                out[name] = np.where(den > 0, _linear(first, q.weights) / den, np.nan)
            else:
                out[name] = _linear(first, q.weights) / _scale(spec, q)
    return out


@dataclass(frozen=True)
class Summary:
    """Ensemble estimates per quantity (keys of :func:`quantities`), one value per row.

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
        Expected summits carrying force over the whole ensemble, R·E[N]·S(s) with s
        the row's lowest height that can (for the seed, h: the contacting summits).
    """

    mean: dict[str, np.ndarray]
    se: dict[str, np.ndarray]
    std: dict[str, np.ndarray]
    se_between: dict[str, np.ndarray]
    expected_contacts: np.ndarray


def force_estimate(
    spec, n_summits: np.ndarray, sums: np.ndarray, weights, *, per_area_only: bool = False
) -> tuple[np.ndarray, np.ndarray]:
    """Mean over realizations of Σ(w·x)/(A K) and its summit-level standard error.

    ``weights`` has one entry per output of the law set; for the seed (a, b, c)
    weighs (P, F, T), e.g. (1, 1, 0) gives the total force of Fig. 4. The variance of
    one patch is Σx² (Poisson N) or Σx² − (Σx)²/N (fixed N) with x = w·(outputs)
    per summit, from the moment columns of ``sums``. ``per_area_only`` divides by A
    instead of A K (area outputs: A_r/A_n).
    """
    _, first, second = _columns(spec.law_set, sums)
    total = _linear(first, weights)
    square = _square(second, weights)
    if spec.count == "fixed":
        square = square - total**2 / n_summits[:, None]
    R = total.shape[0]
    scale = R * spec.area if per_area_only else R * spec.area * spec.material.K
    return total.sum(axis=0) / scale, np.sqrt(np.maximum(square.sum(axis=0), 0.0)) / scale


def summarize(ens: EnsembleSums) -> Summary:
    """Estimates and standard errors of a run (formulas in the module docstring)."""
    spec = ens.spec
    R = spec.realizations
    tot = ens.sums.sum(axis=0)  # (rows, C), pooled over realizations
    n_contact, first, second = _columns(spec.law_set, tot)
    n_total = float(ens.n_summits.sum())
    mean, se = {}, {}
    with np.errstate(invalid="ignore", divide="ignore"):
        for name, q in quantities(spec.law_set, spec.material).items():
            if name == "contact_fraction":
                p = n_contact / n_total
                mean[name], se[name] = p, np.sqrt(p * (1 - p) / n_total)
            elif q.denominator is not None:
                mean[name], se[name] = _ratio(first, second, q)
            else:
                mean[name], se[name] = force_estimate(
                    spec, ens.n_summits, ens.sums, q.weights, per_area_only=q.per_area_only
                )
    per = per_realization(ens)
    with warnings.catch_warnings():  # μ of a patch without contact is NaN and skipped
        warnings.simplefilter("ignore", RuntimeWarning)
        std = {q: np.nanstd(v, axis=0, ddof=1) for q, v in per.items()}
    se_between = {q: v / np.sqrt(R) for q, v in std.items()}
    expected = R * spec.expected_summits * np.asarray(spec.surface.heights.sf(spec.row_s))
    return Summary(mean, se, std, se_between, expected)


def expected_values(spec, curves) -> dict[str, np.ndarray]:
    """What the estimators of :func:`summarize` converge to, one value per row.

    ``curves``: the analytic curves of each branch of ``spec`` (a sequence in the order
    of ``spec.branches``, or one :class:`mcsim.physics.analytic.AnalyticCurves` for approach
    only), with attributes named as the quantities. The analytic curves are per unit
    of η·A; a fixed count N = round(ηA) scales the totals by round(ηA)/(ηA).
    """
    if not isinstance(curves, list | tuple):
        curves = [curves]
    bias = spec.expected_summits / (spec.surface.eta * spec.area)
    out = {}
    for name, q in quantities(spec.law_set, spec.material).items():
        values = [np.asarray(getattr(c, name), dtype=float) for c in curves]
        value = values[0] if len(values) == 1 else np.concatenate(values)
        out[name] = value * (bias if q.total else 1.0)
    return out


def compare_table(
    summary: Summary, expected: dict[str, np.ndarray], h: np.ndarray, branch=None
) -> list[dict]:
    """Rows ``h, branch, quantity, mc_mean, mc_se, analytic, z, note`` for every row and quantity.

    ``h`` and ``branch`` give each row's d/σ and branch (approach by default). z =
    (mc − analytic)/se; NaN, with a note, where the expected number of summits
    carrying force is below :data:`MIN_CONTACTS` or the estimate is undefined.
    """
    branch = ["approach"] * len(h) if branch is None else branch
    undefined = (
        "undefined: no compressive load (mu = friction/load needs load > 0)"
        if "load" in summary.mean
        else "undefined: no contact in the ensemble, or w = 0 (the seed's friction is adhesional)"
    )
    rows = []
    for j, hj in enumerate(h):
        few = summary.expected_contacts[j] < MIN_CONTACTS
        for q in summary.mean:
            m, e, a = summary.mean[q][j], summary.se[q][j], expected[q][j]
            note = ""
            if few:
                note = f"few contacts (expected {summary.expected_contacts[j]:.3g} < {MIN_CONTACTS}): no normal approximation"
            elif not np.isfinite(m):
                note = undefined
            elif not np.isfinite(a):
                note = "no analytic value"
            elif e == 0:
                note = "zero standard error"
            z = (m - a) / e if not note else np.nan
            rows.append({"h": float(hj), "branch": str(branch[j]), "quantity": q, "mc_mean": float(m),
                         "mc_se": float(e), "analytic": float(a), "z": float(z), "note": note})  # fmt: skip
    return rows

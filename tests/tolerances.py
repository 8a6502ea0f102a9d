"""The tolerance table: how far two CPUs may disagree on each quantity of a seed run.

Used by the goldens (``tests/program/test_seed_golden.py``) and by the run files written by
earlier versions (``tests/store/test_runfile.py``); the named tolerances of single
comparisons (``ROUNDING_FEW`` … ``ROUNDING_SUM``) by every test that compares one value
computed two ways.

Rounding-error bounds (Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed.
2002, §4.2, Eq. 4.4): a floating-point sum of n terms, in *any* order or tree, is off by at
most (n − 1)·u·Σ|x_i|, u = ε/2. Two machines each within that differ by at most n·ε·Σ|x_i|,
and for terms of one sign Σ|x_i| = |Σx_i|: a relative tolerance of n·ε, with n the
number of non-zero terms (N_eff, the summits in contact; zeros add nothing). Every seed
output (P, F, T ≥ 0, seed.py) and every moment column (squares, products of those) has
terms of one sign.
"""

from dataclasses import dataclass

import numpy as np

from mcsim.engine.kernels import sum_columns
from mcsim.physics.analytic import QUANTITIES
from mcsim.physics.laws import SEED

EPS = np.finfo(float).eps
COLUMNS = sum_columns(SEED)
FORCES = ("P", "F", "T")
ROWS = tuple(QUANTITIES)  # of the golden stacks: contact_fraction, P, F, T, mu

# --- the tolerance table ----------------------------------------------------------------
#: ulps by which one summit's law value may differ between two CPUs (relative, in ε): the
#: longest chains in seed.py (F, T) are ~6 correctly rounded operations, each ½ε relative
#: on each machine, with or without FMA contraction: ≤ 6ε apart; 8 also covers the 1-2
#: roundings of the normalisation by A K. A square or product of two values: 2·LAW.
LAW = 8
#: Terms in an analytic quadrature sum: the larger of the Gaussian rule (8 panels × 24
#: nodes, distributions.py) and the empirical one (≤ 6 bins × 4 panels × 12 nodes,
#: empirical.py).
QUADRATURE = 6 * 4 * 12
#: ulps by which one quadrature term may differ: exp of the Gaussian weight, ≤ 4 ulp in
#: NumPy's SIMD (SVML) exp and < 1 ulp in glibc's; the rest is correctly rounded
#: arithmetic, the same on every IEEE machine.
EXP = 5


# --- tolerances of single comparisons ----------------------------------------------------
# Relative, for values of one sign; where a value can be zero or cross zero, a test scales
# the same number by the magnitude of the terms that cancel and uses it as an absolute one.
#: ≈ 4.5ε: the same value through a handful (≤ 9) of correctly rounded IEEE-754 operations
#: on each side, each within ½ε (Higham §2.2), e.g. decimal text times a unit factor, or a
#: product of the same inputs in another order: holds on any IEEE machine, FMA or not.
ROUNDING_FEW = 1e-15
#: ≈ 45ε: a closed-form expression of tens of operations, libm's sqrt, pow, cbrt, exp among
#: them (≤ 4 ulp each in glibc and NumPy's SIMD), evaluated two ways.
ROUNDING_FORMULA = 1e-14
#: ≈ 450ε: the same, where a power amplifies the inputs' rounding (x**1.5 multiplies a
#: relative error of x by 1.5, a cube root of a difference by its cancellation) or a chain of
#: such formulas (a root found, then a law evaluated at it).
ROUNDING_CHAIN = 1e-13
#: ≈ 4500ε: a sum of up to ~4500 terms of one sign taken in two orders or trees (a kernel
#: against its NumPy reference, blocks against one sum): Higham Eq. 4.4, ≤ n·ε·Σ|x_i|
#: (the worst case; rounding errors of random sign grow as √n·ε).
ROUNDING_SUM = 1e-12
#: 100× the relative accuracy asked of scipy.integrate.quad by a reference integral
#: (epsrel ≤ 1e-12): QUADPACK's error estimate is an estimate, not a bound. The quantities
#: compared this way were measured to agree to ~1e-14.
QUAD_RTOL = 1e-10
#: Load control (mcsim.physics.loadcontrol): h is root-solved to XTOL = 1e-12 and the load
#: there matches the target to 1e-10, but where the load is a small difference of large
#: attractive and repulsive terms one ulp of h moves it by ~1e-9 relative (its docstring).
LOAD_CONTROL_RTOL = 1e-9


@dataclass(frozen=True)
class Moments:
    """The reference sums of a run, which scale the tolerances of its quantities.

    Attributes
    ----------
    sums : ndarray, shape (R, rows, C)
        Per-realization sums, columns :func:`mcsim.engine.kernels.sum_columns` of the seed.
    area_k : float
        A·K of one patch, N (the normalisation of the totals).
    """

    sums: np.ndarray
    area_k: float = 1.0

    def __getitem__(self, column: str) -> np.ndarray:
        return self.sums[..., COLUMNS.index(column)]

    def pooled(self, column: str) -> np.ndarray:
        return self[column].sum(axis=0)

    @property
    def contacts(self) -> np.ndarray:
        """Summits in contact per realization and row (exact integers), shape (R, rows)."""
        return self["n_contact"]


def _sqrt_error(v, dv):
    """Bound on |√v' − √v| for |v' − v| ≤ dv, v ≥ 0: min(dv/√v, √dv)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.fmin(dv / np.sqrt(v), np.sqrt(dv))


def tol_sums(m: Moments, value):
    """Sums (R, rows, C). n_contact: an integer count, exact. Σx over the n_c contacting
    summits: n_c·ε relative (module docstring) plus LAW; Σx², Σxy: the same with 2·LAW."""
    n = m.contacts[..., None]
    terms = np.array([0.0 if c == "n_contact" else LAW if c in FORCES else 2 * LAW
                      for c in COLUMNS])  # fmt: skip
    return np.where(terms > 0, (n + terms) * EPS * np.abs(value), 0.0)


def tol_totals(q: str, n, value):
    """A normalised total or pooled ratio over n contacting summits (per realization or
    pooled). contact_fraction: N_c/N of exact integers, one correctly rounded division:
    exact. A force total ΣX/(A K): (n + LAW)·ε relative. μ = ΣT/Σ(P + F): the relative
    errors of numerator and denominator add, plus the division's ε."""
    if q == "contact_fraction":
        return np.zeros_like(value)
    rel = (n + LAW) * EPS
    return (2 * rel + EPS if q == "mu" else rel) * np.abs(value)


def tol_mean(m: Moments, q: str, value):
    """Ensemble estimate: a total over all realizations' n_c (the sum over realizations
    is part of the same summation tree)."""
    return tol_totals(q, m.contacts.sum(axis=0), value)


def tol_se(m: Moments, q: str, value):
    """Summit-level standard error (statistics.py), from a difference of moments, so
    bounded by the moments it cancels, not by itself.

    contact_fraction: √(p(1 − p)/N) of exact integers in correctly rounded operations:
    exact. A force X: SE = √V/(R A K), V = Σ_r [Σx² − (ΣX)²/N for a fixed count]. Σx²
    is off by (n + 2·LAW)·ε·Σx², and the fixed-count term, ≤ Σx² (Cauchy–Schwarz), by no
    more: |δV| ≤ 2(n + 2·LAW)·ε·Σx². μ: SE = √Q/Σs, s = p + f, with
    Q = Σt² − 2μΣts + μ²Σs² (the delta method); each moment is off by (n + 2·LAW)·ε and μ
    by 2(n + LAW)·ε relative, so |δQ| ≤ 5(n + 2·LAW)·ε·M with M = Σt² + 2μΣts + μ²Σs², the
    scale Q cancels from; Σs adds its own (n + LAW)·ε relative. √ turns |δV| into
    :func:`_sqrt_error` (|δV|/√V, or √|δV| where V has cancelled to rounding level).
    """
    n = m.contacts.sum(axis=0)
    if q == "contact_fraction":
        return np.zeros_like(value)
    if q in FORCES:
        scale = m.sums.shape[0] * m.area_k
        dv = 2 * (n + 2 * LAW) * EPS * m.pooled(q + q)
        return _sqrt_error((value * scale) ** 2, dv) / scale
    s = m.pooled("P") + m.pooled("F")
    ts = m.pooled("PT") + m.pooled("FT")
    ss = m.pooled("PP") + 2 * m.pooled("PF") + m.pooled("FF")
    with np.errstate(divide="ignore", invalid="ignore"):
        mu = m.pooled("T") / s
        dq = 5 * (n + 2 * LAW) * EPS * (m.pooled("TT") + 2 * mu * ts + mu**2 * ss)
        return _sqrt_error((value * s) ** 2, dq) / s + (n + LAW) * EPS * np.abs(value)


def tol_spread(m: Moments, q: str, per_realization):
    """Standard deviation across realizations x_r (numpy.nanstd, ddof 1): a Lipschitz
    function of the x_r, |δstd| ≤ ‖δx‖₂/√(R − 1), with δx_r from :func:`tol_totals`, plus
    NumPy's own roundings of the mean and the deviations, (R + 2)·ε·max|x_r|/√(R − 1)."""
    x = np.asarray(per_realization)
    dx = tol_totals(q, m.contacts, x)
    r = np.sum(~np.isnan(x), axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        rounding = (r + 2) * EPS * np.nanmax(np.abs(x), axis=0, initial=0.0)
        return (np.sqrt(np.nansum(dx**2, axis=0)) + rounding) / np.sqrt(r - 1)


def tol_analytic(q: str, value):
    """GW integral (analytic.py): a quadrature sum of QUADRATURE positive terms, each
    within EXP ulp: (QUADRATURE + EXP)·ε relative; μ, a ratio of two: twice that plus ε.
    contact_fraction (erfc, or the histogram's survival function) is bounded alike."""
    rel = (QUADRATURE + EXP) * EPS
    return (2 * rel + EPS if q == "mu" else rel) * np.abs(value)


def outside(actual, expected, tolerance) -> np.ndarray:
    """Mask of the entries of ``actual`` farther than ``tolerance`` from ``expected``;
    NaN matches NaN only, integers match exactly. Shape and dtype must match."""
    actual, expected = np.asarray(actual), np.asarray(expected)
    assert (actual.shape, actual.dtype) == (expected.shape, expected.dtype)
    if actual.dtype.kind != "f":
        return actual != expected
    with np.errstate(invalid="ignore"):
        near = np.abs(actual - expected) <= tolerance  # False wherever anything is NaN
    return ~(near | (np.isnan(actual) & np.isnan(expected)))


def assert_close(actual, expected, tolerance, name: str) -> None:
    """Fail naming the entries of ``actual`` outside ``tolerance`` of ``expected``."""
    bad = outside(actual, expected, tolerance)
    if bad.any():
        at = np.argwhere(bad)[:5]
        rows = [f"  {tuple(i)}: {actual[tuple(i)]!r} vs {expected[tuple(i)]!r}, "
                f"tolerance {np.broadcast_to(tolerance, bad.shape)[tuple(i)]:.3g}"
                for i in at]  # fmt: skip
        raise AssertionError(f"{name}: {bad.sum()} of {bad.size} outside tolerance\n"
                             + "\n".join(rows))  # fmt: skip


def _numbers(run, q: str) -> dict[str, np.ndarray]:
    s = run.summary
    return {"realizations": run.realizations[q], "analytic": run.analytic[q], "mean": s.mean[q],
            "se": s.se[q], "std": s.std[q], "se_between": s.se_between[q]}  # fmt: skip


def assert_same_run(actual, expected) -> None:
    """Every number of two runs of the seed law set agrees within the table: the raw sums,
    the per-realization curves, the estimates and their errors, the analytic curves."""
    m = Moments(expected.sums, expected.spec.area * expected.spec.material.K)
    assert_close(actual.sums, expected.sums, tol_sums(m, expected.sums), "sums")
    np.testing.assert_array_equal(actual.n_summits, expected.n_summits)
    for q in ROWS:
        got, ref = _numbers(actual, q), _numbers(expected, q)
        spread = tol_spread(m, q, ref["realizations"])
        tolerance = {
            "realizations": tol_totals(q, m.contacts, ref["realizations"]),
            "analytic": tol_analytic(q, ref["analytic"]),
            "mean": tol_mean(m, q, ref["mean"]),
            "se": tol_se(m, q, ref["se"]),
            "std": spread,
            "se_between": spread / np.sqrt(m.sums.shape[0]) + EPS * np.abs(ref["se_between"]),
        }
        for stat, tol in tolerance.items():
            assert_close(got[stat], ref[stat], tol, f"{stat} of {q}")

"""The seed law set's numbers are frozen: mcsim 0.1's, to rounding.

``tests/data/seed_golden.npz`` was written by ``tests/make_seed_golden.py`` from mcsim 0.1
(checked equal to a run of the 0.1 commit itself) on an AVX2 machine. Another CPU (SIMD
width, FMA contraction, libm) sums and rounds in another order, so each quantity is
compared within the tolerance its conditioning allows (the table below) and no wider: a
changed law, a lost summit or a reseeded stream fails (the last tests). Bit-identity on
one machine, for any worker count, chunk size or scheduler, is tested in
``tests/engine/test_montecarlo.py`` and ``tests/store/test_runfile.py``.

The tolerances and their derivations: the table in ``tests/tolerances.py``.
"""

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from make_seed_golden import AREA, H, cases, kernel_population, monte_carlo
from tolerances import (
    COLUMNS,
    FORCES,
    ROWS,
    Moments,
    assert_close,
    outside,
    tol_analytic,
    tol_mean,
    tol_se,
    tol_sums,
)

from mcsim.engine.kernels import block_sums
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.analytic import gw_curves
from mcsim.physics.laws import SEED

GOLDEN_PATH = Path(__file__).parents[1] / "data" / "seed_golden.npz"
GOLDEN = np.load(GOLDEN_PATH)


def test_the_golden_script_writes_where_this_file_reads():
    import make_seed_golden  # tests/ is on the path (pyproject: pythonpath)

    assert make_seed_golden.OUT.resolve() == GOLDEN_PATH.resolve()


# --- the goldens -------------------------------------------------------------------------


def golden_moments(label: str) -> Moments:
    if label == "kernel_sums":
        return Moments(GOLDEN["kernel_sums"][None])
    return Moments(GOLDEN[f"sums_{label}"], AREA * MATERIALS["silicon"].K)


def golden_tolerance(key: str, value: np.ndarray) -> np.ndarray:
    """Tolerance of golden entry ``key`` (value: its reference) from the table above."""
    kind, _, label = key.partition("_")
    if kind == "N":  # summits per patch: integers
        return np.zeros_like(value)
    if key == "kernel_sums":
        return tol_sums(golden_moments(key), value[None])[0]
    if kind == "sums":
        return tol_sums(golden_moments(label), value)
    per_row = {"analytic": lambda q, v: tol_analytic(q, v),
               "mean": lambda q, v: tol_mean(golden_moments(label), q, v),
               "se": lambda q, v: tol_se(golden_moments(label), q, v)}[kind]  # fmt: skip
    return np.stack([per_row(q, v) for q, v in zip(ROWS, value)])


@pytest.fixture(scope="module")
def current():
    return cases()


@pytest.mark.parametrize("key", sorted(GOLDEN))
def test_seed_numbers_equal_0_1_within_their_tolerances(current, key):
    assert_close(current[key], GOLDEN[key], golden_tolerance(key, GOLDEN[key]), key)


def fails_golden(key: str, value: np.ndarray) -> np.ndarray:
    """Mask of the entries of ``value`` that fail golden entry ``key``."""
    return outside(value, GOLDEN[key], golden_tolerance(key, GOLDEN[key]))


def test_a_changed_law_fails_the_goldens():
    """γ up by 1e-6 relative: the kernel sums and analytic curves of F and T, which depend
    on γ, fail; P, which does not, still passes (the comparison fails for the change)."""
    silicon, smooth = MATERIALS["silicon"], SURFACES["smooth"]
    changed = dataclasses.replace(silicon, gamma=silicon.gamma * (1 + 1e-6))
    z, d = kernel_population()
    sums = fails_golden("kernel_sums", block_sums(z, d, SEED, SEED.arguments(smooth, changed)))
    c = gw_curves(smooth, changed, H)
    curves = fails_golden("analytic_smooth", np.stack([c.contact_fraction, c.P, c.F, c.T, c.mu]))
    for q in ("F", "T"):
        assert sums[:, COLUMNS.index(q)].any() and curves[ROWS.index(q)].any(), q
    assert not sums[:, COLUMNS.index("P")].any() and not curves[ROWS.index("P")].any()


def test_a_lost_summit_fails_the_goldens():
    """The median contacting summit of the deepest row left out of the kernel sums: not
    only the count but every first moment fails, at every row where it touched."""
    z, d = kernel_population()
    touching = np.flatnonzero(z > d.min())
    lost = touching[np.argsort(z[touching])[touching.size // 2]]
    args = SEED.arguments(SURFACES["smooth"], MATERIALS["silicon"])
    bad = fails_golden("kernel_sums", block_sums(np.delete(z, lost), d, SEED, args))
    rows = z[lost] > d
    for q in ("n_contact", *FORCES):
        np.testing.assert_array_equal(bad[:, COLUMNS.index(q)], rows, err_msg=q)


def test_a_reseeded_stream_fails_the_goldens():
    """Seed 8 instead of 7: the summit counts, the sums and the estimates all fail."""
    reseeded = monte_carlo("gaussian_poisson", seed=8)
    for key, value in reseeded.items():
        assert fails_golden(key, value).any(), key

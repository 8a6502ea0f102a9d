"""The fused kernel follows any law set: its outputs, edges, branches and array constants."""

import dataclasses

import numpy as np
import pytest
from lawset_toy import TOY
from tolerances import ROUNDING_SUM

from mcsim.engine.kernels import SUM_COLUMNS, block_sums, block_sums_numpy, sum_columns
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.laws import LAW_SETS, SEED, helpers

SMOOTH = SURFACES["smooth"]
#: Silicon with every optional field a law set may require.
MATERIAL = dataclasses.replace(MATERIALS["silicon"], H=12.5e9, z0=0.3e-9, tau=1e8)


@pytest.fixture(autouse=True, scope="module")
def _private_cache(law_set_cache):
    """Test law sets compile into a throw-away cache, not the user's."""
    mp = pytest.MonkeyPatch()
    mp.setenv("MCSIM_CACHE_DIR", law_set_cache)
    yield
    mp.undo()


def assert_sums_close(fast, ref, rtol=ROUNDING_SUM):
    """Counts exactly; moments to ``rtol`` of each column's largest magnitude (signed
    sums may cancel to zero, where a purely relative bound means nothing)."""
    np.testing.assert_array_equal(fast[:, 0], ref[:, 0], err_msg="contact counts")
    scale = np.maximum(np.max(np.abs(ref), axis=0, keepdims=True), np.finfo(float).tiny)
    assert np.all(np.abs(fast - ref) <= rtol * scale), np.max(np.abs(fast - ref) / scale)


def test_sum_columns_are_count_sums_squares_then_cross_products_in_lexicographic_order():
    assert sum_columns(SEED) == SUM_COLUMNS
    assert sum_columns(TOY) == (
        "n_contact", "load", "area", "grip", "loadload", "areaarea", "gripgrip",
        "loadarea", "loadgrip", "areagrip",
    )  # fmt: skip


def random_rows(rng, sigma):
    """Approach rows (d_turn = d) and retraction rows from the lowest d, shuffled."""
    h = rng.uniform(-3, 3, rng.integers(1, 30))
    d = h * sigma
    turn = np.full_like(d, d.min())
    rows_d, rows_turn = np.concatenate([d, d]), np.concatenate([d, turn])
    perm = rng.permutation(rows_d.size)
    return rows_d[perm], rows_turn[perm]


@pytest.mark.parametrize("branch", ["approach", "retract"])
def test_fused_kernel_matches_the_reference_for_a_stateful_law_set_with_attraction(branch):
    args = TOY.arguments(SMOOTH, MATERIAL)
    edges = TOY.edges_for(SMOOTH, MATERIAL)
    rng = np.random.default_rng(11)
    for _ in range(6):
        z = rng.standard_normal(rng.integers(1, 4000)) * SMOOTH.sigma
        d = rng.uniform(-3, 3, rng.integers(1, 30)) * SMOOTH.sigma
        turn = d if branch == "approach" else np.full_like(d, d.min() - 0.1 * SMOOTH.sigma)
        fast = block_sums(z, d, TOY, args, d_turn=turn, edges=edges)
        ref = block_sums_numpy(z, d, TOY, args, d_turn=turn, edges=edges)
        assert_sums_close(fast, ref)


@pytest.mark.parametrize("branch", ["approach", "retract"])
def test_a_law_calling_helpers_compiles_them_into_the_kernel_and_matches_the_reference(branch):
    """TOY's stateful outputs call helpers of their own file (one through another, one
    reading the table): the kernel compiles them in and agrees with the reference."""
    from lawset_toy import in_contact, overlap, pressed, toy_area, toy_load

    assert helpers(toy_load) == (in_contact, pressed, overlap)
    assert helpers(toy_area) == (in_contact,)
    args, edges = TOY.arguments(SMOOTH, MATERIAL), TOY.edges_for(SMOOTH, MATERIAL)
    rng = np.random.default_rng(23)
    z = rng.standard_normal(5000) * SMOOTH.sigma
    d = np.linspace(3, -1, 41) * SMOOTH.sigma
    turn = d if branch == "approach" else np.full_like(d, d.min())
    fast = block_sums(z, d, TOY, args, d_turn=turn, edges=edges)
    ref = block_sums_numpy(z, d, TOY, args, d_turn=turn, edges=edges)
    assert np.all(fast[:, 1] != 0)  # the load (helpers in_contact, pressed) acts on every row
    assert_sums_close(fast, ref)


def test_the_kernels_cache_stamp_follows_the_source_of_every_helper(monkeypatch, tmp_path):
    """Editing a helper (here: overlap, called through pressed) changes the stamp of the
    kernel's on-disk cache, so numba never serves a kernel built from the old helper."""
    import inspect

    from lawset_toy import overlap

    from mcsim.engine import kernels

    monkeypatch.setenv("MCSIM_CACHE_DIR", str(tmp_path))
    stamps = []
    original = inspect.getsource
    for edited in (False, True):
        suffix = "# edited\n" if edited else ""
        monkeypatch.setattr(
            inspect, "getsource", lambda f, s=suffix: original(f) + (s if f is overlap else "")
        )
        kernels._kernel.cache_clear()
        stamps.append(kernels._compiled(TOY, True).py_func.mcsim_cache)
    kernels._kernel.cache_clear()
    (folder, stamp, key), (folder_edited, stamp_edited, key_edited) = stamps
    assert stamp != stamp_edited, "the stamp follows the helper"
    assert key == key_edited and folder == folder_edited == "kernels", (
        "one index file: the new kernel replaces the old"
    )


def test_reference_counts_contacts_and_attraction_by_the_edges():
    """One summit, one row each: in contact, attracted only, and held on retraction."""
    args, edges = TOY.arguments(SMOOTH, MATERIAL), TOY.edges_for(SMOOTH, MATERIAL)
    c = 0.3 * SMOOTH.sigma
    z = np.array([0.0])
    # approach at δ = -1.5c: attracted (load < 0), not in contact, no area
    d = np.array([1.5 * c, 0.5 * c, 1.5 * c, 2.5 * c])
    turn = np.array([1.5 * c, 0.5 * c, -0.1 * c, -0.1 * c])
    for sums in (block_sums(z, d, TOY, args, d_turn=turn, edges=edges),
                 block_sums_numpy(z, d, TOY, args, d_turn=turn, edges=edges)):  # fmt: skip
        np.testing.assert_array_equal(sums[:, 0], [0, 0, 0, 0])  # δ ≤ jump-in / break-off
        assert sums[0, 1] < 0 and sums[0, 2] == 0  # attraction only
        assert sums[3, 1] == 0  # beyond the reach: nothing
    z = np.array([0.0])
    d, turn = np.array([-0.5 * c, 0.5 * c, 0.5 * c]), np.array([-0.5 * c, 0.5 * c, -0.1 * c])
    for sums in (block_sums(z, d, TOY, args, d_turn=turn, edges=edges),
                 block_sums_numpy(z, d, TOY, args, d_turn=turn, edges=edges)):  # fmt: skip
        # in contact on approach; out of contact at δ = -0.5c on approach, in contact on
        # retraction (δ_max > 0, δ > break-off = -c): hysteresis
        np.testing.assert_array_equal(sums[:, 0], [1, 0, 1])
        assert sums[2, 2] > 0 and sums[1, 2] == 0


def test_fused_kernel_writes_each_row_to_its_own_position_whatever_the_row_order():
    args, edges = TOY.arguments(SMOOTH, MATERIAL), TOY.edges_for(SMOOTH, MATERIAL)
    rng = np.random.default_rng(5)
    z = rng.standard_normal(3000) * SMOOTH.sigma
    d, turn = random_rows(rng, SMOOTH.sigma)
    fast = block_sums(z, d, TOY, args, d_turn=turn, edges=edges)
    for j in range(d.size):
        one = block_sums(z, d[j : j + 1], TOY, args, d_turn=turn[j : j + 1], edges=edges)
        assert_sums_close(fast[j : j + 1], one)  # other rows change the summation order


@pytest.mark.parametrize("name", sorted(LAW_SETS))
@pytest.mark.parametrize("branch", ["approach", "retract"])
def test_fused_kernel_matches_the_reference_for_every_registered_law_set(name, branch):
    law = LAW_SETS[name]
    if branch == "retract" and not law.retract:
        pytest.skip(f"{name} has no retraction branch")
    args, edges = law.arguments(SMOOTH, MATERIAL), law.edges_for(SMOOTH, MATERIAL)
    rng = np.random.default_rng(3)
    for _ in range(4):
        z = rng.standard_normal(rng.integers(1, 4000)) * SMOOTH.sigma
        d = rng.uniform(-3, 3, rng.integers(1, 30)) * SMOOTH.sigma
        turn = d if branch == "approach" else np.full_like(d, d.min())
        fast = block_sums(z, d, law, args, d_turn=turn, edges=edges)
        ref = block_sums_numpy(z, d, law, args, d_turn=turn, edges=edges)
        assert_sums_close(fast, ref)


def test_the_seed_kernel_passes_each_law_its_tuple_and_other_law_sets_count_contacts():
    """The seed's kernel is mcsim 0.1's (each law its own parameter tuple, no contact
    test), which keeps its vectorised summation order and so its bits; a law set with
    edges counts."""
    from mcsim.engine.kernels import _counting, _parameters

    positions, indices = _parameters(SEED.outputs, legacy=True)
    assert positions == ((0, 0), (0, 1), (1, 0), (1, 1), (1, 2), (2, 0), (2, 1), (2, 2), (2, 3))
    assert indices == ((0, 1), (2, 3, 4), (5, 6, 7, 8))
    assert not _counting(SEED, SEED.edges_for(SMOOTH, MATERIAL))
    assert _counting(TOY, TOY.edges_for(SMOOTH, MATERIAL))


def test_outputs_sharing_a_parameter_read_it_once_so_shared_work_is_computed_once():
    """Outside the legacy (seed) kernel, a parameter that several outputs take (TOY: R
    and c) is passed once: the same value to LLVM, which then computes identical
    subexpressions of the outputs once."""
    from mcsim.engine.kernels import _parameters

    positions, (load, area, grip) = _parameters(TOY.outputs, legacy=False)
    assert positions == ((0, 0), (0, 1), (0, 2), (0, 3), (2, 1))  # R, K, c, table, gamma
    assert (load, area, grip) == ((0, 1, 2, 3), (0, 2), (0, 4))


@pytest.mark.parametrize("name", ["seed", "jkr"])
def test_counting_and_bisection_find_the_same_first_rows_so_the_sums_are_bit_identical(name):
    """Up to LINEAR_ROWS rows the kernel finds each summit's first row by counting the
    thresholds above it, beyond by bisection: both give the same buckets, so forcing
    bisection (LINEAR_ROWS = 0) leaves every sum unchanged, bit for bit, ties included."""
    from mcsim.engine import kernels

    law = LAW_SETS[name]
    args, edges = law.arguments(SMOOTH, MATERIAL), law.edges_for(SMOOTH, MATERIAL)
    rng = np.random.default_rng(11)
    z = rng.standard_normal(5000) * SMOOTH.sigma
    d = np.linspace(3, -1, 51) * SMOOTH.sigma
    z[:51] = d  # summits exactly at a row's threshold (approach: δ = 0)
    turn = np.full_like(d, d.min()) if law.retract else d
    counted = block_sums(z, d, law, args, d_turn=turn, edges=edges)
    mp = pytest.MonkeyPatch()
    try:
        mp.setattr(kernels, "LINEAR_ROWS", 0)  # a kernel of its own, in memory and on disk
        bisected = block_sums(z, d, law, args, d_turn=turn, edges=edges)
    finally:
        mp.undo()
    np.testing.assert_array_equal(counted, bisected)

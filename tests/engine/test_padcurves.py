"""Exact per-pad curves from heights drawn again (issue 23): mcsim.engine.padcurves, Run.pull_off."""

import dataclasses
import math

import numpy as np
import pytest

from mcsim.engine import padcurves
from mcsim.engine.montecarlo import MonteCarloSpec, run_sums
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.store.results import assemble

SILICON = MATERIALS["silicon"]
#: The smooth surface at sigma = 2.5 nm of issue 23.
ROUGHER = dataclasses.replace(SURFACES["smooth"], sigma=2.5e-9)


def cycle(h, realizations=30, surface=ROUGHER, area=30e-12, seed=1, law="jkr", **kw):
    spec = MonteCarloSpec(surface, SILICON, np.asarray(h, float), area, realizations, seed,
                          law=law, cycle=True, **kw)  # fmt: skip
    return spec, run_sums(spec, workers=1, keep_heights=True)


def test_heights_drawn_again_are_the_ones_the_run_summed_bit_for_bit():
    spec, ens = cycle(np.linspace(3, -1, 9), realizations=5)
    for r in range(5):
        np.testing.assert_array_equal(padcurves.patch_heights(spec, r), ens.heights[r])


def test_pull_off_does_not_depend_on_the_grids_spacing_or_top():
    # Same turn (so the same s_min and the same heights), other spacing and top.
    coarse = assemble(cycle(np.linspace(4, -1, 11))[1]).pull_off()
    fine = assemble(cycle(np.linspace(2, -1, 61))[1]).pull_off()
    # Tolerance: the minimum is located to XTOL = 1e-7 in h, where the curve is flat to
    # second order (a relative change ~1e-12); 1e-9 leaves room for the summation order.
    np.testing.assert_allclose(fine.force, coarse.force, rtol=1e-9)
    assert not np.allclose(fine.grid_force, coarse.grid_force, rtol=1e-3)  # the grid's do move


def test_pull_off_is_the_minimum_of_a_dense_evaluation_of_the_pads_own_curve():
    spec, ens = cycle(np.linspace(3, -1, 5), realizations=6)
    pull = assemble(ens).pull_off()
    sigma = spec.surface.sigma
    for r in range(6):
        z = ens.heights[r]
        d = np.linspace(spec.turn, z.max() / sigma + 1, 40001) * sigma
        dense = -padcurves.pad_load(spec, z, d, spec.turn * sigma).min()
        # No point of the curve is more tensile than its minimum; a grid of spacing 1.5e-4 in h
        # comes within 1 % (it can miss the square-root cusp of a summit at its break-off).
        assert dense <= pull.force[r] * (1 + 1e-12)
        assert dense >= pull.force[r] * (1 - 1e-2)


def test_every_pad_with_a_touching_summit_pulls_off_with_at_least_one_summits_jkr_force():
    # Issue 23: on a grid ending at h = 4 some pads were still tensile at its top and
    # reported less than one summit's 1.5 pi w R (Johnson 1985, Eq. 5.60), some 0.
    spec, ens = cycle(np.linspace(4, -1, 26), realizations=100)
    pull = assemble(ens).pull_off()
    one = 1.5 * math.pi * SILICON.gamma * spec.surface.R
    assert np.any(pull.grid_force < one * 0.99) and pull.past_grid_top > 0
    assert np.all(pull.force >= one * (1 - 1e-9))
    assert np.all(pull.h[pull.h > pull.top] > 4)


def test_force_turn_is_the_largest_separation_whose_approach_load_reaches_the_force():
    spec, ens = cycle(np.linspace(3, -2, 6), realizations=3)
    sigma = spec.surface.sigma
    for z in ens.heights:
        force = 30e-6
        d_t, load = padcurves.force_turn(spec, z, force)
        assert load >= force and padcurves.pad_load(spec, z, [d_t])[0] == load
        above = np.linspace(d_t + padcurves.XTOL * sigma, z.max() + sigma, 20001)
        assert np.all(padcurves.pad_load(spec, z, above) < force)


@pytest.mark.parametrize("law", ["jkr", "maugis-dugdale"])
def test_the_approach_loads_down_to_the_first_reaching_one_are_the_whole_grids_bit_for_bit(law):
    # force_turn evaluates only a prefix of its points; the kernel's sums depend on the set
    # of rows summed together, so the prefix must give the whole grid's numbers exactly.
    spec, ens = cycle(np.linspace(3, -2, 6), realizations=3, law=law)
    sigma = spec.surface.sigma
    points = np.linspace(4 * sigma, -2 * sigma, 3001)
    for z in ens.heights:
        whole = padcurves.pad_load(spec, z, points)
        for force in (1e-6, 30e-6, whole[1500]):
            values = padcurves._approach_prefix(spec, z, points, lambda load, f=force: load >= f)
            first = np.flatnonzero(whole >= force)[0]
            assert values.size < points.size and values[-1] >= force
            np.testing.assert_array_equal(values[: first + 1], whole[: first + 1])
    never = padcurves._approach_prefix(spec, z, points, lambda load: load > whole.max())
    np.testing.assert_array_equal(never, whole)


def test_force_turn_below_the_grid_is_a_parameter_error():
    from mcsim.model.errors import ParameterError

    spec, ens = cycle(np.linspace(3, 2, 3), realizations=1)
    with pytest.raises(ParameterError, match="extend the separations"):
        padcurves.force_turn(spec, ens.heights[0], 1.0)


@pytest.mark.parametrize("law", ["jkr", "dmt", "maugis-dugdale"])
@pytest.mark.parametrize("humid", [False, True])
def test_the_contact_laws_work_summed_summit_by_summit_is_the_integral_of_the_pads_load(law, humid):
    # The reference integrates the pad's whole contact load (the kernel's sums) between every
    # summit's edges with 40 Gauss-Legendre nodes each: measured within 3e-7 of a 64-node
    # rule on four sub-pieces per summit. pad_work's own 16 nodes per piece: within 1.2e-7 of
    # that (DMT's 1/D^2 tail the worst); the bound 1e-6 leaves their sum a factor 2 to spare.
    # Humid: the smooth surface in air at RH 0.7, whose pads turn deeper (~260 summits touch).
    from mcsim.physics.environment import Environment

    env = Environment(hamaker=1.6e-19, cutoff=0.2e-9, rh=0.7) if humid else None
    spec = MonteCarloSpec(SURFACES["smooth"], SILICON, np.linspace(-2, 5, 8), 30e-12, 3, 0,
                          law=law, cycle=True, environment=env)  # fmt: skip
    for r in range(2):
        z = padcurves.patch_heights(spec, r)
        d_t = padcurves.force_turn(spec, z, 1e6 * spec.area)[0]
        e = padcurves.contact_edges(spec)
        cuts = padcurves._intervals(spec, z, d_t, z.max() - min(e.reach, e.break_off, 0.0), e)
        x, w = np.polynomial.legendre.leggauss(40)
        half = np.diff(cuts)[:, None] / 2
        nodes = ((cuts[:-1, None] + cuts[1:, None]) / 2 + half * x).ravel()
        reference = np.sum((half * w).ravel() * padcurves.contact_load(spec, z, nodes, d_t))
        summed = np.sum(padcurves.contact_works(spec, z, d_t))
        assert summed == pytest.approx(reference, rel=1e-6)

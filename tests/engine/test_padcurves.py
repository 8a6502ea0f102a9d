"""Exact per-pad curves from heights drawn again (issue 23): mcsim.engine.pads.curves, Run.pull_off."""

import dataclasses
import math

import numpy as np
import pytest

from mcsim.engine.montecarlo import run_sums
from mcsim.engine.pads import bounds as padbounds
from mcsim.engine.pads import curves as padcurves
from mcsim.engine.pads import load as padload
from mcsim.engine.spec import MonteCarloSpec
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
        np.testing.assert_array_equal(padload.patch_heights(spec, r), ens.heights[r])


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
        dense = -padload.pad_load(spec, z, d, spec.turn * sigma).min()
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
        assert load >= force and padload.pad_load(spec, z, [d_t])[0] == load
        above = np.linspace(d_t + padload.XTOL * sigma, z.max() + sigma, 20001)
        assert np.all(padload.pad_load(spec, z, above) < force)


@pytest.mark.parametrize("law", ["jkr", "maugis-dugdale"])
def test_the_approach_loads_down_to_the_first_reaching_one_are_the_whole_grids_bit_for_bit(law):
    # force_turn evaluates only a prefix of its points; the kernel's sums depend on the set
    # of rows summed together, so the prefix must give the whole grid's numbers exactly.
    spec, ens = cycle(np.linspace(3, -2, 6), realizations=3, law=law)
    sigma = spec.surface.sigma
    points = np.linspace(4 * sigma, -2 * sigma, 3001)
    for z in ens.heights:
        whole = padload.pad_load(spec, z, points)
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
        z = padload.patch_heights(spec, r)
        d_t = padcurves.force_turn(spec, z, 1e6 * spec.area)[0]
        e = padload.contact_edges(spec)
        cuts = padload.smooth_intervals(spec, z, d_t, z.max() - min(e.reach, e.break_off, 0.0), e)
        x, w = np.polynomial.legendre.leggauss(40)
        half = np.diff(cuts)[:, None] / 2
        nodes = ((cuts[:-1, None] + cuts[1:, None]) / 2 + half * x).ravel()
        reference = np.sum((half * w).ravel() * padload.contact_load(spec, z, nodes, d_t))
        summed = np.sum(padcurves.contact_works(spec, z, d_t))
        assert summed == pytest.approx(reference, rel=1e-6)


# --- Humid pads: the branch and bound of force_turn and pull_off (issue 30, speed) ---------

from mcsim.model.params import RadiusByHeight  # noqa: E402
from mcsim.physics.environment import Environment  # noqa: E402
from mcsim.physics.laws import LAW_SETS, get_law_set  # noqa: E402

#: Law sets a pad can retract with: every registered one with a retraction and a load.
PAD_LAWS = sorted(n for n, law in LAW_SETS.items() if law.retract and "load" in law.names)
#: Materials for the law-set properties: silicon, and a softer, stickier one (Maugis
#: lambda ~7 instead of ~1.3, so the Maugis-Dugdale break-off moves into contact).
MATERIALS_FOR_LAWS = [SILICON, dataclasses.replace(SILICON, E1=40e9, E2=40e9, gamma=1.0)]


#: The surfaces of the humid pads: two presets, and the smooth one with a radius by height
#: of two bands, R x 1.6 up to s = 1.5 and x 0.5 above (a pad touches on summits from about
#: s = 0.4 to 3, in both bands; the report's scans have up to nine bands).
PAD_SURFACES = {
    "smooth": SURFACES["smooth"],
    "intermediate": SURFACES["intermediate"],
    "banded": dataclasses.replace(SURFACES["smooth"], radius_by_height=RadiusByHeight(
        (-1.0, 1.5, 4.0), (1.6, 0.5))),
}  # fmt: skip
#: Law sets and surfaces of the humid pads' tests: each law on the presets, and the report's
#: law (maugis-dugdale, a tabulated law) with a radius by height (each band's open gaps'
#: expectation costs a spec about a second, and the bounds of a band are its law's, checked
#: on the presets).
PRESET_CASES = [(law, surface) for surface in ("smooth", "intermediate") for law in PAD_LAWS]
HUMID_CASES = [*PRESET_CASES, ("maugis-dugdale", "banded")]


def humid(law, rh=0.7, surface="smooth", pads=3, seed=0):
    env = Environment(hamaker=1.6e-19, cutoff=0.2e-9, rh=rh)
    return MonteCarloSpec(PAD_SURFACES[surface], SILICON, np.linspace(-2, 5, 8), 30e-12, pads,
                          seed, law=law, cycle=True, environment=env)  # fmt: skip


def test_the_pad_laws_are_the_ones_with_a_retraction():
    assert PAD_LAWS == ["dmt", "jkr", "maugis-dugdale"]


def test_specs_of_one_surface_environment_and_range_share_one_open_gaps_table():
    # The table depends on the surface, the environment and its range in h only: specs of
    # other law sets, pad counts or seeds read the same one (made once), another humidity not.
    table = padload.open_gap_table(humid("jkr"))
    assert padload.open_gap_table(humid("dmt", pads=2, seed=7)) is table
    assert padload.open_gap_table(humid("maugis-dugdale", rh=0.9)) is not table


@pytest.mark.parametrize("material", MATERIALS_FOR_LAWS, ids=["silicon", "soft"])
@pytest.mark.parametrize("law", PAD_LAWS)
def test_every_pad_law_is_quasiconvex_on_each_branch_and_retracts_independently_of_its_history(
    law, material
):
    # The requirements of mcsim.physics.laws that padbounds.branches rests on, on a dense
    # grid: 0 up to the branch's lowest edge, then no rise down to the minimum, then no fall;
    # the retraction of a summit in contact the same for every delta_max; one out of contact
    # at the turn keeps its approach load. Tolerance of "no rise": 1e-12 of the largest |f|
    # (the laws' rounding; a real rise is the size of the load).
    ls = get_law_set(law)
    surface = SURFACES["smooth"]
    e = ls.edges_for(surface, material)
    scale = max(abs(x) for x in (e.reach, e.jump_in, e.break_off, *e.breakpoints))
    delta = np.concatenate([np.linspace(min(e.reach, e.break_off) - scale, 3 * scale, 20001),
                            np.geomspace(3 * scale, 1e3 * scale, 2001)])  # fmt: skip
    approach = ls.evaluate(delta, surface, material)["load"]
    curves = {"approach": (approach, e.reach)}
    for turn in (e.jump_in + 1e-3 * scale, 2 * scale, 1e3 * scale):
        below = delta <= turn
        retract = ls.evaluate(delta[below], surface, material, "retract", turn)["load"]
        curves[f"retract {turn:.3g}"] = (retract, min(e.reach, e.break_off))
        again = ls.evaluate(delta[below], surface, material, "retract", 2e3 * scale)["load"]
        np.testing.assert_array_equal(retract, again)
    for name, (f, low) in curves.items():
        x = delta[: f.size]
        assert np.all(f[x <= low] == 0), name
        tol = 1e-12 * np.max(np.abs(f))
        k = int(np.argmin(f))
        assert np.all(np.diff(f[: k + 1]) <= tol), name
        assert np.all(np.diff(f[k:]) >= -tol), name
    out_of_contact = delta <= e.jump_in
    kept = ls.evaluate(delta[out_of_contact], surface, material, "retract", e.jump_in)["load"]
    np.testing.assert_array_equal(kept, approach[out_of_contact])


@pytest.mark.parametrize(("law", "surface"), [(law, "smooth") for law in PAD_LAWS]
                         + [("jkr", "banded")])  # fmt: skip
def test_the_branches_bracket_their_minimum_and_jkr_gives_johnsons_forces(law, surface):
    # With a radius by height each band has its own radius, hence its own branches. The
    # minimum found on a grid of 2e5 points lies within one of its steps of the bracket
    # (where f is flat to rounding, the grid's lowest point may lie a rounding beyond).
    from mcsim.physics.surfaceenvironment import contact_adhesion

    spec = humid(law, surface=surface)
    parts = padload.contact_parts(spec)
    assert len(parts) == (2 if surface == "banded" else 1)
    for component, part in zip(spec.surface.components(), parts, strict=True):
        out, args = part.law.outputs[part.law.names.index("load")], part.args[0]
        approach, retract = padbounds.branches(part)
        for b, retracting in ((approach, False), (retract, True)):
            x = np.linspace(b.low, b.rising + (b.rising - b.low), 200001)[1:]
            state = np.full_like(x, 1e-6) if retracting else x
            f = out.law(x, state, *args) if out.stateful else out.law(x, *args)
            step = x[1] - x[0]
            assert b.low <= b.falling and b.falling - step <= x[np.argmin(f)] <= b.rising + step
            assert b.m <= f.min() and b.m >= f.min() * (1 + 2 * padbounds._MIN_MARGIN)
        if law == "jkr":
            # Johnson (1985, Eq. 5.60): -P_c = -1.5 pi w R on retraction; on approach the jump
            # in at delta = 0 lands at -8/9 P_c. Each within the margin of 1e-6 below. With van
            # der Waals the contact law's w is the interface's less its van der Waals share;
            # R the band's.
            w = contact_adhesion(SILICON.gamma, spec.environment)
            pc = 1.5 * math.pi * w * component.R
            assert approach.m == pytest.approx(-8 / 9 * pc, rel=2e-6)
            assert approach.m < -8 / 9 * pc
            assert retract.m == pytest.approx(-pc, rel=2e-6) and retract.m < -pc


def _curve(spec, z, d_turn):
    """An empty humid curve of the summits ``z``: on approach (``d_turn`` None), or retracting
    after ``d_turn`` with the summits in contact then on their band's retraction branch and
    the others on its approach branch."""
    if d_turn is None:
        return padbounds._approach(spec, z, 0.0, 0.0)
    curve = padbounds._retraction(spec, z, d_turn)
    curve.lower = False  # both bounds
    return curve


@pytest.mark.parametrize(("law", "surface"), HUMID_CASES)
def test_the_bounds_of_a_humid_curve_hold_every_value_between_its_points(law, surface):
    # The proven bound (padbounds._Curve.bounds): every value of the pad's net load in a gap
    # between two evaluated points lies between the gap's lower and upper bound. Checked on
    # 300 dense points in each of the gaps of random separations (many summits crossing their
    # edges in each), on approach and on retraction; slack 1e-12 of the pad's largest sum
    # (the sums' rounding, batched differently).
    spec = humid(law, rh=0.9, surface=surface)
    rng = np.random.default_rng(5)
    sigma = spec.surface.sigma
    for r in range(2):
        z = padload.patch_heights(spec, r)
        d_t = padcurves.force_turn(spec, z, 1e6 * spec.area)[0]
        for retract in (False, True):
            low = d_t if retract else d_t - sigma
            x = np.sort(np.concatenate([low + rng.uniform(0, 2, 12) ** 2 * sigma, [low]]))
            curve = _curve(spec, z, d_t if retract else None)
            curve.add(x)
            upper, lower = curve.bounds()
            inside = x[:-1, None] + np.diff(x)[:, None] * np.linspace(0, 1, 300)[None, :]
            values = padload.pad_load(spec, z, inside.ravel(), d_t if retract else None)
            values = values.reshape(inside.shape)
            slack = 1e-12 * np.max(np.abs(curve.sums))
            assert np.all(values.max(axis=1) <= upper + slack)
            assert np.all(values.min(axis=1) >= lower - slack)


@pytest.mark.parametrize(("law", "surface"), PRESET_CASES)
def test_the_bounds_of_a_narrow_gap_close_in_on_the_curve(law, surface):
    # As the gaps narrow the bounds must close in on the curve, or the search splits on down
    # to XTOL wherever the curve comes near the force (DMT's pads on the smooth surface once
    # evaluated 60 000 points): gaps 1e-9 σ wide at 200 random separations, on approach and
    # retraction, have bounds within 1e-7 of the pad's largest sum of each other (measured
    # 8e-9 at most; what is left: the margin on each branch's minimum for the summits
    # between its falling and rising points, and the open gaps' slope times the width).
    spec = humid(law, rh=0.7, surface=surface)
    sigma = spec.surface.sigma
    rng = np.random.default_rng(11)
    z = padload.patch_heights(spec, 0)
    d_t = padcurves.force_turn(spec, z, 1e6 * spec.area)[0]
    for retract in (False, True):
        x = d_t + rng.uniform(-0.5 if not retract else 0.0, 2.0, 200) * sigma
        x = np.sort(np.concatenate([x, x + 1e-9 * sigma]))
        curve = _curve(spec, z, d_t if retract else None)
        curve.add(x)
        upper, lower = curve.bounds()
        narrow = np.diff(curve.x) < 2e-9 * sigma
        assert np.all(upper[narrow] - lower[narrow] <= 1e-7 * np.max(np.abs(curve.sums)))


@pytest.mark.parametrize(("law", "surface"), HUMID_CASES)
def test_humid_turns_and_pull_offs_are_those_of_a_dense_evaluation_of_the_pads_curve(law, surface):
    # Brute force: the turn is the largest d reaching the force (no point of a dense grid
    # above it by more than XTOL reaches it) and the pull-off the most tensile value of the
    # retraction (no dense point, nor any point just either side of an edge a summit crosses,
    # is more tensile: 1e-9 relative, the rounding of sums batched otherwise and the location
    # to XTOL; and a grid of 1e-4 h comes within 1 %, it can miss the square-root cusp of a
    # summit at its break-off). RH 0.3, 0.7, 0.9; preloads 0, 1 MPa. With a radius by height
    # RH 0.9 only, the bounds' test's spec (each band's open gaps' table costs).
    sigma = PAD_SURFACES[surface].sigma
    banded = surface == "banded"
    for rh in (0.9,) if banded else (0.3, 0.7, 0.9):
        pads = {} if banded else {"pads": 2, "seed": int(rh * 10)}
        spec = humid(law, rh=rh, surface=surface, **pads)
        for preload, r in ((0.0, 0), (1e6, 1)):
            z = padload.patch_heights(spec, r)
            force = preload * spec.area
            d_t, load = padcurves.force_turn(spec, z, force)
            assert (load > force) if force == 0 else (load >= force)
            # up to the first touch (a pad rests on its summits: force_turn)
            touch = z.max() - min(padload.contact_edges(spec).jump_in, 0.0)
            above = np.linspace(d_t + padload.XTOL * sigma, touch, 30001)
            dense = padload.pad_load(spec, z, above)
            assert np.all((dense <= force) if force == 0 else (dense < force))
            pull, at = padcurves.pull_off(spec, z, d_t)
            # and both one-sided limits at every edge a summit crosses, its band's (the
            # search splits the retraction just below each, padbounds.humid_pull_off)
            band, cuts = padload.summit_bands(spec, z), []
            for k, part in enumerate(padload.contact_parts(spec)):
                e = part.edges
                in_delta = np.array([e.reach, e.jump_in, e.break_off, *e.breakpoints])
                cuts.append((z[band == k, None] - in_delta[None, :]).ravel())
            cuts = np.concatenate(cuts)
            cuts = cuts[cuts > d_t]
            side = 2 * padload.EDGE * sigma
            # up to where the summits' caps reach (u_c above the highest; the menisci between
            # the adsorbed films pull the pad there at RH 0.9), at steps of about 1e-4 h
            top = z.max() + max(2 * sigma, -spec.edges.reach)
            grid = np.linspace(d_t, top, int((top - d_t) / sigma * 1e4) + 1)
            d = np.concatenate([grid, cuts - side, cuts + side])
            tensile = -padload.pad_load(spec, z, d, d_t).min()
            assert tensile <= pull * (1 + 1e-9)
            assert tensile >= pull * (1 - 1e-2)
            assert -padload.pad_load(spec, z, [at], d_t)[0] == pytest.approx(pull, rel=1e-12)


@pytest.mark.parametrize("law", ["jkr", "maugis-dugdale"])
def test_a_humid_turn_on_a_narrow_peak_just_before_a_jump_in_is_not_stepped_over(law):
    # Just above a summit's jump-in the approach load peaks (the summit then pulls the pad
    # down by its jump). A force between that peak and everything above it is reached only
    # within the jump-in's one-sided limit: force_turn must find it there, not lower down.
    spec = humid(law)
    sigma = spec.surface.sigma
    e = padload.contact_edges(spec)
    found = 0
    for r in range(spec.realizations):  # the pads have such peaks to test on
        if found >= 2:
            break
        z = padload.patch_heights(spec, r)
        d_t = padcurves.force_turn(spec, z, 1e6 * spec.area)[0]
        for c in np.sort(z - e.jump_in)[::-1]:
            if not d_t < c < d_t + 0.3 * sigma:
                continue
            peak = padload.pad_load(spec, z, [c + padload.EDGE * sigma])[0]
            far = np.linspace(c + 1e-3 * sigma, z.max() + 10 * sigma, 40001)  # beyond: load < 0
            above = padload.pad_load(spec, z, far)
            if peak > max(above.max(), 0.0):
                force = (peak + above.max()) / 2
                turn, load = padcurves.force_turn(spec, z, force)
                assert c < turn < c + 1e-3 * sigma and load >= force
                found += 1
    assert found >= 2


@pytest.mark.parametrize(
    ("surface", "rh", "preload", "pads"),
    [("smooth", 0.7, 0.0, (18, 24)), ("intermediate", 0.3, 1e6, (25,))],
)
def test_a_humid_pull_off_in_an_interval_whose_interior_points_are_not_the_lowest_is_found(
    surface, rh, preload, pads
):
    # The pull-off zooms first on the intervals whose interior points are lowest; these pads'
    # minimum lies in another one, where that zoom alone missed it by 1.4e-5 and 1.8e-5
    # relative (smooth) and 5.9 % (intermediate, a few summits touching): the intervals
    # whose bound lies at or below the lowest value met are zoomed on too. Reference: as the
    # dense test above. (Pads of the seed of humid()'s specs of 3 pads.)
    spec = humid("maugis-dugdale", rh=rh, surface=surface)
    sigma = spec.surface.sigma
    for r in pads:
        z = padload.patch_heights(spec, r)
        d_t = padcurves.force_turn(spec, z, preload * spec.area)[0]
        pull = padcurves.pull_off(spec, z, d_t)[0]
        top = z.max() + max(2 * sigma, -spec.edges.reach)
        d = np.linspace(d_t, top, int((top - d_t) / sigma * 1e4) + 1)
        tensile = -padload.pad_load(spec, z, d, d_t).min()
        assert pull * (1 - 1e-2) <= tensile <= pull * (1 + 1e-9)

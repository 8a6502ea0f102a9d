"""Pads in humid air: every pad answer takes the environment (issue 30).

A pad's net load is its summits' contact load less their caps' van der Waals and meniscus
forces and the open gaps' attraction times its area (docs/physics.md, section 'The
environment: summits and open gaps'); force control balances it, ``preload = 0`` is a pad
resting under its own attraction, and its pull-off and work of separation follow from it.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from mcsim.engine.pads import curves as padcurves
from mcsim.engine.pads import load as padload
from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.environment import Environment
from mcsim.physics.laws import get_law_set
from mcsim.physics.laws.attraction import capillary_summit, vdw_summit
from mcsim.physics.surfaceenvironment import (
    open_gap_pressures,
    open_gap_works,
    summit_parameters,
    vdw_share,
)
from mcsim.studies.simulation import simulate
from mcsim.studies.sweeps import sweep

SMOOTH, SILICON = SURFACES["smooth"], MATERIALS["silicon"]
HUMID = Environment(hamaker=1.6e-19, cutoff=0.2e-9, rh=0.7)
H = np.linspace(-2.0, 5.0, 8)


def spec(environment=HUMID, area=30e-12, pads=6, seed=4):
    return MonteCarloSpec(SMOOTH, SILICON, H, area, pads, seed, "jkr", cycle=True,
                          environment=environment)  # fmt: skip


def test_the_net_load_of_a_one_summit_pad_is_its_laws_less_the_open_gaps():
    s = spec()
    z = np.array([2e-9])
    d = np.linspace(-1e-9, 12e-9, 27)
    p = summit_parameters(SMOOTH, HUMID)
    # one interface: the contact law carries w less the van der Waals share A/(12π D0²)
    shared = dataclasses.replace(SILICON, gamma=SILICON.gamma - vdw_share(SILICON.gamma, HUMID))
    contact = get_law_set("jkr").evaluate(z - d, SMOOTH, shared)["load"]
    caps = vdw_summit(z - d, HUMID.hamaker, SMOOTH.R, p["cutoff"], p["band"], p["retardation"])
    caps += capillary_summit(z - d, p["laplace"], SMOOTH.R, p["wet_floor"], p["gap_k"])
    gaps = open_gap_pressures(d / SMOOTH.sigma, SMOOTH, HUMID)
    expected = contact - caps - s.area * (gaps["vdw"] + gaps["capillary"])
    # the open gaps come from a cubic spline within 1e-9 of their largest value
    scale = s.area * np.max(gaps["vdw"] + gaps["capillary"])
    np.testing.assert_allclose(padload.pad_load(s, z, d), expected, rtol=1e-12,
                               atol=1e-9 * scale)  # fmt: skip


def test_the_open_gaps_table_is_within_1e_9_of_the_function():
    s = spec()
    h = np.random.default_rng(2).uniform(H.min(), 14.0, 500)
    exact = open_gap_pressures(h, SMOOTH, HUMID)
    exact = exact["vdw"] + exact["capillary"]
    np.testing.assert_allclose(padload.open_gaps(s)(h), exact, rtol=0,
                               atol=1e-9 * np.max(np.abs(exact)))  # fmt: skip


def test_the_open_gaps_work_table_is_the_integral_of_the_pressure_within_4e_9_of_the_work():
    s = spec()
    h = np.random.default_rng(3).uniform(H.min() - 1.5, 16.0, 200)  # outside the table too
    exact = open_gap_works(h, SMOOTH, HUMID)
    exact = exact["vdw"] + exact["capillary"]
    # the spline is within 1e-9 of the pressure's largest value (test above), so its integral
    # over the table (~20 in h) within 2e-8 σ·max p; the largest work is ~5 σ·max p (measured
    # 5.2 here): within 4e-9 of it (measured 9e-14)
    np.testing.assert_allclose(padload.open_gap_work(s)(h), exact, rtol=0,
                               atol=4e-9 * np.max(np.abs(exact)))  # fmt: skip


def test_a_pad_at_zero_preload_rests_where_its_net_load_turns_compressive_below_its_first_touch():
    s = spec()
    sigma = SMOOTH.sigma
    for r in range(s.realizations):
        z = padload.patch_heights(s, r)
        d_t, load = padcurves.force_turn(s, z, 0.0)
        assert load > 0 and d_t < z.max()
        # just above the turn (beyond the bisection's tolerance) the net load is not compressive
        above = padload.pad_load(s, z, [d_t + 2 * padload.XTOL * sigma])[0]
        assert above <= 0
        # and from far away down to there it never was (the first compressive point)
        d = np.linspace(d_t + 2 * padload.XTOL * sigma, z.max() + 10e-9, 4001)
        assert np.all(padload.pad_load(s, z, d) <= 0)


def test_pads_at_every_humidity_are_drawn_from_the_same_summits():
    heights = [padload.patch_heights(spec(dataclasses.replace(HUMID, rh=rh)), 1)
               for rh in (0.0, 0.5, 0.9)]  # fmt: skip
    heights.append(padload.patch_heights(spec(dataclasses.replace(HUMID, hamaker=3e-19)), 1))
    for z in heights[1:]:
        np.testing.assert_array_equal(z, heights[0])


def test_a_pads_work_of_separation_is_the_integral_of_its_net_force():
    s = spec(pads=2)
    z = padload.patch_heights(s, 0)
    d_t, _ = padcurves.force_turn(s, z, 1e6 * s.area)
    top = z.max() + summit_parameters(SMOOTH, HUMID)["band"]
    d = np.linspace(d_t, top, 400_001)
    net = padload.pad_load(s, z, d, d_t)
    far = open_gap_pressures(top / SMOOTH.sigma, SMOOTH, HUMID)  # beyond: the open gaps alone
    from mcsim.physics.surfaceenvironment import open_gap_works

    tail = open_gap_works(np.float64(top / SMOOTH.sigma), SMOOTH, HUMID)
    expected = -np.trapezoid(net, d) / s.area + float(tail["vdw"] + tail["capillary"])
    assert far["vdw"] > 0
    # trapezoid on 4e5 steps of 4e-14 m across the pad's kinks (square-root edges of jkr):
    # ~1e-6 of the work, measured (the bound: 5x that); pad_work's own error is ~1e-7
    assert padcurves.pad_work(s, z, d_t) == pytest.approx(expected, rel=5e-6)


def test_a_pads_work_is_exact_where_the_caps_kinks_fall_inside_the_contact_laws_intervals():
    # The intermediate surface (sigma = 6.8 nm): the caps' kinks (D0, g_K, u_c) lie inside
    # the intervals between the contact law's edges. The reference cuts at every edge, the
    # caps' included, with 40 Gauss-Legendre nodes each; integrating the caps across their
    # kinks instead missed it by 2.7e-3 (measured, the seed below). Tolerance: the contact
    # law's quadrature, ~1e-7 relative (padcurves.contact_works' docstring).
    s = MonteCarloSpec(SURFACES["intermediate"], SILICON, H, 30e-12, 10, 7, "jkr", cycle=True,
                       environment=HUMID)  # fmt: skip
    z = padload.patch_heights(s, 6)
    d_t, _ = padcurves.force_turn(s, z, 1e6 * s.area)
    top = z.max() + summit_parameters(s.surface, HUMID)["band"]
    cuts = padload.smooth_intervals(s, z, d_t, top)
    x, w = np.polynomial.legendre.leggauss(40)
    half = np.diff(cuts)[:, None] / 2
    nodes = ((cuts[:-1, None] + cuts[1:, None]) / 2 + half * x).ravel()
    from mcsim.physics.surfaceenvironment import open_gap_works

    tail = open_gap_works(np.float64(top / s.surface.sigma), s.surface, HUMID)
    dense = -np.sum((half * w).ravel() * padload.pad_load(s, z, nodes, d_t)) / s.area
    dense += float(tail["vdw"] + tail["capillary"])
    assert padcurves.pad_work(s, z, d_t) == pytest.approx(dense, rel=1e-6)


def test_humidity_raises_the_work_and_a_humid_run_file_gives_humid_pads(tmp_path):
    dry = simulate(SMOOTH, SILICON, H, area="30 um^2", realizations=5, seed=2, law="jkr",
                   cycle=True, preload=0, environment=dataclasses.replace(HUMID, rh=0.0),
                   out=tmp_path / "dry.h5")  # fmt: skip
    wet = simulate(SMOOTH, SILICON, H, area="30 um^2", realizations=5, seed=2, law="jkr",
                   cycle=True, preload=0, environment=HUMID, out=tmp_path / "wet.h5")  # fmt: skip
    from mcsim.store.runfile import read_run

    back = read_run(wet.path).pull_off()
    np.testing.assert_array_equal(back.force, wet.pull_off().force)
    assert np.all(back.force > dry.pull_off().force)  # the same summits, now with menisci
    assert back.preload == 0
    # `mcsim pads` of it says once that the model estimate is not given there
    import io
    from contextlib import redirect_stderr, redirect_stdout

    from mcsim.cli.main import main

    err = io.StringIO()
    with redirect_stderr(err), redirect_stdout(io.StringIO()):
        assert main(["pads", str(wet.path), "--restoring-force", "1uN"]) == 0
    assert err.getvalue().count("p_stick_model is not given") == 1


def test_a_pads_sweep_over_rh_stores_the_pads_work_and_no_model_estimate():
    result = sweep(SMOOTH, SILICON, {"rh": [0.0, 0.5, 0.9]}, law="jkr", h=H, pads=4,
                   restoring_force="1 mN", preload=0, area="30 um^2", seed=5,
                   environment=HUMID)  # fmt: skip
    data = result.data
    work = np.asarray(data["work_of_separation_mean"])
    assert np.all(np.diff(work) > 0)  # the same pads at every RH, more liquid
    assert result.units["work_of_separation_mean"] == "J/m^2"
    for q in ("std", "q05", "q50", "q95"):
        assert np.all(np.isfinite(np.asarray(data[f"work_of_separation_{q}"])))
    assert np.all(np.isnan(np.asarray(data["p_stick_model"])))


def test_pads_below_the_bridges_onset_are_evaluated_once_with_each_rhs_own_numbers(monkeypatch):
    # RH 0, 0.1 and 0.25 lie below the liquid bridges' onset (RH_dry = 0.30: the adsorbed
    # film is still no thicker than its structured layers), where the humidity acts on
    # nothing: the three points draw the same pads (the environment's dimension shares their
    # stream) under the same physics, and the sweep evaluates them once. Each point's numbers
    # are those of its own RH's pads (a sweep of it alone, each pad evaluated at that RH),
    # bit for bit; RH 0.5 has pads of its own.
    import mcsim.studies.sweeppoint

    below = [0.0, 0.1, 0.25]
    assert not any(dataclasses.replace(HUMID, rh=rh).has_capillary for rh in below)
    options = dict(law="jkr", h=H, pads=4, restoring_force="1 mN", preload=0, area="30 um^2",
                   seed=5, environment=HUMID)  # fmt: skip
    evaluated = []
    pads = mcsim.studies.sweeppoint.finite_pads

    def counted(spec, *args, **kwargs):
        evaluated.append(spec.environment.rh)
        return pads(spec, *args, **kwargs)

    monkeypatch.setattr(mcsim.studies.sweeppoint, "finite_pads", counted)
    data = sweep(SMOOTH, SILICON, {"rh": [*below, 0.5]}, **options, workers=2).data
    assert sorted(evaluated) == [0.0, 0.5]
    monkeypatch.setattr(Environment, "acting", lambda self: self)  # each RH's own pads
    for i, rh in enumerate([*below, 0.5]):
        alone = sweep(SMOOTH, SILICON, {"rh": [rh]}, **options).data
        for name in ("pull_off_mean", "pull_off_std", "work_of_separation_mean", "p_stick"):
            assert np.asarray(data[name])[i] == np.asarray(alone[name])[0], (rh, name)
    assert evaluated[2:] == [*below, 0.5]


def test_points_whose_pads_act_alike_are_one_task_in_the_order_of_the_first(monkeypatch):
    # The README's report ran RH 0 and RH 0.3 (below the bridges' onset: the same pads) on
    # two worker threads: the second waited the whole of the first's importance sampling
    # for its result, holding a worker (and on Dask, whose processes do not share it,
    # evaluated the pads again). Such points are now one task, sent where the first is.
    import mcsim.studies.sweeps

    tasks = []
    evaluate_batch = mcsim.studies.sweeps.evaluate_batch

    def recorded(points, config):
        tasks.append([p.environment.rh for p in points])
        return evaluate_batch(points, config)

    monkeypatch.setattr(mcsim.studies.sweeps, "evaluate_batch", recorded)
    options = dict(law="jkr", h=H, pads=2, restoring_force="1 mN", preload=0, area="30 um^2",
                   seed=5, environment=HUMID, workers=1)  # fmt: skip
    sweep(SMOOTH, SILICON, {"rh": [0.0, 0.5, 0.1, 0.9, 0.25]}, **options)
    assert tasks == [[0.0, 0.1, 0.25], [0.5], [0.9]]


def test_worker_processes_give_the_numbers_of_threads(monkeypatch):
    # scheduler="processes" (mcsim report's default): the points on spawned processes of this
    # machine (a pad's search holds the GIL much of the time: threads gain little there),
    # here on 9 pads in all (below POOL_PADS a sweep would keep them in its own process)
    import mcsim.studies.sweeps

    monkeypatch.setattr(mcsim.studies.sweeps, "POOL_PADS", 1)
    options = dict(law="jkr", h=H, pads=3, restoring_force="1 mN", preload=0, area="30 um^2",
                   seed=5, environment=HUMID, workers=2)  # fmt: skip
    grid = {"rh": [0.0, 0.2, 0.6]}
    threads = sweep(SMOOTH, SILICON, grid, **options)
    processes = sweep(SMOOTH, SILICON, grid, **options, scheduler="processes")
    assert set(processes.data) == set(threads.data)
    for name, values in threads.data.items():
        np.testing.assert_array_equal(processes.data[name], values, err_msg=name)

"""A summit radius that depends on height (issue 32, point 3): a surface of several radii is the
sum of plain GW populations, one per band of heights, in the analytic integrals, the Monte Carlo,
the pads and the files."""

import dataclasses
import io
from contextlib import redirect_stderr, redirect_stdout

import numpy as np
import pytest
from scipy import integrate

import mcsim
from mcsim.cli.main import main
from mcsim.engine.montecarlo import run_sums
from mcsim.engine.pads import curves as padcurves
from mcsim.engine.pads import load as padload
from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.errors import ParameterError
from mcsim.model.params import RadiusByHeight, combine_surfaces
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.analytic import gw_curves, hertz_area_fraction
from mcsim.physics.environment import Environment
from mcsim.physics.laws import get_law_set
from mcsim.topography.empirical import Empirical

SMOOTH, SILICON = SURFACES["smooth"], MATERIALS["silicon"]
#: Two bands, the taller sharper: R x 1.8 below s = 0.5, R x 0.6 above.
TWO = RadiusByHeight((-1.0, 0.5, 2.0), (1.8, 0.6))
H = np.linspace(-1.0, 3.0, 9)


def with_bands(surface=SMOOTH, bands=TWO):
    return dataclasses.replace(surface, radius_by_height=bands)


HISTOGRAM = Empirical.from_samples(np.random.default_rng(4).standard_normal(400) * 1e-9)
MEASURED = dataclasses.replace(SMOOTH, heights=HISTOGRAM)


@pytest.mark.parametrize("surface", [SMOOTH, MEASURED], ids=["gaussian", "histogram"])
@pytest.mark.parametrize("law", ["seed", "jkr", "dmt", "maugis-dugdale"])
def test_bands_of_one_radius_are_the_plain_surface(surface, law):
    # Every factor 1: the bands' integrals, each cut exactly at its edges, add up to the whole
    # surface's. They differ by the quadratures' own errors (other panels): measured 1e-15 of
    # each curve's largest value for the closed-form laws, 1.2e-11 for maugis-dugdale (its
    # tabulated law); bound 1e-10 of it (a net load crossing zero is a difference, good to
    # its terms' size only).
    same = with_bands(surface, RadiusByHeight((-1.5, -0.2, 0.4, 1.3), (1.0, 1.0, 1.0)))
    branches = [("approach", None)] + ([("retract", -1.0)] if law != "seed" else [])
    for branch, turn in branches:
        plain = gw_curves(surface, SILICON, H, law, branch, turn).values
        split = gw_curves(same, SILICON, H, law, branch, turn).values
        for name, values in plain.items():
            scale = 1e-10 * np.nanmax(np.abs(values), initial=0.0)
            np.testing.assert_allclose(split[name], values, rtol=1e-10, atol=scale, err_msg=name)
    np.testing.assert_allclose(hertz_area_fraction(same, H), hertz_area_fraction(surface, H),
                               rtol=1e-10)  # fmt: skip


def test_the_analytic_load_sums_each_band_with_its_own_radius():
    # Reference: scipy's adaptive quadrature of eta * integral phi(s) P(delta; R(s)) ds, with the
    # band edge as a break point, against the bands' Gauss-Legendre rules (both ~1e-10).
    law = get_law_set("seed")
    surface = with_bands()
    p = law.outputs[0]
    for h in (-0.5, 0.7, 1.9):
        reference = 0.0
        for part in surface.components():
            args = law.arguments(part, SILICON)[0]
            lo, hi = max(part.heights.lo, h), min(part.heights.hi, h + 12)
            if lo >= hi:
                continue

            def integrand(s, a=args, h=h, band=part.heights):
                return p.law((s - h) * SMOOTH.sigma, *a) * band.pdf(s)

            reference += integrate.quad(integrand, lo, hi, epsabs=0, epsrel=1e-12, limit=200)[0]
        reference *= SMOOTH.eta / SILICON.K
        got = gw_curves(surface, SILICON, [h], "seed").values["P"][0]
        assert got == pytest.approx(reference, rel=1e-9)


def test_the_monte_carlo_of_bands_agrees_with_their_analytic_curves():
    # 200 patches of 300 um^2 (~5100 summits), jkr approach and retraction: every estimate
    # within 5 standard errors of the bands' analytic curves.
    run = mcsim.simulate(with_bands(), SILICON, H, area="300 um^2", realizations=200, seed=3,
                         law="jkr", cycle=True)  # fmt: skip
    z = run.compare().z.to_numpy()
    assert np.all(np.abs(z[np.isfinite(z)]) < 5)
    # and the bands matter: with one radius the same sums would be off
    plain = gw_curves(SMOOTH, SILICON, H, "jkr").values["area"]
    assert np.max(np.abs(run.compare().query("quantity == 'area'").analytic[: H.size] - plain)) > 0


def test_the_sums_of_bands_are_bit_identical_whatever_the_chunks_and_workers():
    spec = MonteCarloSpec(with_bands(), SILICON, H, 3000e-12, 4, 11, "jkr", cycle=True)
    one = run_sums(spec, workers=1, chunk_size=1 << 16)
    two = run_sums(spec, workers=2, chunk_size=1 << 17)
    np.testing.assert_array_equal(one.sums, two.sums)


def test_a_pads_pull_off_and_work_sum_each_band_with_its_radius():
    spec = MonteCarloSpec(with_bands(), SILICON, H, 30e-12, 3, 2, "jkr", cycle=True)
    sigma = SMOOTH.sigma
    for r in range(3):
        z = padload.patch_heights(spec, r)
        d_t = padcurves.force_turn(spec, z, 1e6 * spec.area)[0]
        force = padcurves.pull_off(spec, z, d_t)[0]
        # the load is the sum of each band's summits under their own radius
        band = TWO.band_of(z / sigma)
        d = np.linspace(d_t, z.max() + sigma, 20001)
        specs = [MonteCarloSpec(part, SILICON, H, 30e-12, 3, 2, "jkr", cycle=True)
                 for part in with_bands().components()]  # fmt: skip
        parts = sum(padload.contact_load(s, z[band == k], d, d_t) for k, s in enumerate(specs))
        load = padload.pad_load(spec, z, d, d_t)
        # the same summits summed in other batches: rounding only
        np.testing.assert_allclose(load, parts, rtol=1e-12, atol=1e-18)
        # the exact pull-off lies at or below a dense evaluation's minimum (1e-6: the one-sided
        # limits at square-root break-offs, padload.EDGE)
        assert -force <= load.min() + 1e-6 * force and force > 0
        # the work summed summit by summit against the trapezoid rule on the pad's load: the
        # rule's own error on 2e4 steps across the break-offs' jumps measured 1.2e-5; bound 4x
        dense = -np.trapezoid(load, d) / spec.area
        assert padcurves.pad_work(spec, z, d_t) == pytest.approx(dense, rel=5e-5)


def test_a_run_file_keeps_the_bands_and_its_pads_use_them(tmp_path):
    out = tmp_path / "run.h5"
    surface = with_bands()
    run = mcsim.simulate(surface, SILICON, H, area="30 um^2", realizations=3, seed=2, law="jkr",
                         cycle=True, out=out)  # fmt: skip
    again = mcsim.read_run(out)
    assert again.spec.surface == surface and again.spec == run.spec
    np.testing.assert_array_equal(again.pull_off().force, run.pull_off().force)


HUMID = Environment(hamaker=1.6e-19, cutoff=0.2e-9, rh=0.7)


def test_in_humid_air_each_band_has_its_caps_and_bands_of_one_radius_are_the_plain_surface():
    # Each band's summits carry caps of their own radius (band edge D0 + 1/(2 pi R_k eta)); the
    # open gaps are bounded by the band edge of the summits' mean curvature, 1/sum p_k/R_k (and
    # Nayak's estimates of rq and the summit offset take it), which with every factor 1 is R:
    # the plain surface's curves (bound as above).
    same = with_bands(SMOOTH, RadiusByHeight((-1.5, -0.2, 0.4, 1.3), (1.0, 1.0, 1.0)))
    plain = gw_curves(SMOOTH, SILICON, H, "jkr", environment=HUMID).values
    split = gw_curves(same, SILICON, H, "jkr", environment=HUMID).values
    for name, values in plain.items():
        scale = 1e-10 * np.nanmax(np.abs(values), initial=0.0)
        np.testing.assert_allclose(split[name], values, rtol=1e-10, atol=scale, err_msg=name)
    # every band sharper by one factor: the plain surface of that radius, caps' band edges and
    # the open gaps' included
    sharper = with_bands(SMOOTH, RadiusByHeight((-1.5, -0.2, 0.4, 1.3), (0.6, 0.6, 0.6)))
    scaled = gw_curves(dataclasses.replace(SMOOTH, R=0.6 * SMOOTH.R), SILICON, H, "jkr",
                       environment=HUMID).values  # fmt: skip
    banded = gw_curves(sharper, SILICON, H, "jkr", environment=HUMID).values
    for name, values in scaled.items():
        scale = 1e-10 * np.nanmax(np.abs(values), initial=0.0)
        np.testing.assert_allclose(banded[name], values, rtol=1e-10, atol=scale, err_msg=name)
    surface = with_bands()
    mass = [float(p.heights.sf(-np.inf)) for p in surface.components()]
    radius = surface.mean_curvature_radius
    assert radius == pytest.approx(1 / (mass[0] / 1.8 + mass[1] / 0.6) * SMOOTH.R, rel=1e-14)


def test_the_humid_monte_carlo_of_bands_agrees_with_their_analytic_curves():
    # 300 patches of 300 um^2 at RH 0.7: contact, caps (vdw, capillary) within 5 SE.
    run = mcsim.simulate(with_bands(), SILICON, H[::2], area="300 um^2", realizations=300,
                         seed=4, law="jkr", cycle=True, environment=HUMID)  # fmt: skip
    table = run.compare()
    assert {"vdw", "capillary"} <= set(table.quantity)
    z = table.z.to_numpy()
    assert np.all(np.abs(z[np.isfinite(z)]) < 5)
    # the comparison's caps (the law set's outputs, band by band) are the environment's own
    # expectation of each band's caps (mcsim.physics.surfaceenvironment): the same integrals
    # by two routes, measured equal to 2e-16 (caps given the whole surface's band edge fail it)
    from mcsim.physics.surfaceenvironment import environment_curves

    caps = environment_curves(H[::2], with_bands(), HUMID)
    for term in ("vdw", "capillary"):
        got = table.query(f"quantity == '{term}' and branch == 'approach'").analytic.to_numpy()
        np.testing.assert_allclose(got, caps[f"{term}_caps"] / SILICON.K, rtol=1e-12)


def test_a_radius_by_height_is_refused_where_it_is_not_modelled():
    surface = with_bands()
    with pytest.raises(ParameterError, match="on the CPU only"):
        MonteCarloSpec(surface, SILICON, H, 30e-12, 1, 0, "jkr", device="cuda")
    with pytest.raises(ParameterError, match="cannot be combined"):
        combine_surfaces(surface, SMOOTH, eta=1e13)


@pytest.mark.parametrize(
    "edges, factors, message",
    [
        ((0.0,), (), "at least 2"),
        ((0.0, 1.0), (1.0, 2.0), "2 factors need 3 edges"),
        ((1.0, 0.0), (1.0,), "strictly increasing"),
        ((0.0, float("nan")), (1.0,), "finite"),
        ((0.0, 1.0), (0.0,), "factor = 0.0 is out of range"),
        ((0.0, 1.0), ("x",), "must be numbers"),
        (tuple(range(258)), (1.0,) * 257, "257 bands is out of range"),
    ],
)
def test_bad_bands_are_one_clear_error(edges, factors, message):
    with pytest.raises(ParameterError, match=message):
        RadiusByHeight(edges, factors)


def test_a_bad_bands_table_in_a_surface_file_is_one_line(tmp_path):
    toml = tmp_path / "s.toml"
    toml.write_text('[surface]\nsigma = "1.4 nm"\nR = "1.7 um"\neta = "17 um^-2"\n\n'
                    "[surface.radius_by_height]\nedges = [0, 1]\nfactors = [5000]\n")  # fmt: skip
    err = io.StringIO()
    with redirect_stderr(err):
        code = main(["analytic", "--surface", str(toml), "--h=1"])
    assert code == 2 and err.getvalue().count("\n") == 1
    assert "radius_by_height" in err.getvalue() and "5000" in err.getvalue()


def test_pads_of_bands_say_the_model_is_not_given_rather_than_warn_about_nan(tmp_path):
    out = tmp_path / "run.h5"
    mcsim.simulate(with_bands(), SILICON, H, area="30 um^2", realizations=5, seed=2, law="jkr",
                   cycle=True, out=out)  # fmt: skip
    err = io.StringIO()
    with redirect_stderr(err), redirect_stdout(io.StringIO()):
        code = main(["pads", str(out), "--restoring-force", "1uN"])
    assert code == 0 and "p_stick_model is not given" in err.getvalue()
    assert "warning: p_stick_model nan" not in err.getvalue()


def test_a_humid_pad_of_bands_sums_each_summits_caps_with_its_own_radius():
    # The net load against a direct sum: the contact law per band (checked above) less each
    # summit's van der Waals and meniscus forces with its band's radius and band edge
    # (mcsim.physics.laws.attraction, summit by summit) less the open gaps' pressure.
    from mcsim.physics.laws.attraction import capillary_summit, vdw_summit
    from mcsim.physics.surfaceenvironment import open_gap_works, summit_parameters

    spec = MonteCarloSpec(with_bands(), SILICON, H, 30e-12, 2, 3, "jkr", cycle=True,
                          environment=HUMID)  # fmt: skip
    sigma = SMOOTH.sigma
    for r in range(2):
        z = padload.patch_heights(spec, r)
        d_t = padcurves.force_turn(spec, z, 1e6 * spec.area)[0]
        band = TWO.band_of(z / sigma)
        top = z.max() + max(summit_parameters(p, HUMID)["band"] for p in with_bands().components())
        d = np.linspace(d_t, top, 50001)
        caps = np.zeros_like(d)
        for k, part in enumerate(with_bands().components()):
            p = summit_parameters(part, HUMID)
            delta = z[band == k][None, :] - d[:, None]
            vdw = vdw_summit(delta, p["hamaker"], part.R, p["cutoff"], p["band"],
                             p["retardation"])  # fmt: skip
            meniscus = capillary_summit(delta, p["laplace"], part.R, p["wet_floor"], p["gap_k"])
            caps += (vdw + meniscus).sum(axis=1)
        gaps = spec.area * padload.open_gaps(spec)(d / sigma)
        expected = padload.contact_load(spec, z, d, d_t) - caps - gaps
        load = padload.pad_load(spec, z, d, d_t)
        # the kernel's sums against NumPy's, in another order: rounding (1e-9 of the largest
        # load, as the kernel-against-NumPy check of validation/pad_benchmark.py)
        np.testing.assert_allclose(load, expected, rtol=1e-9, atol=1e-9 * np.abs(load).max())
        force = padcurves.pull_off(spec, z, d_t)[0]
        assert force > 0 and -force <= load.min() + 1e-6 * force  # 1e-6: as above
        # the trapezoid rule on 5e4 steps measured within 3.5e-6 of the work; bound about 5x
        tail = open_gap_works(np.float64(top / sigma), spec.surface, HUMID)
        dense = -np.trapezoid(load, d) / spec.area + float(tail["vdw"] + tail["capillary"])
        assert padcurves.pad_work(spec, z, d_t) == pytest.approx(dense, rel=2e-5)

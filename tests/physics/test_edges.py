"""Numerical edges: extreme separations and parameters give finite, non-negative numbers.

μ is either a finite non-negative number or explicitly undefined (NaN with a note in
the comparison), never a silent NaN. Without adhesion (γ = 0) the seed's friction is 0
and μ undefined everywhere (tests/engine/test_mu_undefined.py).
"""

import itertools

import numpy as np
import pytest

from mcsim import Material, Surface, gw_curves, simulate

H = np.linspace(-40, 40, 81)
SIGMAS = (0.01e-9, 1e-6)  # 0.01 nm .. 1 µm
RADII = (10e-9, 1e-3)  # 10 nm .. 1 mm
DENSITIES = (1e9, 1e15)  # 1e-3 .. 1e3 µm⁻²
GAMMAS = (0.0, 0.5)
CORNERS = list(itertools.product(SIGMAS, RADII, DENSITIES, GAMMAS))


def material(gamma):
    return Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, gamma=gamma)


@pytest.mark.parametrize(("sigma", "R", "eta", "gamma"), CORNERS)
def test_analytic_curves_are_finite_and_non_negative_at_the_extremes(sigma, R, eta, gamma):
    curves = gw_curves(Surface(sigma, R, eta), material(gamma), H)
    for q in ("contact_fraction", "P", "F", "T") + (("mu",) if gamma > 0 else ()):
        values = getattr(curves, q)
        assert np.all(np.isfinite(values)) and np.all(values >= 0), q
    if gamma == 0:
        assert np.all(curves.F == 0) and np.all(curves.T == 0) and np.all(np.isnan(curves.mu))


@pytest.mark.parametrize(("sigma", "R", "eta", "gamma"), CORNERS[::3])
def test_monte_carlo_is_finite_and_says_where_mu_is_undefined(sigma, R, eta, gamma):
    run = simulate(Surface(sigma, R, eta), material(gamma), [-40.0, -1.0, 0.0, 3.0, 40.0],
                   area=2e4 / eta, realizations=2, seed=1, workers=1)  # fmt: skip
    for q in ("contact_fraction", "P", "F", "T"):
        assert np.all(np.isfinite(run.realizations[q])) and np.all(run.realizations[q] >= 0), q
    table = run.compare()
    undefined = ~np.isfinite(table["mc_mean"])
    assert (table.loc[undefined, "quantity"] == "mu").all(), "only μ may be undefined"
    assert table.loc[undefined, "note"].str.len().gt(0).all(), "and then the table says why"
    defined = table["quantity"] != "mu" if gamma == 0 else slice(None)
    assert np.isfinite(table.loc[defined, "analytic"]).all()
    # at h = 40 no summit touches: μ is undefined, not zero
    assert np.isnan(run.summary.mean["mu"][-1])


def test_an_empty_patch_is_reported_not_divided_by_zero():
    run = simulate(
        Surface(1e-9, 1e-6, 1e9), material(0.5), [0.0], area=1e-12, realizations=3, seed=2
    )
    assert np.all(run.n_summits == 0)
    table = run.compare()
    assert table["z"].isna().all() and table["note"].str.startswith("few contacts").all()


# --- the accepted ranges (mcsim.model.params.RANGES, MAX_ABS_H) keep every output finite ----------

RANGE_H = np.array([-1e6, -40.0, 0.0, 40.0, 1e6])


def range_corners():
    from mcsim.model.params import RANGES

    for sigma, R, eta, gamma, E in itertools.product(
        RANGES["sigma"][:2], RANGES["R"][:2], RANGES["eta"][:2], RANGES["gamma"][:2], (1.0, 1e13)
    ):
        yield Surface(sigma, R, eta), Material(E1=E, E2=E, nu1=0.22, nu2=0.22, gamma=gamma)


@pytest.mark.parametrize(("surface", "mat"), list(range_corners()))
def test_every_corner_of_the_accepted_ranges_gives_finite_curves(surface, mat):
    curves = gw_curves(surface, mat, RANGE_H)
    for q in ("contact_fraction", "P", "F", "T") + (("mu",) if mat.gamma > 0 else ()):
        values = getattr(curves, q)
        assert np.all(np.isfinite(values)) and np.all(values >= 0), (q, values)
    assert mat.gamma > 0 or np.all(np.isnan(curves.mu)), "no adhesion: μ undefined"
    for q, values in curves.forces(1.0).items():
        assert np.all(np.isfinite(values)) and np.all(values >= 0), (q, values)


@pytest.mark.parametrize(("surface", "mat"), list(range_corners())[::7])
def test_every_corner_of_the_accepted_ranges_gives_finite_monte_carlo_sums(surface, mat):
    run = simulate(surface, mat, [-1e6, 0.0, 3.0], area=50 / surface.eta, realizations=2,
                   seed=3, workers=1)  # fmt: skip
    for q in ("contact_fraction", "P", "F", "T"):
        assert np.all(np.isfinite(run.realizations[q])), q

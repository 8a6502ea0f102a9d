"""Friction of pads, dry and humid (issue 42): statistics, GW convergence, humidity, p_slip by
plain pads and importance sampling, `mcsim pads --tangential-force` and `mcsim.pad_report`."""

import dataclasses
import io
import json
import math

import numpy as np
import pandas as pd
import pytest
from conftest import run_cli
from scipy.stats import poisson

import mcsim
from mcsim.engine.pads import curves as padcurves
from mcsim.engine.pads import friction as padfriction
from mcsim.engine.pads import load as padload
from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.errors import MCSimError, ParameterError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.environment import Environment
from mcsim.physics.friction import gw_static_friction
from mcsim.studies import padfriction as study
from mcsim.studies.intervals import clopper_pearson

SILICON = MATERIALS["silicon"]
SMOOTH = SURFACES["smooth"]
TAU = dataclasses.replace(SILICON, tau=1e8)
H = np.linspace(4.0, -2.0, 13)
AREA = 30e-12
HUMID = {"hamaker": 1.6e-19}


def _spec(law="jkr", material=SILICON, pads=3, seed=11, environment=None, area=AREA):
    return MonteCarloSpec(SMOOTH, material, H, area, pads, seed, law, cycle=True,
                          environment=environment)  # fmt: skip


# --- statistics ----------------------------------------------------------------------------


def test_statistics_are_the_direct_numpy_ones_and_p_slip_counts_pads_strictly_below_f():
    rng = np.random.default_rng(3)
    t = rng.gamma(3.0, 1e-4, size=41)
    w = np.full(41, 2e-5)
    w[:3] = np.nan  # μ_s undefined on three pads
    s = study.friction_statistics(t, w, tangential_force=float(np.sort(t)[10]))
    assert s.static_friction["mean"] == np.mean(t) and s.static_friction["std"] == np.std(t, ddof=1)
    assert (s.static_friction["q05"], s.static_friction["q50"], s.static_friction["q95"]) == tuple(
        np.quantile(t, [0.05, 0.5, 0.95])
    )
    mu = t[3:] / 2e-5
    assert s.mu_pads == 38 and s.mu_static["mean"] == np.mean(mu)
    assert s.mu_static["se"] == np.std(mu, ddof=1) / math.sqrt(38)
    assert s.p_slip == 10 / 41 and s.p_slip_ci == clopper_pearson(10, 41)


def test_mu_is_nan_where_no_pad_has_a_normal_load():
    s = study.friction_statistics([1e-4, 2e-4], [np.nan, np.nan])
    assert s.mu_pads == 0 and all(math.isnan(v) for v in s.mu_static.values())
    assert s.p_slip is None


@pytest.mark.parametrize("force", [-1e-6, math.inf, math.nan, "-2 uN", "2 m", True])
def test_a_bad_tangential_force_is_a_one_line_error_naming_it(force):
    with pytest.raises(MCSimError, match="tangential_force") as err:
        study.friction_statistics([1e-4], [1e-5], tangential_force=force)
    assert "\n" not in str(err.value)


# --- physics --------------------------------------------------------------------------------


@pytest.mark.parametrize("law, material", [("jkr", SILICON), ("dmt", TAU)])
@pytest.mark.parametrize("h", [0.5, 1.5])
def test_large_pads_converge_to_the_gw_friction_at_the_same_separation(law, material, h):
    # 150 pads of 30 µm² (λ = 510 summits) at a common separation: E[T_s] = λ E[T_a] = A K ×
    # the GW curve (Poisson count). z against the pads' standard error; fixed seeds, |z| < 4.
    spec = _spec(law, material, pads=150, seed=23)
    t = [padfriction.static_friction(spec, padload.patch_heights(spec, r), h * SMOOTH.sigma)
         for r in range(150)]  # fmt: skip
    expected = gw_static_friction(SMOOTH, material, [h], law)[0] * material.K * AREA
    z = (np.mean(t) - expected) / (np.std(t, ddof=1) / math.sqrt(len(t)))
    assert abs(z) < 4, (np.mean(t), expected, z)


#: Relative humidities of the humid pads' checks (0: dry, with van der Waals).
RH = (0.0, 0.5, 0.6, 0.8)


@pytest.fixture(scope="module")
def humid_pads():
    """Each of 2 pads' T_s and contact load at its turn under 1 MPa at each of :data:`RH`: the
    same pads (common random numbers), shape (RH, pads, 2)."""
    out = []
    for rh in RH:
        spec = _spec(pads=2, environment=Environment(**HUMID, rh=rh))
        pads = []
        for r in range(2):
            z = padload.patch_heights(spec, r)
            d_turn, _ = padcurves.force_turn(spec, z, 1e6 * AREA)
            contact = padload.contact_load(spec, z, [d_turn])[0]
            pads.append((padfriction.static_friction(spec, z, d_turn), contact))
        out.append(pads)
    return np.array(out)


def test_friction_rises_with_humidity_as_the_contact_load_grows(humid_pads):
    # the same pads dry and at RH 0.6: menisci press each one deeper
    dry, humid = humid_pads[0], humid_pads[2]
    assert np.all(humid[:, 1] > 1.5 * dry[:, 1]) and np.all(humid[:, 0] > 1.5 * dry[:, 0])


def test_persson_peak_lies_where_the_films_bridge_about_2_3_h_rms(humid_pads):
    # docs/physics.md, 'Friction of pads': on the smooth surface (rq = 1.55 nm) under 1 MPa
    # the pads' friction is largest at RH 0.5, where the bridges span g_K = 2 r_K + 2t =
    # 2.26 rq (d_K = 2 r_K alone 0.97 rq), near Persson's d_K ≈ 3 h_rms once the adsorbed
    # films are counted in the bridge; at RH 0.8 (g_K = 4.87 rq) it is over 20 % lower: the
    # whole pad is wetted and its pull A γ_L/r_K falls.
    from mcsim.physics.gapheights import gap_heights

    t = humid_pads[:, :, 0].mean(axis=1)
    assert t[1] > t[2] > t[3] and t[3] < 0.8 * t[1]
    rq = gap_heights(SMOOTH).rq
    gaps = [Environment(**HUMID, rh=x).condensation_gap / rq for x in (0.5, 0.8)]
    assert gaps == [pytest.approx(2.26, abs=0.005), pytest.approx(4.87, abs=0.005)]


# --- p_slip by importance sampling, on an exact event ------------------------------------

#: A score of the summits whose law is exact: the summits in one band of heights (σ).
BAND = (1.0, 1.75)


def _count(spec, s, *, turn, preload):
    return float(np.count_nonzero((s > BAND[0]) & (s <= BAND[1])))


def _exact_below(m, spec):
    lam = SMOOTH.eta * spec.area * float(SMOOTH.heights.sf(BAND[0]) - SMOOTH.heights.sf(BAND[1]))
    return float(poisson.cdf(m, lam))


@pytest.mark.parametrize("f, event", [(38.5, "slip"), (84.5, "hold")])
def test_importance_sampling_estimates_a_rare_slip_or_hold_without_bias(monkeypatch, f, event):
    # T_s replaced by the count in a band (Poisson, mean 60.5): p_slip = P(count ≤ f − 1/2)
    # exactly, 1.3e-3 or 1 − 1.7e-3; 100 plain pads of which none lies on the rare side switch
    # to importance sampling
    monkeypatch.setattr(study, "pad_static_friction", lambda spec, s, **k: _count(spec, s, **k))
    spec = _spec(pads=100, seed=4)
    exact = _exact_below(math.floor(f), spec)
    assert (1e-3 < exact < 2e-3) if event == "slip" else (1e-3 < 1 - exact < 2e-3)
    plain = 0.0 if event == "slip" else 1.0
    stats = study.FrictionStatistics(
        100, {}, {}, 0, f, plain, clopper_pearson(round(plain * 100), 100)
    )
    out = study.tail_p_slip(spec, stats, turn=2.0, preload=None, tail=None)
    assert out["p_slip_method"] == "importance" and out["p_slip_ess"] >= 30
    half = (out["p_slip_high"] - out["p_slip_low"]) / 2
    assert abs(out["p_slip"] - exact) < 2.5 * half, (out, exact)
    assert out["p_slip_low"] <= out["p_slip"] <= out["p_slip_high"]


def test_plain_pads_keep_their_fraction_where_enough_lie_on_either_side():
    stats = study.friction_statistics(np.arange(1.0, 101.0), np.ones(100), tangential_force=40.5)
    out = study.tail_p_slip(_spec(pads=100), stats, turn=2.0, preload=None, tail=None)
    assert out == {"p_slip": 0.4, "p_slip_low": stats.p_slip_ci[0],
                   "p_slip_high": stats.p_slip_ci[1], "p_slip_ess": 40.0, "p_slip_method": "pads"}  # fmt: skip


# --- the report and the command line ------------------------------------------------------


@pytest.fixture(scope="module")
def cycle_run(tmp_path_factory):
    path = tmp_path_factory.mktemp("friction") / "c.h5"
    mcsim.simulate(SMOOTH, SILICON, np.linspace(2, -1, 16), "30 um^2", cycle=True, law="jkr",
                   realizations=12, seed=3, workers=1, preload="1MPa", out=path)  # fmt: skip
    return path


def test_the_report_adds_each_pads_friction_and_p_slip_as_mcsim_pads_prints_them(cycle_run, capsys):
    code, out, err = run_cli(capsys, "pads", cycle_run, "--tangential-force=0.5mN", "--format",
                             "json")  # fmt: skip
    assert code == 0, err
    printed = json.loads(out)
    report = mcsim.pad_report(mcsim.read_run(cycle_run), tangential_force="0.5 mN")
    for name, (value, unit) in report.quantities().items():
        assert printed[name] == value and printed["units"][name] == unit, name
    assert printed["p_slip_method"] == "pads" and "Savkoor-Briggs" in err
    pads = report.pull_off
    run = mcsim.read_run(cycle_run)
    spec = run.spec
    each = run.pads()
    assert np.array_equal(each.static_friction, pads.static_friction)
    assert np.array_equal(each.mu_static, pads.static_friction / pads.normal_load)
    for r in range(3):  # each pad's T_s at its own turn under the preload
        z = padload.patch_heights(spec, r)
        assert pads.static_friction[r] == padfriction.static_friction(
            spec, z, pads.h_turn[r] * SMOOTH.sigma
        )
    assert np.array_equal(pads.normal_load, np.full(12, 1e6 * AREA))
    k = int(np.count_nonzero(pads.static_friction < 5e-4))
    assert report.slip["p_slip"] == k / 12 and report.friction.p_slip_ci == clopper_pearson(k, 12)
    # without the new options, the report and its printout are what they were
    plain = mcsim.pad_report(mcsim.read_run(cycle_run))
    assert plain.friction is None and plain.pull_off.static_friction is None
    assert not any(k.startswith(("static", "mu_", "p_slip")) for k in plain.quantities())
    assert np.array_equal(plain.pull_off.force, pads.force)


@pytest.mark.parametrize(
    "option, match",
    [("--tangential-force=-1uN", "--tangential-force"), ("--tangential-force=inf", "--tangential-force"),
     ("--tangential-force=nan", "--tangential-force"), ("--tangential-force=5m", "--tangential-force")],
)  # fmt: skip
def test_cli_bad_tangential_force_is_a_one_line_error_and_writes_nothing(cycle_run, tmp_path,
                                                                        capsys, option, match):  # fmt: skip
    png = tmp_path / "p.png"
    code, out, err = run_cli(capsys, "pads", cycle_run, option, "--plot", png)
    assert code != 0 and match in err and len(err.strip().splitlines()) == 1
    assert out == "" and not png.exists()


def test_cli_friction_of_a_law_set_without_it_names_those_that_have(tmp_path, capsys):
    run = tmp_path / "dmt.h5"
    mcsim.simulate(SMOOTH, SILICON, np.linspace(2, -1, 7), "3 um^2", cycle=True, law="dmt",
                   realizations=2, seed=1, workers=1, out=run)  # fmt: skip
    png = tmp_path / "p.png"
    code, _, err = run_cli(capsys, "pads", run, "--tangential-force=1uN", "--plot", png)
    assert code != 0 and len(err.strip().splitlines()) == 1 and not png.exists()
    assert "'dmt' has no friction without a shear strength tau" in err and "jkr" in err
    with pytest.raises(ParameterError, match="no friction"):
        mcsim.pad_report(mcsim.read_run(run), friction=True)


def test_each_pad_as_a_table_is_what_mcsim_pads_csv_prints(cycle_run, capsys):
    code, out, err = run_cli(capsys, "pads", cycle_run, "--friction", "--format", "csv")
    assert code == 0, err
    printed = pd.read_csv(io.StringIO(out), index_col="pad")
    table = mcsim.read_run(cycle_run).pads().to_dataframe()
    pd.testing.assert_frame_equal(printed, table, check_exact=True, check_index_type=False)
    assert table.attrs["units"]["static_friction_N"] == "N"
    assert table.attrs["units"]["mu_static"] == "1"
    assert np.array_equal(table["mu_static"], table["static_friction_N"] / table["normal_load_N"])
    for name in table.columns:
        assert name in err, name  # every column explained in the note

"""`mcsim contact --adhesion` and the study behind it: the exact adhesive cycle of a map beside
GW's adhesion on the same map (mcsim.studies.maps.adhesivecontact)."""

from __future__ import annotations

import dataclasses
import json

import h5py
import numpy as np
import pytest
from conftest import run_cli

from mcsim.model.errors import ParameterError
from mcsim.model.presets import MATERIALS
from mcsim.physics.adhesion import adhesion_summary
from mcsim.physics.analytic import gw_curves
from mcsim.physics.loadcontrol import preload_turn
from mcsim.physics.stickiness import stickiness
from mcsim.studies.maps.adhesivecontact import GW_LAWS, H0_PER_Z0, adhesive_contact

#: examples/scan.npy (periodic, 100 x 100 pixels of 10 nm, 3 nm rms, heights in m) every second
#: pixel: still periodic, 50 x 50 pixels of 20 nm, a quarter of the work
MAP = ("--unit", "m", "--pixel-size", "20nm")
ADHESION = ("--adhesion", "--w", "0.05J/m^2", "--range", "1nm", "--pressure", "200MPa")
SILICON = MATERIALS["silicon"]


@pytest.fixture(scope="module")
def scan(tmp_path_factory) -> str:
    path = tmp_path_factory.mktemp("map") / "scan.npy"
    np.save(path, np.load("examples/scan.npy")[::2, ::2])
    return str(path)


@pytest.fixture(scope="module")
def result(scan):
    return adhesive_contact(scan, SILICON, 200e6, w=0.05, range_=1e-9, steps=16, unit="m",
                            pixel_size=2e-8)  # fmt: skip


def test_every_step_converged_and_the_retraction_revisits_the_approach(result):
    c = result.cycle
    assert c.converged and not c.failed
    assert len(c.approach) == len(c.retraction) == 16
    np.testing.assert_array_equal([s.position for s in c.approach],
                                  [s.position for s in c.retraction][::-1])  # fmt: skip


def test_the_approach_starts_where_nothing_acts_and_ends_pressed(result):
    first, last = result.cycle.approach[0], result.cycle.approach[-1]
    assert first.contact_fraction == 0 and abs(first.mean_pressure) < 1e-6 * result.pressure
    # adhesion pulls: the adhesive contact carries less than the non-adhesive one there
    assert 0 < last.mean_pressure < result.pressure


def test_the_retraction_pulls_off_with_hysteresis_and_work(result):
    s = result.summary()
    assert s["pull_off"] > 0 and s["work_of_separation"] > 0
    # located between the steps: at least the most tensile step's, and between its neighbours
    steps = result.cycle.retraction
    k = int(np.argmin([x.mean_pressure for x in steps]))
    assert s["pull_off"] >= -steps[k].mean_pressure
    assert steps[k - 1].position < s["pull_off_position"] < steps[k + 1].position
    # the loop never gives back more than it took: the hysteresis is >= 0 but for the
    # trapezoid's error over the steps (here no branch ends between them: ~1e-7 of the work)
    assert s["hysteresis"] > -1e-4 * s["work_of_separation"]


def test_gw_is_pressed_to_the_same_largest_pressure_with_the_laws_w_and_range(result):
    """Each law set's GW pull-off equals an independent adhesion summary with w, z0 = range/0.97
    (maugis-dugdale's h0 = the law's range) at the turn of the exact approach's largest load;
    its work is the tensile part of the mean retraction load, −∫ min(p, 0) dd, as the exact
    cycle's: here against a trapezoid on 40 001 points (its kinks: ~1e-4 relative, measured;
    bound 1e-3)."""
    material = dataclasses.replace(SILICON, gamma=0.05, z0=1e-9 / H0_PER_Z0)
    assert [g.law for g in result.gw] == list(GW_LAWS)
    sigma = result.surface.sigma
    for g in result.gw:
        turn = preload_turn(result.surface, material, result.max_pressure, g.law)
        s = adhesion_summary(result.surface, material, g.law, turn=turn)
        assert g.turn == turn and g.pull_off == s.pull_off_pressure
        h = np.linspace(turn, turn + 60e-9 / sigma, 40_001)
        load = gw_curves(result.surface, material, h, g.law, branch="retract", turn=turn).load
        tensile = -material.K * sigma * np.trapezoid(np.minimum(load, 0.0), h)
        assert g.work_of_separation == pytest.approx(tensile, rel=1e-3), g.law
        ratio = result.summary()["gw"][g.law]["pull_off_ratio"]
        assert ratio == pytest.approx(g.pull_off / result.summary()["pull_off"], rel=1e-15)


def test_json_gives_rows_summary_gw_and_stickiness(capsys, scan):
    code, out, err = run_cli(capsys, "contact", scan, *MAP, *ADHESION, "--steps", "8",
                             "--format", "json", "--quiet")  # fmt: skip
    assert code == 0, err
    data = json.loads(out)
    assert len(data["rows"]) == 16 and data["interaction"] == "exponential"
    assert {r["branch"] for r in data["rows"]} == {"approach", "retract"}
    assert set(data["summary"]["gw"]) == set(GW_LAWS)
    assert {"pr_parameter", "energy_ratio", "tabor", "mesh"} <= set(data["stickiness"])
    assert data["units"]["pressure"].startswith("Pa")


def test_subpixel_integrates_the_interaction_and_is_recorded(capsys, scan, tmp_path):
    # The Maugis-Dugdale law at a range of 0.5 nm: its zone is narrower than a pixel of 20 nm
    args = (scan, *MAP, "--adhesion", "--w", "0.05J/m^2", "--range", "0.5nm", "--pressure",
            "200MPa", "--interaction", "maugis-dugdale", "--steps", "6", "--quiet")  # fmt: skip
    code, out, err = run_cli(capsys, "contact", *args, "--subpixel", "2", "--format", "json",
                             "--out", str(tmp_path / "k2.h5"))  # fmt: skip
    assert code == 0, err
    data = json.loads(out)
    study = adhesive_contact(scan, SILICON, 200e6, law="maugis-dugdale", w=0.05, range_=5e-10,
                             steps=6, unit="m", pixel_size=2e-8, subpixel=2)  # fmt: skip
    assert data["subpixel"] == study.subpixel == 2
    assert data["summary"]["pull_off"] == study.summary()["pull_off"]
    with h5py.File(tmp_path / "k2.h5") as f:
        assert f.attrs["subpixel"] == 2
    plain = adhesive_contact(scan, SILICON, 200e6, law="maugis-dugdale", w=0.05, range_=5e-10,
                             steps=6, unit="m", pixel_size=2e-8)  # fmt: skip
    assert plain.subpixel == 1 and plain.summary()["pull_off"] != study.summary()["pull_off"]
    code, out, _ = run_cli(capsys, "contact", *args, "--subpixel", "2")
    assert "the interaction over 2 x 2 points a pixel" in out


def test_table_prints_the_exact_pull_off_beside_gw_s(capsys, scan):
    code, out, _ = run_cli(capsys, "contact", scan, *MAP, *ADHESION, "--steps", "8", "--quiet")
    assert code == 0
    assert "exact: pull-off" in out and "GW on the same map" in out
    for law in GW_LAWS:
        assert f"  {law}: " in out
    assert "stickiness: Pastewka-Robbins" in out


def test_out_keeps_every_steps_fields_with_units_and_plot_draws_the_loop(tmp_path, capsys, scan):
    out, png = tmp_path / "a.h5", tmp_path / "a.png"
    code, _, err = run_cli(capsys, "contact", scan, *MAP, *ADHESION, "--steps", "6", "--out",
                           str(out), "--plot", str(png), "--quiet")  # fmt: skip
    assert code == 0, err
    with h5py.File(out) as f:
        assert f["gap_field"].shape == (12, 50, 50) and f["gap_field"].attrs["units"] == "m"
        assert f["pressure"].attrs["units"] == "Pa" and f.attrs["interaction"] == "exponential"
        assert json.loads(f.attrs["summary"])["pull_off"] > 0
    assert png.stat().st_size > 10_000


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (("--w", "-1J/m^2"), "w"),
        (("--range", "0nm"), "range"),
        (("--steps", "1"), "--steps"),
        (("--pressure", "1MPa,2MPa"), "one pressure"),
        (("--hamaker", "1e-19J"), "not available yet"),
        (("--interaction", "lj"), "interaction"),
        (("--subpixel", "0"), "--subpixel"),
        (("--subpixel", "2.5"), "--subpixel"),
    ],
)
def test_bad_input_is_one_line_and_writes_nothing(tmp_path, capsys, scan, extra, message):
    out = tmp_path / "a.h5"
    code, _, err = run_cli(capsys, "contact", scan, *MAP, *ADHESION, *extra, "--out", str(out))
    assert code == 2 and message in err and len(err.strip().splitlines()) == 1, err
    assert not out.exists() and list(tmp_path.iterdir()) == []


def test_a_map_with_a_missing_pixel_is_refused(tmp_path, scan):
    z = np.load(scan)
    z[3, 4] = np.nan
    np.save(tmp_path / "nan.npy", z)
    with pytest.raises(ParameterError, match="missing pixels"):
        adhesive_contact(tmp_path / "nan.npy", SILICON, 1e8, w=0.05, range_=1e-9, unit="m",
                         pixel_size=2e-8)  # fmt: skip


def test_a_solve_that_does_not_converge_is_an_error_not_a_number(scan):
    with pytest.raises(ParameterError, match=r"did not converge.*no answer"):
        adhesive_contact(scan, SILICON, 2e8, w=0.05, range_=1e-9, steps=4, unit="m",
                         pixel_size=2e-8, max_iter=1)  # fmt: skip


def test_the_result_carries_the_maps_stickiness_and_its_warnings(result, scan):
    """The diagnostics are the map's, for the law's w and range; a grid too coarse for the law
    (a range of 0.05 nm on 20 nm pixels: √(w/ρ² Δx/E*) = 3.4 > 0.5, Wang, Zhou & Müser)
    would be warned about in the result's warnings."""
    z = np.load(scan)
    expected = stickiness(z - z.mean(), 2e-8, SILICON.E_star, 0.05, 1e-9, periodic=True)
    assert result.stickiness == expected
    assert result.warnings()[: len(expected.warnings())] == expected.warnings()
    coarse = stickiness(z - z.mean(), 2e-8, SILICON.E_star, 0.05, 5e-11, periodic=True)
    assert any("does not resolve" in w for w in coarse.warnings())


def test_the_result_shows_itself_in_a_few_lines_as_in_a_notebook(result):
    text = repr(result)
    assert len(text) < 600 and "exact pull-off" in text and all(law in text for law in GW_LAWS)

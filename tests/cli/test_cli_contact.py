"""`mcsim contact` and the study behind it: exact contact of a map beside GW's on the same map."""

import json
import math
import re
from pathlib import Path

import h5py
import numpy as np
import pytest
from conftest import rows_of, run_cli
from scipy import integrate, stats

from mcsim.cli.main import main
from mcsim.model.params import Material, Surface
from mcsim.model.presets import MATERIALS
from mcsim.studies.maps.contact import contact_map, gw_hertz

ROOT = Path(__file__).resolve().parents[2]
SCAN = "examples/scan.npy"  # periodic, 100 x 100 pixels of 10 nm, heights in m
MAP = ("--unit", "m", "--pixel-size", "10nm")
LOADS = "10MPa:100MPa:2:log"


def test_csv_rows_are_the_study_numbers_with_the_pixel_size(capsys):
    code, out, err = run_cli(capsys, "contact", SCAN, *MAP, "--pressure", LOADS, "--format", "csv")
    assert code == 0, err
    rows = rows_of(out)
    result = contact_map(SCAN, MATERIALS["silicon"], [1e7, 1e8], unit="m", pixel_size=1e-8)
    for name, values in result.columns().items():
        np.testing.assert_array_equal([float(r[name]) for r in rows], values, err_msg=name)
    assert [float(r["pixel_size"]) for r in rows] == [1e-8, 1e-8]


def test_table_states_the_pixel_size_and_why_the_map_is_periodic(capsys):
    code, out, _ = run_cli(capsys, "contact", SCAN, *MAP, "--pressure", "100MPa")
    assert code == 0
    assert "100 x 100 pixels of 10 x 10 nm" in out
    assert "periodic: edge steps" in out and "edges join" in out


def test_tolerance_defaults_to_the_solver_s_and_is_obeyed(capsys):
    from mcsim.physics.bem import TOL

    _, out, _ = run_cli(capsys, "contact", SCAN, *MAP, "--pressure", "1GPa", "--format", "json")
    _, loose, _ = run_cli(capsys, "contact", SCAN, *MAP, "--pressure", "1GPa", "--format", "json",
                          "--tol", "1e-3")  # fmt: skip
    assert json.loads(out)["tol"] == TOL and json.loads(loose)["tol"] == 1e-3
    assert json.loads(loose)["rows"][0]["iterations"] < json.loads(out)["rows"][0]["iterations"]
    assert main(["contact", "--help"]) == 0
    stated = re.search(
        r"--tol TOL .*?\(default: ([0-9.e+-]+)\)", " ".join(capsys.readouterr().out.split())
    )
    assert float(stated[1]) == TOL


def test_a_cut_out_map_is_not_periodic_by_default(tmp_path, capsys):
    cut = tmp_path / "cut.npy"
    np.save(cut, np.load(SCAN)[:60, :60])
    code, out, _ = run_cli(capsys, "contact", cut, *MAP, "--pressure", "100MPa", "--format", "json")
    assert code == 0
    reply = json.loads(out)
    assert reply["periodic"] is False and "edges do not join" in reply["periodic_reason"]


def test_no_periodic_is_obeyed_and_said(capsys):
    _, out, _ = run_cli(capsys, "contact", SCAN, *MAP, "--pressure", "100MPa", "--format", "json",
                        "--no-periodic")  # fmt: skip
    reply = json.loads(out)
    assert reply["periodic"] is False and reply["periodic_reason"] == "as asked"
    assert reply["units"]["mean_gap"].startswith("m") and reply["dx_m"] == 1e-8


def test_out_file_holds_compressed_fields_with_cf_attributes(tmp_path, capsys):
    out = tmp_path / "c.h5"
    code, _, err = run_cli(capsys, "contact", SCAN, *MAP, "--pressure", LOADS, "--out", out)
    assert code == 0 and f"wrote {out}" in err
    with h5py.File(out) as f:
        assert f["pressure_field"].shape == (2, 100, 100)
        assert f["pressure_field"].compression == "gzip"
        assert f["gap_field"].attrs["units"] == "m" and f["pressure"].attrs["units"] == "Pa"
        assert "long_name" in f["area_fraction"].attrs
        assert f.attrs["dx"] == 1e-8 and f.attrs["command"].startswith("mcsim")  # sys.argv here
        assert {"schema", "mcsim_version", "created", "source", "periodic"} <= set(f.attrs)
        np.testing.assert_allclose(
            f["pressure_field"][()].mean(axis=(1, 2)), [1e7, 1e8], rtol=1e-12
        )


def test_an_existing_output_is_refused_in_one_line_before_any_work(tmp_path, capsys):
    out = tmp_path / "c.h5"
    out.write_bytes(b"keep")
    code, _, err = run_cli(capsys, "contact", SCAN, *MAP, "--pressure", "1MPa", "--out", out)
    assert code == 2 and err.count("\n") == 1 and err.startswith("mcsim: error:")
    assert out.read_bytes() == b"keep"


def test_plot_is_written(tmp_path, capsys):
    png = tmp_path / "c.png"
    code, _, _ = run_cli(
        capsys, "contact", SCAN, *MAP, "--pressure", LOADS, "--plot", png, "--quiet"
    )
    assert code == 0 and png.read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize(("pressure", "message"), [("-1MPa", "positive"), ("1kg", "--pressure")])
def test_a_bad_pressure_is_one_line_naming_it(capsys, pressure, message):
    code, _, err = run_cli(capsys, "contact", SCAN, *MAP, f"--pressure={pressure}")
    assert code == 2 and err.count("\n") == 1 and message in err


def test_a_histogram_is_refused_as_no_map(capsys):
    code, _, err = run_cli(capsys, "contact", "examples/hist.csv", "--pressure", "1MPa")
    assert code == 2 and err.count("\n") == 1 and "a height histogram has no map" in err


def test_gw_hertz_matches_the_gaussian_closed_forms():
    # Gaussian heights: F_1(h) = φ(h) - h Q(h) in closed form, F_3/2(h) by adaptive quadrature;
    # p = η (4/3)E* R^½ σ^{3/2} F_3/2(h) and A_r/A_n = π η R σ F_1(h) (GW 1966). Both to 1e-8.
    surface = Surface(sigma=3e-9, R=1e-7, eta=1e14, summit_offset=2e-9)
    material = Material(E=2 * (1 - 0.25**2) * 1e11, nu=0.25, w=0.5)  # 1/E* = 2(1-ν²)/E
    E_star, p = material.E_star, np.array([1e6, 1e8])
    h, area, gap = gw_hertz(surface, material, p)
    for hi, pi, ai, gi in zip(h, p, area, gap, strict=True):
        f1 = stats.norm.pdf(hi) - hi * stats.norm.sf(hi)
        f32 = integrate.quad(lambda d, hi=hi: d**1.5 * stats.norm.pdf(hi + d), 0, np.inf, epsabs=0)[
            0
        ]
        # GW's h is root-solved and the reference is scipy's quad (each to ~1e-10): 1e-8 of
        # the value; the mean gap is an exact sum of the printed h and offset: 1e-12
        load = surface.eta * 4 / 3 * E_star * math.sqrt(surface.R) * surface.sigma**1.5 * f32
        np.testing.assert_allclose(load, pi, rtol=1e-8, err_msg="pressure at GW's h")
        np.testing.assert_allclose(
            ai, math.pi * surface.eta * surface.R * surface.sigma * f1, rtol=1e-8
        )
        np.testing.assert_allclose(gi, surface.sigma * hi + 2e-9, rtol=1e-12, err_msg="mean gap")


def test_the_documented_run_and_its_ratios_are_current(capsys):
    # docs/contact.md shows one run and quotes GW's area over the exact one and the mean gaps'
    # ratio at the top load: rerun here, the table compared line by line, the ratios to 2 digits.
    text = (ROOT / "docs" / "contact.md").read_text()
    block = text.split("```text\n$ mcsim contact")[1].split("```")[0].splitlines()
    block[0] = "$ mcsim contact" + block[0]
    argv = block[0].removeprefix("$ mcsim ").split()
    code, out, _ = run_cli(capsys, *argv)
    lines, shown = out.splitlines(), block[1:]
    assert code == 0 and len(lines) == len(shown)
    for got, doc in zip(lines, shown, strict=True):
        if got.startswith(("#", "pressure")):
            assert got == doc
            continue
        # converged to tol 1e-6 of the rms height: the 6-digit gaps may move in their last digit,
        # and the iteration count by a few, with another machine's rounding
        (*cells, iterations, pixel), (*ref, ref_iterations, ref_pixel) = got.split(), doc.split()
        np.testing.assert_allclose(np.float64(cells), np.float64(ref), rtol=2e-5, err_msg=got)
        assert abs(int(iterations) - int(ref_iterations)) <= 3 and pixel == ref_pixel
    r = contact_map(SCAN, MATERIALS["silicon"], [1e6, 1e7, 1e8, 1e9], unit="m", pixel_size=1e-8)
    ratios = ", ".join(f"{x:.2f}" for x in (r.gw_area_fraction / r.area_fraction)[1:3])
    assert f"{ratios} and {r.gw_area_fraction[3] / r.area_fraction[3]:.2f} of the exact" in text
    assert f"{r.mean_gap[3] / r.gw_mean_gap[3]:.1f} times smaller" in text


def test_a_pressure_beyond_the_contact_modulus_is_refused_before_solving(capsys):
    code, _, err = run_cli(capsys, "contact", "examples/scan.npy", "--unit", "m",
                           "--pixel-size", "10nm", "--pressure", "1e30Pa")  # fmt: skip
    assert code == 2 and err.count("\n") == 1
    assert "pressure = 1e+30 Pa is out of range (allowed: below E* = 8.40689e+10 Pa" in err


def test_environment_options_add_the_attraction_columns_and_say_their_limits(capsys, tmp_path):
    out = tmp_path / "c.h5"
    code, table, _ = run_cli(capsys, "contact", SCAN, *MAP, "--pressure", LOADS, "--hamaker",
                             "1.6e-19", "--rh", "0.5", "--out", out, "--quiet")  # fmt: skip
    assert code == 0 and "the attraction does not deform the surface" in table
    _, text, _ = run_cli(capsys, "contact", SCAN, *MAP, "--pressure", LOADS, "--hamaker",
                         "1.6e-19", "--rh", "0.5", "--format", "json")  # fmt: skip
    reply = json.loads(text)
    assert reply["units"]["vdw_pressure"].startswith("Pa")
    assert reply["environment"]["hamaker"] == 1.6e-19 and reply["environment"]["rh"] == 0.5
    with h5py.File(out) as f:
        np.testing.assert_array_equal(
            f["vdw_pressure"][()], [r["vdw_pressure"] for r in reply["rows"]]
        )
        assert f["capillary_pressure"].attrs["units"] == "Pa" and f.attrs["environment_rh"] == 0.5


def test_a_bad_environment_option_is_one_line_naming_it(capsys):
    code, _, err = run_cli(capsys, "contact", SCAN, *MAP, "--pressure", "1MPa", "--rh", "2")
    assert code == 2 and err.count("\n") == 1 and "rh" in err

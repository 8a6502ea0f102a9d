"""The environment on the command line and in TOML files (issue 22): options, the
[environment] table, one clear line per bad value, and the note when nothing condenses."""

import math

import numpy as np
import pytest
from conftest import rows_of, run_cli
from tolerances import ROUNDING_FEW

from mcsim import gw_curves
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.environment import Environment

H = "--h=2:0:3"


def analytic_csv(capsys, *options):
    code, out, err = run_cli(capsys, "analytic", "--surface", *options, H, "--format", "csv")
    assert code == 0, err
    return rows_of(out), err


def test_analytic_columns_match_gw_curves_with_the_environment(capsys):
    rows, err = analytic_csv(capsys, "smooth", "--hamaker", "0.16 aJ", "--cutoff", "0.2 nm",
                             "--rh", "0.6", "--contact-angle", "20")  # fmt: skip
    assert list(rows[0]) == [
        "h",
        "contact_fraction",
        "P",
        "F",
        "T",
        "mu",
        "vdw",
        "capillary",
        "load",
    ]
    env = Environment.from_user(hamaker="0.16 aJ", cutoff="0.2 nm", rh=0.6, contact_angle=20)
    assert env.hamaker == pytest.approx(
        1.6e-19, rel=ROUNDING_FEW
    ) and env.contact_angle == math.radians(20)
    ref = gw_curves(SURFACES["smooth"], MATERIALS["silicon"], [2, 1, 0], environment=env)
    for q in ("vdw", "capillary", "load"):
        np.testing.assert_array_equal([float(r[q]) for r in rows], ref.values[q], err_msg=q)
    assert "Nayak estimate" in err and "rq = 1.551 nm" in err


def test_no_environment_option_leaves_the_columns_as_before(capsys):
    rows, err = analytic_csv(capsys, "smooth")
    assert list(rows[0]) == ["h", "contact_fraction", "P", "F", "T", "mu"]
    assert err == ""


def test_environment_table_of_a_surface_file_and_options_override_it(capsys, tmp_path):
    f, plain = tmp_path / "s.toml", tmp_path / "plain.toml"
    plain.write_text('[surface]\nsigma = "1.4 nm"\nR = "1.7 um"\neta = "17 um^-2"\n')
    f.write_text(plain.read_text() + '[environment]\nhamaker = "1.6e-19 J"\nrh = 0.6\n'
                 "contact_angle = 20\n")  # fmt: skip
    from_file, _ = analytic_csv(capsys, str(f))
    from_options, _ = analytic_csv(capsys, str(plain), "--hamaker", "1.6e-19", "--rh", "0.6",
                                   "--contact-angle", "20")  # fmt: skip
    assert [r["capillary"] for r in from_file] == [r["capillary"] for r in from_options]
    assert [r["vdw"] for r in from_file] == [r["vdw"] for r in from_options]
    overridden, _ = analytic_csv(capsys, str(f), "--rh", "0.3")
    lower, _ = analytic_csv(capsys, str(plain), "--hamaker", "1.6e-19", "--rh", "0.3",
                            "--contact-angle", "20")  # fmt: skip
    assert [r["capillary"] for r in overridden] == [r["capillary"] for r in lower]


def test_films_in_a_file_equal_the_options_and_say_their_band(capsys, tmp_path):
    f, plain = tmp_path / "s.toml", tmp_path / "plain.toml"
    plain.write_text('[surface]\nsigma = "1.4 nm"\nR = "1.7 um"\neta = "17 um^-2"\n')
    f.write_text(plain.read_text() + '[environment]\nrh = 0.25\nfilm_thickness = "1.2 nm"\n'
                 'structured_film = "0.5 nm"\n')  # fmt: skip
    from_file, err = analytic_csv(capsys, str(f))
    from_options, _ = analytic_csv(capsys, str(plain), "--rh", "0.25", "--film-thickness",
                                   "1.2nm", "--structured-film", "0.5 nm")  # fmt: skip
    assert [r["capillary"] for r in from_file] == [r["capillary"] for r in from_options]
    assert any(float(r["capillary"]) > 0 for r in from_file)  # below RH_dry, by the given film
    env = Environment(rh=0.25, film_thickness=1.2e-9, structured_film=0.5e-9)
    assert ("adsorbed film t = 1.2 nm (given)" in err
            and f"{env.wet_floor * 1e9:.4g} nm <= g < {env.condensation_gap * 1e9:.4g} nm" in err)  # fmt: skip
    f.write_text(plain.read_text() + "[environment]\nrh = 0.5\nfilm_thickness = 1e-9\n")
    code, _, err = run_cli(capsys, "analytic", "--surface", f, H)
    assert code != 0 and "[environment]: film_thickness = 1e-09 has no unit" in err


def test_below_rh_dry_the_note_names_the_film_and_the_structured_layers(capsys):
    rows, err = analytic_csv(capsys, "smooth", "--rh", "0.25")
    assert all(float(r["capillary"]) == 0 for r in rows)
    assert "no capillary bridges: adsorbed film t = 0.803 nm <= structured film 0.84 nm" in err


@pytest.mark.parametrize(
    ("given", "wavelength"), [("100nm", 100e-9), ("7 nm", 7e-9), ("none", None)]
)
def test_the_retardation_wavelength_option_sets_the_van_der_waals_law(capsys, given, wavelength):
    rows, err = analytic_csv(capsys, "smooth", "--hamaker", "1.6e-19", "--rh", "0.6",
                             f"--retardation-wavelength={given}")  # fmt: skip
    env = Environment(hamaker=1.6e-19, rh=0.6, retardation_wavelength=wavelength)
    ref = gw_curves(SURFACES["smooth"], MATERIALS["silicon"], [2, 1, 0], environment=env)
    np.testing.assert_array_equal([float(r["vdw"]) for r in rows], ref.values["vdw"])
    said = "none (non-retarded)" if wavelength is None else f"{wavelength * 1e9:.4g} nm"
    assert f"retardation wavelength = {said}" in err


def test_the_default_retardation_is_gregorys_100_nm(capsys):
    default, err = analytic_csv(capsys, "smooth", "--hamaker", "1.6e-19")
    given, _ = analytic_csv(capsys, "smooth", "--hamaker", "1.6e-19", "--retardation-wavelength",
                            "100nm")  # fmt: skip
    flat, _ = analytic_csv(capsys, "smooth", "--hamaker", "1.6e-19", "--retardation-wavelength",
                           "none")  # fmt: skip
    assert [r["vdw"] for r in default] == [r["vdw"] for r in given]
    assert all(float(a["vdw"]) < float(b["vdw"]) for a, b in zip(default, flat))
    assert "retardation wavelength = 100 nm" in err and "lambda = 100 nm" in err


def test_a_file_sets_the_retardation_wavelength_and_refuses_it_bare(capsys, tmp_path):
    f, plain = tmp_path / "s.toml", tmp_path / "plain.toml"
    plain.write_text('[surface]\nsigma = "1.4 nm"\nR = "1.7 um"\neta = "17 um^-2"\n')
    table = '[environment]\nhamaker = "1.6e-19 J"\nretardation_wavelength = '
    f.write_text(plain.read_text() + table + '"none"\n')
    from_file, _ = analytic_csv(capsys, str(f))
    from_options, _ = analytic_csv(capsys, str(plain), "--hamaker", "1.6e-19",
                                   "--retardation-wavelength", "none")  # fmt: skip
    assert [r["vdw"] for r in from_file] == [r["vdw"] for r in from_options]
    f.write_text(plain.read_text() + table + "1e-7\n")
    code, _, err = run_cli(capsys, "analytic", "--surface", f, H)
    assert code != 0 and "[environment]: retardation_wavelength = 1e-07 has no unit" in err


def test_a_file_refuses_a_bare_hamaker_and_unknown_keys(capsys, tmp_path):
    f = tmp_path / "s.toml"
    f.write_text('[surface]\nsigma = "1.4 nm"\nR = "1.7 um"\neta = "17 um^-2"\n'
                 "[environment]\nhamaker = 1.6e-19\n")  # fmt: skip
    code, _, err = run_cli(capsys, "analytic", "--surface", f, H)
    assert code != 0 and "[environment]: hamaker = 1.6e-19 has no unit" in err
    f.write_text('[surface]\nsigma = "1.4 nm"\nR = "1.7 um"\neta = "17 um^-2"\n'
                 "[environment]\nhumidity = 0.5\n")  # fmt: skip
    code, _, err = run_cli(capsys, "analytic", "--surface", f, H)
    assert code != 0 and "unknown key(s) humidity" in err


@pytest.mark.parametrize(
    ("option", "value", "message"),
    [
        ("--rh", "1", r"--rh: rh = 1.0 is out of range \(allowed: \[0, 1\)\)"),
        ("--rh", "-0.1", r"--rh: rh = -0.1 is out of range \(allowed: \[0, 1\)\)"),
        ("--hamaker", "-1e-20", r"--hamaker: hamaker = -1e-20 J is out of range \(allowed: \[0, 1e-16\] J\)"),
        ("--cutoff", "0 nm", r"--cutoff: cutoff = 0.0 m is out of range \(allowed: > 0 m\)"),
        ("--contact-angle", "180", r"--contact-angle: contact_angle = 180.0 deg is out of range \(allowed: \[0, 180\) deg\)"),
        ("--contact-angle", "-5", r"--contact-angle: contact_angle = -5.0 deg is out of range"),
        ("--temperature", "25 °C", r"--temperature: temperature: unknown unit '°C' for a temperature"),
        ("--hamaker", "1 nm", r"--hamaker: hamaker: unknown unit 'nm' for an energy"),
        ("--film-thickness", "-1nm", r"--film-thickness: film_thickness = -1e-09 m is out of range \(allowed: >= 0 m\)"),
        ("--structured-film", "-2 nm", r"--structured-film: structured_film = -2e-09 m is out of range \(allowed: >= 0 m\)"),
        ("--film-thickness", "1 J", r"--film-thickness: film_thickness: unknown unit 'J' for a length"),
        ("--retardation-wavelength", "0nm", r"--retardation-wavelength: retardation_wavelength = 0.0 m is out of range \(allowed: > 0 m\)"),
        ("--retardation-wavelength", "-5nm", r"--retardation-wavelength: retardation_wavelength = -5e-09 m is out of range"),
        ("--retardation-wavelength", "nan", r"--retardation-wavelength: retardation_wavelength: 'nan' is not finite"),
        ("--retardation-wavelength", "100 s", r"--retardation-wavelength: retardation_wavelength: unknown unit 's' for a length"),
        ("--retardation-wavelength", "abc", r"--retardation-wavelength: retardation_wavelength: cannot read 'abc'"),
    ],
)  # fmt: skip
def test_bad_values_get_one_line_naming_the_option(capsys, option, value, message):
    import re

    code, out, err = run_cli(capsys, "analytic", "--surface", "smooth", H, f"{option}={value}")
    assert code != 0 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and re.search(message, lines[0]), err


def test_contact_angle_of_90_degrees_or_more_says_no_condensation(capsys):
    rows, err = analytic_csv(capsys, "smooth", "--rh", "0.6", "--contact-angle", "100")
    assert "no capillary condensation: contact angle 100 deg >= 90 deg" in err
    assert all(float(r["capillary"]) == 0 for r in rows)


@pytest.mark.parametrize("command", ["analytic", "adhesion", "sweep", "simulate"])
def test_every_command_takes_the_environment_options(capsys, command):
    code, out, _ = run_cli(capsys, command, "--help")
    assert code == 0
    for option in ("--hamaker", "--cutoff", "--rh", "--contact-angle", "--temperature",
                   "--liquid-surface-tension", "--molar-volume", "--film-thickness",
                   "--structured-film", "--retardation-wavelength"):  # fmt: skip
        assert option in out, f"{command} {option}"


def test_show_of_a_humid_run_says_its_environment_and_preload(capsys, tmp_path):
    out_file = tmp_path / "humid.h5"
    code, _, err = run_cli(capsys, "simulate", "--surface", "smooth", "--law", "jkr", "--area",
                           "5um^2", "--h=-1:3:5", "--cycle", "--preload", "0", "--rh", "0.6",
                           "--hamaker", "1.6e-19J", "--realizations", "2", "--seed", "1", "--out",
                           out_file)  # fmt: skip
    assert code == 0, err
    code, out, err = run_cli(capsys, "show", out_file)
    assert code == 0, err
    lines = [line for line in out.splitlines() if line.startswith(("environment", "preload"))]
    assert any("Hamaker A = 1.6e-19 J" in line and "RH = 0.6" in line for line in lines)
    assert any(line.startswith("preload       0 Pa") for line in lines)

"""Defects a new user meets on the command line (issue 44, point 7): each is a one-line
``mcsim: error: ...`` naming the field, exit status 2 and nothing written, or a fixed output."""

import json
import sys
import warnings

import h5py
import numpy as np
import pytest
from conftest import run_cli

SCAN = "examples/scan.npy"  # periodic, 100 x 100 pixels of 10 nm, heights in m


def one_line_error(capsys, *argv) -> str:
    code, _, err = run_cli(capsys, *argv)
    assert code == 2, err
    assert err.startswith("mcsim: error: ") and err.count("\n") == 1, err
    return err


@pytest.fixture
def huge_map(tmp_path):
    """A 16 x 16 map whose heights (read in m) are about 1e300 m."""
    path = tmp_path / "huge.npy"
    np.save(path, np.random.default_rng(0).normal(size=(16, 16)) * 1e300)
    return path


@pytest.mark.parametrize("command", [["contact", "--pressure", "1MPa"],
                                     ["contact", "--pressure", "1MPa", "--adhesion"],
                                     ["ingest", "--calibrate"], ["ingest"]])  # fmt: skip
def test_absurd_heights_are_refused_by_name_before_any_work(capsys, tmp_path, huge_map, command):
    out = tmp_path / "out.toml"
    err = one_line_error(capsys, command[0], huge_map, *command[1:], "--unit", "m",
                         "--pixel-size", "10nm", "--out", out)  # fmt: skip
    assert "heights up to" in err and "allowed: |height| <= 1 m" in err
    assert list(tmp_path.iterdir()) == [huge_map]


@pytest.mark.parametrize("size", ["1e300m", "1e-300m"])
@pytest.mark.parametrize("command", [["contact", "--pressure", "1MPa"], ["ingest", "--calibrate"]])
def test_absurd_pixel_sizes_are_refused_by_name(capsys, tmp_path, command, size):
    out = tmp_path / "out.toml"
    err = one_line_error(capsys, command[0], SCAN, *command[1:], "--unit", "m",
                         "--pixel-size", size, "--out", out)  # fmt: skip
    assert "pixel size dx" in err and "allowed: 1e-12 m to 1 m" in err
    assert not any(tmp_path.iterdir())


@pytest.mark.parametrize(("argv", "option"), [
    (["contact", SCAN, "--unit", "m", "--pixel-size", "10nm", "--pressure", "-1MPa"], "--pressure"),
    (["contact", SCAN, "--unit", "m", "--pixel-size", "-1nm", "--pressure", "1MPa"], "--pixel-size"),
    (["ingest", SCAN, "--unit", "m", "--pixel-size", "-1nm"], "--pixel-size"),
    (["analytic", "--surface", "smooth", "--pressure", "-1MPa"], "--pressure"),
    (["simulate", "--surface", "smooth", "--area", "1um^2", "--h=1", "--cycle",
      "--law", "jkr", "--preload", "-1MPa"], "--preload"),
    (["simulate", "--surface", "smooth", "--area", "-1um^2", "--h=1"], "area"),
])  # fmt: skip
def test_a_negative_value_is_refused_by_name_as_not_positive(capsys, tmp_path, argv, option):
    out = [] if argv[0] == "analytic" else ["--out", tmp_path / "o.h5"]
    err = one_line_error(capsys, *argv, *out)
    assert "expected one argument" not in err
    assert err.startswith(("mcsim: error: " + option, "mcsim: error: " + option.lstrip("-"))), err
    assert "(allowed: > 0" in err or "(allowed: >= 0" in err, err
    assert not any(tmp_path.iterdir())


@pytest.mark.parametrize("h", ["-1", "-1,0", "-1:0:3", "-.5"])
def test_negative_separations_still_read_after_a_space(capsys, h):
    code, out, err = run_cli(capsys, "analytic", "--surface", "smooth", "--h", h, "--format", "csv")
    assert code == 0, err
    assert float(out.splitlines()[1].split(",")[0]) == float(h.split(",")[0].split(":")[0])


CYCLE = ["simulate", "--surface", "smooth", "--law", "jkr", "--area", "4um^2", "--cycle",
         "--preload", "1MPa", "--seed", "1"]  # fmt: skip


def test_a_preloaded_cycle_without_h_runs_over_the_sweep_grid_and_says_so(capsys, tmp_path):
    from mcsim.model.presets import MATERIALS, SURFACES
    from mcsim.physics.loadcontrol import preload_turn
    from mcsim.store.runfile import read_run

    code, _, err = run_cli(capsys, *CYCLE, "--out", tmp_path / "c.h5")
    assert code == 0, err
    turn = preload_turn(SURFACES["smooth"], MATERIALS["silicon"], 1e6, "jkr")
    assert (
        -1 < turn < 4 and f"--h=4:-1:51 (d/sigma; the preload's mean turn is h = {turn:.4g})" in err
    )
    np.testing.assert_allclose(read_run(tmp_path / "c.h5").h, np.linspace(4, -1, 51))
    assert f"mcsim pads {tmp_path / 'c.h5'}" in err.splitlines()[-1]  # the next step of a cycle


def test_a_preload_below_the_sweep_grid_extends_it_one_below_the_turn(capsys, tmp_path):
    from mcsim.store.runfile import read_run

    argv = [*CYCLE[:-3], "10GPa", "--seed", "1", "--quiet", "--out", tmp_path / "c.h5"]
    code, _, err = run_cli(capsys, *argv)
    assert code == 0, err
    h = read_run(tmp_path / "c.h5").h
    assert h[0] == 4 and h[-1] <= -2 and np.allclose(np.diff(h), -0.1)


def test_without_h_pressure_or_load_only_a_preloaded_cycle_runs(capsys, tmp_path):
    err = one_line_error(capsys, *CYCLE[:-5], "--out", tmp_path / "c.h5")  # no --cycle, --preload
    assert "--h --pressure --load is required" in err and "--cycle --preload" in err
    assert not any(tmp_path.iterdir())


def test_a_plain_run_s_next_hint_has_no_pads(capsys, tmp_path):
    code, _, err = run_cli(capsys, *CYCLE[:-5], "--h=1", "--out", tmp_path / "c.h5")
    assert code == 0 and "next: mcsim compare" in err and "mcsim pads" not in err


@pytest.fixture(scope="module")
def pads_sweep(tmp_path_factory):
    """A sweep of 10 pads of 4 um^2 at two sigmas, pressed with 1 MPa, against 2 uN."""
    from mcsim.cli.main import main

    path = tmp_path_factory.mktemp("sweep") / "stick.h5"
    argv = ["sweep", "--surface", "smooth", "--law", "jkr", "--vary", "sigma=1.5nm:3nm:2",
            "--preload", "1MPa", "--pads", "10", "--area", "4um^2", "--restoring-force", "2uN",
            "--seed", "1", "--quiet", "--out", str(path)]  # fmt: skip
    assert main(argv) == 0
    return path


@pytest.mark.parametrize("command", ["compare", "pads"])
def test_a_run_command_given_a_sweep_file_names_it_and_the_commands_that_read_it(
    capsys, pads_sweep, command
):
    err = one_line_error(capsys, command, pads_sweep)
    assert "a sweep file (mcsim sweep), not a run file" in err
    assert f"mcsim show {pads_sweep}" in err and "not an mcsim run file" not in err


def test_show_of_a_pads_sweep_prints_each_point_with_p_stick_and_its_interval(capsys, pads_sweep):
    from mcsim.store.sweepfile import read_sweep

    code, out, _ = run_cli(capsys, "show", pads_sweep)
    assert code == 0
    table = read_sweep(pads_sweep).table()
    lines = out.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("# results per point"))
    assert "p_stick: fraction of pads [95 % interval]" in lines[start]
    header, *rows = lines[start + 1 : start + 1 + len(table) + 1]
    assert header.split()[:2] == ["sigma", "law_used"] and "p_stick" in header.split()
    for row, (_, point) in zip(rows, table.iterrows(), strict=True):
        shown = f"{point.p_stick:.3g} [{point.p_stick_low:.3g}, {point.p_stick_high:.3g}]"
        assert shown in row and f"{point.pull_off_pressure:.6g}" in row


def test_compare_csv_prints_data_on_stdout_and_one_note_per_kind_on_stderr(capsys, tmp_path):
    run = tmp_path / "r.h5"
    code, _, _ = run_cli(capsys, *CYCLE[:-5], "--h=4:-1:26", "--quiet", "--out", run)
    assert code == 0
    code, out, err = run_cli(capsys, "compare", run, "--format", "csv")
    assert code == 0
    lines = out.splitlines()
    assert lines[0] == "h,branch,quantity,mc_mean,mc_se,analytic,z"
    assert all(line[0].isdigit() or line[0] == "-" for line in lines[1:])
    empty = sum(line.endswith(",") for line in lines[1:])  # rows whose z is left empty
    assert empty > 10
    assert err.splitlines() == [
        line for line in err.splitlines() if line.startswith("mcsim: note:")
    ]
    assert len(err.splitlines()) == 1 and f"z left empty in {empty} row(s)" in err


def test_a_monte_carlo_sweep_says_its_regime_warning_once(capsys, tmp_path):
    code, _, err = run_cli(capsys, "sweep", "--surface", "smooth", "--law", "jkr", "--vary",
                           "sigma=1.5nm,2nm,3nm", "--mc", "--area", "1um^2", "--h=2:0:3",
                           "--seed", "1", "--out", tmp_path / "s.h5")  # fmt: skip
    assert code == 0, err
    assert err.count("outside the JKR zone") == 1, err
    assert "3 of 3 points outside their law set's regime" in err


def test_a_sweep_warns_once_where_gw_s_area_passes_the_nominal_area(capsys, tmp_path):
    import mcsim
    from mcsim.model.presets import MATERIALS, SURFACES
    from mcsim.physics.adhesion import ValidityWarning

    vary = {"sigma": "0.3nm:20nm:4:log"}
    with pytest.warns(ValidityWarning, match="passes the nominal area") as caught:
        result = mcsim.sweep(SURFACES["smooth"], MATERIALS["silicon"], vary, law="dmt",
                             h=np.linspace(4, -1, 51))  # fmt: skip
    largest = float(np.nanmax(result.data["area"]))
    assert largest > 1 and f"A_r/A_n = {largest:.3g}" in str(caught[0].message)
    assert len([w for w in caught if issubclass(w.category, ValidityWarning)]) == 1
    code, _, err = run_cli(capsys, "sweep", "--surface", "smooth", "--law", "dmt", "--vary",
                           "sigma=0.3nm:20nm:4:log", "--out", tmp_path / "s.h5")  # fmt: skip
    assert code == 0
    lines = [line for line in err.splitlines() if "passes the nominal area" in line]
    assert len(lines) == 1 and lines[0].startswith("mcsim: warning: at 1 of 4 points: ")
    assert f"A_r/A_n = {largest:.3g} at h = -1" in lines[0]


@pytest.mark.parametrize(("text", "dimension", "si"), [
    ("10uN", "force", 1e-05), ("17 um^-2", "density", 1.7e13), ("1.7um", "length", 1.7e-06),
    ("20 deg", "angle", 20 * np.pi / 180), ("0.16 aJ", "energy", 1.6e-19),
])  # fmt: skip
def test_a_quantity_with_a_unit_is_the_nearest_float_to_its_decimal_value(text, dimension, si):
    from mcsim.model.units import parse_quantity

    assert parse_quantity(text, dimension, "x") == si  # rounded once: no spurious digits


def test_a_load_over_an_area_prints_the_pressure_without_spurious_digits(capsys):
    import json

    code, out, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--law", "jkr", "--load",
                           "10uN", "--area", "100um^2", "--format", "json")  # fmt: skip
    assert code == 0
    assert [row["pressure"] for row in json.loads(out)["rows"]] == [100000.0]
    assert '"pressure": 100000.0' in out


def test_a_negative_work_of_separation_comes_with_a_note_on_its_meaning(capsys, tmp_path):
    surface = tmp_path / "s3.toml"
    surface.write_text('[surface]\nsigma = "3 nm"\nR = "1.7 um"\neta = "17 um^-2"\n')
    code, out, err = run_cli(capsys, "adhesion", "--surface", surface, "--law", "jkr",
                             "--preload", "1MPa", "--format", "json")  # fmt: skip
    work = json.loads(out)["work_of_separation"]
    assert code == 0 and work < 0
    assert f"note: the work of separation is negative ({work:.4g} J/m^2): it is signed" in err
    code, _, err = run_cli(capsys, "adhesion", "--surface", surface, "--law", "jkr")
    assert code == 0 and "negative" not in err  # at zero load: only the tensile part
    code, _, err = run_cli(capsys, "sweep", "--surface", "smooth", "--law", "jkr", "--vary",
                           "sigma=1.5nm,3nm", "--preload", "1MPa", "--out", tmp_path / "w.h5")  # fmt: skip
    assert code == 0 and "note: at 1 of 2 points (work_of_separation) the work of separation" in err


def test_pads_shows_a_progress_bar_over_the_pads_on_a_terminal(capsys, tmp_path, monkeypatch):
    run = tmp_path / "c.h5"
    code, _, _ = run_cli(capsys, *CYCLE, "--h=4:-1:26", "--realizations", "3", "--quiet",
                         "--out", run)  # fmt: skip
    assert code == 0
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)
    code, out, err = run_cli(capsys, "pads", run)
    assert code == 0 and "/3 [" in err and "pads/s" in err  # tqdm over the 3 pads
    code, quiet_out, err = run_cli(capsys, "pads", run, "--quiet")
    assert code == 0 and "/3 [" not in err and quiet_out == out


def test_adhesive_contact_prints_one_line_warnings_only_and_bounds_its_steps(capsys):
    code, _, err = run_cli(capsys, "contact", SCAN, "--unit", "m", "--pixel-size", "10nm",
                           "--pressure", "1MPa", "--adhesion", "--steps", "4", "--quiet")  # fmt: skip
    assert code == 0
    assert "Warning:" not in err and all(line.startswith("mcsim: ") for line in err.splitlines())
    assert "mcsim: warning: the grid does not resolve the interaction" in err
    err = one_line_error(capsys, "contact", SCAN, "--pressure", "1MPa", "--adhesion", "--steps",
                         "1000000000")  # fmt: skip
    assert "--steps" in err and "from 2 to 10000" in err


def test_pads_against_a_huge_restoring_force_is_quiet_and_never_sticks(capsys, tmp_path):
    run = tmp_path / "c.h5"  # pads of 30 um^2: ~500 summits each, the model's saddlepoint
    code, _, _ = run_cli(capsys, *CYCLE, "--h=4:-1:26", "--realizations", "3", "--quiet",
                         "--area", "30um^2", "--out", run)  # fmt: skip
    assert code == 0
    with warnings.catch_warnings():  # the CLI would print it as a raw Python warning
        warnings.simplefilter("error", RuntimeWarning)
        code, out, _ = run_cli(capsys, "pads", run, "--restoring-force", "1e300N", "--format",
                               "json")  # fmt: skip
    assert code == 0
    report = json.loads(out)
    assert report["p_stick"] == 0 and report["p_stick_model"] == 0


def test_an_absurd_work_of_adhesion_is_refused_by_name_before_any_solve(capsys, tmp_path):
    err = one_line_error(capsys, "ingest", SCAN, "--unit", "m", "--pixel-size", "10nm",
                         "--calibrate", "--w", "1e300J/m^2", "--out", tmp_path / "s.toml")  # fmt: skip
    assert err.startswith("mcsim: error: w = 1e+300 J/m^2 is out of range (allowed: 0 < w <= 100")
    assert not any(tmp_path.iterdir())
    err = one_line_error(capsys, "contact", SCAN, "--unit", "m", "--pixel-size", "10nm",
                         "--pressure", "1MPa", "--adhesion", "--w", "1e300J/m^2")  # fmt: skip
    assert err.startswith("mcsim: error: w = 1e+300 J/m^2 is out of range (allowed: 0 < w <= 100")


def test_an_option_of_other_commands_says_which_instead_of_suggesting_itself(capsys, tmp_path):
    err = one_line_error(capsys, "pads", tmp_path / "run.h5", "--rh", "0.5")
    assert "did you mean '--rh'" not in err
    assert (
        "--rh is an option of mcsim analytic, adhesion, simulate, sweep, contact, report, not of mcsim pads"
        in err
    )


def test_a_command_run_in_process_records_its_own_arguments_not_the_interpreters(
    capsys, tmp_path, monkeypatch
):
    # main([...]) from a notebook: sys.argv is the kernel's, not the command's
    monkeypatch.setattr(sys, "argv", ["ipykernel_launcher.py", "-f", "kernel.json"])
    out = tmp_path / "t.h5"
    code, _, err = run_cli(capsys, "simulate", "--surface", "smooth", "--area", "1e-10",
                           "--h=3,2", "--realizations", "2", "--seed", "1", "--out", out)  # fmt: skip
    assert code == 0, err
    with h5py.File(out) as f:
        command = f.attrs["command"]
    assert (
        command
        == f"mcsim simulate --surface smooth --area 1e-10 --h=3,2 --realizations 2 --seed 1 --out {out}"
    )


def test_sigterm_ends_any_command_as_ctrl_c_does_with_status_143(capsys, tmp_path):
    # `mcsim pads` died of SIGTERM with no line of its own (only the resource tracker's
    # warning of leaked semaphores); the command line now raises it as Ctrl-C in every
    # command: one line, status 143, no output written
    import os
    import signal
    import threading

    from mcsim.cli.main import terminate

    run, png = tmp_path / "c.h5", tmp_path / "pads.png"
    code, _, err = run_cli(capsys, "simulate", "--surface", "smooth", "--law", "jkr", "--area",
                           "3um^2", "--h=4:-1:51", "--realizations", 300, "--seed", 2, "--cycle",
                           "--preload", "1MPa", "--workers", 1, "--quiet", "--out", run)  # fmt: skip
    assert code == 0, err
    previous = signal.signal(signal.SIGTERM, terminate)  # as the console entry point does
    try:
        threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGTERM)).start()
        code, _, err = run_cli(capsys, "pads", run, "--restoring-force", "1uN", "--workers", 1,
                               "--plot", png)  # fmt: skip
    finally:
        signal.signal(signal.SIGTERM, previous)
    assert code == 143 and err == "mcsim: interrupted (SIGTERM); no output written\n", err
    assert not png.exists()

"""The mcsim command line: outputs, formats and one-line errors with non-zero exit codes."""

import csv
import io
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from conftest import interrupt, run_cli
from tolerances import ROUNDING_FORMULA

from mcsim.cli.main import main
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.analytic import gw_curves


def test_analytic_csv_has_the_six_columns_and_the_analytic_values(capsys):
    code, out, _ = run_cli(
        capsys, "analytic", "--surface", "smooth", "--h=4:-1:6", "--format", "csv"
    )
    assert code == 0
    rows = list(csv.DictReader(io.StringIO(out)))
    assert list(rows[0]) == ["h", "contact_fraction", "P", "F", "T", "mu"]
    h = [float(r["h"]) for r in rows]
    assert h == [4.0, 3.0, 2.0, 1.0, 0.0, -1.0]
    ref = gw_curves(SURFACES["smooth"], MATERIALS["silicon"], h)
    for q in ("contact_fraction", "P", "F", "T", "mu"):
        np.testing.assert_array_equal([float(r[q]) for r in rows], getattr(ref, q), err_msg=q)


def test_analytic_json_and_table_formats(capsys):
    _, out, _ = run_cli(
        capsys, "analytic", "--surface", "rough", "--h=-1,0,1.5", "--format", "json"
    )
    data = json.loads(out)
    assert [d["h"] for d in data] == [-1.0, 0.0, 1.5]
    _, out, _ = run_cli(capsys, "analytic", "--surface", "rough", "--h=0")
    assert "plasticity index psi" in out and "mu" in out


def test_analytic_reads_a_surface_file_with_units(capsys, tmp_path):
    f = tmp_path / "s.toml"
    f.write_text('[surface]\nsigma = "1.4 nm"\nR = "1.7 um"\neta = "17 um^-2"\n')
    _, a, _ = run_cli(capsys, "analytic", "--surface", str(f), "--h=0,1", "--format", "csv")
    _, b, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--h=0,1", "--format", "csv")
    # the preset and the same surface typed in a file (decimal text times units):
    # ROUNDING_FORMULA
    np.testing.assert_allclose(np.loadtxt(io.StringIO(a), delimiter=",", skiprows=1),
                               np.loadtxt(io.StringIO(b), delimiter=",", skiprows=1), rtol=ROUNDING_FORMULA)  # fmt: skip


def test_simulate_then_compare_csv_rows_have_small_z(capsys, tmp_path):
    out = tmp_path / "t.h5"
    code, _, err = run_cli(capsys, "simulate", "--surface", "smooth", "--area", "1e-9", "--h=3:-1:9",
                           "--realizations", "8", "--seed", "1", "--out", str(out))  # fmt: skip
    assert code == 0 and out.exists() and f"mcsim: wrote {out}" in err
    code, text, _ = run_cli(capsys, "compare", str(out), "--format", "csv")
    rows = list(csv.DictReader(io.StringIO(text)))
    assert list(rows[0]) == ["h", "branch", "quantity", "mc_mean", "mc_se", "analytic", "z"]
    assert {r["branch"] for r in rows} == {"approach"}
    assert len(rows) == 9 * 5
    assert {r["quantity"] for r in rows} == {"contact_fraction", "P", "F", "T", "mu"}
    z = np.array([float(r["z"]) for r in rows if r["z"]])
    assert z.size >= 40 and np.all(np.abs(z) < 5)


def test_show_and_plot_describe_a_run(capsys, tmp_path):
    out = tmp_path / "t.h5"
    run_cli(
        capsys,
        "simulate",
        "--surface",
        "rough",
        "--area",
        "100um^2",
        "--h=2,0",
        "--seed",
        "2",
        "--out",
        str(out),
    )
    code, text, _ = run_cli(capsys, "show", str(out))
    assert code == 0
    for word in (
        "seed entropy  2",
        "sigma = 15.8 nm",
        "A = 100 um^2",
        "law set       seed",
        "device        cpu",
    ):
        assert word in text
    code, text, _ = run_cli(capsys, "plot", str(out), "--out", str(tmp_path / "p.png"))
    assert code == 0 and (tmp_path / "p.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["analytic", "--surface", "smoth", "--h=0"], "unknown surface 'smoth'"),
        (
            ["analytic", "--surface", "smooth", "--material", "steel", "--h=0"],
            "unknown material 'steel'",
        ),
        (["analytic", "--surface", "smooth", "--h="], "empty list of separations"),
        (["analytic", "--surface", "smooth", "--h=1,x"], "cannot read '1,x'"),
        (["analytic", "--surface", "smooth", "--h=1:2"], "cannot read '1:2'"),
        (["analytic", "--surface", "smooth", "--h=1,nan"], "separations must be finite"),
        (["analytic", "--surface", "smooth", "--h=1:0:0"], "asks for 0 points"),
        (["analytic", "--surface", "smooth", "--law", "dmtx", "--h=0"], "unknown law set 'dmtx'"),
        (
            ["simulate", "--surface", "smooth", "--area", "0", "--h=0"],
            r"area = 0.0 m\^2 is out of range",
        ),
        (["simulate", "--surface", "smooth", "--area=-1um^2", "--h=0"], "area = -1e-12"),
        (
            ["simulate", "--surface", "smooth", "--area", "1 parsec^2", "--h=0"],
            "unknown unit 'parsec",
        ),
        (
            ["simulate", "--surface", "smooth", "--area", "1e-9", "--h=0", "--realizations", "0"],
            r"argument --realizations: 0 is out of range \(allowed: integer >= 1\)",
        ),
        (
            [
                "simulate",
                "--surface",
                "smooth",
                "--area",
                "1e-9",
                "--h=0",
                "--out",
                "/nonexistent/x.h5",
            ],
            "does not exist",
        ),
        (["compare", "missing.h5"], "missing.h5: no such file"),
        (["show", "missing.h5"], "no such file"),
    ],
)
def test_bad_input_prints_one_line_and_exits_2(capsys, argv, message):
    code, _, err = run_cli(capsys, *argv)
    assert code == 2
    assert err.count("\n") == 1 and err.startswith("mcsim: error: ")
    assert __import__("re").search(message, err), err


def test_debug_flag_shows_the_traceback():
    with pytest.raises(Exception, match="unknown surface"):
        main(["--debug", "analytic", "--surface", "smoth", "--h=0"])


def test_installed_entry_point_reports_version_and_fails_cleanly():
    exe = os.path.join(os.path.dirname(sys.executable), "mcsim")
    done = subprocess.run([exe, "--version"], capture_output=True, text=True)
    assert done.returncode == 0 and done.stdout.startswith("mcsim ")
    done = subprocess.run(
        [exe, "analytic", "--surface", "smoth", "--h=0"], capture_output=True, text=True
    )
    assert done.returncode == 2 and "Traceback" not in done.stderr


def test_ctrl_c_leaves_a_resumable_run_that_resumes_to_identical_numbers(
    tmp_path, long_run_reference
):
    """SIGINT during a long simulate: exit 130, an incomplete run in the checkpoint beside
    the path (another run in the folder untouched, no temporaries); --resume then gives the
    uninterrupted datasets."""
    import h5py

    from mcsim.engine.kernels import SUM_COLUMNS
    from mcsim.store.files import checkpoint_path
    from mcsim.store.runfile import read_state

    exe = os.path.join(os.path.dirname(sys.executable), "mcsim")
    other = tmp_path / "other.h5"
    assert main(["simulate", "--surface", "rough", "--area", "1e-10", "--h=0", "--out", str(other),
                 "--quiet"]) == 0  # fmt: skip
    before = other.read_bytes()
    out = tmp_path / "t.h5"
    args = ["simulate", "--surface", "smooth", "--h=2:-1:7", "--area", "1e-8", "--realizations", "500",
            "--seed", "3", "--workers", "1", "--out", str(out)]  # fmt: skip
    env = {**os.environ, "PYTHONFAULTHANDLER": "1"}
    proc = subprocess.Popen(
        [exe, *args, "--checkpoint-every", "0.05"], stderr=subprocess.PIPE, text=True, env=env
    )
    deadline = time.monotonic() + 30
    while not checkpoint_path(out).exists() and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.01)  # until the run has checkpointed some progress
    assert proc.poll() is None, "the long run finished before it could be interrupted"
    code, err = interrupt(proc)
    assert code == 130, err
    assert "--resume" in err
    state, _ = read_state(checkpoint_path(out))
    assert not state.complete and state.done_blocks.sum() > 0
    assert other.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["other.h5", "t.partial.h5"]

    assert main([*args, "--resume", "--quiet"]) == 0
    reference = long_run_reference  # the uninterrupted run of args
    with h5py.File(out) as f:
        assert f.attrs["complete"]
        columns = [f[f"realizations/sums/{c}"][()] for c in SUM_COLUMNS]
        np.testing.assert_array_equal(np.stack(columns, axis=-1), reference.sums)
        np.testing.assert_array_equal(f["summary/se/mu"][()], reference.summary.se["mu"])


def test_unreachable_dask_scheduler_is_a_one_line_error(capsys, tmp_path, monkeypatch):
    pytest.importorskip("distributed", reason="Dask (extra 'dask') not installed")
    import mcsim.engine.cluster

    monkeypatch.setattr(
        mcsim.engine.cluster, "CONNECT_TIMEOUT", 0.5
    )  # nothing listens: no need to wait
    code, _, err = run_cli(capsys, "simulate", "--surface", "smooth", "--area", "1e-10", "--h=0",
                           "--scheduler", "tcp://127.0.0.1:9", "--out", str(tmp_path / "x.h5"))  # fmt: skip
    assert code == 2 and "cannot reach the Dask scheduler at 'tcp://127.0.0.1:9'" in err
    assert not (tmp_path / "x.h5").exists()


@pytest.mark.parametrize(
    ("surface", "message"),
    [
        (
            'sigma = "-1.4 nm"\nR = "1.7 um"\neta = "17 um^-2"',
            r"sigma = -1.4e-09 m is out of range \(allowed: \[1e-12, 0.01\] m\)",
        ),
        ('sigma = "1.4 nm"\nR = "0 um"\neta = "17 um^-2"', r"R = 0.0 m is out of range"),
        (
            'sigma = "1.4 nm"\nR = "1.7 um"\neta = "-17 um^-2"',
            r"eta = -1[0-9.e+]* m\^-2 is out of range \(allowed: \[1, 1e\+20\] m\^-2\)",
        ),
        ('sigma = "1.4 nm"\nR = "1.7 um"\neta = "inf um^-2"', "not finite"),
        ('sigma = "1.4 parsec"\nR = "1.7 um"\neta = "17 um^-2"', "unknown unit 'parsec'"),
        ('sigma = "1.4 nm"\nR = "1.7 um"', "missing key 'eta'"),
    ],
)
def test_invalid_surface_file_values_give_one_line_and_exit_2(capsys, tmp_path, surface, message):
    f = tmp_path / "s.toml"
    f.write_text(f"[surface]\n{surface}\n")
    code, _, err = run_cli(capsys, "analytic", "--surface", str(f), "--h=0")
    assert code == 2 and err.count("\n") == 1
    assert str(f) in err and __import__("re").search(message, err), err


@pytest.mark.parametrize(
    ("material", "message"),
    [
        (
            'E = "-160 GPa"\nnu = 0.22\ngamma = "0.5 J/m^2"',
            r"E1 = -160000000000.0 Pa is out of range \(allowed: >= 1 Pa\)",
        ),
        (
            'E = "160 GPa"\nnu = 0.5\ngamma = "0.5 J/m^2"',
            r"nu1 = 0.5 is out of range \(allowed: \(-1, 0.5\)\)",
        ),
        ('E = "160 GPa"\nnu = -1\ngamma = "0.5 J/m^2"', r"nu1 = -1.0 is out of range"),
        (
            'E = "160 GPa"\nnu = 0.22\ngamma = "-0.5 J/m^2"',
            r"gamma = -0.5 J/m\^2 is out of range \(allowed: \[0, 1000\]",
        ),
        (
            'E = "160 GPa"\nnu = 0.22\ngamma = "0.5 J/m^2"\nH = "0 GPa"',
            r"H = 0.0 Pa is out of range",
        ),
        ('E = "160 GPa"\nnu = 0.22', "missing key 'gamma'"),
    ],
)
def test_invalid_material_file_values_give_one_line_and_exit_2(capsys, tmp_path, material, message):
    f = tmp_path / "m.toml"
    f.write_text(f"[material]\n{material}\n")
    code, _, err = run_cli(capsys, "analytic", "--surface", "smooth", "--material", str(f), "--h=0")
    assert code == 2 and err.count("\n") == 1
    assert str(f) in err and __import__("re").search(message, err), err


def test_json_output_is_strict_json_with_null_for_undefined_values(capsys, tmp_path):
    out = tmp_path / "t.h5"
    run_cli(capsys, "simulate", "--surface", "smooth", "--area", "1e-10", "--h=4,0", "--seed", "1",
            "--out", str(out), "--quiet")  # fmt: skip
    _, text, _ = run_cli(capsys, "compare", str(out), "--format", "json")
    rows = json.loads(text, parse_constant=lambda c: pytest.fail(f"non-standard JSON constant {c}"))
    few = [r for r in rows if r["h"] == 4.0]
    assert all(r["z"] is None for r in few) and all(r["note"] for r in few)


@pytest.fixture
def toy_material(monkeypatch, tmp_path, law_set_cache):
    """The test-only toy law set registered, and a material file giving tau."""
    from lawset_toy import TOY, TOY_APPROACH_ONLY

    from mcsim.physics.laws import LAW_SETS

    monkeypatch.setenv("MCSIM_CACHE_DIR", law_set_cache)
    monkeypatch.setitem(LAW_SETS, TOY.name, TOY)
    monkeypatch.setitem(LAW_SETS, TOY_APPROACH_ONLY.name, TOY_APPROACH_ONLY)
    path = tmp_path / "m.toml"
    path.write_text('[material]\nE = "160 GPa"\nnu = 0.22\ngamma = "0.5 J/m^2"\ntau = "100 MPa"\n')
    return str(path)


def test_simulate_cycle_with_a_law_set_then_compare_lists_both_branches(
    capsys, tmp_path, toy_material
):
    out = tmp_path / "t.h5"
    code, _, _ = run_cli(capsys, "simulate", "--surface", "smooth", "--material", toy_material,
                         "--law", "toy", "--cycle", "--area", "1e-10", "--h=2:0:3", "--seed", "1",
                         "--out", str(out), "--quiet")  # fmt: skip
    assert code == 0
    code, text, _ = run_cli(capsys, "compare", str(out), "--format", "csv")
    rows = list(csv.DictReader(io.StringIO(text)))
    assert list(rows[0]) == ["h", "branch", "quantity", "mc_mean", "mc_se", "analytic", "z"]
    assert [(r["h"], r["branch"]) for r in rows[:: len(rows) // 6]] == [
        ("2.0", "approach"), ("1.0", "approach"), ("0.0", "approach"),
        ("2.0", "retract"), ("1.0", "retract"), ("0.0", "retract")]  # fmt: skip
    assert {r["quantity"] for r in rows} == {
        "contact_fraction",
        "load",
        "area",
        "grip",
        "friction",
        "mu",
    }
    _, text, _ = run_cli(capsys, "show", str(out))
    assert "cycle: approach, then retraction from h = 0" in text
    code, text, _ = run_cli(capsys, "plot", str(out), "--out", str(tmp_path / "c.png"))
    assert code == 0 and (tmp_path / "c.png").stat().st_size > 10_000


def test_cycle_with_a_law_set_without_retraction_is_a_one_line_error(
    capsys, tmp_path, toy_material
):
    code, _, err = run_cli(capsys, "simulate", "--surface", "smooth", "--material", toy_material,
                           "--law", "toy-approach", "--cycle", "--area", "1e-10", "--h=1,0",
                           "--out", str(tmp_path / "t.h5"))  # fmt: skip
    assert code != 0 and len(err.strip().splitlines()) == 1
    assert "law set 'toy-approach' has no retraction branch" in err


def _writing_commands(tmp_path, run_file):
    """Every command that writes a file, with the file it writes."""
    png = tmp_path / "f.png"
    return [
        (["analytic", "--surface", "smooth", "--law", "jkr", "--pressure", "1kPa,1MPa",
          "--plot", png], png),
        (["adhesion", "--surface", "smooth", "--law", "jkr", "--plot", png], png),
        (["plot", run_file, "--out", png], png),
        (["pads", run_file, "--plot", png], png),
        (["simulate", "--surface", "smooth", "--law", "jkr", "--area", "2um^2", "--h=2:0:3",
          "--cycle", "--realizations", "2", "--seed", "1", "--out", tmp_path / "s.h5"],
         tmp_path / "s.h5"),
        (["sweep", "--surface", "smooth", "--vary", "sigma=1nm,2nm", "--h=1,0",
          "--out", tmp_path / "w.h5"], tmp_path / "w.h5"),
        (["ingest", "examples/scan.txt", "--pixel-size", "10nm", "--unit", "nm",
          "--out", tmp_path / "scan.toml"], tmp_path / "scan.toml"),
    ]  # fmt: skip


@pytest.mark.parametrize("index", range(7))
def test_every_written_file_is_announced_on_stderr_and_quiet_silences_it(
    capsys, tmp_path, monkeypatch, index
):
    import shutil

    root = Path(__file__).resolve().parents[2]
    shutil.copytree(root / "examples", tmp_path / "examples")
    run_file = tmp_path / "c.h5"
    assert run_cli(capsys, "simulate", "--surface", "smooth", "--law", "jkr", "--area", "2um^2",
                   "--h=2:0:3", "--cycle", "--realizations", "3", "--seed", "1",
                   "--out", run_file, "--quiet")[0] == 0  # fmt: skip
    argv, written = _writing_commands(tmp_path, run_file)[index]
    monkeypatch.chdir(tmp_path)
    code, out, err = run_cli(capsys, *argv)
    assert code == 0, err
    assert f"mcsim: wrote {written}" in err and "wrote" not in out
    code, out, err = run_cli(capsys, *argv, "--quiet", "--overwrite")
    assert code == 0 and written.exists() and "wrote" not in err + out


def test_paper_announces_every_file_it_wrote(capsys, tmp_path):
    code, _, err = run_cli(capsys, "paper", "--no-mc", "--out", tmp_path / "paper")
    written = [Path(line.removeprefix("mcsim: wrote ")) for line in err.splitlines()
               if line.startswith("mcsim: wrote ")]  # fmt: skip
    assert code == 0 and len(written) == 7  # five figures and two tables
    assert all(path.is_file() for path in written)

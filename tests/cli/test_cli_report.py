"""``mcsim report``: one command, two files (HTML and JSON) or none."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import mcsim.studies.report as study
from mcsim.cli.main import main
from mcsim.studies.report import Report, lot

SCAN = str(Path(__file__).resolve().parents[2] / "examples" / "scan.npy")
DEVICE = ["--unit", "m", "--pixel-size", "10nm", "--restoring-force", "1uN", "--quiet"]

_PNG = (b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\x00\x00\x00\x01\x00\x00\x00\x01\x08\x06\x00\x00"
        b"\x00\x1f\x15\xc4\x89\x00\x00\x00\rIDATx\x9cc\xf8\xcf\xc0\xf0\x1f\x00\x05\x00\x01\xff"
        b"\x89\x99=\x1d\x00\x00\x00\x00IEND\xaeB`\x82")  # fmt: skip


def _report(**kwargs) -> Report:
    """A report with made-up numbers: what the command does with it, not the physics."""
    row = {"rh": 0.5, "p_stick": 0.25, "p_stick_low": 0.1, "p_stick_high": 0.45,
           "p_stick_method": "pads", "p_stick_ess": 5.0, **lot(0.25, 0.1, 0.45, 10),
           "rh_margin": -0.2, "pull_off_mean": 1e-6, "work_of_separation_mean": 1e-3,
           "warnings": []}  # fmt: skip
    return Report(
        inputs={"scan": SCAN, "command": "mcsim report"}, version="0", created="now",
        elapsed=1.0, scan={}, contact={"pressure": [], "load": [], "exact_area": [],
        "gw_area": [], "gw_calibrated_area": [], "exact_mean_gap": [], "patches": []},
        stickiness={}, device={"devices": 10, "pads": 4, "pad_area": 1e-12, "law": "jkr",
        "law_choice": "", "restoring_force_from": "given"},
        humidity={"rh_dry": 0.3, "rh_cr": 0.3}, rows=[row], warnings={},
        figures={"stiction": _PNG, "contact": _PNG},
    )  # fmt: skip


@pytest.fixture
def fake(monkeypatch):
    """``report`` replaced by one that records its arguments and returns :func:`_report`."""
    calls = []

    def report(*args, **kwargs):
        calls.append((args, kwargs))
        return _report()

    monkeypatch.setattr(study, "report", report)
    return calls


def test_it_writes_the_html_and_the_json_beside_it(fake, tmp_path, capsys):
    out = tmp_path / "lot.html"
    assert main(["report", SCAN, *DEVICE, "--rh", "0,0.5", "--devices", "10",
                 "--out", str(out)]) == 0  # fmt: skip
    assert out.read_text().startswith("<!DOCTYPE html>")
    data = json.loads(out.with_suffix(".json").read_text())
    assert data["rows"][0]["p_any"] == pytest.approx(1 - 0.75**10)
    ((_, kwargs),) = fake
    assert kwargs["rh"] == "0,0.5" and kwargs["devices"] == 10 and kwargs["pad_area"] == "10um^2"
    assert kwargs["restoring_force"] == "1uN" and kwargs["progress"] is False
    assert kwargs["command"].split()[0] == "mcsim"  # the command line, recorded


def test_the_environment_options_reach_the_report(fake, tmp_path):
    out = tmp_path / "r.html"
    assert main(["report", SCAN, *DEVICE, "--asperity-roughness", "0.5nm", "--hamaker", "0",
                 "--out", str(out)]) == 0  # fmt: skip
    env = fake[0][1]["environment"]
    assert env.asperity_roughness == pytest.approx(0.5e-9) and env.hamaker == 0


def test_an_existing_report_is_kept_without_overwrite(fake, tmp_path, capsys):
    out = tmp_path / "r.html"
    out.with_suffix(".json").write_text("mine")
    assert main(["report", SCAN, *DEVICE, "--out", str(out)]) == 2
    assert "r.json: file exists (pass --overwrite to replace it)" in capsys.readouterr().err
    assert fake == []  # refused before any work
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.json"]
    assert main(["report", SCAN, *DEVICE, "--out", str(out), "--overwrite"]) == 0
    assert json.loads(out.with_suffix(".json").read_text())["version"] == "0"


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--devices", "0"], "--devices"),
        (["--devices", "-2"], "--devices"),
        (["--rh", "0,1.2"], "rh = 1.2: out of range (allowed: 0 <= RH < 1)"),
        (["--pad-area", "1nm^2"], "cannot touch"),
        (["--restoring-force", "0uN"], "restoring_force = 0.0 N: out of range"),
        (["--out", "r.txt"], "its name must end in .html"),
    ],
)
def test_bad_input_is_one_line_and_writes_nothing(argv, message, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["report", SCAN, *DEVICE, *argv]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []


def test_a_scan_that_does_not_read_is_one_line(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "bad.npy").write_bytes(b"not a map")
    assert main(["report", "bad.npy", *DEVICE]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mcsim: error: bad.npy") and err.count("\n") == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.npy"]


def test_ctrl_c_during_the_work_leaves_nothing(tmp_path, capsys, monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(study, "report", interrupted)
    monkeypatch.chdir(tmp_path)
    assert main(["report", SCAN, *DEVICE]) == 130
    assert "interrupted (SIGINT); no output written" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_ctrl_c_between_the_two_files_leaves_neither(fake, tmp_path, monkeypatch):
    import mcsim.store.outputs as outputs

    real = outputs.write_atomic

    def then_interrupted(path, write, **kwargs):
        real(path, write, **kwargs)
        raise KeyboardInterrupt  # as if Ctrl-C landed right after the first file

    monkeypatch.setattr(outputs, "write_atomic", then_interrupted)
    monkeypatch.chdir(tmp_path)
    assert main(["report", SCAN, *DEVICE]) == 130
    assert list(tmp_path.iterdir()) == []


def test_the_readme_command_and_defaults_are_the_parsers():
    """README, "From a scan to a stiction report": its command parses, and the defaults it
    names (100 pads per RH, importance sampling below 10 on a side) are the code's."""
    import re
    import shlex

    from mcsim.cli.main import build_parser
    from mcsim.studies.rareevent import MIN_TAIL_PADS, SWITCH

    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text()
    section = readme.split("## From a scan to a stiction report", 1)[1].split("\n## ", 1)[0]
    command = re.search(r"```bash\n(.*?)```", section, re.S)[1].replace("\\\n", " ")
    argv = shlex.split(command.split("#")[0])
    args = build_parser().parse_args(argv[1:])
    assert (args.pad_area, args.restoring_force, args.devices) == ("10um^2", "10uN", 1000)
    defaults = build_parser().parse_args(["report", SCAN])
    assert defaults.pads == 100 == study.DEFAULT_PADS == MIN_TAIL_PADS
    assert "pads (100)" in section and "fewer than 10 pads" in section and SWITCH == 10

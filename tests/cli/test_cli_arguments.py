"""Command-line arguments: every bad value is one line, ``mcsim: error: ...``, exit status 2.

argparse's own errors (unknown option, bad type, missing argument) included; ``--help``
keeps its usual multi-line output.
"""

import re

import pytest

from mcsim.cli.main import main

SIMULATE = ["simulate", "--surface", "smooth", "--area", "1um^2", "--h=0", "--quiet"]


def one_line_error(capsys, argv) -> str:
    status = main(argv)
    err = capsys.readouterr().err
    assert status == 2
    assert err.startswith("mcsim: error: ") and err.count("\n") == 1, err
    return err


@pytest.mark.parametrize(
    ("option", "message"),
    [
        ("--seed=-1", r"argument --seed: -1 is out of range \(allowed: integer >= 0\)"),
        ("--seed=1.5", r"argument --seed: '1.5' is not a whole number"),
        ("--realizations=1e9", r"argument --realizations: '1e9' is not a whole number"),
        ("--realizations=-3", r"argument --realizations: -3 is out of range"),
        ("--workers=0", r"argument --workers: 0 is out of range"),
        ("--chunk-size=x", r"argument --chunk-size: 'x' is not a whole number"),
        ("--count=many", r"argument --count: invalid choice: 'many'"),
        ("--bogus", r"unrecognized arguments: --bogus"),
        ("--checkpoint-every=-1", r"checkpoint_every = -1.0 s is out of range \(allowed: >= 0 s\)"),
        ("--checkpoint-every=nan", r"checkpoint_every = nan"),
    ],
)
def test_bad_simulate_options_are_one_line_errors(capsys, tmp_path, option, message):
    err = one_line_error(capsys, [*SIMULATE, "--out", str(tmp_path / "r.h5"), option])
    assert re.search(message, err), err
    assert not (tmp_path / "r.h5").exists()


@pytest.mark.parametrize(
    "argv",
    [[], ["simulate"], ["analytic", "--surface", "smooth"], ["frobnicate"], ["paper", "--seed=-2"]],
)
def test_missing_or_unknown_arguments_are_one_line_errors(capsys, argv):
    err = one_line_error(capsys, argv)
    assert "--help" in err


def test_help_is_still_the_full_usage(capsys):
    assert main(["simulate", "--help"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("usage: mcsim simulate") and "--realizations" in out


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("0:1:100000000", r"asks for 100000000 points \(allowed: 1 <= num <= 10000\)"),
        (
            ",".join(["0"] * 10_001),
            r"10001 separations, more than the limit of 10000",
        ),
        ("--h=-1e17", r"h = -1e\+17 is out of range \(allowed: -1e\+06 <= h <= 1e\+06\)"),
    ],
)
def test_absurd_separation_specs_are_refused_at_once(capsys, spec, message):
    h = spec if spec.startswith("--h=") else f"--h={spec}"
    code = main(["analytic", "--surface", "smooth", h])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and re.search(message, err), err


@pytest.mark.parametrize(
    ("argv", "suggestion"),
    [
        (["adhesion", "--surface", "smooth", "--trun", "1"], "did you mean '--turn'?"),
        (["adhesio", "--surface", "smooth"], "did you mean 'adhesion'?"),
        (["adhesion", "--surface", "smooth", "--format", "jsn"], "did you mean 'json'?"),
        (["adhesion", "--surface", "smooth", "--law", "jk"], "did you mean 'jkr'?"),
        (["adhesion", "--surface", "smoth"], "did you mean 'smooth'?"),
        (["adhesion", "--surface", "smooth", "--material", "silcon"], "did you mean 'silicon'?"),
        (["sweep", "--surface", "smooth", "--vary", "sigm=1nm,2nm", "--out", "x.h5"],
         "did you mean 'sigma'?"),
    ],
)  # fmt: skip
def test_a_misspelled_option_command_choice_or_name_gets_a_did_you_mean(
    capsys, tmp_path, monkeypatch, argv, suggestion
):
    monkeypatch.chdir(tmp_path)
    assert suggestion in one_line_error(capsys, argv)
    assert not list(tmp_path.iterdir())  # nothing written


def test_an_option_far_from_every_known_one_gets_no_suggestion(capsys):
    assert "did you mean" not in one_line_error(
        capsys, ["adhesion", "--surface", "smooth", "--zzz"]
    )


@pytest.mark.parametrize(("command", "default"),
                         [("analytic", "seed"), ("simulate", "seed"), ("sweep", "seed"),
                          ("adhesion", "auto")])  # fmt: skip
def test_every_law_option_lists_the_registered_law_sets_and_says_its_default(
    capsys, command, default
):
    from mcsim.cli.options import LAW_SET_NAMES
    from mcsim.physics.laws import LAW_SETS

    assert set(LAW_SET_NAMES) == set(LAW_SETS)
    assert main([command, "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split()).replace("- ", "-")
    for name in LAW_SETS:
        assert name in text
    assert f"default here: {default} (" in text

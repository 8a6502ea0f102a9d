"""A run outside its law set's regime says so where the user meets it: ``simulate`` prints
the same regime warnings as ``analytic`` (unless ``--quiet``), and ``show`` repeats them."""

from mcsim.cli.main import main

#: jkr on the smooth surface: Maugis lambda = 1.52, below the JKR zone (lambda > 5).
JKR_ON_SMOOTH = ["--surface", "smooth", "--material", "silicon", "--law", "jkr", "--h", "1"]
WARNING = "warning: law jkr used at Maugis lambda = 1.52 < 5, outside the JKR zone"


def test_simulate_warns_as_analytic_does(capsys, tmp_path):
    assert main(["analytic", *JKR_ON_SMOOTH]) == 0
    assert WARNING in capsys.readouterr().err
    out = tmp_path / "run.h5"
    assert (
        main(["simulate", *JKR_ON_SMOOTH, "--area", "10um^2", "--seed", "1", "--out", str(out)])
        == 0
    )
    assert WARNING in capsys.readouterr().err
    assert main(["show", str(out)]) == 0
    assert f"regime        {WARNING}" in capsys.readouterr().out


def test_quiet_silences_the_warning(capsys, tmp_path):
    argv = ["simulate", *JKR_ON_SMOOTH, "--area", "10um^2", "--seed", "1", "--quiet"]
    assert main([*argv, "--out", str(tmp_path / "run.h5")]) == 0
    assert capsys.readouterr().err == ""


def test_the_seed_law_set_in_its_own_regime_warns_of_nothing(capsys, tmp_path):
    argv = ["simulate", "--surface", "smooth", "--h", "1", "--area", "10um^2", "--seed", "1"]
    assert main([*argv, "--out", str(tmp_path / "run.h5")]) == 0
    assert "warning" not in capsys.readouterr().err

"""The seed's μ = T/(P + F) (Eq. 8) is undefined, not zero, without adhesion (issue 33).

The seed's friction is adhesional (Savkoor-Briggs, Eq. 6): with w = 0 it gives T = 0
at every separation, and the model says nothing about friction. A tribologist reading
μ = 0 would take the surfaces for frictionless; μ is NaN instead ("undefined" in the
table, empty in CSV, null in JSON) in the analytic curves, the Monte Carlo estimates,
``compare`` and the per-patch curves, while T itself stays 0.
"""

from __future__ import annotations

import contextlib
import io

import numpy as np

import mcsim
from mcsim.cli import main as cli
from mcsim.model.params import Material

NO_ADHESION = Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, gamma=0.0, H=12.5e9)


def test_analytic_mu_of_the_seed_without_adhesion_is_nan_and_t_is_zero():
    curves = mcsim.gw_curves("smooth", NO_ADHESION, [1.0, 0.0])
    assert np.all(curves.T == 0)
    assert np.all(curves.P > 0)  # the surfaces touch: P + F > 0, yet μ is undefined
    assert np.all(np.isnan(curves.mu))


def test_analytic_mu_of_the_seed_with_adhesion_is_a_number():
    assert np.all(np.isfinite(mcsim.gw_curves("smooth", "silicon", [1.0, 0.0]).mu))


def test_monte_carlo_mu_without_adhesion_is_nan_in_every_estimate():
    # 20 um^2 x 17 um^-2 x 3 patches: >= 160 summits in contact at h = 1, above the 100
    # below which compare gives no z and says "few contacts" instead of "undefined"
    run = mcsim.simulate("smooth", NO_ADHESION, [1.0, 0.0], "20um^2", realizations=3, seed=1,
                         workers=1)  # fmt: skip
    assert np.all(run.summary.mean["T"] == 0)
    for values in (run.summary.mean["mu"], run.summary.se["mu"], run.realizations["mu"],
                   run.analytic["mu"]):  # fmt: skip
        assert np.all(np.isnan(values)), values
    rows = run.compare().query("quantity == 'mu'")
    assert rows["note"].str.startswith("undefined: no contact in the ensemble, or w = 0").all()
    assert rows["z"].isna().all()


def cli_out(*argv) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        assert cli.main([str(a) for a in argv]) == 0
    return out.getvalue()


def test_analytic_command_prints_mu_undefined_without_adhesion(tmp_path):
    toml = tmp_path / "m.toml"
    toml.write_text('[material]\nE = "160 GPa"\nnu = 0.22\ngamma = "0 J/m^2"\n')
    table = cli_out("analytic", "--surface", "smooth", "--material", toml, "--h=1,0")
    rows = [line.split() for line in table.splitlines() if line[:1] in "01"]
    assert [r[-1] for r in rows] == ["undefined", "undefined"], table
    assert "mu = T/(P+F) (Eq. 8), undefined where w = 0" in table
    csv = cli_out("analytic", "--surface", "smooth", "--material", toml, "--h=1,0",
                  "--format", "csv")  # fmt: skip
    assert [line.rsplit(",", 1)[1] for line in csv.splitlines()[1:]] == ["", ""], csv

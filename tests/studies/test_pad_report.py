"""``mcsim.pad_report``: the analysis of ``mcsim pads`` in the Python API, the same numbers
as the command prints, computed below the command line (mcsim.studies.pads)."""

import json

import numpy as np
import pytest
from conftest import run_cli

import mcsim
from mcsim.model.errors import ParameterError
from mcsim.studies.pads import FEW_CONTACTS, analytic_pad_pull_off, pad_statistics

OPTIONS = {"law": "jkr", "realizations": 12, "seed": 3, "workers": 1}


@pytest.fixture(scope="module")
def cycle_run(tmp_path_factory):
    path = tmp_path_factory.mktemp("report") / "c.h5"
    mcsim.simulate("smooth", "silicon", np.linspace(2, -1, 16), "1.5 um^2", cycle=True,
                   out=path, **OPTIONS)  # fmt: skip
    return path


def test_the_report_is_what_mcsim_pads_prints_as_json(cycle_run, capsys):
    code, out, _ = run_cli(capsys, "pads", cycle_run, "--restoring-force=2uN", "--format", "json")
    printed = json.loads(out)
    report = mcsim.pad_report(mcsim.read_run(cycle_run), restoring_force=2e-6)
    quantities = report.quantities()
    assert code == 0 and list(quantities) == [k for k in printed if k in quantities]
    for name, (value, unit) in quantities.items():  # JSON keeps every digit of a float
        assert printed[name] == value and printed["units"][name] == unit, name


def test_the_report_holds_the_statistics_of_each_pads_pull_off_and_the_analytic_mean(cycle_run):
    run = mcsim.read_run(cycle_run)
    report = mcsim.pad_report(run)
    assert np.array_equal(report.pull_off.force, run.pull_off().force)
    assert report.statistics == pad_statistics(run.pull_off().force)
    assert report.analytic_mean == analytic_pad_pull_off(run.spec)
    assert report.p_stick_model is None and report.turns == {}
    assert "p_stick" not in report.quantities() and report.quantities()["mean"][1] == "N"
    # ηA Φ(min h): the expected summits above the closest approach (Eq. 1's count, per pad)
    spec = run.spec
    assert report.contacts == spec.surface.eta * spec.area * float(spec.surface.heights.sf(-1.0))
    assert report.contacts > FEW_CONTACTS


@pytest.mark.filterwarnings("ignore::mcsim.physics.adhesion.RegimeWarning")  # jkr at lambda 1.5
def test_a_restoring_force_adds_the_models_probability_of_sticking(cycle_run):
    from mcsim.physics.adhesion import adhesion_summary
    from mcsim.studies.stiction import p_stick_model

    run = mcsim.read_run(cycle_run)
    report = mcsim.pad_report(run, restoring_force=2e-6, interval="wilson")
    spec = run.spec  # no preload: the mean-field turn is the run's min(h)
    h_off = adhesion_summary(spec.surface, spec.material, "jkr", turn=spec.turn).h_pull_off
    expected = p_stick_model(spec, 2e-6, turn=spec.turn, h_pull_off=h_off)
    assert report.statistics.interval == "wilson" and report.p_stick_model == expected
    assert report.quantities()["restoring_force"] == (2e-6, "N")


def test_a_run_without_a_cycle_is_refused_naming_what_it_needs():
    run = mcsim.simulate("smooth", "silicon", [1.0, 0.0], "1 um^2", **OPTIONS)
    with pytest.raises(ParameterError, match=r"^pull-off needs a cycle run \(--cycle\)"):
        mcsim.pad_report(run)

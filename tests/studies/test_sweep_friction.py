"""``mcsim sweep --pads --friction / --tangential-force`` (issue 42): the pads' static friction
and p_slip at every point, varied rh, preload and tangential force on common pads, the file's
variables, the figure, and the defaults left bit for bit as they were."""

import dataclasses

import numpy as np
import pytest
from conftest import run_cli

from mcsim.model.errors import ParameterError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.store.sweepfile import read_sweep
from mcsim.store.sweepvariables import FRICTION, PAD_STRINGS, PADS, SLIP, SLIP_STRINGS, STICK
from mcsim.studies.sweeps import sweep

SMOOTH = dataclasses.replace(SURFACES["smooth"], sigma=2.5e-9)
SILICON = MATERIALS["silicon"]
OPTIONS = {"law": "jkr", "area": "30um^2", "pads": 12, "seed": 7, "workers": 1}


@pytest.fixture(scope="module")
def friction_sweep(tmp_path_factory):
    """Two preloads × two tangential forces, 12 pads each, no restoring force; written."""
    path = tmp_path_factory.mktemp("friction") / "f.h5"
    result = sweep(SMOOTH, SILICON, {"preload": "1MPa,3MPa", "tangential_force": "100uN,300uN"},
                   out=path, **OPTIONS)  # fmt: skip
    return result, path


def test_the_sweep_stores_friction_and_p_slip_with_their_units_and_no_p_stick(friction_sweep):
    _, path = friction_sweep
    on_disk = read_sweep(path)
    for name, (unit, meaning) in (FRICTION | SLIP).items():
        assert on_disk.units[name] == unit and on_disk.long_names[name] == meaning
        assert on_disk.data[name].shape == (2, 2) and np.all(np.isfinite(on_disk.data[name]))
    assert set(on_disk.data["p_slip_method"].ravel()) == {"pads"}
    assert not set(STICK) & set(on_disk.data) and "p_stick_method" not in on_disk.data
    assert "restoring_force" not in on_disk.attrs and on_disk.attrs["friction"]
    assert on_disk.units["preload"] == "Pa" and on_disk.units["tangential_force"] == "N"


def test_points_that_differ_in_preload_or_tangential_force_share_their_pads(
    friction_sweep, tmp_path
):
    result, _ = friction_sweep
    d = result.data
    t = d["static_friction_mean"]
    assert np.array_equal(t[:, 0], t[:, 1])  # the tangential force changes nothing but p_slip
    assert np.all(d["p_slip"][:, 0] <= d["p_slip"][:, 1])
    assert np.all(t[1] > t[0]) and np.all(d["mu_static_mean"][1] < d["mu_static_mean"][0])
    one = sweep(SMOOTH, SILICON, {"tangential_force": "100uN,300uN"}, preload="3MPa", **OPTIONS)
    for k in (*FRICTION, *SLIP):  # the same pads as the varied preload's, bit for bit
        assert np.array_equal(one.data[k], result.data[k][1]), k


def test_friction_leaves_every_other_variable_bit_for_bit_and_is_absent_by_default():
    vary = {"sigma": "2.5nm"}
    plain = sweep(SMOOTH, SILICON, vary, restoring_force="20uN", preload="1MPa", **OPTIONS)
    both = sweep(SMOOTH, SILICON, vary, restoring_force="20uN", preload="1MPa",
                 tangential_force="0.2mN", **OPTIONS)  # fmt: skip
    assert not set(FRICTION) & set(plain.data) and not set(SLIP) & set(plain.data)
    assert set(PADS) | set(PAD_STRINGS) <= set(plain.data) and "friction" not in plain.attrs
    assert set(both.data) == set(plain.data) | set(FRICTION) | set(SLIP) | set(SLIP_STRINGS)
    for k, v in plain.data.items():
        same = (v == both.data[k]) if v.dtype == object else np.array_equal(v, both.data[k], True)
        assert np.all(same), k


def test_friction_alone_adds_its_statistics_without_p_slip():
    out = sweep(SMOOTH, SILICON, {"sigma": "2.5nm"}, preload="1MPa", friction=True, **OPTIONS)
    assert np.isfinite(out.data["mu_static_mean"][0]) and "p_slip" not in out.data


@pytest.mark.parametrize(
    "options, match",
    [({"tangential_force": "-1uN"}, "tangential_force"),
     ({"tangential_force": float("inf")}, "tangential_force"),
     ({"tangential_force": float("nan")}, "tangential_force"),
     ({"tangential_force": "1uN", "pads": None}, "tangential_force applies to the pads only"),
     ({"friction": True, "pads": None}, "friction applies to the pads only"),
     ({"friction": True, "law": "dmt"}, "'dmt' has no friction without a shear strength tau"),
     ({"friction": "yes"}, "friction = 'yes'"),
     ({"restoring_force": None}, "pads need the restoring force"),
     ({"tangential_force": "1uN", "vary": {"tangential_force": "1uN,2uN"}}, "both as a value"),
     ({"tangential_force": "1uN", "vary": {"preload": "1MPa"}, "turn": 0.5}, "turn and vary preload"),
     ({"tangential_force": "1uN", "vary": {"preload": "-1MPa,1MPa"}}, "vary preload"),
     ({"friction": True, "pads": None, "vary": {"tangential_force": "1uN"}}, "vary tangential_force")],
)  # fmt: skip
def test_bad_friction_options_are_one_line_errors_and_write_nothing(tmp_path, options, match):
    options = {**OPTIONS, "restoring_force": None, "vary": {"sigma": "2.5nm"}} | options
    if options["pads"] is None:
        del options["pads"], options["area"]
    vary = options.pop("vary")
    out = tmp_path / "bad.h5"
    with pytest.raises(ParameterError, match=match) as err:
        sweep(SMOOTH, SILICON, vary, out=out, **options)
    assert "\n" not in str(err.value) and not list(tmp_path.iterdir())


def test_cli_sweep_varies_rh_with_a_tangential_force_and_plots_mu_s(tmp_path, capsys):
    out, png = tmp_path / "rh.h5", tmp_path / "rh.png"
    code, _, err = run_cli(capsys, "sweep", "--surface", "smooth", "--law", "jkr", "--hamaker",
                           "1.6e-19J", "--vary", "rh=0,0.6", "--preload", "1MPa", "--pads", "2",
                           "--area", "10um^2", "--tangential-force", "0.5mN", "--seed", "1",
                           "--out", out, "--quiet")  # fmt: skip
    assert code == 0, err
    result = read_sweep(out)
    t = result.data["static_friction_mean"]
    assert t[1] > t[0] and result.attrs["tangential_force"] == pytest.approx(5e-4, rel=1e-15)
    code, _, err = run_cli(capsys, "plot", out, "--out", png, "--quiet")
    assert code == 0 and png.stat().st_size > 10_000, err


def test_cli_sweep_bad_tangential_force_writes_nothing(tmp_path, capsys):
    out = tmp_path / "bad.h5"
    code, _, err = run_cli(capsys, "sweep", "--surface", "smooth", "--law", "jkr", "--vary",
                           "sigma=2nm", "--pads", "2", "--area", "10um^2",
                           "--tangential-force=-5uN", "--out", out)  # fmt: skip
    assert code != 0 and "tangential_force" in err and len(err.strip().splitlines()) == 1
    assert not out.exists()


def test_plot_kind_stiction_draws_p_stick_of_a_sweep_that_has_both(tmp_path, capsys):
    out = tmp_path / "both.h5"
    sweep(SMOOTH, SILICON, {"sigma": "2.5nm,3nm"}, restoring_force="20uN", preload="1MPa",
          tangential_force="0.2mN", out=out, **OPTIONS)  # fmt: skip
    for kind in ("auto", "stiction"):
        png = tmp_path / f"{kind}.png"
        code, _, err = run_cli(capsys, "plot", out, "--kind", kind, "--out", png, "--quiet")
        assert code == 0 and png.exists(), err

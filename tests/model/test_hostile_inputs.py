"""Hostile inputs to the Python API and the files: each ends in an MCSimError naming the
field, never another exception, a silent conversion or a raw RuntimeWarning."""

import numpy as np
import pytest

import mcsim
from mcsim.cli.main import main
from mcsim.model.errors import MCSimError, ParameterError, UnitError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.environment import Environment
from mcsim.store.config import load_surface

HUGE = 10**400  # an integer no float holds (TOML integers are unbounded too)
SMOOTH = {"sigma": 1.4e-9, "R": 1.7e-6, "eta": 17e12}


@pytest.mark.parametrize("field", ["sigma", "R", "eta"])
def test_an_integer_beyond_every_float_is_out_of_range(field):
    with pytest.raises(ParameterError, match=rf"^{field} = inf m.* is out of range"):
        mcsim.Surface(**(SMOOTH | {field: HUGE}))


@pytest.mark.parametrize("flag", [True, np.True_])
def test_a_boolean_is_not_a_number(flag):
    with pytest.raises(ParameterError, match=r"^R must be a number, got (np\.)?True"):
        mcsim.Surface(**(SMOOTH | {"R": flag}))


def test_material_takes_e_and_nu_for_two_identical_solids_as_the_toml_does():
    one = mcsim.Material(E="160 GPa", nu=0.22, w=0.5)
    assert one == mcsim.Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, gamma=0.5)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"E": 1e11, "E1": 2e11, "nu": 0.2}, r"^E: give either E \(both solids\) or E1 and E2"),
        ({"E1": 2e11, "nu": 0.2}, r"^E2: missing \(give E1 and E2, or E"),
        ({"E": 2e11}, r"^nu1: missing"),
    ],
)
def test_material_moduli_are_given_one_way(kwargs, message):
    with pytest.raises(ParameterError, match=message):
        mcsim.Material(**kwargs, w=0.5)


def test_gw_curves_takes_preset_names_as_the_command_line_does():
    h = np.linspace(-1, 3, 5)
    by_name = mcsim.gw_curves("smooth", "silicon", h)
    by_object = mcsim.gw_curves(SURFACES["smooth"], MATERIALS["silicon"], h)
    np.testing.assert_array_equal(
        by_name.values["P"], by_object.values["P"]
    )  # the same inputs: same bits


def test_an_unknown_preset_name_lists_the_presets():
    with pytest.raises(
        ParameterError, match=r"^surface must be a Surface or a preset name \(rough,"
    ):
        mcsim.gw_curves("smoot", "silicon", [1.0])
    with pytest.raises(ParameterError, match=r"^material must be a Material or a preset name"):
        mcsim.load_control("smooth", 5, [1e5])


@pytest.mark.parametrize("key", ["sigma", "summit_offset", "rq"])
def test_a_toml_integer_beyond_every_float_is_a_one_line_error(tmp_path, key):
    lines = {"sigma": '"1.4nm"', "R": '"1.7um"', "eta": '"17um^-2"'} | {key: str(HUGE)}
    path = tmp_path / "s.toml"
    path.write_text("[surface]\n" + "".join(f"{k} = {v}\n" for k, v in lines.items()))
    with pytest.raises(UnitError, match=rf"{key}: an integer of 401 digits is too large") as err:
        load_surface(path)
    assert "\n" not in str(err.value)


@pytest.mark.filterwarnings("error::RuntimeWarning")
@pytest.mark.parametrize(
    ("edges", "message"),
    [
        (f"[-{HUGE}, 0, {HUGE}]", "histogram edges and weights must be finite"),
        ("[-1e300, 0, 1e300]", "histogram edges span too wide a range"),
    ],
)
def test_histogram_edges_beyond_floats_are_refused_without_warnings(tmp_path, edges, message):
    path = tmp_path / "s.toml"
    path.write_text('[surface]\nsigma = "1.4nm"\nR = "1.7um"\neta = "17um^-2"\n'
                    f'heights = {{edges = {edges}, counts = [1, 2], unit = "nm"}}\n')  # fmt: skip
    with pytest.raises(ParameterError, match=message):
        load_surface(path)


def test_an_absurd_hamaker_constant_is_refused():
    assert Environment(hamaker=1e-16).hamaker == 1e-16  # the bound itself is accepted
    with pytest.raises(
        ParameterError, match=r"hamaker = 1e\+300 J is out of range \(allowed: \[0, 1e-16\] J\)"
    ):
        Environment(hamaker=1e300)


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["analytic", "--surface", "smooth", "--material", "silicon", "--h", "1",
          "--hamaker", "1e300J"], r"hamaker = 1e\+300 J is out of range"),
        (["simulate", "--surface", "smooth", "--area", "1um^2", "--h=0", "--quiet",
          "--workers", str(10**23)], r"--workers: \d+ is out of range \(allowed: integer from 1 to 1024\)"),
    ],
)  # fmt: skip
def test_absurd_command_line_values_are_one_line_errors(capsys, tmp_path, argv, message):
    assert main([*argv, *(["--out", str(tmp_path / "r.h5")] if argv[0] == "simulate" else [])]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mcsim: error: ") and err.count("\n") == 1, err
    assert __import__("re").search(message, err), err


def test_every_error_above_is_an_mcsim_error():
    assert issubclass(ParameterError, MCSimError) and issubclass(UnitError, MCSimError)


@pytest.mark.parametrize("path", [5, None, b"run.h5", ""])
def test_a_file_argument_that_is_not_a_path_is_refused_by_name(path):
    with pytest.raises(
        MCSimError, match=r"^path (must be a file path|= '' is not a valid file path)"
    ):
        mcsim.read_run(path)


def test_an_empty_out_is_refused_instead_of_writing_the_default_path(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    argv = ["simulate", "--surface", "smooth", "--area", "1um^2", "--h=0", "--quiet", "--out", ""]
    assert main(argv) == 2
    assert "--out = '' is not a valid file path" in capsys.readouterr().err
    assert not any(tmp_path.rglob("*"))  # nothing written, no runs/ folder


def test_a_reader_message_quoting_binary_data_stays_one_short_line():
    from mcsim.topography.readers.base import MAX_MESSAGE, ReaderError

    message = str(ReaderError("scan.ibw: not readable (" + "\x00\x07\xff" * 40_000 + ")"))
    assert "\n" not in message and "\x00" not in message
    assert len(message) < MAX_MESSAGE + 40 and message.endswith("characters cut)")


def test_a_run_whose_state_cannot_fit_is_refused_before_anything_is_planned():
    from mcsim.engine.spec import MAX_STATE_BYTES, MonteCarloSpec, state_bytes

    inputs = dict(surface=SURFACES["smooth"], material=MATERIALS["silicon"], h=[2.0, 1.0],
                  area=2e-12, entropy=1)  # fmt: skip
    per = state_bytes(MonteCarloSpec(**inputs, realizations=1), 1)
    most = MAX_STATE_BYTES // per
    assert MonteCarloSpec(**inputs, realizations=most).realizations == most  # the bound fits
    with pytest.raises(
        ParameterError, match=rf"^realizations = {most + 1} need .* at most {most} realizations"
    ):
        MonteCarloSpec(**inputs, realizations=most + 1)


def test_the_command_line_and_the_api_cap_the_workers_alike():
    import argparse

    from mcsim.cli.options import workers_type
    from mcsim.studies.runoptions import MAX_WORKERS, check_workers

    assert workers_type(str(MAX_WORKERS)) == check_workers(MAX_WORKERS) == MAX_WORKERS
    with pytest.raises(argparse.ArgumentTypeError):
        workers_type(str(MAX_WORKERS + 1))
    with pytest.raises(ParameterError):
        check_workers(MAX_WORKERS + 1)

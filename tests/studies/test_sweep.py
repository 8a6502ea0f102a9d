"""``mcsim sweep``: curves, adhesion summaries and regime numbers on a grid of inputs, in one
netCDF-compatible HDF5 file; bit-identical to ``mcsim analytic``/``mcsim adhesion`` at
every point, whatever the workers, and after an interruption and resume."""

import csv
import dataclasses
import io
import json
import warnings

import numpy as np
import pytest
from conftest import run_cli
from tolerances import ROUNDING_FEW

from mcsim.model.errors import MCSimError, ParameterError
from mcsim.model.presets import MATERIALS, PAPER_SURFACES, SURFACES
from mcsim.physics.adhesion import RegimeWarning, adhesion_summary
from mcsim.physics.analytic import gw_curves
from mcsim.store.sweepvariables import SUMMARY
from mcsim.studies.sweeps import sweep

SMOOTH, SILICON = SURFACES["smooth"], MATERIALS["silicon"]
#: The four Table-1 surfaces' σ (m).
TABLE1_SIGMA = [SURFACES[name].sigma for name in PAPER_SURFACES]
H = [3.0, 1.0, 0.0, -0.5]


@pytest.fixture(scope="module")
def sigma_sweep(tmp_path_factory):
    """A 40-point log σ sweep (dmt, the smooth surface's R and η) through the four
    Table-1 σ, written to a file."""
    sigma = np.unique(np.concatenate([np.geomspace(0.3e-9, 20e-9, 36), TABLE1_SIGMA]))
    assert sigma.size == 40
    path = tmp_path_factory.mktemp("sweep") / "sigma.h5"
    result = sweep(SMOOTH, SILICON, {"sigma": sigma}, law="dmt", h=H, out=path, workers=2)
    return result, path


def test_a_40_point_sigma_sweep_reproduces_the_analytic_curves_and_adhesion_summary_at_the_table1_sigma(
    sigma_sweep,
):
    result, _ = sigma_sweep
    for s in TABLE1_SIGMA:
        i = int(np.flatnonzero(result.coords["sigma"] == s)[0])
        surface = dataclasses.replace(SMOOTH, sigma=s)
        curves = gw_curves(surface, SILICON, H, "dmt")
        for q, values in curves.values.items():
            np.testing.assert_array_equal(result.data[q][i], values, err_msg=f"{q} at sigma {s}")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RegimeWarning)
            summary = adhesion_summary(surface, SILICON, "dmt")
        assert result.data["error"][i] == ""
        for k in (*SUMMARY, "tabor", "maugis_lambda", "adhesion_parameter", "plasticity_index"):
            np.testing.assert_equal(result.data[k][i], getattr(summary, k), err_msg=k)
        assert result.data["regime_warning"][i] == "; ".join(summary.warnings)


def test_the_sweep_file_equals_mcsim_analytic_and_mcsim_adhesion_output_at_the_smooth_surface(
    sigma_sweep, capsys
):
    _, path = sigma_sweep
    xr = pytest.importorskip("xarray")
    point = xr.open_dataset(path, engine="h5netcdf").sel(sigma=SMOOTH.sigma)
    code, out, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--law", "dmt",
                           "--h=3,1,0,-0.5", "--format", "csv")  # fmt: skip
    assert code == 0
    rows = list(csv.DictReader(io.StringIO(out)))
    for q in ("contact_fraction", "load", "area"):
        np.testing.assert_array_equal(point[q].values, [float(r[q]) for r in rows], err_msg=q)
    code, out, _ = run_cli(
        capsys, "adhesion", "--surface", "smooth", "--law", "dmt", "--format", "json"
    )
    assert code == 0
    cli = json.loads(out)
    for k in (*SUMMARY, "tabor", "maugis_lambda", "adhesion_parameter", "plasticity_index"):
        assert float(point[k]) == cli[k], k


def test_the_sweep_file_opens_in_xarray_with_sigma_and_h_as_coordinates_and_units(sigma_sweep):
    result, path = sigma_sweep
    xr = pytest.importorskip("xarray")
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        assert dict(ds.sizes) == {"sigma": 40, "h": len(H)}
        np.testing.assert_array_equal(ds["sigma"].values, result.coords["sigma"])
        assert ds["sigma"].attrs["units"] == "m"
        np.testing.assert_array_equal(ds["h"].values, H)
        assert ds["load"].dims == ("sigma", "h")
        assert ds["pull_off"].dims == ("sigma",)
        assert ds["work_of_separation"].attrs["units"] == "J/m^2"
        assert ds["pull_off_pressure"].attrs["units"] == "Pa"
        assert ds["load"].attrs["units"] == "1"
        assert ds["error"].dtype.kind in "OU"  # text, not bytes
        assert ds.attrs["mcsim_version"]
        assert json.loads(ds.attrs["varied"]) == ["sigma"]
        xr.testing.assert_identical(ds.drop_attrs(), result.to_xarray().drop_attrs())


def test_read_sweep_and_show_give_back_the_file(sigma_sweep, capsys):
    from mcsim.store.sweepfile import read_sweep

    result, path = sigma_sweep
    back = read_sweep(path)
    assert back.grid == ("sigma",)
    assert_same_data(back.data, result.data)
    assert back.units == result.units
    code, out, _ = run_cli(capsys, "show", str(path))
    assert code == 0
    assert "Parameter sweep" in out and "40 values" in out and "failed" in out


def test_a_damaged_sweep_file_is_refused_with_one_line(tmp_path, capsys):
    from mcsim.model.errors import RunFileError
    from mcsim.store.sweepfile import read_sweep

    path = tmp_path / "s.h5"
    sweep(SMOOTH, SILICON, {"sigma": "1nm,2nm"}, h=H, out=path)
    raw = bytearray(path.read_bytes())
    at = raw.find(np.array(H).tobytes())  # the coordinate h
    assert at > 0
    raw[at + 7] ^= 0x10
    path.write_bytes(bytes(raw))
    with pytest.raises(RunFileError, match="checksum mismatch"):
        read_sweep(path)
    code, _, err = run_cli(capsys, "show", str(path))
    assert code == 2 and err.count("\n") == 1 and "s.h5: damaged sweep file" in err


def test_table_is_tidy_one_row_per_point_with_units():
    result = sweep(SMOOTH, SILICON, {"sigma": "1nm,2nm", "gamma": "0.1:0.5:3"}, law="seed", h=H)
    df = result.table()
    assert len(df) == 6
    assert list(df.columns[:2]) == ["sigma", "gamma"]
    np.testing.assert_array_equal(df["sigma"], [1e-9] * 3 + [2e-9] * 3)  # C order
    np.testing.assert_allclose(df["gamma"], [0.1, 0.3, 0.5] * 2, rtol=ROUNDING_FEW)  # a linspace
    assert df.attrs["units"]["sigma"] == "m"
    assert df.attrs["units"]["gamma"] == "J/m^2"
    assert "pull_off" not in df  # the seed has no net load
    assert {"tabor", "adhesion_parameter", "error"} <= set(df.columns)


def test_grid_is_the_outer_product_in_the_order_given():
    result = sweep(SMOOTH, SILICON, {"gamma": [0.2, 0.4], "E": "100GPa,150GPa,200GPa"}, h=H)
    assert result.grid == ("gamma", "E")
    assert result.data["P"].shape == (2, 3, len(H))
    material = dataclasses.replace(SILICON, gamma=0.4, E1=150e9, E2=150e9)
    np.testing.assert_array_equal(result.data["F"][1, 1], gw_curves(SMOOTH, material, H).F)


def test_law_is_a_string_coordinate_and_each_law_has_its_own_curves(tmp_path):
    xr = pytest.importorskip("xarray")
    path = tmp_path / "laws.h5"
    sweep(SMOOTH, SILICON, {"law": "seed,dmt"}, h=H, out=path)
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        assert list(ds["law"].values) == ["seed", "dmt"]
        np.testing.assert_array_equal(ds["P"].sel(law="seed"), gw_curves(SMOOTH, SILICON, H).P)
        assert np.all(np.isnan(ds["P"].sel(law="dmt")))
        assert np.isnan(ds["pull_off"].sel(law="seed"))
        assert float(ds["pull_off"].sel(law="dmt")) > 0


def test_cli_sweep_writes_the_file_and_refuses_to_replace_it_without_overwrite(tmp_path, capsys):
    path = tmp_path / "s.h5"
    args = ["sweep", "--surface", "smooth", "--law", "dmt", "--vary", "sigma=1nm,2nm",
            "--h=2,0", "--out", str(path)]  # fmt: skip
    code, _, err = run_cli(capsys, *args)
    assert code == 0 and path.is_file()
    assert f"wrote {path} (2 points" in err
    code, _, err = run_cli(capsys, *args)
    assert code == 2
    assert "file exists" in err and len(err.strip().splitlines()) == 1
    code, _, _ = run_cli(capsys, *args, "--overwrite")
    assert code == 0


def test_a_failed_point_is_recorded_and_reported_with_its_inputs_and_the_others_kept(
    tmp_path, capsys, monkeypatch
):
    import mcsim.studies.sweeppoint

    def failing_at_gamma_01(surface, material, law, turn=None):
        if material.gamma == 0.1:
            raise ParameterError("no root found (injected)")
        return adhesion_summary(surface, material, law, turn=turn)

    monkeypatch.setattr(mcsim.studies.sweeppoint, "adhesion_summary", failing_at_gamma_01)
    path = tmp_path / "fail.h5"
    code, _, err = run_cli(capsys, "sweep", "--surface", "smooth", "--law", "dmt", "--vary",
                           "gamma=0.1,0.5", "--h=2,0", "--out", str(path))  # fmt: skip
    assert code == 1
    assert path.is_file()
    failed = [line for line in err.splitlines() if "failed:" in line]
    assert len(failed) == 1 and "gamma = 0.1" in failed[0] and "injected" in failed[0]
    xr = pytest.importorskip("xarray")
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        assert "injected" in str(ds["error"].values[0])
        assert np.isnan(ds["pull_off"].values[0])  # the step that failed
        assert np.all(np.isfinite(ds["load"].values[0]))  # the curves before it are kept
        assert ds["error"].values[1] == "" and ds["pull_off"].values[1] > 0


def test_a_point_without_adhesion_has_zero_pull_off_not_a_failure(tmp_path, capsys):
    # gamma = 0: the approach load is never tensile, the surfaces rest apart under no load.
    path = tmp_path / "noadh.h5"
    code, _, err = run_cli(capsys, "sweep", "--surface", "smooth", "--law", "dmt", "--vary",
                           "gamma=0,0.5", "--h=2,0", "--out", str(path))  # fmt: skip
    assert code == 0, err
    xr = pytest.importorskip("xarray")
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        assert ds["error"].values[0] == ""
        assert ds["pull_off"].values[0] == 0 and ds["work_of_separation"].values[0] == 0
        assert str(ds["error"].values[1]) == "" and float(ds["pull_off"].values[1]) > 0


@pytest.mark.parametrize(
    ("vary", "extra", "message"),
    [
        (["foo=1:2:3"], [], "unknown input 'foo'"),
        (["sigma=1GPa:2GPa:3"], [], "vary sigma: unknown unit 'GPa' for a length"),
        (["sigma=1nm:2nm:0"], [], "empty range"),
        (["sigma=2nm:1nm:3:log"], [], "empty range"),
        (["sigma=1nm", "sigma=2nm"], [], "given twice"),
        (["E=100GPa,200GPa", "E1=150GPa"], [], "both set E1"),
        (["area=1um^2,2um^2"], [], "add --mc"),
        (["sigma=1nm:2nm:1000", "gamma=0.1:1:1001"], [], "more than the limit of 1000000"),
        (["sigma=-1nm,1nm"], [], "vary sigma: sigma = -1e-09 m is out of range"),
        (["law=jkr,nope"], [], "unknown law set 'nope'"),
        (["law=jkr,dmt"], ["--law", "seed"], "given both as --law"),
        (["sigma"], [], "give NAME=SPEC"),
        (["sigma=1nm,2nm"], ["--mc"], "needs the patch area"),
        (["sigma=1nm,2nm"], ["--realizations", "3"], "add --mc"),
    ],
)
def test_bad_sweep_input_is_a_one_line_error_naming_the_field(
    tmp_path, capsys, vary, extra, message
):
    argv = ["sweep", "--surface", "smooth", *extra, "--out", str(tmp_path / "x.h5")]
    for v in vary:
        argv += ["--vary", v]
    code, _, err = run_cli(capsys, *argv)
    assert code == 2
    assert err.startswith("mcsim: error:") and len(err.strip().splitlines()) == 1
    assert message in err
    assert not (tmp_path / "x.h5").exists()


def test_api_refuses_an_empty_vary_and_area_without_mc():
    with pytest.raises(ParameterError, match="at least one input"):
        sweep(SMOOTH, SILICON, {})
    with pytest.raises(MCSimError, match="Monte Carlo runs only"):
        sweep(SMOOTH, SILICON, {"sigma": [1e-9]}, area="1um^2")


# --- execution: threads, Dask, interruption and resume ------------------------------------

#: A small grid with every kind of output: curves, adhesion summary, regime numbers.
SMALL = {"sigma": "1nm,2nm", "gamma": "0.3,0.5,0.7"}


def assert_same_data(a, b):
    """Every data variable of two sweeps (results or open files) is equal, bit for bit."""
    assert set(a) == set(b)
    for k in a:
        x, y = np.asarray(a[k]), np.asarray(b[k])
        if x.dtype.kind in "fc":
            np.testing.assert_array_equal(x, y, err_msg=k)
        else:
            assert x.astype(str).tolist() == y.astype(str).tolist(), k


def read_data(path):
    xr = pytest.importorskip("xarray")
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        return {k: v.values for k, v in ds.data_vars.items()}


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    path = tmp_path_factory.mktemp("serial") / "serial.h5"
    return sweep(SMOOTH, SILICON, SMALL, law="dmt", h=H, workers=1, out=path), path


def test_two_worker_threads_give_the_serial_sweep_bit_for_bit(serial):
    threads = sweep(SMOOTH, SILICON, SMALL, law="dmt", h=H, workers=2)
    assert_same_data(threads.data, serial[0].data)


def test_a_two_worker_local_dask_cluster_gives_the_serial_sweep_bit_for_bit(
    serial, dask_local_client
):
    # A Client passed through the API, as one made by dask-jobqueue would be.
    distributed = sweep(SMOOTH, SILICON, SMALL, law="dmt", h=H, scheduler=dask_local_client)
    assert_same_data(distributed.data, serial[0].data)


def test_an_interrupted_sweep_resumes_without_recomputing_and_equals_the_uninterrupted_one(
    serial, tmp_path, monkeypatch
):
    import mcsim.studies.sweeppoint as sweeps

    path, evaluate, calls = tmp_path / "resumed.h5", sweeps.evaluate, []

    def stop_at_point_3(point, config):
        calls.append(point.index)
        if point.index == 3:
            raise KeyboardInterrupt
        return evaluate(point, config)

    monkeypatch.setattr(sweeps, "evaluate", stop_at_point_3)
    with pytest.raises(KeyboardInterrupt):
        sweep(SMOOTH, SILICON, SMALL, law="dmt", h=H, workers=1, out=path)
    partial = tmp_path / "resumed.partial.h5"
    assert not path.exists() and partial.is_file()
    assert read_data(partial)["done"].ravel().tolist() == [1, 1, 1, 0, 0, 0]
    with pytest.raises(MCSimError, match="checkpoint"):  # not replaced by a fresh start
        sweep(SMOOTH, SILICON, SMALL, law="dmt", h=H, workers=1, out=path)
    monkeypatch.setattr(sweeps, "evaluate", lambda point, config: calls.append(point.index) or evaluate(point, config))  # fmt: skip
    calls.clear()
    sweep(SMOOTH, SILICON, SMALL, law="dmt", h=H, workers=2, out=path, resume=True)
    assert sorted(calls) == [3, 4, 5]  # the completed points are never recomputed
    assert not partial.exists()
    assert_same_data(read_data(path), read_data(serial[1]))


def test_completed_points_are_checkpointed_as_they_finish(tmp_path, monkeypatch):
    import mcsim.studies.sweeps as sweeps

    write, saved = sweeps.write_sweep, []

    def spy(path, result, attrs, *, complete, done=None):
        if not complete:
            saved.append(int(done.sum()))
        return write(path, result, attrs, complete=complete, done=done)

    monkeypatch.setattr(sweeps, "write_sweep", spy)
    sweep(SMOOTH, SILICON, {"sigma": "1nm,2nm,3nm"}, h=H, out=tmp_path / "s.h5", checkpoint_every=0)
    assert saved == [1, 2, 3]  # checkpoint_every=0: after every point
    assert not (tmp_path / "s.partial.h5").exists()  # removed once the sweep is in place


def test_resume_refuses_a_checkpoint_of_other_inputs(tmp_path, monkeypatch):
    import mcsim.studies.sweeppoint as sweeps

    evaluate = sweeps.evaluate

    def stop_at_point_1(point, config):
        if point.index == 1:
            raise KeyboardInterrupt
        return evaluate(point, config)

    monkeypatch.setattr(sweeps, "evaluate", stop_at_point_1)
    path = tmp_path / "s.h5"
    with pytest.raises(KeyboardInterrupt):
        sweep(SMOOTH, SILICON, {"sigma": "1nm,2nm,3nm"}, h=H, workers=1, out=path)
    monkeypatch.setattr(sweeps, "evaluate", evaluate)
    with pytest.raises(ParameterError, match="cannot resume"):
        sweep(SMOOTH, SILICON, {"sigma": "1nm,2nm,4nm"}, h=H, out=path, resume=True)


def test_ctrl_c_during_a_cli_sweep_saves_the_completed_points_and_resume_finishes_it(
    serial, tmp_path, capsys, monkeypatch
):
    import signal

    import mcsim.studies.sweeppoint as sweeps

    evaluate = sweeps.evaluate

    def ctrl_c_at_point_2(point, config):
        if point.index == 2:
            signal.raise_signal(
                signal.SIGINT
            )  # recorded by mcsim.engine.interrupt, raised between points
        return evaluate(point, config)

    monkeypatch.setattr(sweeps, "evaluate", ctrl_c_at_point_2)
    path = tmp_path / "cli.h5"
    argv = ["sweep", "--surface", "smooth", "--law", "dmt", "--vary", "sigma=1nm,2nm",
            "--vary", "gamma=0.3,0.5,0.7", "--h=3,1,0,-0.5", "--workers", "1", "--out", str(path)]  # fmt: skip
    code, _, err = run_cli(capsys, *argv)
    assert code == 130
    assert "--resume" in err and len(err.strip().splitlines()) == 1
    monkeypatch.setattr(sweeps, "evaluate", evaluate)
    code, _, _ = run_cli(capsys, *argv, "--resume")
    assert code == 0
    assert_same_data(read_data(path), read_data(serial[1]))


# --- Monte Carlo per point -----------------------------------------------------------------


def test_cli_monte_carlo_sweep_stores_means_and_standard_errors_over_h(tmp_path, capsys):
    path = tmp_path / "mc.h5"
    code, _, _ = run_cli(capsys, "sweep", "--surface", "smooth", "--vary", "sigma=1nm,2nm", "--h=1,0",
                         "--mc", "--area", "1um^2", "--realizations", "2", "--seed", "3", "--out", str(path))  # fmt: skip
    assert code == 0
    data = read_data(path)
    assert data["mc_P"].shape == data["mc_P_se"].shape == (2, 2)
    assert np.all(data["mc_contact_fraction"][:, 1] > 0)
    xr = pytest.importorskip("xarray")
    with xr.open_dataset(path, engine="h5netcdf") as ds:
        assert ds.attrs["realizations"] == 2 and ds.attrs["area"] == 1e-12


def test_monte_carlo_per_point_uses_the_points_own_seed_whatever_the_workers():
    from mcsim.studies.simulation import simulate
    from mcsim.studies.sweeppoint import point_seed

    vary = {"sigma": "1nm,2nm", "area": "1um^2,2um^2"}
    kwargs = dict(law="seed", h=[2.0, 0.5], mc=True, realizations=2, seed=7)
    one = sweep(SMOOTH, SILICON, vary, workers=1, **kwargs)
    two = sweep(SMOOTH, SILICON, vary, workers=2, **kwargs)
    assert_same_data(one.data, two.data)
    assert one.grid == ("sigma", "pad_area")
    surface = dataclasses.replace(SMOOTH, sigma=2e-9)
    run = simulate(surface, SILICON, [2.0, 0.5], 1e-12, realizations=2, seed=point_seed(7, 2))
    for q in ("contact_fraction", "P", "F", "T", "mu"):
        np.testing.assert_array_equal(one.data[f"mc_{q}"][1, 0], run.summary.mean[q], err_msg=q)
        np.testing.assert_array_equal(one.data[f"mc_{q}_se"][1, 0], run.summary.se[q], err_msg=q)
    assert one.units["pad_area"] == "m^2"
    other_seed = sweep(SMOOTH, SILICON, vary, workers=1, **{**kwargs, "seed": 8})
    assert not np.array_equal(other_seed.data["mc_P"], one.data["mc_P"])


def test_varying_w_is_varying_the_work_of_adhesion_gamma():
    by_w = sweep(SMOOTH, SILICON, {"w": "0.2,0.5"}, law="dmt", h=H)
    by_gamma = sweep(SMOOTH, SILICON, {"gamma": "0.2,0.5"}, law="dmt", h=H)
    for k in ("pull_off", "work_of_separation", "load"):
        np.testing.assert_array_equal(by_w.data[k], by_gamma.data[k])

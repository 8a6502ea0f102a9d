"""HDF5 run files: content, provenance, round trip, atomic and non-destructive writes."""

import shutil
from pathlib import Path

import h5py
import numpy as np
import pytest
from tolerances import ROUNDING_FEW, assert_same_run

from mcsim import RunFileError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.analytic import QUANTITIES
from mcsim.store.runfile import SCHEMA_VERSION, read_run
from mcsim.studies.simulation import simulate

H = [2.0, 1.0, 0.0]


def make_run(path, **kw):
    args = dict(realizations=3, seed=4, out=path)
    return simulate(SURFACES["smooth"], MATERIALS["silicon"], H, "300 um^2", **{**args, **kw})


def test_run_file_records_provenance_and_inputs_with_units(tmp_path):
    make_run(tmp_path / "a.h5")
    with h5py.File(tmp_path / "a.h5") as f:
        assert f.attrs["schema_version"] == SCHEMA_VERSION
        for key in (
            "mcsim_version",
            "created",
            "command",
            "seed_entropy",
            "law",
            "count",
            "area",
            "realizations",
        ):
            assert key in f.attrs, key
        assert f.attrs["seed_entropy"] == "4"
        assert f.attrs["area"] == pytest.approx(300e-12, rel=ROUNDING_FEW)
        assert f["input/surface"].attrs["sigma"] == pytest.approx(1.4e-9, rel=ROUNDING_FEW)
        assert "m^-2" in f["input/surface"].attrs["units"]
        assert f["d"].attrs["units"] == "m"
        assert f["realizations/sums/P"].shape == (3, 3)
        for q in QUANTITIES:
            assert f[f"realizations/{q}"].shape == (3, 3)
            assert f[f"analytic/{q}"].shape == (3,)
            assert f[f"summary/se/{q}"].attrs["units"] == "1"


def test_reader_returns_what_was_written(tmp_path):
    run = make_run(tmp_path / "a.h5")
    back = read_run(tmp_path / "a.h5")
    assert back.spec.surface == run.spec.surface
    assert back.spec.material == run.spec.material
    np.testing.assert_array_equal(back.h, run.h)
    np.testing.assert_array_equal(back.sums, run.sums)
    for q in QUANTITIES:
        np.testing.assert_array_equal(back.summary.mean[q], run.summary.mean[q])
        np.testing.assert_array_equal(back.analytic[q], run.analytic[q])
    assert back.compare().equals(run.compare())


def test_same_seed_writes_identical_datasets(tmp_path):
    make_run(tmp_path / "a.h5")
    make_run(tmp_path / "b.h5", workers=2, chunk_size=1000)
    with h5py.File(tmp_path / "a.h5") as a, h5py.File(tmp_path / "b.h5") as b:
        names = []
        a.visititems(
            lambda name, obj: names.append(name) if isinstance(obj, h5py.Dataset) else None
        )
        assert len(names) > 20
        for name in names:
            np.testing.assert_array_equal(a[name][()], b[name][()], err_msg=name)


def test_dataframe_has_one_row_per_source_realization_h_and_quantity(tmp_path):
    df = read_run(make_run(tmp_path / "a.h5").path).to_dataframe()
    assert list(df.columns) == ["source", "realization", "h", "d", "quantity", "value", "unit"]
    # 3 realizations + mean, se, std, se_between, analytic; 3 separations; 5 quantities
    assert len(df) == (3 + 5) * 3 * 5
    assert not df.duplicated(["source", "realization", "h", "quantity"]).any()
    one = df.query("source == 'realization' and realization == 1 and quantity == 'P' and h == 0.0")
    assert one["unit"].item() == "P/(A K)"


def test_existing_run_is_never_overwritten_without_asking(tmp_path):
    path = tmp_path / "a.h5"
    make_run(path)
    before = path.read_bytes()
    with pytest.raises(RunFileError, match="file exists"):
        make_run(path, seed=5)
    assert path.read_bytes() == before
    make_run(path, seed=5, overwrite=True)
    assert read_run(path).spec.entropy == 5


def test_interrupted_run_leaves_no_partial_file_and_the_old_run_intact(tmp_path, monkeypatch):
    path = tmp_path / "a.h5"
    make_run(path)
    before = path.read_bytes()

    def interrupt(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr("mcsim.store.runfile.dataset", interrupt)  # dies while writing
    with pytest.raises(KeyboardInterrupt):
        make_run(path, seed=6, overwrite=True)
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.h5"], "no temporary file left"


def test_reader_refuses_an_unknown_schema_version(tmp_path):
    path = make_run(tmp_path / "a.h5").path
    with h5py.File(path, "r+") as f:
        f.attrs["schema_version"] = 99
    with pytest.raises(RunFileError, match="schema version 99 is not supported"):
        read_run(path)


def test_reader_refuses_files_that_are_not_runs(tmp_path):
    (tmp_path / "x.h5").write_bytes(b"not hdf5 at all")
    with pytest.raises(RunFileError, match="not an HDF5 file"):
        read_run(tmp_path / "x.h5")
    with h5py.File(tmp_path / "y.h5", "w") as f:
        f["a"] = 1
    with pytest.raises(RunFileError, match="not an mcsim run file"):
        read_run(tmp_path / "y.h5")
    with pytest.raises(RunFileError, match="no such file"):
        read_run(tmp_path / "missing.h5")


def test_output_folder_must_exist_and_be_writable(tmp_path):
    with pytest.raises(RunFileError, match="does not exist"):
        make_run(tmp_path / "nope" / "a.h5")


def test_output_folder_must_be_writable(tmp_path, monkeypatch):
    monkeypatch.setattr(
        "os.access", lambda path, mode: False
    )  # as if not writable (root ignores modes)
    with pytest.raises(RunFileError, match="is not writable"):
        make_run(tmp_path / "a.h5")


def test_kept_heights_are_one_compressed_ragged_array_split_by_count(tmp_path):
    run = make_run(tmp_path / "a.h5", keep_heights=True)
    back = read_run(run.path)
    assert len(back.heights) == 3
    for a, b in zip(run.heights, back.heights):
        np.testing.assert_array_equal(a, b)
    with h5py.File(run.path) as f:
        assert f["heights/z"].compression == "gzip" and f["heights/z"].shuffle
        assert list(f["heights/count"][()]) == [z.size for z in run.heights]
        assert f["heights/count"].attrs["sample_dimension"] == "summit"  # CF ragged array


def test_an_edited_result_is_detected_on_open(tmp_path):
    path = make_run(tmp_path / "a.h5").path
    with h5py.File(path, "r+") as f:
        f["summary/mean/P"][1] *= 1.0001
    with pytest.raises(RunFileError, match="checksum mismatch"):
        read_run(path)


def test_an_edited_input_is_detected_on_open(tmp_path):
    path = make_run(tmp_path / "a.h5").path
    with h5py.File(path, "r+") as f:
        f["input/surface"].attrs["sigma"] = 2e-9
    with pytest.raises(RunFileError, match="checksum mismatch"):
        read_run(path)


def test_datasets_that_disagree_with_the_inputs_are_refused_even_with_a_valid_checksum(tmp_path):
    from mcsim.store.files import checksum

    path = make_run(tmp_path / "a.h5").path
    with h5py.File(path, "r+") as f:
        f.attrs["realizations"] = 5
        f.attrs["checksum"] = checksum(f)
    with pytest.raises(
        RunFileError, match=r"realizations/N has shape \(3,\), the inputs ask for \(5,\)"
    ):
        read_run(path)


@pytest.mark.parametrize("keep", [0.1, 0.5, 0.9, 0.999])
def test_a_truncated_file_is_refused_with_a_clear_message(tmp_path, keep):
    path = make_run(tmp_path / "a.h5").path
    data = path.read_bytes()
    path.write_bytes(data[: int(len(data) * keep)])
    with pytest.raises(RunFileError, match=r"(not an HDF5 file, or truncated|damaged run file)"):
        read_run(path)


def test_an_incomplete_run_is_refused_unless_the_completed_part_is_asked_for(tmp_path):
    from mcsim.engine.montecarlo import EnsembleSums, run_sums
    from mcsim.engine.spec import MonteCarloSpec
    from mcsim.store.runfile import write_checkpoint

    spec = MonteCarloSpec(SURFACES["smooth"], MATERIALS["silicon"], np.array(H), 3e-10, 4, 9)
    full = run_sums(spec)
    partial = EnsembleSums.start(spec)
    partial.sums[:2], partial.done_blocks[:2] = full.sums[:2], full.n_blocks[:2]
    write_checkpoint(tmp_path / "p.h5", partial, command="test")
    with pytest.raises(RunFileError, match=r"incomplete run \(2 of 4 realizations done\)"):
        read_run(tmp_path / "p.h5")
    run = read_run(tmp_path / "p.h5", allow_incomplete=True)
    assert not run.complete and run.spec.realizations == 2
    np.testing.assert_array_equal(run.sums, full.sums[:2])


def test_run_files_written_before_the_named_axes_still_open():
    """tests/data/run_schema1_before_axes.h5 was written by mcsim 0.1.0 (commit 58787dd),
    before the dimension scales: 2 realizations, h = [1, 0], smooth on silicon, seed 7. Its
    numbers equal a fresh run's within the cross-machine tolerances (test_seed_golden)."""
    old = read_run(Path(__file__).parents[1] / "data" / "run_schema1_before_axes.h5")
    assert old.spec.surface == SURFACES["smooth"] and old.spec.realizations == 2
    np.testing.assert_array_equal(old.h, [1.0, 0.0])
    again = simulate(SURFACES["smooth"], MATERIALS["silicon"], [1.0, 0.0], "100 um^2",
                     realizations=2, seed=7)  # fmt: skip
    assert_same_run(again, old)


# --- schema 2: any law set, cycles; schema 3: CF attributes, a branch axis; 1 and 2 read --

SCHEMA1 = Path(__file__).parents[1] / "data" / "run_schema1.h5"


def test_a_schema_1_run_file_still_opens_with_the_same_results():
    """tests/data/run_schema1.h5 was written by mcsim before schema 2 (commit 58787dd):
    ``simulate(SURFACES["smooth"], MATERIALS["silicon"], [2.0, 1.0, 0.0, -0.5], 1e-10,
    realizations=2, seed=5, out=...)``. It opens, and its stored numbers equal a fresh run
    of the same inputs within the cross-machine tolerances (test_seed_golden)."""
    old = read_run(SCHEMA1)
    assert old.attrs["schema_version"] == 1
    assert old.spec.law == "seed" and not old.spec.cycle
    fresh = simulate(SURFACES["smooth"], MATERIALS["silicon"], [2.0, 1.0, 0.0, -0.5], 1e-10,
                     realizations=2, seed=5)  # fmt: skip
    assert_same_run(fresh, old)
    labels = ["h", "branch", "quantity", "note"]  # the numbers are checked above
    assert old.compare()[labels].equals(fresh.compare()[labels])


@pytest.fixture
def toy(monkeypatch, law_set_cache):
    import dataclasses

    from lawset_toy import TOY

    from mcsim.physics.laws import LAW_SETS

    monkeypatch.setenv("MCSIM_CACHE_DIR", law_set_cache)
    monkeypatch.setitem(LAW_SETS, TOY.name, TOY)
    return dataclasses.replace(MATERIALS["silicon"], tau=1e8, z0=0.3e-9)


def test_the_run_file_records_the_law_set_outputs_columns_branches_and_turn(tmp_path, toy):
    import json

    from mcsim.engine.kernels import sum_columns, sum_units
    from mcsim.physics.laws import get_law_set

    simulate(SURFACES["smooth"], toy, H, "300 um^2", realizations=2, seed=4, law="toy", cycle=True,
             out=tmp_path / "a.h5")  # fmt: skip
    with h5py.File(tmp_path / "a.h5") as f:
        assert f.attrs["schema_version"] == SCHEMA_VERSION == 3
        assert f.attrs["law"] == "toy" and bool(f.attrs["cycle"])
        assert json.loads(f.attrs["law_outputs"]) == {"load": "N", "area": "m^2", "grip": "N"}
        assert json.loads(f.attrs["branches"]) == ["approach", "retract"]
        assert f.attrs["turn"] == 0.0
        assert list(json.loads(f.attrs["quantities"])) == [
            "contact_fraction", "load", "area", "grip", "friction", "mu"]  # fmt: skip
        assert [b.decode() for b in f["branch"][()]] == ["approach", "retract"]
        columns = sum_columns(get_law_set("toy"))
        assert columns[:4] == ("n_contact", "load", "area", "grip") and len(columns) == 10
        for column, units in zip(columns, sum_units(get_law_set("toy")), strict=True):
            assert f[f"realizations/sums/{column}"].shape == (2, 2, 3)  # realization, branch, h
            assert f[f"realizations/sums/{column}"].attrs["units"] == units
        assert f["summary/mean/area"].shape == (2, 3)
        assert f["summary/mean/area"].attrs["description"] == "area/A"
        assert f["input/material"].attrs["tau"] == 1e8
        assert f["input/material"].attrs["z0"] == 0.3e-9


def test_a_cycle_run_of_another_law_set_reads_back_as_written(tmp_path, toy):
    run = simulate(SURFACES["smooth"], toy, H, "300 um^2", realizations=2, seed=4, law="toy",
                   cycle=True, out=tmp_path / "a.h5")  # fmt: skip
    back = read_run(tmp_path / "a.h5")
    assert back.spec == run.spec and back.spec.cycle and back.spec.material.tau == 1e8
    np.testing.assert_array_equal(back.sums, run.sums)
    for q in run.quantities:
        np.testing.assert_array_equal(back.summary.mean[q], run.summary.mean[q])
        np.testing.assert_array_equal(back.realizations[q], run.realizations[q])
    np.testing.assert_array_equal(back.pull_off().force, run.pull_off().force)
    table = back.compare()
    assert list(table.columns[:3]) == ["h", "branch", "quantity"]
    assert list(table.branch.unique()) == ["approach", "retract"]
    df = back.to_dataframe()
    assert "branch" in df.columns and set(df.quantity) == set(run.quantities)


def test_the_seed_dataframe_columns_are_unchanged(tmp_path):
    df = make_run(tmp_path / "a.h5").to_dataframe()
    assert list(df.columns) == ["source", "realization", "h", "d", "quantity", "value", "unit"]


SCHEMA2 = Path(__file__).parents[1] / "data" / "run_schema2_cycle.h5"


def test_a_run_sampled_with_the_cell_model_of_the_environment_is_refused_with_its_reason():
    """tests/data/run_schema2_cycle.h5 (mcsim at 952d384: jkr, cycle, an environment, kept
    heights) sampled its environment over cells, mcsim 0.2's model, which counted the area
    near contact twice: its sums mean another model, so it is refused, saying why."""
    with pytest.raises(RunFileError, match=r"sampled over cells .* run it again"):
        read_run(SCHEMA2)


def without_environment(path: Path, tmp_path: Path) -> Path:
    """A copy of the run file ``path`` without its /environment group, signed again."""
    from mcsim.store.files import checksum

    out = tmp_path / "dry.h5"
    shutil.copy(path, out)
    with h5py.File(out, "r+") as f:
        del f["environment"]
        f.attrs["checksum"] = checksum(f)
    return out


def test_a_schema_2_cycle_file_still_opens_with_the_same_results(tmp_path):
    """The same schema-2 file without its environment group (above): read, it gives exactly
    the rows it stores (a cycle's approach rows, then its retraction rows, on one axis);
    written again as schema 3, it reads back the same."""
    from mcsim.store.runfile import write_run

    old = read_run(without_environment(SCHEMA2, tmp_path))
    assert old.attrs["schema_version"] == 2
    assert old.spec.cycle and old.spec.law == "jkr" and old.environment is None
    with h5py.File(SCHEMA2) as f:
        np.testing.assert_array_equal(old.sums, f["realizations/sums"][()])
        for q in old.quantities:
            np.testing.assert_array_equal(old.realizations[q], f[f"realizations/{q}"][()])
            np.testing.assert_array_equal(old.analytic[q], f[f"analytic/{q}"][()])
            for stat in ("mean", "se", "std", "se_between"):
                np.testing.assert_array_equal(getattr(old.summary, stat)[q],
                                              f[f"summary/{stat}/{q}"][()])  # fmt: skip
        for r, z in enumerate(old.heights):
            np.testing.assert_array_equal(z, f[f"heights/{r}"][()])
    new = read_run(write_run(tmp_path / "v3.h5", old, command="test").path)
    assert new.attrs["schema_version"] == 3 and new.spec == old.spec
    np.testing.assert_array_equal(new.sums, old.sums)
    for q in old.quantities:
        np.testing.assert_array_equal(new.realizations[q], old.realizations[q])
        np.testing.assert_array_equal(new.analytic[q], old.analytic[q])
        for stat in ("mean", "se", "std", "se_between"):
            np.testing.assert_array_equal(getattr(new.summary, stat)[q],
                                          getattr(old.summary, stat)[q])  # fmt: skip
    for a, b in zip(new.heights, old.heights, strict=True):
        np.testing.assert_array_equal(a, b)
    assert new.compare().equals(old.compare())


def test_a_run_whose_compressed_curves_are_all_zero_still_reads(tmp_path):
    """No summit reaches these separations: gzip shrinks the zero curves and sums ~1000-fold,
    far past the 64-fold expansion allowed to contiguous data, and the file still reads."""
    h = np.linspace(30.0, 20.0, 200)
    run = simulate(SURFACES["smooth"], MATERIALS["silicon"], h, "1 um^2", realizations=2000,
                   seed=1, workers=1, out=tmp_path / "far.h5")  # fmt: skip
    assert not run.sums[..., 0].any()
    sizes = []
    with h5py.File(run.path) as f:
        assert f["realizations/sums/n_contact"].compression == "gzip"
        f.visititems(
            lambda _, obj: sizes.append(obj.nbytes) if isinstance(obj, h5py.Dataset) else None
        )
    assert sum(sizes) > 64 * run.path.stat().st_size
    np.testing.assert_array_equal(read_run(run.path).sums, run.sums)


def test_a_compressed_dataset_declaring_more_than_deflate_can_expand_is_refused(tmp_path):
    path = make_run(tmp_path / "a.h5").path
    with h5py.File(path, "r+") as f:
        del f["analytic/P"]
        f.create_dataset("analytic/P", shape=(10**8,), dtype="f8", chunks=(10**4,),
                         compression="gzip")  # fmt: skip  # no chunk written
    with pytest.raises(RunFileError, match=r"dataset analytic/P declares 800000000 bytes, more "
                                           r"than its 0 compressed bytes can hold"):  # fmt: skip
        read_run(path)

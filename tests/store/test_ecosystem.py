"""Results in the scientific Python ecosystem: every HDF5 file mcsim writes in xarray (named,
aligned axes with CF units and long names), short summaries in Jupyter, pandas tables."""

import dataclasses
import re
import warnings
from pathlib import Path

import h5py
import numpy as np
import pandas as pd
import pytest
import xarray as xr

import mcsim.store.runfile
import mcsim.store.sweepfile
from mcsim import gw_curves
from mcsim.engine.kernels import SUM_COLUMNS
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.analytic import QUANTITIES
from mcsim.physics.environment import Environment
from mcsim.store.files import COMPRESS_ABOVE
from mcsim.store.results import SUM_UNITS
from mcsim.store.runfile import read_run
from mcsim.studies.simulation import simulate
from mcsim.studies.sweeps import sweep

H = [2.0, 1.0, 0.0]
R = 3
AXES = {"h", "realization"}
GROUPS = ("realizations", "realizations/sums", "progress", "analytic", "summary",
          "summary/mean", "summary/se")  # fmt: skip
SMOOTH, SILICON = SURFACES["smooth"], MATERIALS["silicon"]
HUMID = Environment(hamaker=1.6e-19, cutoff=0.2e-9, rh=0.6, contact_angle=0.3)
GUIDE = Path(__file__).parents[2] / "docs" / "guide"

#: The units mcsim writes, in UDUNITS-2 syntax (``1``; symbols with integer powers, joined
#: by a space or ``/``): each of "1", "m", "m^2", "m^-2", "m^4", "N", "N^2", "N m^2", "Pa",
#: "Pa^2", "J/m^2" was checked to parse with cf_units (the CF conventions' UDUNITS-2).
UNITS = re.compile(r"1|[A-Za-z]+(\^-?[0-9]+)?([ /][A-Za-z]+(\^-?[0-9]+)?)*")


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    path = tmp_path_factory.mktemp("eco") / "a.h5"
    return simulate(SMOOTH, SILICON, H, "300 um^2", realizations=R, seed=4, out=path)


@pytest.fixture(scope="module")
def written(tmp_path_factory) -> dict[str, Path]:
    """One file of each kind mcsim writes: runs (approach, cycle, with an environment and
    kept heights, load-controlled) and sweeps (plain, with Monte Carlo, with pads)."""
    from mcsim.cli.main import main

    folder = tmp_path_factory.mktemp("kinds")
    paths = {k: folder / f"{k}.h5" for k in ("approach", "cycle", "environment", "load control",
                                               "sweep", "sweep mc", "sweep pads")}  # fmt: skip
    jkr = {"law": "jkr", "realizations": R, "seed": 4, "workers": 1}
    simulate(SMOOTH, SILICON, H, "300 um^2", out=paths["approach"], **(jkr | {"law": "seed"}))
    simulate(SMOOTH, SILICON, H, "300 um^2", cycle=True, out=paths["cycle"], **jkr)
    simulate(SMOOTH, SILICON, H, "300 um^2", cycle=True, environment=HUMID, keep_heights=True,
             out=paths["environment"], **jkr)  # fmt: skip
    assert main(["simulate", "--surface", "smooth", "--law", "jkr", "--pressure", "1MPa,3MPa",
                 "--area", "300um^2", "--realizations", "2", "--seed", "4", "--workers", "1",
                 "--out", str(paths["load control"]), "--quiet"]) == 0  # fmt: skip
    grid = {"sigma": "2.5nm,3nm"}
    sweep(SMOOTH, SILICON, grid, law="jkr", h=H, workers=1, out=paths["sweep"])
    sweep(SMOOTH, SILICON, grid, law="jkr", h=H, mc=True, area="10um^2", realizations=2, seed=7,
          workers=1, out=paths["sweep mc"])  # fmt: skip
    sweep(SMOOTH, SILICON, grid, law="jkr", pads=8, seed=7, area="30um^2", restoring_force="20uN",
          preload="1MPa", workers=1, out=paths["sweep pads"])  # fmt: skip
    return paths


def open_group(path, group):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # phony dimensions come with a warning
        return xr.open_dataset(path, group=group, engine="h5netcdf").load()


def groups_with_data(path) -> list[str]:
    """The root and every group of the file that holds datasets."""
    found = ["/"]
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: found.append(name) if isinstance(obj, h5py.Group) and any(
            isinstance(v, h5py.Dataset) for v in obj.values()) else None)  # fmt: skip
    return found


@pytest.mark.parametrize("kind", ["approach", "cycle", "environment", "load control", "sweep",
                                  "sweep mc", "sweep pads"])  # fmt: skip
def test_every_file_kind_opens_in_xarray_with_named_axes_units_and_long_names(written, kind):
    path = written[kind]
    for group in groups_with_data(path):
        ds = open_group(path, group)
        assert ds.variables, (kind, group)
        for dim in ds.dims:
            assert not dim.startswith("phony_dim"), (kind, group, dim)
            assert dim in ds.coords, (kind, group, dim)
        for name, variable in ds.variables.items():
            units, long_name = variable.attrs.get("units"), variable.attrs.get("long_name")
            assert isinstance(units, str) and UNITS.fullmatch(units), (kind, group, name, units)
            assert isinstance(long_name, str) and long_name.strip(), (kind, group, name)
            assert "unit" not in variable.attrs, (kind, group, name)  # one spelling: CF's


def test_a_cycle_stores_its_branches_on_a_branch_axis_not_as_repeated_rows(written):
    path = written["cycle"]
    run, M = read_run(path), len(H)
    for group, name, stored in (("realizations", "load", run.realizations["load"]),
                                ("realizations/sums", "n_contact", run.sums[..., 0])):  # fmt: skip
        ds = open_group(path, group)
        assert ds[name].dims == ("realization", "branch", "h")
        assert list(ds["branch"].values) == ["approach", "retract"]
        np.testing.assert_array_equal(ds["h"].values, H)
        np.testing.assert_array_equal(ds[name].sel(branch="approach").values, stored[:, :M])
        np.testing.assert_array_equal(ds[name].sel(branch="retract").values, stored[:, M:])
    mean = open_group(path, "summary/mean")
    assert mean["load"].dims == ("branch", "h")
    retract = mean["load"].sel(branch="retract", h=1.0).item()
    assert retract == run.summary.mean["load"][M + H.index(1.0)]
    with h5py.File(path) as f:
        assert "row" not in f and f["branch"].shape == (2,)


def test_large_datasets_are_stored_chunked_gzip_and_shuffled_small_ones_contiguous(tmp_path):
    h = np.linspace(2.0, 0.0, 40)
    run = simulate(SMOOTH, SILICON, h, "10 um^2", law="jkr", cycle=True, realizations=40,
                   seed=3, workers=1, out=tmp_path / "big.h5")  # fmt: skip
    with h5py.File(run.path, "r") as f:
        big = ("realizations/load", "realizations/sums/load", "realizations/sums/n_contact")
        for name in big:
            assert f[name].nbytes > COMPRESS_ABOVE
            assert (f[name].compression, f[name].shuffle) == ("gzip", True), name
            assert f[name].chunks is not None, name
        for name in ("h", "realizations/N", "summary/mean/load"):
            assert f[name].nbytes <= COMPRESS_ABOVE
            assert (f[name].compression, f[name].chunks) == (None, None), name
        # plain h5py reads them: (realization, branch, h)
        np.testing.assert_array_equal(f["realizations/sums/load"][()],
                                      run.sums[..., 1].reshape(40, 2, h.size))  # fmt: skip
    back = read_run(run.path)
    np.testing.assert_array_equal(back.sums, run.sums)
    np.testing.assert_array_equal(back.realizations["load"], run.realizations["load"])


def test_an_edit_inside_a_compressed_dataset_is_detected_on_open(tmp_path):
    from mcsim import RunFileError

    path = simulate(SMOOTH, SILICON, np.linspace(2.0, 0.0, 40), "10 um^2", law="jkr", cycle=True,
                    realizations=40, seed=3, workers=1, out=tmp_path / "big.h5").path  # fmt: skip
    with h5py.File(path, "r+") as f:
        assert f["realizations/load"].compression == "gzip"
        f["realizations/load"][5, 1, 3] *= 1.0001
    with pytest.raises(RunFileError, match="checksum mismatch"):
        read_run(path)


def test_the_load_variable_is_read_as_ds_load_in_brackets_as_the_file_docs_say(written):
    """``ds.load`` is xarray's method (read into memory): the curve is ``ds["load"]``."""
    for path, group in ((written["sweep"], "/"), (written["cycle"], "summary/mean")):
        ds = xr.open_dataset(path, group=group, engine="h5netcdf")
        assert callable(ds.load) and not isinstance(ds.load, xr.DataArray)
        assert ds["load"].attrs["units"] == "1"
        assert "net normal force" in ds["load"].attrs["long_name"]
    sections = {"python.md": "## Run files", "sweeps.md": "# Parameter sweeps"}
    for page, heading in sections.items():
        text = (GUIDE / page).read_text()
        section = text.split(heading + "\n", 1)[1].split("\n# ", 1)[0].split("\n## ", 1)[0]
        assert 'ds["load"]' in section, f'docs/guide/{page}, {heading}: no ds["load"]'
    for module in (mcsim.store.runfile, mcsim.store.sweepfile):
        assert 'ds["load"]' in module.__doc__, module.__name__


@pytest.mark.parametrize("group", GROUPS)
def test_each_group_opens_in_xarray_with_named_axes_and_their_values(run, group):
    ds = open_group(run.path, group)
    assert set(ds.dims) <= AXES and ds.dims, dict(ds.dims)
    for dim in ds.dims:
        assert dim in ds.coords, dim
    if "h" in ds.dims:
        np.testing.assert_array_equal(ds["h"].values, run.h)
    if "realization" in ds.dims:
        np.testing.assert_array_equal(ds["realization"].values, np.arange(R))


def test_datatree_gives_the_same_axis_the_same_name_and_values_in_every_group(run):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tree = xr.open_datatree(run.path, engine="h5netcdf").load()
    np.testing.assert_array_equal(tree["d"].values, run.d)
    assert tree["d"].dims == ("h",)
    sizes = {}
    for node in tree.subtree:
        for dim, size in node.dataset.sizes.items():
            assert dim in AXES, (node.path, dim)
            assert sizes.setdefault(dim, size) == size, (node.path, dim)
            np.testing.assert_array_equal(node[dim].values, tree["realizations"][dim].values)
    assert sizes == {"h": len(H), "realization": R}
    mu = tree["summary/mean/mu"]
    assert mu.dims == ("h",)
    assert mu.sel(h=0.0).item() == run.summary.mean["mu"][H.index(0.0)]
    P = tree["realizations/sums/P"]
    assert P.dims == ("realization", "h")
    np.testing.assert_array_equal(P.values, run.sums[..., 1])
    P = tree["realizations/P"]
    np.testing.assert_array_equal(P.sel(realization=2, h=1.0), run.realizations["P"][2, 1])


def test_each_raw_sums_column_is_a_variable_with_its_own_units(run):
    with h5py.File(run.path) as f:
        sums = f["realizations/sums"]
        assert sorted(k for k in sums if k not in AXES) == sorted(SUM_COLUMNS)
        units = {c: sums[c].attrs["units"] for c in SUM_COLUMNS}
    assert list(units.values()) == list(SUM_UNITS)
    assert units["n_contact"] == "1"
    assert units["P"] == units["F"] == units["T"] == "N"
    assert {units[c] for c in ("PP", "FF", "TT", "PF", "PT", "FT")} == {"N^2"}
    ds = open_group(run.path, "realizations/sums")
    assert {c: ds[c].attrs["units"] for c in SUM_COLUMNS} == units
    assert ds["n_contact"].attrs["long_name"] == "summits in contact"


# --- Jupyter and pandas: short summaries, labelled tables ------------------------------


def test_run_repr_is_a_short_summary_of_inputs_and_completeness_not_the_arrays(run):
    text = repr(run)
    assert "array(" not in text and len(text.splitlines()) <= 10, text
    for words in ("smooth", "silicon", "seed", "3 values from 0 to 2", "300 µm²",
                  "3, complete", str(run.path)):  # fmt: skip
        assert words in text, words
    partial = repr(dataclasses.replace(run, complete=False))
    assert "unfinished" in partial and "3, complete;" not in partial


def test_run_html_summary_is_a_table_with_the_same_rows(run):
    page = run._repr_html_()
    assert page.startswith("<table") and page.endswith("</table>")
    assert page.count("<tr>") == len(repr(run).splitlines()) - 1
    assert "silicon" in page and "array(" not in page


def test_curves_repr_stays_short_for_long_sweeps_and_names_the_sweep():
    curves = gw_curves(SURFACES["rough"], MATERIALS["silicon"], np.linspace(4, -1, 5001))
    text = repr(curves)
    assert "array(" not in text and len(text.splitlines()) <= 6, text
    for words in ("rough", "silicon", "seed", "5001 values from -1 to 4"):
        assert words in text, words
    assert curves._repr_html_().count("<tr>") == len(text.splitlines()) - 1


def test_curves_table_is_a_dataframe_with_columns_named_by_their_normalisation():
    h = [2.0, 0.0, -1.0]
    curves = gw_curves(SURFACES["smooth"], MATERIALS["silicon"], h)
    table = curves.table()
    assert isinstance(table, pd.DataFrame)
    assert list(table.columns) == ["h = d/σ", "N_c/N", "P/(A_n K)", "F/(A_n K)", "T/(A_n K)",
                                   "μ = T/(P + F)"]  # fmt: skip
    np.testing.assert_array_equal(table["h = d/σ"], h)
    for label, q in zip(table.columns[1:], QUANTITIES, strict=True):
        np.testing.assert_array_equal(table[label], getattr(curves, q))


def test_a_cycle_run_and_submodules_read_naturally_in_a_notebook():
    import mcsim
    from mcsim.model.presets import MATERIALS, SURFACES

    assert mcsim.physics.laws.get_law_set("jkr").name == "jkr"  # after a plain `import mcsim`
    run = mcsim.simulate(SURFACES["smooth"], MATERIALS["silicon"], [1.0, 0.0], "10um^2",
                         seed=1, law="jkr", cycle=True)  # fmt: skip
    assert "retraction from h = 0" in repr(run) and "retraction" in run._repr_html_()

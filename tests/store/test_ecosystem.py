"""Results in the scientific Python ecosystem: run files in xarray (named, aligned axes),
short summaries in Jupyter, pandas tables."""

import dataclasses
import warnings

import h5py
import numpy as np
import pandas as pd
import pytest
import xarray as xr

from mcsim import gw_curves
from mcsim.engine.kernels import SUM_COLUMNS
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.analytic import QUANTITIES
from mcsim.studies.simulation import simulate

H = [2.0, 1.0, 0.0]
R = 3
AXES = {"h", "realization", "column"}
GROUPS = ("realizations", "progress", "analytic", "summary", "summary/mean", "summary/se")


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    path = tmp_path_factory.mktemp("eco") / "a.h5"
    return simulate(SURFACES["smooth"], MATERIALS["silicon"], H, "300 um^2", realizations=R,
                    seed=4, out=path)  # fmt: skip


def open_group(path, group):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # phony dimensions come with a warning
        return xr.open_dataset(path, group=group, engine="h5netcdf").load()


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
    if "column" in ds.dims:
        assert list(ds["column"].values) == list(SUM_COLUMNS)


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
    assert sizes == {"h": len(H), "realization": R, "column": len(SUM_COLUMNS)}
    mu = tree["summary/mean/mu"]
    assert mu.dims == ("h",)
    assert mu.sel(h=0.0).item() == run.summary.mean["mu"][H.index(0.0)]
    sums = tree["realizations/sums"]
    assert sums.dims == ("realization", "h", "column")
    np.testing.assert_array_equal(sums.sel(column="P").values, run.sums[..., 1])
    P = tree["realizations/P"]
    np.testing.assert_array_equal(P.sel(realization=2, h=1.0), run.realizations["P"][2, 1])


def test_raw_sums_carry_one_unit_per_column(run):
    with h5py.File(run.path) as f:
        sums = f["realizations/sums"]
        units = dict(zip(sums.attrs["columns"], sums.attrs["units"], strict=True))
        assert sums.attrs["unit"] != "N"  # the counts and second moments are not forces
    assert list(units) == list(SUM_COLUMNS)
    assert units["n_contact"] == "1"
    assert units["P"] == units["F"] == units["T"] == "N"
    assert {units[c] for c in ("PP", "FF", "TT", "PF", "PT", "FT")} == {"N^2"}
    tree = xr.open_datatree(run.path, engine="h5netcdf")
    assert list(tree["realizations/sums"].attrs["units"]) == list(units.values())


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

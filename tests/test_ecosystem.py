"""Results in the scientific Python ecosystem: run files in xarray (named, aligned axes)."""

import warnings

import h5py
import numpy as np
import pytest
import xarray as xr

from mcsim.kernels import SUM_COLUMNS
from mcsim.presets import MATERIALS, SURFACES
from mcsim.simulation import simulate

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

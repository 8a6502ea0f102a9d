"""simulate(environment=...): van der Waals and capillary pressure sampled over each patch's cells.

Tolerances: |z| < 5 with z = (mc − analytic)/se and se the cells' standard error
(iid cells given N, mcsim.engine.cells), so a correct run fails by chance with
probability ~6e-7 per comparison; the seeds are fixed.
"""

import dataclasses

import h5py
import numpy as np
import pytest

from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.environment import Environment
from mcsim.store.runfile import read_run
from mcsim.studies.simulation import simulate
from mcsim.topography.empirical import Empirical

SMOOTH, SILICON = SURFACES["smooth"], MATERIALS["silicon"]
HUMID = Environment(hamaker=1.6e-19, cutoff=0.2e-9, rh=0.6, contact_angle=0.3)
H = [2.5, 1.0, 0.0]
#: Beyond these, the run file of an environment run must equal the plain run's.
PROVENANCE = {"created", "command", "checksum"}


def _run(surface=SMOOTH, environment=HUMID, **kwargs):
    options = {"area": "300 um^2", "realizations": 4, "seed": 11, "workers": 1} | kwargs
    return simulate(surface, SILICON, H, environment=environment, **options)


def _assert_agrees(run):
    table = run.compare()
    env = table[table.quantity.isin(["vdw", "capillary"])]
    assert set(env.quantity) == {"vdw", "capillary"}
    assert (env.note == "").all(), env
    assert np.all(np.abs(env.z) < 5), env


def test_gaussian_heights_agree_with_the_analytic_curves():
    _assert_agrees(_run())


def test_measured_histogram_agrees_with_the_analytic_curves():
    # A skewed (exponential) map, far from Gaussian: the cells sample the histogram itself.
    z = np.random.default_rng(5).exponential(1.0, 50_000)
    shape = Empirical.from_samples(z - z.mean(), bins=40, source="test map")
    surface = dataclasses.replace(SMOOTH, rq=1.6e-9, summit_offset=1.5e-9, map_heights=shape)
    _assert_agrees(_run(surface))


def test_contact_sums_are_the_same_with_and_without_the_environment():
    with_env, without = _run(), _run(environment=None)
    np.testing.assert_array_equal(with_env.sums, without.sums)
    assert without.environment is None


@pytest.mark.parametrize("workers, chunk_size", [(2, 1 << 16), (1, 1 << 17)])
def test_cell_sums_do_not_depend_on_workers_or_chunk_size(workers, chunk_size):
    # 160k summits per patch: three blocks of cells, so the chunking matters.
    big = {"area": "9400 um^2", "realizations": 2}
    reference = _run(**big, workers=1, chunk_size=1 << 16)
    other = _run(**big, workers=workers, chunk_size=chunk_size)
    assert reference.environment.cells.n_cells.min() > 2 * (1 << 16)
    np.testing.assert_array_equal(reference.environment.cells.sums, other.environment.cells.sums)


def _contents(path):
    with h5py.File(path, "r") as f:
        attrs = {k: v for k, v in f.attrs.items() if k not in PROVENANCE}
        data = {}
        f.visititems(
            lambda name, obj: data.setdefault(
                name, obj[()] if isinstance(obj, h5py.Dataset) else dict(obj.attrs)
            )
        )
        return attrs, data


def test_run_file_without_environment_is_unchanged_and_with_it_only_gains_a_group(tmp_path):
    plain = _run(environment=None, out=tmp_path / "plain.h5")
    _run(environment=None, out=tmp_path / "none.h5")
    simulate(SMOOTH, SILICON, H, area="300 um^2", realizations=4, seed=11, workers=1,
             out=tmp_path / "keyword.h5")  # fmt: skip
    _run(out=tmp_path / "env.h5")
    attrs, data = _contents(plain.path)
    for other in ("none.h5", "keyword.h5"):
        other_attrs, other_data = _contents(tmp_path / other)
        assert other_attrs == attrs
        assert other_data.keys() == data.keys()
    env_attrs, env_data = _contents(tmp_path / "env.h5")
    assert env_attrs == attrs
    assert not any(k.startswith("environment") for k in data)
    assert {k for k in env_data if not k.startswith("environment")} == set(data)
    for k, v in data.items():
        if isinstance(v, np.ndarray):
            np.testing.assert_array_equal(env_data[k], v, err_msg=k)


def test_run_file_records_the_environment_and_reads_back(tmp_path):
    run = _run(out=tmp_path / "env.h5")
    with h5py.File(run.path, "r") as f:
        a = f["environment"].attrs
        assert (a["hamaker"], a["cutoff"], a["rh"], a["contact_angle"]) == (
            1.6e-19,
            0.2e-9,
            0.6,
            0.3,
        )
        assert a["gap_source"].startswith("Nayak estimate")
        assert a["rq"] == run.environment.cells.gap.rq
        assert '"cutoff": "m"' in a["units"]
    back = read_run(run.path)
    assert back.environment.cells.environment == HUMID
    np.testing.assert_array_equal(back.vdw.mean, run.vdw.mean)
    np.testing.assert_array_equal(back.capillary.se, run.capillary.se)

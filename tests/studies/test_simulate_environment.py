"""simulate(environment=...): each summit's cap summed with the contacts, the open gaps added.

The caps' van der Waals and meniscus forces are outputs of the law set (docs/physics.md,
section 'The environment: summits and open gaps'): summed over the same summits as the
loads, with the summit-level standard errors of docs/physics.md, section 'Monte Carlo
statistics'. Tolerances: |z| < 5 with z = (mc − analytic)/se, so a correct run fails by chance
with probability ~6e-7 per comparison; the seeds are fixed. The calibration of those standard
errors over many patches is tests/engine/test_zscore_calibration.py.
"""

import dataclasses

import h5py
import numpy as np
import pytest

from mcsim.engine.kernels import block_sums_numpy, sum_columns
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.environment import Environment
from mcsim.physics.surfaceenvironment import open_gap_pressures
from mcsim.store.runfile import read_run
from mcsim.studies.simulation import simulate
from mcsim.topography.empirical import Empirical

SMOOTH, SILICON = SURFACES["smooth"], MATERIALS["silicon"]
HUMID = Environment(hamaker=1.6e-19, cutoff=0.2e-9, rh=0.6, contact_angle=0.3)
H = [2.5, 1.0, 0.0]
#: Beyond these, the run files of the same dry inputs must be equal.
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


def test_gaussian_summits_agree_with_the_analytic_curves():
    _assert_agrees(_run())


def test_a_measured_summit_histogram_agrees_with_the_analytic_curves():
    # A skewed (exponential) summit population, far from Gaussian: the caps integrate over it.
    z = np.random.default_rng(5).exponential(1.0, 50_000)
    shape = Empirical.from_samples(z - z.mean(), bins=40, source="test map")
    _assert_agrees(_run(dataclasses.replace(SMOOTH, heights=shape)))


def test_the_caps_are_summed_over_the_same_summits_as_the_loads():
    run = _run(keep_heights=True, law="jkr", realizations=2)
    law, spec = run.spec.law_set, run.spec
    assert law.names == ("load", "area", "vdw", "capillary")
    for r, z in enumerate(run.heights):
        again = block_sums_numpy(z, spec.d, law, spec.arguments, edges=spec.edges)
        # the kernel and the NumPy reference add in other orders: rounding of a sum
        np.testing.assert_allclose(run.sums[r], again, rtol=1e-12, atol=0)
    # the summits drawn reach down to the caps' band edge, below the contacts' s_min
    assert spec.s_min < min(H) - 1


@pytest.mark.parametrize("workers, chunk_size", [(2, 1 << 16), (1, 1 << 17)])
def test_the_sums_do_not_depend_on_workers_or_chunk_size(workers, chunk_size):
    # 160k summits per patch: three blocks, so the chunking matters.
    big = {"area": "9400 um^2", "realizations": 2}
    reference = _run(**big, workers=1, chunk_size=1 << 16)
    other = _run(**big, workers=workers, chunk_size=chunk_size)
    assert reference.n_summits.min() > 2 * (1 << 16)
    np.testing.assert_array_equal(reference.sums, other.sums)


def test_the_run_adds_the_open_gaps_to_the_caps():
    run = _run()
    spec = run.spec
    gaps = open_gap_pressures(spec.row_h, spec.surface, HUMID)
    for term in ("vdw", "capillary"):
        estimate = getattr(run, term)
        np.testing.assert_array_equal(
            estimate.mean, run.summary.mean[term] + gaps[term] / SILICON.K
        )
        np.testing.assert_array_equal(estimate.se, run.summary.se[term])


def _contents(path):
    with h5py.File(path, "r") as f:
        attrs = {k: v for k, v in f.attrs.items() if k not in PROVENANCE}
        data = {}

        def keep(name, obj):  # returns None: visititems stops at the first non-None return
            data[name] = obj[()] if isinstance(obj, h5py.Dataset) else dict(obj.attrs)

        f.visititems(keep)
        return attrs, data


def test_run_file_without_environment_is_unchanged_and_with_it_gains_the_caps_and_a_group(
    tmp_path,
):
    plain = _run(environment=None, out=tmp_path / "plain.h5")
    _run(environment=None, out=tmp_path / "none.h5")
    _run(environment=Environment(), out=tmp_path / "inactive.h5")  # nothing acts: dry
    simulate(SMOOTH, SILICON, H, area="300 um^2", realizations=4, seed=11, workers=1,
             out=tmp_path / "keyword.h5")  # fmt: skip
    _run(out=tmp_path / "env.h5")
    attrs, data = _contents(plain.path)
    for other in ("none.h5", "inactive.h5", "keyword.h5"):
        other_attrs, other_data = _contents(tmp_path / other)
        assert other_attrs == attrs
        assert other_data.keys() == data.keys()
        for k, v in data.items():
            if isinstance(v, np.ndarray):
                np.testing.assert_array_equal(other_data[k], v, err_msg=k)
    _, env_data = _contents(tmp_path / "env.h5")
    assert not any(k.startswith("environment") for k in data)
    assert {"environment", "environment/open_gaps/vdw", "realizations/sums/vdw",
            "realizations/sums/capillary", "summary/mean/vdw"} <= set(env_data)  # fmt: skip
    assert set(data) <= set(env_data)


def test_run_file_records_the_environment_and_reads_back(tmp_path):
    run = _run(out=tmp_path / "env.h5")
    with h5py.File(run.path, "r") as f:
        a = f["environment"].attrs
        stored = (a["hamaker"], a["cutoff"], a["rh"], a["contact_angle"])
        assert stored == (1.6e-19, 0.2e-9, 0.6, 0.3)
        assert a["gap_source"].startswith("Nayak estimate")
        assert a["rq"] == run.environment.gap.rq
        assert a["band_edge"] == pytest.approx(0.2e-9 + 1 / (2 * np.pi * SMOOTH.R * SMOOTH.eta))
        assert '"cutoff": "m"' in a["units"] and "open gaps" in a["model"]
    back = read_run(run.path)
    assert back.spec.environment == HUMID and back.spec == run.spec
    np.testing.assert_array_equal(back.vdw.mean, run.vdw.mean)
    np.testing.assert_array_equal(back.capillary.se, run.capillary.se)
    assert sum_columns(back.spec.law_set) == sum_columns(run.spec.law_set)


def test_run_file_records_the_films_and_refuses_menisci_written_before_them(tmp_path):
    """The films of docs/physics.md, section 'Water below the Kelvin gate: adsorbed films':
    stored (film_thickness NaN for the isotherm) and read back; a humid file without them was
    sampled with the Kelvin gate, whose caps mean another model: refused, saying why."""
    from mcsim.model.errors import RunFileError
    from mcsim.store.files import checksum

    given = dataclasses.replace(HUMID, film_thickness=1.2e-9, structured_film=0.5e-9)
    dry = Environment(hamaker=1.6e-19)
    for env, name in ((HUMID, "isotherm.h5"), (given, "given.h5"), (dry, "dry.h5")):
        run = _run(environment=env, out=tmp_path / name)
        with h5py.File(run.path, "r") as f:
            a = f["environment"].attrs
            assert a["film"] == env.film and a["structured_film"] == env.structured_film
            assert np.isnan(a["film_thickness"]) == (env.film_thickness is None)
        assert read_run(run.path).spec.environment == env
    for name in ("isotherm.h5", "dry.h5"):  # as written before the films
        with h5py.File(tmp_path / name, "r+") as f:
            for k in ("film_thickness", "structured_film"):
                del f["environment"].attrs[k]
            f.attrs["checksum"] = checksum(f)
    with pytest.raises(RunFileError, match=r"predate the adsorbed films .* run it again"):
        read_run(tmp_path / "isotherm.h5")
    assert read_run(tmp_path / "dry.h5").spec.environment == dry  # no menisci: the same model


def test_run_file_records_the_retardation_and_an_older_file_reads_as_non_retarded(tmp_path):
    """The wavelength is stored (m; NaN: non-retarded); a file written before retardation has
    none, and its sums were non-retarded: it reads back with retardation_wavelength None."""
    from mcsim.store.files import checksum

    run = _run(out=tmp_path / "env.h5")
    with h5py.File(run.path, "r") as f:
        assert f["environment"].attrs["retardation_wavelength"] == 100e-9
        assert '"retardation_wavelength": "m"' in f["environment"].attrs["units"]
    flat_env = dataclasses.replace(HUMID, retardation_wavelength=None)
    flat = _run(environment=flat_env, out=tmp_path / "flat.h5")
    # the same summits (common random numbers): retardation lowers every row's attraction
    assert np.all(run.vdw.mean < flat.vdw.mean)
    with h5py.File(flat.path, "r+") as f:
        assert np.isnan(f["environment"].attrs["retardation_wavelength"])
        del f["environment"].attrs["retardation_wavelength"]  # as written before retardation
        f.attrs["checksum"] = checksum(f)
    back = read_run(flat.path)
    assert back.spec.environment == flat_env
    np.testing.assert_array_equal(back.vdw.mean, flat.vdw.mean)


def test_a_measured_map_keeps_its_heights_about_the_mean_plane_in_the_file(tmp_path):
    z = np.random.default_rng(5).exponential(1.0, 50_000)
    shape = Empirical.from_samples(z - z.mean(), bins=40, source="test map")
    surface = dataclasses.replace(SMOOTH, rq=1.6e-9, summit_offset=1.5e-9, map_heights=shape)
    run = _run(surface, out=tmp_path / "map.h5")
    back = read_run(run.path)
    assert back.spec.surface.rq == 1.6e-9 and back.spec.surface.map_heights is not None
    np.testing.assert_array_equal(back.vdw.mean, run.vdw.mean)


def test_an_interrupted_humid_run_resumes_to_the_same_bits(tmp_path):
    """The checkpoint records the environment (it sets the sums' columns): a run stopped after
    its first realization and resumed equals the run made in one go, bit for bit."""
    from mcsim.engine.montecarlo import EnsembleSums
    from mcsim.store.runfile import read_state, write_checkpoint

    whole = _run(out=tmp_path / "whole.h5")
    partial = EnsembleSums.start(whole.spec)
    partial.sums[:1], partial.done_blocks[:1] = whole.sums[:1], whole.ensemble.n_blocks[:1]
    write_checkpoint(tmp_path / "run.partial.h5", partial, command="test")
    state, _ = read_state(tmp_path / "run.partial.h5")
    assert state.spec == whole.spec and state.spec.environment == HUMID
    resumed = _run(out=tmp_path / "run.h5", resume=True)
    np.testing.assert_array_equal(resumed.sums, whole.sums)
    np.testing.assert_array_equal(resumed.vdw.mean, whole.vdw.mean)

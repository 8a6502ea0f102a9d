"""The GPU backend (mcsim.engine.cuda): vocabulary, real CUDA compilation, simulator and GPU.

Three levels, each skipped with its reason where it cannot run:

* always: the vocabulary check, the Philox generator's known answers, the one-line
  error without a GPU;
* with numba-cuda and NVVM (``pip install 'numba-cuda[cu13]'``, no GPU needed): every
  registered law set's kernel compiled to PTX by the real CUDA compiler, which rejects
  NumPy functions (numba's simulator would not);
* with numba-cuda: tests/cuda_checks.py under the CUDA simulator (small populations),
  and on a GPU where one is available.
"""

from __future__ import annotations

import functools
import importlib.util
import os
import subprocess
import sys
import types
from unittest import mock

import numpy as np
import pytest
from conftest import CudaChecks
from cuda_checks import MATERIAL, SURFACE, law_sets
from lawset_toy import toy_grip

from mcsim.engine import cuda as mc
from mcsim.engine import cudaheights
from mcsim.model.errors import ParameterError
from mcsim.physics.laws import LAW_SETS, ieee

HAVE_NUMBA_CUDA = importlib.util.find_spec("numba_cuda") is not None
needs_numba_cuda = pytest.mark.skipif(not HAVE_NUMBA_CUDA, reason="numba-cuda is not installed")


def law_using_where(delta, R):
    return np.where(delta > 0, R * delta, 0.0)


def law_using_a_helper(delta, R):
    return R * _helper(delta)


def _helper(delta):
    return np.sqrt(np.maximum(delta, 0.0))


def law_using_a_helper_using_where(delta, R):
    return R * _helper_using_where(delta)


def _helper_using_where(delta):
    return np.where(delta > 0, delta, 0.0)


def law_using_a_function_of_another_module(delta, R):
    return toy_grip(delta, R, R)


def test_a_law_outside_the_vocabulary_is_rejected_before_compilation():
    with pytest.raises(ParameterError, match=r"np\.where"):
        mc.check_vocabulary(law_using_where)
    with pytest.raises(ParameterError, match=r"_helper_using_where uses np\.where"):
        mc.check_vocabulary(law_using_a_helper_using_where)
    with pytest.raises(ParameterError, match="toy_grip"):
        mc.check_vocabulary(law_using_a_function_of_another_module)
    mc.check_vocabulary(law_using_a_helper)  # a helper of the law's own file


def test_every_registered_law_function_keeps_to_the_vocabulary():
    for law in LAW_SETS.values():
        for fn in law.laws:
            mc.check_vocabulary(fn)


def philox_python():
    """The sampler's source (the text the kernel compiles) run as plain Python."""
    ns = {"np": np, "HEIGHTS": cudaheights.HEIGHTS, "_ndtri": None}
    exec(cudaheights.PHILOX, ns)
    return ns


@pytest.mark.parametrize(
    ("counter", "key", "expected"),
    [
        ((0, 0, 0, 0), (0, 0), (0x6627E8D5, 0xE169C58D, 0xBC57AC4C, 0x9B00DBD8)),
        ((0xFFFFFFFF,) * 4, (0xFFFFFFFF,) * 2, (0x408F276D, 0x41C83B0E, 0xA20BC7C6, 0x6D5451FD)),
        (
            (0x243F6A88, 0x85A308D3, 0x13198A2E, 0x03707344),
            (0xA4093822, 0x299F31D0),
            (0xD16CFE09, 0x94FDCCEB, 0x5001E420, 0x24126EA1),
        ),
    ],
)
def test_the_height_generator_is_philox4x32_10(counter, key, expected):
    """Random123's known-answer vectors (kat_vectors, philox4x32 10)."""
    philox = philox_python()["_philox"]
    words = philox(*(np.uint64(c) for c in counter), *(np.uint64(k) for k in key))
    assert tuple(int(w) for w in words) == expected


def test_uniforms_lie_strictly_inside_the_unit_interval():
    unit = philox_python()["_unit"]
    top = np.uint64(0xFFFFFFFF)
    assert unit(np.uint64(0), np.uint64(0)) == 2**-53
    assert unit(top, top) == 1 - 2**-53


@pytest.mark.parametrize("missing", ["numba_cuda", "numba.cuda"])
def test_device_cuda_without_numba_cuda_is_a_parameter_error(monkeypatch, missing):
    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda n, *a: None if n == missing else real(n, *a)
    )
    monkeypatch.setitem(sys.modules, missing, None)
    with pytest.raises(ParameterError, match=r"mcsim\[gpu\]"):
        mc.require_gpu()


@needs_numba_cuda
def test_device_cuda_without_a_gpu_is_a_parameter_error(monkeypatch):
    from numba import cuda

    monkeypatch.delenv("NUMBA_ENABLE_CUDASIM", raising=False)
    monkeypatch.setattr(cuda, "is_available", lambda: False)
    with pytest.raises(ParameterError, match="no CUDA GPU"):
        mc.require_gpu()


def test_unsupported_height_distributions_are_refused_on_the_gpu():
    other = types.SimpleNamespace(name="weibull")
    with pytest.raises(ParameterError, match="weibull"):
        cudaheights.height_sampler(other, 0.0)


# -- the real CUDA compiler (NVVM), no GPU needed ------------------------------------


def _nvvm_available() -> bool:
    if not HAVE_NUMBA_CUDA or mc.simulating():
        return False
    try:
        from numba.cuda.cudadrv import nvvm

        nvvm.NVVM()
    except Exception:
        return False
    return True


needs_nvvm = pytest.mark.skipif(
    not _nvvm_available(),
    reason="NVVM (CUDA's compiler) is not installed: pip install 'numba-cuda[cu13]'",
)


def kernel_ptx(law, args, cc=(9, 0)) -> str:
    """PTX of ``law``'s kernel for an H100 (sm_90), compiled by NVVM without a GPU."""
    from numba import cuda, typeof

    arr, iarr = typeof(np.zeros(1)), typeof(np.zeros(1, np.int64))
    i64, f64, u64, flag = typeof(np.int64(0)), typeof(1.0), typeof(np.uint64(0)), typeof(True)
    params = [arr if np.ndim(p) else f64 for a in args for p in a] or [f64]
    sig = (arr, iarr, iarr, i64, f64, u64, u64, i64, f64, arr, arr, arr, flag,
           arr, arr, arr, f64, f64, typeof(np.zeros((1, 1, 1))), *params)  # fmt: skip
    # device functions compile for the current device's capability: name one
    fake = types.SimpleNamespace(compute_capability=cc)
    with mock.patch("numba.cuda.dispatcher.get_current_device", return_value=fake):
        return cuda.compile_ptx(mc._namespace(law)["_kernel"], sig, cc=cc)[0]


@needs_nvvm
@pytest.mark.parametrize("name", sorted(law_sets()))
def test_every_law_set_kernel_compiles_with_the_real_cuda_compiler(name):
    law = law_sets()[name]
    ptx = kernel_ptx(law, law.arguments(SURFACE, MATERIAL))
    assert ".entry" in ptx and "sm_90" in ptx


@needs_nvvm
def test_law_functions_reach_the_cuda_compiler_through_the_device_vocabulary():
    """The real CUDA target cannot compile NumPy ufuncs (numba-cuda 0.30: KeyError
    <ufunc 'sqrt'>); the law's own source with np bound to device_numpy compiles."""
    from numba import cuda, float64

    fn = LAW_SETS["seed"].laws[0]
    sig = (float64,) * (1 + len(LAW_SETS["seed"].outputs[0].parameter_names))
    with pytest.raises(Exception, match="sqrt"):
        cuda.compile_ptx(fn, sig, device=True, cc=(9, 0))
    compiled = mc.device_source(fn)
    assert compiled.__globals__["np"] is mc.device_numpy()
    cuda.compile_ptx(compiled, sig, device=True, cc=(9, 0))


@needs_nvvm
def test_a_helper_compiles_as_a_device_function_that_the_law_calls():
    """The law's ``_helper`` is bound to its CUDA device function, which the real CUDA
    compiler compiles for the law's call (a float64 signature) into the law's PTX."""
    from numba import cuda, float64

    compiled = mc.device_source(law_using_a_helper)
    helper = compiled.__globals__["_helper"]
    assert helper is mc.device_function(_helper)
    assert isinstance(helper, cuda.dispatcher.CUDADispatcher)
    fake = types.SimpleNamespace(compute_capability=(9, 0))
    with mock.patch("numba.cuda.dispatcher.get_current_device", return_value=fake):
        ptx = cuda.compile_ptx(compiled, (float64, float64), device=True, cc=(9, 0))[0]
    assert (float64,) in helper.overloads
    assert "_helper" in ptx


@needs_numba_cuda
def test_the_ieee_helpers_become_cudas_bit_casts_on_a_real_device(monkeypatch):
    """The simulator runs the NumPy helpers; the CUDA compiler gets libdevice's casts."""
    from numba.cuda import libdevice

    monkeypatch.setattr(mc, "simulating", lambda: False)
    assert mc._on_device(ieee.float_bits) is libdevice.double_as_longlong
    assert mc._on_device(ieee.bits_float) is libdevice.longlong_as_double
    assert mc._on_device(2.5) == 2.5


@needs_numba_cuda
def test_the_device_numpy_holds_only_the_vocabulary():
    shim = mc.device_numpy()
    names = {n for n in vars(shim) if not n.startswith("__")}
    assert names == set(mc.VOCABULARY)
    assert not hasattr(shim, "where")


# -- the kernel's results: simulator, and a GPU where there is one -------------------


@functools.cache  # a fresh process per probe (~1 s); the answer holds for the session
def _gpu_reason() -> str | None:
    if not HAVE_NUMBA_CUDA:
        return "numba-cuda is not installed"
    probe = "from numba import cuda; print(cuda.is_available())"
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_ENABLE_CUDASIM"}
    out = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True, text=True)
    return None if out.stdout.strip() == "True" else "no CUDA GPU on this machine"


@pytest.fixture(scope="module", params=["simulator", "gpu"])
def checks(request, tmp_path_factory, cuda_simulator_checks):
    """The results of tests/cuda_checks.py: under the simulator (small populations;
    started as the session started, see conftest.py), and on a GPU where there is one."""
    if request.param == "simulator":
        if not HAVE_NUMBA_CUDA:
            pytest.skip("numba-cuda is not installed")
        return cuda_simulator_checks.result()
    reason = _gpu_reason()
    if reason is not None:
        print(f"GPU checks skipped: {reason}")
        pytest.skip(reason)
    folder = tmp_path_factory.mktemp("cuda-gpu")
    return CudaChecks(False, folder, "200000", "65536,65536,65536,1000").result()


def test_gpu_block_sums_equal_numpy_for_every_law_set_and_branch(checks):
    """Every registered law set and the toy, whose outputs call helpers (device
    functions on the GPU), as do jkr's and elastic-plastic's, and jkr with the
    environment's caps (tests/cuda_checks.py)."""
    laws = law_sets()
    expected = {f"{n}/approach" for n in laws}
    expected |= {f"{n}/retract" for n, law in laws.items() if law.retract}
    assert set(checks["block_sums"]) == expected
    for case, r in checks["block_sums"].items():
        assert r["n_contact"] == r["ref_n_contact"], case
        assert r["error"] < 1e-12, case


def test_gpu_sampling_is_bit_identical_for_any_launch_configuration(checks):
    for r in checks["sampling"].values():
        assert r["identical_across_launches"]
        assert r["other_seed_differs"]


def test_gpu_sums_are_bit_identical_for_any_split_of_the_rows(checks):
    """More rows than one group of the reduction (SHARED_BYTES) holds, in one launch or
    two: the same bits."""
    assert checks["rows_split_identical"]


def test_gpu_heights_follow_the_truncated_distribution(checks):
    """Contact counts at h = −0.5 (= s_min), 0, 1, 2 against P(S > h)/P(S > s_min)."""
    for r in checks["sampling"].values():
        assert r["all_contact_at_s_min"]
        assert max(abs(z) for z in r["z_scores"][1:]) < 5


def test_same_seed_twice_gives_identical_gpu_run_files_that_record_the_device(checks):
    run = checks["simulate"]
    assert run["device"] == "cuda"
    assert run["datasets"] > 5 and run["identical"]


def test_a_gpu_run_agrees_with_the_analytic_curves(checks):
    """``Run.compare`` (what ``mcsim compare`` prints): every finite |z| < 5."""
    z = checks["simulate"]["z"]
    assert len(z) >= 6
    assert max(abs(v) for v in z) < 5
    caps = checks["simulate"]["z_caps"]  # a humid jkr run: the caps' van der Waals and menisci
    assert len(caps) >= 4
    assert max(abs(v) for v in caps) < 5


def test_a_launchs_sums_stay_within_launch_bytes():
    # 51 rows of the seed's 10 columns: the most blocks; 1000 rows: as many as 256 MiB hold
    assert mc.blocks_per_launch(51, 10) == mc.LAUNCH_BLOCKS
    assert mc.blocks_per_launch(1000, 10) == mc.LAUNCH_BYTES // 80000 < mc.LAUNCH_BLOCKS
    assert mc.blocks_per_launch(10**9, 10) == 1  # never none


def test_an_unknown_device_is_a_parameter_error():
    from mcsim.engine.spec import MonteCarloSpec

    with pytest.raises(ParameterError, match="device = 'tpu'"):
        MonteCarloSpec(SURFACE, MATERIAL, [0.0], 1e-10, 1, 1, device="tpu")


@pytest.mark.parametrize(
    "command",
    [
        ["simulate", "--h", "0,1", "--area", "1e-10", "--seed", "1"],
        ["sweep", "--law", "dmt", "--vary", "gamma=0.1,0.2", "--h", "0,1", "--mc", "--area",
         "1e-10", "--seed", "1"],
    ],
    ids=["simulate", "sweep"],
)  # fmt: skip
def test_device_cuda_on_a_machine_without_a_gpu_is_a_one_line_cli_error(tmp_path, command):
    if _gpu_reason() is None:
        pytest.skip("this machine has a GPU")
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_ENABLE_CUDASIM"}
    out = tmp_path / "run.h5"
    done = subprocess.run(
        [sys.executable, "-m", "mcsim", *command, "--surface", "smooth", "--material", "silicon",
         "--device", "cuda", "--out", str(out)],
        env=env, capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert done.returncode != 0
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "cuda" in lines[0], done.stderr
    assert list(tmp_path.iterdir()) == []


def test_a_sweeps_monte_carlo_runs_use_the_device_asked_for_and_record_it(monkeypatch):
    import mcsim.engine.cuda
    import mcsim.studies.simulation
    import mcsim.studies.sweeps

    simulate = mcsim.studies.simulation.simulate

    used = []

    def on_cpu(*args, device="cpu", **kwargs):  # stands in for the GPU: records the device
        used.append(device)
        return simulate(*args, **kwargs)

    monkeypatch.setattr(mcsim.engine.cuda, "require_gpu", lambda: None)
    monkeypatch.setattr(mcsim.studies.simulation, "simulate", on_cpu)
    result = mcsim.studies.sweeps.sweep(SURFACE, MATERIAL, {"gamma": [0.1, 0.2]}, law="dmt", h=[1.0],
                                mc=True, area=1e-11, seed=1, device="cuda")  # fmt: skip
    assert used == ["cuda", "cuda"] and result.attrs["device"] == "cuda"
    with pytest.raises(ParameterError, match="Monte Carlo runs only"):
        mcsim.studies.sweeps.sweep(SURFACE, MATERIAL, {"gamma": [0.1]}, law="dmt", device="cuda")


def test_a_cpu_run_file_records_its_device(tmp_path):
    import h5py

    from mcsim.studies.simulation import simulate

    simulate(SURFACE, MATERIAL, [1.0], 200 / SURFACE.eta, seed=1, out=tmp_path / "r.h5")
    with h5py.File(tmp_path / "r.h5") as f:
        assert f.attrs["device"] == "cpu"


def test_a_run_cannot_be_resumed_on_another_device():
    from mcsim.engine.montecarlo import EnsembleSums, run_sums
    from mcsim.engine.spec import MonteCarloSpec

    cpu = MonteCarloSpec(SURFACE, MATERIAL, [0.0], 1e-10, 1, 1)
    gpu = MonteCarloSpec(SURFACE, MATERIAL, [0.0], 1e-10, 1, 1, device="cuda")
    assert cpu.differences(gpu) == ["device"]
    with pytest.raises(ParameterError, match="device"):
        run_sums(gpu, resume=EnsembleSums.start(cpu))

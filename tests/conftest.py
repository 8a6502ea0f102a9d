"""Shared fixtures: real AFM files for the reader and ingest tests.

AFMReader's source distribution (LGPL-3.0) carries real .gwy, .ibw, .spm and .jpk maps
under ``tests/resources/``. They are fetched at test time with pip into a cache outside
the repository (``$MCSIM_TEST_DATA`` or ``~/.cache/mcsim-test-data``) and never
committed. Nanosurf's NSFopen package (MIT, a test dependency) ships real .nid maps.
"""

import csv
import importlib.util
import io
import json
import os
import subprocess
import sys
import tarfile
from pathlib import Path

import pytest

try:
    from _pytest.approx import ApproxScalar
except ImportError:  # pytest < 8.4 kept it in python_api
    from _pytest.python_api import ApproxScalar

# pytest.approx(x, rel=r) also accepts anything within an absolute 1e-12 unless abs= is
# given: in SI units that floor is most of the value (1e-9 m, 1e-6 N, 1e-19 J), so
# approx(1.6e-19, rel=1e-15) would accept 0. Every tolerance here states its own scale:
# no floor (a comparison with 0 gives its abs= itself). Checked, since the default is
# pytest's class attribute, not an API: a pytest that ignores it fails here, loudly.
ApproxScalar.DEFAULT_ABSOLUTE_TOLERANCE = 0.0
assert 0.0 != pytest.approx(1.6e-19, rel=1e-15), "pytest.approx keeps an absolute floor"

AFMREADER = "afmreader-0.0.7"
#: The files the tests use, and the licence that travels with them.
AFM_FILES = ("sample_0.gwy", "sample_0.ibw")
_OFFLINE = (
    "NewConnectionError",
    "Failed to establish a new connection",
    "Temporary failure in name resolution",
    "Name or service not known",
    "Network is unreachable",
    "Could not fetch URL",
    "ConnectTimeout",
    "ReadTimeout",
    "No matching distribution found",
)


def _cache() -> Path:
    return Path(os.environ.get("MCSIM_TEST_DATA", Path.home() / ".cache" / "mcsim-test-data"))


@pytest.fixture(scope="session")
def afm_resources() -> Path:
    """Folder with AFMReader 0.0.7's real sample maps (downloaded once, then cached)."""
    cache = _cache()
    folder = cache / AFMREADER / "tests" / "resources"
    if all((folder / name).is_file() for name in AFM_FILES):
        return folder
    cache.mkdir(parents=True, exist_ok=True)
    sdist = cache / f"{AFMREADER}.tar.gz"
    if not sdist.is_file():
        spec = AFMREADER.replace("-", "==")
        done = subprocess.run(
            [sys.executable, "-m", "pip", "download", "--no-deps", "--no-binary", ":all:",
             spec, "-d", str(cache)],
            capture_output=True, text=True, timeout=600,
        )  # fmt: skip
        if done.returncode != 0:
            log = done.stdout + done.stderr
            if any(marker in log for marker in _OFFLINE):
                pytest.skip(f"cannot reach the package registry to fetch {spec} (real AFM files)")
            pytest.fail(f"pip download {spec} failed:\n{log[-2000:]}")
    wanted = {f"{AFMREADER}/tests/resources/{name}" for name in AFM_FILES}
    wanted.add(f"{AFMREADER}/COPYING")
    with tarfile.open(sdist) as tar:
        members = [m for m in tar.getmembers() if m.name in wanted]
        tar.extractall(cache, members=members, filter="data")
    return folder


@pytest.fixture(scope="session")
def nid_files() -> dict[str, Path]:
    """Real Nanosurf .nid maps shipped with NSFopen, by stem."""
    nsfopen = pytest.importorskip("NSFopen", reason="NSFopen ships the real .nid sample files")
    root = Path(nsfopen.__file__).parent / "example"
    return {p.stem: p for p in sorted(root.glob("*/*.nid"))}


def interrupt(proc, timeout: float = 60.0) -> tuple[int, str]:
    """Send Ctrl-C (SIGINT) to ``proc`` and return its exit code and stderr.

    If it has not exited after ``timeout`` seconds, SIGABRT makes Python's faulthandler
    (``PYTHONFAULTHANDLER=1`` in the child's environment) print every thread's stack,
    and the test fails with it: a hang is reported with where it hung.
    """
    import signal
    import subprocess

    import pytest

    proc.send_signal(signal.SIGINT)
    try:
        _, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.send_signal(signal.SIGABRT)
        _, err = proc.communicate(timeout=30)
        pytest.fail(f"no exit {timeout:g} s after SIGINT; stacks:\n{err}")
    return proc.returncode, err or ""


@pytest.fixture(scope="session")
def law_set_cache(tmp_path_factory) -> str:
    """A throw-away kernel cache (``MCSIM_CACHE_DIR``) for the test-only law sets, never
    the user's; one for the session, so that a kernel compiled once is found on disk
    again after a test has cleared the in-process cache."""
    return str(tmp_path_factory.mktemp("law-set-cache"))


@pytest.fixture(scope="session")
def long_run_reference():
    """The uninterrupted ``mcsim simulate --surface smooth --h=2:-1:7 --area 1e-8
    --realizations 500 --seed 3`` (a ~4 s run that the Ctrl-C and SIGKILL tests interrupt
    and resume), computed once for the session."""
    import numpy as np

    from mcsim.model.presets import MATERIALS, SURFACES
    from mcsim.studies.simulation import simulate

    h = np.linspace(2, -1, 7)
    return simulate(SURFACES["smooth"], MATERIALS["silicon"], h, 1e-8, realizations=500, seed=3)


@pytest.fixture(scope="session")
def dask_local_client():
    """One local Dask cluster of two single-threaded worker processes for the whole session
    (starting one costs ~10 s on two cores), as ``mcsim.engine.cluster.dask_client("local")`` makes."""
    pytest.importorskip("distributed", reason="Dask (extra 'dask') not installed")
    from mcsim.engine.cluster import dask_client

    with dask_client("local", workers=2) as client:
        yield client


class CudaChecks:
    """``python tests/cuda_checks.py ARGV`` (see there) running in a process of its own,
    its output in ``folder``; :meth:`result` waits for it and returns its JSON."""

    def __init__(self, simulator: bool, folder: Path, *argv: str):
        env = dict(os.environ)
        env.pop("NUMBA_ENABLE_CUDASIM", None)
        if simulator:
            env["NUMBA_ENABLE_CUDASIM"] = "1"
        self.out, self.err = folder / "stdout.txt", folder / "stderr.txt"
        script = Path(__file__).with_name("cuda_checks.py")
        with open(self.out, "w") as out, open(self.err, "w") as err:
            self.proc = subprocess.Popen([sys.executable, str(script), *argv, str(folder)],
                                         env=env, stdout=out, stderr=err, text=True)  # fmt: skip

    def result(self, timeout: float = 900) -> dict:
        code = self.proc.wait(timeout=timeout)
        assert code == 0, self.err.read_text()[-3000:]
        return json.loads(self.out.read_text().strip().splitlines()[-1])

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()


def _runs_the_simulator_checks(item) -> bool:
    callspec = getattr(item, "callspec", None)
    return callspec is not None and callspec.params.get("checks") == "simulator"


@pytest.fixture(scope="session", autouse=True)
def cuda_simulator_checks(request, tmp_path_factory):
    """tests/cuda_checks.py under numba's CUDA simulator, started in the background as
    the session starts when test_cuda.py's simulator checks are selected (else None).

    The simulator runs each CUDA thread as a Python thread: ~35 s on one core, which
    the other tests (mostly on one core) leave free; the checks share nothing with
    them (their own process and folder), and test_cuda.py waits for the result.
    """
    if importlib.util.find_spec("numba_cuda") is None or not any(
        _runs_the_simulator_checks(item) for item in request.session.items
    ):
        yield None
        return
    checks = CudaChecks(True, tmp_path_factory.mktemp("cuda-simulator"), "300", "500,200")
    yield checks
    checks.stop()  # only if the tests that wait for it did not run


def run_cli(capsys, *argv):
    """``mcsim ARGV`` in this process (arguments as strings): exit code, stdout, stderr."""
    from mcsim.cli.main import main

    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def rows_of(out: str) -> list[dict]:
    """The rows of CSV text."""
    return list(csv.DictReader(io.StringIO(out)))


def pytest_collection_modifyitems(items):
    """The slow tests first (stable order otherwise): ``make test`` spreads the suite over two
    workers, and the runs of the README's and the guide's pages as written (one test per
    page) then start at once on both, spread by worksteal, instead of starting last and
    running alone."""
    items.sort(key=lambda item: item.get_closest_marker("slow") is None)

"""Shared fixtures: real AFM files for the reader and ingest tests.

AFMReader's source distribution (LGPL-3.0) carries real .gwy, .ibw, .spm and .jpk maps
under ``tests/resources/``. They are fetched at test time with pip into a cache outside
the repository (``$MCSIM_TEST_DATA`` or ``~/.cache/mcsim-test-data``) and never
committed. Nanosurf's NSFopen package (MIT, a test dependency) ships real .nid maps.
"""

import os
import subprocess
import sys
import tarfile
from pathlib import Path

import pytest

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
def long_run_reference():
    """The uninterrupted ``mcsim simulate --surface smooth --h=2:-1:7 --area 1e-8
    --realizations 500 --seed 3`` (a ~4 s run that the Ctrl-C and SIGKILL tests interrupt
    and resume), computed once for the session."""
    import numpy as np

    from mcsim.presets import MATERIALS, SURFACES
    from mcsim.simulation import simulate

    h = np.linspace(2, -1, 7)
    return simulate(SURFACES["smooth"], MATERIALS["silicon"], h, 1e-8, realizations=500, seed=3)


@pytest.fixture(scope="session")
def dask_local_client():
    """One local Dask cluster of two single-threaded worker processes for the whole session
    (starting one costs ~10 s on two cores), as ``mcsim.cluster.dask_client("local")`` makes."""
    pytest.importorskip("distributed", reason="Dask (extra 'dask') not installed")
    from mcsim.cluster import dask_client

    with dask_client("local", workers=2) as client:
        yield client

"""Start-up of ``import mcsim`` and of the command line (issue 12, "The CPU command line").

Each test runs a fresh interpreter, so that what it loads is its own. No timings are
asserted: the tests pin down what the start-up does (which libraries it imports, how
the garbage collector treats its objects); docs/performance.md gives the seconds.
"""

import subprocess
import sys

#: Libraries a light command must not import (each costs 0.1–1 s to load).
HEAVY = ("numpy", "scipy", "pandas", "matplotlib", "xarray", "dask", "h5py", "numba", "tqdm")

_LOADED = "sorted({m.split('.')[0] for m in sys.modules} & set(HEAVY))"


def _python(code: str, tmp_path) -> str:
    done = subprocess.run(
        [sys.executable, "-c", f"HEAVY = {HEAVY!r}\n{code}"],
        capture_output=True, text=True, cwd=tmp_path, timeout=300,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    return done.stdout.strip()


def test_import_mcsim_loads_no_numerical_library(tmp_path):
    assert _python(f"import sys, mcsim\nprint({_LOADED})", tmp_path) == "[]"


def test_help_loads_no_numerical_library(tmp_path):
    code = (
        "import contextlib, io, sys\nfrom mcsim.cli.main import main\n"
        "for argv in (['--help'], ['simulate', '--help'], ['--version']):\n"
        "    with contextlib.redirect_stdout(io.StringIO()):\n"
        "        assert main(argv) == 0\n"
        f"print({_LOADED})"
    )
    assert _python(code, tmp_path) == "[]"


def test_simulate_loads_no_table_plotting_or_cluster_library(tmp_path):
    """A run needs NumPy, SciPy's special functions, numba and h5py; nothing else."""
    code = (
        "import sys\nfrom mcsim.cli.main import main\n"
        "assert main(['simulate', '--surface', 'smooth', '--area', '1um^2', '--h', '4:-1:5',"
        " '--seed', '1', '--out', 'run.h5', '--quiet']) == 0\n"
        f"print({_LOADED})"
    )
    assert _python(code, tmp_path) == "['h5py', 'numba', 'numpy', 'scipy']"


def test_command_runs_no_full_garbage_collection_and_leaves_nothing_to_traverse_at_exit(
    tmp_path,
):
    """The start-up's ~10⁵ long-lived objects are never traversed by a full collection
    of the cyclic garbage collector, neither while a run starts nor when it exits
    (:func:`mcsim.cli.main.console`): together ≈0.4 s of a ``simulate`` command."""
    code = (
        "import atexit, gc, sys\nfull = []\n"
        "gc.callbacks.append(lambda phase, info: full.append(info) if phase == 'start'"
        " and info['generation'] == 2 else None)\n"
        "atexit.register(lambda: print(len(full), gc.get_freeze_count() > 0))\n"
        "sys.argv = ['mcsim', 'simulate', '--surface', 'smooth', '--area', '1um^2',"
        " '--h', '4:-1:51', '--seed', '1', '--out', 'run.h5', '--quiet']\n"
        "from mcsim.cli.main import console\nconsole()\n"
    )
    assert _python(code, tmp_path) == "0 True"

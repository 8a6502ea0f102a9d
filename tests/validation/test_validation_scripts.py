"""The validation scripts judge their own criteria: each ``--quick`` run exits 0 with PASS lines.

Every script in ``validation/`` prints one ``PASS``/``FAIL`` line per criterion (the
measured value and its bound) and exits with status 1 on a FAIL (``validation/README.md``).
Here each runs with ``--quick`` (a smaller run that still judges its criteria) and
``--out`` in a temporary folder. Not run here: ``benchmark.py``, ``sweep_benchmark.py`` and
``scaling.py`` (their ``--quick`` runs take 20–80 s of timing work) and ``benchmark_cuda.py``
(needs a GPU); ``memory.py --quick`` judges memory and z-scores, never time.

A script runs as ``python validation/SCRIPT.py`` runs it (``__main__``, its folder first on
``sys.path``, its exit status from ``sys.exit``) but in the test's own process, which has
already imported NumPy, SciPy and mcsim and loaded the compiled kernels: a new interpreter
would spend seconds on that for each script. ``memory.py`` measures the peak memory of the
child processes it starts, not its own. A script that starts a process pool
(``OWN_PROCESS``) runs in a process of its own: its workers would be forks of this one.
"""

import runpy
import subprocess
import sys
from pathlib import Path

import pytest

VALIDATION = Path(__file__).resolve().parents[2] / "validation"
SCRIPTS = (
    "adhesion_table",
    "convergence",
    "environment",
    "exact_pstick",
    "finite_patch",
    "fuller_tabor",
    "gw_moments",
    "humid_pads",
    "md_sphere",
    "pad_friction",
    "memory",
    "pad_variation",
    "radius_height",
    "stiction_model",
    "tail_benchmark",
)
#: Scripts whose --quick run starts a process pool (concurrent.futures.ProcessPoolExecutor), or
#: measures its child processes' peak memory (RUSAGE_CHILDREN is the largest of every child
#: the process ever waited for: in a test worker, earlier tests' children too).
OWN_PROCESS = ("tail_benchmark", "memory")


def run_as_main(argv: list[str], monkeypatch, capsys) -> tuple[int, str, str]:
    """``python ARGV`` in this process: its exit status, standard output and error."""
    monkeypatch.syspath_prepend(str(Path(argv[0]).parent))
    monkeypatch.setattr(sys, "argv", argv)
    try:
        runpy.run_path(argv[0], run_name="__main__")
        code = 0
    except SystemExit as stop:
        code = stop.code if isinstance(stop.code, int) else int(stop.code is not None)
    finally:
        if "matplotlib.pyplot" in sys.modules:  # the script's figures, as its exit closes them
            sys.modules["matplotlib.pyplot"].close("all")
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("script", SCRIPTS)
def test_quick_run_passes_its_criteria(script, tmp_path, monkeypatch, capsys):
    argv = [str(VALIDATION / f"{script}.py"), "--quick", "--out", str(tmp_path)]
    if script in OWN_PROCESS:
        done = subprocess.run([sys.executable, *argv], capture_output=True, text=True, timeout=600)
        code, out, err = done.returncode, done.stdout, done.stderr
    else:
        code, out, err = run_as_main(argv, monkeypatch, capsys)
    report = f"{out[-4000:]}\n{err[-4000:]}"
    assert code == 0, report
    lines = out.splitlines()
    assert any(line.startswith("PASS: ") for line in lines), report
    assert not any(line.startswith("FAIL: ") for line in lines), report


def test_a_failed_criterion_sets_exit_status_1(monkeypatch):
    monkeypatch.syspath_prepend(str(VALIDATION))
    from reporting import Checks

    checks = Checks()
    checks.at_most("within", 1.0, 2.0)
    checks.at_most("NaN is no pass", float("nan"), 2.0)
    checks.at_least("below", 1.0, 2.0)
    assert [line.split(":")[0] for line in checks.lines] == ["PASS", "FAIL", "FAIL"]
    with pytest.raises(SystemExit) as stop:
        checks.exit()
    assert stop.value.code == 1


def test_an_unjudged_timing_criterion_cannot_fail(monkeypatch):
    monkeypatch.syspath_prepend(str(VALIDATION))
    from reporting import Checks

    checks = Checks(timing_judged=False)
    checks.at_least("speed-up", 1.0, 10.0, timing=True)
    assert checks.lines[0].startswith("INFO")
    with pytest.raises(SystemExit) as stop:
        checks.exit()
    assert stop.value.code == 0

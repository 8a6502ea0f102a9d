"""The validation scripts judge their own criteria: each ``--quick`` run exits 0 with PASS lines.

Every script in ``validation/`` prints one ``PASS``/``FAIL`` line per criterion (the
measured value and its bound) and exits with status 1 on a FAIL (``validation/README.md``).
Here each runs with ``--quick`` (a smaller run that still judges its criteria) and
``--out`` in a temporary folder. Not run here: ``benchmark.py``, ``sweep_benchmark.py`` and
``scaling.py`` (their ``--quick`` runs take 20–80 s of timing work) and ``benchmark_cuda.py``
(needs a GPU); ``memory.py --quick`` judges memory and z-scores, never time.
"""

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
    "pad_friction",
    "memory",
    "pad_variation",
    "radius_height",
    "stiction_model",
    "tail_benchmark",
)


@pytest.mark.parametrize("script", SCRIPTS)
def test_quick_run_passes_its_criteria(script, tmp_path):
    cmd = [sys.executable, str(VALIDATION / f"{script}.py"), "--quick", "--out", str(tmp_path)]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    report = f"{done.stdout[-4000:]}\n{done.stderr[-4000:]}"
    assert done.returncode == 0, report
    lines = done.stdout.splitlines()
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

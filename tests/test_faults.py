"""Fault tests: SIGKILL at seeded moments, a full disk, two writers on one path.

Each runs `mcsim simulate` in a subprocess and checks that the output path holds
nothing, a resumable incomplete run or a complete run — never an unreadable file —
and that resuming reproduces the uninterrupted numbers exactly.
"""

import os
import resource
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from conftest import interrupt

from mcsim import RunFileError
from mcsim.cli import main
from mcsim.presets import MATERIALS, SURFACES
from mcsim.runfile import read_run, read_state
from mcsim.simulation import simulate

EXE = os.path.join(os.path.dirname(sys.executable), "mcsim")
H = np.linspace(2, -1, 7)
ARGS = ["simulate", "--surface", "smooth", "--h=2:-1:7", "--area", "1e-8", "--realizations", "500",
        "--seed", "3", "--workers", "1", "--quiet"]  # fmt: skip


#: A run that takes no time.
SMALL = ["simulate", "--surface", "rough", "--area", "1e-10", "--h=0", "--quiet"]


@pytest.fixture(scope="module")
def reference():
    """The uninterrupted run."""
    return simulate(SURFACES["smooth"], MATERIALS["silicon"], H, 1e-8, realizations=500, seed=3)


def start_and_wait_for_progress(out):
    """Start a ~4 s run that checkpoints every 20 ms; return once its first checkpoint exists."""
    env = {**os.environ, "PYTHONFAULTHANDLER": "1"}
    proc = subprocess.Popen([EXE, *ARGS, "--out", str(out), "--checkpoint-every", "0.02"],
                            stderr=subprocess.PIPE, text=True, env=env)  # fmt: skip
    deadline = time.monotonic() + 30
    while not out.exists() and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.01)
    assert proc.poll() is None, "the run ended before its first checkpoint"
    return proc


@pytest.mark.parametrize("moment", np.random.default_rng(20261122).uniform(0.0, 2.0, 3).round(2))
def test_sigkill_leaves_nothing_or_a_readable_run_and_resume_completes_it(
    tmp_path, reference, moment
):
    """Killed ``moment`` seconds after its first checkpoint."""
    out = tmp_path / "t.h5"
    proc = start_and_wait_for_progress(out)
    time.sleep(moment)
    proc.kill()
    proc.wait()
    if out.exists():
        state, _ = read_state(out)  # readable: never a torn file
        args = [*ARGS, "--out", str(out), "--resume"] if not state.complete else None
    else:
        args = [*ARGS, "--out", str(out)]
    if args is not None:
        assert main(args) == 0
    run = read_run(out)
    np.testing.assert_array_equal(run.sums, reference.sums)
    np.testing.assert_array_equal(run.summary.mean["mu"], reference.summary.mean["mu"])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.h5"], "no lock or temporary file left"


def _limit_file_size():
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # get EFBIG instead of being killed
    resource.setrlimit(resource.RLIMIT_FSIZE, (40_000, 40_000))


def test_full_disk_gives_a_clear_error_and_leaves_earlier_runs_untouched(tmp_path):
    earlier = tmp_path / "earlier.h5"
    assert main([*SMALL, "--out", str(earlier)]) == 0
    before = earlier.read_bytes()
    out = tmp_path / "big.h5"  # ~100 kB of results: past the 40 kB limit
    done = subprocess.run(
        [EXE, *ARGS, "--out", str(out)], capture_output=True, text=True, preexec_fn=_limit_file_size
    )
    assert done.returncode == 2, done.stderr
    assert done.stderr.startswith(
        f"mcsim: error: {out}: cannot write the run file (File too large)"
    )
    assert done.stderr.count("\n") == 1 and "Traceback" not in done.stderr
    assert earlier.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["earlier.h5"]


def test_two_writers_on_one_path_one_wins_the_other_fails_cleanly(tmp_path, reference):
    out = tmp_path / "t.h5"
    procs = [
        subprocess.Popen([EXE, *ARGS, "--out", str(out)], stderr=subprocess.PIPE, text=True)
        for _ in range(2)
    ]
    results = [(p.wait(timeout=120), p.stderr.read()) for p in procs]
    codes = sorted(code for code, _ in results)
    assert codes == [0, 2], results
    err = next(e for code, e in results if code == 2)
    assert "another mcsim process" in err or "file exists" in err
    np.testing.assert_array_equal(read_run(out).sums, reference.sums)


def test_a_lock_left_by_a_killed_writer_is_taken_over(tmp_path):
    out = tmp_path / "t.h5"
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    (tmp_path / "t.h5.lock").write_text(f"{os.uname().nodename} {dead.pid}")
    (tmp_path / ".t.h5.abc.tmp").write_bytes(b"half a file")
    assert main([*SMALL, "--out", str(out)]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.h5"]


def test_a_live_writer_keeps_its_lock(tmp_path, capsys):
    out = tmp_path / "t.h5"
    (tmp_path / "t.h5.lock").write_text(f"{os.uname().nodename} {os.getpid()}")
    assert (
        main(["simulate", "--surface", "rough", "--area", "1e-10", "--h=0", "--out", str(out)]) == 2
    )
    assert "another mcsim process" in capsys.readouterr().err
    assert not out.exists()


def test_resume_refuses_other_arguments(tmp_path, capsys):
    out = tmp_path / "t.h5"
    state_args = [*ARGS, "--out", str(out)]
    proc = start_and_wait_for_progress(out)
    code, err = interrupt(proc)
    assert code == 130, err
    assert not read_state(out)[0].complete
    changed = [a if a != "1e-8" else "2e-8" for a in state_args]
    assert main([*changed, "--resume"]) == 2
    err = capsys.readouterr().err
    assert "cannot resume" in err and "area differ(s) from the recorded run" in err
    with pytest.raises(RunFileError, match="incomplete run"):
        read_run(out)

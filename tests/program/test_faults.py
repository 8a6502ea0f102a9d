"""Fault tests: SIGKILL at seeded moments, a full disk, concurrent writers on one path,
interrupted --overwrite and --resume of every surface kind.

Each runs `mcsim simulate` and checks that the output path holds nothing, the earlier
complete run or the new complete run — never an unreadable or incomplete file — that
the checkpoint beside it (``<stem>.partial.h5``) is readable, and that resuming
reproduces the uninterrupted numbers exactly.
"""

import contextlib
import fcntl
import os
import re
import resource
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from conftest import interrupt

from mcsim import RunFileError
from mcsim.cli.main import main
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.store.runfile import read_run, read_state
from mcsim.studies.simulation import simulate


def checkpoint_path(out):
    """The documented checkpoint beside a run file: ``<stem>.partial<suffix>``."""
    return out.with_name(f"{out.stem}.partial{out.suffix}")


EXE = os.path.join(os.path.dirname(sys.executable), "mcsim")
H = np.linspace(2, -1, 7)
ARGS = ["simulate", "--surface", "smooth", "--h=2:-1:7", "--area", "1e-8", "--realizations", "500",
        "--seed", "3", "--workers", "1", "--quiet"]  # fmt: skip


#: A run that takes no time.
SMALL = ["simulate", "--surface", "rough", "--area", "1e-10", "--h=0", "--quiet"]
#: ARGS on a tenth of the area: the same run file and the same 500 tasks (one block each,
#: an interruption check between any two), a tenth of the work.
SHORT = [a if a != "1e-8" else "1e-9" for a in ARGS]


@pytest.fixture(scope="module")
def short_reference():
    """The uninterrupted run of SHORT."""
    return simulate(SURFACES["smooth"], MATERIALS["silicon"], H, 1e-9, realizations=500, seed=3)


def start_and_wait_for_progress(out):
    """Start a ~4 s run that checkpoints every 20 ms; return once its first checkpoint exists."""
    env = {**os.environ, "PYTHONFAULTHANDLER": "1"}
    partial = checkpoint_path(out)
    proc = subprocess.Popen([sys.executable, "-m", "mcsim", *ARGS, "--out", str(out),
                             "--checkpoint-every", "0.02"],
                            stderr=subprocess.PIPE, text=True, env=env)  # fmt: skip
    deadline = time.monotonic() + 60
    while not partial.exists() and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.01)
    assert proc.poll() is None, "the run ended before its first checkpoint"
    return proc


@pytest.mark.parametrize("moment", np.random.default_rng(20261122).uniform(0.0, 2.0, 3).round(2))
def test_sigkill_leaves_nothing_or_a_complete_run_and_resume_completes_it(
    tmp_path, long_run_reference, moment
):
    """Killed ``moment`` seconds after its first checkpoint; then the same command with
    --resume (what a batch script does) ends with the uninterrupted numbers."""
    out = tmp_path / "t.h5"
    proc = start_and_wait_for_progress(out)
    time.sleep(moment)
    proc.kill()
    proc.wait()
    if out.exists():
        assert read_state(out)[0].complete, "the path never holds an incomplete run"
    else:
        # Readable (never torn), and never a complete run (it may have every block done).
        assert not read_state(checkpoint_path(out))[1]["complete"]
        assert main([*ARGS, "--out", str(out), "--resume"]) == 0
    run = read_run(out)
    reference = long_run_reference  # the uninterrupted run of ARGS
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
    out = tmp_path / "big.h5"  # ~500 kB of results: past the 40 kB limit
    done = subprocess.run(
        [EXE, *SHORT, "--out", str(out)],
        capture_output=True,
        text=True,
        preexec_fn=_limit_file_size,
    )
    assert done.returncode == 2, done.stderr
    assert re.match(  # the final write, or a checkpoint (after 10 s on a slow machine)
        rf"mcsim: error: {tmp_path}/big(\.partial)?\.h5: cannot write the run file \(File too large\)\n$",
        done.stderr,
    ), done.stderr
    assert earlier.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["earlier.h5"]


@contextlib.contextmanager
def small_file_system(path, size):
    """A tmpfs of ``size`` mounted on ``path`` (needs root), or a skip."""
    path.mkdir()
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(path)],
                          capture_output=True, text=True)  # fmt: skip
    if done.returncode != 0:
        pytest.skip(f"cannot mount a small tmpfs for a real full disk: {done.stderr.strip()}")
    try:
        yield path
    finally:
        subprocess.run(["umount", str(path)], check=True)


def test_a_real_full_disk_gives_one_line_and_no_crash_and_leaves_earlier_runs_untouched(
    tmp_path,
):
    """ENOSPC on a 200 kB tmpfs: the HDF5 library used to print a two-line error and the
    process then segfaulted."""
    with small_file_system(tmp_path / "disk", "200k") as disk:
        earlier = disk / "earlier.h5"
        assert main([*SMALL, "--out", str(earlier)]) == 0
        before = earlier.read_bytes()
        out = disk / "big.h5"  # ~1.5 MB of results
        big = [a if a != "500" else "1500" for a in SHORT]
        done = subprocess.run([sys.executable, "-m", "mcsim", *big, "--area", "1e-10", "--out", str(out)],
                              capture_output=True, text=True)  # fmt: skip
        assert done.returncode == 2, done.stderr
        assert re.fullmatch(
            rf"mcsim: error: {disk}/big(\.partial)?\.h5: cannot write the run file "
            r"\(No space left on device\)\n",
            done.stderr,
        ), done.stderr
        assert earlier.read_bytes() == before
        assert sorted(p.name for p in disk.iterdir()) == ["earlier.h5"]


WRITER = [sys.executable, "-m", "mcsim", *SMALL[:-1], "--realizations", "20", "--seed", "1"]


@pytest.mark.parametrize("stale", [False, True], ids=["no-lock-file", "stale-lock-file"])
def test_concurrent_writers_on_one_path_exactly_one_wins_the_others_fail_cleanly(tmp_path, stale):
    """Four writers started together (with a lock file left by a killed process, or
    none): one writes the run, each other one prints one line and exits 2."""
    out = tmp_path / "t.h5"
    if stale:
        dead = subprocess.Popen([sys.executable, "-c", "pass"])
        dead.wait()
        (tmp_path / "t.h5.lock").write_text(f"{os.uname().nodename} {dead.pid}")
    procs = [
        subprocess.Popen([*WRITER, "--out", str(out)], stderr=subprocess.PIPE, text=True)
        for _ in range(4)
    ]
    results = [(p.wait(timeout=300), p.stderr.read()) for p in procs]
    assert sorted(code for code, _ in results) == [0, 2, 2, 2], results
    for code, err in results:
        if code == 2:
            assert err.count("\n") == 1 and "Traceback" not in err, err
            assert "another mcsim process" in err or "file exists" in err, err
    assert read_run(out).complete
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.h5"]


def test_a_lock_left_by_a_killed_writer_is_free(tmp_path):
    out = tmp_path / "t.h5"
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    (tmp_path / "t.h5.lock").write_text(f"{os.uname().nodename} {dead.pid}")
    (tmp_path / ".t.h5.abc.tmp").write_bytes(b"half a file")
    assert main([*SMALL, "--out", str(out)]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.h5"]


def test_a_lock_file_naming_a_live_unrelated_process_is_free(tmp_path):
    """After a kill, the dead writer's pid may be reused by any process: only a held lock
    counts, not the pid written in the file (which used to block the path forever)."""
    out = tmp_path / "t.h5"
    (tmp_path / "t.h5.lock").write_text(f"{os.uname().nodename} {os.getpid()}")
    assert main([*SMALL, "--out", str(out)]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.h5"]


def test_a_live_writer_keeps_its_lock_and_its_lock_file(tmp_path, capsys):
    out = tmp_path / "t.h5"
    lock_file = tmp_path / "t.h5.lock"
    with open(lock_file, "w") as held:
        held.write("otherhost 12345")
        held.flush()
        fcntl.flock(held, fcntl.LOCK_EX)
        assert main([*SMALL, "--out", str(out)]) == 2
        assert lock_file.exists(), "never delete a lock file another process holds"
    err = capsys.readouterr().err
    assert "another mcsim process (otherhost pid 12345)" in err and err.count("\n") == 1
    assert not out.exists()


def test_resume_refuses_other_arguments(tmp_path, capsys):
    out = tmp_path / "t.h5"
    state_args = [*ARGS, "--out", str(out)]
    proc = start_and_wait_for_progress(out)
    code, err = interrupt(proc)
    assert code == 130, err
    assert not out.exists() and not read_state(checkpoint_path(out))[0].complete
    changed = [a if a != "1e-8" else "2e-8" for a in state_args]
    assert main([*changed, "--resume"]) == 2
    err = capsys.readouterr().err
    assert err == (
        f"mcsim: error: cannot resume {out}: its checkpoint t.partial.h5 holds a run "
        "with a different area (file: 1e-08, asked: 2e-08)\n"
    )
    with pytest.raises(RunFileError, match="incomplete run"):
        read_run(checkpoint_path(out))


def test_resume_with_nothing_to_resume_starts_from_the_beginning_and_says_so(
    tmp_path, capsys, short_reference
):
    out = tmp_path / "t.h5"
    assert main([*SHORT, "--out", str(out), "--resume"]) == 0
    err = capsys.readouterr().err
    assert err == (
        f"mcsim: {out}: nothing to resume (no checkpoint t.partial.h5): starting the run "
        "from the beginning\n"
    )
    np.testing.assert_array_equal(read_run(out).sums, short_reference.sums)


def interrupt_after(monkeypatch, calls: int) -> None:
    """Make the run's interruption check see a Ctrl-C at its ``calls``-th call."""
    import mcsim.engine.interrupt
    from mcsim.engine.interrupt import Interrupted

    count = iter(range(calls, 0, -1))

    def check():
        if next(count, 0) == 1:
            raise Interrupted(signal.SIGINT)

    monkeypatch.setattr(mcsim.engine.interrupt, "check", check)


def test_an_interrupted_overwrite_keeps_the_earlier_run_until_the_new_one_completes(
    tmp_path, monkeypatch, capsys, short_reference
):
    out = tmp_path / "t.h5"
    assert main([*SMALL, "--out", str(out)]) == 0
    before = out.read_bytes()
    args = [*SHORT, "--out", str(out), "--overwrite"]
    interrupt_after(monkeypatch, 5)
    assert main(args) == 130
    assert out.read_bytes() == before, "the complete earlier run survives the interruption"
    assert f"progress saved in {checkpoint_path(out)}" in capsys.readouterr().err
    monkeypatch.undo()
    assert not read_state(checkpoint_path(out))[0].complete
    assert main([*SHORT, "--out", str(out), "--resume"]) == 2  # replacing needs --overwrite
    assert "already holds a finished run with a different surface" in capsys.readouterr().err
    assert out.read_bytes() == before
    assert main([*args, "--resume"]) == 0
    np.testing.assert_array_equal(read_run(out).sums, short_reference.sums)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.h5"]


HIST_ROWS = "z [nm], count\n" + "".join(
    f"{z:g}, {c}\n"
    for z, c in zip(np.arange(-3, 3.5, 0.5), [1, 2, 6, 14, 27, 40, 45, 38, 25, 12, 6, 3, 1])
)
SURFACES_TOML = {
    "gaussian": 'sigma = "1.4 nm"\nR = "1.7 um"\neta = "17 um^-2"\n',
    "inline-histogram": 'R = "1.7 um"\neta = "17 um^-2"\n[surface.heights]\nunit = "nm"\n'
    "edges = [-3, -2, -1, 0, 1, 2, 3, 4]\ncounts = [2, 10, 30, 35, 15, 6, 2]\n",
    "histogram-file": 'R = "1.7 um"\neta = "17 um^-2"\nheights = "hist.csv"\n',
}


@pytest.mark.parametrize("kind", SURFACES_TOML)
def test_every_surface_kind_resumes_bit_identically_after_an_interruption(
    tmp_path, monkeypatch, kind
):
    """Histogram surfaces used to fail to resume (``Empirical is immutable``, from a deepcopy)."""
    (tmp_path / "hist.csv").write_text(HIST_ROWS)
    surface = tmp_path / "s.toml"
    surface.write_text(f'[surface]\nname = "{kind}"\n{SURFACES_TOML[kind]}')
    args = ["simulate", "--surface", str(surface), "--h=2:-1:4", "--area", "1e-8", "--seed", "5",
            "--realizations", "4", "--chunk-size", "65536", "--workers", "2", "--quiet"]  # fmt: skip
    assert main([*args, "--out", str(tmp_path / "ref.h5")]) == 0
    out = tmp_path / "t.h5"
    interrupt_after(monkeypatch, 5)
    assert main([*args, "--out", str(out)]) == 130
    monkeypatch.undo()
    state = read_state(checkpoint_path(out))[0]
    assert 0 < state.done_blocks.sum() < state.n_blocks.sum()
    assert main([*args, "--out", str(out), "--resume"]) == 0
    ref, run = read_run(tmp_path / "ref.h5"), read_run(out)
    for q in run.realizations:
        np.testing.assert_array_equal(run.realizations[q], ref.realizations[q], err_msg=q)
    np.testing.assert_array_equal(run.sums, ref.sums)


def test_the_first_checkpoint_comes_early_then_every_checkpoint_every(monkeypatch):
    """A kill after the first tasks of a run with ``--checkpoint-every 3600`` used to lose
    everything: the first checkpoint now follows FIRST_CHECKPOINT seconds of work."""
    import mcsim.engine.montecarlo as mc

    monkeypatch.setattr(mc, "FIRST_CHECKPOINT", 0.0)
    s = mc.MonteCarloSpec(SURFACES["smooth"], MATERIALS["silicon"], H, 3e-8, 2, 1)
    saved = []
    mc.run_sums(s, workers=1, chunk_size=mc.BLOCK, checkpoint_every=3600,
                checkpoint=lambda st: saved.append(st.done_blocks.sum()))  # fmt: skip
    assert saved == [1], "one checkpoint, after the first task; the next one is an hour away"


def test_tasks_are_generated_lazily_so_memory_stays_flat_at_any_patch_size():
    """A 1 m^2 patch (1.7e13 summits) built a list of tens of millions of tasks (5 GB)."""
    from collections.abc import Iterator

    from mcsim.engine.montecarlo import PatchPlan, make_tasks

    tasks = make_tasks([PatchPlan(10**18, 10**18)], chunk_size=1 << 18)
    assert isinstance(tasks, Iterator)
    assert next(tasks).stop == 4


def test_an_area_beyond_the_samplers_range_is_a_one_line_error(tmp_path, capsys):
    """--area 1e6 (m^2) used to end in numpy's 'lam value too large' traceback."""
    assert main([*SMALL, "--area", "1e6", "--out", str(tmp_path / "x.h5")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    assert "area = 1e+06 m^2 holds E[N] = eta*area = 1.47e+19 summits per patch" in err
    assert "(allowed: at most 1e+18)" in err


def test_a_huge_run_prints_an_estimate_and_stops_promptly_on_ctrl_c(tmp_path):
    """--area 1 m^2 (1.7e13 summits): an estimate on stderr before any work, flat memory,
    and Ctrl-C honoured (it was ignored for over 15 minutes)."""
    out = tmp_path / "t.h5"
    env = {**os.environ, "PYTHONFAULTHANDLER": "1"}
    proc = subprocess.Popen([sys.executable, "-m", "mcsim", "simulate", "--surface", "smooth",
                             "--h=2", "--area", "1", "--seed", "1", "--out", str(out)],
                            stderr=subprocess.PIPE, text=True, env=env)  # fmt: skip
    first = proc.stderr.readline()
    assert first.startswith(
        "mcsim: long run: 1.7e+13 summits, 3.87e+11 contacting (summit, h) pairs"
    )
    time.sleep(1)
    code, err = interrupt(proc)
    assert code == 130, err
    assert err.startswith("mcsim: interrupted (SIGINT)") and err.count("\n") == 1, err
    assert not out.exists()

"""Signal stress test: SIGINT bursts, SIGTERM and SIGKILL at seeded moments, during runs
and during resumes, on a Gaussian and a measured-histogram surface.

Every step runs ``python -m mcsim simulate`` in a subprocess and sends its signals at a
seeded moment after the run has taken its lock (its signal handling is then in place).
After each step: no hang (a stuck process is reported with every thread's stack),
the exit status of the first signal (130 for SIGINT, 143 for SIGTERM; 0 only if the
run had already completed), no traceback, one line on stderr, and no stray file (a
SIGKILL may leave its lock file and a temporary, which the next run clears). Finally
``--resume`` completes the run, bit-identical to an uninterrupted one.

``MCSIM_SIGNAL_CAMPAIGN=N`` runs N sequences per surface instead of 1 (a longer campaign,
with seeded random attacks after the first).
"""

import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from mcsim.store.runfile import read_run, read_state


def checkpoint_path(out):
    """The documented checkpoint beside a run file: ``<stem>.partial<suffix>``."""
    return out.with_name(f"{out.stem}.partial{out.suffix}")


SEQUENCES = int(os.environ.get("MCSIM_SIGNAL_CAMPAIGN", "1"))
SURFACE_TOML = {
    "gaussian": 'sigma = "1.4 nm"\nR = "1.7 um"\neta = "17 um^-2"\n',
    "histogram": 'R = "1.7 um"\neta = "17 um^-2"\n[surface.heights]\nunit = "nm"\n'
    "edges = [-3, -2, -1, 0, 1, 2, 3, 4]\ncounts = [2, 10, 30, 35, 15, 6, 2]\n",
}
#: A run of about a second on one core: 40 patches of ~34,000 summits, 7 separations.
RUN = ["simulate", "--h=2:-1:7", "--area", "2e-9", "--realizations", "40", "--seed", "11",
       "--chunk-size", "65536", "--checkpoint-every", "0.05", "--quiet"]  # fmt: skip
#: Signals of one burst. The exit status is that of the first signal handled: 130 or 143
#: (Python runs the handlers of signals pending together in signal-number order).
ATTACKS = {
    "sigint-burst": [signal.SIGINT] * 5,
    "sigterm": [signal.SIGTERM],
    "mixed-burst": [signal.SIGTERM, signal.SIGINT, signal.SIGTERM, signal.SIGINT],
    "sigkill": [signal.SIGKILL],
}


def run_step(cmd, folder, out, rng, name):
    """Start ``cmd``, wait for its lock, attack it at a seeded moment; return (attack, code, err)."""
    env = {**os.environ, "PYTHONFAULTHANDLER": "1"}
    proc = subprocess.Popen(cmd, stderr=subprocess.PIPE, text=True, env=env, cwd=folder)
    lock = folder / f"{out.name}.lock"
    deadline = time.monotonic() + 60
    while proc.poll() is None and time.monotonic() < deadline:  # until it holds the lock
        try:
            if lock.read_text().endswith(f" {proc.pid}"):
                break
        except FileNotFoundError:
            pass
        time.sleep(0.002)
    signals = ATTACKS[name]
    time.sleep(rng.uniform(0, 1.2))
    for s in signals:
        if proc.poll() is None:
            proc.send_signal(s)
        time.sleep(rng.uniform(0, 0.003))  # a burst: several within milliseconds
    try:
        _, err = proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        proc.send_signal(signal.SIGABRT)
        _, err = proc.communicate(timeout=30)
        pytest.fail(f"{name}: no exit 60 s after the signals; stacks:\n{err}")
    return name, proc.returncode, err


def check_step(name, code, err, folder, out):
    complete = out.exists() and read_state(out)[0].complete
    statuses = {-s if s == signal.SIGKILL else 128 + s for s in ATTACKS[name]}
    assert code in statuses or (code == 0 and complete), (name, code, err)
    if code == -signal.SIGKILL:
        return
    assert "Traceback" not in err, err
    assert all(line.startswith("mcsim: ") for line in err.splitlines()), err
    if code > 0:
        assert err.splitlines()[-1].startswith(
            f"mcsim: interrupted ({signal.Signals(code - 128).name})"
        )
    names = {p.name for p in folder.iterdir()} - {"s.toml"}
    assert names <= {out.name, checkpoint_path(out).name}, names
    assert not (out.exists() and checkpoint_path(out).exists()), names
    if checkpoint_path(out).exists():
        assert not read_state(checkpoint_path(out))[1]["complete"]  # all blocks may be done


@pytest.fixture(scope="module")
def references(tmp_path_factory):
    """Uninterrupted runs, per surface kind (computed once)."""
    from mcsim.model.presets import MATERIALS
    from mcsim.store.config import load_surface
    from mcsim.studies.simulation import simulate

    folder = tmp_path_factory.mktemp("references")
    cached = {}

    def reference(kind):
        if kind not in cached:
            (folder / f"{kind}.toml").write_text(
                f'[surface]\nname = "{kind}"\n{SURFACE_TOML[kind]}'
            )
            surface = load_surface(str(folder / f"{kind}.toml"))
            cached[kind] = simulate(surface, MATERIALS["silicon"], np.linspace(2, -1, 7), 2e-9,
                                    realizations=40, seed=11)  # fmt: skip
        return cached[kind]

    return reference


@pytest.mark.parametrize("sequence", range(SEQUENCES))
@pytest.mark.parametrize("kind", sorted(SURFACE_TOML))
def test_signals_at_any_moment_never_hang_or_lose_work_and_resume_bit_identically(
    tmp_path, references, kind, sequence
):
    """A run and then its resume attacked in turn, then resumed to the end."""
    rng = np.random.default_rng([20261123, sequence, len(kind)])
    names = sorted(ATTACKS)  # the first sequences of the two surfaces cover every attack
    if sequence == 0:
        attacks = names[:2] if kind == "gaussian" else names[2:]
    else:
        attacks = list(rng.choice(names, 2))
    surface = tmp_path / "s.toml"
    surface.write_text(f'[surface]\nname = "{kind}"\n{SURFACE_TOML[kind]}')
    out = tmp_path / "t.h5"
    cmd = [sys.executable, "-m", "mcsim", *RUN, "--surface", surface.name, "--out", out.name,
           "--workers", str(rng.integers(1, 3))]  # fmt: skip
    check_step(*run_step(cmd, tmp_path, out, rng, attacks[0]), tmp_path, out)
    if not out.exists():  # interrupted: a resume, attacked in its turn
        check_step(*run_step([*cmd, "--resume"], tmp_path, out, rng, attacks[1]), tmp_path, out)
    if not out.exists():
        done = subprocess.run([*cmd, "--resume"], cwd=tmp_path, capture_output=True, text=True,
                              timeout=120)  # fmt: skip
        assert done.returncode == 0, done.stderr
    ref, run = references(kind), read_run(out)
    np.testing.assert_array_equal(run.sums, ref.sums)
    for q in run.realizations:
        np.testing.assert_array_equal(run.realizations[q], ref.realizations[q], err_msg=q)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml", "t.h5"]

"""One point's pads on worker processes (issue 44, item 6): the plain pads of ``finite_pads`` and
importance sampling's stages in contiguous chunks on one pool, bit-identical to one worker,
and what ``mcsim sweep --pads`` of one point and ``mcsim pads`` give them."""

import dataclasses
import signal
import threading
import time

import numpy as np
import pytest
from conftest import run_cli

import mcsim.engine.cluster
from mcsim.engine import interrupt
from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.studies import pads, rareevent
from mcsim.studies.padpool import PadPool, chunks
from mcsim.studies.pads import finite_pads
from mcsim.studies.tail import importance_p_stick

#: The few-summit pads of test_tail.py at 3 µm² (51 summits), under 1 MPa at their mean-field turn.
SURFACE = dataclasses.replace(SURFACES["smooth"], sigma=3e-9)
TURN = 2.1279


def _spec(seed, n=10):
    return MonteCarloSpec(SURFACE, MATERIALS["silicon"], np.linspace(4, -1, 51), 3e-12, n, seed,
                          "jkr", cycle=True)  # fmt: skip


@pytest.fixture
def pools(monkeypatch):
    """The worker counts of every process pool started, in order."""
    started, real = [], mcsim.engine.cluster.process_pool

    def spy(workers):
        started.append(workers)
        return real(workers)

    monkeypatch.setattr(mcsim.engine.cluster, "process_pool", spy)
    return started


def test_chunks_are_contiguous_in_order_and_cover_every_pad_once():
    for n, workers in [(0, 2), (3, 2), (500, 2), (501, 3), (7, 1)]:
        parts = chunks(n, workers)
        assert [i for c in parts for i in range(n)[c]] == list(range(n))
        assert len(parts) == (1 if workers == 1 else max(1, min(n, 4 * workers)))


def test_importance_sampling_on_two_processes_is_bit_identical_to_one(pools):
    # every stage's pads scored by their pull-off on one pool of 2 processes for the call
    options = dict(turn=TURN, preload=1e6, pads=100, pilot=50)
    one = importance_p_stick(_spec(4), 18e-6, **options)
    assert pools == []  # one worker: this process, no pool
    two = importance_p_stick(_spec(4), 18e-6, **options, workers=2)
    assert pools == [2]
    assert one.reached and one.hits > 0
    for field in dataclasses.fields(one):
        a, b = getattr(one, field.name), getattr(two, field.name)
        np.testing.assert_array_equal(np.asarray(a, dtype=object), np.asarray(b, dtype=object),
                                      err_msg=field.name)  # fmt: skip


def test_a_score_that_cannot_be_pickled_runs_on_threads_of_this_process(pools):
    # a closure: no worker process could call it; it is called here, once a pad
    calls = []

    def band(s):
        calls.append(1)
        return float(np.count_nonzero((s > 1.9) & (s <= 2.6)))

    e = importance_p_stick(_spec(5), 3.5, turn=TURN, pads=100, pilot=50, score=band, workers=2)
    assert pools == [] and len(calls) == e.evaluations


def test_finite_pads_on_two_processes_are_bit_identical_to_one(monkeypatch, pools):
    # 40 plain pads with their static friction, in 8 chunks (more than PROCESS_PADS here)
    monkeypatch.setattr(pads, "PROCESS_PADS", 10)
    options = dict(preload=1e6, turn=TURN, h_pull_off=2.3, tail=False, friction=True)
    one = finite_pads(_spec(6, n=40), 18e-6, **options)
    two = finite_pads(_spec(6, n=40), 18e-6, **options, workers=2)
    assert pools == [2] and one.keys() == two.keys()
    for name in one:
        np.testing.assert_array_equal(two[name], one[name], err_msg=name)


def test_few_plain_pads_stay_in_this_process(pools):
    finite_pads(_spec(6, n=20), 18e-6, preload=1e6, turn=TURN, h_pull_off=2.3, tail=False,
                workers=2)  # fmt: skip
    assert pads.PROCESS_PADS > 20 and pools == []


def test_finite_pads_hand_their_pool_to_importance_sampling(monkeypatch, pools):
    # one pool for the point: its plain pads' and its tail's
    monkeypatch.setattr(pads, "PROCESS_PADS", 10)
    given = []

    def tail(*args, workers, **kwargs):
        given.append(workers)
        raise KeyboardInterrupt

    monkeypatch.setattr(rareevent, "importance_p_stick", tail)
    with pytest.raises(KeyboardInterrupt):
        finite_pads(_spec(6, n=100), 18e-6, preload=1e6, turn=TURN, h_pull_off=2.3, tail=True,
                    workers=2)  # fmt: skip
    assert pools == [2] and isinstance(given[0], PadPool) and given[0].workers == 2


def test_a_signal_ends_the_pads_on_processes_without_waiting_for_them(monkeypatch, pools):
    # a Ctrl-C 2 s in, recorded: this process stops waiting at its next check and ends the
    # workers, their 20 000 pads (about 10 s a core) unfinished
    monkeypatch.setattr(pads, "PROCESS_PADS", 10)
    ctrl_c = threading.Timer(2.0, signal.raise_signal, (signal.SIGINT,))
    with interrupt.interruptible():
        start = time.monotonic()
        ctrl_c.start()
        with pytest.raises(interrupt.Interrupted):
            finite_pads(_spec(6, n=20_000), 18e-6, preload=1e6, turn=TURN, h_pull_off=2.3,
                        tail=False, workers=2)  # fmt: skip
    assert pools == [2] and time.monotonic() - start < 5


PADS_CLI = ("sweep", "--surface", "smooth", "--law", "jkr", "--vary", "sigma=3nm", "--pads", 40,
            "--area", "3um^2", "--preload", "1MPa", "--restoring-force", "18uN", "--seed", 1,
            "--quiet")  # fmt: skip


def test_a_one_point_sweep_runs_its_pads_on_the_workers_processes(monkeypatch, pools, tmp_path,
                                                                  capsys):  # fmt: skip
    # the point is one task in the command's process; its pads get --workers processes,
    # and --workers 1 keeps them here: the same numbers
    from mcsim.store.sweepfile import read_sweep
    from mcsim.store.sweepvariables import PADS

    monkeypatch.setattr(pads, "PROCESS_PADS", 10)
    code, _, err = run_cli(capsys, *PADS_CLI, "--workers", 1, "--out", tmp_path / "one.h5")
    assert code == 0 and pools == [], err
    code, _, err = run_cli(capsys, *PADS_CLI, "--workers", 2, "--out", tmp_path / "two.h5")
    assert code == 0 and pools == [2], err
    one, two = read_sweep(tmp_path / "one.h5"), read_sweep(tmp_path / "two.h5")
    for name in PADS:
        np.testing.assert_array_equal(two.data[name], one.data[name], err_msg=name)


def test_mcsim_pads_gives_its_importance_sampling_the_workers(monkeypatch, tmp_path, capsys):
    given = []

    def tail(*args, workers, **kwargs):
        given.append(workers)
        raise KeyboardInterrupt

    run = tmp_path / "c.h5"
    code, _, err = run_cli(capsys, "simulate", "--surface", "smooth", "--law", "jkr", "--area",
                           "1.5um^2", "--h=2:-1:16", "--realizations", 100, "--seed", 3,
                           "--workers", 1, "--cycle", "--quiet", "--out", run)  # fmt: skip
    assert code == 0, err
    monkeypatch.setattr(rareevent, "importance_p_stick", tail)
    for workers in (3, 1):
        run_cli(capsys, "pads", run, "--restoring-force", "1uN", "--tail", "--workers", workers)
    assert [(type(w), w.workers) for w in given] == [(PadPool, 3), (PadPool, 1)]


def test_a_runs_own_pads_on_two_processes_are_bit_identical_to_one(monkeypatch, pools, tmp_path,
                                                                   capsys):  # fmt: skip
    # mcsim pads' plain pads (Run.pull_off): 40 pads pressed with 1 MPa, each to its own turn,
    # with their static friction, in contiguous ranges on the pool from PROCESS_PADS pads on
    import mcsim

    run = tmp_path / "c.h5"
    code, _, err = run_cli(capsys, "simulate", "--surface", "smooth", "--law", "jkr", "--area",
                           "3um^2", "--h=4:-1:51", "--realizations", 40, "--seed", 6, "--workers",
                           1, "--cycle", "--preload", "1MPa", "--quiet", "--out", run)  # fmt: skip
    assert code == 0, err
    monkeypatch.setattr(pads, "PROCESS_PADS", 10)
    one = mcsim.pad_report(mcsim.read_run(run), 18e-6, friction=True).pull_off
    assert pools == []
    two = mcsim.pad_report(mcsim.read_run(run), 18e-6, friction=True, workers=2).pull_off
    assert pools == [2] and one.turn_load is not None and np.all(one.static_friction > 0)
    for field in dataclasses.fields(one):
        np.testing.assert_array_equal(np.asarray(getattr(two, field.name), dtype=object),
                                      np.asarray(getattr(one, field.name), dtype=object),
                                      err_msg=field.name)  # fmt: skip

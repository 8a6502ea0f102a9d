"""``--resume`` of a finished run or sweep: with the same inputs a no-op (the file untouched,
byte for byte and its modification time, one notice); with other inputs refused in one line
naming the first that differs; a kill between the final write and the checkpoint's removal
is finished by ``--resume``."""

import dataclasses
import logging
import os
import re

import h5py
import numpy as np
import pytest
from conftest import run_cli

from mcsim.model.errors import ParameterError, RunFileError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.store.runfile import read_run
from mcsim.store.sweepfile import read_sweep
from mcsim.studies.simulation import simulate
from mcsim.studies.sweeps import sweep

SMOOTH, SILICON = SURFACES["smooth"], MATERIALS["silicon"]
H = [2.0, 1.0, 0.0]
RUN = dict(surface=SMOOTH, material=SILICON, h=H, area="300 um^2", realizations=3, seed=7)
RUN_ARGS = ["simulate", "--surface", "smooth", "--h=2,1,0", "--area", "300um^2",
            "--realizations", "3", "--seed", "7"]  # fmt: skip
SWEEP_ARGS = ["sweep", "--surface", "smooth", "--vary", "sigma=1nm,2nm", "--h=2,1,0"]


def snapshot(path):
    """The file's bytes and modification time (ns)."""
    return path.read_bytes(), os.stat(path).st_mtime_ns


@pytest.fixture
def finished(tmp_path):
    """A finished run file of RUN, and its snapshot."""
    path = tmp_path / "r.h5"
    simulate(**RUN, out=path)
    return path, snapshot(path)


def test_resuming_a_finished_run_returns_it_untouched_with_a_notice(finished, caplog):
    path, before = finished
    with caplog.at_level(logging.INFO, logger="mcsim"):
        run = simulate(**RUN, out=path, resume=True)
    assert snapshot(path) == before
    assert [r.getMessage() for r in caplog.records] == [
        f"{path}: already holds this finished run: nothing to do"
    ]
    assert run.path == path and run.spec == read_run(path).spec


@pytest.mark.parametrize("quiet", [[], ["--quiet"]], ids=["", "quiet"])
def test_cli_resume_of_a_finished_run_exits_0_and_prints_only_its_notice(tmp_path, capsys, quiet):
    path = tmp_path / "r.h5"
    assert run_cli(capsys, *RUN_ARGS, "--out", path)[0] == 0
    before = snapshot(path)
    code, out, err = run_cli(capsys, *RUN_ARGS, "--out", path, "--resume", *quiet)
    assert (code, out) == (0, "")
    assert err == f"mcsim: {path}: already holds this finished run: nothing to do\n"
    assert snapshot(path) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.h5"]


def test_resume_of_a_finished_run_ignores_what_the_numbers_do_not_depend_on(finished):
    path, before = finished
    simulate(**RUN, out=path, resume=True, workers=1, chunk_size=1 << 16, checkpoint_every=0)
    assert snapshot(path) == before


def test_seedless_resume_takes_the_finished_runs_seed_and_says_so(tmp_path, caplog):
    """Without a seed any seed is asked for: the finished run is the run asked for."""
    path = tmp_path / "r.h5"
    simulate(**{**RUN, "seed": None}, out=path)
    before = snapshot(path)
    with caplog.at_level(logging.INFO, logger="mcsim"):
        run = simulate(**{**RUN, "seed": None}, out=path, resume=True)
    assert snapshot(path) == before
    (message,) = [r.getMessage() for r in caplog.records]
    assert message == (f"{path}: already holds this finished run (no seed given: taken as the "
                       f"file's, {run.spec.entropy}): nothing to do")  # fmt: skip


DIFFERENT_RUNS = {
    "seed": ({"seed": 8}, "seed (file: 7, asked: 8)"),
    "realizations": ({"realizations": 4}, "realizations (file: 3, asked: 4)"),
    "area": ({"area": "400 um^2"}, "area (file: 3e-10, asked: 4e-10)"),
    "h": ({"h": [2.0, 1.0, -1.0]}, "h (file: (2.0, 1.0, 0.0), asked: (2.0, 1.0, -1.0))"),
    "law": ({"law": "dmt"}, "law (file: 'seed', asked: 'dmt')"),
    "count": ({"count": "fixed"}, "count (file: 'poisson', asked: 'fixed')"),
    "cycle": ({"cycle": True}, "cycle (file: False, asked: True)"),
    "device": ({"device": "cuda"}, "device (file: 'cpu', asked: 'cuda')"),
    "surface": ({"surface": dataclasses.replace(SMOOTH, sigma=2e-9)},
                "surface sigma (file: 1.4e-09, asked: 2e-09)"),
    "material": ({"material": dataclasses.replace(SILICON, gamma=0.25)},
                 "material gamma (file: 0.5, asked: 0.25)"),
    "keep_heights": ({"keep_heights": True}, "keep_heights (file: False, asked: True)"),
}  # fmt: skip


@pytest.mark.parametrize("change, named", DIFFERENT_RUNS.values(), ids=DIFFERENT_RUNS)
def test_resume_of_a_finished_run_of_other_inputs_is_refused_naming_the_input(
    finished, change, named
):
    path, before = finished
    expected = (f"{path}: already holds a finished run with a different {named}; "
                "use --overwrite to replace it or another --out")  # fmt: skip
    with pytest.raises(RunFileError, match=f"^{re.escape(expected)}$"):
        simulate(**{**RUN, **change}, out=path, resume=True)
    assert snapshot(path) == before


def test_cli_resume_of_a_finished_run_of_another_seed_is_refused_in_one_line(tmp_path, capsys):
    path = tmp_path / "r.h5"
    assert run_cli(capsys, *RUN_ARGS, "--out", path)[0] == 0
    before = snapshot(path)
    argv = [a if a != "7" else "8" for a in RUN_ARGS]
    code, out, err = run_cli(capsys, *argv, "--out", path, "--resume")
    assert (code, out) == (2, "")
    assert err == (f"mcsim: error: {path}: already holds a finished run with a different seed "
                   "(file: 7, asked: 8); use --overwrite to replace it or another --out\n")  # fmt: skip
    assert snapshot(path) == before


def test_resume_refuses_a_damaged_finished_run_by_name(finished):
    path, _ = finished
    with h5py.File(path, "r+") as f:
        f["realizations/sums/n_contact"][0, 0] += 1.0  # an edit the checksum does not cover
    with pytest.raises(RunFileError, match=f"^{re.escape(str(path))}: damaged run file: checksum"):
        simulate(**RUN, out=path, resume=True)


def test_a_kill_between_the_final_write_and_the_checkpoints_removal_is_finished_by_resume(
    tmp_path, capsys, monkeypatch
):
    """The process ends just after the run file is renamed into place, its checkpoint
    (saved after every task) still beside it: --resume removes the checkpoint, exits 0
    and leaves the run. (A kill also leaves the lock file, free: see test_faults.)"""
    import mcsim.store.runfile as runfile

    write = runfile.write_run

    def write_then_die(*args, **kwargs):
        write(*args, **kwargs)
        raise KeyboardInterrupt

    path = tmp_path / "r.h5"
    argv = [*RUN_ARGS, "--out", path, "--checkpoint-every", "0", "--quiet"]
    monkeypatch.setattr(runfile, "write_run", write_then_die)
    assert run_cli(capsys, *argv)[0] == 130
    monkeypatch.undo()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.h5", "r.partial.h5"]
    before = snapshot(path)
    code, out, err = run_cli(capsys, *argv, "--resume")
    assert (code, out) == (0, ""), err
    assert err == f"mcsim: {path}: already holds this finished run: nothing to do\n"
    assert snapshot(path) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.h5"]


def test_a_kill_after_the_last_checkpoint_before_the_final_write_is_finished_by_resume(
    tmp_path, monkeypatch
):
    """The checkpoint saved after the last task has every block done: --resume writes it
    (it was refused as damaged: 'progress disagrees with the complete flag')."""
    import mcsim.store.runfile as runfile

    def killed(*args, **kwargs):
        raise KeyboardInterrupt

    path = tmp_path / "r.h5"
    monkeypatch.setattr(runfile, "write_run", killed)
    with pytest.raises(KeyboardInterrupt):
        simulate(**RUN, out=path, checkpoint_every=0)
    monkeypatch.undo()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.partial.h5"]
    run = simulate(**RUN, out=path, resume=True)
    np.testing.assert_array_equal(run.sums, simulate(**RUN).sums)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.h5"]


# --- sweeps ---------------------------------------------------------------------------

SWEEP = dict(surface=SMOOTH, material=SILICON, vary={"sigma": "1nm,2nm"}, h=H)


@pytest.fixture
def finished_sweep(tmp_path):
    """A finished sweep file of SWEEP, and its snapshot."""
    path = tmp_path / "s.h5"
    sweep(**SWEEP, out=path)
    return path, snapshot(path)


def test_resuming_a_finished_sweep_returns_it_untouched_with_a_notice(finished_sweep, caplog):
    path, before = finished_sweep
    with caplog.at_level(logging.INFO, logger="mcsim"):
        result = sweep(**SWEEP, out=path, resume=True)
    assert snapshot(path) == before
    assert [r.getMessage() for r in caplog.records] == [
        f"{path}: already holds this finished sweep: nothing to do"
    ]
    assert result.path == path and result.attrs["created"] == read_sweep(path).attrs["created"]


def test_cli_resume_of_a_finished_sweep_exits_0_and_prints_only_its_notice(tmp_path, capsys):
    path = tmp_path / "s.h5"
    assert run_cli(capsys, *SWEEP_ARGS, "--out", path)[0] == 0
    before = snapshot(path)
    code, out, err = run_cli(capsys, *SWEEP_ARGS, "--out", path, "--resume")
    assert (code, out) == (0, "")
    assert err == f"mcsim: {path}: already holds this finished sweep: nothing to do\n"
    assert snapshot(path) == before


DIFFERENT_SWEEPS = {
    "values": ({"vary": {"sigma": "1nm,4nm"}}, "varied values (file: [[1e-09, 2e-09]], asked: [[1e-09, 4e-09]])"),
    "varied": ({"vary": {"R": "1um,2um"}}, "varied (file: ['sigma'], asked: ['R'])"),
    "h": ({"h": [2.0, 1.0, -1.0]}, "h (file: [2.0, 1.0, 0.0], asked: [2.0, 1.0, -1.0])"),
    "law": ({"law": "dmt"}, "law (file: 'seed', asked: 'dmt')"),
    "turn": ({"turn": 0.5}, "turn (file: None, asked: 0.5)"),
    "surface": ({"surface": dataclasses.replace(SMOOTH, eta=2e12)},
                "surface eta (file: 17000000000000.0, asked: 2000000000000.0)"),
    "material": ({"material": dataclasses.replace(SILICON, gamma=0.25)},
                 "material gamma (file: 0.5, asked: 0.25)"),
    "mc": ({"mc": True, "area": "1 um^2", "seed": 1}, "mc (file: False, asked: True)"),
}  # fmt: skip


@pytest.mark.parametrize("change, named", DIFFERENT_SWEEPS.values(), ids=DIFFERENT_SWEEPS)
def test_resume_of_a_finished_sweep_of_other_inputs_is_refused_naming_the_input(
    finished_sweep, change, named
):
    path, before = finished_sweep
    expected = (f"{path}: already holds a finished sweep with a different {named}; "
                "use --overwrite to replace it or another --out")  # fmt: skip
    with pytest.raises(RunFileError, match=f"^{re.escape(expected)}$"):
        sweep(**{**SWEEP, **change}, out=path, resume=True)
    assert snapshot(path) == before


MC_SWEEP = {**SWEEP, "mc": True, "area": "1 um^2", "realizations": 2}


@pytest.mark.parametrize("seed, accepted", [(5, True), (6, False), (None, True)])
def test_resume_of_a_finished_monte_carlo_sweep_compares_the_seed_unless_none_is_given(
    tmp_path, seed, accepted
):
    path = tmp_path / "s.h5"
    sweep(**MC_SWEEP, seed=5, out=path)
    before = snapshot(path)
    if accepted:
        sweep(**MC_SWEEP, seed=seed, out=path, resume=True)
    else:
        with pytest.raises(RunFileError, match=re.escape("different seed (file: 5, asked: 6)")):
            sweep(**MC_SWEEP, seed=seed, out=path, resume=True)
    assert snapshot(path) == before


def test_a_kill_between_the_final_sweep_write_and_the_checkpoints_removal_is_finished_by_resume(
    tmp_path, monkeypatch
):
    import mcsim.studies.sweeps as sweeps

    write = sweeps.write_sweep

    def write_then_die(*args, complete, **kwargs):
        write(*args, complete=complete, **kwargs)
        if complete:
            raise KeyboardInterrupt  # the process ends here, its checkpoint still beside

    path = tmp_path / "s.h5"
    monkeypatch.setattr(sweeps, "write_sweep", write_then_die)
    with pytest.raises(KeyboardInterrupt):
        sweep(**SWEEP, out=path, checkpoint_every=0)
    monkeypatch.undo()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.h5", "s.partial.h5"]
    before = snapshot(path)
    sweep(**SWEEP, out=path, resume=True)
    assert snapshot(path) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.h5"]


def interrupt_sweep_at_point_1(path, monkeypatch):
    """Run SWEEP into ``path`` until a Ctrl-C at its second point: its checkpoint holds one point."""
    import mcsim.studies.sweeppoint as sweeps

    evaluate = sweeps.evaluate

    def stop_at_point_1(point, config):
        if point.index == 1:
            raise KeyboardInterrupt
        return evaluate(point, config)

    monkeypatch.setattr(sweeps, "evaluate", stop_at_point_1)
    with pytest.raises(KeyboardInterrupt):
        sweep(**SWEEP, workers=1, out=path)
    monkeypatch.undo()


def test_resume_refuses_a_sweep_checkpoint_of_other_inputs_naming_the_input(tmp_path, monkeypatch):
    path = tmp_path / "s.h5"
    interrupt_sweep_at_point_1(path, monkeypatch)
    expected = (f"cannot resume {path}: its checkpoint s.partial.h5 holds a sweep with a different "
                "law (file: 'seed', asked: 'dmt')")  # fmt: skip
    with pytest.raises(ParameterError, match=f"^{re.escape(expected)}$"):
        sweep(**{**SWEEP, "law": "dmt"}, out=path, resume=True)


def test_resume_of_a_finished_run_of_another_mcsim_version_is_refused(finished):
    """Its numbers may differ from this version's (a law fixed since): not the run asked for."""
    from mcsim._version import __version__
    from mcsim.store.files import checksum

    path, _ = finished
    with h5py.File(path, "r+") as f:
        f.attrs["mcsim_version"] = "0.0.1"
        f.attrs["checksum"] = checksum(f)
    named = f"mcsim version (file: '0.0.1', asked: {__version__!r})"
    with pytest.raises(RunFileError, match=re.escape(f"a different {named}")):
        simulate(**RUN, out=path, resume=True)


def test_resume_refuses_an_unfinished_sweep_at_the_output_path(tmp_path, monkeypatch):
    """A checkpoint copied onto the output path is not a finished sweep."""
    path = tmp_path / "s.h5"
    interrupt_sweep_at_point_1(path, monkeypatch)
    (tmp_path / "s.partial.h5").rename(path)
    with pytest.raises(
        RunFileError, match=f"^{re.escape(str(path))}: damaged sweep file: it holds"
    ):
        sweep(**SWEEP, out=path, resume=True)


def test_a_surface_with_environment_only_fields_resumes_without_an_environment(tmp_path, caplog):
    # A surface ingest writes carries rq, summit_offset and the map's heights, which only the
    # environment reads; a run without one neither uses nor stores them, so resuming it (or a
    # checkpoint of it) must not see them as a different input.
    measured = dataclasses.replace(SMOOTH, rq=1.6e-9, summit_offset=1.5e-9)
    path = tmp_path / "r.h5"
    first = simulate(**(RUN | {"surface": measured}), out=path)
    before = snapshot(path)
    with caplog.at_level(logging.WARNING):
        again = simulate(**(RUN | {"surface": measured}), out=path, resume=True)
    assert snapshot(path) == before and "nothing to do" in caplog.text
    assert again.spec == first.spec and again.spec.surface.rq is None

"""Run and sweep files whose values were edited and re-signed (checksum recomputed) are
refused in one line naming the field and the value, whatever command reads them (issue 33).

The checksum only proves that nothing changed since the file was signed; a value that no
run or sweep can hold (a negative preload, a count below zero, a NaN sum, a probability
above 1, zero pads) must be caught by the reader's own checks, not by a traceback in the
command that uses it.
"""

from __future__ import annotations

import contextlib
import io

import h5py
import numpy as np
import pytest

from mcsim.cli import main as cli
from mcsim.store.files import checksum
from mcsim.store.sweepfile import read_sweep


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> dict:
    """A cycle run with a preload and a pads sweep, as bytes."""
    import mcsim

    folder = tmp_path_factory.mktemp("signed")
    mcsim.simulate("smooth", "silicon", [2.0, 0.0], "1um^2", realizations=2, seed=9, law="jkr",
                   cycle=True, preload="1kPa", workers=1, out=folder / "run.h5")  # fmt: skip
    mcsim.sweep("smooth", "silicon", {"gamma": [0.1, 0.2]}, law="jkr", h=[2.0, 0.0], pads=5,
                restoring_force="1nN", area="1um^2", seed=1, workers=1, out=folder / "pads.h5")  # fmt: skip
    return {name: (folder / name).read_bytes() for name in ("run.h5", "pads.h5")}


def resigned(tmp_path, raw: bytes, name: str, edit) -> str:
    """The file ``raw`` with ``edit(f)`` applied and its checksum recomputed."""
    path = tmp_path / name
    path.write_bytes(raw)
    with h5py.File(path, "r+") as f:
        edit(f)
        f.attrs["checksum"] = checksum(f)
    return str(path)


def attribute(key, value):
    return lambda f: f.attrs.__setitem__(key, value)


def dataset(name, change):
    def edit(f):
        f[name][...] = change(f[name][()])

    return edit


def cli_run(*argv) -> tuple[int, str]:
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        code = cli.main([str(a) for a in argv])
    return code, err.getvalue()


RUN_EDITS = {
    "preload as text": (attribute("preload", "x"), "attribute preload is 'x', not a number"),
    "negative preload": (
        attribute("preload", -5.0),
        "attribute preload holds -5.0 (allowed: finite numbers >= 0)",
    ),
    "infinite preload": (attribute("preload", np.inf), "attribute preload holds inf"),
    "negative summit count": (
        dataset("realizations/N", lambda v: -v - 1),
        "dataset realizations/N holds -",
    ),
    "negative blocks done": (
        dataset("progress/done_blocks", lambda v: v * 0 - 1),
        "dataset progress/done_blocks holds -1 at index [0]",
    ),
    "NaN sums": (
        dataset("realizations/sums/n_contact", lambda v: v * np.nan),
        "dataset realizations/sums/n_contact holds nan at index [0, 0]",
    ),
    "negative contacts": (
        dataset("realizations/sums/n_contact", lambda v: v * 0 - 2),
        "dataset realizations/sums/n_contact holds -2.0",
    ),
    "negative sum of squares": (
        dataset("realizations/sums/loadload", lambda v: -v - 1),
        "dataset realizations/sums/loadload holds -",
    ),
    "infinite sum": (
        dataset("realizations/sums/load", lambda v: v + np.inf),
        "dataset realizations/sums/load holds ",
    ),
}


@pytest.mark.parametrize("case", sorted(RUN_EDITS))
@pytest.mark.parametrize("command", ["show", "compare", "pads"])
def test_a_resigned_run_with_impossible_values_is_refused_in_one_line(
    files, tmp_path, case, command
):
    edit, message = RUN_EDITS[case]
    path = resigned(tmp_path, files["run.h5"], "run.h5", edit)
    code, err = cli_run(command, path)  # pads used to raise TypeError on a text preload
    assert code == 2 and err.count("\n") == 1, err
    assert err.startswith(f"mcsim: error: {path}: damaged run file: {message}"), err


def test_a_resigned_checkpoint_with_more_blocks_done_than_planned_is_refused(files, tmp_path):
    path = resigned(tmp_path, files["run.h5"], "run.h5",
                    dataset("progress/done_blocks", lambda v: v + 1))  # fmt: skip
    code, err = cli_run("show", path)
    assert code == 2
    assert "dataset progress/done_blocks counts more blocks than progress/n_blocks plans" in err


SWEEP_EDITS = {
    "p_stick 2": (
        dataset("p_stick", lambda v: v * 0 + 2),
        "dataset p_stick holds 2.0 at index [0] (allowed: 0 to 1, or NaN)",
    ),
    "negative p_stick_model": (
        dataset("p_stick_model", lambda v: v * 0 - 0.5),
        "dataset p_stick_model holds -0.5",
    ),
    "p_stick outside its interval": (
        dataset("p_stick_low", lambda v: np.minimum(v + 0.9, 1.0)),
        "dataset p_stick lies outside its interval",
    ),
    "zero pads": (attribute("pads", 0), "attribute pads holds 0 (allowed: finite numbers >= 1)"),
    "pads as text": (attribute("pads", "x"), "attribute pads is 'x', not an integer"),
    "negative restoring force": (
        attribute("restoring_force", -1.0),
        "attribute restoring_force holds -1.0",
    ),
    "negative preload": (attribute("preload", -1.0), "attribute preload holds -1.0"),
    "no pad area": (lambda f: f.attrs.__delitem__("area"), "attribute area is missing"),
    "negative contacting summits": (
        dataset("contacting_summits", lambda v: -v - 1),
        "dataset contacting_summits holds -",
    ),
}


@pytest.mark.parametrize("case", sorted(SWEEP_EDITS))
@pytest.mark.parametrize("command", ["show", "plot"])
def test_a_resigned_pads_sweep_with_impossible_values_is_refused_in_one_line(
    files, tmp_path, case, command
):
    edit, message = SWEEP_EDITS[case]
    path = resigned(tmp_path, files["pads.h5"], "pads.h5", edit)
    argv = [command, path] + (["--out", tmp_path / "p.png"] if command == "plot" else [])
    code, err = cli_run(*argv)  # plot used to raise ZeroDivisionError (pads 0), ValueError (p 2)
    assert code == 2 and err.count("\n") == 1, err
    assert err.startswith(f"mcsim: error: {path}: damaged sweep file: {message}"), err
    assert not (tmp_path / "p.png").exists()


def test_a_pads_sweep_with_a_preload_and_a_failed_point_still_reads(tmp_path):
    """NaN where a point failed and a preload are what sweeps write: no refusal."""
    import mcsim

    out = tmp_path / "s.h5"
    mcsim.sweep("smooth", "silicon", {"gamma": [0.1, 0.2]}, law="jkr", h=[2.0, 0.0], pads=3,
                restoring_force="1nN", preload="1kPa", area="1um^2", seed=1, workers=1, out=out)  # fmt: skip
    with h5py.File(out, "r+") as f:  # as a failed point is stored
        for k in ("p_stick", "p_stick_low", "p_stick_high", "pull_off_std"):
            f[k][0] = np.nan
        f.attrs["checksum"] = checksum(f)
    assert read_sweep(out).attrs["preload"] == 1000.0

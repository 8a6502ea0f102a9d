"""One rule for every command that writes (`plot`, `paper`, `ingest`): no silent replacement,
never onto an input, never onto a non-regular file, no temporaries left behind."""

import os
from pathlib import Path

import pytest

from mcsim.cli.main import main
from mcsim.model.errors import MCSimError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.store.outputs import check_output, write_atomic
from mcsim.studies.paper import FIGURE_FILES, paper_monte_carlo
from mcsim.studies.simulation import simulate

PNG = b"\x89PNG\r\n\x1a\n"


def run_cli(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.endswith(".tmp"))


def one_line_error(code: int, err: str, *needles: str) -> None:
    assert code == 2 and err.startswith("mcsim: error: ") and err.count("\n") == 1, err
    for needle in needles:
        assert needle in err, (needle, err)


# -- the rule itself ------------------------------------------------------------------------


def test_existing_file_is_replaced_only_with_overwrite(tmp_path):
    path = tmp_path / "a.txt"
    path.write_text("old")
    with pytest.raises(MCSimError, match=r"a\.txt: file exists \(pass --overwrite"):
        write_atomic(path, lambda tmp: tmp.write_text("new"))
    assert path.read_text() == "old"
    write_atomic(path, lambda tmp: tmp.write_text("new"), overwrite=True)
    assert path.read_text() == "new" and leftovers(tmp_path) == []


def test_an_input_is_never_written_even_through_links(tmp_path):
    source = tmp_path / "in.h5"
    source.write_text("input")
    (tmp_path / "soft.h5").symlink_to(source)
    os.link(source, tmp_path / "hard.h5")
    for target in (source, tmp_path / "soft.h5", tmp_path / "hard.h5", tmp_path / "." / "in.h5"):
        with pytest.raises(MCSimError, match="is an input of this command"):
            write_atomic(target, lambda tmp: tmp.write_text("x"), inputs=[source], overwrite=True)
    assert source.read_text() == "input"


@pytest.mark.parametrize("kind", ["folder", "fifo", "device", "broken link", "link to folder"])
def test_non_regular_files_are_never_replaced(tmp_path, kind):
    target = tmp_path / "out.png"
    if kind == "folder":
        target.mkdir()
    elif kind == "fifo":
        os.mkfifo(target)
    elif kind == "device":
        target = Path("/dev/null")
    elif kind == "broken link":
        target.symlink_to(tmp_path / "nowhere")
    else:
        (tmp_path / "d").mkdir()
        target.symlink_to(tmp_path / "d")
    before = os.lstat(target)
    with pytest.raises(MCSimError, match=r"is (a folder|a pipe|a device|a broken symbolic link)"):
        write_atomic(target, lambda tmp: tmp.write_text("x"), overwrite=True)
    after = os.lstat(target)
    assert (after.st_mode, after.st_ino) == (before.st_mode, before.st_ino)
    assert leftovers(tmp_path) == []


def test_a_link_to_a_regular_file_replaces_its_target_and_keeps_the_link(tmp_path):
    (tmp_path / "real.txt").write_text("old")
    (tmp_path / "link.txt").symlink_to(tmp_path / "real.txt")
    write_atomic(tmp_path / "link.txt", lambda tmp: tmp.write_text("new"), overwrite=True)
    assert (tmp_path / "link.txt").is_symlink() and (tmp_path / "real.txt").read_text() == "new"


def test_a_failed_write_keeps_the_old_file_and_leaves_no_temporary(tmp_path):
    path = tmp_path / "a.txt"
    path.write_text("old")

    def fail(tmp):
        tmp.write_text("half")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        write_atomic(path, fail, overwrite=True)
    assert path.read_text() == "old" and leftovers(tmp_path) == []


def test_a_file_that_appears_during_the_write_is_not_replaced(tmp_path):
    path = tmp_path / "a.txt"

    def racing(tmp):
        tmp.write_text("mine")
        path.write_text("theirs")  # another process wins the race

    with pytest.raises(MCSimError, match="file exists"):
        write_atomic(path, racing)
    assert path.read_text() == "theirs" and leftovers(tmp_path) == []


def test_check_output_names_a_missing_folder(tmp_path):
    with pytest.raises(MCSimError, match="does not exist"):
        check_output(tmp_path / "no" / "a.png")


# -- mcsim plot -----------------------------------------------------------------------------


@pytest.fixture(scope="module")
def run_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("run") / "t.h5"
    simulate(SURFACES["rough"], MATERIALS["silicon"], [2, 0], "100um^2", seed=2, out=path)
    return path


def test_plot_refuses_an_existing_png_without_overwrite(capsys, run_file, tmp_path):
    png = tmp_path / "p.png"
    png.write_bytes(b"keep")
    code, _, err = run_cli(capsys, "plot", run_file, "--out", png)
    one_line_error(code, err, "p.png: file exists (pass --overwrite")
    assert png.read_bytes() == b"keep"
    code, _, err = run_cli(capsys, "plot", run_file, "--out", png, "--overwrite")
    assert code == 0, err
    assert png.read_bytes().startswith(PNG) and leftovers(tmp_path) == []


def test_plot_never_writes_onto_its_run_file(capsys, run_file):
    before = run_file.read_bytes()
    code, _, err = run_cli(capsys, "plot", run_file, "--out", run_file, "--overwrite")
    one_line_error(code, err, "must end in .png")
    soft, hard = run_file.with_name("soft.png"), run_file.with_name("hard.png")
    soft.symlink_to(run_file)
    os.link(run_file, hard)
    for png in (soft, hard):
        code, _, err = run_cli(capsys, "plot", run_file, "--out", png, "--overwrite")
        one_line_error(code, err, "is an input of this command")
    assert run_file.read_bytes() == before


def test_plot_out_must_be_a_png_name(capsys, run_file, tmp_path):
    other = tmp_path / "other.h5"
    other.write_bytes(b"another run")
    code, _, err = run_cli(capsys, "plot", run_file, "--out", other, "--overwrite")
    one_line_error(code, err, "must end in .png")
    assert other.read_bytes() == b"another run"


@pytest.mark.parametrize("kind", ["folder", "device"])
def test_plot_refuses_a_non_regular_target_even_with_overwrite(capsys, run_file, tmp_path, kind):
    if kind == "folder":
        target = tmp_path / "d.png"
        target.mkdir()
    else:
        target = tmp_path / "null.png"
        target.symlink_to("/dev/null")
    code, _, err = run_cli(capsys, "plot", run_file, "--out", target, "--overwrite")
    one_line_error(code, err, f"is a {kind}")
    assert leftovers(tmp_path) == []


def test_plot_overlays_several_runs(capsys, run_file, tmp_path):
    second = tmp_path / "u.h5"
    simulate(SURFACES["smooth"], MATERIALS["silicon"], [1, 0], "100um^2", seed=3, out=second)
    code, _, err = run_cli(capsys, "plot", run_file, second)
    one_line_error(code, err, "--out")
    code, _, err = run_cli(capsys, "plot", run_file, second, "--out", tmp_path / "both.png")
    assert code == 0, err
    assert (tmp_path / "both.png").read_bytes().startswith(PNG)


# -- mcsim paper ----------------------------------------------------------------------------


def test_paper_refuses_to_replace_an_earlier_reproduction_without_overwrite(capsys, tmp_path):
    out = tmp_path / "paper"
    code, _, err = run_cli(capsys, "paper", "--out", out, "--no-mc")
    assert code == 0, err
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    code, _, err = run_cli(capsys, "paper", "--out", out, "--no-mc")
    one_line_error(code, err, "file exists (pass --overwrite")
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    code, _, err = run_cli(capsys, "paper", "--out", out, "--no-mc", "--overwrite")
    assert code == 0, err
    assert sorted(p.name for p in out.iterdir()) == sorted(before)


def test_paper_refuses_an_existing_run_before_any_monte_carlo_work(capsys, tmp_path):
    out = tmp_path / "paper"
    out.mkdir()
    (out / "mc_smooth.h5").write_bytes(b"an earlier run")
    code, _, err = run_cli(capsys, "paper", "--out", out)
    one_line_error(code, err, "mc_smooth.h5: file exists")
    assert [p.name for p in out.iterdir()] == ["mc_smooth.h5"]  # nothing computed or written
    with pytest.raises(MCSimError, match=r"mc_smooth\.h5: file exists"):
        paper_monte_carlo(out, log=None)
    assert (out / "mc_smooth.h5").read_bytes() == b"an earlier run"


def test_paper_refuses_a_folder_in_place_of_a_figure_even_with_overwrite(capsys, tmp_path):
    out = tmp_path / "paper"
    out.mkdir()
    figure = out / next(iter(FIGURE_FILES))
    figure.mkdir()
    code, _, err = run_cli(capsys, "paper", "--out", out, "--no-mc", "--overwrite")
    one_line_error(code, err, "is a folder")
    assert figure.is_dir() and [p.name for p in out.iterdir()] == [figure.name]


# -- mcsim ingest ---------------------------------------------------------------------------


def _histogram(path: Path) -> Path:
    path.write_text("z [nm], count\n-1, 1\n0, 4\n1, 2\n2, 1\n")
    return path


def test_ingest_never_overwrites_its_input(capsys, tmp_path):
    # the companion histogram of s.toml is s-heights.csv: here the input itself
    source = _histogram(tmp_path / "s-heights.csv")
    before = source.read_bytes()
    code, _, err = run_cli(capsys, "ingest", source, "--out", tmp_path / "s.toml", "--R", "2um",
                           "--eta", "10um^-2", "--overwrite")  # fmt: skip
    one_line_error(code, err, "is an input of this command")
    assert source.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s-heights.csv"]


def test_ingest_refuses_a_non_regular_output_even_with_overwrite(capsys, tmp_path):
    source = _histogram(tmp_path / "h.csv")
    os.mkfifo(tmp_path / "s-heights.png")
    code, _, err = run_cli(capsys, "ingest", source, "--out", tmp_path / "s.toml", "--R", "2um",
                           "--eta", "10um^-2", "--overwrite")  # fmt: skip
    one_line_error(code, err, "s-heights.png: is a pipe")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["h.csv", "s-heights.png"]


def test_ingest_overwrite_replaces_every_output_and_leaves_no_temporary(capsys, tmp_path):
    source = _histogram(tmp_path / "h.csv")
    args = ("ingest", source, "--out", tmp_path / "s.toml", "--R", "2um", "--eta", "10um^-2")
    assert run_cli(capsys, *args)[0] == 0
    code, _, err = run_cli(capsys, *args)
    one_line_error(code, err, "file exists")
    assert run_cli(capsys, *args, "--overwrite")[0] == 0
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["h.csv", "s-heights.csv", "s-heights.png", "s.toml"]


def test_ingest_overwrite_removes_the_files_of_an_earlier_ingest_it_does_not_write(
    capsys, tmp_path
):
    # docs/contact.md's ingest after the README's: no --plot figure of the earlier run stays
    source = _histogram(tmp_path / "h.csv")
    args = ("ingest", source, "--out", tmp_path / "s.toml", "--R", "2um", "--eta", "10um^-2")
    assert run_cli(capsys, *args, "--plot")[0] == 0
    assert (tmp_path / "s-gw.png").is_file()
    for name in ("s.toml", "s-heights.csv", "s-heights.png"):
        (tmp_path / name).unlink()  # the figure alone is still an output of this ingest
    code, _, err = run_cli(capsys, *args)
    one_line_error(code, err, "s-gw.png: file exists")
    (tmp_path / "s-pads.h5").write_bytes(b"an earlier --synthesize")
    code, _, err = run_cli(capsys, *args, "--overwrite")
    assert code == 0, err
    assert f"mcsim: removed {tmp_path / 's-gw.png'} (an earlier ingest's" in err
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["h.csv", "s-heights.csv", "s-heights.png", "s.toml"]


def test_an_unwritable_folder_is_a_one_line_error(capsys, run_file, tmp_path):
    if os.geteuid() == 0:
        pytest.skip("root writes into read-only folders")
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o500)
    try:
        code, _, err = run_cli(capsys, "plot", run_file, "--out", folder / "p.png")
    finally:
        folder.chmod(0o700)
    one_line_error(code, err, "cannot write it")
    assert list(folder.iterdir()) == []

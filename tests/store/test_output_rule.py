"""One output rule for every command, run and sweep files included (mcsim/store/outputs.py):
only regular files are replaced, a symbolic link to one is followed (its target replaced,
the link kept), and a broken link, a folder or a pipe is refused even with --overwrite.
A pipe is never opened for reading either (``show`` would block on it)."""

import os

import pytest

from mcsim.cli.main import main

SIMULATE = ["simulate", "--surface", "smooth", "--area", "1um^2", "--h=0", "--seed", "1", "--quiet"]


def one_line_error(capsys, argv) -> str:
    assert main(argv) != 0
    err = capsys.readouterr().err
    assert err.startswith("mcsim: error: ") and err.count("\n") == 1, err
    return err


@pytest.mark.parametrize("overwrite", [[], ["--overwrite"]])
def test_a_broken_link_a_folder_link_and_a_pipe_are_refused_even_with_overwrite(
    capsys, tmp_path, overwrite
):
    (tmp_path / "broken.h5").symlink_to(tmp_path / "nowhere.h5")
    (tmp_path / "folder").mkdir()
    (tmp_path / "to-folder.h5").symlink_to(tmp_path / "folder")
    os.mkfifo(tmp_path / "pipe.h5")
    for name, reason in [("broken.h5", "is a broken symbolic link"),
                         ("to-folder.h5", "is a folder"), ("pipe.h5", "is a pipe")]:  # fmt: skip
        err = one_line_error(capsys, [*SIMULATE, "--out", str(tmp_path / name), *overwrite])
        assert reason in err, err
    assert not (tmp_path / "nowhere.h5").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["broken.h5", "folder", "pipe.h5",
                                                          "to-folder.h5"]  # fmt: skip


def test_a_link_to_a_run_file_is_followed_with_overwrite_its_target_replaced(capsys, tmp_path):
    target = tmp_path / "target.h5"
    assert main([*SIMULATE, "--out", str(target)]) == 0
    link = tmp_path / "link.h5"
    link.symlink_to(target)
    assert "file exists" in one_line_error(capsys, [*SIMULATE, "--out", str(link)])
    before = target.stat().st_mtime_ns
    assert main([*SIMULATE, "--out", str(link), "--overwrite", "--seed", "2"]) == 0
    assert link.is_symlink() and os.readlink(link) == str(target)  # the link kept
    assert target.stat().st_mtime_ns != before  # its target replaced
    from mcsim import read_run

    assert read_run(link).spec.entropy == 2


def test_show_of_a_pipe_says_so_instead_of_blocking(capsys, tmp_path):
    os.mkfifo(tmp_path / "pipe.h5")
    assert "pipe.h5: not a regular file" in one_line_error(
        capsys, ["show", str(tmp_path / "pipe.h5")]
    )

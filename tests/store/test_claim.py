"""The claim of an output (mcsim.store.claim) that simulate() and sweep() share: what a
resume finds beside the file, and the final write; with stand-in readers, since the claim
does not depend on what the file holds."""

import contextlib
import logging

import pytest

from mcsim._version import __version__
from mcsim.model.errors import ParameterError, RunFileError
from mcsim.store.claim import claim_output
from mcsim.store.files import checkpoint_path


def claim(stack, out, *, attrs=None, **options):
    """``claim_output`` with readers that return the path they read (and ``attrs``)."""
    attrs = {"mcsim_version": __version__} if attrs is None else attrs
    return claim_output(stack, out, what="thing", read_finished=lambda p: ("finished", p),
                        read_checkpoint=lambda p: (("checkpoint", p), attrs), **options)  # fmt: skip


def test_resume_finds_the_finished_file_before_any_checkpoint(tmp_path):
    out = tmp_path / "a.h5"
    out.write_bytes(b"x")
    checkpoint_path(out).write_bytes(b"y")
    with contextlib.ExitStack() as stack:
        found = claim(stack, out, overwrite=False, resume=True)
        assert (found.finished, found.checkpoint) == (("finished", out), None)
        assert (tmp_path / "a.h5.lock").exists()  # held while the stack is open
    assert not (tmp_path / "a.h5.lock").exists()


def test_resume_continues_a_checkpoint_and_refuses_one_of_other_inputs(tmp_path):
    out = tmp_path / "a.h5"
    checkpoint_path(out).write_bytes(b"y")
    with contextlib.ExitStack() as stack:
        found = claim(stack, out, overwrite=False, resume=True)
        assert found.checkpoint == ("checkpoint", checkpoint_path(out)) and found.finished is None
        found.check_checkpoint({"seed": 1}, {"seed": 1})
        with pytest.raises(ParameterError, match=r"^cannot resume .*a.h5: its checkpoint "
                           r"a.partial.h5 holds a thing with a different seed \(file: 1, asked: 2\)$"):  # fmt: skip
            found.check_checkpoint({"seed": 1}, {"seed": 2})


@pytest.mark.parametrize(
    ("attrs", "says"),
    [({"mcsim_version": "0.0.1"}, r"a.partial.h5: written by mcsim 0.0.1; resume it with that version$"),
     ({"mcsim_version": __version__, "complete": True}, r"damaged checkpoint: it holds a complete thing$")],
)  # fmt: skip
def test_a_checkpoint_of_another_version_or_marked_complete_is_refused(tmp_path, attrs, says):
    out = tmp_path / "a.h5"
    checkpoint_path(out).write_bytes(b"y")
    with contextlib.ExitStack() as stack, pytest.raises(RunFileError, match=says):
        claim(stack, out, attrs=attrs, overwrite=False, resume=True)


def test_resume_with_nothing_there_starts_from_the_beginning_and_says_so(tmp_path, caplog):
    out = tmp_path / "a.h5"
    with caplog.at_level(logging.INFO, logger="mcsim"), contextlib.ExitStack() as stack:
        found = claim(stack, out, overwrite=False, resume=True)
    assert (found.finished, found.checkpoint) == (None, None)
    assert [r.getMessage() for r in caplog.records] == [
        f"{out}: nothing to resume (no checkpoint a.partial.h5): starting the thing from the beginning"
    ]


def test_overwrite_removes_a_checkpoint_and_finish_writes_then_removes_the_new_one(tmp_path):
    out = tmp_path / "a.h5"
    checkpoint_path(out).write_bytes(b"old")
    with contextlib.ExitStack() as stack:
        found = claim(stack, out, overwrite=True, resume=False)
        assert not checkpoint_path(out).exists()
        checkpoint_path(out).write_bytes(b"progress")
        assert found.finish(lambda path: path.write_bytes(b"done")) == 4
    assert out.read_bytes() == b"done" and not checkpoint_path(out).exists()


def test_a_finished_file_of_the_inputs_asked_for_is_returned_with_a_notice(tmp_path, caplog):
    out = tmp_path / "a.h5"
    out.write_bytes(b"x")
    checkpoint_path(out).write_bytes(b"its own")
    with caplog.at_level(logging.INFO, logger="mcsim"), contextlib.ExitStack() as stack:
        found = claim(stack, out, overwrite=False, resume=True)
        with pytest.raises(RunFileError, match=r"already holds a finished thing with a different "
                           r"law \(file: 'jkr', asked: 'dmt'\); use --overwrite"):  # fmt: skip
            found.already_finished({"law": "jkr"}, {"law": "dmt"}, own_checkpoint=lambda p: True)
        assert checkpoint_path(out).exists()
        same = found.already_finished({"law": "jkr"}, {"law": "jkr"}, own_checkpoint=lambda p: True)
    assert same == ("finished", out) and not checkpoint_path(out).exists()
    assert [r.getMessage() for r in caplog.records] == [
        f"{out}: already holds this finished thing: nothing to do"
    ]

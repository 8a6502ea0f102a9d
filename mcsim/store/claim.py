"""Claiming an output: what a run or a sweep does with the file it is asked to write.

:func:`mcsim.simulate` and :func:`mcsim.sweep` write the same way, in one sequence:

1. **claim** ``out`` (:func:`claim_output`): the path checked, its lock held, checked again
   under the lock (:mod:`mcsim.store.files`);
2. with ``resume``, **a finished result** at ``out`` is returned untouched when it is the one
   asked for, else refused naming the first input that differs (:meth:`Claim.already_finished`);
3. else **a checkpoint** beside it (``<stem>.partial<suffix>``) is continued when it holds the
   same inputs, else refused (:meth:`Claim.check_checkpoint`); no checkpoint: the work starts
   from the beginning, with a warning; without ``resume`` a checkpoint left there is removed;
4. the complete result is **written** atomically, then the checkpoint removed (:meth:`Claim.finish`).

What the file holds and how its inputs compare is the caller's: it passes the readers
and the inputs as dicts (:func:`mcsim.store.files.first_difference` names the first that
differs).
"""

from __future__ import annotations

import contextlib
import logging
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from mcsim._version import __version__
from mcsim.model.errors import ParameterError, RunFileError
from mcsim.store import files

log = logging.getLogger(__name__)


@dataclass
class Claim:
    """An output held for writing, and what a resume found there.

    Attributes
    ----------
    out : Path
        The output file; its lock is held while the claim's stack is open.
    partial : Path
        Its checkpoint, :func:`mcsim.store.files.checkpoint_path`.
    what : str
        What is written (``"run"``, ``"sweep"``), for the messages.
    finished : object or None
        With ``resume``: the complete result already at ``out`` (checksum verified).
    checkpoint : object or None
        With ``resume`` and no finished result: the checkpoint's state, to continue.
    checkpoint_attrs : dict
        The checkpoint's root attributes (empty without one).
    """

    out: Path
    partial: Path
    what: str
    finished: object = None
    checkpoint: object = None
    checkpoint_attrs: dict | None = None

    def already_finished(self, recorded: dict, asked: dict, *, own_checkpoint: Callable[[Path], bool],
                         seed_note: str = ""):  # fmt: skip
        """``finished``, if its ``recorded`` inputs are the ``asked`` ones: resuming it is a
        no-op (the file untouched; a checkpoint left beside it by a kill after the final write,
        ``own_checkpoint(partial)``, is removed). Otherwise a RunFileError naming the first
        input that differs. ``seed_note`` ends the notice (a seed taken from the file)."""
        differs = files.first_difference(recorded, asked)
        if differs:
            raise RunFileError(f"{self.out}: already holds a finished {self.what} with a different "
                               f"{differs}; use --overwrite to replace it or another --out")  # fmt: skip
        if self.partial.exists() and own_checkpoint(self.partial):
            self.partial.unlink()  # the finished result's own checkpoint: killed before removing it
        log.warning("%s: already holds this finished %s%s: nothing to do", self.out, self.what,
                    seed_note)  # fmt: skip
        return self.finished

    def check_checkpoint(self, recorded: dict, asked: dict) -> None:
        """Refuse to continue a checkpoint whose ``recorded`` inputs are not the ``asked`` ones."""
        differs = files.first_difference(recorded, asked)
        if differs:
            raise ParameterError(f"cannot resume {self.out}: its checkpoint {self.partial.name} "
                                 f"holds a {self.what} with a different {differs}")  # fmt: skip

    def finish(self, write: Callable[[Path], object]):
        """``write(out)`` (an atomic write of the complete result), then the checkpoint removed;
        what ``write`` returns."""
        result = write(self.out)
        self.partial.unlink(missing_ok=True)  # after the complete result is in place
        return result


def claim_output(
    stack: contextlib.ExitStack,
    out,
    *,
    overwrite: bool,
    resume: bool,
    what: str,
    read_finished: Callable[[Path], object],
    read_checkpoint: Callable[[Path], tuple[object, dict]],
) -> Claim:
    """Claim ``out`` for the life of ``stack`` and, with ``resume``, read what is there.

    Parameters
    ----------
    stack : contextlib.ExitStack
        Holds the lock of ``out`` until it closes.
    out : str or path-like
        The output file (:func:`mcsim.store.files.check_output_path`: an existing file, or
        another run's checkpoint, is refused unless ``overwrite`` or ``resume``).
    overwrite, resume : bool
        Start again (any checkpoint removed), or continue (see the module docstring).
    what : str
        ``"run"`` or ``"sweep"``, for the messages.
    read_finished : callable
        Reads a complete result from a path (verifying its checksum).
    read_checkpoint : callable
        Reads a checkpoint from a path: its state and its root attributes.

    Returns
    -------
    Claim

    Raises
    ------
    RunFileError
        The path cannot be written or is locked by another process; a finished result or
        checkpoint is damaged; the checkpoint holds a complete result or was written by
        another mcsim version.
    """
    out = files.check_output_path(out, overwrite=overwrite, resume=resume)
    stack.enter_context(files.lock(out))
    files.check_output_path(out, overwrite=overwrite, resume=resume)  # another may have finished
    partial = files.checkpoint_path(out)
    claim = Claim(out, partial, what, checkpoint_attrs={})
    if resume and not overwrite and out.exists():
        claim.finished = read_finished(out)
    elif resume and partial.exists():
        claim.checkpoint, attrs = read_checkpoint(partial)
        if attrs.get("complete"):
            raise RunFileError(f"{partial}: damaged checkpoint: it holds a complete {what}")
        if attrs.get("mcsim_version") != __version__:
            raise RunFileError(f"{partial}: written by mcsim {attrs.get('mcsim_version')}; "
                               "resume it with that version")  # fmt: skip
        claim.checkpoint_attrs = attrs
    elif resume:
        log.warning("%s: nothing to resume (no checkpoint %s): starting the %s from the beginning",
                    out, partial.name, what)  # fmt: skip
    else:
        partial.unlink(missing_ok=True)  # --overwrite: start again
    return claim

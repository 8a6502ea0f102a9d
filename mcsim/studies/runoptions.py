"""The options :func:`mcsim.simulate` and :func:`mcsim.sweep` share, checked as the command
line checks them (``--workers``, ``--checkpoint-every``), so that the Python API refuses
what ``mcsim simulate`` and ``mcsim sweep`` refuse, in a ParameterError naming the option."""

from __future__ import annotations

from mcsim.model.errors import ParameterError
from mcsim.model.params import check_range

#: Most worker threads or processes (``--workers``): more than any machine's cores only
#: slows a run down.
MAX_WORKERS = 1024


def check_workers(workers) -> int | None:
    """``workers`` if it is None (all cores) or an integer from 1 to :data:`MAX_WORKERS`."""
    if workers is None:
        return None
    if isinstance(workers, bool) or not isinstance(workers, int) or not 1 <= workers <= MAX_WORKERS:
        raise ParameterError(f"workers = {workers!r} is out of range "
                             f"(allowed: None or an integer from 1 to {MAX_WORKERS})")  # fmt: skip
    return workers


def check_checkpoint_every(seconds) -> float:
    """``seconds`` between checkpoints as a float: a number >= 0 (s)."""
    if isinstance(seconds, str):  # no unit table for times: a number, as --checkpoint-every
        raise ParameterError(f"checkpoint_every must be a number of seconds, got {seconds!r}")
    return check_range("checkpoint_every", seconds, "s", low=0.0, low_open=False)

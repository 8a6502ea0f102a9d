"""SIGINT (Ctrl-C) and SIGTERM (batch schedulers): the one owner of interruption.

Inside :func:`interruptible`, the first SIGINT or SIGTERM is recorded, not raised where
it lands: a run calls :func:`check` at safe points (between tasks, and at least every
0.1 s while it waits for one), which raises :class:`Interrupted`. The run then writes
its final checkpoint and cleans up while further signals are counted and otherwise
ignored, so that no second signal can break the cleanup (a hang in a thread pool's
shutdown, a temporary file left behind). The previous handlers are restored on exit.

Handlers can only be installed from the main thread; elsewhere, and inside an active
:func:`interruptible`, it does nothing (the outer one owns the signals). Only the
standard library is imported, so the CLI installs it before any heavy import.
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator

SIGNALS = (signal.SIGINT, signal.SIGTERM)

#: Signals received inside the active :func:`interruptible`, in order (None: not active).
_received: list[int] | None = None


class Interrupted(KeyboardInterrupt):
    """A run stopped by a signal.

    Attributes
    ----------
    signum : int
        The first signal received.
    exit_status : int
        128 + signum, the shell's convention (130 for SIGINT, 143 for SIGTERM).
    """

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum
        self.exit_status = 128 + signum


def _record(signum: int, frame) -> None:
    if _received is not None:
        _received.append(signum)


def check() -> None:
    """Raise :class:`Interrupted` if a signal arrived inside the active :func:`interruptible`."""
    if _received:
        raise Interrupted(_received[0])


def received() -> int | None:
    """The first signal received inside the active :func:`interruptible`, if any."""
    return _received[0] if _received else None


@contextlib.contextmanager
def interruptible() -> Iterator[None]:
    """Own SIGINT and SIGTERM for the ``with`` block (see the module docstring)."""
    global _received
    if _received is not None or threading.current_thread() is not threading.main_thread():
        yield
        return
    _received = []
    previous = {s: signal.signal(s, _record) for s in SIGNALS}
    try:
        yield
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
        _received = None

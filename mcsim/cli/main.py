"""The ``mcsim`` command line: a thin layer over the Python API.

Errors in the input print one line (``mcsim: error: ...``) and exit with status 2;
``--debug`` shows the traceback instead. Ctrl-C exits with status 130 and leaves no
partial output; SIGTERM the same with status 143. ``simulate`` (see
:mod:`mcsim.engine.interrupt`) keeps its progress in the checkpoint beside the run file, for
``--resume``.
"""

from __future__ import annotations

import argparse
import re
import shlex
import signal
import sys

from mcsim._version import __version__
from mcsim.cli import (
    adhesion,
    analytic,
    compare,
    contact,
    ingest,
    pads,
    paper,
    plot,
    report,
    show,
    simulate,
    sweep,
)
from mcsim.engine.interrupt import Interrupted
from mcsim.model.errors import MCSimError

#: The commands, in the order of ``mcsim --help``.
COMMANDS = (analytic, adhesion, paper, simulate, sweep, compare, show, plot, pads, ingest, contact,
            report)  # fmt: skip


# --- commands ----------------------------------------------------------------------------


# --- parser ------------------------------------------------------------------------------


#: An argument that starts like a negative number (``-1MPa``, ``-.5``, ``-1e3,0``, ``-inf``) is
#: a value, never an option: no option of mcsim starts with a digit, a point or ``inf``/``nan``.
_NEGATIVE_VALUE = re.compile(r"-(\.?\d|inf|nan)", re.IGNORECASE)


class _Parser(argparse.ArgumentParser):
    """argparse with the one-line error contract: ``mcsim: error: ...``, exit status 2.

    A value that starts like a negative number (``--pressure -1MPa``) is read as the option's
    value, to be refused by name if out of range, rather than as an unknown option
    (argparse takes only plain numbers such as ``-1`` or ``-.5`` for values).
    """

    def _parse_optional(self, arg_string):
        if _NEGATIVE_VALUE.match(arg_string):
            return None
        return super()._parse_optional(arg_string)

    def error(self, message: str):
        text = " ".join(message.split())  # argparse's messages may wrap
        self.exit(2, f"mcsim: error: {text}{self._suggestion(text)} (see: {self.prog} --help)\n")

    def _suggestion(self, text: str) -> str:
        """'; did you mean ...?' for a misspelled option or choice, else ''."""
        import difflib
        import re

        if m := re.match(r"unrecognized arguments: (\S+)", text):
            word, known = m[1].split("=")[0], self._option_strings()
            others = self._commands_with(word)
            if others:  # an option of other commands, not of this one
                command = self._command()
                return (f"; {word} is an option of mcsim {', '.join(others)}"
                        + (f", not of mcsim {command}" if command else ""))  # fmt: skip
        elif m := re.search(r"invalid choice: '([^']*)' \(choose from (.*)\)$", text):
            word, known = m[1], re.findall(r"'([^']*)'", m[2])
        else:
            return ""
        close = difflib.get_close_matches(word, known, n=1)
        return f"; did you mean {close[0]!r}?" if close else ""

    def _command_parsers(self) -> dict:
        """The commands' parsers by name (none for a command's own parser)."""
        for action in self._actions:
            if isinstance(action, argparse._SubParsersAction):
                return dict(action.choices)
        return {}

    def _commands_with(self, option: str) -> list[str]:
        """The commands that have ``option``."""
        return [name for name, p in self._command_parsers().items()
                if any(option in a.option_strings for a in p._actions)]  # fmt: skip

    def _command(self) -> str | None:
        """The command named in the arguments being parsed (:attr:`argv`), if any."""
        names = self._command_parsers()
        return next((a for a in getattr(self, "argv", None) or sys.argv[1:] if a in names), None)

    def _option_strings(self) -> list[str]:
        """Every option of this parser and of its commands (argparse reports an unknown
        option of a command from the top parser)."""
        parsers = [self]
        for action in self._actions:
            if isinstance(action, argparse._SubParsersAction):
                parsers += list(action.choices.values())
        return [s for p in parsers for a in p._actions for s in a.option_strings]


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="mcsim",
        description="Monte Carlo discrete-asperity simulator for adhesion and adhesional friction of rough surfaces.",
    )
    parser.add_argument("--version", action="version", version=f"mcsim {__version__}")
    parser.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    for command in COMMANDS:
        command.add_parser(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    parser.argv = argv
    try:
        args = parser.parse_args(argv)
    except SystemExit as done:  # --help, --version or a one-line usage error: its status
        return done.code if isinstance(done.code, int) else 2
    # the command line that outputs record: the one parsed (main([...]) in a notebook records
    # its own arguments, not the kernel's sys.argv)
    words = sys.argv[1:] if argv is None else argv
    args.command_line = shlex.join(["mcsim", *map(str, words)])
    try:
        return args.func(args)
    except KeyboardInterrupt as stop:  # Ctrl-C, or SIGTERM (console) outside simulate and sweep
        signum = stop.signum if isinstance(stop, Interrupted) else signal.SIGINT
        print(f"mcsim: interrupted ({signal.Signals(signum).name}); no output written",
              file=sys.stderr)  # fmt: skip
        return 128 + signum
    except BrokenPipeError:  # output piped into `head` and the like
        import os

        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except (MCSimError, OSError) as err:
        if args.debug:
            raise
        message = (
            str(err)
            if isinstance(err, MCSimError)
            else f"{err.filename or ''}: {err.strerror or err}"
        )
        print(f"mcsim: error: {message}", file=sys.stderr)
        return 2


#: Young collections between two full ones of the cyclic garbage collector in a command
#: (Python's default: 10). See :func:`console`.
FULL_COLLECTION_EVERY = 10_000


def terminate(signum: int, frame) -> None:
    """SIGTERM as Ctrl-C: :class:`~mcsim.engine.interrupt.Interrupted`, raised where the
    command is (``simulate`` and ``sweep`` own the signal while they run and save their
    progress first); the command ends with status 143 and one line, no output written."""
    raise Interrupted(signum)


def console() -> None:
    """Entry point of the ``mcsim`` command and ``python -m mcsim``.

    SIGTERM (a batch scheduler's, ``kill``) ends every command as Ctrl-C does
    (:func:`terminate`), with status 143. Once the exit status is decided, SIGINT and
    SIGTERM are ignored, so that a late signal can neither kill the interpreter while it
    exits nor print a traceback.

    The cyclic garbage collector leaves the start-up's objects alone: importing NumPy,
    SciPy, h5py and numba's registries makes ~10⁵ long-lived objects and hardly any
    garbage, yet each full collection traverses them all (≈0.1 s for the two a
    ``simulate`` start-up triggers), and the interpreter's last collection at exit
    once more (≈0.3 s). So a command runs full collections only after
    :data:`FULL_COLLECTION_EVERY` young ones (garbage that dies young, the bulk of
    it, is still collected at once), and once the exit status is decided everything is
    frozen (:func:`gc.freeze`): the process ends without traversing it. The API is
    unaffected; nothing here touches the numbers.
    """
    import gc

    young, middle, _ = gc.get_threshold()
    gc.set_threshold(young, middle, FULL_COLLECTION_EVERY)
    signal.signal(signal.SIGTERM, terminate)
    code = main()
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, signal.SIG_IGN)
    gc.freeze()
    raise SystemExit(code)


if __name__ == "__main__":
    console()

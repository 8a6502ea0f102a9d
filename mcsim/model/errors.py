"""The exceptions mcsim raises for bad input.

Every error is a :class:`MCSimError` (a :class:`ValueError`), so callers can catch
one type; the CLI prints its message on one line and exits non-zero.
"""


class MCSimError(ValueError):
    """Base class of every error mcsim raises for bad input or a bad file."""


class ParameterError(MCSimError):
    """A parameter is missing, non-finite or outside its allowed range."""


class UnitError(MCSimError):
    """A quantity carries an unknown unit or a unit of the wrong dimension."""


class RunFileError(MCSimError):
    """A run file cannot be written, or is not a readable mcsim run."""


class WorkerError(MCSimError):
    """A worker process of this machine ended abruptly (killed, out of memory, or a script
    that each spawned worker runs again): the machine's failure, not one input's, so a sweep
    raises it rather than recording it as one point's ``error``."""

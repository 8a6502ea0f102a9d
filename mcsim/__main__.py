import signal

from .cli import main

code = main()
for _signal in (signal.SIGINT, signal.SIGTERM):  # the exit status is decided: finish exiting
    signal.signal(_signal, signal.SIG_IGN)
raise SystemExit(code)

"""Closing ``--dask local`` is quiet (issue 33): no "Worker process still alive after 4.0
seconds, killing" per worker when its process is slow to exit (as many processes on few
cores are, each tearing down NumPy and numba). Here the worker is made slow to exit on
purpose: the nanny waits its 4 s and kills it."""

from __future__ import annotations

import os

import pytest


def _exit_slowly() -> None:
    import atexit
    import time

    atexit.register(time.sleep, 60)  # killed after the nanny's 4 s, long before this ends


def test_closing_a_local_cluster_that_kills_a_slow_worker_prints_no_warning(capfd, caplog):
    pytest.importorskip("distributed", reason="Dask (extra 'dask') not installed")
    from mcsim.engine.cluster import dask_client

    with dask_client("local", workers=1) as client:
        client.run(_exit_slowly)
    err = capfd.readouterr().err + caplog.text  # distributed's handler, or pytest's
    assert "still alive" not in err and "killing" not in err, err


def _warn_from_the_worker() -> None:
    import logging

    logging.getLogger("distributed.worker").warning("a worker's own warning")


def test_a_local_clusters_workers_print_no_warning_lines(capfd, caplog):
    # Ctrl-C during `mcsim report --dask local` cancels the workers' tasks, and each worker
    # warned "Async instruction ... ended with CancelledError" on stderr under the one line
    # "interrupted; no output written". A worker's warning stands for those here.
    pytest.importorskip("distributed", reason="Dask (extra 'dask') not installed")
    from mcsim.engine.cluster import dask_client

    with dask_client("local", workers=1) as client:
        client.run(_warn_from_the_worker)
    err = capfd.readouterr().err + caplog.text
    assert "a worker's own warning" not in err, err


_SCRIPT = """from mcsim.engine.cluster import process_pool
{guard}
    with process_pool(1) as submit:
        print("result", submit(abs, -1).result())
"""


@pytest.mark.parametrize("guard", ["if True:", 'if __name__ == "__main__":'])
def test_a_script_that_starts_worker_processes_gets_a_result_or_an_error_not_a_hang(
    tmp_path, guard
):
    # A spawned worker imports the script that started it: without the guard it starts
    # workers of its own and dies (multiprocessing.Pool would replace it forever: a hang).
    import subprocess
    import sys

    script = tmp_path / "script.py"
    script.write_text(_SCRIPT.format(guard=guard))
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                          timeout=120, cwd=tmp_path)  # fmt: skip
    if "__main__" in guard:
        assert done.returncode == 0 and done.stdout == "result 1\n", done.stderr
    else:
        assert done.returncode == 1, done.stderr
        assert "WorkerError: a worker process ended abruptly" in done.stderr


_KILLED = """import os, time
from mcsim.engine.cluster import process_pool
if __name__ == "__main__":
    with process_pool(1) as submit:
        print(submit(os.getpid).result(), flush=True)
        submit(time.sleep, 120)
        time.sleep(120)
"""


def _running(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] not in ("Z", "X")
    except FileNotFoundError:
        return False


@pytest.mark.skipif(not os.path.isdir("/proc/self"), reason="reads /proc (Linux)")
def test_a_worker_process_ends_with_its_parent_killed_outright(tmp_path):
    # SIGKILL of `mcsim report` (or the out-of-memory killer) cannot end its workers, and a
    # process pool's queues kept them waiting forever after their task: each now watches
    # its parent and ends with it, its task unfinished.
    import subprocess
    import sys
    import time

    script = tmp_path / "killed.py"
    script.write_text(_KILLED)
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True)
    worker = int(proc.stdout.readline())
    assert _running(worker)
    proc.kill()
    proc.wait(timeout=30)
    deadline = time.monotonic() + 15
    while _running(worker) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not _running(worker), "the worker outlived its killed parent"

"""The design-map kernel in a process of its own, and how close two runs of it must agree.

``python tests/designmap_checks.py IN.npz OUT.npz [IN2.npz OUT2.npz ...] [--from-cache]``
runs :func:`mcsim.engine.maps.designmap.jkr_summaries` on the inputs of each ``IN.npz`` in turn
(:func:`inputs`; with an environment where they hold ``hamaker``) and saves its outputs to
the ``OUT.npz`` after it; ``--from-cache`` then asserts that every function of the kernel
came from numba's on-disk cache. tests/engine/test_designmap.py and
test_designmap_environment.py run it with the interpreter (``NUMBA_DISABLE_JIT=1``) and in a
fresh cache (:func:`run_elsewhere`, :func:`run_each_elsewhere`).
"""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np

#: The kernel run by the interpreter, or compiled in another process, against the one
#: compiled here: the same arithmetic, rounded differently (the GW sums reassociated and
#: contracted under fast-math, another math library), so
#:
#: * curves: 1e-14 of their scale (a 32-node sum rounded in another order: ~32ε = 7e-15);
#: * turn: 3e-12 in h (each a Brent root within 1e-12 + 4ε|h| of the zero of loads that
#:   agree to rounding, so the two may stop on either side of it);
#: * pull-off, works of separation, hysteresis: 2e-10 relative (the retraction moves with
#:   the turn, δ_max = σ(s − turn): up to 40 times the turn's 3e-12, as measured in
#:   tests/engine/test_designmap_environment.py; the pull-off is a minimum: second order);
#: * pull-off location: 1e-7 in h (the bounded minimiser stops within 2(√ε x + 1e-8/3) of
#:   the minimum, x < 1 its distance from the bracket's start: 3.7e-8 each, 7.4e-8 apart).
#:
#: Measured: 3e-14 (summary), 3e-8 (location), 6e-16 (curves).
AGREE = {"curve": 1e-14, "turn": 3e-12, "summary": 2e-10, "h_pull_off": 1e-7}

_ARGUMENTS = ("sigma", "R", "eta", "E_star", "K", "gamma", "h")
_ENVIRONMENT = ("hamaker", "rh", "contact_angle", "cutoff")


def inputs(points, h, environments=None) -> dict[str, np.ndarray]:
    """The arguments of ``jkr_summaries`` at ``points`` ((surface, material) pairs) and
    separations ``h``, as arrays; with ``environments`` (one per point) their fields."""
    s, m = zip(*points)
    out = {"sigma": [x.sigma for x in s], "R": [x.R for x in s], "eta": [x.eta for x in s],
           "E_star": [x.E_star for x in m], "K": [x.K for x in m], "gamma": [x.gamma for x in m],
           "h": h}  # fmt: skip
    if environments is not None:
        out |= {k: [getattr(e, k) or 0.0 for e in environments] for k in _ENVIRONMENT}
    return {k: np.asarray(v, dtype=float) for k, v in out.items()}


def summaries(arguments: dict) -> dict[str, np.ndarray]:
    """``jkr_summaries`` at ``arguments`` (:func:`inputs`), in this process."""
    from mcsim.engine.maps.designmap import jkr_summaries
    from mcsim.physics.environment import Environment

    environment = None
    if "hamaker" in arguments:
        fields = zip(*(arguments[k] for k in _ENVIRONMENT))
        environment = [Environment(hamaker=a or None, rh=rh, contact_angle=t, cutoff=c)
                       for a, rh, t, c in fields]  # fmt: skip
    return jkr_summaries(*(arguments[k] for k in _ARGUMENTS), environment=environment)


def run_elsewhere(arguments: dict, folder, name: str, *options, **environ) -> dict:
    """:func:`summaries` in a fresh Python process with the environment variables
    ``environ`` (files in ``folder``); ``options``: ``--from-cache``."""
    return run_each_elsewhere([arguments], folder, name, *options, **environ)[0]


def run_each_elsewhere(batches: list[dict], folder, name: str, *options, **environ) -> list[dict]:
    """:func:`summaries` of each of ``batches`` in turn, all in one fresh Python process (one
    start-up, and the functions compiled for one batch not compiled again for the next), as
    :func:`run_elsewhere`."""
    files = []
    for i, arguments in enumerate(batches):
        np.savez(folder / f"{name}-{i}-in.npz", **arguments)
        files += [folder / f"{name}-{i}-in.npz", folder / f"{name}-{i}.npz"]
    subprocess.run([sys.executable, __file__, *map(str, files), *options],
                   env=os.environ | environ, check=True)  # fmt: skip
    return [dict(np.load(out)) for out in files[1::2]]


def assert_agree(got: dict, expected: dict) -> None:
    """Every output of ``got`` within :data:`AGREE` of ``expected``."""
    assert sorted(got) == sorted(expected)
    for k, v in expected.items():
        v = np.asarray(v, dtype=float)
        if v.ndim == 2:  # curves: of their scale
            scale = np.max(np.abs(v), axis=1, keepdims=True)
            assert np.all(np.abs(got[k] - v) <= AGREE["curve"] * scale), k
        elif k in ("turn", "h_pull_off"):
            np.testing.assert_allclose(got[k], v, rtol=0, atol=AGREE[k], err_msg=k)
        elif k == "status":
            np.testing.assert_array_equal(got[k], v, err_msg=k)
        else:
            # AGREE: the reason of each tolerance sits above its definition
            np.testing.assert_allclose(got[k], v, rtol=AGREE["summary"], atol=0, err_msg=k)


def main() -> None:
    files = [a for a in sys.argv[1:] if a != "--from-cache"]
    for source, target in zip(files[::2], files[1::2], strict=True):
        np.savez(target, **summaries(dict(np.load(source))))
    if "--from-cache" in sys.argv[1:]:
        from mcsim.engine.maps.designmap import _kernels

        # a function compiled here, not loaded, counts a miss
        assert not any(k.stats.cache_misses for k in _kernels()), "compiled again"
        assert any(k.stats.cache_hits for k in _kernels()), "not loaded from the cache"


if __name__ == "__main__":
    main()

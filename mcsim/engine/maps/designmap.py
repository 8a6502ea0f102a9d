"""Compiled adhesion summaries of many design points at once: the fast path of analytic sweeps.

:func:`mcsim.physics.adhesion.adhesion_summary` finds, for one point, the separation of
zero approach load, the pull-off (the most tensile retraction load) and the work of
separation and hysteresis, each step a NumPy quadrature driven from Python by SciPy's root
finder and minimiser. :func:`jkr_summaries` does the same steps for a whole batch of points
of the ``jkr`` law set on Gaussian heights in one compiled call (numba, no per-point
Python), with the same law functions (:mod:`mcsim.physics.laws.jkr`). The kernel is plain
numba functions in two modules, each with its steps, rules and measured accuracy in its
docstring:

* :mod:`mcsim.engine.maps.kernel`: the contact alone (``batch``): the GW integrals, the
  zero-load turn, the work of separation and hysteresis, the pull-off;
* :mod:`mcsim.engine.maps.environment`: with an environment (``batch_net``; van der Waals
  attraction and capillary condensation on the summits' caps and across the open gaps
  between them, over Gaussian heights, :mod:`mcsim.physics.environment`), the same steps on the net load, and the parameters
  and outputs of the environment (:func:`~mcsim.engine.maps.environment.environment_params`).

This module runs them. They are imported, and their on-disk cache enabled, at the first
call (:func:`_kernels`; numba compiles them once, 10–40 s, then every process loads them
from ``<mcsim.engine.kernels.cache_dir()>/designmap``, see
:func:`mcsim.engine.maps.kernel.enable_cache`), so that importing this module loads no numba.
The same first call removes what earlier versions left in the cache: the kernel as
generated modules, ``kernels/mcsim_designmap_jkr_*``, and numba's files of them
(:func:`_remove_generated_modules`).

The process in which numba compiles the kernel gets numbers slightly apart from those of
every process that loads it from the cache, which agree bit for bit among themselves (numba
links the separately compiled fast-math functions, the GW integrals, differently in the two
cases). Measured: the turn, pull-off, works and hysteresis 3e-14 relative at most, the curves
1e-16 of their scale, the pull-off's location 3e-8 in h (its minimiser stops within 1e-8
plus √ε times the bracket's width): within every tolerance of the tests, which check it
(tests/designmap_checks.py). So the first sweep after an install, or after the kernel
changed, may differ from later ones by that much; nothing hides it (earlier versions
compiled the kernel in a child process for that).
"""

from __future__ import annotations

import contextlib
import functools
import math
import threading

import numpy as np

from mcsim.engine.kernels import cache_dir
from mcsim.engine.maps.status import NO_REST, OK, REFERENCE
from mcsim.model.params import Surface
from mcsim.physics.adhesion import NODES
from mcsim.physics.environment import Environment
from mcsim.physics.gapheights import nayak_heights
from mcsim.physics.surfaceenvironment import contact_adhesion

# The entry point, and the statuses of its points.
__all__ = ["NO_REST", "OK", "REFERENCE", "jkr_summaries"]


_LOCK = threading.Lock()


def _kernels():
    """The kernel's entry points, dry and with an environment, their cache enabled, and
    the stale generated modules removed: once per process (module docstring)."""
    with _LOCK:
        return _first_use()


@functools.cache
def _first_use():
    from mcsim.engine.maps.environment import batch_net
    from mcsim.engine.maps.kernel import batch, enable_cache

    _remove_generated_modules()
    enable_cache(batch, batch_net)
    return batch, batch_net


def _remove_generated_modules() -> None:
    """Remove the design-map kernel that earlier versions of mcsim generated into the cache:
    ``kernels/mcsim_designmap_jkr_*`` (the modules and their markers) and numba's files of
    them in ``kernels/__pycache__`` (module docstring)."""
    folder = cache_dir() / "kernels"
    for path in [*folder.glob("mcsim_designmap_jkr_*"),
                 *folder.glob("__pycache__/mcsim_designmap_jkr_*")]:  # fmt: skip
        with contextlib.suppress(OSError):  # removed by another process, or not ours to remove
            path.unlink()


def jkr_summaries(sigma, R, eta, E_star, K, gamma, h, turn=None, environment=None, rq=None,
                  summit_offset=None) -> dict[str, np.ndarray]:  # fmt: skip
    """Approach curves and adhesion summaries of the ``jkr`` law set at many points at once.

    Parameters
    ----------
    sigma, R, eta : array_like
        Per point: standard deviation of the summit heights (m, Gaussian), summit radius
        (m), summit density (1/m²).
    E_star, K, gamma : array_like
        Per point: contact modulus E* and K = 4E*/3 (Pa), work of adhesion w (J/m²).
    h : array_like
        Separations d/σ of the approach curves.
    turn : float, optional
        Closest approach h_turn before retraction; default the zero of the approach load.
    environment : Environment or sequence of Environment, optional
        For every point, or one per point: van der Waals and capillary attraction on the
        summits' caps and across the open gaps of Gaussian heights, as
        ``adhesion_summary(..., environment=...)`` (module docstring). None (default): the
        contact alone.
    rq, summit_offset : array_like, optional
        Per point, with ``environment``: Rq and the summit plane's offset y_s of the heights
        about the mean plane, m (:func:`mcsim.physics.gapheights.gap_heights`); default both
        Nayak's estimates from σ, R, η (:func:`mcsim.physics.gapheights.nayak_heights`).

    Returns
    -------
    dict of str to ndarray
        ``load`` (load/(A_n K)) and ``area`` (A_r/A_n), shape (points, len(h)); per point
        ``turn``, ``pull_off`` (force/(A_n K)), ``h_pull_off``, ``work_of_separation`` and
        ``hysteresis`` (J/m²), and ``status`` (:data:`OK`, :data:`NO_REST`: the surfaces
        rest apart, summary zero and ``turn`` the top of the summits, or
        :data:`REFERENCE`: give the point to :func:`mcsim.physics.adhesion.adhesion_summary`).
        With ``environment``: ``load`` is the net load, ``vdw`` and ``capillary`` the
        attractions per nominal area/K (as :func:`mcsim.gw_curves`), and per point
        ``work_of_separation_contact``, ``work_of_separation_vdw`` and
        ``work_of_separation_capillary`` (J/m²; with the surfaces in contact at rest their
        sum is ``work_of_separation``), ``kelvin_radius``, ``rq`` and ``summit_offset`` (m).
    """
    from mcsim.engine.maps.environment import S_NODES_NET, environment_outputs, environment_params
    from mcsim.engine.maps.kernel import S_NODES, gauss_rule
    from mcsim.physics.laws.jkr import reduced_constants

    sigma, R, eta, E_star, K, gamma = np.broadcast_arrays(
        *(np.atleast_1d(np.asarray(x, dtype=float)) for x in (sigma, R, eta, E_star, K, gamma))
    )
    if isinstance(environment, Environment):
        environment = [environment] * sigma.size
    if environment is not None:  # one interface: the contact law carries w less van der Waals
        gamma = np.array([contact_adhesion(g, e) for g, e in zip(gamma, environment)])
    params = np.empty((sigma.size, 7))
    for i in range(sigma.size):
        c = reduced_constants(R[i], E_star[i], gamma[i])
        params[i] = (c["delta_c"], c["jkr_kappa"], c["jkr_t_c"], c["jkr_hertz"],
                     c["jkr_adhesion"], c["jkr_area_unit"], eta[i])  # fmt: skip
    if environment is not None:
        if rq is None or summit_offset is None:
            rq, summit_offset, _ = zip(*map(nayak_heights, sigma, R, eta))
        rq, summit_offset = (np.broadcast_to(np.asarray(x, dtype=float), sigma.shape)
                             for x in (rq, summit_offset))  # fmt: skip
        surfaces = [Surface(*x, rq=q, summit_offset=y)
                    for *x, q, y in zip(sigma, R, eta, rq, summit_offset)]  # fmt: skip
        params = np.hstack([params, environment_params(environment, surfaces, K)])
    h = np.ascontiguousarray(h, dtype=float)
    turns = np.full(sigma.size, math.nan if turn is None else float(turn))
    curves = np.empty((sigma.size, 2 if environment is None else 4, h.size))
    summary = np.empty((sigma.size, 5))
    status = np.empty(sigma.size, dtype=np.int64)
    dry, net = _kernels()
    kernel, s_nodes = (dry, S_NODES) if environment is None else (net, S_NODES_NET)
    kernel(np.ascontiguousarray(sigma), np.ascontiguousarray(eta / K), params, turns, h,
           *gauss_rule(s_nodes), *np.polynomial.legendre.leggauss(NODES), curves, summary, status)  # fmt: skip
    scale = K * sigma  # load·K is force per nominal area; dd = σ dh
    out = {
        "load": curves[:, 0],
        "area": curves[:, 1],
        "turn": summary[:, 0],
        "pull_off": summary[:, 1],
        "h_pull_off": summary[:, 2],
        "work_of_separation": scale * summary[:, 3],
        "hysteresis": scale * summary[:, 4],
        "status": status,
    }
    if environment is not None:
        out |= environment_outputs(environment, surfaces, out, curves)
    return out

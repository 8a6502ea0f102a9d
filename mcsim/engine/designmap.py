"""Compiled adhesion summaries of many design points at once: the fast path of analytic sweeps.

:func:`mcsim.physics.adhesion.adhesion_summary` finds, for one point, the separation of
zero approach load, the pull-off (the most tensile retraction load) and the work of
separation and hysteresis, each step a NumPy quadrature driven from Python by SciPy's root
finder and minimiser. :func:`jkr_summaries` does the same steps for a whole batch of points
of the ``jkr`` law set on Gaussian heights in one compiled call (numba, no per-point
Python), with the same law functions (:mod:`mcsim.physics.laws.jkr`). The kernel is in two
modules, each with its steps, rules and measured accuracy in its docstring:

* :mod:`mcsim.engine.mapkernel`: the contact alone (``_batch``): the GW integrals, the
  zero-load turn, the work of separation and hysteresis, the pull-off;
* :mod:`mcsim.engine.mapenvironment`: with an environment (``_batch_net``; van der Waals
  attraction and capillary condensation across the gaps of Gaussian heights,
  :mod:`mcsim.physics.environment`), the same steps on the net load, and the parameters
  and outputs of the environment (:func:`~mcsim.engine.mapenvironment.environment_params`).

This module compiles them and runs them. The kernel source is compiled once and cached on
disk like the Monte Carlo kernel (:func:`_compiled`: a generated module whose name carries a
hash of every source it runs). The process in which numba compiles it would get numbers up
to 5e-14 (relative) apart from every process that loads it from the cache, so it is
compiled in a child process and loaded (:func:`_kernel`): the first sweep after an install
gives the same bits as every later one. (Inlining the fast-math callees also makes the two
agree, but without their flags the batch runs at half the speed and compiles in 18 s
instead of 12, 38 instead of 16 with the environment; all-inlined with fast-math, 36 and
95 s.)
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import inspect
import math
import os
import re
import subprocess
import sys
import threading

import numpy as np

from mcsim.engine import mapenvironment, mapkernel
from mcsim.engine.kernels import generated_module, law_source, numba_version
from mcsim.engine.mapenvironment import (
    _attraction,
    _attractions,
    _batch_net,
    _capillary,
    _environment_outputs,
    _gap_moments,
    _ndtr,
    _net_load,
    _point_net,
    _zero_load_turn_net,
    environment_params,
)
from mcsim.engine.mapkernel import (
    NO_REST,
    OK,
    REFERENCE,
    S_NODES,
    _batch,
    _load,
    _minimum,
    _point,
    _retraction,
    _root,
    _rule,
    _zero_load_turn,
    gw_load,
)
from mcsim.physics.adhesion import NODES
from mcsim.physics.environment import Environment
from mcsim.physics.gapheights import nayak_heights
from mcsim.physics.laws.jkr import jkr_area, jkr_load

# The entry point, and the statuses of its points (defined with the kernel that sets them).
__all__ = ["NO_REST", "OK", "REFERENCE", "jkr_summaries"]


#: The kernel's functions, in the order the generated module defines them.
_FUNCTIONS = (gw_load, _load, _root, _minimum, _zero_load_turn, _retraction, _point, _batch,
              _gap_moments, _ndtr, _capillary, _attractions, _attraction, _net_load,
              _zero_load_turn_net, _point_net, _batch_net)  # fmt: skip
#: Functions compiled a second time on the net load: each name in their source replaced.
_NET_VARIANTS = (_root, _minimum)
_NET_NAMES = {"_load": "_net_load", "_root": "_root_net", "_minimum": "_minimum_net"}
_COMPILE_LOCK = threading.Lock()


def _constants() -> dict:
    """The module constants the kernel reads, by name, from :mod:`~mcsim.engine.mapkernel` and
    :mod:`~mcsim.engine.mapenvironment` (their order is the generated text's, hence its hash)."""
    names = ("APPROACH_PANELS", "GAUSSIAN_TOP", "GRID", "H_TOLERANCE", "NO_REST", "OK", "PANELS",
             "REFERENCE", "VDW_TAIL", "VDW_SPREAD", "BLOCK", "P_VDW", "P_RQ", "P_CUTOFF", "P_OFFSET", "P_LAPLACE", "P_GAP",
             "P_TOP", "P_K", "_SQRT_2PI", "_TAIL")  # fmt: skip
    namespace = vars(mapkernel) | vars(mapenvironment)
    return {k: namespace[k] for k in names}


#: Set in the child process that compiles the kernel (:func:`_kernel`).
_CHILD = "MCSIM_DESIGNMAP_COMPILE"


def _kernel(entry: str):
    """The entry point ``entry`` (``_batch`` or ``_batch_net``) of the compiled module, run
    from numba's on-disk cache.

    The process in which numba compiles the kernel gets numbers up to 5e-14 (relative)
    apart from those of every process that loads it from the cache, which agree bit for
    bit among themselves (numba links the separately compiled fast-math callees differently
    in the two cases). So that the first sweep after an install gives the same bits as
    every later one, a kernel not yet compiled into the cache (no marker beside the
    generated module) is compiled in a child process (:func:`_compile_in_child`) and then
    loaded here. Should the child fail (a cache that cannot be written, say), the kernel is
    compiled here, as numba would.
    """
    with _COMPILE_LOCK:
        module = _compiled()
        marker = f"{module.__file__}.{entry}.compiled"
        if not os.path.exists(marker) and _CHILD not in os.environ:
            code = f"from mcsim.engine.designmap import _compile_in_child; _compile_in_child({entry!r})"
            path = os.pathsep.join(p for p in sys.path if isinstance(p, str))  # as imported here
            env = os.environ | {_CHILD: "1", "PYTHONPATH": path}
            with contextlib.suppress(subprocess.TimeoutExpired):  # then compiled here
                subprocess.run([sys.executable, "-c", code], env=env, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL, check=False, timeout=600)  # fmt: skip
        return getattr(module, entry)


def _compile_in_child(entry: str) -> None:
    """Compile ``entry`` into the on-disk cache by one tiny batch (or find it there), then
    leave its marker."""
    with_environment = entry == "_batch_net"
    environment = Environment(hamaker=1e-19, rh=0.5) if with_environment else None
    jkr_summaries([1e-9], [1e-6], [1e13], [1e11], [4e11 / 3], [0.1], [1.0, 0.0],
                  environment=environment)  # fmt: skip
    # Compiled into the cache, or found there (an earlier mcsim's, or another process's).
    open(f"{_compiled().__file__}.{entry}.compiled", "w").close()


def _net_source(f) -> str:
    """The source of ``f`` renamed to its net-load variant (:data:`_NET_NAMES`)."""
    text = inspect.getsource(f)
    for old, new in _NET_NAMES.items():
        text = re.sub(rf"\b{old}\(", f"{new}(", text)
    return text


@functools.cache
def _compiled():
    """The module of ``_batch`` and ``_batch_net``, compiled by numba with the JKR law
    functions inlined, cached on disk.

    The generated module holds the source of every function of :data:`_FUNCTIONS` and the
    net-load variants of :data:`_NET_VARIANTS`; its name carries a hash of those sources,
    the law functions' and numba's version, so the on-disk cache is reused across
    processes and never goes stale.
    """
    options = 'nogil=True, cache=True, error_model="numpy"'
    # The sums over the s nodes may be reordered (vectorised); NaN (the turn not given)
    # is tested outside them, so no flag that assumes it away.
    fast = options + ', fastmath={"reassoc", "contract", "nsz"}'
    law = 'inline="always", error_model="numpy"'
    parts = [
        '"""Generated by mcsim.engine.designmap; do not edit."""\n',
        "import math\n\nimport numba\nimport numpy as np\n",
        "from mcsim.engine.kernels import compile_law",
        "from mcsim.physics.laws.jkr import jkr_area, jkr_load",
        # numba freezes globals into the compiled code: their values are written here, so
        # that the hash below changes with them
        *(f"{k} = {v!r}" for k, v in _constants().items()),
        *(f"{k} = np.array({getattr(mapenvironment, k).tolist()!r})" for k in ("VDW_U", "VDW_W")),
        "",
        f"load_law = compile_law(jkr_load, {law})",
        f"area_law = compile_law(jkr_area, {law})\n",
    ]
    for f in _FUNCTIONS:
        flags = fast if f in (gw_load, _load) else options
        parts += [inspect.getsource(f), f"{f.__name__} = numba.njit({flags})({f.__name__})\n"]
    for f in _NET_VARIANTS:
        name = _NET_NAMES[f.__name__]
        parts += [_net_source(f), f"{name} = numba.njit({options})({name})\n"]
    text = "\n".join(parts)
    sources = [text, law_source(jkr_load), law_source(jkr_area), numba_version()]
    digest = hashlib.sha256("\n".join(sources).encode()).hexdigest()[:16]
    return generated_module(f"mcsim_designmap_jkr_{digest}", text)


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
        For every point, or one per point: van der Waals and capillary attraction across the
        gaps of Gaussian heights, as ``adhesion_summary(..., environment=...)`` (module
        docstring). None (default): the contact alone.
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
    from mcsim.physics.laws.jkr import reduced_constants

    sigma, R, eta, E_star, K, gamma = np.broadcast_arrays(
        *(np.atleast_1d(np.asarray(x, dtype=float)) for x in (sigma, R, eta, E_star, K, gamma))
    )
    params = np.empty((sigma.size, 7))
    for i in range(sigma.size):
        c = reduced_constants(R[i], E_star[i], gamma[i])
        params[i] = (c["delta_c"], c["jkr_kappa"], c["jkr_t_c"], c["jkr_hertz"],
                     c["jkr_adhesion"], c["jkr_area_unit"], eta[i])  # fmt: skip
    if environment is not None:
        if isinstance(environment, Environment):
            environment = [environment] * sigma.size
        if rq is None or summit_offset is None:
            rq, summit_offset, _ = zip(*map(nayak_heights, sigma, R, eta))
        rq, summit_offset = (np.broadcast_to(np.asarray(x, dtype=float), sigma.shape)
                             for x in (rq, summit_offset))  # fmt: skip
        params = np.hstack([params, environment_params(environment, rq, summit_offset, sigma, K)])
    h = np.ascontiguousarray(h, dtype=float)
    turns = np.full(sigma.size, math.nan if turn is None else float(turn))
    curves = np.empty((sigma.size, 2 if environment is None else 4, h.size))
    summary = np.empty((sigma.size, 5))
    status = np.empty(sigma.size, dtype=np.int64)
    kernel = _kernel("_batch" if environment is None else "_batch_net")
    kernel(np.ascontiguousarray(sigma), np.ascontiguousarray(eta / K), params, turns, h,
           *_rule(S_NODES), *np.polynomial.legendre.leggauss(NODES), curves, summary, status)  # fmt: skip
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
        out |= _environment_outputs(environment, params, out, curves, sigma)
    return out

"""The Monte Carlo engine: explicit summit populations on finite patches.

A run is ``realizations`` independent patches of nominal area A. Each patch holds N
summits (N ~ Poisson(ηA), or N = round(ηA) fixed). Only summits above the lowest
separation h_min can touch at any separation of the sweep, so the engine draws their
number exactly (Binomial(N, S(h_min)), or Poisson thinning) and their heights from
the distribution truncated to s > h_min: the same law as sampling all N, far less
work at high h_min.

Reproducibility: heights are drawn and summed in fixed blocks of :data:`BLOCK`
summits. Block b of realization r draws from its own stream
``SeedSequence(entropy, spawn_key=(r, 1 + b))`` (the counts use ``(r, 0)``); these are
exactly the children ``SeedSequence(entropy).spawn(...)`` would make. Per-block partial
sums are combined in block order. The result is therefore bit-identical for any
chunk size and any number of workers.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

import numpy as np

from .errors import ParameterError
from .kernels import SUM_COLUMNS, block_sums
from .laws import get_law_set
from .params import Material, Surface, check_range

#: Summits per random stream and per partial sum. Part of the reproducibility contract:
#: changing it changes the numbers.
BLOCK = 1 << 16

#: Default number of summits handled by one task (a whole number of blocks).
DEFAULT_CHUNK = 1 << 20

COUNT_MODES = ("poisson", "fixed")


@dataclass(frozen=True)
class MonteCarloSpec:
    """Everything that defines a Monte Carlo run (and so its numbers).

    Parameters
    ----------
    surface : Surface
        Summit population.
    material : Material
        Material pair.
    h : ndarray
        Dimensionless separations d/σ, any order.
    area : float
        Nominal area of one patch, m².
    realizations : int
        Number of independent patches.
    entropy : int
        Seed entropy of the root :class:`numpy.random.SeedSequence`.
    law : str
        Law-set name.
    count : {"poisson", "fixed"}
        N ~ Poisson(ηA) or N = round(ηA).
    """

    surface: Surface
    material: Material
    h: np.ndarray
    area: float
    realizations: int
    entropy: int
    law: str = "seed"
    count: str = "poisson"

    def __post_init__(self) -> None:
        h = np.atleast_1d(np.asarray(self.h, dtype=float))
        if h.ndim != 1 or h.size == 0:
            raise ParameterError("h must be a non-empty list of separations")
        if not np.all(np.isfinite(h)):
            raise ParameterError(f"h must be finite, got {h[~np.isfinite(h)][0]!r}")
        object.__setattr__(self, "h", h)
        object.__setattr__(self, "area", check_range("area", self.area, "m^2", low=0))
        if (
            isinstance(self.realizations, bool)
            or not isinstance(self.realizations, int | np.integer)
            or self.realizations < 1
        ):
            raise ParameterError(
                f"realizations = {self.realizations!r} is out of range (allowed: integer >= 1)"
            )
        if self.count not in COUNT_MODES:
            raise ParameterError(f"count = {self.count!r} is not one of {', '.join(COUNT_MODES)}")
        if self.count == "fixed" and round(self.surface.eta * self.area) < 1:
            raise ParameterError(
                f"area = {self.area!r} m^2 holds {self.surface.eta * self.area:.3g} summits: "
                "round(eta*area) must be >= 1 for count='fixed'"
            )
        get_law_set(self.law)

    @property
    def d(self) -> np.ndarray:
        """Separations in m."""
        return self.h * self.surface.sigma

    @property
    def expected_summits(self) -> float:
        """E[N] per patch."""
        n = self.surface.eta * self.area
        return float(round(n)) if self.count == "fixed" else n


@dataclass(frozen=True)
class PatchPlan:
    """The summit counts of one realization (drawn before any height)."""

    n_summits: int
    n_above: int

    @property
    def n_blocks(self) -> int:
        return -(-self.n_above // BLOCK)

    def block_size(self, b: int) -> int:
        return min(BLOCK, self.n_above - b * BLOCK)


def _stream(entropy: int, *key: int) -> np.random.Generator:
    return np.random.default_rng(np.random.SeedSequence(entropy, spawn_key=key))


def plan_patch(spec: MonteCarloSpec, r: int) -> PatchPlan:
    """Draw N and the number of summits above h_min for realization ``r``."""
    rng = _stream(spec.entropy, r, 0)
    p = float(spec.surface.heights.sf(spec.h.min()))
    lam = spec.surface.eta * spec.area
    if spec.count == "fixed":
        n = round(lam)
        return PatchPlan(n, int(rng.binomial(n, p)))
    above = int(rng.poisson(lam * p))
    below = int(rng.poisson(lam * (1 - p)))
    return PatchPlan(above + below, above)


def sample_block(spec: MonteCarloSpec, plan: PatchPlan, r: int, b: int) -> np.ndarray:
    """Heights (m) of block ``b`` of realization ``r``: summits above h_min only."""
    rng = _stream(spec.entropy, r, 1 + b)
    s = spec.surface.heights.sample_above(plan.block_size(b), float(spec.h.min()), rng)
    return s * spec.surface.sigma


@dataclass
class EnsembleSums:
    """Raw Monte Carlo totals of a run.

    Attributes
    ----------
    spec : MonteCarloSpec
        The run definition.
    n_summits : ndarray, shape (R,)
        N of each patch.
    sums : ndarray, shape (R, M, 10)
        Per realization and separation (in the order of ``spec.h``): the columns of
        :data:`mcsim.kernels.SUM_COLUMNS`, forces in N.
    heights : list of ndarray or None
        Sampled heights above h_min (m) per realization, when kept.
    """

    spec: MonteCarloSpec
    n_summits: np.ndarray
    sums: np.ndarray
    heights: list[np.ndarray] | None = field(default=None, repr=False)


def _tasks(plans: list[PatchPlan], chunk_blocks: int) -> Iterator[tuple[int, int, int]]:
    for r, plan in enumerate(plans):
        for start in range(0, plan.n_blocks, chunk_blocks):
            yield r, start, min(start + chunk_blocks, plan.n_blocks)


def run_sums(
    spec: MonteCarloSpec,
    *,
    workers: int = 1,
    chunk_size: int = DEFAULT_CHUNK,
    keep_heights: bool = False,
    progress: Callable[[int], None] | None = None,
) -> EnsembleSums:
    """Sample every patch of ``spec`` and sum the per-summit laws at every separation.

    Parameters
    ----------
    spec : MonteCarloSpec
        The run.
    workers : int
        Threads running tasks (the kernel and the samplers release the GIL).
    chunk_size : int
        Summits per task, rounded up to whole blocks; does not change the numbers.
    keep_heights : bool
        Keep the sampled heights (memory grows with N).
    progress : callable, optional
        Called with the number of summits finished after each task.

    Returns
    -------
    EnsembleSums
    """
    if workers < 1:
        raise ParameterError(f"workers = {workers!r} is out of range (allowed: integer >= 1)")
    if chunk_size < 1:
        raise ParameterError(f"chunk_size = {chunk_size!r} is out of range (allowed: integer >= 1)")
    law = get_law_set(spec.law)
    args = law.arguments(spec.surface, spec.material)
    order = np.argsort(-spec.d, kind="stable")
    d_desc = spec.d[order]
    plans = [plan_patch(spec, r) for r in range(spec.realizations)]
    chunk_blocks = max(1, math.ceil(chunk_size / BLOCK))

    def task(item: tuple[int, int, int]):
        r, start, stop = item
        blocks = [sample_block(spec, plans[r], r, b) for b in range(start, stop)]
        partial = [block_sums(z, d_desc, law, args) for z in blocks]
        return item, partial, (blocks if keep_heights else None)

    sums_desc = np.zeros((spec.realizations, spec.d.size, len(SUM_COLUMNS)))
    kept: list[list[np.ndarray]] = [[] for _ in plans]
    with ThreadPoolExecutor(max_workers=workers) as pool:
        # map() yields in submission order: partial sums are added in block order.
        for (r, start, stop), partial, blocks in pool.map(task, _tasks(plans, chunk_blocks)):
            for part in partial:
                sums_desc[r] += part
            if blocks is not None:
                kept[r].extend(blocks)
            if progress is not None:
                progress(sum(plans[r].block_size(b) for b in range(start, stop)))
    sums = np.empty_like(sums_desc)
    sums[:, order] = sums_desc  # back to the order of spec.h
    heights = [np.concatenate(k) if k else np.empty(0) for k in kept] if keep_heights else None
    return EnsembleSums(spec, np.array([p.n_summits for p in plans]), sums, heights)

"""The tilted law of a pad's summits above the cut, its likelihood ratio and its
cross-entropy fit: the sampling law of :mod:`mcsim.studies.tail` (whose docstring derives it)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: Smoothing of the fitted tilt: new = SMOOTHING · fit + (1 − SMOOTHING) · previous.
SMOOTHING = 0.7
#: Depth of the cut below the mean-field turn, in σ: the summits above it are tilted.
CUT = 1.0
#: Width of the height bins of the tilt, in σ, and their number (the last one open above).
BIN = 0.25
BINS = 16
#: Smallest ratio of tilted to nominal intensity (keeps the tilted law covering the event).
RATIO_FLOOR = 0.01


@dataclass(frozen=True)
class Tilt:
    """The tilted law of a pad's summits above the cut (:mod:`mcsim.studies.tail`).

    Attributes
    ----------
    ratio : tuple of float
        r_k, the tilted intensity over the nominal one in each height bin above the cut
        (:data:`BINS` bins of :data:`BIN` σ from the cut, the last one open); 1: nominal.
    """

    ratio: tuple[float, ...]


def cut(spec, turn: float) -> float:
    """The cut s_c = max(s_min, h̄ − :data:`CUT`) (σ) above which summits are tilted."""
    return max(spec.s_min, turn - CUT)


class Law:
    """The nominal and tilted laws of a pad's summits (heights in σ) and the likelihood ratio."""

    def __init__(self, spec, cut: float):
        self.spec, self.cut = spec, cut
        self.heights = spec.surface.heights
        lam = spec.surface.eta * spec.area
        self.below = lam * float(self.heights.sf(spec.s_min))  # Poisson mean above s_min
        self.edges = cut + BIN * np.arange(BINS + 1)
        self.edges[-1] = np.inf
        self.mass = lam * -np.diff(self.heights.sf(self.edges))  # nominal count per bin

    def bins(self, highs: list) -> np.ndarray:
        """Summits above the cut per pad and bin, shape (pads, :data:`BINS`)."""
        pad = np.repeat(np.arange(len(highs)), [h.size for h in highs])
        k = np.searchsorted(self.edges, np.concatenate([*highs, np.empty(0)]), side="right") - 1
        return np.bincount(pad * BINS + k, minlength=len(highs) * BINS).reshape(-1, BINS)

    def _in_bin(self, k: int, n: int, rng) -> np.ndarray:
        """``n`` nominal heights in bin ``k``: drawn above its lower edge, those above its
        upper edge drawn again (the nominal law restricted to the bin)."""
        out = np.empty(0)
        while out.size < n:
            s = self.heights.sample_above(n - out.size, self.edges[k], rng)
            out = np.concatenate([out, s[s <= self.edges[k + 1]]])
        return out

    def draw(self, tilt: Tilt | None, n: int, rng) -> tuple[list, list]:
        """``n`` pads: each one's heights above s_min (σ), and those above the cut (from ``tilt``)."""
        low = split(self.heights.sample_above(int((c := rng.poisson(self.below, n)).sum()),
                                               self.spec.s_min, rng), c)  # fmt: skip
        ratio = np.ones(BINS) if tilt is None else np.asarray(tilt.ratio)
        counts = rng.poisson(self.mass * ratio, size=(n, BINS))
        s = np.concatenate([self._in_bin(k, int(counts[:, k].sum()), rng) for k in range(BINS)])
        pad = np.concatenate([np.repeat(np.arange(n), counts[:, k]) for k in range(BINS)])
        high = split(s[np.argsort(pad, kind="stable")], counts.sum(axis=1))
        return [np.concatenate([a[a <= self.cut], b]) for a, b in zip(low, high)], high

    def log_ratio(self, tilt: Tilt | None, counts: np.ndarray) -> np.ndarray:
        """log L of each pad from its summits per bin above the cut, ``counts`` (:mod:`mcsim.studies.tail`)."""
        if tilt is None:
            return np.zeros(len(counts))
        r = np.asarray(tilt.ratio)
        return np.sum(self.mass * (r - 1)) - counts @ np.log(r)

    def weight(self, laws: list, sizes: list, counts: np.ndarray) -> np.ndarray:
        """The balance heuristic w = 1/Σ_j c_j/L_j, c_j = n_j/Σ n, of pads drawn from ``laws``
        (None: nominal) in numbers ``sizes``, from their summits per bin (:mod:`mcsim.studies.tail`)."""
        total = sum(sizes)
        with np.errstate(over="ignore"):
            return 1.0 / sum(n / total * np.exp(-self.log_ratio(q, counts))
                             for q, n in zip(laws, sizes, strict=True))  # fmt: skip


def split(values: np.ndarray, counts: np.ndarray) -> list:
    """``values`` cut into consecutive pieces of ``counts``."""
    return np.split(values, np.cumsum(counts)[:-1])


def fit(law: Law, previous: Tilt, counts: np.ndarray, weights: np.ndarray, cap=math.inf,
        smoothing: float = SMOOTHING) -> Tilt:  # fmt: skip
    """The smoothed cross-entropy tilt from elite pads' summits per bin above the cut and their
    weights: each bin's weighted mean count over its nominal count, at most ``cap`` (per bin),
    ``smoothing`` of it and the rest ``previous`` (:mod:`mcsim.studies.tail`)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        fit = (weights @ counts) / (np.sum(weights) * law.mass)
    fit = np.where(law.mass > 0, fit, 1.0)
    r = smoothing * fit + (1 - smoothing) * np.asarray(previous.ratio)
    return Tilt(tuple(np.maximum(np.minimum(r, cap), RATIO_FLOOR).tolist()))


def half(tilt: Tilt) -> Tilt:
    """The tilt half-way to ``tilt`` (in log): ratios √r_k."""
    return Tilt(tuple(math.sqrt(r) for r in tilt.ratio))

"""Figures of the environment: the work of separation against relative humidity.

>>> from mcsim.figures.environment import humidity_figure
>>> fig = humidity_figure(read_sweep("rh.h5"))                        # doctest: +SKIP

From a sweep over ``rh`` (``mcsim sweep --vary rh=... --law auto`` or another law set
with an adhesion summary): the work of separation and its parts, contact, van der Waals
and capillary (J/m², log axis), against RH, with the ceiling of the capillary work
2γ_L cos θ (flat surfaces in contact as RH → 1; DelRio et al., Appl. Phys. Lett. 90,
163104, 2007) and three regimes (after DelRio et al., Langmuir 25, 11727, 2009), bounded
here where the capillary work reaches :data:`DRY_BELOW` and :data:`SATURATED_ABOVE` of
the ceiling (linear interpolation between the sweep's points):

* dry: W_cap < 10 % of the ceiling, the van der Waals and contact works dominate;
* transition: the menisci spread over the gaps as r_K grows;
* saturated: W_cap > 90 % of the ceiling, the liquid fills almost every gap.

The regimes are shaded and named (above the ceiling, where no curve runs) only where the
sweep crosses from one to another; a sweep inside one regime says so in its title, as it
names a part that is 0 at every RH, or nowhere positive (the contacts' part of the work,
−∫ load dd, is negative where the attraction presses the summits harder than they pull),
neither drawn on the log axis; a part's points that are not drawn (≤ 0, or below the axis)
are counted in its legend entry. The title says from which RH on the capillary work is the
largest part: "dry" compares the menisci with their ceiling, not with the other parts. The
legend sits below.
"""

from __future__ import annotations

import itertools
import json
import math

import numpy as np

from mcsim.model.errors import ParameterError

#: Fraction of the ceiling 2γ_L cos θ below which the capillary work counts as dry.
DRY_BELOW = 0.1
#: Fraction of the ceiling above which it counts as saturated.
SATURATED_ABOVE = 0.9

#: The parts drawn, with their legend labels and styles.
PARTS = {
    "work_of_separation": ("total", {"color": "k", "lw": 2.0}),
    "work_of_separation_contact": ("contact (summits)", {"color": "#0072B2", "ls": "--"}),
    "work_of_separation_vdw": ("van der Waals (gaps)", {"color": "#009E73", "ls": "-."}),
    "work_of_separation_capillary": ("capillary (menisci)", {"color": "#D55E00", "ls": ":"}),
}


#: What each regime's name means here.
REGIME_MEANING = {
    "dry": f"capillary work < {100 * DRY_BELOW:.0f} % of the ceiling",
    "transition": "capillary work between "
    f"{100 * DRY_BELOW:.0f} % and {100 * SATURATED_ABOVE:.0f} % of the ceiling",
    "saturated": f"capillary work > {100 * SATURATED_ABOVE:.0f} % of the ceiling",
}


def _capillary_largest(rh: np.ndarray, data: dict) -> float | None:
    """The RH from which on the capillary work is the largest of the positive parts; None
    where it is not so at the sweep's last RH."""
    capillary = data["work_of_separation_capillary"]
    others = np.max([data[k] for k in PARTS if k not in ("work_of_separation",
                     "work_of_separation_capillary")], axis=0)  # fmt: skip
    largest = capillary > np.maximum(others, 0)
    if not largest[-1]:
        return None
    start = largest.size - np.argmin(largest[::-1]) if not largest.all() else 0
    return float(rh[start])


def regime_bounds(rh: np.ndarray, capillary: np.ndarray, ceiling: float) -> tuple[float, float]:
    """RH where the capillary work first reaches 10 % and 90 % of the ceiling, by linear
    interpolation between the sweep's points; NaN where the sweep does not reach it, −inf
    where its first point is already past it (the bound lies below the sweep)."""

    def first(fraction: float) -> float:
        above = np.flatnonzero(capillary >= fraction * ceiling)
        if above.size == 0:
            return math.nan
        i = above[0]
        if i == 0:
            return -math.inf
        y0, y1 = capillary[i - 1], capillary[i]
        return float(rh[i - 1] + (fraction * ceiling - y0) / (y1 - y0) * (rh[i] - rh[i - 1]))

    return first(DRY_BELOW), first(SATURATED_ABOVE)


def humidity_figure(sweep):
    """Work of separation (total, contact, vdW, capillary) against RH from an ``rh`` sweep.

    Parameters
    ----------
    sweep : mcsim.store.sweepfile.Sweep
        A sweep whose only varied input is ``rh``, with an adhesion summary.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ParameterError
        A sweep that does not vary ``rh`` alone or has no capillary work.
    """
    from matplotlib.figure import Figure

    if [d for d in sweep.grid if sweep.coords[d].size > 1] != ["rh"]:
        raise ParameterError("plot: the humidity figure needs a sweep that varies rh alone")
    if "work_of_separation_capillary" not in sweep.data:
        raise ParameterError("plot: the sweep has no capillary work (use a law set with an "
                             "adhesion summary: --law auto, jkr, dmt, maugis-dugdale)")  # fmt: skip
    env = json.loads(sweep.attrs["environment"])
    ceiling = 2 * env["surface_tension"] * math.cos(env["contact_angle"])
    rh = np.asarray(sweep.coords["rh"], dtype=float)
    order = np.argsort(rh)
    rh = rh[order]
    data = {k: np.ravel(sweep.data[k])[order] for k in PARTS}
    fig = Figure(figsize=(6.4, 5.2), layout="constrained")
    ax = fig.subplots()
    positive = np.concatenate([v[v > 0] for v in data.values()] + [[ceiling]])
    low = max(positive.min(), ceiling * 1e-6)
    left, right = 100 * rh[0], 100 * rh[-1]
    margin = 0.03 * (right - left) or 1.0  # end markers drawn whole
    lo, hi = left - margin, right + margin
    absent, given_back = [], []
    for key, (label, style) in PARTS.items():
        y = data[key]
        if not np.any(y > 0):  # nothing to draw on a log axis: said in the title instead
            (given_back if np.any(y < 0) else absent).append(label)
            continue
        shown = (y >= low / 2) & (y > 0)  # the axis' range, below
        if not shown.all():  # every point not drawn is counted, in the legend
            zero, below = int(np.sum(y <= 0)), int(np.sum((y > 0) & ~shown))
            label += "".join((f"; {zero} of {y.size} RH ≤ 0" if zero else "",
                              f"; {below} of {y.size} RH below the axis" if below else ""))  # fmt: skip
            label += " (not drawn)"
        ax.plot(100 * rh, np.where(shown, y, np.nan), marker="o", ms=3, label=label, **style)
    ax.axhline(
        ceiling, color="0.4", lw=1, label=rf"ceiling $2\gamma_L\cos\theta$ = {ceiling:.3g} J/m$^2$"
    )
    dry, saturated = regime_bounds(rh, data["work_of_separation_capillary"], ceiling)
    edges = [
        lo,
        *(lo if v == -math.inf else hi if v != v else 100 * v for v in (dry, saturated)),
        hi,
    ]
    spans = [(a, b, name, shade) for (a, b), name, shade in zip(
        itertools.pairwise(edges), ("dry", "transition", "saturated"), ("#56B4E9", "#E69F00", "#CC79A7"))
        if b > a]  # fmt: skip
    if (
        len(spans) > 1
    ):  # shaded and named (above the ceiling, where no curve runs) only if it changes
        for a, b, name, shade in spans:
            ax.axvspan(a, b, color=shade, alpha=0.12, lw=0)
            narrow = b - a < 0.2 * (hi - lo)  # upright, the name would spill out of its band
            ax.text((a + b) / 2, 0.98, name, transform=ax.get_xaxis_transform(), ha="center",
                    va="top", fontsize=9, rotation=90 if narrow else 0)  # fmt: skip
    ax.set_yscale("log")
    ax.set_ylim(low / 2, ceiling * 10)
    ax.set_xlim(lo, hi)
    ax.set_xlabel("Relative humidity RH (%)")
    ax.set_ylabel(r"Work of separation (J/m$^2$)")

    def bound(v: float) -> str:
        if v == -math.inf:
            return f"below RH = {left:.0f} %"
        return f"at RH = {100 * v:.0f} %" if v == v else f"not reached by RH = {right:.0f} %"

    lines = [f"Work of separation against humidity ({sweep.attrs.get('law', '')})",
             f"capillary work at 10 % of the ceiling {bound(dry)},",
             f"at 90 % {bound(saturated)}"]  # fmt: skip
    if len(spans) == 1:
        lines.append(f"regime: {spans[0][2]} ({REGIME_MEANING[spans[0][2]]}) over the whole sweep")
    largest = _capillary_largest(rh, data)
    if largest is not None:  # "dry" measures the menisci against flat surfaces, not the total
        lines.append(f"capillary the largest part of the work from RH = {100 * largest:.0f} %")
    if absent:
        lines.append(f"{', '.join(absent)}: 0 at every RH (not drawn on a log axis)")
    if given_back:  # the work is −∫ F dd: pressed contacts give back their elastic energy
        lines.append(f"{', '.join(given_back)}: <= 0 at every RH (energy given back; not drawn)")
    ax.set_title("\n".join(lines), fontsize=9)
    fig.legend(loc="outside lower center", ncols=2, fontsize=8, frameon=False)
    return fig

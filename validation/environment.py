"""The environment's local laws (issue 22): limits, −dW/dD = p, Gaussian terms against
quadrature, and the proximity model over the whole height distribution of the seed's four
Table-1 surfaces, as DelRio et al. wrote it, beside the published dry and humid adhesion of
polysilicon. These are the building blocks; mcsim applies them to the summits' caps and the
open gaps between them (docs/physics.md), and its answer for a device resting on its summits
is checked against DelRio et al.'s measurements by ``validation/humid_pads.py``.

Inputs: A = 1.6e-19 J (silicon across air), D0 = 0.2 nm, no retardation (b = 0, as
DelRio et al.), water at 25 °C (γ_L 0.072 J/m²,
V_m 1.80e-5 m³/mol, T 298.15 K), θ = 0. Rq and the summit offset y_s of each surface are
Nayak/McCool estimates from σ, R, η (rough at the seed's α of 2.5–4.9). The work of
separation is taken from the mean summit plane at contact, d = 0, i.e. D_t = y_s.

Published numbers (quoted from the papers' text as reported in docs/physics.md and issue 22,
not re-fitted here): DelRio et al., Nature Materials 4, 629 (2005): dry adhesion of
polysilicon of a few nm rms is of order µJ/m², dominated by van der Waals forces across
the non-contacting area; DelRio et al., Appl. Phys. Lett. 90, 163104 (2007): above a
threshold RH that rises with roughness the adhesion jumps and rises toward 2γ_L cos θ =
144 mJ/m².

Criteria (PASS/FAIL lines, exit status 1 on a FAIL):

* flat limits (Rq = 1e-15 m at D_t = D0) within 1e-5 relative of the closed forms: the
  model's first-order corrections are Rq/D0 = 5e-6 and, for capillarity, D0/(2 r_K);
* −dW/dD = p within 1e-6 relative: the central difference's truncation error is of order
  (step/D0)² = 2.5e-7 at the smallest gap, D0;
* the Gaussian terms within 1e-12 relative of adaptive quadrature (requested to 1e-13);
* the four surfaces (d = 0): the RH where W_cap reaches half of 2γ_L cos θ rises with
  roughness (DelRio et al. 2007), and no W_cap exceeds 2γ_L cos θ (from d = 0 and 3σ).

The timings are reported, not judged; ``--quick`` times fewer repeats.
"""

from __future__ import annotations

import math
import timeit

import numpy as np
from reporting import Checks, parser, save_figure, write_summary
from scipy import integrate, stats

from mcsim.model.presets import MATERIALS, PAPER_SURFACES, SURFACES
from mcsim.physics.analytic import gw_curves
from mcsim.physics.capillary import capillary_pressure, capillary_work
from mcsim.physics.environment import Environment, kelvin_radius
from mcsim.physics.gapheights import nayak_heights
from mcsim.physics.surfaceenvironment import environment_curves
from mcsim.physics.vanderwaals import vdw_pressure, vdw_work
from mcsim.topography.empirical import Empirical

A, D0, GAMMA = 1.6e-19, 0.2e-9, 0.072
#: Retardation b = 0: the local laws as DelRio et al. wrote them, non-retarded (mcsim's
#: default environment retards them, Gregory 1981: tests/physics/test_environment_retarded.py).
FLAT_LAW = 0.0
CEILING = 2 * GAMMA  # θ = 0


def check_limits(checks: Checks) -> list[str]:
    flat = 1e-15
    r_k = float(kelvin_radius(0.8))
    rows = [
        ("W_vdW, flat, D_t = D0", vdw_work(D0, flat, A, D0, FLAT_LAW), A / (12 * math.pi * D0**2)),
        (
            "W_cap, flat, D_t = D0, RH 0.8",
            capillary_work(D0, flat, D0, GAMMA, r_k, 0.0),
            2 * GAMMA - GAMMA * D0 / r_k,
        ),
        (
            "W_cap, flat, RH 1 - 1e-7",
            capillary_work(D0, flat, D0, GAMMA, kelvin_radius(1 - 1e-7), 0.0),
            CEILING,
        ),
    ]
    lines = [
        "## Limits (Rq = 1e-15 m)",
        "",
        "| quantity | model | closed form | rel. diff |",
        "|---|---|---|---|",
    ]
    for name, got, want in rows:
        lines.append(f"| {name} | {float(got):.10g} | {want:.10g} | {float(got) / want - 1:.1e} |")
        checks.at_most(f"{name}: |model/closed form - 1|", abs(float(got) / want - 1), 1e-5)
    return lines


def check_derivatives(checks: Checks) -> list[str]:
    rq = 1.2e-9
    edges = np.arange(-12 * rq, 12 * rq + 0.025e-9, 0.05e-9)
    histogram = Empirical.from_histogram(edges, np.diff(stats.norm.cdf(edges / rq)))
    D, step = np.array([0.27, 0.63, 1.57, 3.11, 6.23]) * 1e-9, 1e-13
    cap = (D0, GAMMA, float(kelvin_radius(0.85)), math.radians(30))
    lines = [
        "## −dW/dD = p (central differences, step 1e-13 m, D = 0.27–6.23 nm, Rq 1.2 nm)",
        "",
        "| heights | term | max rel. diff |",
        "|---|---|---|",
    ]
    for label, heights in (("Gaussian", rq), ("histogram (0.05 nm bins)", histogram)):
        for term, work, pressure, args in (
            ("vdW", vdw_work, vdw_pressure, (A, D0, FLAT_LAW)),
            ("capillary", capillary_work, capillary_pressure, cap),
        ):
            slope = -(work(D + step, heights, *args) - work(D - step, heights, *args)) / (2 * step)
            diff = np.max(np.abs(slope / pressure(D, heights, *args) - 1))
            lines.append(f"| {label} | {term} | {diff:.1e} |")
            checks.at_most(f"-dW/dD = p, {label}, {term}: max |slope/p - 1|", diff, 1e-6)
    return lines


def quad_expectation(D, rq, f, extra=()):
    """E[f(g); g >= D0], g = D − z, z ~ N(0, rq²), by adaptive quad in t = (g − D0)/rq."""
    a = (D - D0) / rq
    ends = sorted({0.0, *(p for p in (D0 / rq, a - 3, a, a + 3, *extra) if 0 < p < a + 12)})
    return sum(
        integrate.quad(
            lambda t: f(D0 + rq * t) * stats.norm.pdf(a - t),
            lo,
            hi,
            epsabs=0,
            epsrel=1e-13,
            limit=200,
        )[0]
        for lo, hi in zip(ends, [*ends[1:], max(a, 0) + 12])
    )


def check_quadrature(checks: Checks) -> list[str]:
    cases = [(0.8e-9, 0.5e-9, 0.55, 0.3), (3.3e-9, 4.4e-9, 0.9, 0.6), (12e-9, 9e-9, 0.97, 0.1)]
    lines = [
        "## Gaussian terms against adaptive quadrature (scipy.integrate.quad)",
        "",
        "| Rq (nm) | D (nm) | RH | θ (rad) | p_vdW | W_vdW | p_cap | W_cap |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for rq, D, rh, theta in cases:
        r_k = float(kelvin_radius(rh))
        g_k = 2 * r_k * math.cos(theta)
        t_k = ((g_k - D0) / rq,)
        contact = stats.norm.sf((D - D0) / rq)
        ref = [
            A / (6 * math.pi) * quad_expectation(D, rq, lambda g: g**-3),
            A / (12 * math.pi) * (quad_expectation(D, rq, lambda g: g**-2) + contact / D0**2),
            GAMMA / r_k * quad_expectation(D, rq, lambda g, g_k=g_k: float(g < g_k), t_k),
            GAMMA
            / r_k
            * (
                quad_expectation(D, rq, lambda g, g_k=g_k: max(g_k - g, 0.0), t_k)
                + (g_k - D0) * contact
            ),
        ]
        cap = (D0, GAMMA, r_k, theta)
        got = [
            vdw_pressure(D, rq, A, D0, FLAT_LAW),
            vdw_work(D, rq, A, D0, FLAT_LAW),
            capillary_pressure(D, rq, *cap),
            capillary_work(D, rq, *cap),
        ]
        diffs = [float(g) / r - 1 for g, r in zip(got, ref)]
        cells = " | ".join(f"{x:.1e}" for x in diffs)
        lines.append(f"| {rq * 1e9:g} | {D * 1e9:g} | {rh} | {theta} | {cells} |")
        checks.at_most(
            f"Gaussian terms against quad, Rq {rq * 1e9:g} nm, D {D * 1e9:g} nm: max |rel. diff|",
            max(abs(x) for x in diffs),
            1e-12,
        )
    return lines


def surfaces_table(rh: np.ndarray, h_t: float) -> tuple[list[str], dict]:
    """W_vdW and W_cap(RH) from d = h_t σ per surface, all RH of all surfaces in one call."""
    est = {name: nayak_heights(s.sigma, s.R, s.eta) for name, s in SURFACES.items()}
    names = list(PAPER_SURFACES)
    rq = np.array([est[n].rq for n in names])[:, None]
    sigma = np.array([SURFACES[n].sigma for n in names])[:, None]
    D_t = np.array([est[n].summit_offset for n in names])[:, None] + h_t * sigma
    w_cap = capillary_work(D_t, rq, D0, GAMMA, kelvin_radius(rh), 0.0)  # (surfaces, RH)
    w_vdw = vdw_work(D_t[:, 0], rq[:, 0], A, D0, FLAT_LAW)
    lines = [
        f"## The four Table-1 surfaces from d = {h_t:g}σ (A 1.6e-19 J, D0 0.2 nm, water, "
        "θ = 0, D_t = y_s + d)",
        "",
        "| surface | σ (nm) | Rq (nm) | y_s (nm) | α | W_vdW (µJ/m²) | W_cap at RH 0.5 / 0.9 / "
        "0.99 (mJ/m²) | RH at W_cap = 72 mJ/m² |",
        "|---|---|---|---|---|---|---|---|",
    ]
    marks = [int(np.argmin(np.abs(rh - x))) for x in (0.5, 0.9, 0.99)]
    for i, name in enumerate(names):
        e = est[name]
        above = np.flatnonzero(w_cap[i] >= CEILING / 2)
        half = f"{rh[above[0]]:.3f}" if above.size else "> 0.999"
        caps = " / ".join(f"{w_cap[i, k] * 1e3:.3g}" for k in marks)
        lines.append(
            f"| {name} | {SURFACES[name].sigma * 1e9:g} | {e.rq * 1e9:.3g} | "
            f"{e.summit_offset * 1e9:.3g} | {e.alpha:.2f} | {w_vdw[i] * 1e6:.3g} | {caps} | {half} |"
        )
    half_rh = [float(rh[np.argmax(w >= CEILING / 2)]) if w.max() >= CEILING / 2 else 1.0
               for w in w_cap]  # fmt: skip
    return lines, {"names": names, "w_cap": w_cap, "w_vdw": w_vdw, "half_rh": half_rh}


def timings(number: int) -> list[str]:
    smooth, silicon = SURFACES["smooth"], MATERIALS["silicon"]
    env = Environment(hamaker=A, cutoff=D0, rh=0.6)
    h = np.linspace(4, -1, 51)
    t_env = (
        min(
            timeit.repeat(
                lambda: environment_curves(h, smooth, env),
                number=number,
                repeat=5,
            )
        )
        / number
    )
    t_gw = (
        min(timeit.repeat(lambda: gw_curves(smooth, silicon, h), number=number, repeat=5)) / number
    )
    rh = np.linspace(0.01, 0.99, 50)
    sigma = np.geomspace(0.3e-9, 20e-9, 40)[:, None]
    estimates = [nayak_heights(s, smooth.R, smooth.eta) for s in sigma[:, 0]]
    rq = np.array([e.rq for e in estimates])[:, None]
    D_t = np.array([e.summit_offset for e in estimates])[:, None]

    def grid():
        return (
            vdw_work(D_t, rq, A, D0, FLAT_LAW),
            capillary_work(D_t, rq, D0, GAMMA, kelvin_radius(rh), 0.0),
        )

    t_grid = min(timeit.repeat(grid, number=5, repeat=3)) / 5
    return [
        f"## Speed (best of 5 repeats of {number}; not judged)",
        "",
        f"- environment_curves (caps and open gaps), 51 h, smooth surface, vdW + capillary: "
        f"{t_env * 1e3:.2f} ms",
        f"- gw_curves (seed laws), same 51 h: {t_gw * 1e3:.2f} ms",
        f"- work terms on a 40 σ × 50 RH grid (2000 points, vdW + capillary): "
        f"{t_grid * 1e3:.1f} ms",
    ]


def figure(rh, table, args) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for i, name in enumerate(table["names"]):
        (line,) = ax.plot(rh, table["w_cap"][i] * 1e3, label=f"{name}: capillary")
        ax.axhline(table["w_vdw"][i] * 1e3, color=line.get_color(), ls=":", lw=1)
    ax.axhline(CEILING * 1e3, color="k", ls="--", lw=1, label="2γ_L cos θ")
    ax.set_yscale("log")
    ax.set_ylim(1e-4, 300)
    ax.set_xlabel("relative humidity")
    ax.set_ylabel("work of separation from d = 0 (mJ/m²)")
    ax.set_title("Proximity model, Table-1 surfaces (dotted: dry vdW)", fontsize=10)
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    save_figure(fig, args.out / "environment.png", args)


def main() -> None:
    args = parser(__doc__.splitlines()[0]).parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    rh = np.linspace(0.001, 0.999, 999)
    checks = Checks()
    table_lines, table = surfaces_table(rh, 0.0)
    resting_lines, resting = surfaces_table(rh, 3.0)
    half = table["half_rh"]  # rough, intermediate, smooth, super-smooth
    checks.holds("d = 0: RH at W_cap = gamma_L cos(theta) rises with roughness",
                 bool(np.all(np.diff(half) < 0)),
                 " > ".join(f"{x:.3f}" for x in half) + " (rough ... super-smooth)")  # fmt: skip
    checks.at_most("largest W_cap (d = 0 and 3 sigma) / (2 gamma_L cos theta)",
                   max(table["w_cap"].max(), resting["w_cap"].max()) / CEILING, 1.0)  # fmt: skip
    published = [
        "Published (quoted from the papers' text as reported in docs/physics.md and issue 22, "
        "not re-fitted): dry adhesion of polysilicon of a few nm rms is of order µJ/m² "
        "(DelRio et al. 2005); humid adhesion jumps above a threshold RH that rises with "
        "roughness, toward 2γ_L cos θ = 144 mJ/m² (DelRio et al. 2007)."
    ]
    lines = [
        *check_limits(checks),
        "",
        *check_derivatives(checks),
        "",
        *check_quadrature(checks),
        "",
        *table_lines,
        "",
        *resting_lines,
        "",
        *published,
        "",
        *timings(5 if args.quick else 50),
        "",
        *checks.summary(),
    ]
    write_summary(args.out / "environment.txt", lines, args)
    figure(rh, table, args)
    checks.exit()


if __name__ == "__main__":
    main()

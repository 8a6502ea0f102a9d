"""Humid stiction of pads resting on their tallest summits, against DelRio et al.'s measurements.

DelRio et al. measured the adhesion of polysilicon cantilevers resting on their own
asperities (no external load) in dry and humid air (Nature Materials 4, 629, 2005; Appl.
Phys. Lett. 90, 163104, 2007; Langmuir 25, 11727, 2009). What their abstracts state, and what
this script judges: dry adhesion of a few µJ/m² to tens, dominated by van der Waals forces
across the non-contacting area and falling about as 1/D_ave² with the average gap; below a
critical humidity RH_cr the adhesion stays at its dry value (between RH_dry and RH_cr bridges
are confined to the contacting asperities, held open by their own nanoscale roughness), at
RH_cr it jumps (menisci spread across the interface) and then rises toward
2γ_L cos θ = 144 mJ/m²; RH_cr rises with roughness.

Surfaces that hang together (docs/physics.md, 'Humid air as measured'): beam and substrate
each carry one isotropic self-affine spectrum (Hurst 0.8, flat below the roll-off
q_r = 2π/1 µm), correlated by ρ = 0.5 (the beam partly replicates its substrate), so that the
gap between them has a combined rms Rq of 3, 5 and 8 nm, as DelRio's samples
(:func:`mcsim.model.counterface.combine`: each face at Rq/√(2(1 − ρ)) = Rq). Its wavelengths above 100 nm make the summits:
their spectral moments m0, m2, m4 give σ_s, R, η and the summit offset y_s by Nayak's and
McCool's relations (:func:`mcsim.model.counterface.summits_of`), so that R falls and σ_s, y_s
grow with Rq at a fixed η (printed). Its wavelengths from 100 nm down to 5 nm are the
asperities' own nanoscale roughness σ_n (``asperity_roughness``), which sets RH_cr. Silicon
with w = 0.1 J/m² and the maugis-dugdale law set (valid at every Maugis λ; the surfaces' λ
are printed, and every regime warning too), A = 1.6e-19 J, D0 = 0.21 nm (one interface: its
van der Waals share A/(12πD0²) lies within w; 'One interface, one law'), Gregory's retarded
van der Waals, water at 25 °C with its adsorbed films (the isotherm), θ = 0. Pads of 100 µm²
under no preload (each pad turns where its own net load first turns compressive), the same
summits at every RH (common random numbers). Γ is the mean over the pads of each pad's work
of separation, −∫ F_net dd / A from its own turn (mcsim.engine.pads.curves.pad_work); D_ave the
mean-plane gap at the turn, averaged over the pads.

Criteria (PASS/FAIL lines, exit status 1 on a FAIL), as the issue on humid air sets them:

* dry Γ (RH 0) between 1 and 100 µJ/m² at every Rq (DelRio et al. 2005: µJ/m²);
* the slope of ln Γ_dry against ln D_ave over the three roughnesses within −2 ± 0.3;
* at every Rq, Γ stays within 20 % of its dry value below RH_cr (a constant dry regime);
* at every Rq the onset of the jump, RH* (the first grid humidity where Γ leaves its dry value
  by more than 20 %), is a rise of at least 5-fold within 0.05 of RH, and RH* is the model's
  RH_cr to the grid's step;
* RH* never falls as Rq rises, and is higher at 8 nm than at 3 nm;
* the smoothest surface reaches at least half of 2γ_L cos θ at RH 0.95, and no Γ passes
  2γ_L cos θ.

Also drawn: Γ(RH) for the three roughnesses with their dry levels and the ceiling, and
p_stick(RH) of the 5 nm pads at one restoring force, with Clopper–Pearson 95 % intervals
(``humid_pads.png``, ``humid_pads_stick.png``). Run: ``python validation/humid_pads.py``
(20 pads a point, about ten minutes on one core) or ``--quick`` (2 pads a point, at RH 0,
either side of each surface's RH_cr, and 0.95 for the smoothest).
"""

from __future__ import annotations

import dataclasses
import math
import time
import warnings

import numpy as np
from reporting import Checks, parser, save_figure, write_summary
from scipy import integrate

from mcsim.engine.pads import curves as padcurves
from mcsim.engine.pads import load as padload
from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.counterface import combine, combined_rms, summits_of
from mcsim.model.params import Surface
from mcsim.model.presets import MATERIALS
from mcsim.physics.adhesion import maugis_parameter
from mcsim.physics.environment import Environment
from mcsim.studies.intervals import clopper_pearson

RQ = (3e-9, 5e-9, 8e-9)
#: The spectrum: Hurst exponent, roll-off, the summits' shortest and the nanoscale
#: roughness's shortest wavelength, m.
HURST, ROLL_OFF, SUMMIT_SCALE, NANO_SCALE = 0.8, 1e-6, 100e-9, 5e-9
#: Correlation of the beam's and the substrate's heights: a beam released from a sacrificial
#: layer partly replicates the substrate (DelRio et al., Appl. Phys. Lett. 90, 163104, 2007).
REPLICATION = 0.5
AREA = 100e-12
LAW = "maugis-dugdale"
HAMAKER, CUTOFF = 1.6e-19, 0.21e-9
MATERIAL = dataclasses.replace(MATERIALS["silicon"], gamma=0.1)
RH = (0.0, 0.1, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9,
      0.95)  # fmt: skip
CEILING = 2 * 0.072  # 2γ_L cos θ, J/m²
#: Restoring force of the p_stick figure (5 nm pads), N.
RESTORING = 20e-6
#: Separations of the pads' spec, h = d/σ: the lowest bounds the turns.
H = np.linspace(-2.0, 6.0, 9)


def spectrum_parts(rq: float) -> tuple[Surface, float]:
    """The GW surface of the gap between beam and substrate at the spectrum's summit scale,
    and the gap's nanoscale roughness σ_n (m), for a gap of rms ``rq``.

    Each face carries the self-affine spectrum (module docstring) at the rms
    rq/√(2(1 − ρ)), ρ = :data:`REPLICATION` (the beam partly replicates the substrate it was
    released from); its moments m_n = ∫ q^(n+1) C(q) dq, profile moments m2 = (1/2)⟨|∇z|²⟩ and
    m4 = (3/8)⟨(∇²z)²⟩ up to the summit scale give its summits (Nayak 1971), and
    :func:`mcsim.model.counterface.combine` the gap's; the nanoscale parts combine the same way.
    """
    q_r, q_s, q_n = (2 * math.pi / x for x in (ROLL_OFF, SUMMIT_SCALE, NANO_SCALE))

    def c(q):  # the radial spectrum, flat below the roll-off
        return 1.0 if q < q_r else (q / q_r) ** (-2 * (1 + HURST))

    def moment(n, lo, hi):
        cut = [q_r] if lo < q_r < hi else None
        return integrate.quad(lambda q: q ** (n + 1) * c(q), lo, hi, points=cut, limit=200)[0]

    face = rq / math.sqrt(2 * (1 - REPLICATION))
    scale = face**2 / moment(0, 0.0, q_n)
    m0, m2 = scale * moment(0, 0.0, q_s), scale * moment(2, 0.0, q_s) / 2
    m4 = scale * moment(4, 0.0, q_s) * 3 / 8
    s = summits_of(m0, m2, m4)
    beam = Surface(sigma=s.sigma, R=s.R, eta=s.eta, name="beam")
    substrate = Surface(sigma=s.sigma, R=s.R, eta=s.eta, name="substrate")
    gap = combine(beam, substrate, REPLICATION)
    nano = combined_rms(*[math.sqrt(scale * moment(0, q_s, q_n))] * 2, REPLICATION)
    return dataclasses.replace(gap, name=f"Rq {rq * 1e9:g} nm"), nano


def environment(rq: float, rh: float) -> Environment:
    return Environment(hamaker=HAMAKER, cutoff=CUTOFF, rh=rh,
                       asperity_roughness=spectrum_parts(rq)[1])  # fmt: skip


def pads(rq: float, rh: float, n: int, seed: int, area: float = AREA) -> dict:
    """Work of separation (J/m²), pull-off (N) and mean-plane gap at the turn (m) of n pads."""
    s = spectrum_parts(rq)[0]
    spec = MonteCarloSpec(s, MATERIAL, H, area, n, seed, LAW, cycle=True,
                          environment=environment(rq, rh))  # fmt: skip
    work, force, gap = np.empty(n), np.empty(n), np.empty(n)
    for r in range(n):
        z = padload.patch_heights(spec, r)
        d_t, _ = padcurves.force_turn(spec, z, 0.0)
        work[r] = padcurves.pad_work(spec, z, d_t)
        force[r] = padcurves.pull_off(spec, z, d_t)[0]
        gap[r] = d_t + s.summit_offset
    return {"work": work, "force": force, "gap": gap}


def critical_rh(rq: float) -> float:
    """The model's RH_cr of the surface of rms ``rq`` (:attr:`Environment.critical_rh`)."""
    return environment(rq, 0.5).critical_rh


def quick_grid(rq: float) -> tuple[float, ...]:
    """RH 0 and the grid points either side of the surface's RH_cr (and 0.95 for the
    smoothest, whose approach to the ceiling is judged)."""
    grid = np.asarray(RH)
    k = int(np.searchsorted(grid, critical_rh(rq)))
    points = {0.0, float(grid[k - 1]), float(grid[min(k, grid.size - 1)])}
    return tuple(sorted(points | ({0.95} if rq == RQ[0] else set())))


def main() -> None:
    p = parser(__doc__.splitlines()[0])
    p.set_defaults(seed=3)
    args = p.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    n, area = (2, AREA) if args.quick else (20, AREA)
    grids = {rq: np.asarray(quick_grid(rq) if args.quick else RH) for rq in RQ}
    lines = [f"# Humid pads resting on their summits ({n} pads of {area * 1e12:g} µm² per point)",
             "", "| Rq (nm) | σ_s (nm) | R (µm) | η (µm⁻²) | y_s (nm) | σ_n (nm) | Maugis λ | RH_cr |",
             "|---|---|---|---|---|---|---|---|"]  # fmt: skip
    for rq in RQ:
        s, nano = spectrum_parts(rq)
        lam = maugis_parameter(s, MATERIAL)
        lines.append(f"| {rq * 1e9:g} | {s.sigma * 1e9:.3g} | {s.R * 1e6:.3g} | "
                     f"{s.eta * 1e-12:.3g} | {s.summit_offset * 1e9:.3g} | {nano * 1e9:.3g} | "
                     f"{lam:.3g} | {critical_rh(rq):.3g} |")  # fmt: skip
    start = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        results = {rq: [pads(rq, rh, n, args.seed, area) for rh in grids[rq]] for rq in RQ}
    seconds = time.perf_counter() - start
    notes = sorted({str(w.message) for w in caught})
    lines += ["", f"warnings raised ({len(notes)}):", *(f"- {w}" for w in notes), ""]
    gamma = {rq: np.array([x["work"].mean() for x in rows]) for rq, rows in results.items()}
    se = {rq: np.array([x["work"].std(ddof=1) / math.sqrt(n) for x in rows])
          for rq, rows in results.items()}  # fmt: skip
    d_ave = np.array([results[rq][0]["gap"].mean() for rq in RQ])
    dry = np.array([gamma[rq][0] for rq in RQ])

    lines += [f"Γ in µJ/m² (mean ± its standard error over the pads; {seconds:.0f} s)", "",
              "| Rq (nm) | D_ave dry (nm) | Γ at RH: ... |", "|---|---|---|"]  # fmt: skip
    for i, rq in enumerate(RQ):
        cells = ", ".join(f"{x:g}: {g * 1e6:.3g} ± {e * 1e6:.2g}"
                          for x, g, e in zip(grids[rq], gamma[rq], se[rq]))  # fmt: skip
        lines.append(f"| {rq * 1e9:g} | {d_ave[i] * 1e9:.3g} | {cells} |")
    lines.append("")

    checks = Checks()
    for i, rq in enumerate(RQ):
        value = dry[i] * 1e6
        checks.holds(f"dry Γ at Rq {rq * 1e9:g} nm in [1, 100] µJ/m²", 1 <= value <= 100,
                     f"{value:.3g} µJ/m²")  # fmt: skip
    slope = float(np.polyfit(np.log(d_ave), np.log(dry), 1)[0])
    checks.holds("slope of ln Γ_dry against ln D_ave within -2 ± 0.3", abs(slope + 2) <= 0.3,
                 f"{slope:.3g} (D_ave {', '.join(f'{x * 1e9:.3g}' for x in d_ave)} nm)")  # fmt: skip
    onsets = []
    for rq in RQ:
        g, cr, rh = gamma[rq], critical_rh(rq), grids[rq]
        below = g[rh < cr]
        checks.at_most(f"Rq {rq * 1e9:g} nm: largest |Γ/Γ_dry − 1| below RH_cr = {cr:.3g}",
                       float(np.max(np.abs(below / g[0] - 1))), 0.2)  # fmt: skip
        # the onset of the jump: the first grid humidity where Γ leaves its dry value by 20 %
        k = int(np.flatnonzero(np.abs(g / g[0] - 1) > 0.2)[0]) if np.any(
            np.abs(g / g[0] - 1) > 0.2) else rh.size - 1  # fmt: skip
        onsets.append(float(rh[k]))
        step = float(rh[k] - rh[k - 1])
        checks.at_least(f"Rq {rq * 1e9:g} nm: the jump at its onset RH* = {rh[k]:g}, over "
                        f"{step:.2g} of RH (x)", float(g[k] / g[k - 1]) if step <= 0.05 + 1e-9
                        else 0.0, 5.0)  # fmt: skip
        checks.holds(f"Rq {rq * 1e9:g} nm: RH* is the first grid humidity at or above RH_cr",
                     rh[k - 1] < cr <= rh[k], f"RH* {rh[k]:g}, RH_cr {cr:.3g}")  # fmt: skip
    lines += ["onset of the jump RH*: " + ", ".join(
        f"{rq * 1e9:g} nm: {t:g}" for rq, t in zip(RQ, onsets)), ""]  # fmt: skip
    checks.at_most("RH* never falls as Rq rises: largest fall", float(np.max(-np.diff(onsets))),
                   0.0)  # fmt: skip
    checks.holds("RH* at 8 nm above RH* at 3 nm", onsets[-1] > onsets[0],
                 f"{onsets[-1]:g} against {onsets[0]:g}")  # fmt: skip
    wet = gamma[RQ[0]][list(grids[RQ[0]]).index(0.95)]
    checks.at_least("smoothest Γ at RH 0.95 / (2γ_L cos θ)", wet / CEILING, 0.5)
    checks.at_most("largest Γ / (2γ_L cos θ)", max(float(g.max()) for g in gamma.values()) / CEILING,
                   1.0)  # fmt: skip
    lines += checks.summary()
    write_summary(args.out / "humid_pads.txt", lines, args)
    figures(grids, gamma, se, results, area, args)
    checks.exit()


def figures(grids, gamma, se, results, area, args) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for rq in RQ:
        (line,) = ax.plot([], [])
        color = line.get_color()
        ax.errorbar(grids[rq], gamma[rq] * 1e3, yerr=se[rq] * 1e3, marker="o", ms=4, capsize=2,
                    color=color, label=f"Rq = {rq * 1e9:g} nm")  # fmt: skip
        ax.axhline(gamma[rq][0] * 1e3, color=color, ls=":", lw=1)
    ax.axhline(CEILING * 1e3, color="k", ls="--", lw=1, label="2γ_L cos θ (flat, wetting)")
    ax.set_yscale("log")
    ax.set_xlabel("relative humidity RH (1)")
    ax.set_ylabel("work of separation Γ (mJ/m²)")
    for rq in RQ:
        ax.axvline(critical_rh(rq), color="0.6", ls="-.", lw=0.8)
    ax.set_title(f"Pads of {area * 1e12:g} µm² resting on their summits (dotted: dry; "
                 "dash-dot: RH_cr)", fontsize=10)  # fmt: skip
    ax.legend(fontsize=8, loc="center left")
    fig.tight_layout()
    save_figure(fig, args.out / "humid_pads.png", args)

    rows = results[RQ[1]]
    k = np.array([int(np.count_nonzero(x["force"] > RESTORING)) for x in rows])
    n = rows[0]["force"].size
    low, high = np.array([clopper_pearson(int(j), n) for j in k]).T
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    ax.errorbar(grids[RQ[1]], k / n, yerr=[k / n - low, high - k / n], marker="o", ms=4, capsize=2,
                color="k", label="pads, 95 % Clopper–Pearson")  # fmt: skip
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel("relative humidity RH (1)")
    ax.set_ylabel("p_stick = P(pull-off > F_r) (1)")
    ax.set_title(f"Rq = {RQ[1] * 1e9:g} nm, {n} pads of {area * 1e12:g} µm², "
                 f"F_r = {RESTORING * 1e6:g} µN, no preload", fontsize=10)  # fmt: skip
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    save_figure(fig, args.out / "humid_pads_stick.png", args)


if __name__ == "__main__":
    main()

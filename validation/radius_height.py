"""Why one radius cannot calibrate GW on the shipped map, and what does: taller summits are sharper.

``mcsim ingest --calibrate`` fits one summit-radius scale s to the exact (FFT boundary
element) contact areas of a map at p/E* = 1e-4 … 1e-2 (mcsim.studies.maps.calibration); on
``examples/scan.npy`` (periodic, 10 nm pixels, silicon), with one radius for every summit
(``--no-radius-by-height``) its worst area error is 13.8 %, above the 10 % issue 32 asks for.
This script measures where the error comes from, on the map's own summits (direct route:
8-neighbour maxima, each with its curvature κ_i = −(z_xx + z_yy)/2):

1. The summits' curvature grows with their height (Nayak, Trans. ASME J. Lubr. Technol. 93,
   398, 1971: the mean curvature of a Gaussian surface's summits rises with their height);
   GW gives every summit the one radius 1/⟨κ⟩. The correlation of height and κ, with its
   Fisher z (atanh r · √(n − 3): ~N(0, 1) for uncorrelated heights and curvatures).
2. GW's area curve summed over the map's own summits (Hertz, Eq. 2: load K R^½ δ^{3/2}, area
   π R δ per summit, at 4000 separations; the area at each exact load by interpolation
   against the load), with one scale s fitted as calibration does (minimax in
   |ln(A_GW/A_exact)|): (a) every summit the one radius 1/⟨κ⟩, (b) every summit its own
   radius 1/κ_i (summits with κ_i ≤ 0 dropped and counted).

3. What ``ingest --calibrate`` does with it: a radius by height, one radius per bin of the
   summit-height histogram from a line through ln κ_i against height
   (mcsim.topography.summits.radius_by_height), then the one scale, on the surface file's GW
   (the histogram, its bands, the analytic integrals).

Criteria: the correlation positive with Fisher z ≥ 3; with the summits' own radii one scale
reaches the issue's 10 %; and so does ``ingest --calibrate`` with its radius by height, at the
fitted loads (in sample) and leaving each load out of the fit in turn (out of sample, within
the fitted range). The one-radius errors, and ``ingest --calibrate``'s error at p/E* = 3e-2
above the fitted range (where the calibration makes no claim, and ``ingest`` warns when it
passes 10 %), are reported (INFO). What it says: the calibration's missing ingredient was
a summit radius that depends on the summit's height, not a second global scale (σ_s and η
scalings only translate GW's log area–log load curve). Run: ``python
validation/radius_height.py`` (``--quick`` is the same run: a 100² map, ten exact solves, ~3 s).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from reporting import Checks, parser, write_summary
from scipy import optimize

from mcsim.model.presets import MATERIALS
from mcsim.studies.maps.calibration import LOADS
from mcsim.studies.maps.ingest import ingest_file
from mcsim.topography.readers import read_height_map
from mcsim.topography.summits import summit_curvatures

MAP = Path(__file__).resolve().parents[1] / "examples" / "scan.npy"
PIXEL = 10e-9
TARGET = 0.10


def area_at_loads(R: np.ndarray, z: np.ndarray, pressure: np.ndarray, area: float) -> np.ndarray:
    """A_r/A_n of Hertz summits of radii ``R`` and heights ``z`` (m) at nominal ``pressure``
    (Pa, silicon's K): Σ π R δ and Σ K R^½ δ^{3/2} over a dense grid of separations."""
    K = 4 * MATERIALS["silicon"].E_star / 3
    d = np.linspace(z.max(), z.min() - 3 * z.std(), 4000)
    delta = np.clip(z[None, :] - d[:, None], 0.0, None)
    a = (np.pi * R * delta).sum(axis=1) / area
    p = (K * np.sqrt(R) * delta**1.5).sum(axis=1) / area
    return np.interp(pressure, p, a)


def one_scale(R, z, pressure, exact, area) -> tuple[float, np.ndarray]:
    """The minimax radius scale and the ratios A_GW/A_exact it leaves."""

    def worst(x):
        return float(
            np.max(np.abs(np.log(area_at_loads(R * math.exp(x), z, pressure, area) / exact)))
        )

    x = optimize.minimize_scalar(worst, bounds=(-3, 3), method="bounded").x
    return math.exp(x), area_at_loads(R * math.exp(x), z, pressure, area) / exact


def main() -> None:
    p = parser(__doc__.splitlines()[0])
    args = p.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    silicon = MATERIALS["silicon"]
    one, bands = (ingest_file(MAP, unit="m", pixel_size=PIXEL, calibrate=silicon,
                              radius_by_height=by).calibration for by in (False, True))  # fmt: skip
    z_map = read_height_map(MAP, unit="m", pixel_size=PIXEL).heights
    z_map = z_map - z_map.mean()  # a periodic map is levelled by its mean only (calibrate's)
    z, kappa = summit_curvatures(z_map, PIXEL, PIXEL, periodic=True)
    area = z_map.size * PIXEL**2
    r = float(np.corrcoef(z, kappa)[0, 1])
    fisher = math.atanh(r) * math.sqrt(z.size - 3)
    convex = kappa > 0
    pressure = LOADS * silicon.E_star
    cases = {"one radius 1/<kappa>": np.full(z.size, 1 / kappa.mean()),
             "own radius 1/kappa_i": 1 / np.where(convex, kappa, np.inf)}  # fmt: skip
    rows, worst = [], {}
    for name, R in cases.items():
        scale, ratios = one_scale(R, z, pressure, one.exact_area, area)
        worst[name] = float(np.max(np.abs(ratios - 1)))
        rows.append(f"| {name} | {scale:.3g} | {' | '.join(f'{x:.3f}' for x in ratios)} | "
                    f"{worst[name]:.1%} |")  # fmt: skip
    lines = [f"# {MAP.name}: {z.size} summits ({np.count_nonzero(~convex)} with kappa <= 0 "
             f"dropped from the own-radius sum), corr(height, kappa) = {r:.3f} (Fisher z "
             f"{fisher:.2f})", "",
             f"ingest --calibrate, the surface file's GW: one radius: scale {one.radius_scale:.4g}, "
             f"worst {one.in_sample_worst:.1%} in sample, {one.loo_worst:.1%} leave-one-out, "
             f"{one.extrapolated_error:+.1%} at p/E* = {one.extrapolated_load:g}; radius by height: "
             f"scale {bands.radius_scale:.4g}, worst {bands.in_sample_worst:.1%} in sample (ratios "
             + ", ".join(f"{r:.3f}" for r in bands.gw_area / bands.exact_area)
             + f"), {bands.loo_worst:.1%} leave-one-out (errors "
             + ", ".join(f"{e:+.3f}" for e in bands.loo_error)
             + f"), {bands.extrapolated_error:+.1%} at p/E* = {bands.extrapolated_load:g}", "",
             "| GW on the map's own summits | scale | " + " | ".join(
                 f"p/E* {x:.3g}" for x in LOADS) + " | worst |",
             "|---" * (3 + LOADS.size) + "|", *rows, "",
             f"INFO: one radius, one scale: worst {worst['one radius 1/<kappa>']:.1%}",
             f"INFO: ingest --calibrate (radius by height) at p/E* = {bands.extrapolated_load:g}, "
             f"above the fitted range: A_GW/A_exact - 1 = {bands.extrapolated_error:+.1%}", ""]  # fmt: skip
    checks = Checks()
    checks.at_least("Fisher z of corr(summit height, curvature)", fisher, 3.0)
    checks.at_most("own radii, one scale: worst |A_GW/A_exact - 1|", worst["own radius 1/kappa_i"],
                   TARGET)  # fmt: skip
    checks.at_most("ingest --calibrate (radius by height): worst |A_GW/A_exact - 1| in sample",
                   bands.in_sample_worst, TARGET)  # fmt: skip
    checks.at_most("ingest --calibrate (radius by height): worst |A_GW/A_exact - 1| leave-one-out",
                   bands.loo_worst, TARGET)  # fmt: skip
    lines += checks.summary()
    write_summary(args.out / "radius_height.txt", lines, args)
    checks.exit()


if __name__ == "__main__":
    main()

"""Per-summit moments of the seed laws, by an independent quadrature (scipy ``quad``).

Used by the validation scripts to predict the Monte Carlo scatter (docs/physics.md,
"Monte Carlo statistics"). For one summit with standardized height S ~ N(0, 1) at
separation h = d/σ, the per-summit load, adhesion term and friction are
x(S) = X_a(σ(S − h)) for S > h and 0 otherwise (Eqs. 2, 4, 6). Then, for a patch of
N summits,

* relative SE of a total X ∈ {P, F, T}: c_X/√N, with c_X² = E[x²]/E[x]² for
  N ~ Poisson(ηA) and E[x²]/E[x]² − 1 for fixed N;
* relative SE of μ = ΣT/(ΣP + ΣF) (delta method, either count): c_μ/√N with
  c_μ² = E[(t − μ(p + f))²] / (μ² E[p + f]²).

The expectations are computed here with adaptive quadrature in u = √(s − h) (which
removes the δ^{3/2} branch point), independently of the Gauss–Legendre rule that
:func:`mcsim.physics.analytic.gw_curves` uses.

Run on its own (``python validation/gw_moments.py``, a second; ``--quick`` is the same),
it checks itself, PASS/FAIL lines and exit status 1 on a FAIL: the mean Hertz load per
summit against K R^½ σ^{3/2} F_{3/2}(h) from 40-digit mpmath values (12 digits quoted,
so within 1e-10 relative, the quadrature's requested tolerance); the fixed-N c_P at
h = −1 … 4 against 1.04, 1.82, 3.87, 11.1, 47, 313 (computed once from c_P² =
F_3/F_{3/2}² − 1, to within half a unit of the last digit quoted); and the means P̄, F̄,
T̄ against ``gw_curves`` within 1e-9 relative (both are accurate to ~1e-13).
"""

from __future__ import annotations

import numpy as np
from scipy import integrate

from mcsim.model.params import Material, Surface
from mcsim.physics.laws import seed

_PAIRS = ("p", "f", "t", "pp", "ff", "tt", "pf", "pt", "ft")


def summit_moments(surface: Surface, material: Material, h: float) -> dict[str, float]:
    """E[x], E[x·y] over one Gaussian summit at separation ``h`` (forces in N, products in N²).

    Keys ``p, f, t, pp, ff, tt, pf, pt, ft``; non-contacting summits contribute zero.
    """
    R, K, G, gamma, sigma = surface.R, material.K, material.G, material.gamma, surface.sigma

    def forces(u: float) -> dict[str, float]:
        delta = sigma * u * u
        return {
            "p": float(seed.hertz_load(delta, R, K)),
            "f": float(seed.johnson_adhesion(delta, R, K, gamma)),
            "t": float(seed.savkoor_briggs_friction(delta, R, K, G, gamma)),
        }

    def integrand(u: float, key: str) -> float:
        x = forces(u)
        value = x[key] if len(key) == 1 else x[key[0]] * x[key[1]]
        s = h + u * u
        return value * 2.0 * u * np.exp(-0.5 * s * s) / np.sqrt(2.0 * np.pi)

    return {
        key: integrate.quad(
            integrand, 0.0, np.inf, args=(key,), epsabs=0.0, epsrel=1e-10, limit=400
        )[0]
        for key in _PAIRS
    }


def scatter_coefficients(
    surface: Surface, material: Material, h: float, count: str = "poisson"
) -> dict[str, float]:
    """c_X such that the relative SE of a patch of N summits is c_X/√N (dimensionless).

    Keys ``P, F, T, mu``; ``count`` is ``"poisson"`` or ``"fixed"`` (μ is the same for both).
    """
    m = summit_moments(surface, material, h)
    minus = {"poisson": 0.0, "fixed": 1.0}[count]
    c = {q: np.sqrt(m[x + x] / m[x] ** 2 - minus) for q, x in (("P", "p"), ("F", "f"), ("T", "t"))}
    load = m["p"] + m["f"]
    mu = m["t"] / load
    var = m["tt"] - 2 * mu * (m["pt"] + m["ft"]) + mu**2 * (m["pp"] + 2 * m["pf"] + m["ff"])
    c["mu"] = np.sqrt(var) / (load * mu)
    return c


def mean_totals(surface: Surface, material: Material, h: float) -> dict[str, float]:
    """GW means P̄, F̄, T̄ (÷ A·K, as Eqs. 3, 5, 7) and μ from the same quadrature."""
    m = summit_moments(surface, material, h)
    scale = surface.eta / material.K
    return {"P": scale * m["p"], "F": scale * m["f"], "T": scale * m["t"],
            "mu": m["t"] / (m["p"] + m["f"])}  # fmt: skip


#: F_{3/2}(h) from 40-digit mpmath, to 12 digits (independent reference values).
F_3_2 = {-1.0: 1.40459747047, 0.0: 4.30019993662e-1, 1.0: 7.56681773910e-2,
         2.0: 6.64817762359e-3, 3.0: 2.63967554270e-4, 4.0: 4.43915595854e-6}  # fmt: skip
#: Fixed-N c_P at h = −1 … 4 (computed once, quoted to 3 digits; see the module docstring).
C_P_FIXED = {-1.0: 1.04, 0.0: 1.82, 1.0: 3.87, 2.0: 11.1, 3.0: 47.0, 4.0: 313.0}


def main() -> None:
    from reporting import Checks, parser

    from mcsim.model.presets import MATERIALS, SURFACES
    from mcsim.physics.analytic import gw_curves

    parser(__doc__.splitlines()[0]).parse_args()
    surface, material = SURFACES["smooth"], MATERIALS["silicon"]
    checks = Checks()
    h = np.array(sorted(F_3_2))
    exact = gw_curves(surface, material, h)
    scale = material.K * np.sqrt(surface.R) * surface.sigma**1.5
    load, c_p, means = [], [], []
    for j, hj in enumerate(h):
        m = summit_moments(surface, material, hj)
        load.append(abs(m["p"] / (scale * F_3_2[hj]) - 1))
        c = scatter_coefficients(surface, material, hj, "fixed")["P"]
        digits = 10 ** (np.floor(np.log10(C_P_FIXED[hj])) - 2)  # a unit of the 3rd digit
        c_p.append(abs(c - C_P_FIXED[hj]) / (digits / 2))
        totals = mean_totals(surface, material, hj)
        means += [abs(totals[q] / getattr(exact, q)[j] - 1) for q in ("P", "F", "T", "mu")]
    checks.at_most(
        "mean Hertz load / (K R^1/2 sigma^3/2 F_3/2) - 1, h = -1 ... 4", max(load), 1e-10
    )
    checks.at_most("|c_P fixed - quoted| / half a unit of its last digit, h = -1 ... 4",
                   max(c_p), 1.0)  # fmt: skip
    checks.at_most("means P, F, T, mu against gw_curves: max |rel. diff|", max(means), 1e-9)
    print("\n".join(checks.summary()))
    checks.exit()


if __name__ == "__main__":
    main()

"""Fuller & Tabor's (1975) rough-surface JKR theory by direct quadrature, independent of mcsim.

Fuller & Tabor (Proc. R. Soc. Lond. A 345, 327, 1975, §2) put Greenwood–Williamson
asperities (η per nominal area, radius R, Gaussian heights z of rms σ) against a rigid
flat at one separation d: the backing is rigid, so each asperity is held at its
interference δ = z − d (fixed grips). Each asperity is a JKR sphere (Johnson, Kendall &
Roberts, Proc. R. Soc. Lond. A 324, 301, 1971), on the curve parametrised by its contact
radius a,

    δ(a) = a²/R − √(2πwa/E*),        P(a) = 4E*a³/(3R) − √(8πwE*a³),

stable (under fixed grips) for a ≥ a_c, a_c³ = πwR²/(8E*), where δ has its minimum
δ_c = −¾(π²w²R/E*²)^{1/3} and P = −(5/6)πwR. On approach an asperity touches at δ = 0
(a_0³ = 2πwR²/E*); on retraction from a closest approach d_t the asperities that touched
(z > d_t) stay in contact down to δ_c. The load per nominal area is the GW sum

    p(d) = η ∫_{z_lo}^∞ P(z − d) φ(z) dz,   z_lo = d (approach), max(d_t, d + δ_c) (retraction),

φ the Gaussian density of z. Here it is integrated in a (z = d + δ(a), dz = δ'(a) da), so
that δ(a) is never inverted inside the integral, with adaptive ``scipy.integrate.quad``;
mcsim instead inverts δ → a in closed form and integrates in h by Gauss–Legendre
(:func:`mcsim.physics.analytic.gw_curves`). The pull-off is the most tensile p on
retraction, the work of separation ∫ max(−p, 0) dd from d_t; the unit F&T normalise by,
P_c = (3/2)πwR, is the pull-off of one JKR sphere under load control (the most tensile
point of P(a), at a³ = 9πwR²/(8E*) > a_c³, so the fixed-grip curve passes through it).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

from scipy import integrate, optimize

#: Heights beyond ±TOP σ are left out (Gaussian tail 1e-23 of the density).
TOP = 10.0
#: Tolerances of every quad: relative, and absolute in units of P_c σ (the size of the
#: integral ∫ P(z − d) e^{−z²/2σ²} dz where all asperities are near their pull-off), which
#: decides where the load crosses zero.
EPSREL, EPSABS = 1e-11, 1e-14


@dataclass(frozen=True)
class JKRSurface:
    """GW surface of JKR asperities: R (m), E* (Pa), w (J/m²), σ (m), η (1/m²)."""

    R: float
    E_star: float
    w: float
    sigma: float
    eta: float

    @classmethod
    def of(cls, surface, material) -> JKRSurface:
        """From mcsim's Surface and Material (Gaussian heights)."""
        return cls(surface.R, material.E_star, material.gamma, surface.sigma, surface.eta)

    @property
    def a_c(self) -> float:
        """Contact radius at the fixed-grip break-off, a_c³ = πwR²/(8E*), m."""
        return (math.pi * self.w * self.R**2 / (8 * self.E_star)) ** (1 / 3)

    @property
    def delta_c(self) -> float:
        """Break-off interference δ_c = δ(a_c) = −¾(π²w²R/E*²)^{1/3}, m."""
        return self.delta(self.a_c)

    @property
    def p_c(self) -> float:
        """JKR pull-off of one sphere under load control, (3/2)πwR, N."""
        return 1.5 * math.pi * self.w * self.R

    def delta(self, a: float) -> float:
        """Interference δ(a), m (JKR 1971)."""
        return a * a / self.R - math.sqrt(2 * math.pi * self.w * a / self.E_star)

    def slope(self, a: float) -> float:
        """dδ/da (dimensionless)."""
        return 2 * a / self.R - 0.5 * math.sqrt(2 * math.pi * self.w / (self.E_star * a))

    def force(self, a: float) -> float:
        """Load P(a) of one asperity, N, compressive positive (JKR 1971)."""
        return 4 * self.E_star * a**3 / (3 * self.R) - math.sqrt(
            8 * math.pi * self.w * self.E_star * a**3
        )

    def radius(self, delta: float) -> float:
        """Contact radius a ≥ a_c at interference ``delta`` ≥ δ_c (m), by Brent's method."""
        lo = self.a_c
        if delta <= self.delta_c:
            return lo
        hi = 2 * lo
        while self.delta(hi) < delta:
            hi *= 2
        return optimize.brentq(lambda a: self.delta(a) - delta, lo, hi, xtol=1e-14 * hi,
                               rtol=1e-15)  # fmt: skip

    def load(self, d: float, turn: float | None = None) -> float:
        """Load per nominal area p(d), Pa: on approach (``turn`` None) or on retraction
        from the closest approach ``turn`` (both separations in m)."""
        s = self.sigma
        z_lo = d if turn is None else max(turn, d + self.delta_c)
        z_lo = max(z_lo, -TOP * s)
        if z_lo >= (TOP - 1e-9) * s:  # nothing left (up to rounding of the end point)
            return 0.0
        norm = self.eta / (s * math.sqrt(2 * math.pi))

        def integrand(a: float) -> float:
            z = (d + self.delta(a)) / s
            return self.force(a) * math.exp(-0.5 * z * z) * self.slope(a)

        # break points where the Gaussian changes fastest, so that quad sees its peak
        cuts = [self.radius(z_lo - d)]
        cuts += [self.radius(k * s - d) for k in (-3, -1, 0, 1, 3) if k * s > z_lo]
        cuts.append(self.radius(TOP * s - d))
        total = sum(
            integrate.quad(
                integrand, lo, hi, epsabs=EPSABS * self.p_c * s, epsrel=EPSREL, limit=200
            )[0]
            for lo, hi in itertools.pairwise(cuts)
        )
        return norm * total

    def grid(self, start: float, stop: float) -> list[float]:
        """Separations from ``start`` to ``stop`` (m) in steps of at most 0.05σ and |δ_c|/4
        (finer than one asperity's tensile range), at most 400 steps."""
        step = max(min(0.05 * self.sigma, -self.delta_c / 4), abs(stop - start) / 400)
        n = math.ceil(abs(stop - start) / step)
        return [start + (stop - start) * k / n for k in range(n + 1)]

    def retraction_grid(self, turn: float) -> list[float]:
        """:meth:`grid` from ``turn`` to where the last asperity lets go, with the kink
        d = turn − δ_c, where the lower limit of the retraction integral changes form."""
        end = TOP * self.sigma - self.delta_c
        return sorted({*self.grid(turn, end), turn - self.delta_c})

    def pull_off(self, turn: float) -> tuple[float, float]:
        """Most tensile retraction load from ``turn`` (m): (−p, Pa, ≥ 0; its separation, m).

        The smallest load on :meth:`retraction_grid`, then a bounded Brent minimisation
        between its neighbours.
        """
        grid = self.retraction_grid(turn)
        values = [self.load(x, turn) for x in grid]
        i = min(range(len(grid)), key=values.__getitem__)
        if values[i] >= 0:
            return 0.0, math.nan
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
        best = optimize.minimize_scalar(lambda x: self.load(x, turn), bounds=(lo, hi),
                                        method="bounded", options={"xatol": 1e-9 * self.sigma})  # fmt: skip
        if best.fun < values[i]:
            return -float(best.fun), float(best.x)
        return -values[i], grid[i]

    def rest(self) -> float | None:
        """Separation of zero load on approach, coming from far away (m); None if the
        approach load is never tensile.

        Scanned (:meth:`grid`) down from TOP σ to where every asperity is pressed in beyond
        δ = −2δ_c (there the load is compressive), then solved by Brent's method.
        """
        previous = None
        for x in self.grid(TOP * self.sigma, -TOP * self.sigma + 2 * self.delta_c):
            value = self.load(x)
            if previous is not None and previous[1] < 0 <= value:
                return optimize.brentq(self.load, x, previous[0], xtol=1e-13 * self.sigma)
            previous = (x, value)
        return None

    def works(self, turn: float) -> tuple[float, float]:
        """Work of separation ∫ max(−p_retract, 0) dd and hysteresis ∫ (p_approach −
        p_retract) dd from ``turn`` (m) to where the last asperity lets go, J/m².

        Adaptive quadrature over d, split at the kink d = turn − δ_c and where the
        retraction load changes sign (on :meth:`retraction_grid`, then by Brent's method).
        """
        grid = self.retraction_grid(turn)
        values = [self.load(x, turn) for x in grid]
        cuts = set(grid[:: max(len(grid) // 8, 1)]) | {grid[-1], turn - self.delta_c}
        for (x0, v0), (x1, v1) in zip(zip(grid, values), zip(grid[1:], values[1:])):
            if v0 * v1 < 0:
                cuts.add(optimize.brentq(lambda x: self.load(x, turn), x0, x1,
                                         xtol=1e-13 * self.sigma))  # fmt: skip
        cuts = sorted(cuts)
        scale = self.eta * self.p_c * self.sigma  # J/m²: the size of both integrals

        def integral(f) -> float:
            return sum(
                integrate.quad(f, lo, hi, epsabs=EPSABS * scale, epsrel=1e-10, limit=200)[0]
                for lo, hi in itertools.pairwise(cuts)
            )

        work = integral(lambda x: max(-self.load(x, turn), 0.0))
        hysteresis = integral(lambda x: self.load(x) - self.load(x, turn))
        return work, hysteresis

"""Exact adhesive contact of a height map against a rigid flat, by FFT boundary elements.

A rough elastic half-space (contact modulus E*, heights z on a grid of pixels of area ΔA)
meets a rigid flat at height d above the map's mean plane; the gap is g = u − z + d (u the
surface displacement, pushed away from the flat by a compressive pressure). The state
minimises (Rey, Anciaux & Molinari, Comput. Mech. 60, 69, 2017, Eqs. 1–4; Müser et al.,
Tribol. Lett. 65, 118, 2017)

    Π(u) = ½ Σ u·p(u) ΔA + Σ φ(g) ΔA,    subject to g ≥ 0 on every pixel,

the elastic energy of the half-space plus the interaction energy of a gap-dependent law φ
(:mod:`mcsim.physics.interactions`), under **displacement control**: d is imposed and the
mean pressure p̄ = −(1/A) dΠ/dd is the output, so the unstable branches of a load curve
are followed up to their ends, where the solution jumps.

* **Periodic maps**: the stiffness p̃ = (E*|q|/2) ũ, the inverse of the Green's function of
  :func:`mcsim.physics.bem.periodic_response`. Its q = 0 mode, the mean displacement, is
  fixed at zero, so the mean gap is d (mean-gap control, as in the contact-mechanics
  challenge). The variables are x ≥ 0 with g = d x / x̄, which keeps the mean gap at d
  with simple bounds; the mean pressure is the Lagrange multiplier of that constraint,
  −∂Π/∂g on the pixels out of contact.
* **Non-periodic maps**: the displacement on the grid of twice the map's size, padded as in
  :func:`mcsim.physics.bem.padded_response` (Hockney 1970), with the stiffness 1/G̃ of
  that grid and no interaction on the padding. At the minimum the pressure on the padding
  vanishes (the gradient there), so the pressure acts on the map alone;
  :attr:`AdhesiveSolution.padding_residual` reports what is left of it.
* **The solver**: a bound-constrained quasi-Newton method, L-BFGS directions projected onto
  the bounds with a backtracking line search (:func:`_projected_lbfgs`; the scheme of
  L-BFGS-B, Byrd, Lu, Nocedal & Zhu, SIAM J. Sci. Comput. 16, 1190, 1995, without its
  generalised Cauchy point, which made SciPy's a step 3–4 times dearer on 256² maps and
  its Python set-up of the bounds cost 0.7 s a solve), on variables scaled by the
  law's range and the largest traction w/range, so that the gradient is the force balance
  on each pixel in units of w/range. It is restarted (its memory cleared) when its line
  search stalls, as it can at the kink of the Maugis–Dugdale law.

**Sub-pixel quadrature** (``subpixel`` = k > 1): the interaction energy of a pixel is the
mean of φ over k × k points of it (the midpoints of its k × k sub-squares), the gap there
the bilinear interpolant of the pixel-centre gaps (:mod:`mcsim.physics.subpixel`; beyond
the map's edge the edge value, or the periodic image):

    E_int = (ΔA/k²) Σ_q φ((B g)_q),    ∂E_int/∂g = (ΔA/k²) Bᵀ φ'(B g),

B the interpolation (:func:`mcsim.physics.subpixel.spread`), Bᵀ its transpose
(:func:`~mcsim.physics.subpixel.gather`). It stays variational (the traction is −∂E_int/∂g,
so the energy checks, the continuation and the jump detection hold as before), and where
φ' is constant over a pixel and its neighbours it gives the pixel-centre traction (the
columns of B sum to k²). It cures the **lattice trapping** of a step law: at the pixel
centres the Dugdale traction acts on whole pixels, the zone's edge moves pixel by pixel
and the retraction holds on too long, an error first order in Δx/(zone width) (λ = 2:
+5.7 % in the sphere's pull-off on 128² pixels); with k² points the traction of a pixel
the edge crosses changes in k² steps (λ = 2: +0.17 % on 64² with k = 4; the grid
convergence in docs/contact.md). The contact condition g ≥ 0 stays on the pixel centres
(the interpolant is then ≥ 0 too), and so does the elastic part. Cost: φ and φ' on k²
points a pixel and B, Bᵀ (compiled), against two FFTs of the padded grid: a 64² sphere's
retraction takes 1.5–3 times as long with k = 4 and 12 times with k = 8
(validation/md_sphere.py).

**Convergence** (:func:`solve_gap`): the residual is the largest force imbalance, relative
to the largest traction of the law (w/range): |p + φ'(g)| on pixels out of contact (less the
mean pressure on a periodic map), the tension beyond what the wall can hold on pixels in
contact, and |p| on the padding. A solution is ``converged`` when it is below ``tol``.

**Continuation** (:func:`follow`; :func:`mcsim.physics.adhesivecycle.cycle` for an approach
and retraction with its jumps): each position is warm-started from the
previous solution. A step that lands on another branch changes the mean pressure by much
more than the previous step predicts, and dissipates energy: along one branch the energy
per area e obeys de/dd = −p̄, so D = e₀ − e₁ − ½(p̄₀ + p̄₁)(d₁ − d₀) > 0 measures what a
jump lost; bisection of d confirms and locates it.

Everything is SI: heights, gaps, positions and pixel sizes in m, E* and pressures in Pa,
energies per area in J/m².
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

import numpy as np
from scipy import fft

from mcsim.model.errors import ParameterError
from mcsim.physics import bem
from mcsim.physics.interactions import (
    Exponential,
    Interaction,
    MaugisDugdale,
    mesh_parameter,
)
from mcsim.physics.stickiness import MESH_LIMIT

#: Default tolerance: largest force imbalance relative to the largest traction w/range.
TOL = 1e-5
#: Default most quasi-Newton iterations of one solve.
MAX_ITER = 5000
#: A pixel is in contact when its gap is below this fraction of the law's range.
CONTACT_GAP = 1e-9
#: Smallest range allowed, relative to the pixel size.
MIN_RANGE_PER_PIXEL = 1e-3
_MEMORY = 10  # correction pairs of the quasi-Newton method
_RESTARTS = 20  # most restarts (memory cleared) in one solve
_ARMIJO = 1e-4  # sufficient decrease of the line search
_HALVINGS = 40  # most halvings of one line search
_ROUNDING = 1e-10  # relative change of the energy below which its rounding hides a decrease


@dataclass(frozen=True)
class AdhesiveSolution:
    """The adhesive contact at one position of the flat.

    Attributes
    ----------
    position : float
        Imposed height d of the flat above the map's mean plane, m.
    mean_pressure : float
        Mean (nominal) pressure on the map, Pa: compressive positive, tensile negative.
    contact_fraction : float
        Fraction of pixels in contact (gap below :data:`CONTACT_GAP` × range).
    attractive_fraction : float
        Fraction of pixels whose gap is below the law's range (contact included).
    patches : int
        Contact patches (:func:`mcsim.physics.bem.count_patches`).
    mean_gap : float
        Mean gap over the map, m (equal to ``position`` on a periodic map).
    energy : float
        Elastic plus interaction energy per nominal area, J/m².
    iterations : int
        Quasi-Newton iterations of this solve.
    residual : float
        Largest force imbalance relative to w/range (module docstring).
    converged : bool
        ``residual <= tol`` within ``max_iter`` iterations.
    padding_residual : float
        Largest |pressure| on the padding of a non-periodic map, relative to w/range (0 on
        a periodic map).
    gap_field, pressure_field : ndarray or None
        Gap (m) and pressure (Pa, tensile negative) on each pixel, when kept.
    displacement_field : ndarray or None
        The solver's displacement variables (m; on the padded grid of a non-periodic
        map), when kept: ``initial`` of the next :func:`solve_gap`.
    """

    position: float
    mean_pressure: float
    contact_fraction: float
    attractive_fraction: float
    patches: int
    mean_gap: float
    energy: float
    iterations: int
    residual: float
    converged: bool
    padding_residual: float
    gap_field: np.ndarray | None = None
    pressure_field: np.ndarray | None = None
    displacement_field: np.ndarray | None = None


def check_inputs(heights, pixel_size, E_star: float, law: Interaction) -> np.ndarray:
    """Check a problem's inputs; return the heights as floats.

    Parameters
    ----------
    heights : array_like
        Height map, m, 2-D, finite.
    pixel_size : float or (float, float)
        Pixel size, m.
    E_star : float
        Contact modulus E*, Pa.
    law : MaugisDugdale or Exponential
        The interaction.

    Returns
    -------
    ndarray

    Raises
    ------
    ParameterError
        A bad map, modulus or law, or a range below :data:`MIN_RANGE_PER_PIXEL` of the pixel
        or above the map's height range.

    Warns
    -----
    UserWarning
        When the mesh parameter (:func:`mcsim.physics.interactions.mesh_parameter`) exceeds
        :data:`mcsim.physics.stickiness.MESH_LIMIT`: the pixels do not resolve the law.
    """
    z = np.asarray(heights, dtype=float)
    if z.ndim != 2 or min(z.shape) < 2:
        raise ParameterError(
            f"`heights` must be a 2-D map of at least 2 x 2 pixels, got shape {z.shape}"
        )
    if not np.all(np.isfinite(z)):
        raise ParameterError("`heights` must be finite: fill or crop the map's missing pixels")
    if not (math.isfinite(E_star) and E_star > 0):
        raise ParameterError(f"`E_star` must be positive and finite, Pa, got {E_star!r}")
    if not isinstance(law, MaugisDugdale | Exponential):
        raise ParameterError(f"`law` must be MaugisDugdale or Exponential, got {law!r}")
    dx = max(bem.pixel_sides(pixel_size))
    if law.range < MIN_RANGE_PER_PIXEL * dx:
        raise ParameterError(
            f"`range` = {law.range:.4g} m is below {MIN_RANGE_PER_PIXEL:g} of the pixel size "
            f"({dx:.4g} m): the pixels cannot resolve the law"
        )
    span = float(z.max() - z.min())
    if law.range > span:
        raise ParameterError(
            f"`range` = {law.range:.4g} m is above the map's height range ({span:.4g} m): "
            "the law reaches over the whole map"
        )
    mesh = mesh_parameter(law, dx, E_star)
    if mesh > MESH_LIMIT:
        warnings.warn(
            f"mesh parameter sqrt(|phi''| dx / E*) = {mesh:.3g} > {MESH_LIMIT}: the pixels "
            "do not resolve the interaction (Wang, Zhou & Muser 2021); refine the map",
            stacklevel=2,
        )
    return z


def _unit_stiffness(shape: tuple[int, int], pixel_size) -> np.ndarray:
    """|q|/2, 1/m: the periodic stiffness p̃/ũ for E* = 1 Pa, zero at q = 0 (whose mode, the
    mean displacement, is not a variable)."""
    response = bem.periodic_response(shape, pixel_size, 1.0)
    with np.errstate(divide="ignore"):
        return np.where(response > 0, 1.0 / response, 0.0)


def _dot(a: np.ndarray, b: np.ndarray) -> float:
    """Σ a·b without BLAS, whose threads fight the FFT's on a shared machine (as in bem)."""
    return float(np.einsum("i,i->", a, b))


def _projected_lbfgs(fun, x, lower, tol: float, max_iter: int) -> tuple[np.ndarray, int]:
    """Minimise ``fun`` (value and gradient) subject to x ≥ ``lower``: the two-loop L-BFGS
    direction (Nocedal, Math. Comp. 35, 773, 1980) on the free variables, projected onto the
    bounds, with Armijo backtracking along the projected path (Bertsekas, IEEE Trans. Autom.
    Control 21, 174, 1976; the scheme of L-BFGS-B without its Cauchy point, Byrd et al. 1995).
    A variable at its bound whose gradient pushes into it is fixed for the step. Stops when
    the projected gradient's largest component is at most ``tol``, after ``max_iter``
    iterations, or when the line search fails; returns (x, iterations). Where the energy's
    change is within its rounding, the line search judges the decrease by the gradients."""
    x = np.maximum(x, lower)
    f, g = fun(x)
    pairs: list[tuple[np.ndarray, np.ndarray, float]] = []
    for iteration in range(max_iter + 1):
        active = (x <= lower) & (g > 0)
        pg = np.where(active, 0.0, g)
        largest = float(np.abs(pg).max())
        if largest <= tol or iteration == max_iter:
            return x, iteration
        q, alphas = pg.copy(), []
        for s, y, rho in reversed(pairs):
            alphas.append(rho * _dot(s, q))
            q -= alphas[-1] * y
        s, y, rho = pairs[-1] if pairs else (None, None, 0.0)
        q *= 1.0 / (rho * _dot(y, y)) if pairs else 1.0 / largest  # first: unit largest move
        for (s, y, rho), alpha in zip(pairs, reversed(alphas), strict=True):
            q += (alpha - rho * _dot(y, q)) * s
        direction = np.where(active, 0.0, -q)
        if not _dot(direction, pg) < 0:  # not a descent direction: steepest descent
            direction, pairs = -pg / largest, []
        t = 1.0
        for _ in range(_HALVINGS):
            x_new = np.maximum(x + t * direction, lower)
            f_new, g_new = fun(x_new)
            step = x_new - x
            wanted = _ARMIJO * _dot(g, step)
            if f_new - f <= wanted:
                break
            # near the minimum the decrease falls below the rounding of f: estimate it from
            # the gradients instead (exact for a quadratic: Δf = ½ (g + g_new)·step)
            if abs(f_new - f) <= _ROUNDING * abs(f) and 0.5 * _dot(g + g_new, step) <= wanted:
                break
            t *= 0.5
        else:
            return x, iteration
        s, y = x_new - x, g_new - g
        sy = _dot(s, y)
        if sy > 1e-12 * _dot(y, y):  # keep the pair where the curvature is positive
            pairs = [*pairs[1 - _MEMORY :], (s, y, 1.0 / sy)]
        x, f, g = x_new, f_new, g_new
    return x, max_iter


class Problem:
    """One map, modulus and law in the solver's units: lengths per range, pressures per
    largest traction, energies per w and pixel."""

    def __init__(self, heights, pixel_size, E_star: float, law: Interaction, periodic: bool,
                 subpixel: int = 1):  # fmt: skip
        z = check_inputs(heights, pixel_size, E_star, law)
        check_subpixel(subpixel)
        dx, dy = bem.pixel_sides(pixel_size)
        self.law, self.periodic, self.shape = law, periodic, z.shape
        self.subpixel = int(subpixel)
        self.length, self.traction = law.range, law.max_traction
        self.z = (z - z.mean()) / self.length
        scale = E_star * self.length**2 / law.w  # stiffness per unit: (Pa/m) · range / traction
        if periodic:
            self.grid = z.shape
            stiffness = _unit_stiffness(z.shape, (dx, dy))
        else:
            self.grid = (2 * z.shape[0], 2 * z.shape[1])
            stiffness = 1.0 / bem.padded_response(z.shape, (dx, dy), 1.0).real
        self.stiffness = stiffness * scale
        self.size = z.size

    def pressure(self, u: np.ndarray) -> np.ndarray:
        """Elastic pressure of a displacement on the grid, both dimensionless."""
        return fft.irfft2(fft.rfft2(u, workers=-1) * self.stiffness, s=self.grid, workers=-1)

    def law_terms(self, g: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """φ/w (summed: the interaction energy) and ∂/∂g of that sum · range/w, of
        dimensionless gaps, from the law's own functions; with ``subpixel`` k > 1, φ at the
        k × k points of each pixel on the bilinear interpolant of the gaps."""
        if self.subpixel == 1:
            gap = g * self.length
            return self.law.energy(gap) / self.law.w, self.law.pressure(gap) / -self.traction
        from mcsim.physics.subpixel import gather, spread  # numba, only when asked for

        k, wrap = self.subpixel, self.periodic
        gap = spread(g, k, wrap) * self.length
        weight = 1.0 / k**2
        phi = self.law.energy(gap) * (weight / self.law.w)
        dphi = gather(self.law.pressure(gap) * (weight / -self.traction), k, wrap)
        return phi, dphi

    def start(self, d: float, initial: np.ndarray | None) -> np.ndarray:
        """Feasible starting variables: ``initial`` (m) or the undeformed surface."""
        ny, nx = self.shape
        if initial is None:
            u = np.zeros(self.grid)
        else:
            u = np.asarray(initial, dtype=float) / self.length
            if u.shape != self.grid:
                raise ParameterError(
                    f"`initial` must have the solver's shape {self.grid}, got {u.shape}"
                )
        if self.periodic:  # x = g ≥ 0, scaled to mean d
            x = np.maximum(u - u.mean() - self.z + d, 0.0)
            return x * (d / x.mean()) if x.mean() > 0 else np.full(self.shape, d)
        u = u.copy()
        u[:ny, :nx] = np.maximum(u[:ny, :nx], self.z - d)
        return u

    def evaluate(self, v: np.ndarray, d: float) -> dict:
        """The state of variables ``v`` at position ``d`` (both dimensionless)."""
        ny, nx = self.shape
        if self.periodic:
            x = v.reshape(self.shape)
            g = d * x / max(x.mean(), 1e-300)
            u = g + self.z - d
        else:
            u = v.reshape(self.grid)
            g = u[:ny, :nx] - self.z + d
        p = self.pressure(u)
        phi, dphi = self.law_terms(g)
        f = 0.5 * float(np.einsum("ij,ij->", u, p)) + float(phi.sum())
        force = p[:ny, :nx] + dphi  # ∂Π/∂g per pixel
        return {"x": v, "g": g, "u": u, "p": p, "force": force, "f": f}

    def objective(self, v: np.ndarray, d: float) -> tuple[float, np.ndarray]:
        """Π (per w and pixel area) and its gradient in the variables."""
        s = self.evaluate(v, d)
        if self.periodic:
            x = v.reshape(self.shape)
            mu = float(np.einsum("ij,ij->", s["force"], s["g"])) / (self.size * d)
            return s["f"], ((d / max(x.mean(), 1e-300)) * (s["force"] - mu)).ravel()
        grad = s["p"].copy()
        grad[: self.shape[0], : self.shape[1]] = s["force"]
        return s["f"], grad.ravel()

    def lower(self, d: float) -> np.ndarray:
        """Lower bounds of the variables: g ≥ 0 (none on the padding)."""
        if self.periodic:
            return np.zeros(self.size)
        lower = np.full(self.grid, -np.inf)
        lower[: self.shape[0], : self.shape[1]] = self.z - d
        return lower.ravel()

    def balance(self, s: dict, d: float) -> tuple[np.ndarray, float, float, float]:
        """Pressure field (dimensionless), mean pressure, residual and padding residual."""
        ny, nx = self.shape
        g, force = s["g"], s["force"]
        touching = g < CONTACT_GAP
        if self.periodic:
            mu = float(np.einsum("ij,ij->", force, g)) / (self.size * d)
            pressure, excess, padding = s["p"] - mu, force - mu, 0.0
        else:
            pressure, excess = s["p"][:ny, :nx], force
            outside = s["p"].copy()
            outside[:ny, :nx] = 0.0
            padding = float(np.abs(outside).max())
        free = np.where(touching, 0.0, np.abs(excess))
        held = np.where(touching, np.maximum(-excess, 0.0), 0.0)
        residual = max(float(free.max()), float(held.max()), padding)
        return pressure, float(pressure.mean()), residual, padding

    def solve(self, d_si: float, initial, tol: float, max_iter: int, keep: bool):
        """Minimise from ``initial`` (m), restarted when the line search stalls; returns
        (solution, displacement in m)."""
        if not math.isfinite(d_si):
            raise ParameterError(f"`position` must be finite, m, got {d_si!r}")
        d = d_si / self.length
        if self.periodic and d <= 0:
            raise ParameterError(
                f"`position` must be positive on a periodic map (it is the mean gap), got {d_si!r}"
            )
        v = self.start(d, initial).ravel()
        lower, iterations, f_old = self.lower(d), 0, math.inf
        for _ in range(_RESTARTS):
            if self.periodic:
                v = v * (d / max(v.mean(), 1e-300))
            v, nit = _projected_lbfgs(lambda x: self.objective(x, d), v, lower, tol,
                                      max_iter - iterations)  # fmt: skip
            iterations += max(nit, 1)
            s = self.evaluate(v, d)
            pressure, mean, residual, padding = self.balance(s, d)
            if residual <= tol or iterations >= max_iter or not s["f"] < f_old:
                break
            f_old = s["f"]
        return self._solution(d, s, pressure, mean, residual, padding, iterations, tol, keep)

    def _solution(self, d, s, pressure, mean, residual, padding, iterations, tol, keep):
        g, law = s["g"], self.law
        touching = g < CONTACT_GAP
        fields = {}
        if keep:
            fields = {"gap_field": g * self.length, "pressure_field": pressure * self.traction,
                      "displacement_field": s["u"] * self.length}  # fmt: skip
        solution = AdhesiveSolution(
            position=d * self.length, mean_pressure=mean * self.traction,
            contact_fraction=float(touching.mean()), attractive_fraction=float(np.mean(g < 1.0)),
            patches=bem.count_patches(touching, self.periodic), mean_gap=float(g.mean()) * law.range,
            energy=s["f"] * law.w / self.size, iterations=iterations, residual=residual,
            converged=bool(residual <= tol), padding_residual=padding, **fields,
        )  # fmt: skip
        return solution, s["u"] * self.length


def check_subpixel(subpixel: int) -> None:
    """Refuse a number of quadrature points per pixel side that is not an integer ≥ 1."""
    if isinstance(subpixel, bool) or not isinstance(subpixel, int | np.integer) or subpixel < 1:
        raise ParameterError(f"`subpixel` must be an integer >= 1, got {subpixel!r}")


def check_solver(tol: float, max_iter: int) -> None:
    """Refuse a tolerance outside (0, 1) or a number of iterations below 1."""
    if not (0 < tol < 1):
        raise ParameterError(f"`tol` must lie in (0, 1), got {tol!r}")
    if int(max_iter) != max_iter or max_iter < 1:
        raise ParameterError(f"`max_iter` must be a positive integer, got {max_iter!r}")


def solve_gap(
    heights,
    pixel_size,
    E_star: float,
    law: Interaction,
    position: float,
    *,
    periodic: bool,
    tol: float = TOL,
    max_iter: int = MAX_ITER,
    initial: np.ndarray | None = None,
    subpixel: int = 1,
) -> AdhesiveSolution:
    """Adhesive contact of a height map with a rigid flat at one position (module docstring).

    Parameters
    ----------
    heights : array_like
        Height map z, m (rows along y, columns along x), finite; higher is nearer the flat.
    pixel_size : float or (float, float)
        Pixel size, m: one value, or ``(dx, dy)``.
    E_star : float
        Contact modulus E*, Pa.
    law : MaugisDugdale or Exponential
        The interaction (:mod:`mcsim.physics.interactions`).
    position : float
        Height d of the flat above the map's mean plane, m (> 0 on a periodic map, where it
        is the mean gap).
    periodic : bool
        The map repeats; otherwise it is zero-padded (module docstring).
    tol : float
        Largest force imbalance relative to w/range (default :data:`TOL`).
    max_iter : int
        Most quasi-Newton iterations.
    initial : ndarray, optional
        :attr:`AdhesiveSolution.displacement_field` of a previous solve (a warm start).
    subpixel : int
        Quadrature points k per pixel side for the interaction energy (module docstring,
        "Sub-pixel quadrature"); 1 (default): φ at the pixel centres.

    Returns
    -------
    AdhesiveSolution
        With its fields; ``converged`` says whether ``tol`` was reached.

    References
    ----------
    Rey, Anciaux & Molinari, Comput. Mech. 60, 69 (2017); Nocedal, Math. Comp. 35, 773 (1980);
    Byrd, Lu, Nocedal & Zhu, SIAM J.
    Sci. Comput. 16, 1190 (1995).
    """
    check_solver(tol, max_iter)
    problem = Problem(heights, pixel_size, E_star, law, periodic, subpixel)
    return problem.solve(position, initial, tol, max_iter, keep=True)[0]


def follow(
    heights,
    pixel_size,
    E_star: float,
    law: Interaction,
    positions: Iterable[float],
    *,
    periodic: bool,
    tol: float = TOL,
    max_iter: int = MAX_ITER,
    keep_fields: bool = False,
    initial: np.ndarray | None = None,
    subpixel: int = 1,
) -> Iterator[AdhesiveSolution]:
    """Solutions at a sequence of positions, each warm-started from the previous one.

    Parameters
    ----------
    heights, pixel_size, E_star, law, periodic, tol, max_iter
        As for :func:`solve_gap`.
    positions : iterable of float
        Heights d of the flat, m: descending for an approach, ascending for a retraction.
    keep_fields : bool
        Keep each solution's fields (memory then grows with the steps).
    initial : ndarray, optional
        Displacement to start the first step from (a warm start), m.
    subpixel : int
        As for :func:`solve_gap`.

    Yields
    ------
    AdhesiveSolution
        One per position; only the previous displacement is kept between them.
    """
    check_solver(tol, max_iter)
    problem = Problem(heights, pixel_size, E_star, law, periodic, subpixel)
    u = initial
    for d in positions:
        solution, u = problem.solve(float(d), u, tol, max_iter, keep=keep_fields)
        yield solution

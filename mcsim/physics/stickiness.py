"""Where a height map meets adhesion: is it sticky, and can the grid and the model be trusted?

Four dimensionless numbers, each a pure function of SI scalars (vectorised), and
:func:`stickiness`, which measures a map's slopes, curvatures and full-contact energy and
returns them all as a :class:`Stickiness` with its :meth:`Stickiness.warnings`.

Definitions
-----------
Those of the Pastewka group, e.g. ``SurfaceTopography``'s ``rms_gradient`` and
``rms_curvature_from_area``, which returns half the Laplacian:

* rms slope h′ = √⟨|∇h|²⟩ (dimensionless);
* rms curvature h″ = √⟨(∇²h/2)²⟩, 1/m: the rms of the mean curvature (half the Laplacian).
  For h = a cos(kx): h′ = ak/√2, h″ = ak²/(2√2).

The numbers
-----------
1. **Pastewka–Robbins parameter** (Pastewka & Robbins, PNAS 111, 3298 (2014)):
   Π_PR = (h′ E* Δr / (2w)) · (h′² / (h″ Δr))^{2/3}; the contact is sticky (its repulsive area
   against load bends into the tensile quadrant) where Π_PR < 1. The factor 2 is κ_rep ≈ 2 of
   A_rep = κ_rep F/(h′E*); (h′²/(h″Δr))^{2/3} is the scaling of A_rep/A_att (the attractive
   ring of width s around a contact of diameter ∝ h′/h″, where the edge gap ∝ s^{3/2} reaches
   Δr). It holds while the interaction range is short against the gap scale near contact
   edges, g0 = (16/3) h′²/h″ (Monti, Sanner & Pastewka, Tribol. Lett. 69, 80 (2021)): Δr/g0 <
   :data:`PR_RANGE_LIMIT` = 0.1.
2. **Persson–Tosatti energy ratio** (Persson & Tosatti, J. Chem. Phys. 115, 5597 (2001),
   Eq. 2): the elastic energy per area stored when the surface is pressed flat into full
   contact, U_el/A = (E*/4) ∫ |q| C(q) d²q/(2π)², with C(q) normalised so that
   ∫ C d²q/(2π)² = ⟨h²⟩ (Jacobs, Junge & Pastewka, Surf. Topogr. Metrol. Prop. 5, 013001
   (2017); Persson's own C carries the 1/(2π)² inside, hence his "(E*/4)∫ d²q q C(q)").
   Full contact is energetically favourable (sticky) where U_el/A < w, i.e. the ratio
   U_el/(A w) < 1. For h = a cos(kx): U_el/A = E* k a²/8 = π E* a²/(4λ) (the pressure that
   flattens it is E* k a cos(kx)/2, and the energy is half its work, ½⟨p h⟩). On a map it is
   the discrete sum U_el/A = (E*/4) Σ_q |q| |H_q|²/N², H = the FFT of the N-pixel map.
3. **Generalised Tabor parameter** (Müser, Beilstein J. Nanotechnol. 5, 419 (2014); Wang,
   Zhou & Müser, Lubricants 9, 17 (2021)): μ_T = R^{1/3} ℓ_a^{2/3} / Δr with R = 1/h″ and
   ℓ_a = w/E*, the classical Tabor parameter (R w²/(E*² Δr³))^{1/3} with the summits' radius
   replaced by the rms curvature's. Large μ_T: short-ranged (JKR-like) adhesion.
4. **Mesh parameter** (Wang, Zhou & Müser, Lubricants 9, 17 (2021)):
   √(|V″|max Δx / E*), V(g) the interaction energy per area as a function of the gap and
   |V″|max the largest curvature of it; the grid resolves the interaction while it is below
   :data:`MESH_LIMIT` = 0.5. :func:`stickiness` takes the exponential law V(g) = −w e^{−g/Δr},
   whose |V″|max = w/Δr² (:func:`exponential_curvature`). A Maugis–Dugdale law (constant
   traction w/Δr up to the gap Δr) has a traction step, so an unbounded V″: no mesh resolves
   it, and the step smoothed over a gap interval δg gives |V″|max = w/(Δr δg).

The interaction range Δr is one number throughout: PR's range of the attraction, Müser's ρ,
and the decay length of the exponential law.

Validity
--------
All four assume linear elasticity of a half-space and small slopes (h′ ≲ 0.3); none of them
accounts for a finite sample (a map of side L only carries wavelengths up to L).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mcsim.model.errors import ParameterError

#: Δr/g0 above which the Pastewka–Robbins criterion is outside its validity (Monti et al. 2021).
PR_RANGE_LIMIT = 0.1

#: Mesh parameter √(|V″|max Δx/E*) above which the grid does not resolve the interaction.
MESH_LIMIT = 0.5

#: Fewest pixels along each side of a map.
MIN_SIDE = 3


def _checked(name: str, value, unit: str) -> np.ndarray:
    """``value`` as a float array, every element finite and > 0, or a ParameterError naming it."""
    a = np.asarray(value, dtype=float)
    bad = ~(np.isfinite(a) & (a > 0))
    if np.any(bad):
        first, unit = float(a[bad].flat[0]), f" {unit}" if unit else ""
        raise ParameterError(f"`{name}` = {first!r}{unit} is out of range (allowed: > 0{unit})")
    return a


def _result(a: np.ndarray):
    """A 0-d array as a float, anything else unchanged."""
    return float(a) if a.ndim == 0 else a


def pastewka_robbins(slope_rms, curvature_rms, e_star, w, delta_r):
    """Pastewka–Robbins parameter Π_PR = (h′E*Δr/(2w)) (h′²/(h″Δr))^{2/3}; sticky where < 1.

    Pastewka & Robbins, PNAS 111, 3298 (2014) (module docstring, point 1). Valid where
    Δr/g0 < :data:`PR_RANGE_LIMIT` (:func:`gap_scale`).

    Parameters
    ----------
    slope_rms : array_like
        rms slope h′ = √⟨|∇h|²⟩ (dimensionless).
    curvature_rms : array_like
        rms curvature h″ = √⟨(∇²h/2)²⟩, 1/m.
    e_star : array_like
        Contact modulus E*, Pa.
    w : array_like
        Work of adhesion, J/m².
    delta_r : array_like
        Range of the interaction Δr, m.

    Returns
    -------
    float or ndarray
        Π_PR (dimensionless), broadcast over the inputs.
    """
    h1 = _checked("slope_rms", slope_rms, "")
    h2 = _checked("curvature_rms", curvature_rms, "1/m")
    e = _checked("e_star", e_star, "Pa")
    w = _checked("w", w, "J/m^2")
    dr = _checked("delta_r", delta_r, "m")
    return _result(h1 * e * dr / (2 * w) * (h1**2 / (h2 * dr)) ** (2 / 3))


def gap_scale(slope_rms, curvature_rms):
    """Gap scale near contact edges g0 = (16/3) h′²/h″, m (Monti, Sanner & Pastewka 2021).

    Parameters
    ----------
    slope_rms : array_like
        rms slope h′ (dimensionless).
    curvature_rms : array_like
        rms curvature h″ = √⟨(∇²h/2)²⟩, 1/m.

    Returns
    -------
    float or ndarray
        g0, m. The Pastewka–Robbins criterion holds where Δr/g0 < :data:`PR_RANGE_LIMIT`.
    """
    h1 = _checked("slope_rms", slope_rms, "")
    h2 = _checked("curvature_rms", curvature_rms, "1/m")
    return _result(16 / 3 * h1**2 / h2)


def tabor_parameter(curvature_rms, e_star, w, delta_r):
    """Generalised Tabor parameter μ_T = R^{1/3} (w/E*)^{2/3} / Δr with R = 1/h″.

    Müser, Beilstein J. Nanotechnol. 5, 419 (2014); Wang, Zhou & Müser, Lubricants 9, 17
    (2021) (module docstring, point 3).

    Parameters
    ----------
    curvature_rms : array_like
        rms curvature h″ = √⟨(∇²h/2)²⟩, 1/m.
    e_star : array_like
        Contact modulus E*, Pa.
    w : array_like
        Work of adhesion, J/m².
    delta_r : array_like
        Range of the interaction ρ = Δr, m.

    Returns
    -------
    float or ndarray
        μ_T (dimensionless).
    """
    h2 = _checked("curvature_rms", curvature_rms, "1/m")
    e = _checked("e_star", e_star, "Pa")
    w = _checked("w", w, "J/m^2")
    dr = _checked("delta_r", delta_r, "m")
    return _result((1 / h2) ** (1 / 3) * (w / e) ** (2 / 3) / dr)


def exponential_curvature(w, delta_r):
    """Largest |V″| of the exponential law V(g) = −w e^{−g/Δr}: w/Δr², Pa/m (at contact, g = 0).

    Parameters
    ----------
    w : array_like
        Work of adhesion, J/m².
    delta_r : array_like
        Decay length Δr, m.

    Returns
    -------
    float or ndarray
        |V″|max, J/m⁴ = Pa/m.
    """
    w = _checked("w", w, "J/m^2")
    dr = _checked("delta_r", delta_r, "m")
    return _result(w / dr**2)


def mesh_parameter(curvature_max, pixel_size, e_star):
    """Mesh parameter √(|V″|max Δx / E*); the grid resolves the interaction below 0.5.

    Wang, Zhou & Müser, Lubricants 9, 17 (2021) (module docstring, point 4).

    Parameters
    ----------
    curvature_max : array_like
        Largest curvature |V″|max of the interaction energy per area against the gap, Pa/m
        (:func:`exponential_curvature` for the exponential law).
    pixel_size : array_like
        Grid spacing Δx, m.
    e_star : array_like
        Contact modulus E*, Pa.

    Returns
    -------
    float or ndarray
        The mesh parameter (dimensionless); compare with :data:`MESH_LIMIT`.
    """
    v2 = _checked("curvature_max", curvature_max, "Pa/m")
    dx = _checked("pixel_size", pixel_size, "m")
    e = _checked("e_star", e_star, "Pa")
    return _result(np.sqrt(v2 * dx / e))


def _checked_map(z, pixel_size: float) -> np.ndarray:
    z = np.asarray(z, dtype=float)
    if z.ndim != 2 or min(z.shape) < MIN_SIDE:
        raise ParameterError(
            f"`z` must be a 2-D height map with at least {MIN_SIDE}×{MIN_SIDE} pixels, "
            f"got shape {z.shape}"
        )
    if not np.all(np.isfinite(z)):
        raise ParameterError(
            f"`z` has {np.count_nonzero(~np.isfinite(z))} non-finite pixels (allowed: none; "
            "fill or crop them first)"
        )
    _checked("pixel_size", pixel_size, "m")
    return z - z.mean()


def hann_window(shape: tuple[int, int]) -> np.ndarray:
    """The 2-D Hann window of a non-periodic map, scaled so that its mean square is 1.

    The outer product of two periodic Hann windows sin²(πn/N), n = 0 … N−1; the scaling keeps
    the mean square of a windowed map an estimate of the map's own (used here and by
    :func:`mcsim.topography.synthesis.radial_psd`).

    Parameters
    ----------
    shape : tuple of int
        (rows, columns).

    Returns
    -------
    ndarray
        The window, dimensionless.
    """
    rows, cols = (np.sin(np.pi * np.arange(n) / n) ** 2 for n in shape)
    window = np.outer(rows, cols)
    return window / np.sqrt(np.mean(window**2))


def slope_curvature_rms(z, pixel_size: float, periodic: bool = False) -> tuple[float, float]:
    """rms slope h′ = √⟨|∇h|²⟩ and rms curvature h″ = √⟨(∇²h/2)²⟩ of a map by finite differences.

    ⟨|∇h|²⟩ = ⟨(∂_x h)²⟩ + ⟨(∂_y h)²⟩ with forward differences; ∇²h by the five-point
    Laplacian. Non-periodic: the differences that fit in the map (forward ones on N−1 pairs,
    the Laplacian on the interior pixels); periodic: they wrap across the edges. For
    h = a cos(kx) sampled with pixel Δx these give (2 sin(kΔx/2)/Δx) a/√2 and
    (4 sin²(kΔx/2)/Δx²) a/(2√2): below the continuum values by at most (kΔx)²/24 and
    (kΔx)²/12 relatively.

    Parameters
    ----------
    z : array_like
        Height map, m; rows along y, columns along x, square pixels. Only its mean is removed:
        level a measured map first (:func:`mcsim.topography.summits.level`).
    pixel_size : float
        Pixel size, m.
    periodic : bool
        The map repeats: differences wrap across the edges.

    Returns
    -------
    (float, float)
        h′ (dimensionless) and h″, 1/m.
    """
    z = _checked_map(z, pixel_size)
    dx = float(pixel_size)
    if periodic:
        slope2 = sum(np.mean((np.roll(z, -1, axis) - z) ** 2) for axis in (0, 1))
        laplacian = sum(np.roll(z, -1, axis) - 2 * z + np.roll(z, 1, axis) for axis in (0, 1))
    else:
        slope2 = sum(np.mean(np.diff(z, axis=axis) ** 2) for axis in (0, 1))
        laplacian = z[2:, 1:-1] + z[:-2, 1:-1] + z[1:-1, 2:] + z[1:-1, :-2] - 4 * z[1:-1, 1:-1]
    return math.sqrt(slope2) / dx, math.sqrt(np.mean((laplacian / 2) ** 2)) / dx**2


def full_contact_energy(z, pixel_size: float, e_star: float, periodic: bool = False) -> float:
    """Persson–Tosatti elastic energy per area of pressing the map flat: (E*/4)∫|q|C d²q/(2π)².

    Persson & Tosatti, J. Chem. Phys. 115, 5597 (2001), Eq. 2, with C normalised so that
    ∫C d²q/(2π)² = ⟨h²⟩ (module docstring, point 2). Computed as the discrete sum
    (E*/4) Σ_q |q| |H_q|²/N² over the map's FFT H (N pixels, q = 2π × ``numpy.fft.fftfreq``).
    A non-periodic map is multiplied by :func:`hann_window` first (its edges would otherwise
    add a spurious step at every edge).

    Parameters
    ----------
    z : array_like
        Height map, m; square pixels; its mean is removed.
    pixel_size : float
        Pixel size, m.
    e_star : float
        Contact modulus E*, Pa.
    periodic : bool
        The map repeats (no window).

    Returns
    -------
    float
        U_el/A, J/m². Sticky (full contact favourable) where it is below w.
    """
    z = _checked_map(z, pixel_size)
    e = float(_checked("e_star", e_star, "Pa"))
    if not periodic:
        z = z * hann_window(z.shape)
    qy, qx = (2 * np.pi * np.fft.fftfreq(n, pixel_size) for n in z.shape)
    q = np.hypot(qy[:, None], qx[None, :])
    power = np.abs(np.fft.fft2(z)) ** 2 / z.size**2
    return e / 4 * float(np.sum(q * power))


@dataclass(frozen=True)
class Stickiness:
    """Every stickiness diagnostic of one height map against one adhesive interaction.

    Attributes
    ----------
    slope_rms : float
        h′ = √⟨|∇h|²⟩ (dimensionless).
    curvature_rms : float
        h″ = √⟨(∇²h/2)²⟩, 1/m.
    pr_parameter : float
        Pastewka–Robbins Π_PR (dimensionless); sticky where < 1.
    gap_scale : float
        g0 = (16/3) h′²/h″, m.
    range_over_gap : float
        Δr/g0 (dimensionless); PR holds below :data:`PR_RANGE_LIMIT`.
    elastic_energy : float
        Persson–Tosatti U_el/A of full contact, J/m².
    energy_ratio : float
        U_el/(A w) (dimensionless); full contact favourable where < 1.
    tabor : float
        Generalised Tabor parameter μ_T (dimensionless).
    mesh : float
        Mesh parameter √(|V″|max Δx/E*) for the exponential law (dimensionless).
    e_star, w, delta_r, pixel_size : float
        The inputs: Pa, J/m², m, m.
    shape : tuple of int
        (rows, columns) of the map.
    periodic : bool
        The map was taken as repeating.
    """

    slope_rms: float
    curvature_rms: float
    pr_parameter: float
    gap_scale: float
    range_over_gap: float
    elastic_energy: float
    energy_ratio: float
    tabor: float
    mesh: float
    e_star: float
    w: float
    delta_r: float
    pixel_size: float
    shape: tuple[int, int]
    periodic: bool

    @property
    def sticky_pr(self) -> bool:
        """Sticky by Pastewka & Robbins (Π_PR < 1)."""
        return self.pr_parameter < 1

    @property
    def sticky_pt(self) -> bool:
        """Sticky by Persson & Tosatti (U_el/A < w)."""
        return self.energy_ratio < 1

    def warnings(self) -> list[str]:
        """One line per criterion that says the grid or the model cannot be trusted here.

        Returns
        -------
        list of str
            Empty where Δr/g0 < :data:`PR_RANGE_LIMIT` and the mesh parameter is below
            :data:`MESH_LIMIT`.
        """
        lines = []
        if not self.range_over_gap < PR_RANGE_LIMIT:
            lines.append(
                f"the Pastewka-Robbins criterion is outside its validity: Δr/g0 = "
                f"{self.range_over_gap:.3g} >= {PR_RANGE_LIMIT:g} (interaction range "
                f"{self.delta_r:.3g} m not short against the edge gap scale g0 = "
                f"{self.gap_scale:.3g} m; Monti, Sanner & Pastewka 2021)"
            )
        if not self.mesh < MESH_LIMIT:
            largest = MESH_LIMIT**2 * self.e_star * self.delta_r**2 / self.w
            lines.append(
                f"the grid does not resolve the interaction: √(|V''|max Δx/E*) = {self.mesh:.3g} "
                f">= {MESH_LIMIT:g} (pixel {self.pixel_size:.3g} m; below {largest:.3g} m needed "
                "for an exponential law of range Δr; Wang, Zhou & Müser 2021)"
            )
        return lines


def stickiness(
    z, pixel_size: float, e_star: float, w: float, delta_r: float, periodic: bool = False
) -> Stickiness:
    """Every stickiness diagnostic of a height map (module docstring), with its warnings.

    Parameters
    ----------
    z : array_like
        Levelled height map, m; rows along y, columns along x, square pixels; no NaN.
    pixel_size : float
        Pixel size, m.
    e_star : float
        Contact modulus E*, Pa.
    w : float
        Work of adhesion, J/m².
    delta_r : float
        Range of the interaction Δr, m (PR's range, Müser's ρ, the exponential law's decay).
    periodic : bool
        The map repeats: differences wrap, and no window before the FFT.

    Returns
    -------
    Stickiness
    """
    for name, value, unit in (
        ("e_star", e_star, "Pa"),
        ("w", w, "J/m^2"),
        ("delta_r", delta_r, "m"),
    ):
        _checked(name, value, unit)
    h1, h2 = slope_curvature_rms(z, pixel_size, periodic)
    if not (h1 > 0 and h2 > 0):
        raise ParameterError(
            f"`z` is flat (rms slope {h1:.3g}, rms curvature {h2:.3g} 1/m): no roughness to judge"
        )
    g0 = gap_scale(h1, h2)
    energy = full_contact_energy(z, pixel_size, e_star, periodic)
    return Stickiness(
        slope_rms=h1,
        curvature_rms=h2,
        pr_parameter=pastewka_robbins(h1, h2, e_star, w, delta_r),
        gap_scale=g0,
        range_over_gap=float(delta_r) / g0,
        elastic_energy=energy,
        energy_ratio=energy / float(w),
        tabor=tabor_parameter(h2, e_star, w, delta_r),
        mesh=mesh_parameter(exponential_curvature(w, delta_r), pixel_size, e_star),
        e_star=float(e_star),
        w=float(w),
        delta_r=float(delta_r),
        pixel_size=float(pixel_size),
        shape=(int(np.shape(z)[0]), int(np.shape(z)[1])),
        periodic=bool(periodic),
    )

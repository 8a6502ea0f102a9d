"""Pads synthesised from a measured map's spectrum: its radial PSD, a self-affine fit, Fourier synthesis.

Conventions
-----------
A map of Ny × Nx square pixels of side Δx (rows along y, columns along x) covers
A = Nx Ny Δx². Its FFT H_q (``numpy.fft.fft2``, unnormalised) gives the periodogram
C_q = A |H_q|² / N², N = Nx Ny, so that

    Σ_q C_q / A = ∫ C(q) d²q/(2π)² = ⟨h²⟩

(Parseval, exact for a periodic map; the mode spacing Δq_x Δq_y/(2π)² is 1/A): the
normalisation of Jacobs, Junge & Pastewka, Surf. Topogr. Metrol. Prop. 5, 013001 (2017),
Eq. 9 ff. C is in m⁴ and q in rad/m (q = 2π × ``numpy.fft.fftfreq``).

* :func:`radial_psd` levels the map (its mean if periodic, a plane otherwise,
  :func:`~mcsim.topography.summits.level`), multiplies a non-periodic one by the 2-D Hann
  window of :func:`mcsim.physics.stickiness.hann_window` (mean square 1, so Σ C_q/A still
  estimates ⟨h²⟩), and averages C_q over annuli of width Δq = 2π/max(Lx, Ly) centred on
  multiples of Δq (bin k holds the modes with round(|q|/Δq) = k; q = 0, the mean, is left out).
  Each bin's mean of n modes scatters by a relative √(2/n): the modes q and −q of a real map
  are the same number, so a bin holds about n/2 independent exponentially distributed
  ordinates.
* :func:`self_affine_fit` fits C(q) = C0 for q < q_r, C0 (q/q_r)^{−2(1+H)} above (a self-affine
  surface of Hurst exponent H with a roll-off at q_r; Jacobs et al. 2017, Eq. 21) by weighted
  least squares on ln C, profiled over q_r (module :func:`self_affine_fit`).
* :func:`synthesize` draws Gaussian random maps of a given isotropic PSD: white noise ξ
  (unit variance per pixel) is filtered in Fourier space, H_q = √(N C(|q|)/A) · FFT(ξ)_q, so
  that E|H_q|² = N² C(|q|)/A. H is Hermitian because ξ is real and C depends on |q| only, so
  the map is real (its imaginary part, rounding, is dropped). The maps are periodic, have
  zero mean (C(0) is set to 0) and the target mean square Σ_q C(|q|)/A **in expectation**
  (not rescaled): each pad's mean square scatters with variance 2 Σ_q (C_q/A)², as real pads
  cut from one surface do.
* :func:`synthesize_like` synthesises pads of a measured map's shape and pixel size from its
  radial PSD (``method="psd"``: each mode gets its own bin's mean, so the expected mean square
  is exactly the periodogram's Σ_k n_k C_k/A) or from its self-affine fit
  (``method="self-affine"``: the fitted H and q_r, with C0 scaled so that the expected mean
  square is that same number).

Randomness follows SPEC 7: ``np.random.default_rng(rng)`` once at the public entry, pad i from
the i-th child of ``Generator.spawn`` (``SeedSequence`` spawning), so the same ``rng`` gives
bit-identical pads and pad i does not depend on how many pads are drawn.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np
from scipy.special import digamma

from mcsim.model.errors import ParameterError
from mcsim.physics.stickiness import hann_window
from mcsim.topography.summits import level

#: Fewest pixels along each side of a map or a pad.
MIN_SIDE = 8

METHODS = ("psd", "self-affine")


def _check_pixel_size(pixel_size) -> float:
    if not (isinstance(pixel_size, int | float | np.floating | np.integer)
            and math.isfinite(pixel_size) and pixel_size > 0):  # fmt: skip
        raise ParameterError(f"`pixel_size` = {pixel_size!r} m is out of range (allowed: > 0 m)")
    return float(pixel_size)


def _check_shape(shape) -> tuple[int, int]:
    if len(shape) != 2 or min(shape) < MIN_SIDE:
        raise ParameterError(
            f"`shape` = {tuple(shape)} is out of range (allowed: 2-D, at least "
            f"{MIN_SIDE}×{MIN_SIDE} pixels)"
        )
    return int(shape[0]), int(shape[1])


def _check_map(z) -> np.ndarray:
    z = np.asarray(z, dtype=float)
    if z.ndim != 2:
        raise ParameterError(f"`z` must be a 2-D height map, got shape {z.shape}")
    _check_shape(z.shape)
    if not np.all(np.isfinite(z)):
        raise ParameterError(
            f"`z` has {np.count_nonzero(~np.isfinite(z))} non-finite pixels (allowed: none; "
            "fill or crop them first)"
        )
    return z


def wavevectors(shape: tuple[int, int], pixel_size: float) -> np.ndarray:
    """|q| of every mode of a map's FFT, rad/m (q = 2π × ``numpy.fft.fftfreq``), shape ``shape``."""
    qy, qx = (2 * np.pi * np.fft.fftfreq(n, pixel_size) for n in shape)
    return np.hypot(qy[:, None], qx[None, :])


def _bin_index(q: np.ndarray, width: float) -> np.ndarray:
    """The annulus of each |q|: round(|q|/Δq); the one rule of :func:`radial_psd` and its lookup."""
    return np.rint(q / width).astype(int)


@dataclasses.dataclass(frozen=True)
class RadialPSD:
    """The radially averaged periodogram of a map (module docstring); callable as C(q).

    Attributes
    ----------
    q : ndarray
        Mean |q| of each non-empty annulus's modes, rad/m.
    C : ndarray
        Mean periodogram C_q over the annulus, m⁴.
    n_modes : ndarray
        Number of modes in the annulus (q and −q counted apart).
    index : ndarray
        The annulus number k (centre kΔq).
    width : float
        Annulus width Δq = 2π/max(Lx, Ly), rad/m.
    area : float
        Map area A, m²; Σ n_modes·C/A is the map's (windowed) mean square.
    """

    q: np.ndarray
    C: np.ndarray
    n_modes: np.ndarray
    index: np.ndarray
    width: float
    area: float

    def __call__(self, q) -> np.ndarray:
        """C of the annulus that each |q| falls in (piecewise constant), 0 outside every annulus, m⁴."""
        k = _bin_index(np.asarray(q, dtype=float), self.width)
        table = np.zeros(int(self.index.max()) + 2)
        table[self.index] = self.C
        return table[np.clip(k, 0, table.size - 1)]

    def mean_square(self) -> float:
        """∫C d²q/(2π)² = Σ n_modes·C/A, m²: the map's mean square (exactly, if periodic)."""
        return float(np.sum(self.n_modes * self.C) / self.area)


def radial_psd(z, pixel_size: float, periodic: bool = False) -> RadialPSD:
    """The isotropic PSD C(q) of a map, ∫C d²q/(2π)² = ⟨h²⟩ (module docstring).

    Parameters
    ----------
    z : array_like
        Height map, m; rows along y, columns along x, square pixels, no NaN, at least 8×8.
    pixel_size : float
        Pixel size, m.
    periodic : bool
        The map repeats: only its mean is removed and no window is applied. Otherwise a plane
        is removed and the 2-D Hann window applied.

    Returns
    -------
    RadialPSD
    """
    z = _check_map(z)
    dx = _check_pixel_size(pixel_size)
    h = level(z, 0 if periodic else 1)
    if not periodic:
        h = h * hann_window(h.shape)
    area = h.size * dx**2
    periodogram = area * np.abs(np.fft.fft2(h)) ** 2 / h.size**2
    q = wavevectors(h.shape, dx)
    width = 2 * np.pi / (max(h.shape) * dx)
    k = _bin_index(q, width)
    k[0, 0] = -1  # the mean
    keep = k >= 0
    n = np.bincount(k[keep], minlength=k.max() + 1)
    total = np.bincount(k[keep], weights=periodogram[keep], minlength=k.max() + 1)
    q_sum = np.bincount(k[keep], weights=q[keep], minlength=k.max() + 1)
    full = np.flatnonzero(n)
    return RadialPSD(
        q=q_sum[full] / n[full],
        C=total[full] / n[full],
        n_modes=n[full],
        index=full,
        width=width,
        area=area,
    )


@dataclasses.dataclass(frozen=True)
class SelfAffineFit:
    """C(q) = C0 for q < q_r and C0 (q/q_r)^{−2(1+H)} above; callable as C(q).

    Attributes
    ----------
    hurst : float
        Hurst exponent H (dimensionless).
    hurst_se : float
        Its standard error from the weighted fit at the chosen q_r (dimensionless).
    q_r : float
        Roll-off wavevector, rad/m (the smallest q fitted where no roll-off is seen).
    C0 : float
        The plateau, m⁴.
    q_max : float
        The largest q fitted, rad/m.
    rms : float
        √(∫_{|q|<q_max} C d²q/(2π)²) of the model, m.
    """

    hurst: float
    hurst_se: float
    q_r: float
    C0: float
    q_max: float
    rms: float

    def __call__(self, q) -> np.ndarray:
        """The model's C at |q| (rad/m), m⁴."""
        q = np.asarray(q, dtype=float)
        return self.C0 * np.maximum(q / self.q_r, 1.0) ** (-2 * (1 + self.hurst))


def _model_mean_square(c0: float, q_r: float, hurst: float, q_max: float) -> float:
    """(1/2π)∫_0^{q_max} q C dq = C0 q_r²/(4π) [1 + (1 − (q_max/q_r)^{−2H})/H], m²."""
    log_ratio = math.log(max(q_max / q_r, 1.0))
    tail = 2 * log_ratio if hurst == 0 else -math.expm1(-2 * hurst * log_ratio) / hurst
    return c0 * q_r**2 / (4 * math.pi) * (1 + tail)


def self_affine_fit(q, C, n_modes=None) -> SelfAffineFit:
    """Fit C(q) = C0 (flat) below q_r and C0 (q/q_r)^{−2(1+H)} above, by weighted least squares.

    For each trial roll-off q_r among the given q (the smallest meaning no roll-off), ln C is
    linear in (ln C0, 1+H): ln C = ln C0 − 2(1+H) max(ln(q/q_r), 0), solved by weighted least
    squares; the q_r with the smallest weighted residual wins. With ``n_modes`` each point's
    ln C has variance ≈ 1/m, m = n/2 independent ordinates (module docstring), so the weights
    are m and ln C is first corrected for the bias of the log of a mean of m exponentials,
    E ln C̄ = ln C + ψ(m) − ln m. Without ``n_modes`` all weights are 1 and the standard error
    is scaled by the residual scatter.

    Parameters
    ----------
    q : array_like
        Wavevectors, rad/m, > 0 (e.g. :attr:`RadialPSD.q`).
    C : array_like
        PSD, m⁴, > 0.
    n_modes : array_like, optional
        Modes averaged into each C (:attr:`RadialPSD.n_modes`).

    Returns
    -------
    SelfAffineFit
    """
    q, c = np.asarray(q, dtype=float), np.asarray(C, dtype=float)
    if q.ndim != 1 or q.shape != c.shape or q.size < 4:
        raise ParameterError(f"`q` and `C` must be 1-D of one length ≥ 4, got {q.shape}, {c.shape}")
    for name, a, unit in (("q", q, "rad/m"), ("C", c, "m^4")):
        if not np.all(np.isfinite(a) & (a > 0)):
            raise ParameterError(f"`{name}` must be finite and > 0 {unit} everywhere")
    order = np.argsort(q)
    q, y = q[order], np.log(c[order])
    if n_modes is None:
        weight = np.ones_like(q)
    else:
        m = np.asarray(n_modes, dtype=float)[order] / 2
        if m.shape != q.shape or not np.all(m >= 0.5):
            raise ParameterError("`n_modes` must hold one count ≥ 1 per point of `q`")
        weight = m
        y = y - (digamma(m) - np.log(m))
    best = None
    for q_r in q[:-2]:
        x = np.stack([np.ones_like(q), -2 * np.maximum(np.log(q / q_r), 0.0)], axis=1)
        normal = x.T @ (weight[:, None] * x)
        params = np.linalg.solve(normal, x.T @ (weight * y))
        ssr = float(np.sum(weight * (y - x @ params) ** 2))
        if best is None or ssr < best[0]:
            best = (ssr, q_r, params, normal)
    ssr, q_r, (log_c0, one_plus_h), normal = best
    variance = np.linalg.inv(normal)[1, 1]
    if n_modes is None:
        variance *= ssr / (q.size - 3)
    c0, hurst = math.exp(log_c0), float(one_plus_h - 1)
    return SelfAffineFit(
        hurst=hurst,
        hurst_se=math.sqrt(variance),
        q_r=float(q_r),
        C0=c0,
        q_max=float(q[-1]),
        rms=math.sqrt(_model_mean_square(c0, float(q_r), hurst, float(q[-1]))),
    )


def _pads(shape, dx: float, psd: Callable, rng: np.random.Generator, n: int) -> np.ndarray:
    q = wavevectors(shape, dx)
    c = np.zeros(shape)
    c[q > 0] = np.asarray(psd(q[q > 0]), dtype=float)
    if not np.all(np.isfinite(c) & (c >= 0)):
        raise ParameterError("`psd` must return finite values ≥ 0 m^4 at every |q| > 0")
    area = c.size * dx**2
    gain = np.sqrt(c.size * c / area)
    pads = np.empty((n, *shape))
    for pad, child in zip(pads, rng.spawn(n)):
        pad[...] = np.fft.ifft2(gain * np.fft.fft2(child.standard_normal(shape))).real
    return pads


def _check_n(n) -> int:
    if not (isinstance(n, int | np.integer) and n >= 1):
        raise ParameterError(f"`n` = {n!r} is out of range (allowed: an integer ≥ 1)")
    return int(n)


def synthesize(shape, pixel_size: float, psd: Callable, rng=None, n: int = 1) -> np.ndarray:
    """``n`` periodic Gaussian pads of an isotropic PSD by Fourier filtering (module docstring).

    Parameters
    ----------
    shape : tuple of int
        (rows, columns) of each pad, at least 8×8.
    pixel_size : float
        Pixel size, m.
    psd : callable
        C(q): m⁴ for an array of |q| > 0 in rad/m (e.g. a :class:`RadialPSD` or a
        :class:`SelfAffineFit`).
    rng : None, int, SeedSequence or Generator
        Passed once to ``np.random.default_rng``; pad i comes from its i-th spawned child.
    n : int
        Number of pads.

    Returns
    -------
    ndarray
        Heights, m, shape (n, rows, columns); each pad's mean is 0 and its expected mean square
        Σ_q C(|q|)/A.
    """
    rng = np.random.default_rng(rng)
    shape = _check_shape(tuple(shape))
    return _pads(shape, _check_pixel_size(pixel_size), psd, rng, _check_n(n))


def synthesize_like(
    z, pixel_size: float, n: int = 1, rng=None, *, method: str = "psd", periodic: bool = False
) -> np.ndarray:
    """``n`` pads with a measured map's shape, pixel size and spectrum (module docstring).

    Parameters
    ----------
    z : array_like
        Height map, m (as :func:`radial_psd`).
    pixel_size : float
        Pixel size, m.
    n : int
        Number of pads.
    rng : None, int, SeedSequence or Generator
        Passed once to ``np.random.default_rng``.
    method : {"psd", "self-affine"}
        The map's own radial PSD, or its :func:`self_affine_fit` with C0 scaled so that the
        expected mean square is the map's periodogram's.
    periodic : bool
        The map repeats (:func:`radial_psd`).

    Returns
    -------
    ndarray
        Heights, m, shape (n, rows, columns) of ``z``.
    """
    rng = np.random.default_rng(rng)
    if method not in METHODS:
        raise ParameterError(f"`method` = {method!r} is not one of {', '.join(METHODS)}")
    n = _check_n(n)
    spectrum = radial_psd(z, pixel_size, periodic)
    shape, dx = np.shape(z), float(pixel_size)
    psd: Callable = spectrum
    if method == "self-affine":
        fit = self_affine_fit(spectrum.q, spectrum.C, spectrum.n_modes)
        q = wavevectors(shape, dx)
        scale = spectrum.mean_square() * spectrum.area / float(np.sum(fit(q[q > 0])))
        psd = dataclasses.replace(fit, C0=fit.C0 * scale, rms=fit.rms * math.sqrt(scale))
    return _pads(shape, dx, psd, rng, n)

"""Two rough surfaces: a counter-surface facing the surface, and the correlation of their heights.

See docs/physics.md, section 'Two rough surfaces'.

The gap between two rough surfaces is the difference of their topographies, z = z1 − z2
(both heights measured upward in one frame). GW's model of two rough surfaces is one rough
surface, the difference, against a flat. For heights of rms σ1, σ2 and correlation
ρ = cov(z1, z2)/(σ1 σ2) the difference has

    σ² = σ1² + σ2² − 2ρ σ1 σ2,

and so does each spectral moment of an isotropic Gaussian surface (m0 = ⟨z²⟩, m2 = ⟨z_x²⟩,
m4 = ⟨z_xx²⟩), since a slope or curvature of the difference is the difference of the
slopes or curvatures:

    m_n = m_n1 + m_n2 − 2ρ √(m_n1 m_n2).

**Assumption**: one ρ for all three moments (heights, slopes and curvatures correlate
alike: a coherence independent of wavelength). Nothing in a GW surface's σ, R, η says how
the correlation depends on wavelength; one number is the simplest model that reduces to
the two exact limits, independent surfaces (ρ = 0) and a perfect replica (ρ = 1, flat gap).

The GW parameters go through the moments (Nayak 1971; McCool, Wear 107, 37, 1986): a
Gaussian isotropic surface has η = m4/(6π√3 m2), R = 0.375 √(π/m4),
σ_s² = m0 − 0.8968 m2²/m4 = (1 − 0.8968/α) m0, α = m0 m4/m2², and its mean summit plane lies
y_s = 4 √(m0/(πα)) above the mean plane. :func:`spectral_moments` inverts them for each
surface, :func:`combine` adds the moments and returns the summits of the sum. At ρ = 0 the
radius obeys 1/R² = 1/R1² + 1/R2², the rule of the paper's Table 1
(:func:`mcsim.model.params.combine_surfaces`), which this generalises: it also derives η.

Why ρ matters: a MEMS beam released from a sacrificial layer partly replicates the
substrate it was deposited on (DelRio et al., Appl. Phys. Lett. 90, 163104, 2007), so the
two faces are positively correlated (ρ > 0) and the gap is smoother than two independent
surfaces would make it.

Combined here: two Gaussian GW surfaces given by σ, R, η. Refused (one-line errors): a
measured summit-height histogram, a radius by height, given ``rq``/``summit_offset``/
``map_heights`` (measured heights about a mean plane): their shapes do not combine through
three moments. Two measured height maps combine exactly, as maps (``mcsim ingest MAP
--counter-surface MAP2``, :func:`mcsim.topography.summits.facing_gap`).
"""

from __future__ import annotations

import math
from typing import NamedTuple

from mcsim.model.distributions import GAUSSIAN
from mcsim.model.errors import ParameterError
from mcsim.model.params import Surface, check_range
from mcsim.model.presets import as_surface

#: Nayak's constant in σ_s² = m0 − 0.8968 m2²/m4 (McCool 1986).
NAYAK = 0.8968

#: Name of the default counter-surface: a flat one (no counter-surface).
FLAT = "flat"


class Moments(NamedTuple):
    """Spectral moments of an isotropic Gaussian surface (McCool 1986).

    Attributes
    ----------
    m0 : float
        Mean square height ⟨z²⟩ about the mean plane, m².
    m2 : float
        Mean square slope ⟨(∂z/∂x)²⟩, dimensionless.
    m4 : float
        Mean square curvature ⟨(∂²z/∂x²)²⟩, m⁻².
    """

    m0: float
    m2: float
    m4: float


class Summits(NamedTuple):
    """GW summits of an isotropic Gaussian surface from its moments (:func:`summits_of`).

    Attributes
    ----------
    sigma : float
        Standard deviation of the summit heights σ_s, m.
    R : float
        Summit radius, m.
    eta : float
        Summit density η, m⁻².
    rq : float
        Rms height √m0 about the mean plane, m.
    summit_offset : float
        Mean summit height above the mean plane y_s = 4√(m0/(πα)), m.
    alpha : float
        Nayak's bandwidth parameter α = m0 m4/m2².
    """

    sigma: float
    R: float
    eta: float
    rq: float
    summit_offset: float
    alpha: float


def spectral_moments(sigma: float, R: float, eta: float) -> Moments:
    """The moments of the Gaussian surface whose summits are σ_s, R, η (McCool 1986, inverted).

    m4 = π(0.375/R)², m2 = m4/(6π√3 η), m0 = σ_s² + 0.8968 m2²/m4.

    Parameters
    ----------
    sigma : float
        Standard deviation of the summit heights σ_s, m.
    R : float
        Summit radius, m.
    eta : float
        Summit density η, m⁻².
    """
    m4 = math.pi * (0.375 / R) ** 2
    m2 = m4 / (6 * math.pi * math.sqrt(3) * eta)
    m0 = sigma**2 + NAYAK * m2**2 / m4
    return Moments(m0, m2, m4)


def summits_of(m0: float, m2: float, m4: float, alpha: float | None = None) -> Summits:
    """The GW summits of an isotropic Gaussian surface of moments m0, m2, m4 (Nayak 1971;
    McCool 1986): η = m4/(6π√3 m2), R = 0.375√(π/m4), σ_s = √((1 − 0.8968/α) m0) (0 where
    α ≤ 0.8968), y_s = 4√(m0/(πα)).

    Parameters
    ----------
    m0, m2, m4 : float
        Moments, m², 1, m⁻² (> 0).
    alpha : float, optional
        α = m0 m4/m2² if already computed (a map's, from its normalised moments); default
        computed here.
    """
    alpha = m0 * m4 / m2**2 if alpha is None else alpha
    return Summits(
        sigma=math.sqrt(max(1 - NAYAK / alpha, 0.0) * m0),
        R=0.375 * math.sqrt(math.pi / m4),
        eta=m4 / (6 * math.pi * math.sqrt(3) * m2),
        rq=math.sqrt(m0),
        summit_offset=4 * math.sqrt(m0 / (math.pi * alpha)),
        alpha=alpha,
    )


def check_correlation(value, name: str = "correlation") -> float:
    """ρ as a float in [−1, 1]; anything else (NaN, ±inf, out of range, not a number) raises
    a ParameterError naming ``name``, the value and the range."""
    return check_range(name, value, "1", low=-1.0, high=1.0, low_open=False, high_open=False)


def difference_moment(a: float, b: float, correlation: float) -> float:
    """A moment of the difference of two surfaces: a + b − 2ρ√(ab) (0 if rounding makes it
    negative: ρ = 1 and a = b).

    Parameters
    ----------
    a, b : float
        The same moment of each surface (m0 in m², m2, m4 in m⁻²; or any variance).
    correlation : float
        ρ in [−1, 1].
    """
    return max(a + b - 2 * correlation * math.sqrt(a * b), 0.0)


def combined_rms(sigma1: float, sigma2: float, correlation: float) -> float:
    """Rms of the difference of two heights of rms σ1, σ2 and correlation ρ:
    √(σ1² + σ2² − 2ρσ1σ2), m.

    ρ = 0: √(σ1² + σ2²); ρ = −1: σ1 + σ2; ρ = 1: |σ1 − σ2|.
    """
    return math.sqrt(difference_moment(sigma1**2, sigma2**2, check_correlation(correlation)))


def _check_plain(surface: Surface, role: str) -> None:
    """Refuse what does not combine through the moments (module docstring)."""
    label = f"{role} {surface.name!r}" if surface.name else role
    given = [
        name
        for name in ("rq", "summit_offset", "map_heights")
        if getattr(surface, name) is not None
    ]
    if surface.heights != GAUSSIAN:
        why = f"has measured summit heights ({surface.heights.name})"
    elif surface.radius_by_height is not None:
        why = "has a radius by height"
    elif given:
        why = f"gives {', '.join(given)} (measured heights about its mean plane)"
    else:
        return
    raise ParameterError(
        f"counter-surface: the {label} {why}: only two Gaussian GW surfaces (sigma, R, eta) "
        "combine through their spectral moments; combine two measured height maps as maps "
        "(mcsim ingest MAP --counter-surface MAP2)"
    )


def combine(
    surface: Surface | str, counter: Surface | str | None = None, correlation: float = 0.0
) -> Surface:
    """The GW surface of the gap between ``surface`` and a rough ``counter``-surface.

    Each surface's σ_s, R, η is turned into its spectral moments (:func:`spectral_moments`),
    each moment of the difference is m_n1 + m_n2 − 2ρ√(m_n1 m_n2) (one ρ for all moments:
    see the module docstring), and the summits of the sum (:func:`summits_of`) are returned
    with their rq and summit offset (Nayak 1971; McCool, Wear 107, 37, 1986).

    Parameters
    ----------
    surface : Surface or str
        The surface (or a preset's name): Gaussian summit heights, one radius.
    counter : Surface or str or None
        The counter-surface facing it (or a preset's name), as ``surface``; None or
        ``"flat"``: a flat counter-surface, and ``surface`` itself is returned (the same
        object).
    correlation : float
        ρ, the correlation of the two surfaces' heights (and slopes and curvatures) in one
        frame, in [−1, 1]: 0 independent, > 0 partly replicated (a beam released from a
        layer deposited on its substrate; DelRio et al., Appl. Phys. Lett. 90, 163104, 2007).
        Must be 0 without a counter-surface.

    Returns
    -------
    Surface
        Named ``"<surface>-on-<counter>"``, with ``rq`` and ``summit_offset`` of the sum.

    Raises
    ------
    ParameterError
        ρ outside [−1, 1] or NaN; ρ ≠ 0 with a flat counter-surface; a surface that does
        not combine (module docstring); a flat gap (ρ = 1 with identical surfaces) or moments
        with no summit population (α ≤ 0.8968); a combination outside the ranges of
        :class:`~mcsim.model.params.Surface`.
    """
    correlation = check_correlation(correlation)
    return gap_surface(as_surface(surface), as_counter(counter), correlation)


def as_counter(value: Surface | str | None) -> Surface | None:
    """A counter-surface argument resolved: None for a flat one (None or ``"flat"``), else
    :func:`~mcsim.model.presets.as_surface` (a Surface or a preset's name, the field named
    ``counter-surface``)."""
    if value is None or (isinstance(value, str) and value == FLAT):
        return None
    return as_surface(value, "counter-surface")


def gap_surface(surface: Surface, counter: Surface | None, correlation: float = 0.0) -> Surface:
    """:func:`combine` of surfaces resolved already (``counter`` None: flat), as every module
    below the public boundary calls it; parameters, result and errors as :func:`combine`'s."""
    correlation = check_correlation(correlation)
    if counter is None:
        if correlation != 0:
            raise ParameterError(f"correlation = {correlation!r} needs a counter-surface (a flat "
                                 "one has no heights to correlate with; allowed without one: 0)")  # fmt: skip
        return surface
    _check_plain(surface, "surface")
    _check_plain(counter, "counter-surface")
    one, two = (
        spectral_moments(surface.sigma, surface.R, surface.eta),
        spectral_moments(counter.sigma, counter.R, counter.eta),
    )
    m0, m2, m4 = (difference_moment(a, b, correlation) for a, b in zip(one, two, strict=True))
    floor = 1e-12  # relative: below it a moment is rounding of equal ones cancelling
    cancelled = [what for m, a, b, what in zip((m0, m2, m4), one, two, ("heights", "slopes",
                 "curvatures"), strict=True) if m <= floor * (a + b)]  # fmt: skip
    if cancelled:
        raise ParameterError(f"counter-surface: the combined surface is flat: at correlation = "
                             f"{correlation:g} the two surfaces' {' and '.join(cancelled)} cancel "
                             "(a perfect replica leaves no gap topography; allowed: a correlation "
                             "below 1, or surfaces that differ)")  # fmt: skip
    summits = summits_of(m0, m2, m4)
    if summits.alpha <= NAYAK:
        raise ParameterError(f"counter-surface: the combined moments have alpha = m0 m4/m2^2 = "
                             f"{summits.alpha:.4g} <= {NAYAK} at correlation = {correlation:g}: no "
                             "summit population (sigma_s^2 = m0 - 0.8968 m2^2/m4 <= 0); use a lower "
                             "correlation")  # fmt: skip
    name = f"{surface.name or 'surface'}-on-{counter.name or 'counter'}"
    try:
        return Surface(sigma=summits.sigma, R=summits.R, eta=summits.eta, name=name,
                       rq=summits.rq, summit_offset=summits.summit_offset)  # fmt: skip
    except ParameterError as err:
        raise ParameterError(f"counter-surface: the combined surface: {err}") from None

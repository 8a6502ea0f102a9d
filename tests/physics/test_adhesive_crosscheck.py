"""The adhesive FFT-BEM against ContactEngineering's Adhesion and ContactMechanics (optional).

ContactEngineering's ``Adhesion`` (MIT) minimises the same energy as
:mod:`mcsim.physics.adhesivebem`: the elastic energy of a periodic half-space
(ContactMechanics' ``PeriodicFFTElasticHalfSpace``, stiffness E*|q|/2 with ``young`` the
contact modulus E*) plus the exponential law φ = −γ0 e^{−g/ρ} per area
(``Adhesion.Interactions.Exponential(gamma0, rho)``, the same φ as mcsim's ``Exponential``),
with a hard wall (``BoundedSmoothContactSystem``), by SciPy's L-BFGS-B on the displacements.
The problems are matched as follows:

* **Geometry.** Their gap is u − h − offset, mcsim's u − z + d: the same heights
  (h = z, zero mean) and the same displacement, with offset = −d for the rigid part.
* **The q = 0 mode.** Theirs is a variable, held by a spring of the lowest non-zero
  stiffness π E*/L (``stiffness_q0=None``): their ``offset`` is a rigid displacement
  behind that spring, and their state at an offset has the mean gap ū − offset and the mean
  pressure (π E*/L) ū. mcsim imposes the mean gap (the mean displacement is not a variable).
  A state of theirs is a stationary state of mcsim's problem at its mean gap, so mcsim is
  solved at the mean gaps Adhesion reaches.
* **Units.** Theirs is solved in nm and GPa (every number of order one: SciPy's tolerances
  are absolute); w = 0.1 J/m² = 0.1 GPa·nm.
* **Tolerance.** Both stop on the largest force imbalance on a pixel (out of contact; the
  tension beyond what the wall holds in contact): mcsim at ``TOL`` × w/ρ per area, Adhesion
  at the projected gradient ``gtol`` = ``TOL`` × (w/ρ) × ΔA per pixel (``ftol = 0``, so that
  only that stops it). Each state is then within ``TOL`` × w/ρ of the exact force balance:
  the mean pressures may differ by 2 ``TOL`` × w/ρ, and the gaps by that imbalance over the
  stiffness of the softest mode, π E*/L less the interaction's largest curvature w/ρ² (an
  estimate of the largest gap difference: the imbalance as if it were all in the longest
  wave, where the half-space yields most).

Measured (Adhesion 0.93, ContactMechanics 1.8.3; 8 offsets from 2ρ above the highest
point, mean pressure −0.78 MPa, through −7.8 MPa to 206 MPa and 25 % of the pixels in
contact): mean pressures within 7.1e-7 w/ρ (bound 2e-5), gaps within 1.3e-6 ρ (bound
9.3e-6), the same contact pixels at every offset. Their offset against their mean gap and
pressure, to 4.4e-16 relative. The fixtures take about 2 s with ``OPENBLAS_NUM_THREADS=1``,
6 s without it at load 5 on 2 cores (SciPy's BLAS threads wait on each other).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mcsim.physics import adhesivebem
from mcsim.physics.interactions import Exponential, mesh_parameter
from mcsim.topography.synthesis import synthesize

SKIP = "not installed (optional: pip install -e '.[crosscheck]')"
pytest.importorskip("Adhesion", reason=f"Adhesion is {SKIP}")
pytest.importorskip("ContactMechanics", reason=f"ContactMechanics is {SKIP}")

NM, GPA = 1e-9, 1e9  # Adhesion's units: lengths in nm, pressures in GPa
N, SIDE, RMS, HURST = 64, 1e-6, 1e-9, 0.8  # a 64² self-affine map of 1 µm, rms 1 nm
E_STAR, W, RHO = 1e11, 0.1, 1e-9  # Pa, J/m², m
LAW = Exponential(W, RHO)
TOL = adhesivebem.TOL
# the last rigid offset, nm (the flat 0.2 nm below the mean plane before it deforms): mean
# pressure 206 MPa, 25 % of the pixels in contact
CLOSEST = 0.2
STEPS = 8
# force imbalance of either solution, Pa; the softest mode's stiffness, Pa/m
IMBALANCE = TOL * LAW.max_traction
SOFTEST = math.pi * E_STAR / SIDE - LAW.max_curvature


@pytest.fixture(scope="module")
def surface() -> np.ndarray:
    """The heights, m, zero mean; the law is resolved (mesh parameter 0.125 < 0.5)."""
    z = synthesize((N, N), SIDE / N, lambda q: q ** (-2 * (1 + HURST)), rng=1)[0]
    z = (z - z.mean()) * (RMS / z.std())
    assert mesh_parameter(LAW, SIDE / N, E_STAR) < 0.5
    return z


@pytest.fixture(scope="module")
def theirs(surface):
    """Adhesion's approach: rigid offsets from 2ρ above the highest point to ``CLOSEST`` below
    the mean plane, each warm-started from the previous displacement; per offset a dict of the
    offset (nm), the result, the mean displacement ū (nm), the gap field (nm) and the mean
    pressure (Pa); and their q = 0 stiffness (GPa/nm)."""
    from Adhesion.Interactions import Exponential as TheirExponential
    from Adhesion.System import BoundedSmoothContactSystem
    from ContactMechanics import PeriodicFFTElasticHalfSpace
    from SurfaceTopography import Topography

    side = SIDE / NM
    substrate = PeriodicFFTElasticHalfSpace((N, N), E_STAR / GPA, (side, side))
    system = BoundedSmoothContactSystem(
        substrate, TheirExponential(W / (GPA * NM), RHO / NM),
        Topography(surface / NM, (side, side), periodic=True),
    )  # fmt: skip
    options = {"gtol": IMBALANCE / GPA * (side / N) ** 2, "ftol": 0.0, "maxiter": 10_000}
    states, u = [], None
    for offset in -np.linspace(surface.max() / NM + 2 * RHO / NM, -CLOSEST, STEPS):
        result = system.minimize_proxy(offset=offset, initial_displacements=u, options=options)
        u = result.x
        states.append({"offset": offset, "result": result, "mean_u": float(u.mean()),
                       "gap": system.gap.copy(),
                       "pressure": system.compute_normal_force() / side**2 * GPA})  # fmt: skip
    return states, float(substrate.surface_stiffness[0, 0].real)


@pytest.fixture(scope="module")
def ours(surface, theirs):
    """mcsim's approach through the mean gaps Adhesion reached, warm-started, with fields."""
    gaps = [float(s["gap"].mean()) * NM for s in theirs[0]]
    return list(adhesivebem.follow(surface, SIDE / N, E_STAR, LAW, gaps, periodic=True,
                                   keep_fields=True))  # fmt: skip


def test_their_offset_is_a_rigid_shift_behind_a_spring_at_q0(theirs):
    # Their mean gap is ū − offset, and their mean pressure (π E*/L) ū: the offset imposes
    # the mean gap only through the lowest mode's spring. To rounding: the gap's sum over the
    # pixels, and the force summed over the pixels by their FFT.
    states, k0 = theirs
    eps = np.finfo(float).eps
    # their q = 0 stiffness: π E* q1 (q1 = 1/L) through two reciprocals
    assert k0 == pytest.approx(math.pi * (E_STAR / GPA) / (SIDE / NM), rel=4 * eps)
    rounding = N * N * eps
    for s in states:
        assert s["gap"].mean() == pytest.approx(s["mean_u"] - s["offset"], rel=rounding)
        assert s["pressure"] / GPA == pytest.approx(k0 * s["mean_u"], rel=rounding)


def test_both_converge_on_an_approach_through_tension_into_contact(theirs, ours):
    states, _ = theirs
    assert all(s["result"].success for s in states), [s["result"].message for s in states]
    assert all(s.converged for s in ours)
    pressures = [s["pressure"] for s in states]
    assert min(pressures) < -5e6 and max(pressures) > 1e8  # tensile, then compressive
    assert ours[0].contact_fraction == 0 and ours[-1].contact_fraction > 0.1


def test_mean_pressures_agree_within_both_tolerances(theirs, ours):
    measured = np.array([s.mean_pressure for s in ours])
    expected = np.array([s["pressure"] for s in theirs[0]])
    np.testing.assert_allclose(measured, expected, rtol=0, atol=2 * IMBALANCE)


def test_gap_fields_agree_within_both_tolerances_over_the_softest_stiffness(theirs, ours):
    bound = 2 * IMBALANCE / SOFTEST  # 9.3e-6 of the range
    for s, mine in zip(theirs[0], ours, strict=True):
        np.testing.assert_allclose(mine.gap_field, s["gap"] * NM, rtol=0, atol=bound)


def test_contact_pixels_agree_but_where_a_gap_is_within_the_bound(theirs, ours):
    # Their pixels in contact sit on the bound (gap exactly 0); mcsim's are below
    # CONTACT_GAP × range. A pixel in contact in one only must have a gap within the bound
    # of the gap fields' agreement in the other (none does here: the sets are equal).
    bound = 2 * IMBALANCE / SOFTEST
    for s, mine in zip(theirs[0], ours, strict=True):
        touching = s["gap"] == 0
        differ = touching != (mine.gap_field < adhesivebem.CONTACT_GAP * RHO)
        assert np.all(mine.gap_field[differ] <= bound)
        assert np.all(s["gap"][differ] * NM <= bound)
        assert mine.contact_fraction == pytest.approx(touching.mean(), abs=differ.mean())

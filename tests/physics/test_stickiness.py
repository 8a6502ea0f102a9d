"""Stickiness diagnostics: each number against a hand computation or a closed form, its scaling,
the warnings exactly where the criteria fail, and bad input refused by name."""

import dataclasses
import math

import numpy as np
import pytest

from mcsim.model.errors import ParameterError
from mcsim.physics.stickiness import (
    MESH_LIMIT,
    PR_RANGE_LIMIT,
    exponential_curvature,
    full_contact_energy,
    gap_scale,
    mesh_parameter,
    pastewka_robbins,
    slope_curvature_rms,
    stickiness,
    tabor_parameter,
)

#: Relative rounding of a few float operations (sums of a few thousand terms included).
ROUNDING = 1e-12


def wave(shape, pixel_size, amplitude, mx, my=0):
    """a cos(2π(mx x/Lx + my y/Ly)) on a periodic grid: exactly mx, my periods across the map."""
    ny, nx = shape
    y, x = np.meshgrid(np.arange(ny) / ny, np.arange(nx) / nx, indexing="ij")
    return amplitude * np.cos(2 * np.pi * (mx * x + my * y))


# --- the formulas by hand -------------------------------------------------------------------


def test_pastewka_robbins_by_hand():
    # h' = 0.2, h'' = 1e7 /m, Δr = 0.5 nm: h'²/(h''Δr) = 0.04/0.005 = 8, 8^(2/3) = 4;
    # h'E*Δr/(2w) = 0.2·1e9·5e-10/(2·0.05) = 1. So Π = 4.
    assert pastewka_robbins(0.2, 1e7, 1e9, 0.05, 5e-10) == pytest.approx(4.0, rel=ROUNDING)


def test_gap_scale_by_hand():
    # g0 = 16/3 · 0.04 / 1e7 = 0.64/3e7 m; Δr/g0 = 5e-10·3e7/0.64 = 3/128.
    assert gap_scale(0.2, 1e7) == pytest.approx(0.64 / 3e7, rel=ROUNDING)
    assert 5e-10 / gap_scale(0.2, 1e7) == pytest.approx(3 / 128, rel=ROUNDING)


def test_tabor_parameter_by_hand():
    # R = 1/h'' = 1 µm, ℓa = w/E* = 1/1e9 m: R^(1/3) ℓa^(2/3) = 1e-2 · 1e-6 = 1e-8 m; / 1 nm = 10.
    assert tabor_parameter(1e6, 1e9, 1.0, 1e-9) == pytest.approx(10.0, rel=ROUNDING)


def test_mesh_parameter_by_hand():
    # |V''| = w/Δr² = 0.05/(5e-10)² = 2e17 Pa/m; √(2e17 · 1e-9 / 1e9) = √0.2.
    assert exponential_curvature(0.05, 5e-10) == pytest.approx(2e17, rel=ROUNDING)
    assert mesh_parameter(2e17, 1e-9, 1e9) == pytest.approx(math.sqrt(0.2), rel=ROUNDING)


# --- scaling laws ----------------------------------------------------------------------------


def test_pastewka_robbins_scales_as_e_star_over_w_and_cube_root_of_range():
    base = pastewka_robbins(0.1, 3e6, 1e10, 0.1, 1e-9)
    np.testing.assert_allclose(pastewka_robbins(0.1, 3e6, [2e10, 5e10], 0.1, 1e-9),
                               [2 * base, 5 * base], rtol=ROUNDING)  # fmt: skip
    np.testing.assert_allclose(pastewka_robbins(0.1, 3e6, 1e10, [0.2, 0.4], 1e-9),
                               [base / 2, base / 4], rtol=ROUNDING)  # fmt: skip
    # Δr^(1 - 2/3) = Δr^(1/3); h''^(-2/3); h'^(1 + 4/3) = h'^(7/3).
    assert pastewka_robbins(0.1, 3e6, 1e10, 0.1, 8e-9) == pytest.approx(2 * base, rel=ROUNDING)
    assert pastewka_robbins(0.1, 24e6, 1e10, 0.1, 1e-9) == pytest.approx(base / 4, rel=ROUNDING)
    assert pastewka_robbins(0.8, 3e6, 1e10, 0.1, 1e-9) == pytest.approx(2**7 * base, rel=ROUNDING)


def test_tabor_parameter_scales_as_w_to_two_thirds_over_range():
    base = tabor_parameter(1e6, 1e9, 1.0, 1e-9)
    assert tabor_parameter(1e6, 1e9, 8.0, 1e-9) == pytest.approx(4 * base, rel=ROUNDING)
    assert tabor_parameter(1e6, 8e9, 1.0, 1e-9) == pytest.approx(base / 4, rel=ROUNDING)
    assert tabor_parameter(1e6, 1e9, 1.0, 3e-9) == pytest.approx(base / 3, rel=ROUNDING)


# --- the map's slopes, curvatures and full-contact energy -------------------------------------


def test_sinusoid_slope_and_curvature_are_the_discrete_values_and_near_the_continuum():
    """h = a cos(kx): continuum h' = ak/√2 and h'' = ak²/(2√2) (h'' the rms of ∇²h/2).

    Forward differences and the five-point Laplacian give them with k replaced by
    2 sin(kΔx/2)/Δx (slope) and its square (curvature), exactly on a periodic grid; the
    relative shortfall is at most (kΔx)²/24 and (kΔx)²/12.
    """
    dx, a, periods, n = 2e-9, 3e-9, 2, 128  # 64 pixels per wavelength
    k = 2 * np.pi * periods / (n * dx)
    slope, curvature = slope_curvature_rms(wave((16, n), dx, a, periods), dx, periodic=True)
    k_discrete = 2 * math.sin(k * dx / 2) / dx
    assert slope == pytest.approx(a * k_discrete / math.sqrt(2), rel=ROUNDING)
    assert curvature == pytest.approx(a * k_discrete**2 / (2 * math.sqrt(2)), rel=ROUNDING)
    assert 0 < 1 - slope / (a * k / math.sqrt(2)) <= (k * dx) ** 2 / 24
    assert 0 < 1 - curvature / (a * k**2 / (2 * math.sqrt(2))) <= (k * dx) ** 2 / 12


def test_slope_of_a_tilt_and_curvature_of_a_paraboloid_on_a_cut_out_map():
    dx, s, c = 1e-8, 0.03, 2e5
    y, x = np.meshgrid(np.arange(20) * dx, np.arange(30) * dx, indexing="ij")
    assert slope_curvature_rms(s * x + 2 * s * y, dx)[0] == pytest.approx(
        math.sqrt(5) * s, rel=ROUNDING
    )
    # z = c(x² + y²)/2: ∇²z/2 = c everywhere (the five-point Laplacian is exact on quadratics).
    assert slope_curvature_rms(c * (x**2 + y**2) / 2, dx)[1] == pytest.approx(c, rel=1e-9)


def test_full_contact_energy_of_a_sinusoid_is_its_closed_form():
    """h = a cos(q·r): the pressure that flattens it is p = E*|q|h/2 (Green's function
    2/(E*|q|)), and the energy is half its work, U/A = ⟨p h⟩/2 = E*|q|a²/8 = πE*a²/(4λ)."""
    shape, dx, a, e_star = (24, 40), 5e-9, 2e-9, 1.5e11
    qx, qy = 2 * np.pi * 3 / (40 * dx), 2 * np.pi * 2 / (24 * dx)
    energy = full_contact_energy(wave(shape, dx, a, 3, 2), dx, e_star, periodic=True)
    assert energy == pytest.approx(e_star * math.hypot(qx, qy) * a**2 / 8, rel=ROUNDING)
    lam = 40 * dx / 3
    along_x = full_contact_energy(wave(shape, dx, a, 3), dx, e_star, periodic=True)
    assert along_x == pytest.approx(math.pi * e_star * a**2 / (4 * lam), rel=ROUNDING)


def test_full_contact_energy_scales_as_the_square_of_the_heights():
    z = np.random.default_rng(3).standard_normal((16, 16)) * 1e-9
    base = full_contact_energy(z, 1e-8, 1e11)
    assert full_contact_energy(3 * z, 1e-8, 1e11) == pytest.approx(9 * base, rel=ROUNDING)


# --- the map-based summary and its warnings ------------------------------------------------------


DX, A, PERIODS, N = 1e-9, 1e-9, 1, 64
K = 2 * np.pi * PERIODS / (N * DX)
MAP = wave((N, N), DX, A, PERIODS)


def diagnose(**changes):
    inputs = dict(z=MAP, pixel_size=DX, e_star=1e11, w=0.1, delta_r=3e-10, periodic=True)
    return stickiness(**(inputs | changes))


def test_summary_joins_the_formulas_on_the_maps_numbers():
    d = diagnose()
    h1, h2 = slope_curvature_rms(MAP, DX, periodic=True)
    assert (d.slope_rms, d.curvature_rms) == (h1, h2)
    assert d.pr_parameter == pastewka_robbins(h1, h2, 1e11, 0.1, 3e-10)
    assert d.range_over_gap == pytest.approx(3e-10 / (16 / 3 * h1**2 / h2), rel=ROUNDING)
    assert d.energy_ratio == pytest.approx(1e11 * K * A**2 / 8 / 0.1, rel=ROUNDING)
    assert d.tabor == tabor_parameter(h2, 1e11, 0.1, 3e-10)
    assert d.mesh == pytest.approx(math.sqrt(0.1 / 9e-20 * DX / 1e11), rel=ROUNDING)
    assert d.sticky_pt == (d.energy_ratio < 1) and d.sticky_pr == (d.pr_parameter < 1)


def test_no_warning_where_both_criteria_hold():
    d = diagnose()
    assert d.range_over_gap < PR_RANGE_LIMIT and d.mesh < MESH_LIMIT
    assert d.warnings() == []


def test_a_range_long_against_the_gap_scale_warns_about_pastewka_robbins_only():
    d = diagnose()
    g0 = d.gap_scale
    long_range = diagnose(delta_r=0.2 * g0, w=0.1 * (0.2 * g0 / 3e-10) ** 2)  # same mesh
    assert long_range.mesh == pytest.approx(d.mesh, rel=ROUNDING)
    (line,) = long_range.warnings()
    assert "Pastewka-Robbins criterion is outside its validity" in line and "Δr/g0 = 0.2" in line


def test_a_coarse_grid_warns_about_the_mesh_only():
    d = diagnose(w=10.0)
    assert d.range_over_gap < PR_RANGE_LIMIT and d.mesh > MESH_LIMIT
    (line,) = d.warnings()
    assert "the grid does not resolve the interaction" in line


@pytest.mark.parametrize(
    ("field", "limit", "phrase"),
    [("range_over_gap", PR_RANGE_LIMIT, "Pastewka-Robbins"), ("mesh", MESH_LIMIT, "grid")],
)
def test_warnings_switch_on_exactly_at_the_limits(field, limit, phrase):
    d = diagnose()
    below = dataclasses.replace(d, **{field: np.nextafter(limit, 0)})
    at = dataclasses.replace(d, **{field: limit})
    assert below.warnings() == []
    assert len(at.warnings()) == 1 and phrase in at.warnings()[0]


# --- bad input ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("changes", "match"),
    [
        ({"w": -0.1}, "`w` = -0.1 J/m\\^2 is out of range"),
        ({"e_star": 0.0}, "`e_star` = 0.0 Pa is out of range"),
        ({"delta_r": math.nan}, "`delta_r` = nan m"),
        ({"pixel_size": -1e-9}, "`pixel_size` = -1e-09 m"),
        ({"z": np.where(np.eye(N, dtype=bool), np.nan, MAP)}, "`z` has 64 non-finite pixels"),
        ({"z": MAP[:2]}, "`z` must be a 2-D height map with at least 3×3"),
        ({"z": np.zeros((8, 8))}, "`z` is flat"),
    ],
)
def test_bad_input_is_refused_by_name(changes, match):
    with pytest.raises(ParameterError, match=match):
        diagnose(**changes)


def test_bad_scalars_are_refused_by_name_in_vectorised_form():
    with pytest.raises(ParameterError, match=r"`curvature_rms` = -1\.0 1/m"):
        pastewka_robbins(0.1, [1e6, -1.0], 1e9, 0.1, 1e-9)

"""The Maugis–Dugdale law set: its table against a direct solution of Maugis' equations,
its branches under fixed penetration, its DMT and JKR limits, its edges and errors.

Dimensionless quantities are those of Johnson & Greenwood (1997): A = a/(πwR²/K)^{1/3},
P̄ = P/(πwR), Δ = δ/(π²w²R/K²)^{1/3}. Errors of P̄ and A² are relative to max(|P̄|, 1)
and max(A², 1): P̄ changes sign and A vanishes at touch-down.
"""

import dataclasses

import mpmath
import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar
from tolerances import ROUNDING_CHAIN, ROUNDING_FEW, ROUNDING_FORMULA

from mcsim import Material, Surface
from mcsim.engine.kernels import compile_law
from mcsim.model.errors import ParameterError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.laws import get_law_set
from mcsim.physics.laws import maugis_dugdale as md

LAMBDAS = (0.1, 0.3, 1.0, 3.0, 10.0)
BOUND = 1e-8  # the table's error bound
SILICON = dataclasses.replace(MATERIALS["silicon"], z0=0.3e-9)


def maugis_m(A, lam):
    """m = c/a from Maugis' first equation, by brentq (the direct solution)."""

    def f(m):
        mu, th = np.sqrt(m * m - 1.0), np.arccos(1.0 / m)
        return (
            0.5 * lam * A * A * (mu + (m * m - 2.0) * th)
            + 4.0 / 3.0 * lam * lam * A * (mu * th - m + 1.0)
            - 1.0
        )

    hi = 2.0
    while f(hi) < 0:
        hi *= 2.0
    # the reference root to rounding: the tolerances below are relative to it
    return brentq(f, 1.0, hi, xtol=1e-15, rtol=1e-15)


def direct(A, lam):
    """(P̄, Δ) at contact radius A, from Maugis' equations."""
    m = maugis_m(A, lam)
    mu, th = np.sqrt(m * m - 1.0), np.arccos(1.0 / m)
    return A**3 - lam * A * A * (mu + m * m * th), A * A - 4.0 / 3.0 * lam * A * mu


def direct_mp(A, lam):
    """The same at 40 digits (mpmath), for the large-A tail where m → 1."""
    with mpmath.workdps(40):
        A, lam = mpmath.mpf(A), mpmath.mpf(lam)

        def f(m):
            mu, th = mpmath.sqrt(m * m - 1), mpmath.acos(1 / m)
            return (
                lam * A * A / 2 * (mu + (m * m - 2) * th)
                + 4 * lam**2 * A / 3 * (mu * th - m + 1)
                - 1
            )

        m = mpmath.findroot(f, (mpmath.mpf(1), mpmath.mpf(2)), solver="anderson")
        mu, th = mpmath.sqrt(m * m - 1), mpmath.acos(1 / m)
        return float(A**3 - lam * A * A * (mu + m * m * th)), float(A * A - 4 * lam * A * mu / 3)


def turning_point(lam):
    """A and Δ where Δ(A) is least on the contact curve (λ > λ_c), by direct solution."""
    res = minimize_scalar(lambda A: direct(A, lam)[1], bounds=(1e-6, 2.0), method="bounded",
                          options={"xatol": 1e-12})  # fmt: skip
    return res.x, res.fun


def table_values(delta, lam, delta_max=np.inf):
    """P̄ and A² from the law functions in dimensionless units (unit scales, no edges)."""
    tab = md.table(lam)
    delta = np.asarray(delta, dtype=float)
    common = {
        "md_jump_in": -1e300,
        "md_break_off": -1e300,
        "md_per_delta_unit": 1.0,
        "md_delta_lo": tab.delta_lo,
        "md_delta_touch": tab.delta_touch,
    }
    P = md.load(delta, delta_max, md_force_unit=1.0, md_lambda=lam, md_h0=tab.h0, md_b=tab.b,
                md_table=tab.coefficients, **common)  # fmt: skip
    A2 = md.area(delta, delta_max, md_area_unit=1.0, md_table=tab.coefficients, **common)
    return P, A2


def stable_radii(lam, a_max):
    """Contact radii on the stable branch, crowded towards its lower end."""
    a_lo = turning_point(lam)[0] if lam > md.LAMBDA_C else 0.0
    offsets = np.geomspace(1e-5, 1.0, 40) * max(a_lo, 0.05)
    return np.concatenate([a_lo + offsets, np.geomspace(a_lo + 0.06, a_max, 200)])


def check(P, A2, P_ref, A_ref):
    err_P = np.abs(P - P_ref) / np.maximum(np.abs(P_ref), 1.0)
    err_A = np.abs(A2 - A_ref**2) / np.maximum(A_ref**2, 1.0)
    assert err_P.max() <= BOUND, f"load: max error {err_P.max():.2e} at A = {A_ref[err_P.argmax()]}"
    assert err_A.max() <= BOUND, f"area: max error {err_A.max():.2e} at A = {A_ref[err_A.argmax()]}"


@pytest.mark.parametrize("lam", LAMBDAS)
def test_table_matches_a_direct_solution_of_maugis_equations(lam):
    A = stable_radii(lam, 50.0)
    P_ref, delta = np.array([direct(a, lam) for a in A]).T
    check(*table_values(delta, lam), P_ref, A)


@pytest.mark.parametrize("lam", LAMBDAS)
def test_table_holds_its_bound_far_into_the_large_penetration_tail(lam):
    A = np.geomspace(50.0, 1e6, 30)
    P_ref, delta = np.array([direct_mp(a, lam) for a in A]).T
    check(*table_values(delta, lam), P_ref, A)


@pytest.mark.parametrize("lam", (0.1, 0.3))
def test_out_of_contact_the_load_is_the_elastic_dugdale_zone_and_joins_contact_at_touch_down(lam):
    # zone of radius C: Δ = −h̄0 + C²/2 − (8/(3π))λC, P̄ = −(π/2)λC² (module docstring)
    tab = md.table(lam)
    b, h0 = 8 * lam / (3 * np.pi), 2 / (np.pi * lam)
    C0 = brentq(lambda C: 0.25 * np.pi * lam * C * C + 4 / 3 * lam**2 * (np.pi / 2 - 1) * C - 1,
                0.0, 100.0, xtol=1e-15)  # fmt: skip  # Maugis' first equation at A = 0
    C = np.linspace(b, C0, 50)[1:-1]
    delta = -h0 + C * C / 2 - b * C
    P, A2 = table_values(delta, lam)
    np.testing.assert_allclose(P, -np.pi / 2 * lam * C * C, rtol=1e-13)
    assert np.all(A2 == 0)
    touch = -h0 + C0 * C0 / 2 - b * C0
    assert touch == pytest.approx(tab.delta_touch, rel=ROUNDING_CHAIN), (
        "touch-down: the central gap closes"
    )
    below, above = table_values([touch - 1e-10, touch + 1e-10], lam)[0]
    assert abs(above - below) < 1e-8, "the load is continuous at touch-down"


def test_the_zone_force_tends_to_the_rigid_sphere_dugdale_force_as_lambda_vanishes():
    lam = 1e-3
    tab = md.table(lam)
    gap = np.linspace(0.1, 0.9, 9) * tab.h0  # g = −Δ, out of contact (touch-down: g = 0.05)
    P = table_values(-gap, lam)[0]
    rigid = -2.0 * (1.0 - gap / tab.h0)  # −2πRσ0(h0 − g) in units of πwR
    # the elastic zone adds −πλbC (b = 8λ/(3π), C the zone radius): O(λ^{3/2}) → 0
    C = tab.b + np.sqrt(tab.b**2 + 2 * (tab.h0 - gap))
    np.testing.assert_allclose(P - rigid, -np.pi * lam * tab.b * C, rtol=1e-9)
    assert np.abs(P - rigid).max() < 1e-4


def test_small_lambda_reproduces_dmt_pull_off_2_pi_w_r():
    devs = [md.pull_off(lam)[0] + 2.0 for lam in (1e-1, 1e-2, 1e-3)]
    assert devs[0] > devs[1] > devs[2] > 0
    assert devs[2] < 1e-4  # O(λ^{3/2}) at λ = 1e-3
    # under fixed penetration too: the most tensile load on retraction
    tab = md.table(1e-3)
    P = table_values(np.linspace(tab.delta_break, 1.0, 20001), 1e-3)[0]
    assert P.min() == pytest.approx(-2.0, abs=1e-4)


def test_large_lambda_reproduces_jkr():
    lam = 1e3
    tab = md.table(lam)
    # load control: pull-off 1.5 πwR
    assert md.pull_off(lam)[0] == pytest.approx(-1.5, abs=1e-6)
    # fixed penetration: break-off at δ_c = −¾(π²w²R/E*²)^{1/3} where P = −(5/6)πwR
    assert tab.delta_break == pytest.approx(-0.75 * (4 / 3) ** (2 / 3), abs=1e-6)
    P_break = table_values(tab.delta_break, lam)[0]
    assert P_break == pytest.approx(-5 / 6, abs=1e-6)
    # jump-in at δ = −h0 → 0, onto the JKR branch at P = −(4/3)πwR (O(1/λ) away)
    assert table_values(-tab.h0, lam)[0] == pytest.approx(-4 / 3, abs=1e-3)


@pytest.mark.parametrize("lam", LAMBDAS)
def test_load_controlled_pull_off_matches_a_direct_minimisation(lam):
    res = minimize_scalar(lambda A: direct(A, lam)[0], bounds=(1e-6, 3.0), method="bounded",
                          options={"xatol": 1e-10})  # fmt: skip
    P, _ = md.pull_off(lam)
    assert P == pytest.approx(min(res.fun, direct(1e-6, lam)[0]), abs=1e-10)


def test_pull_off_falls_from_dmt_to_jkr_as_lambda_grows():
    P = np.array([md.pull_off(lam)[0] for lam in np.geomspace(1e-3, 1e3, 25)])
    assert np.all(np.diff(P) > 0) and -2 < P.min() and P.max() < -1.5


@pytest.mark.parametrize("lam", LAMBDAS)
def test_break_off_is_the_turning_point_of_the_curve_under_fixed_penetration(lam):
    tab = md.table(lam)
    if lam > md.LAMBDA_C:
        expected = turning_point(lam)[1]
    else:  # out of contact: least Δ = −h̄0 + C²/2 − bC at C = b
        expected = -2 / (np.pi * lam) - 0.5 * (8 * lam / (3 * np.pi)) ** 2
    assert tab.delta_break == pytest.approx(expected, abs=1e-10)


@pytest.mark.parametrize("lam", np.geomspace(1e-3, 1e3, 13))
def test_the_contact_curve_has_one_turning_point_beyond_which_it_is_single_valued(lam):
    # the table solves Δ(ψ) = Δ on (0, ψ_lo] by bisection: Δ must fall monotonically there
    psi = np.linspace(1e-4, np.pi / 2, 20001)
    delta = md.contact_curve(psi, lam)[2]
    turns = np.count_nonzero(np.diff(np.sign(np.diff(delta))))
    assert turns == (1 if lam > md.LAMBDA_C else 0)
    stable = delta[psi <= md.table(lam).psi_lo]
    assert np.all(np.diff(stable) < 0)


def test_maugis_lambda_is_about_1_16_tabor():
    R, w, z0, E_star = SURFACES["smooth"].R, SILICON.gamma, SILICON.z0, SILICON.E_star
    tabor = np.cbrt(R * w * w / (E_star**2 * z0**3))
    # Maugis's λ ≈ 1.16 μ_T, three digits; the exact ratio 1.1621 (test_adhesion.py) is 1.8e-3
    # from it: 2e-3, below half a unit of the last digit (4.3e-3)
    assert md.maugis_lambda(R, SILICON.K, w, z0) / tabor == pytest.approx(1.16, rel=2e-3)


@pytest.mark.parametrize("surface", ("rough", "smooth"))  # λ = 0.62 and 1.52
def test_evaluate_gives_newtons_and_square_metres_on_both_branches(surface):
    law, surf = get_law_set("maugis-dugdale"), SURFACES[surface]
    edges = law.edges_for(surf, SILICON)
    lam = md.maugis_lambda(surf.R, SILICON.K, SILICON.gamma, SILICON.z0)
    a_unit, delta_unit, force_unit = md.units(surf.R, SILICON.K, SILICON.gamma)
    assert edges.jump_in == edges.reach == pytest.approx(-0.97 * SILICON.z0, rel=ROUNDING_FEW)
    A = stable_radii(lam, 5.0)[5:]
    P_ref, delta_ref = np.array([direct(a, lam) for a in A]).T
    if lam < md.LAMBDA_C:  # and out of contact: the Dugdale zone C from b to 2b (jump-in)
        b, C = 8 * lam / (3 * np.pi), 8 * lam / (3 * np.pi) * np.linspace(1.05, 1.95, 10)
        A = np.append(A, np.zeros_like(C))
        P_ref = np.append(P_ref, -np.pi / 2 * lam * C * C)
        delta_ref = np.append(delta_ref, -2 / (np.pi * lam) + C * C / 2 - b * C)
    delta = delta_ref * delta_unit
    retract = law.evaluate(delta, surf, SILICON, branch="retract")
    approach = law.evaluate(delta, surf, SILICON, branch="approach")
    assert set(retract) == set(approach) == {"load", "area"}
    # against the parametric MD solution (a root per point): 1e-8 of the value, or of the
    # force/area unit where the load crosses zero and the area vanishes (measured 6e-9, 5e-5
    # relative at an area of 1e-24 of its unit)
    np.testing.assert_allclose(
        retract["load"], P_ref * force_unit, rtol=1e-8, atol=1e-8 * force_unit
    )
    area_unit = np.pi * a_unit**2
    # the area vanishes at break-off: 1e-8 of the unit there (as above)
    np.testing.assert_allclose(retract["area"], area_unit * A**2, rtol=1e-8, atol=1e-8 * area_unit)
    jumped = delta > edges.jump_in
    assert np.any(~jumped), "some points lie between break-off and jump-in"
    assert np.array_equal(approach["load"][jumped], retract["load"][jumped])
    assert np.all(approach["load"][~jumped] == 0) and np.all(approach["area"][~jumped] == 0)
    # beyond break-off, and for a summit that never jumped in, nothing
    far = np.array([edges.break_off * 1.001, edges.break_off * 2])
    for out in (law.evaluate(far, surf, SILICON, branch="retract"),
                law.evaluate(delta, surf, SILICON, branch="retract", delta_max=edges.jump_in)):  # fmt: skip
        assert np.all(out["load"] == 0) and np.all(out["area"] == 0)


def test_compiled_law_functions_equal_the_numpy_ones():
    law, surf = get_law_set("maugis-dugdale"), SURFACES["rough"]
    args_load, args_area = law.arguments(surf, SILICON)
    rng = np.random.default_rng(1)
    delta = rng.uniform(-1e-9, 1e-8, 400)
    delta_max = delta + (rng.random(400) < 0.5) * rng.uniform(0, 1e-8, 400)
    for fn, args in ((md.load, args_load), (md.area, args_area)):
        compiled = compile_law(fn)
        expected = fn(delta, delta_max, *args)
        got = np.array([compiled(d, m, *args) for d, m in zip(delta, delta_max)])
        assert np.count_nonzero(expected) > 100
        # numba's libm and NumPy's on the same formula (measured bit-equal); the load is signed:
        # absolute, scaled by the largest value
        np.testing.assert_allclose(
            got, expected, rtol=0, atol=ROUNDING_FORMULA * np.abs(expected).max()
        )


def test_sin_minus_u_cos_sums_the_series_to_every_bit_the_full_series_gives():
    # Below u = 1 the module sums 9 terms of sin u − u cos u = Σ (−1)^{k+1} 2k u^{2k+1}/(2k+1)!
    # in place: to the last bit the 13 terms of the plain loop the tables were first built
    # with, from tiny u to just below 1; and close to the closed form where it has no
    # cancellation.
    rng = np.random.default_rng(7)
    u = np.concatenate([rng.uniform(0, 1, 1_000_000), 1 - rng.uniform(0, 1e-3, 200_000),
                        np.exp(rng.uniform(np.log(1e-30), 0, 500_000)),
                        np.nextafter(1.0, 0) - np.arange(1000) * 2.0**-52])  # fmt: skip
    u = u[u < 1]
    term, total = u**3 / 3.0, np.zeros_like(u)
    for k in range(1, 14):
        total = total + term
        term = -term * u * u * (k + 1) / (k * (2 * k + 2) * (2 * k + 3))
    got = md._sin_minus_u_cos(u)
    assert np.array_equal(got, total)
    big = u > 0.5
    np.testing.assert_allclose(got[big], np.sin(u[big]) - u[big] * np.cos(u[big]), rtol=1e-14)


def test_the_table_is_built_once_per_lambda():
    assert md.table(0.5) is md.table(0.5)


def test_without_z0_it_says_so_in_one_line():
    law = get_law_set("maugis-dugdale")
    with pytest.raises(ParameterError, match="z0") as info:
        law.evaluate([0.0], SURFACES["rough"], dataclasses.replace(SILICON, z0=None))
    assert "\n" not in str(info.value)


def test_lambda_outside_the_tabulated_range_is_refused():
    stiff = Material(E1=1e13, E2=1e13, nu1=0.2, nu2=0.2, gamma=0.01, z0=1e-6)  # λ ≈ 2e-7
    with pytest.raises(ParameterError, match="lambda"):
        get_law_set("maugis-dugdale").evaluate([0.0], Surface(1e-9, 1e-9, 1e12), stiff)


def test_importing_the_law_sets_does_not_load_scipy_interpolate_or_optimize():
    """Every command imports mcsim.physics.laws; the table's SciPy tools cost ~0.35 s at start-up."""
    import subprocess
    import sys

    code = "import sys, mcsim.physics.laws; print(sorted(m for m in ('scipy.interpolate', 'scipy.optimize') if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"

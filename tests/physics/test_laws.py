"""Contact-model law sets beyond the seed: jkr, dmt, elastic-plastic (issue 10, §2).

Single summits against the published relations, evaluated independently of the law
functions (JKR through the contact radius a; DMT and Kogut–Etsion from their
formulas); edges; the evaluate() interface; the kernel vocabulary (numba compiles
each law function); material fields z0 and tau from files and the API.
"""

import numpy as np
import pytest
from scipy import integrate
from tolerances import QUAD_RTOL, ROUNDING_CHAIN, ROUNDING_FEW, ROUNDING_FORMULA, assert_close

from mcsim.cli.main import main
from mcsim.engine.kernels import compile_law
from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.laws import dmt, elastic_plastic, get_law_set, helpers, ieee, jkr
from mcsim.physics.laws import maugis_dugdale as md
from mcsim.store.config import load_material, material_from_table
from mcsim.topography.empirical import Empirical

SILICON = MATERIALS["silicon"]
SMOOTH = SURFACES["smooth"]
R, E, W = SMOOTH.R, SILICON.E_star, SILICON.gamma


def jkr_through_a(a):
    """JKR (Fuller & Tabor 1975) as functions of the contact radius a: δ, P, A."""
    delta = a * a / R - np.sqrt(2 * np.pi * W * a / E)
    load = 4 * E * a**3 / (3 * R) - np.sqrt(8 * np.pi * W * E * a**3)
    return delta, load, np.pi * a * a


A_SCALE = (R * R * W / E) ** (1 / 3)
A_FOLD = A_SCALE * (np.pi / 8) ** (1 / 3)  # contact radius at δ_c
A_JUMP = A_SCALE * (2 * np.pi) ** (1 / 3)  # contact radius at δ = 0 on the stable branch
DELTA_C = -0.75 * np.cbrt(np.pi**2 * W**2 * R / E**2)


@pytest.mark.parametrize(
    ("branch", "a_min"),
    # next to the fold δ(a) is flat, so a(δ) is ill-conditioned: start 1e-4 above it
    [("retract", A_FOLD * (1 + 1e-4)), ("approach", A_JUMP * (1 + 1e-9))],
)
def test_jkr_equals_the_jkr_relations_through_the_contact_radius_on_both_branches(branch, a_min):
    a = a_min * np.geomspace(1, 1e4, 3001)
    delta, load, area = jkr_through_a(a)
    out = get_law_set("jkr").evaluate(delta, SMOOTH, SILICON, branch=branch)
    assert np.all(np.abs(out["load"] - load) <= 1e-10 * np.abs(load))
    assert np.all(np.abs(out["area"] - area) <= 1e-10 * area)


def test_jkr_is_zero_outside_its_contact_set():
    law = get_law_set("jkr")
    approach = law.evaluate(-np.geomspace(1e-15, 1e-6, 50), SMOOTH, SILICON)
    assert np.all(approach["load"] == 0) and np.all(approach["area"] == 0)
    assert law.evaluate(0.0, SMOOTH, SILICON)["load"] == 0
    below = DELTA_C * np.array([1.0, 1 + 1e-12, 2, 1e3])
    retract = law.evaluate(below, SMOOTH, SILICON, branch="retract")
    assert np.all(retract["load"] == 0) and np.all(retract["area"] == 0)
    # on retraction, a summit that never touched (δ_max ≤ 0) stays out of contact
    never = law.evaluate([-1e-10, DELTA_C / 2], SMOOTH, SILICON, branch="retract", delta_max=0.0)
    assert np.all(never["load"] == 0) and np.all(never["area"] == 0)


def test_jkr_jumps_in_at_minus_four_thirds_pi_w_r_and_breaks_off_at_delta_c_at_minus_five_sixths():
    law = get_law_set("jkr")
    edges = law.edges_for(SMOOTH, SILICON)
    assert (edges.reach, edges.jump_in) == (0.0, 0.0)
    assert edges.break_off == pytest.approx(DELTA_C, rel=ROUNDING_FEW)
    # the edge is the law's own: in contact just above it, not at it
    above = np.nextafter(edges.break_off, 0.0)
    assert law.evaluate([edges.break_off, above], SMOOTH, SILICON, branch="retract")["load"][1] < 0
    assert law.evaluate(edges.break_off, SMOOTH, SILICON, branch="retract")["load"] == 0
    # δ_c = −¾ π^{2/3} (Rw²/E*²)^{1/3} (Greenwood's reduced units)
    assert DELTA_C == pytest.approx(
        -0.75 * np.pi ** (2 / 3) * (R * W**2 / E**2) ** (1 / 3), rel=ROUNDING_FORMULA
    )
    jump = law.evaluate(1e-300, SMOOTH, SILICON)
    assert jump["load"] == pytest.approx(-4 / 3 * np.pi * W * R, rel=1e-12)
    assert jump["area"] == pytest.approx(np.pi * A_JUMP**2, rel=1e-12)
    # P(δ) has a square-root fold at δ_c: 1e-14 above it P is within ~1e-7 of its limit
    pull = law.evaluate(DELTA_C * (1 - 1e-14), SMOOTH, SILICON, branch="retract")
    assert pull["load"] == pytest.approx(-5 / 6 * np.pi * W * R, rel=1e-6)
    assert pull["area"] == pytest.approx(np.pi * A_FOLD**2, rel=1e-6)


def test_jkr_without_adhesion_is_hertz():
    material = Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, gamma=0.0)
    delta = np.concatenate([[-1e-9, 0.0], np.geomspace(1e-14, 1e-6, 40)])
    out = get_law_set("jkr").evaluate(delta, SMOOTH, material)
    d = np.maximum(delta, 0)
    # d**1.5 multiplies d's rounding by 1.5, then K √R: ROUNDING_CHAIN
    np.testing.assert_allclose(out["load"], material.K * np.sqrt(R) * d**1.5, rtol=ROUNDING_CHAIN)
    np.testing.assert_allclose(out["area"], np.pi * R * d, rtol=ROUNDING_FORMULA)


def test_dmt_matches_hertz_minus_2_pi_w_r_in_contact_and_the_derjaguin_van_der_waals_force_outside():
    z0 = SILICON.z0
    law = get_law_set("dmt")
    delta = np.concatenate(
        [-np.geomspace(1e-15, 8.99 * z0, 200), [0.0], np.geomspace(1e-15, 1e-6, 200)]
    )
    out = law.evaluate(delta, SMOOTH, SILICON)
    d = np.maximum(delta, 0)
    gap = z0 - np.minimum(delta, 0)
    expected = np.where(
        delta > 0,
        4 / 3 * E * np.sqrt(R) * d**1.5 - 2 * np.pi * W * R,
        -2 * np.pi * W * R * (z0 / gap) ** 2,
    )
    # the load crosses zero in contact (Hertz = 2πWR): absolute, scaled by the terms that cancel
    scale = np.where(delta > 0, 4 / 3 * E * np.sqrt(R) * d**1.5 + 2 * np.pi * W * R, -expected)
    assert_close(out["load"], expected, ROUNDING_FORMULA * scale, "DMT load")
    np.testing.assert_allclose(out["area"], np.pi * R * d, rtol=ROUNDING_FEW, atol=0)
    assert (
        law.evaluate(delta, SMOOTH, SILICON, branch="retract")["load"].tolist()
        == out["load"].tolist()
    )


def test_dmt_load_is_continuous_at_zero_interference():
    law = get_law_set("dmt")
    at = law.evaluate([-1e-25, 0.0, 1e-25], SMOOTH, SILICON)["load"]
    np.testing.assert_allclose(at, -2 * np.pi * W * R, rtol=ROUNDING_FORMULA)


def test_dmt_attraction_is_cut_off_at_the_documented_gap():
    z0 = SILICON.z0
    law = get_law_set("dmt")
    reach = law.edges_for(SMOOTH, SILICON).reach
    assert reach == pytest.approx(z0 - 10 * z0, rel=ROUNDING_FEW)
    load = law.evaluate([reach * (1 - 1e-12), reach, 2 * reach], SMOOTH, SILICON)["load"]
    # 1e-12 of reach inside the cutoff, (z0/gap)² is 1.8e-12 above 1/100: 1e-11
    assert load[0] == pytest.approx(-2 * np.pi * W * R / 100, rel=1e-11)
    assert load[1] == 0 and load[2] == 0
    wide = dmt.dmt_law_set(cutoff=20)
    assert wide.edges_for(SMOOTH, SILICON).reach == pytest.approx(-19 * z0, rel=ROUNDING_FEW)
    assert wide.evaluate(-15 * z0, SMOOTH, SILICON)["load"] < 0


@pytest.mark.parametrize("cutoff", [0.5, -1, float("inf"), float("nan"), "ten"])
def test_dmt_cutoff_out_of_range_is_refused_naming_it(cutoff):
    with pytest.raises(ParameterError, match="cutoff") as err:
        dmt.dmt_law_set(cutoff)
    assert "\n" not in str(err.value)


def skewed_rough_surface() -> Surface:
    edges = np.linspace(-3.0, 4.0, 36)
    counts = np.exp(-0.5 * ((edges[:-1] + edges[1:]) / 2 + 0.3) ** 2) * (1 + 0.1 * np.arange(35))
    heights = Empirical.from_histogram(edges * 15.8e-9, counts)
    rough = SURFACES["rough"]
    return Surface(sigma=heights.sigma, R=rough.R, eta=rough.eta, heights=heights)


@pytest.mark.parametrize("h", [-1.0, 0.0, 2.0])
@pytest.mark.parametrize("heights", ["gaussian", "empirical"])
def test_dmt_truncated_fraction_is_the_share_of_the_attraction_beyond_the_cutoff(h, heights):
    # independent route: expectations over the summit heights of the law function
    # itself, (practically) untruncated with a cutoff of 1e6 z0
    # rough: σ = 15.8 nm, so the cutoff gap 3 nm is 0.17σ
    surface = SURFACES["rough"] if heights == "gaussian" else skewed_rough_surface()
    sigma, pdf = surface.sigma, surface.heights.pdf
    law = dmt.dmt_law_set(1e6)
    args = law.arguments(surface, SILICON)[0]
    hertz = SILICON.K * np.sqrt(surface.R)

    def attraction(s):
        delta = sigma * (s - h)
        return -(dmt.dmt_load(delta, *args) - hertz * max(delta, 0) ** 1.5) * pdf(s)

    s_cut = h - 9 * SILICON.z0 / sigma
    edges = getattr(surface.heights, "edges", np.array([]))

    def quad(a, b):
        inside = [e for e in edges if a < e < b] or None
        return integrate.quad(attraction, a, b, points=inside, limit=500, epsabs=0, epsrel=1e-12)[0]

    dropped = quad(-40, s_cut)
    kept = quad(s_cut, h) + quad(h, 40)
    got = dmt.truncated_fraction(surface, SILICON, [h])
    assert got.shape == (1,) and 0 < got[0] < 1
    assert got[0] == pytest.approx(dropped / (dropped + kept), rel=QUAD_RTOL)


def test_dmt_needs_z0_and_says_so_in_one_line():
    material = Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, gamma=0.5)
    with pytest.raises(ParameterError, match="'z0'") as err:
        get_law_set("dmt").evaluate(0.0, SMOOTH, material)
    assert "\n" not in str(err.value)


def kogut_etsion(delta, material=SILICON, surface=SMOOTH):
    """Kogut & Etsion (2002) fits, written with ** and branches (the test's own copy)."""
    k = 0.454 + 0.41 * material.nu
    H = material.H
    w_c = (np.pi * k * H / (2 * material.E_star)) ** 2 * surface.R
    p_c = 2 / 3 * np.pi * k * H * surface.R * w_c
    a_c = np.pi * surface.R * w_c
    load, area = [], []
    for x in np.asarray(delta) / w_c:
        if x <= 0:
            p, a = 0.0, 0.0
        elif x < 1:
            p, a = x**1.5, x
        elif x < 6:
            p, a = 1.03 * x**1.425, 0.93 * x**1.136
        elif x < 110:
            p, a = 1.40 * x**1.263, 0.94 * x**1.146
        else:
            p, a = 3 * x / k, 2 * x
        load.append(p * p_c)
        area.append(a * a_c)
    return np.array(load), np.array(area), w_c


def test_elastic_plastic_matches_the_kogut_etsion_fits_in_every_range():
    w_c = kogut_etsion([1.0])[2]
    x = np.concatenate([[-1.0, 0.0], np.geomspace(1e-6, 1e3, 400), [1.0, 6.0, 110.0]])
    load, area, _ = kogut_etsion(x * w_c)
    out = get_law_set("elastic-plastic").evaluate(x * w_c, SMOOTH, SILICON)
    # powers such as x**1.425 of a ratio: ROUNDING_CHAIN (measured 4.8e-16)
    np.testing.assert_allclose(out["load"], load, rtol=ROUNDING_CHAIN, atol=0)
    np.testing.assert_allclose(out["area"], area, rtol=ROUNDING_CHAIN, atol=0)
    # H is the hardness: fully plastic, the mean pressure load/area is H itself
    deep = get_law_set("elastic-plastic").evaluate(200 * w_c, SMOOTH, SILICON)
    assert deep["load"] / deep["area"] == pytest.approx(SILICON.H, rel=1e-14)


@pytest.mark.parametrize(
    ("c", "e"), [(1.03, 1.425), (1.40, 1.263), (0.93, 1.136), (0.94, 1.146)]
)  # fmt: skip
def test_the_elastic_plastic_power_is_c_x_to_the_e_within_five_ulp_from_1_to_110(c, e):
    """The module docstring's bound, 1.1e-15 = 5 ulp relative of ``c * x**e`` (measured
    worst: exactly that for e = 1.136), and x clamped to [1, 110] outside."""
    x = np.geomspace(1.0, 110.0, 20001)
    got = elastic_plastic.fit_power(x, c, e, 2.0**e)
    np.testing.assert_allclose(got, c * x**e, rtol=5 * np.finfo(float).eps, atol=0)
    ends = elastic_plastic.fit_power(np.array([0.5, 1e3]), c, e, 2.0**e)
    np.testing.assert_allclose(ends, [c, c * 110.0**e], rtol=5 * np.finfo(float).eps, atol=0)


def test_each_shared_formula_is_one_helper_that_both_outputs_call():
    """The JKR inversion and the elastic-plastic power are written once, in helpers of
    their law files; laws calling only NumPy and the ieee bit casts have no helpers."""
    assert helpers(jkr.jkr_load) == helpers(jkr.jkr_area) == (jkr.reduced_root,)
    assert helpers(elastic_plastic.elastic_plastic_load) == (elastic_plastic.fit_power,)
    assert helpers(elastic_plastic.elastic_plastic_area) == (elastic_plastic.fit_power,)
    assert helpers(md.load) == helpers(dmt.dmt_load) == ()


def test_elastic_plastic_lists_its_discontinuities_as_breakpoints_in_metres():
    w_c = kogut_etsion([1.0])[2]
    assert w_c == pytest.approx(
        elastic_plastic.critical_interference(R, E, SILICON.H, SILICON.nu), rel=ROUNDING_FEW
    )
    edges = get_law_set("elastic-plastic").edges_for(SMOOTH, SILICON)
    np.testing.assert_allclose(edges.breakpoints, [w_c, 6 * w_c, 110 * w_c], rtol=ROUNDING_FEW)
    assert (edges.reach, edges.jump_in, edges.break_off) == (0.0, 0.0, 0.0)


def test_elastic_plastic_refuses_retraction_in_one_line():
    with pytest.raises(ParameterError, match="elastic-plastic") as err:
        get_law_set("elastic-plastic").evaluate(1e-9, SMOOTH, SILICON, branch="retract")
    assert "\n" not in str(err.value)


def test_elastic_plastic_needs_the_hardness():
    material = Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, gamma=0.5)
    with pytest.raises(ParameterError, match="'H'"):
        get_law_set("elastic-plastic").evaluate(1e-9, SMOOTH, material)


@pytest.mark.parametrize("name", ["jkr", "dmt", "elastic-plastic"])
def test_evaluate_returns_load_in_newtons_and_area_in_square_metres(name):
    law = get_law_set(name)
    assert law.names == ("load", "area")
    assert [o.unit for o in law.outputs] == ["N", "m^2"]
    assert law.friction
    delta = np.linspace(-2e-9, 5e-9, 11)
    branches = ["approach", "retract"] if law.retract else ["approach"]
    for branch in branches:
        out = law.evaluate(delta, SMOOTH, SILICON, branch=branch)
        assert set(out) == {"load", "area"}
        assert out["load"].shape == out["area"].shape == delta.shape
        assert np.all(out["area"] >= 0)


LAWS = [
    (jkr.jkr_load, True),
    (jkr.jkr_area, True),
    (dmt.dmt_load, False),
    (dmt.dmt_area, False),
    (elastic_plastic.elastic_plastic_load, False),
    (elastic_plastic.elastic_plastic_area, False),
    (md.load, True),
    (md.area, True),
]
EXTREMES = np.array([-1e300, -1.0, -1e-9, -1e-300, 0.0, 1e-300, 1e-12, 1e-9, 1e-6, 1.0, 1e30])


def law_arguments(f):
    for name in ("jkr", "dmt", "elastic-plastic", "maugis-dugdale"):
        law = get_law_set(name)
        for o, args in zip(law.outputs, law.arguments(SMOOTH, SILICON)):
            if o.law is f:
                return args
    raise AssertionError(f)


@pytest.mark.parametrize(("f", "stateful"), LAWS, ids=[f.__name__ for f, _ in LAWS])
def test_law_values_are_finite_for_extreme_finite_inputs_without_warnings(f, stateful):
    args = law_arguments(f)
    with np.errstate(divide="raise", over="raise", invalid="raise"):
        if stateful:
            for delta_max in (-1.0, 0.0, 1e-9, np.inf):
                assert np.all(np.isfinite(f(EXTREMES, np.full_like(EXTREMES, delta_max), *args)))
        else:
            assert np.all(np.isfinite(f(EXTREMES, *args)))


BIT_PATTERNS = np.array([0.0, -0.0, 5e-324, 2.0**-70, 1.0, 1.5, np.pi, 1e30, -2.5, np.inf])


def test_the_ieee_helpers_are_the_bit_casts_in_numpy_and_in_compiled_code():
    expected = BIT_PATTERNS.view(np.int64)
    np.testing.assert_array_equal(ieee.float_bits(BIT_PATTERNS), expected)
    assert ieee.float_bits(1.0) == 1023 << 52 and np.ndim(ieee.float_bits(1.0)) == 0
    np.testing.assert_array_equal(ieee.bits_float(expected).view(np.int64), expected)
    to_int, to_float = compile_law(ieee.float_bits), compile_law(ieee.bits_float)
    for x, bits in zip(BIT_PATTERNS, expected):
        assert to_int(x) == bits
        assert np.float64(to_float(bits)).view(np.int64) == bits


@pytest.mark.parametrize(("f", "stateful"), LAWS, ids=[f.__name__ for f, _ in LAWS])
def test_each_law_function_compiles_with_numba_and_equals_numpy(f, stateful):
    compiled = compile_law(f)
    args = law_arguments(f)
    deltas = np.concatenate(
        [EXTREMES, -np.geomspace(1e-12, 4e-9, 60), np.geomspace(1e-13, 1e-6, 120)]
    )
    for delta in deltas:
        for delta_max in (delta, 1.0) if stateful else (None,):
            a = (delta, delta_max, *args) if stateful else (delta, *args)
            expected = float(f(*(np.float64(v) for v in a)))
            got = compiled(*a)
            assert abs(got - expected) <= 1e-14 * abs(expected), (delta, delta_max, got, expected)


def test_silicon_preset_has_the_documented_equilibrium_spacing():
    assert SILICON.z0 == 0.3e-9 and SILICON.tau is None


MATERIAL = """
[material]
E = "160 GPa"
nu = 0.22
gamma = "0.5 J/m^2"
"""


def test_material_files_accept_z0_tau_and_h_with_units(tmp_path):
    f = tmp_path / "m.toml"
    f.write_text(MATERIAL + 'z0 = "0.3 nm"\ntau = "100 MPa"\nH = "12.5 GPa"\n')
    material = load_material(f)
    assert material.z0 == pytest.approx(0.3e-9, rel=ROUNDING_FEW)
    assert material.tau == pytest.approx(100e6, rel=ROUNDING_FEW)
    assert material.H == pytest.approx(12.5e9, rel=ROUNDING_FEW)
    plain = material_from_table({"E": 160e9, "nu": 0.22, "gamma": 0.5})
    assert plain.z0 is None and plain.tau is None


@pytest.mark.parametrize(
    ("line", "field"),
    [
        ('tau = "0 MPa"', "tau"),
        ('tau = "-100 MPa"', "tau"),
        ('z0 = "0 nm"', "z0"),
        ('z0 = "-0.3 nm"', "z0"),
    ],
)
def test_nonpositive_tau_or_z0_in_a_file_is_a_one_line_error_naming_the_field(
    capsys, tmp_path, line, field
):
    f = tmp_path / "m.toml"
    f.write_text(MATERIAL + line + "\n")
    with pytest.raises(ParameterError, match=rf"{field} = -?0\.|{field} = -") as err:
        load_material(f)
    assert "\n" not in str(err.value) and str(f) in str(err.value)
    code = main(["analytic", "--surface", "smooth", "--material", str(f), "--h=0"])
    err_text = capsys.readouterr().err
    assert code == 2 and err_text.count("\n") == 1 and f"{field} = " in err_text


@pytest.mark.parametrize(
    ("field", "value"), [("tau", 0.0), ("tau", -1e8), ("z0", 0.0), ("z0", -3e-10)]
)
def test_nonpositive_tau_or_z0_through_the_api_is_an_error_naming_the_field(field, value):
    with pytest.raises(ParameterError, match=rf"^{field} = .* is out of range \(allowed: > 0"):
        Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, gamma=0.5, **{field: value})


def test_surface_argument_is_only_read_for_r():
    # the per-summit laws see the surface only through R
    other = Surface(sigma=99e-9, R=R, eta=1e12)
    for name in ("jkr", "dmt", "elastic-plastic"):
        law = get_law_set(name)
        a = law.evaluate([1e-10, 1e-9], SMOOTH, SILICON)
        b = law.evaluate([1e-10, 1e-9], other, SILICON)
        assert all(np.array_equal(a[k], b[k]) for k in a)

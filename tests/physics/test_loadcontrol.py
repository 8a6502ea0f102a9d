"""Results versus load (issue 11, §1): load control on the approach branch."""

import json
import math

import numpy as np
import pytest
from conftest import rows_of, run_cli
from scipy import integrate, optimize, stats
from tolerances import LOAD_CONTROL_RTOL, QUAD_RTOL, ROUNDING_FEW, ROUNDING_FORMULA

from mcsim import gw_curves
from mcsim.cli.options import parse_values
from mcsim.figures.loadcontrol import light_load_ratio
from mcsim.model.errors import ParameterError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.loadcontrol import XTOL, load_control, solve_targets

SMOOTH, SILICON = SURFACES["smooth"], MATERIALS["silicon"]
MAT = """[material]
E = "160 GPa"
nu = 0.22
gamma = "0.5 J/m^2"
H = "12.5 GPa"
z0 = "0.3 nm"
tau = "100 MPa"
"""


@pytest.mark.parametrize("law, quantity", [("seed", "P"), ("jkr", "load")])
def test_the_found_separation_reproduces_the_pressure_to_1e_9(law, quantity):
    pressure = np.geomspace(1e3, 1e7, 5)
    result = load_control(SMOOTH, SILICON, pressure, law)
    assert result.quantity == quantity and result.equilibrium.all()
    again = gw_curves(SMOOTH, SILICON, result.h, law).values[quantity] * SILICON.K
    np.testing.assert_allclose(again, pressure, rtol=LOAD_CONTROL_RTOL, atol=0)
    # The root lies within 1e-9 in h: the load crosses p between h - 1e-9 and h + 1e-9.
    below = gw_curves(SMOOTH, SILICON, result.h - 1e-9, law).values[quantity] * SILICON.K
    above = gw_curves(SMOOTH, SILICON, result.h + 1e-9, law).values[quantity] * SILICON.K
    assert np.all(below >= pressure) and np.all(above <= pressure)


@pytest.mark.parametrize("law", ["seed", "jkr"])
def test_a_monotone_load_path_has_no_jump_and_h_falls_as_the_pressure_rises(law):
    result = load_control(SMOOTH, SILICON, np.geomspace(1e3, 1e8, 8), law)
    assert not result.jump.any()
    assert np.all(np.diff(result.h) < 0)


def _wavy(h):
    """Toy load: tensile near contact, then a local maximum and minimum below the rest."""
    x = 5.0 - h
    return x - 1.5 * np.sin(x)


def test_a_non_monotone_load_gives_the_stable_branch_and_flags_the_jump():
    grid = np.linspace(5.0, -5.0, 2001)
    targets = np.array([5.0, 6.3, 7.0, -0.1, -0.5])
    h, jump, found = solve_targets(_wavy, grid, targets)
    x_max = 2 * math.pi - math.acos(2 / 3)  # local maximum of the load (6.56)
    x_rest = optimize.brentq(lambda x: x - 1.5 * math.sin(x), 1.0, 2.0)  # zero load, stable
    x = 5.0 - h
    assert found.tolist() == [True, True, True, True, False]
    assert jump.tolist() == [False, False, True, False, False]
    np.testing.assert_allclose(_wavy(h[:4]), targets[:4], rtol=1e-9)
    assert x[1] < x_max < x[2]  # 6.3 before the local maximum; 7 beyond the dip
    assert math.acos(1 / 1.5) < x[3] < x_rest  # tensile: between the pull-off and the rest
    assert math.isnan(h[4])


def test_a_tensile_load_beyond_the_pull_off_has_no_equilibrium():
    result = load_control(SMOOTH, SILICON, [-1e3, -1e8], "jkr")
    assert result.equilibrium.tolist() == [True, False]
    assert math.isnan(result.h[1]) and math.isnan(result.curves.load[1])
    assert result.curves.load[0] * SILICON.K == pytest.approx(-1e3, rel=LOAD_CONTROL_RTOL)


def test_no_positive_load_without_adhesion_is_refused():
    with pytest.raises(ParameterError, match="pressure = 0 Pa is out of range"):
        load_control(SMOOTH, SILICON, [0.0, 1e3], "seed")


def test_pressure_csv_columns_are_exact(capsys, tmp_path):
    material = tmp_path / "mat.toml"
    material.write_text(MAT)
    code, out, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--law", "jkr",
                           "--pressure", "1kPa:10MPa:31:log", "--format", "csv")  # fmt: skip
    assert code == 0
    assert out.splitlines()[0] == "pressure,h,contact_fraction,load,area,jump,equilibrium"
    rows = rows_of(out)
    assert len(rows) == 31 and float(rows[-1]["pressure"]) == pytest.approx(
        1e7, rel=ROUNDING_FORMULA
    )
    _, out, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--law", "jkr", "--material",
                        str(material), "--pressure", "1MPa", "--format", "csv")  # fmt: skip
    assert out.splitlines()[0].startswith("pressure,h,contact_fraction,load,area,friction,mu,")
    _, out, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--pressure", "1MPa",
                        "--format", "csv")  # fmt: skip
    assert out.splitlines()[0].startswith("pressure,h,contact_fraction,P,F,T,mu,")


@pytest.mark.parametrize("law, quantity", [("seed", "P"), ("jkr", "load")])
def test_csv_h_reproduces_the_pressure_through_mcsim_analytic(capsys, law, quantity):
    _, out, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--law", law,
                        "--pressure", "20kPa,3MPa", "--format", "csv")  # fmt: skip
    h = [r["h"] for r in rows_of(out)]
    _, out, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--law", law,
                        f"--h={','.join(h)}", "--format", "csv")  # fmt: skip
    load = [float(r[quantity]) * SILICON.K for r in rows_of(out)]
    # h through the CSV (repr) and back: the load there within LOAD_CONTROL_RTOL
    assert load == pytest.approx([2e4, 3e6], rel=LOAD_CONTROL_RTOL)


def test_load_with_area_is_pressure_times_area_and_forces_come_in_newtons(capsys):
    _, by_load, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--law", "jkr", "--load",
                            "1uN,10uN", "--area", "100um^2", "--format", "json")  # fmt: skip
    _, by_pressure, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--law", "jkr",
                                "--pressure", "10kPa,100kPa", "--format", "json")  # fmt: skip
    a, b = json.loads(by_load), json.loads(by_pressure)
    assert a["units"]["pressure"] == "Pa" and a["units"]["load_N"] == "N"
    for ra, rb in zip(a["rows"], b["rows"]):
        # force/area against the pressure typed: a rounding or two; the same root h, each within
        # XTOL of it (h crosses zero: absolute); the load there within LOAD_CONTROL_RTOL
        assert ra["pressure"] == pytest.approx(rb["pressure"], rel=ROUNDING_FEW)
        assert ra["h"] == pytest.approx(rb["h"], abs=2 * XTOL)
        assert ra["load_N"] == pytest.approx(ra["force_N"], rel=LOAD_CONTROL_RTOL)
        assert ra["area_m2"] == pytest.approx(ra["area"] * 1e-10, rel=ROUNDING_FEW)
    assert [r["force_N"] for r in a["rows"]] == pytest.approx([1e-6, 1e-5], rel=ROUNDING_FEW)


def test_area_gives_dimensional_columns_on_the_h_grid(capsys):
    _, out, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--h=1,2", "--area", "1mm^2",
                        "--format", "csv")  # fmt: skip
    row = rows_of(out)[0]
    # CSV numbers are repr: the same products, a rounding or two apart (measured ≤ 1.7e-16)
    assert float(row["P_N"]) == pytest.approx(float(row["P"]) * SILICON.K * 1e-6, rel=ROUNDING_FEW)
    assert float(row["N_c"]) == pytest.approx(
        float(row["contact_fraction"]) * SMOOTH.eta * 1e-6, rel=ROUNDING_FEW
    )


def test_pressure_and_load_specs_read_units_lists_and_log_ranges():
    # a log range: a power of the ratio on each side, ROUNDING_FORMULA; units: ROUNDING_FEW
    assert parse_values("1kPa:10MPa:31:log", "pressure", "--pressure") == pytest.approx(
        np.geomspace(1e3, 1e7, 31).tolist(), rel=ROUNDING_FORMULA
    )
    assert parse_values("1kPa,2 MPa,30", "pressure", "--pressure") == [1e3, 2e6, 30.0]
    assert parse_values("0:1mN:3", "force", "--load") == pytest.approx(
        [0, 5e-4, 1e-3], rel=ROUNDING_FEW
    )
    assert parse_values("1uN,10uN", "force", "--load") == pytest.approx(
        [1e-6, 1e-5], rel=ROUNDING_FEW
    )


@pytest.mark.parametrize(
    "argv, message",
    [
        (["--pressure", "0"], "--pressure: 0 Pa is out of range (allowed: > 0"),
        (["--pressure=-1kPa"], "--pressure: -1000 Pa is out of range (allowed: > 0"),
        (["--pressure", "1kPa:1MPa:0:log"], "asks for '0' points"),
        (["--pressure", "0:1MPa:5:log"], "log range needs start > 0"),
        (["--pressure", "1nm"], "--pressure: unknown unit 'nm' for a pressure"),
        (["--pressure", "1kPa:2kPa"], "--pressure: cannot read"),
        (["--load", "1uN"], "--load needs --area"),
        (["--load", "1nm", "--area", "1mm^2"], "--load: unknown unit 'nm' for a force"),
        (["--pressure", "1kPa", "--area", "1uN"], "--area: unknown unit 'uN' for an area"),
        (["--pressure", "1kPa", "--h=1"], "not allowed with argument"),
        (["--pressure", "1kPa", "--branch", "retract"], "approach branch only"),
        (["--pressure", "1kPa", "--plot", "x.pdf"], "its name must end in .png"),
        (["--h=1", "--plot", "x.png"], "--plot applies to --pressure/--load only"),
    ],
)
def test_bad_load_control_input_is_a_one_line_error(capsys, argv, message):
    code, out, err = run_cli(capsys, "analytic", "--surface", "smooth", *argv)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and message in err


def test_gw_light_load_ratio_is_three_pi_over_four_root_r_over_sigma_times_f1_over_f32():
    h = np.array([0.5, 2.0, 3.5])
    kappa = light_load_ratio(SMOOTH, h)

    def f(n, x):
        return integrate.quad(lambda s: (s - x) ** n * stats.norm.pdf(s), x, np.inf)[0]

    expected = [0.75 * math.pi * math.sqrt(SMOOTH.R / SMOOTH.sigma) * f(1, x) / f(1.5, x)
                for x in h]  # fmt: skip
    # light_load_ratio's own quadrature against quad at its default epsrel 1.5e-8:
    # measured 6.9e-8 apart; 1e-6 is 15× that
    np.testing.assert_allclose(kappa, expected, rtol=1e-6)


def test_plot_is_written_and_an_existing_file_is_kept(capsys, tmp_path):
    path = tmp_path / "load.png"
    argv = ["analytic", "--surface", "smooth", "--law", "jkr", "--pressure", "1kPa:1MPa:4:log",
            "--format", "csv", "--plot", str(path)]  # fmt: skip
    assert run_cli(capsys, *argv)[0] == 0
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    code, _, err = run_cli(capsys, *argv)
    assert code == 2 and "--overwrite" in err


@pytest.mark.parametrize("law, quantity", [("seed", "P"), ("jkr", "load")])
def test_monte_carlo_load_at_the_found_separation_agrees_with_the_pressure(law, quantity):
    import mcsim

    result = load_control(SMOOTH, SILICON, [1e5, 1e6], law)
    run = mcsim.simulate(SMOOTH, SILICON, result.h, "100 um^2", realizations=40, seed=7, law=law)
    rows = run.compare()
    rows = rows[rows.quantity == quantity]
    np.testing.assert_allclose(
        rows.analytic.to_numpy() * SILICON.K, [1e5, 1e6], rtol=LOAD_CONTROL_RTOL
    )
    assert np.all(np.abs(rows.z.to_numpy()) < 5)


def _stand_off_surface():
    """Super-smooth Table-1 summits (R, η) with 1 % of them on stand-off bumps 9 nm high
    (a two-level histogram: 99 % in [-1, 1] nm, 1 % in [8, 10] nm), as dimples or
    particles make them; the rest of the super-smooth surface's inputs, silicon, JKR."""
    import dataclasses

    from mcsim.topography.empirical import Empirical

    heights = Empirical.from_histogram([-1e-9, 1e-9, 8e-9, 10e-9], [0.99, 0.0, 0.01])
    return dataclasses.replace(SURFACES["super-smooth"], sigma=heights.sigma, heights=heights,
                               name="stand-off")  # fmt: skip


def test_a_stand_off_surface_jumps_into_contact_and_a_pull_beyond_its_pull_off_has_no_equilibrium():
    """A real non-monotone approach load (the Gaussian Table-1 surfaces have a single
    tensile minimum, so no jump under load control): the stand-off summits touch first
    (tensile, then compressive, up to a local maximum p_max ≈ 36 MPa at h ≈ 1), then the
    main population jumps in and the load falls to ≈ −5 MPa at h ≈ 0 before it rises.
    A load above p_max is reached through a jump; a pull beyond the stand-offs' own
    pull-off (≈ −0.49 MPa, at h ≈ 8.4) has no equilibrium, though the deeper tensile
    minimum of the main population would carry it. (The Table-1 surfaces' own "no
    equilibrium" case: test_a_tensile_load_beyond_the_pull_off_has_no_equilibrium.)"""
    surface = _stand_off_surface()
    h = np.linspace(10.0, -1.0, 2201)  # spacing 0.005
    p = gw_curves(surface, SILICON, h, "jkr").load * SILICON.K
    stand_offs, main = h > 5, (h > -0.5) & (h < 3)
    k_max = np.flatnonzero(main)[np.argmax(p[main])]  # the stand-offs' maximum
    p_max, p_off = p[k_max], p[stand_offs].min()  # and their pull-off
    k_deep = k_max + np.argmin(p[k_max:])  # the main population's tensile minimum
    p_deep = p[k_deep]
    assert 0.5 < h[k_max] < 1.5 and p_deep < p_off < 0 < p_max
    targets = [0.5 * p_max, 1.5 * p_max, 0.5 * p_off, (p_off + p_deep) / 2]
    result = load_control(surface, SILICON, targets, "jkr")
    assert result.equilibrium.tolist() == [True, True, True, False]
    assert result.jump.tolist() == [False, True, False, False]
    assert result.h[0] > h[k_max] and result.h[1] < h[k_deep]
    assert result.h[2] > 5  # on the stand-offs
    again = gw_curves(surface, SILICON, result.h[:3], "jkr").load * SILICON.K
    np.testing.assert_allclose(again, targets[:3], rtol=1e-9)


def test_simulate_at_pressures_runs_at_the_balancing_separations_and_the_load_agrees(
    capsys, tmp_path
):
    """Acceptance (issue 11 §1), through the command line: ``mcsim simulate --pressure``
    runs the Monte Carlo at the separations ``mcsim analytic --pressure`` finds (exactly
    those h), and the patches' mean load balances each pressure within |z| < 5."""
    out = tmp_path / "lc.h5"
    code, _, err = run_cli(capsys, "simulate", "--surface", "smooth", "--law", "jkr",
                           "--pressure", "100kPa,1MPa", "--area", "100um^2", "--realizations",
                           "40", "--seed", "7", "--workers", "1", "--out", str(out))  # fmt: skip
    assert code == 0 and "load control" in err
    _, csv_out, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--law", "jkr",
                            "--pressure", "100kPa,1MPa", "--format", "csv")  # fmt: skip
    from mcsim.store.runfile import read_run

    run = read_run(out)
    assert run.h.tolist() == [float(r["h"]) for r in rows_of(csv_out)]
    assert json.loads(run.attrs["load_control"]) == {"pressure": [1e5, 1e6], "unit": "Pa"}
    rows = run.compare()
    rows = rows[rows.quantity == "load"]
    np.testing.assert_allclose(
        rows.analytic.to_numpy() * SILICON.K, [1e5, 1e6], rtol=LOAD_CONTROL_RTOL
    )
    assert np.all(np.abs(rows.z.to_numpy()) < 5)


def test_simulate_with_load_divides_by_the_patch_area(capsys, tmp_path):
    argv = ["simulate", "--surface", "smooth", "--law", "seed", "--area", "100um^2", "--seed", "1",
            "--workers", "1", "--quiet"]  # fmt: skip
    assert run_cli(capsys, *argv, "--load", "1uN", "--out", str(tmp_path / "a.h5"))[0] == 0
    assert run_cli(capsys, *argv, "--pressure", "10kPa", "--out", str(tmp_path / "b.h5"))[0] == 0
    from mcsim.store.runfile import read_run

    # the same root h of two runs, each within XTOL (h crosses zero: absolute)
    assert read_run(tmp_path / "a.h5").h == pytest.approx(
        read_run(tmp_path / "b.h5").h, abs=2 * XTOL
    )
    code, out, _ = run_cli(capsys, "show", str(tmp_path / "b.h5"))
    assert code == 0 and "load control  nominal pressure p = 10000 .. 10000 Pa (1 values)" in out


@pytest.mark.parametrize(
    "argv, message",
    [
        (["--pressure", "0"], "--pressure: 0 Pa is out of range (allowed: > 0"),
        (["--pressure=-1kPa"], "--pressure: -1000 Pa is out of range (allowed: > 0"),
        (["--pressure", "1nm"], "--pressure: unknown unit 'nm' for a pressure"),
        (["--load", "1um"], "--load: unknown unit 'um' for a force"),
        (["--pressure", "1kPa", "--h=1"], "not allowed with argument"),
        (["--pressure", "1kPa", "--cycle"], "approach branch only"),
        ([], "one of the arguments --h --pressure --load is required"),
    ],
)
def test_bad_simulate_load_control_input_is_a_one_line_error(capsys, tmp_path, argv, message):
    code, out, err = run_cli(capsys, "simulate", "--surface", "smooth", "--law", "jkr", "--area",
                             "100um^2", "--out", str(tmp_path / "x.h5"), *argv)  # fmt: skip
    assert code == 2 and out == "" and not (tmp_path / "x.h5").exists()
    assert len(err.strip().splitlines()) == 1 and message in err


def test_plot_of_a_load_controlled_run_shows_each_patch_and_both_standard_errors(capsys, tmp_path):
    out = tmp_path / "lc.h5"
    argv = ["simulate", "--surface", "smooth", "--law", "jkr", "--material", str(_material(tmp_path)),
            "--pressure", "1MPa,10MPa", "--area", "100um^2", "--realizations", "5", "--seed", "2",
            "--workers", "1", "--quiet", "--out", str(out)]  # fmt: skip
    assert run_cli(capsys, *argv)[0] == 0
    code, _, err = run_cli(capsys, "plot", str(out))
    assert code == 0 and "each patch" in err
    assert out.with_suffix(".png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"

    from mcsim.figures.loadcontrol import load_run_figure
    from mcsim.store.runfile import read_run

    run = read_run(out)
    fig = load_run_figure(run)
    area_ax, friction_ax = fig.axes
    patches = area_ax.get_lines()[0]
    x, y = patches.get_data()
    load, area = run.realizations["load"].ravel(), run.realizations["area"].ravel()
    tensile = int(np.count_nonzero(load <= 0))  # one of the 10 patches at 1 MPa (seed 2)
    assert f"({tensile} with $p \\leq 0$ not shown)" in patches.get_label() and tensile == 1
    expected_x = np.sort(load[load > 0] * SILICON.K / SILICON.E_star)
    np.testing.assert_allclose(np.sort(x), expected_x, rtol=1e-12)
    np.testing.assert_allclose(np.sort(y), np.sort(area[load > 0]), rtol=1e-12)
    bars = area_ax.containers[0]  # the means, with error bars in x and in y
    assert bars.has_xerr and bars.has_yerr
    assert any("GW light load" in line.get_label() for line in area_ax.get_lines())
    assert friction_ax.containers[0].has_xerr and friction_ax.containers[0].has_yerr


def _material(tmp_path):
    path = tmp_path / "mat.toml"
    path.write_text(MAT)
    return path


@pytest.mark.parametrize("law", ["seed", "jkr"])
def test_load_control_figure_marks_the_gw_light_load_line_for_every_law_set(tmp_path, law):
    from mcsim.figures.loadcontrol import load_control_figure
    from mcsim.physics.loadcontrol import hertz_area_fraction
    from mcsim.store.config import load_material

    material = load_material(_material(tmp_path))
    result = load_control(SMOOTH, material, np.geomspace(1e3, 1e7, 5), law)
    area_ax, friction_ax = load_control_figure(result).axes
    labels = [line.get_label() for line in area_ax.get_lines()]
    assert any(label.startswith("GW light load") for label in labels)
    y = area_ax.get_lines()[0].get_data()[1]
    expected = hertz_area_fraction(SMOOTH, result.h) if law == "seed" else result.curves.area
    # the figure plots the same numbers (measured equal)
    np.testing.assert_allclose(y, expected, rtol=ROUNDING_FEW)
    if law == "jkr":  # friction = tau A_r: its light-load line tau kappa p/E*
        assert any("GW light load" in line.get_label() for line in friction_ax.get_lines())


def test_hertz_area_fraction_is_pi_eta_r_sigma_f1():
    from mcsim.physics.loadcontrol import hertz_area_fraction

    h = np.array([0.5, 2.0])
    f1 = [
        integrate.quad(
            lambda s, x=x: (s - x) * stats.norm.pdf(s), x, np.inf, epsabs=0, epsrel=1e-12
        )[0]
        for x in h
    ]
    expected = math.pi * SMOOTH.eta * SMOOTH.R * SMOOTH.sigma * np.array(f1)
    np.testing.assert_allclose(hertz_area_fraction(SMOOTH, h), expected, rtol=QUAD_RTOL)


def test_plot_versus_load_refuses_a_cycle_run_and_several_runs_in_one_line(capsys, tmp_path):
    argv = ["simulate", "--surface", "smooth", "--law", "jkr", "--area", "1um^2", "--h=1,0",
            "--seed", "1", "--workers", "1", "--quiet"]  # fmt: skip
    assert run_cli(capsys, *argv, "--cycle", "--out", str(tmp_path / "c.h5"))[0] == 0
    assert run_cli(capsys, *argv, "--out", str(tmp_path / "a.h5"))[0] == 0
    for runs, message in [(["c.h5"], "needs an approach run"), (["a.h5", "a.h5"], "one run")]:
        code, out, err = run_cli(capsys, "plot", *(str(tmp_path / r) for r in runs), "--versus",
                                 "load", "--out", str(tmp_path / "x.png"))  # fmt: skip
        assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and message in err
    assert not (tmp_path / "x.png").exists()


def test_the_api_takes_pressures_written_as_on_the_command_line():
    from mcsim.physics.loadcontrol import load_control

    spec = load_control(SMOOTH, SILICON, "1kPa:1MPa:2:log", "jkr")
    values = load_control(SMOOTH, SILICON, [1e3, 1e6], "jkr")
    np.testing.assert_array_equal(spec.h, values.h)
    with pytest.raises(ParameterError, match=r"pressure = \['lots'\]: give numbers"):
        load_control(SMOOTH, SILICON, ["lots"], "jkr")


# --- the seed's real contact area under load control (issue 33) ------------------------------


def test_the_seed_under_load_control_has_the_hertz_area_of_greenwood_williamson():
    result = load_control(SMOOTH, SILICON, [1e3, 1e6, 1e7], "seed")
    h = result.h
    # GW 1966, Eq. 9 with a Hertz summit's area pi R delta: A_r/A_n = pi eta R sigma F_1(h),
    # F_1(h) = int_h^inf (s - h) phi(s) ds = phi(h) - h Q(h) for Gaussian heights (closed form)
    f1 = stats.norm.pdf(h) - h * stats.norm.sf(h)
    expected = math.pi * SMOOTH.eta * SMOOTH.R * SMOOTH.sigma * f1
    # 8x24-point Gauss-Legendre against a closed form: QUAD_RTOL (its own accuracy ~1e-13)
    np.testing.assert_allclose(result.curves.values["area"], expected, rtol=QUAD_RTOL, atol=0)


def test_analytic_seed_versus_pressure_prints_area_and_with_area_area_m2(capsys):
    code, out, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--pressure", "1kPa,1MPa",
                           "--area", "1mm^2", "--format", "csv")  # fmt: skip
    assert code == 0
    rows = rows_of(out)
    assert {"area", "area_m2"} <= set(rows[0]), list(rows[0])  # neither was there
    for row in rows:
        # area_m2 = (A_r/A_n) x 1e-6 m^2: one rounding of a product
        assert float(row["area_m2"]) == pytest.approx(float(row["area"]) * 1e-6, rel=ROUNDING_FEW)
        assert float(row["area"]) > 0

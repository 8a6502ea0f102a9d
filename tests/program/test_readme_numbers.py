"""Every number README.md and the user guide (docs/guide/) quote outside "Performance" is
computed here and compared.

Each claim is a pattern that must match the pages exactly once, in one of them (line breaks
read as spaces), and a function computing the quoted numbers. Inputs and constants (presets,
ranges, defaults) must equal the code's value; results (``rounded``) must print as quoted
at the precision quoted: "90.8" is compared with the computed value written with one
decimal, "2.600e-5" with four significant digits. Changing the code or the pages alone
fails the test, naming the text.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from mcsim.engine.statistics import MIN_CONTACTS
from mcsim.model.params import MAX_ABS_H, RANGES, plasticity_index
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics import adhesion
from mcsim.physics.adhesion import adhesion_summary, maugis_parameter, tabor_parameter
from mcsim.physics.environment import DEFAULT_CUTOFF, Environment
from mcsim.physics.loadcontrol import XTOL

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
#: The landing page and the guide's pages, where the numbers checked here are quoted.
PAGES = (README, *sorted((ROOT / "docs" / "guide").glob("*.md")))
#: Their text, whitespace collapsed; a form feed between pages (no pattern spans two).
TEXT = "\f".join(" ".join(page.read_text().split()) for page in PAGES)

SILICON = MATERIALS["silicon"]
SMOOTH = SURFACES["smooth"]


def quoted(pattern: str) -> tuple[str, ...]:
    """The groups of the one match of `pattern` in the pages (whitespace collapsed)."""
    matches = list(re.finditer(pattern, TEXT))
    assert len(matches) == 1, f"the pages: {len(matches)} matches of {pattern!r}, expected 1"
    return matches[0].groups()


def at_precision(text: str, value: float) -> str:
    """`value` written as `text` is: the same decimals, or significant digits in e-notation."""
    if "e" in text:
        mantissa = text.split("e")[0]
        digits = len(mantissa.split(".")[1]) if "." in mantissa else 0
        m, e = f"{value:.{digits}e}".split("e")
        return f"{m}e{int(e)}"
    digits = len(text.split(".")[1]) if "." in text else 0
    return f"{value:.{digits}f}"


def check_rounded(pattern: str, *values: float) -> None:
    """The pages' numbers (groups of `pattern`) print as the computed `values`."""
    texts = tuple(t.replace("−", "-") for t in quoted(pattern))
    assert len(texts) == len(values)
    computed = tuple(at_precision(t, v) for t, v in zip(texts, values, strict=True))
    assert computed == texts, f"the pages say {texts} for {pattern!r}; the code gives {computed}"


def check_exact(pattern: str, *values: float) -> None:
    """The pages' numbers (groups of `pattern`) equal the code's inputs or constants."""
    texts = quoted(pattern)
    parsed = tuple(float(re.sub(r"[,\s]", "", t)) for t in texts)  # "14,700", "10 000"
    np.testing.assert_allclose(parsed, values, rtol=1e-12, err_msg=f"the pages: {pattern!r}")


# Inputs and constants ---------------------------------------------------------------------


def validation_script(name: str):
    """The module of ``validation/<name>.py`` (its inputs and criteria, which the README quotes)."""
    import importlib.util

    path = ROOT / "validation" / f"{name}.py"
    sys.path.insert(0, str(path.parent))
    try:
        spec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
    finally:
        sys.path.remove(str(path.parent))
    return module


def test_silicon_preset():
    check_exact(
        r"E = (\S+) GPa, ν = (\S+), H = (\S+) GPa, γ = (\S+) J/m², and an assumed equilibrium "
        r"spacing z0 = (\S+) nm",
        SILICON.E1 / 1e9, SILICON.nu1, SILICON.H / 1e9, SILICON.gamma, SILICON.z0 * 1e9,
    )  # fmt: skip
    assert (SILICON.E1, SILICON.nu1) == (SILICON.E2, SILICON.nu2)


def test_table1_eta_of_the_rough_surface():
    check_exact(r'"14,700" in the table means η = (\S+) µm⁻²', SURFACES["rough"].eta / 1e12)


def test_smooth_surface_of_the_toml_example():
    check_exact(
        r'sigma = "(\S+) nm" # std of summit heights R = "(\S+) um" # summit radius '
        r'eta = "(\S+) um\^-2"',
        SMOOTH.sigma * 1e9, SMOOTH.R * 1e6, SMOOTH.eta / 1e12,
    )  # fmt: skip


def test_parameter_ranges():
    check_exact(r"E >= (\S+) Pa \(with K, G <= 10¹⁴ Pa\)", RANGES["E"][0])
    assert RANGES["K"][1] == 1e14
    check_exact(r"0 <= γ <= 10³ J/m², (\S+) Pa <= H <= 10¹³ Pa", RANGES["H"][0])
    assert (RANGES["gamma"], RANGES["H"][1]) == ((0.0, 1e3, "J/m^2"), 1e13)
    check_exact(
        r"1 pm <= σ <= 1 cm, (\S+) nm <= R <= (\S+) m", RANGES["R"][0] * 1e9, RANGES["R"][1]
    )
    assert RANGES["sigma"][:2] == (1e-12, 1e-2)
    check_exact(r"(\S+) <= η <= 10²⁰ m⁻²", RANGES["eta"][0])
    assert RANGES["eta"][1] == 1e20
    assert quoted(r"(each finite with \|h\| <= 10⁶)") and MAX_ABS_H == 1e6


def test_the_error_of_a_bad_surface_is_the_one_the_readme_shows():
    from mcsim import Surface
    from mcsim.model.errors import ParameterError

    call, kind, message = quoted(r"`(mcsim\.Surface\(sigma=-1, R=1e-6, eta=1e12\))` raises "
                                 r"`(\w+): (.+?)`")  # fmt: skip
    assert call == "mcsim.Surface(sigma=-1, R=1e-6, eta=1e12)" and kind == "ParameterError"
    with pytest.raises(ParameterError) as raised:
        Surface(sigma=-1, R=1e-6, eta=1e12)
    assert str(raised.value) == message


def test_adhesion_map_thresholds():
    check_exact(
        r"\(DMT for λ < (\S+), JKR for λ > (\S+), Maugis–Dugdale between\)",
        adhesion.DMT_BELOW, adhesion.JKR_ABOVE,
    )  # fmt: skip


def test_environment_defaults():
    env = Environment()
    check_exact(r"default (\S+) nm\), `--rh`", DEFAULT_CUTOFF * 1e9)
    check_exact(r"`--temperature` \(kelvin only, default (\S+) K\)", env.temperature)
    check_exact(r"\(default water, (\S+) J/m²\)", env.surface_tension)
    check_exact(r"\(default water, (\S+) m³/mol\)", env.molar_volume)
    check_exact(r"5\.32 D/λ\), λ default (\S+) nm; `none`", env.retardation_wavelength * 1e9)
    assert env.retardation * env.retardation_wavelength == pytest.approx(5.32, rel=1e-15)
    check_rounded(r"up to 2γ_L cos θ ≈ (\S+) J/m²", 2 * env.surface_tension)


def test_load_control_tolerance_and_z_threshold():
    check_exact(r"Brent's method to (\S+) in h\)", XTOL)
    check_exact(r"Where fewer than (\S+) contacting summits are expected", MIN_CONTACTS)


def test_the_gpu_backends_blocks_and_launches():
    from mcsim.engine import cuda
    from mcsim.engine.montecarlo import BLOCK

    check_exact(r"each block of (\S+) summits is reduced in a fixed order", BLOCK)
    check_exact(r"at most (\S+) blocks and (\S+) MiB of sums per launch",
                cuda.LAUNCH_BLOCKS, cuda.LAUNCH_BYTES / 2**20)  # fmt: skip


def test_guarantees_state_the_bounds_the_tests_check():
    from designmap_checks import AGREE  # (the ~1e-13 of the curves: tests/physics/test_analytic.py)

    check_exact(r"the compiling one within (\S+) relative \(summaries\) and (\S+) in h",
                AGREE["summary"], AGREE["h_pull_off"])  # fmt: skip
    check_exact(r"agrees with it within stated tolerances, (\S+) relative for the summary:",
                AGREE["summary"])  # fmt: skip


def test_zero_sticking_pads_bound():
    # Clopper-Pearson's upper 95 % bound for 0 of n is 1 - 0.025^(1/n) ≈ -ln(0.025)/n
    check_rounded(r"0 sticking pads out of n only says p < (\S+)/n", -math.log(0.025))


# Computed results -------------------------------------------------------------------------


def test_friction_bound_of_identical_materials():
    # (2/√3)√(G/K) with the code's G and K of silicon (README point 5)
    check_rounded(
        r"√\(\(1−ν\)/\(2\(2−ν\)\)\) = (\S+) at ν = 0.22",
        2 / math.sqrt(3) * math.sqrt(SILICON.G / SILICON.K),
    )


def test_plasticity_indices():
    check_rounded(
        r"ψ = \(E\*/H\)√\(σ/R\): (\S+) for the rough surface .{0,80}?, (\S+) intermediate, "
        r"(\S+) smooth, (\S+) super-smooth",
        *(plasticity_index(SURFACES[s], SILICON) for s in ("rough", "intermediate", "smooth", "super-smooth")),
    )  # fmt: skip


def test_maugis_lambda_of_the_smooth_surface():
    check_rounded(r"\(Maugis λ = (\S+): the JKR–DMT", maugis_parameter(SMOOTH, SILICON))
    ratio = maugis_parameter(SMOOTH, SILICON) / tabor_parameter(SMOOTH, SILICON)
    check_rounded(r"`maugis_lambda` \(λ = (\S+) μ_T\)", ratio)
    check_rounded(r"the thresholds `--law auto` uses; λ = (\S+) μ_T\)", ratio)


def test_humidity_example_smooth_at_60_percent():
    summary = adhesion_summary(
        SMOOTH, SILICON, "maugis-dugdale", environment=Environment(hamaker=1.6e-19, rh=0.6)
    )
    check_rounded(
        r"gives a work of separation of (\S+) J/m²: (\S+)\s+from the summits' contact law, (\S+) "
        r"from van der Waals and (\S+) from the menisci \(Kelvin\s+radius (\S+) "
        r"nm\), at the rest of zero net load h_turn = (\S+)\.",
        summary.work_of_separation, summary.work_of_separation_contact,
        summary.work_of_separation_vdw, summary.work_of_separation_capillary,
        summary.kelvin_radius * 1e9, summary.turn,
    )  # fmt: skip


def test_humid_thresholds_and_films():
    from mcsim.physics import films
    from mcsim.physics.environment import NANO_GAP

    # "Will my device stick in humid air?": A = 1.6e-19 J, σ_n = 0.5 nm, water at 298.15 K
    env = Environment(hamaker=1.6e-19, asperity_roughness=0.5e-9)
    check_rounded(r"\*\*Nothing changes up to RH_cr ≈ ([\d.]+)\*\*", env.critical_rh)
    check_exact(r"`--asperity-roughness`, σ_n = (\S+) nm here\) holds each contact (\d+)σ_n open",
                env.asperity_roughness * 1e9, NANO_GAP)  # fmt: skip
    check_rounded(r"film on each face \(about (\S+) nm, ice-like, by RH (\S+), when bridges",
                  films.film_thickness(env.bridging_rh) * 1e9, env.bridging_rh)  # fmt: skip
    check_rounded(r"above RH_dry = ([\d.]+), the adsorbed films' onset", env.bridging_rh)
    (rh,) = quoted(
        r"default the isotherm t\(RH\) of water on silicon oxide, [\d.]+ nm at RH ([\d.]+)\)"
    )
    check_rounded(
        r"of water on silicon oxide, (\S+) nm at RH", films.film_thickness(float(rh)) * 1e9
    )
    check_rounded(r"\(its ice-like first layers, default (\S+) nm: menisci form only on a thicker "
                  r"film, above RH ([\d.]+) by default", films.STRUCTURED_FILM * 1e9,
                  films.film_humidity(films.STRUCTURED_FILM))  # fmt: skip


def test_the_van_der_waals_share_of_silicons_work_of_adhesion():
    from mcsim.physics.surfaceenvironment import contact_adhesion, vdw_share

    env = Environment(hamaker=1.6e-19)  # default cutoff D0 and retardation wavelength λ
    check_exact(r"of silicon's w = (\S+) J/m², A/\(12πD0²\)/\(1 \+ 5\.32 D0/λ\) = \S+ J/m² \(A = "
                r"(\S+) J, D0 = (\S+) nm, Gregory's retardation λ = (\S+) nm\)", SILICON.gamma,
                env.hamaker, env.cutoff * 1e9, env.retardation_wavelength * 1e9)  # fmt: skip
    check_rounded(r"of silicon's w = \S+ J/m², A/\(12πD0²\)/\(1 \+ 5\.32 D0/λ\) = (\S+) J/m² .{0,120}?"
                  r"the contacts carry the other (\S+) J/m²", vdw_share(SILICON.gamma, env),
                  contact_adhesion(SILICON.gamma, env))  # fmt: skip


def _pull_off_pressure(sigma: float, w: float = SILICON.gamma) -> float:
    """Analytic pull-off per nominal area (Pa) of the smooth surface at `sigma`, law auto."""
    surface = type(SMOOTH)(sigma=sigma, R=SMOOTH.R, eta=SMOOTH.eta)
    material = type(SILICON)(E1=SILICON.E1, E2=SILICON.E2, nu1=SILICON.nu1, nu2=SILICON.nu2,
                              gamma=w, H=SILICON.H, z0=SILICON.z0)  # fmt: skip
    law, _ = adhesion.choose_law(surface, material)
    return adhesion_summary(surface, material, law).pull_off_pressure


def test_design_sigma_numbers():
    p1, p2, p5 = (_pull_off_pressure(s * 1e-9) for s in (1, 2, 5))
    check_rounded(
        r"Between σ = 2 nm and 5 nm the pull-off pressure falls by more than six decades \((\S+) MPa to "
        r"(\S+) Pa\); at σ = 1 nm it is (\S+) MPa: a 10 µm × 10 µm pad then holds on with (\S+) mN",
        p2 / 1e6, p5, p1 / 1e6, p1 * 1e-10 * 1e3,
    )  # fmt: skip
    assert 6 < math.log10(p2 / p5) < 7
    # the first σ of the guide's 40-point grid (0.3 nm … 20 nm, log) with no tensile approach
    grid = np.geomspace(0.3e-9, 20e-9, 40)
    low, high = np.searchsorted(grid, 5e-9), len(grid) - 1  # pull-off > 0 at low, 0 at high
    assert _pull_off_pressure(grid[low]) > 0 and _pull_off_pressure(grid[high]) == 0
    while high - low > 1:  # the pull-off falls with σ: bisect for the first zero
        middle = (low + high) // 2
        low, high = (middle, high) if _pull_off_pressure(grid[middle]) > 0 else (low, middle)
    check_rounded(r"From σ ≈ (\S+) nm up the approach load is never tensile", grid[high] * 1e9)


@pytest.fixture(scope="module")
def pads_run(tmp_path_factory) -> Path:
    """The guide's run of 300 pads (step 2 of "Designing against stiction"), ~3 s."""
    out = tmp_path_factory.mktemp("pads") / "pads.h5"
    args = (
        "simulate --surface smooth --law maugis-dugdale --cycle --h=4:0:41 --area 10um^2 "
        "--realizations 300 --seed 1"
    )
    readme = r"(--area 10um\^2 \\ --realizations 300 --seed 1 --out pads\.h5)"
    assert quoted(r"maugis-dugdale --cycle --h=4:0:41 " + readme)  # the guide's command
    mcsim_here(*args.split(), "--out", str(out), "--quiet")
    return out


def mcsim(*args: str) -> str:
    """Standard output of the ``mcsim`` command of this interpreter's environment."""
    command = [str(Path(sys.executable).parent / "mcsim"), *args]
    return subprocess.run(command, capture_output=True, text=True, check=True).stdout


def mcsim_here(*args: str) -> str:
    """Standard output of ``mcsim ARGS`` run in this process (:func:`mcsim.cli.main.main`),
    for the commands that tests/program/test_readme.py runs, as written or on fewer points
    (its SMALLER), each in a process of its own: a new interpreter here would only import
    NumPy, SciPy and mcsim again."""
    return mcsim_here_with_stderr(*args)[0]


def mcsim_here_with_stderr(*args: str) -> tuple[str, str]:
    """Standard output and standard error of ``mcsim ARGS`` run in this process."""
    from mcsim.cli.main import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(list(args))
    assert code == 0, err.getvalue()
    return out.getvalue(), err.getvalue()


def test_pad_statistics(pads_run):
    # the guide's `mcsim pads` commands, in this process (test_readme.py runs them as written)
    cp, wilson = (
        json.loads(mcsim_here("pads", str(pads_run), "--restoring-force", "130uN", "--format",
                              "json", *extra))
        for extra in ((), ("--interval", "wilson"))
    )  # fmt: skip
    check_rounded(
        r"Here (\S+) pads of 10 µm² \(E\[N\] = (\S+) summits\) pull off with (\S+) ± (\S+) µN "
        r"\(std (\S+) µN, 5–95 %: (\S+)–(\S+) µN\), and (\S+) of the 300 stick against 130 µN: "
        r"p_stick = (\S+), 95 % interval (\S+)–(\S+) \(Clopper–Pearson\) or (\S+)–(\S+) \(Wilson\)",
        cp["pads"], 10e-12 * SMOOTH.eta, *(1e6 * cp[k] for k in ("mean", "se", "std", "q05", "q95")),
        cp["p_stick"] * cp["pads"], cp["p_stick"], cp["p_stick_ci_low"], cp["p_stick_ci_high"],
        wilson["p_stick_ci_low"], wilson["p_stick_ci_high"],
    )  # fmt: skip
    check_rounded(r"gives the GW analytic mean \(`analytic_mean`: the analytic pull-off × A K, (\S+) µN here\)",
                  1e6 * cp["analytic_mean"])  # fmt: skip


def test_pads_csv_has_the_columns_the_readme_lists_and_its_note_the_analytic_mean(pads_run):
    (columns,) = quoted(r"mcsim pads pads\.h5 --format csv > runs/pads\.csv # columns (\S+)")
    out, err = mcsim_here_with_stderr("pads", str(pads_run), "--format", "csv")
    assert out.splitlines()[0] == columns
    (note,) = [line for line in err.splitlines() if "analytic_mean = " in line]
    assert note.startswith("mcsim: note: pads = 300, mean = ")  # a count: no unit after it
    assert not re.search(r" = \S+ 1[,;]", note), f"a dimensionless value with a unit 1: {note}"


def test_analytic_with_an_area_adds_the_columns_the_readme_lists():
    (args, named) = quoted(r"mcsim (analytic --surface smooth --h=2:0:5 --area 1mm\^2) # adds the "
                           r"columns (.+?) \(N\)")  # fmt: skip
    header = {}
    for extra in ((), ("--area", "1mm^2")):
        plain = [a for a in args.split() if a not in ("--area", "1mm^2")]
        out = mcsim_here(*plain, *extra, "--format", "csv", "--quiet")
        header[extra] = next(line for line in out.splitlines() if not line.startswith("#"))
    added = [c for c in header[("--area", "1mm^2")].split(",") if c not in header[()].split(",")]
    assert added == named.split(", ")


def test_design_map_stiction_boundary():
    # the largest σ of the map's grid (0.3 nm … 100 nm, 25 log) with a pull-off above 1 kPa,
    # at two w of its grid (0.002 … 5 J/m², 13 log); the pull-off falls with σ: bisect
    sigmas, ws = np.geomspace(0.3e-9, 100e-9, 25), np.geomspace(0.002, 5, 13)
    largest = []
    for w in (ws[3], ws[11]):
        low, high = 0, len(sigmas) - 1  # above 1 kPa at low, not at high
        assert _pull_off_pressure(sigmas[low], w) > 1e3 >= _pull_off_pressure(sigmas[high], w)
        while high - low > 1:
            middle = (low + high) // 2
            above = _pull_off_pressure(sigmas[middle], w) > 1e3
            low, high = (middle, high) if above else (low, middle)
        largest.append(sigmas[low] * 1e9)
    check_rounded(
        r"grows with w, from (\S+) nm at w = (\S+) J/m² to (\S+) nm at (\S+) J/m²",
        largest[0],
        ws[3],
        largest[1],
        ws[11],
    )


def test_engine_and_file_constants():
    from mcsim.engine import montecarlo, spec
    from mcsim.engine.pads import load as padload
    from mcsim.model import distributions
    from mcsim.store.schema import MAX_EXPANSION
    from mcsim.studies.pads import FEW_CONTACTS
    from mcsim.studies.paper import MC_AREA
    from mcsim.studies.stiction import OFFSETS
    from mcsim.topography.maps import BYTES_PER_PIXEL

    check_exact(r"located to (\S+) in h\) at `h_pull_off`", adhesion.H_TOLERANCE)
    check_exact(r"the minimum of the mean curve, located to (\S+) in h", adhesion.H_TOLERANCE)
    check_exact(r"located in continuous h to (\S+) between the grid's", padload.XTOL)
    check_exact(r"drawn in fixed blocks of (\S+) summits", montecarlo.BLOCK)
    assert quoted(r"(ηA is limited to 10¹⁸ summits)") and spec.MAX_SUMMITS == 1e18
    check_rounded(r"NumPy's Poisson sampler ends near (\S+)·10¹⁸", np.iinfo(np.int64).max / 1e18)
    check_exact(r"\(after (\S+) s of work, then every", montecarlo.FIRST_CHECKPOINT)
    check_exact(r"no more than (\S+) times the file's size", MAX_EXPANSION)
    check_exact(r"one Monte Carlo patch of (\S+) mm² per surface", MC_AREA * 1e6)
    check_exact(r"fewer than ~(\S+) summits the sweep warns", FEW_CONTACTS)
    check_exact(
        r"for the Gaussian p \((\S+)×(\S+)-point Gauss–Legendre",
        distributions._PANELS, distributions._NODES_PER_PANEL,
    )  # fmt: skip
    check_exact(r"needs about (\S+) bytes per pixel", BYTES_PER_PIXEL)
    check_exact(r"the tails at (\d+) separations joined by their Gaussian copula", len(OFFSETS))
    check_rounded(r"\(a 16384² map: (\S+) GB\)", BYTES_PER_PIXEL * 16384**2 / 1e9)


def test_more_constants_of_the_code():
    import inspect
    import tomllib

    from mcsim.engine import montecarlo
    from mcsim.figures.topography import MAX_DRAWN_BINS
    from mcsim.physics import validity
    from mcsim.physics.laws import dmt
    from mcsim.store import files, runfile
    from mcsim.studies import simulation, tail
    from mcsim.studies.maps import adhesivecontact
    from mcsim.topography import mapsurface

    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    # the README's quick start, and the guide's installation page that repeats it
    pythons = re.findall(r"On a fresh machine with Python ≥ (\S+) \(and `make`\)", TEXT)
    assert len(pythons) == 2 and {f">={p}" for p in pythons} == {project["requires-python"]}
    check_exact(r"cut at D = (\S+) z0 \(the outputs report", dmt.DEFAULT_CUTOFF)
    check_exact(r"schema version (\d+), netCDF-compatible", runfile.SCHEMA_VERSION)
    check_exact(r"Datasets over (\d+) KiB \(the per-patch curves", files.COMPRESS_ABOVE / 1024)
    check_exact(r"checked between tasks and every (\S+) s while waiting", montecarlo.POLL)
    default = inspect.signature(simulation.simulate).parameters["checkpoint_every"].default
    check_exact(r"every `--checkpoint-every` seconds, default (\d+),", default)
    check_exact(r"Per step \((\d+) by default, `--steps`\)", adhesivecontact.STEPS)
    check_exact(r"a histogram of more than (\d+) bins is drawn merged into at most (\d+) bars",
                MAX_DRAWN_BINS, MAX_DRAWN_BINS)  # fmt: skip
    check_exact(r"direct and spectral routes more than a factor (\d+) apart",
                mapsurface.ROUTE_DISAGREEMENT)  # fmt: skip
    check_exact(r"or beyond A_r/A_n = (\S+) \(where neighbouring contacts interact\)",
                validity.INTERACTING_AREA)  # fmt: skip
    assert quoted(r"(A fifth of the estimate's pads are drawn from the real law and three tenths "
                  r"from a law half-way to the tilted one)")  # fmt: skip
    assert (tail.DEFENSIVE, tail.HALF_WAY) == (0.2, 0.3)
    check_rounded(
        r"because these summits sit at Maugis λ ≈ (\S+),", maugis_parameter(SMOOTH, SILICON)
    )


def test_the_coverage_asked_of_importance_sampling_is_the_benchmarks():
    module = validation_script("tail_benchmark")
    check_exact(r"95 % interval in at least (\d+) % of the runs, the coverage asked of them",
                module.COVERAGE * 100)  # fmt: skip


def test_humidity_threshold_of_the_intermediate_surface():
    # the guide's sweep, rh = 0.05 … 0.95 in 10 steps, law auto; the work of separation
    # grows with rh: its ends below the threshold and the two points above it suffice
    surface = SURFACES["intermediate"]
    law, _ = adhesion.choose_law(surface, SILICON)

    def work(rh: float) -> float:
        environment = Environment(hamaker=1.6e-19, rh=rh)
        return adhesion_summary(surface, SILICON, law, environment=environment).work_of_separation

    low, dry_top, threshold, above, top = (work(rh) for rh in (0.05, 0.25, 0.75, 0.85, 0.95))
    assert low == dry_top  # below RH_dry (the films' onset, 0.30) nothing condenses
    check_rounded(
        r"stays at (\S+) µJ/m² \(van der\s+Waals\) up to RH 0\.25, creeps to (\S+) µJ/m² at 75 % "
        r".{0,120}is (\S+) µJ/m² at 85 % and jumps to\s+(\S+) J/m² at 95 %",
        low * 1e6, threshold * 1e6, above * 1e6, top,
    )  # fmt: skip


@pytest.mark.slow
def test_p_stick_table(tmp_path):
    # the guide's sweep of "How likely is my device to stick?" (about 8 s of CPU)
    import xarray as xr

    args = quoted(
        r"mcsim (sweep --surface smooth --law jkr --vary sigma=1\.5nm:3nm:4 --preload "
        r"1MPa \\ --pads 100 --area 30um\^2 --restoring-force 20uN --seed 1) --out stick"
    )
    mcsim(*args[0].replace("\\ ", "").split(), "--out", str(tmp_path / "stick.h5"), "--quiet")
    with xr.open_dataset(tmp_path / "stick.h5", engine="h5netcdf") as ds:
        for i, sigma in enumerate(ds.sigma.values):
            row = ds.isel(sigma=i)
            check_rounded(
                rf"\| ({sigma * 1e9:.1f}) \| (\S+) \[(\S+), (\S+)\] \| (\S+) \| (\S+)",
                sigma * 1e9, *(float(row[v]) for v in ("p_stick", "p_stick_low", "p_stick_high",
                                                      "p_stick_model", "contacting_summits")),
            )  # fmt: skip
            row_start = re.escape(f"| {sigma * 1e9:.1f} |")
            method = quoted(rf"{row_start}[^|]+\|[^|]+\|[^|]+\| (\w+) \|")
            assert method == (str(row["p_stick_method"].values),)


def test_when_importance_sampling_replaces_the_fraction_of_the_pads():
    from mcsim.studies.rareevent import MIN_ESS, MIN_TAIL_PADS, SWITCH, TAIL_PADS, TAIL_PILOT
    from mcsim.studies.tail import CONFIRM

    check_exact(r"\| at least (\d+) pads stick and (\d+) do not \| `pads`", SWITCH, SWITCH)
    check_exact(r"\| fewer than (\d+) on either side \(at least (\d+) pads\) \| `importance`",
                SWITCH, MIN_TAIL_PADS)  # fmt: skip
    check_exact(r"\| fewer than (\d+) on either side, but fewer than (\d+) pads or `p_stick_ess` "
                r"below (\d+) \| `pads`", SWITCH, MIN_TAIL_PADS, MIN_ESS)  # fmt: skip
    check_exact(r"\| `--tail` \(at least (\d+) pads\) \| `importance`", MIN_TAIL_PADS)
    check_exact(r"pilot stages of a tenth as many pads as `--pads` \(at least (\d+); from (\d+) "
                r"`--pads` on, those pads are its first stage\) and as many pads again \(at least "
                r"(\d+)\)", TAIL_PILOT, TAIL_PILOT, TAIL_PADS)  # fmt: skip
    check_exact(r"where its effective sample size `p_stick_ess` is at least (\d+);", MIN_ESS)
    check_exact(r"rests on fewer than (\d+) effective pads, too few to confirm", CONFIRM)


def test_a_few_pads_stay_in_the_commands_process():
    from mcsim.studies.pads import PROCESS_PADS
    from mcsim.studies.sweeps import POOL_PADS

    check_exact(r"fewer than (\d+) pads in all, where no importance sampling can run", POOL_PADS)
    check_exact(r"and its plain ones from (\d+) pads on, run on `--workers`", PROCESS_PADS)
    check_exact(r"`mcsim pads`' \(the run's own pads from (\d+) on", PROCESS_PADS)


def test_the_report_resolves_p_stick_to_its_resolution():
    from mcsim.studies.report import DEFAULT_PADS, RESOLUTION

    check_exact(r"resolves p_stick to (\S+) devices of the lot: where it shows the rarer side "
                r"below (\S+)/N", RESOLUTION, RESOLUTION)  # fmt: skip
    check_exact(r"simulates `--pads` pads \((\d+)\) at each RH", DEFAULT_PADS)


@pytest.mark.slow
def test_tail_example(tmp_path):
    # the guide's sweep of "Far in the tail: importance sampling" (about 50 s of CPU)
    import xarray as xr

    args = quoted(
        r"mcsim (sweep --surface smooth --law jkr --vary sigma=3nm --preload 1MPa --pads 2000 "
        r"\\ --area 30um\^2 --restoring-force 83uN --tail --seed 1) --out tail"
    )
    mcsim(*args[0].replace("\\ ", "").split(), "--out", str(tmp_path / "tail.h5"), "--quiet")
    with xr.open_dataset(tmp_path / "tail.h5", engine="h5netcdf") as ds:
        row = ds.isel(sigma=0)
        assert str(row["p_stick_method"].values) == "importance"
        check_rounded(
            r"gives p_stick = (\S+) \[(\S+), (\S+)\] \(`p_stick_ess` (\S+)\) where `p_stick_model` "
            r"says (\S+): (\S+) summits touch a pad here",
            *(float(row[v]) for v in ("p_stick", "p_stick_low", "p_stick_high", "p_stick_ess",
                                      "p_stick_model", "contacting_summits")),
        )  # fmt: skip


@pytest.mark.slow
def test_p_stick_model_runs_low_in_the_tail_against_importance_sampling():
    # the guide's "its tail runs low" (about 12 s of CPU): 255 summits touch, every pad
    # retracted from h = 0; the model lies below the importance sampling's interval
    import dataclasses

    from mcsim.engine.spec import MonteCarloSpec
    from mcsim.studies.stiction import p_stick_model
    from mcsim.studies.tail import importance_p_stick

    surface = dataclasses.replace(SURFACES["smooth"], sigma=1.4e-9)
    spec = MonteCarloSpec(surface, SILICON, np.linspace(4, -1, 51), 30e-12, 2000, 1, "jkr",
                          cycle=True)  # fmt: skip
    h_off = adhesion_summary(surface, SILICON, "jkr", 0.0).h_pull_off
    model = p_stick_model(spec, 340e-6, turn=0.0, h_pull_off=h_off, preload=None)
    tail = importance_p_stick(spec, 340e-6, turn=0.0, pads=2000, pilot=300)
    contacting = surface.eta * 30e-12 * float(surface.heights.sf(0.0))
    check_rounded(r"with (\S+) summits touching \(σ = 1\.4 nm, 30 µm², every pad retracted from "
                  r"h = 0\) it says (\S+) at 340 µN, where importance sampling finds (\S+) \[(\S+), "
                  r"(\S+)\]", contacting, model, tail.p_stick, tail.low, tail.high)  # fmt: skip
    assert model < tail.low


@pytest.mark.slow
def test_humid_p_stick_table(tmp_path):
    # the guide's sweep of "Will my device stick in humid air?" (about 15 s of CPU)
    import xarray as xr

    args = quoted(
        r"mcsim (sweep --surface smooth --law maugis-dugdale --hamaker 1\.6e-19J "
        r"--asperity-roughness 0\.5nm \\ --vary rh=0,0\.3,0\.4,0\.45,0\.5,0\.55,0\.7,0\.9 "
        r"--preload 0 --pads 40 --area 30um\^2 \\ --restoring-force 450uN --seed 1) --out humid"
    )
    mcsim_here(*args[0].replace("\\ ", "").split(), "--out", str(tmp_path / "humid.h5"), "--quiet")
    with xr.open_dataset(tmp_path / "humid.h5", engine="h5netcdf") as ds:
        shown = 0
        for i, rh in enumerate(ds.rh.values):
            pattern = rf"\| ({rh:g}) \| (\S+) \[(\S+), (\S+)\] \| (\S+) \| (\S+) \|"
            if not re.search(pattern, TEXT):
                continue  # the table leaves some humidities out
            row = ds.isel(rh=i)
            check_rounded(
                pattern, rh, *(float(row[v]) for v in ("p_stick", "p_stick_low", "p_stick_high")),
                float(row["pull_off_mean"]) * 1e6, float(row["work_of_separation_mean"]) * 1e3,
            )  # fmt: skip
            shown += 1
        assert shown == 6
        # the pull-off peaks and falls while the work of separation keeps rising
        (wet, humid) = (ds.sel(rh=rh) for rh in (0.5, 0.9))
        check_rounded(r"the mean pull-off falls from (\S+) to (\S+) µN between RH 0\.5 and 0\.9 here",
                      float(wet["pull_off_mean"]) * 1e6, float(humid["pull_off_mean"]) * 1e6)  # fmt: skip
        assert float(ds["pull_off_mean"].max()) == float(wet["pull_off_mean"])
        assert np.all(np.diff(ds["work_of_separation_mean"].sel(rh=ds.rh >= 0.5).values) > 0)
        assert float(humid["p_stick"]) < 1  # "some pads are released again"


@pytest.mark.slow
def test_friction_slip_table(tmp_path):
    # the guide's sweep of "Will my pad slip?" (about 20 s of CPU)
    import xarray as xr

    from mcsim.studies.rareevent import MIN_TAIL_PADS, SWITCH

    args = quoted(
        r"mcsim (sweep --surface smooth --law jkr --hamaker 1\.6e-19J --vary "
        r"preload=0\.1MPa:10MPa:5:log \\ --vary rh=0,0\.6 --pads 40 --area 30um\^2 "
        r"--tangential-force 1\.75mN --seed 1) --out slip"
    )
    mcsim_here(*args[0].replace("\\ ", "").split(), "--out", str(tmp_path / "slip.h5"), "--quiet")
    with xr.open_dataset(tmp_path / "slip.h5", engine="h5netcdf") as ds:
        shown = 0
        for i, p in enumerate(ds.preload.values):
            for j, rh in enumerate(ds.rh.values):
                pattern = (rf"\| ({p / 1e6:.3g}) \| ({rh:g}) \| (\S+) \| (\S+) \[(\S+), (\S+)\] \| "
                           rf"(\S+) \[(\S+), (\S+)\] \|")  # fmt: skip
                if not re.search(pattern, TEXT):
                    continue  # the table leaves some points out
                row = ds.isel(preload=i, rh=j)
                check_rounded(pattern, p / 1e6, rh, float(row["static_friction_mean"]) * 1e3,
                              *(float(row[v]) for v in ("mu_static_mean", "mu_static_q05",
                              "mu_static_q95", "p_slip", "p_slip_low", "p_slip_high")))  # fmt: skip
                shown += 1
        assert shown == 7
        dry, humid = ds.sel(rh=0.0), ds.sel(rh=0.6)
        t, mu = dry["static_friction_mean"].values * 1e3, dry["mu_static_mean"].values
        check_rounded(r"\(from (\S+) to (\S+) mN dry over the whole range\)", t[0], t[-1])
        check_rounded(r"the 5–95 % of the pads\): from (\S+) to (\S+) dry\.", mu[0], mu[-1])
        at_1 = float(ds.sel(preload=1e6, rh=0.6)["static_friction_mean"]) * 1e3
        dry_1 = float(ds.sel(preload=1e6, rh=0.0)["static_friction_mean"]) * 1e3
        check_rounded(r"\((\S+) against (\S+) mN at 1 MPa\)", at_1, dry_1)
        check_rounded(r"Humidity raises T_s by (\S+) % here", (at_1 / dry_1 - 1) * 100)
        quoted(r"slips under this force unless it is pressed with the top preload; at RH 0\.6 "
               r"none of the pads does at any preload")  # fmt: skip
        slip = dry["p_slip"].values
        assert np.all(slip[:-1] > 0.5) and slip[-1] < 0.5 and np.all(humid["p_slip"].values == 0)
    check_exact(r"where fewer than (\d+) pads lie on one side \(and at least (\d+) pads were "
                r"simulated\) importance sampling estimates it", SWITCH, MIN_TAIL_PADS)  # fmt: skip


def test_lim_et_al_inputs_are_the_validation_scripts():
    module = validation_script("pad_friction")
    poly, nitride = (
        module.MEASURED["polysilicon/polysilicon"],
        module.MEASURED["nitride/polysilicon"],
    )
    check_exact(r"\(μ_s = (\S+) ± (\S+) polysilicon on polysilicon, (\S+) ± (\S+) nitride on "
                r"polysilicon\)", *poly, *nitride)  # fmt: skip
    check_exact(r"Table-1 surface at (\S+)–(\S+) kPa: μ_s within a decade",
                module.PRESSURES[0] / 1e3, module.PRESSURES[-1] / 1e3)  # fmt: skip


def test_tail_reach_point_is_the_validation_scripts():
    module = validation_script("tail_benchmark")
    check_exact(r"point at\s+p ≈ 1e-6 draws (\d+) final pads and stages of (\d+) in each search",
                module.REACH_PADS, module.REACH_PILOT)  # fmt: skip


@pytest.mark.slow
def test_force_control_against_a_common_turn():
    # "Force control matters": 400 jkr pads of 30 µm² at σ = 2.5 nm (seed 1, the sweep's
    # default grid h = 4 … −1), each pressed to 1 MPa, then all turned at the mean-field turn
    # (about 5 s of CPU)
    import dataclasses

    from mcsim.engine.pads import curves as padcurves
    from mcsim.engine.pads import load as padload
    from mcsim.engine.spec import MonteCarloSpec
    from mcsim.physics.loadcontrol import preload_turn
    from mcsim.studies.pads import pad_statistics

    surface, area = dataclasses.replace(SMOOTH, sigma=2.5e-9), 30e-12
    turn = preload_turn(surface, SILICON, 1e6, "jkr")
    spec = MonteCarloSpec(surface, SILICON, np.linspace(4, -1, 51), area, 400, 1, "jkr", cycle=True)
    own, common, turns = [], [], []
    for r in range(spec.realizations):
        z = padload.patch_heights(spec, r)
        d_turn, _ = padcurves.force_turn(spec, z, 1e6 * area)
        turns.append(d_turn)
        own.append(padcurves.pull_off(spec, z, d_turn)[0])
        common.append(padcurves.pull_off(spec, z, turn * surface.sigma)[0])
    stats = [pad_statistics(np.array(f), restoring_force=20e-6) for f in (own, common)]
    check_rounded(
        r"pull off with mean (\S+) N, standard deviation (\S+) N and p_stick (\S+) \[(\S+), (\S+)\];"
        r" retracted from the common mean-field turn h̄ = (\S+) the same pads give (\S+) N, (\S+) N "
        r"and (\S+) \[(\S+), (\S+)\]\. .{0,100}\(correlation (\S+) between the turn",
        stats[0].mean, stats[0].std, stats[0].p_stick, *stats[0].p_stick_ci, turn,
        stats[1].mean, stats[1].std, stats[1].p_stick, *stats[1].p_stick_ci,
        np.corrcoef(turns, own)[0, 1],
    )  # fmt: skip


def test_separation_limits_and_bandwidth_of_the_paper_surfaces():
    from mcsim.cli.options import MAX_SEPARATIONS
    from mcsim.physics.gapheights import nayak_heights

    check_exact(r"inclusive\), at most (\d+\s\d+) separations", MAX_SEPARATIONS)
    alphas = [nayak_heights(SURFACES[s].sigma, SURFACES[s].R, SURFACES[s].eta).alpha
              for s in ("rough", "intermediate", "smooth", "super-smooth")]  # fmt: skip
    check_rounded(r"have a low bandwidth parameter α \((\S+)–(\S+)\)", min(alphas), max(alphas))


def test_paper_mu_table_separations_and_pad_summits():
    from mcsim.studies.paper import MU_TABLE_H

    texts = quoted(r"prints μ at h = (\S+), (\S+), (\S+), (\S+), (\S+) and the plasticity index")
    assert tuple(float(t.replace("−", "-")) for t in texts) == tuple(MU_TABLE_H)
    check_rounded(
        r"A pad of 30 µm² on the smooth surface holds ~(\S+) summits", 30e-12 * SMOOTH.eta
    )


def test_every_file_the_pages_name_exists():
    named = set(re.findall(r"`((?:tests|validation|docs|examples|runs)/[\w./-]+\.(?:py|toml|md))`",
                           TEXT))  # fmt: skip
    missing = sorted(p for p in named if not (ROOT / p).exists())
    assert named and not missing, f"the pages name files that do not exist: {missing}"


def test_the_stickiness_thresholds_are_the_codes():
    from mcsim.physics import stickiness

    check_exact(r"its validity Δr/g0 = \S+ \(below (\S+): valid\)", stickiness.PR_RANGE_LIMIT)
    check_exact(r"\(below (\S+): the pixels resolve the law; above it mcsim warns\)",
                stickiness.MESH_LIMIT)  # fmt: skip


@pytest.mark.slow
def test_adhesive_contact_of_the_shipped_scan():
    # "Is GW's adhesion right on my map?": the guide's command as JSON (about 10 s of CPU)
    (args,) = quoted(
        r"mcsim (contact examples/scan\.npy --unit m --pixel-size 10nm --adhesion --w "
        r"0\.1J/m\^2 --range 1nm \\ --pressure 100MPa) --plot"
    )
    data = json.loads(mcsim_here(*args.replace("\\ ", "").split(), "--format", "json", "--quiet"))
    s, gw, sticky = data["summary"], data["summary"]["gw"], data["stickiness"]
    check_rounded(r"the exact pull-off is (\S+) kPa and the work of separation (\S+) mJ/m²",
                  s["pull_off"] / 1e3, s["work_of_separation"] * 1e3)  # fmt: skip
    ratios = [gw[law]["pull_off_ratio"] for law in ("jkr", "dmt", "maugis-dugdale")]
    check_rounded(r"GW gives (\S+)× that pull-off with jkr, (\S+)× with dmt and (\S+)× with "
                  r"maugis-dugdale: no law set is within 20 %", *ratios)  # fmt: skip
    assert all(abs(r - 1) > 0.2 for r in ratios)
    check_rounded(
        r"the Pastewka–Robbins parameter is (\S+) \(above 1: not sticky", sticky["pr_parameter"]
    )
    assert sticky["pr_parameter"] > 1
    check_rounded(r"its validity Δr/g0 = (\S+) \(below 0\.1: valid\), and the mesh criterion (\S+) "
                  r"\(below 0\.5", sticky["range_over_gap"], sticky["mesh"])  # fmt: skip
    assert sticky["range_over_gap"] < 0.1 and sticky["mesh"] < 0.5
    assert len(data["rows"]) == 60  # 30 steps, approach and retraction

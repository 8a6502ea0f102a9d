"""GW calibrated on the exact solution (issue 32, point 3): `mcsim ingest --calibrate` fits one
summit-radius scale to exact solves, records it, and every command reading the file uses it."""

import io
import math
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import numpy as np
import pytest

from mcsim.cli.main import main
from mcsim.model.presets import MATERIALS
from mcsim.store.config import load_surface
from mcsim.studies.calibration import LOADS, TARGET, _errors, calibrate
from mcsim.studies.contact import gw_hertz
from mcsim.studies.ingest import ingest_file

ROOT = Path(__file__).resolve().parents[2]
SCAN = ROOT / "examples" / "scan.npy"  # periodic, 100 x 100 pixels of 10 nm, heights in m
MAP = {"unit": "m", "pixel_size": 1e-8}
SILICON = MATERIALS["silicon"]


def run_cli(*argv) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        code = main([str(a) for a in argv])
    return code, out.getvalue(), err.getvalue()


@pytest.fixture(scope="module")
def calibrated(tmp_path_factory):
    result = ingest_file(SCAN, **MAP, calibrate=SILICON)
    toml = result.write_surface(tmp_path_factory.mktemp("cal") / "scan.toml")[0]
    return result, toml


def test_the_scale_is_the_one_that_makes_the_worst_area_error_smallest(calibrated):
    c = calibrated[0].calibration
    pressure = LOADS * SILICON.E_star
    surface = calibrated[0].surface
    worst = np.max(np.abs(_errors(surface, SILICON, pressure, c.exact_area, c.radius_scale)))
    # fitted to 1e-8 in ln s: a scale 1e-4 away on either side is worse
    for factor in (1 - 1e-4, 1 + 1e-4):
        other = _errors(surface, SILICON, pressure, c.exact_area, c.radius_scale * factor)
        assert np.max(np.abs(other)) > worst
    # and it improves on the measured radius everywhere it matters: the worst error
    assert c.worst < np.max(np.abs(c.uncalibrated_area / c.exact_area - 1))


def test_calibrated_gw_area_on_the_shipped_scan_is_within_its_recorded_error(calibrated):
    # Measured once on examples/scan.npy (100 x 100 Gaussian-correlated, 10 nm pixels): the best
    # single scale, 1.347, leaves 13.8 % at the ends (+14 % at 1e-4 E*, where the exact contact is
    # 23 pixels; -12 % at 1e-2 E*, where contacts interact): above the 10 % target, and said so.
    c = calibrated[0].calibration
    assert c.radius_scale == pytest.approx(1.347, abs=5e-4)
    assert c.worst == pytest.approx(0.138, abs=5e-4)
    assert c.worst > TARGET and "one radius scale cannot follow" in c.warnings()[0]
    ratio = c.gw_area / c.exact_area
    assert np.all(np.abs(ratio[1:-1] - 1) <= TARGET)  # within 10 % inside the range's ends
    for doc in ("README.md", "docs/contact.md"):  # the numbers they quote
        text = " ".join((ROOT / doc).read_text().split())
        assert f"{c.radius_scale:.3f}" in text and f"{c.worst * 100:.1f} %" in text, doc
    text = " ".join((ROOT / "docs" / "contact.md").read_text().split())
    assert f"here {c.gw_gap[-1] * 1e9:.2f} nm against {c.exact_gap[-1] * 1e9:.2f} nm" in text
    assert (
        f"+{(ratio[0] - 1) * 100:.0f} % at 1e-4" in text
        and f"−{(1 - ratio[-1]) * 100:.0f} %" in text
    )


def test_the_docs_say_why_one_scale_falls_short_as_radius_height_measures_it(monkeypatch):
    # validation/radius_height.py: GW summed over the map's own summits, one radius for all
    # against each its own; the numbers docs/contact.md quotes are these.
    monkeypatch.syspath_prepend(str(ROOT / "validation"))
    from radius_height import one_scale

    from mcsim.topography.readers import read_height_map
    from mcsim.topography.summits import summit_curvatures

    exact = calibrate(SCAN, SILICON, **MAP).exact_area
    z_map = read_height_map(SCAN, **MAP).heights
    z, kappa = summit_curvatures(z_map - z_map.mean(), 1e-8, 1e-8, periodic=True)
    assert np.all(kappa > 0)
    area, pressure = z_map.size * 1e-16, LOADS * SILICON.E_star
    own = one_scale(1 / kappa, z, pressure, exact, area)[1]
    one = one_scale(np.full(z.size, 1 / kappa.mean()), z, pressure, exact, area)[1]
    r = np.corrcoef(z, kappa)[0, 1]
    text = " ".join((ROOT / "docs" / "contact.md").read_text().split())
    assert f"correlate, r = {r:.2f})" in text
    assert f"one scale is within {np.max(np.abs(own - 1)) * 100:.1f} % at all five" in text
    assert f"(with one radius, {np.max(np.abs(one - 1)) * 100:.1f} %;" in text
    # the measured cause: a height-dependent radius brings one scale within the 10 %
    assert np.max(np.abs(own - 1)) <= TARGET < np.max(np.abs(one - 1))


def test_the_surface_file_records_the_scale_and_every_reader_uses_it(calibrated):
    result, toml = calibrated
    c = result.calibration
    text = toml.read_text()
    assert "[surface.calibration]" in text and "does NOT fix the mean gap" in text
    assert "worst_error = 0.1375" in text and "load = [0.0001, 0.000316228" in text
    loaded = load_surface(toml)
    # R and the scale in 12 significant digits: 1e-11
    assert loaded.R == pytest.approx(result.surface.R * c.radius_scale, rel=1e-11)
    area = gw_hertz(loaded, SILICON, LOADS * SILICON.E_star)[1]
    np.testing.assert_allclose(area, c.gw_area, rtol=1e-9)  # the same area, from the file
    code, out, _ = run_cli("analytic", "--surface", toml, "--pressure", "10MPa")
    assert code == 0 and f"R = {result.surface.R * c.radius_scale * 1e6:.4g} um" in out


def test_the_mean_gap_is_recorded_and_not_calibrated(calibrated):
    c = calibrated[0].calibration
    # GW's mean gap at 1e-2 E* stays far from the exact one: 1.44 against 2.51 nm
    assert c.gw_gap[-1] < 0.6 * c.exact_gap[-1]
    assert "the mean gap is NOT calibrated" in "\n".join(c.lines())


def test_a_bad_radius_scale_in_a_file_is_one_line(calibrated, tmp_path):
    toml = tmp_path / "scan.toml"  # beside copies of its histogram files
    toml.write_text(calibrated[1].read_text().replace("radius_scale = ", "radius_scale = -"))
    for name in ("scan-heights.csv", "scan-map-heights.csv"):
        (tmp_path / name).write_text((calibrated[1].parent / name).read_text())
    code, _, err = run_cli("analytic", "--surface", toml, "--h=1")
    assert code == 2 and err.count("\n") == 1 and "radius_scale" in err


def test_calibrate_on_a_histogram_is_refused_in_one_line(tmp_path):
    path = tmp_path / "h.csv"
    path.write_text("0, 1\n1, 3\n2, 1\n")
    code, _, err = run_cli("ingest", path, "--R", "1um", "--eta", "1um^-2", "--calibrate")
    assert code == 2 and err.count("\n") == 1 and "--calibrate needs a height map" in err


def test_the_ratio_does_not_depend_on_the_material():
    # both areas scale with p/E*: gold gives the scale silicon gives (to the fit's 1e-8 in ln s
    # and the solver's tolerance 1e-6)
    gold = calibrate(SCAN, MATERIALS["silicon"].__class__(E1=79e9, E2=79e9, nu1=0.42, nu2=0.42,
                                                         gamma=0.3, name="gold"), **MAP)  # fmt: skip
    silicon = calibrate(SCAN, SILICON, **MAP)
    assert math.isclose(gold.radius_scale, silicon.radius_scale, rel_tol=1e-4)

"""GW's validity said: warnings where its area passes the nominal area or where summits interact,
and where its work of separation of the contact exceeds w (issue 32, point 4)."""

import io
import math
import warnings
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import numpy as np
from scipy import optimize

from mcsim.cli.main import main
from mcsim.model.params import Surface
from mcsim.model.presets import MATERIALS
from mcsim.physics.adhesion import ValidityWarning, adhesion_summary
from mcsim.physics.analytic import gw_curves
from mcsim.physics.loadcontrol import hertz_area_fraction
from mcsim.physics.validity import INTERACTING_AREA, area_warnings, work_warnings

ROOT = Path(__file__).resolve().parents[2]
SILICON = MATERIALS["silicon"]
#: The direct-route summits of NSFopen's sapphire.nid, as mcsim ingest finds them (Gaussian here).
SAPPHIRE = Surface(sigma=0.2267e-9, R=1.147e-6, eta=587e12)


def run_cli(*argv) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        code = main([str(a) for a in argv])
    return code, out.getvalue(), err.getvalue()


def test_small_areas_give_no_warning():
    assert area_warnings([0.01, INTERACTING_AREA, np.nan], [3.0, 1.0, -9.0]) == []


def test_an_area_beyond_the_interaction_bound_names_the_largest_and_its_separation():
    (line,) = area_warnings([0.05, 0.3, 0.2], [2.0, 0.5, 1.0])
    assert "beyond where independent summits hold" in line and "A_r/A_n = 0.3 at h = 0.5" in line


def test_an_area_above_the_nominal_area_says_so():
    (line,) = area_warnings([0.5, 2.54], [0.0, -1.0])
    assert "passes the nominal area" in line and "A_r/A_n = 2.54 at h = -1" in line


def test_a_work_of_separation_above_w_is_warned_and_one_below_is_not():
    assert work_warnings(0.49, 0.5) == [] and work_warnings(math.nan, 0.5) == []
    (line,) = work_warnings(1.39, 0.5)
    assert "1.39 J/m^2, exceeds the work of adhesion w = 0.5 J/m^2" in line


def test_seed_curves_use_their_hertz_area_and_warn_just_past_the_bound():
    # h where the Hertz summits' area is exactly the bound, to 1e-12 in h
    h0 = optimize.brentq(lambda h: hertz_area_fraction(SAPPHIRE, h)[0] - INTERACTING_AREA,
                         -3, 6, xtol=1e-12)  # fmt: skip
    assert gw_curves(SAPPHIRE, SILICON, [h0 + 1e-6, 4.0], "seed").validity_warnings() == []
    (line,) = gw_curves(SAPPHIRE, SILICON, [h0 - 1e-6, 4.0], "seed").validity_warnings()
    assert "beyond where independent summits hold" in line


def test_law_set_curves_use_their_own_area():
    curves = gw_curves(SAPPHIRE, SILICON, [-1.0], "jkr")
    (line,) = curves.validity_warnings()
    assert f"A_r/A_n = {curves.area[0]:.3g} at h = -1" in line and curves.area[0] > 1


def test_adhesion_summary_warns_where_its_turn_is_beyond_gw():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        s = adhesion_summary(SAPPHIRE, SILICON, "maugis-dugdale")
    assert s.work_of_separation > SILICON.w  # 1.40 J/m² at the zero-load turn h = -2.93
    assert len(s.validity) == 2 and "passes the nominal area" in s.validity[0]
    assert "exceeds the work of adhesion" in s.validity[1]
    assert [str(w.message) for w in caught if w.category is ValidityWarning] == list(s.validity)


def test_adhesion_summary_in_gw_s_range_is_silent():
    with warnings.catch_warnings():
        warnings.simplefilter("error", ValidityWarning)
        s = adhesion_summary(SAPPHIRE, SILICON, "maugis-dugdale", turn=3.0)
    assert s.validity == () and s.work_of_separation < SILICON.w


def test_a_real_scan_through_ingest_analytic_and_adhesion_is_warned_about(nid_files, tmp_path):
    # the report: NSFopen's sapphire.nid ingested, then A_r/A_n = 2.5 at h = -1 and a
    # work of separation of 1.39 J/m^2 > w = 0.5 J/m^2, without a word
    toml = tmp_path / "sapphire.toml"
    assert run_cli("ingest", nid_files["sapphire"], "--out", toml, "--quiet")[0] == 0
    code, _, err = run_cli("analytic", "--surface", toml, "--h=2:-1:4", "--law", "maugis-dugdale")
    assert code == 0 and "warning: GW's real contact area passes the nominal area" in err
    docs = " ".join((ROOT / "docs" / "contact.md").read_text().split())
    area = err.split("A_r/A_n = ")[1].split(" at h = -1")[0]  # the numbers docs/contact.md quotes
    assert f"gives A_r/A_n = {area} at h = −1 with the Maugis–Dugdale law set" in docs
    code, _, err = run_cli("adhesion", "--surface", toml)
    assert code == 0 and "warning: GW's work of separation of the contact, 1.39 J/m^2" in err
    assert "a work of separation of 1.39 J/m² above w = 0.5 J/m²" in docs
    code, _, err = run_cli("analytic", "--surface", toml, "--pressure", "1MPa:1GPa:4:log")
    assert code == 0 and "warning: GW's real contact area passes the nominal area" in err

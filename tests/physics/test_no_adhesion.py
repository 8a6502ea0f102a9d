"""dmt and maugis-dugdale without adhesion (w = 0) are Hertz, with or without z0 (issue 33).

With w = 0 there is no attraction, so its range z0 is not needed and there is no tail to
cut: both laws reduce to Hertz's sphere, P = K R^½ δ^{3/2} and area πRδ (Hertz 1882;
Johnson 1985, §4.2), nothing out of contact. The seed's P is that Hertz load (Eq. 2) and
its area :func:`hertz_area_fraction`, the references here.
"""

from __future__ import annotations

import numpy as np
import pytest
from conftest import run_cli
from tolerances import ROUNDING_FEW

import mcsim
from mcsim.model.params import Material
from mcsim.physics.laws import get_law_set
from mcsim.physics.laws.seed import hertz_load
from mcsim.physics.loadcontrol import hertz_area_fraction

SMOOTH = mcsim.Surface(sigma=1.4e-9, R=1.7e-6, eta=17e12)
H = np.linspace(-3.0, 3.0, 13)

#: maugis-dugdale reads Hertz from its table (a cubic spline per interval of a geometric
#: grid): measured 1.2e-10 per summit (δ/R from 1e-14 to 1), 1.9e-11 over the GW
#: integral; the law set's own table is tested to 1e-8 against Maugis' equations.
MD_TABLE_RTOL = 1e-9


def no_adhesion(z0):
    return Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, gamma=0.0, z0=z0)


@pytest.mark.parametrize("z0", [None, 0.3e-9])
def test_dmt_without_adhesion_is_hertz(z0):
    curves = mcsim.gw_curves(SMOOTH, no_adhesion(z0), H, "dmt")
    hertz = mcsim.gw_curves(SMOOTH, no_adhesion(z0), H)  # the seed's P: Hertz (Eq. 2)
    # the same quadrature of Hertz's load minus an exact zero: identical but for a
    # rounding or two in the normalisation
    np.testing.assert_allclose(curves.load, hertz.P, rtol=ROUNDING_FEW, atol=0)
    np.testing.assert_allclose(curves.area, hertz_area_fraction(SMOOTH, H), rtol=ROUNDING_FEW,
                               atol=0)  # fmt: skip


@pytest.mark.parametrize("branch", ["approach", "retract"])
@pytest.mark.parametrize("z0", [None, 0.3e-9])
def test_maugis_dugdale_without_adhesion_is_hertz_on_both_branches(z0, branch):
    curves = mcsim.gw_curves(SMOOTH, no_adhesion(z0), H, "maugis-dugdale", branch=branch)
    hertz = mcsim.gw_curves(SMOOTH, no_adhesion(z0), H)
    np.testing.assert_allclose(curves.load, hertz.P, rtol=MD_TABLE_RTOL, atol=0)
    # the table's A² = Δ is linear in each interval: a cubic spline holds it to rounding
    np.testing.assert_allclose(curves.area, hertz_area_fraction(SMOOTH, H), rtol=ROUNDING_FEW * 4,
                               atol=0)  # fmt: skip


def test_maugis_dugdale_per_summit_without_adhesion_is_hertz_and_zero_apart():
    material = no_adhesion(None)
    delta = np.concatenate([-np.geomspace(1e-6, 1e-20, 50), [0.0], np.geomspace(1e-20, 1e-6, 500)])
    out = get_law_set("maugis-dugdale").evaluate(delta, SMOOTH, material)
    touching = delta > 0
    assert np.all(out["load"][~touching] == 0) and np.all(out["area"][~touching] == 0)
    hertz = hertz_load(delta[touching], SMOOTH.R, material.K)
    np.testing.assert_allclose(out["load"][touching], hertz, rtol=MD_TABLE_RTOL, atol=0)


def test_monte_carlo_of_maugis_dugdale_without_adhesion_matches_dmt_summit_by_summit():
    """The same seed draws the same summits: both law sets give Hertz on each of them."""
    runs = [mcsim.simulate(SMOOTH, no_adhesion(None), [1.0, 0.0], "2um^2", realizations=2,
                           seed=4, law=law, workers=1) for law in ("dmt", "maugis-dugdale")]  # fmt: skip
    np.testing.assert_allclose(runs[1].realizations["load"], runs[0].realizations["load"],
                               rtol=MD_TABLE_RTOL, atol=0)  # fmt: skip


@pytest.mark.parametrize("law", ["dmt", "maugis-dugdale"])
def test_analytic_command_takes_w_0_without_z0_and_prints_no_cutoff_note(capsys, tmp_path, law):
    for z0 in ("", 'z0 = "0.3 nm"\n'):
        toml = tmp_path / "m.toml"
        toml.write_text(f'[material]\nE = "160 GPa"\nnu = 0.22\ngamma = "0 J/m^2"\n{z0}')
        code, out, err = run_cli(capsys, "analytic", "--surface", "smooth", "--material", toml,
                                 "--law", law, "--h=1,0")  # fmt: skip
        assert code == 0 and "load" in out, (
            err
        )  # used to need z0 (both) or gamma > 0 (maugis-dugdale)
        assert "tail" not in err and "cut" not in err, err  # no tail to cut without attraction


def test_dmt_and_maugis_dugdale_with_adhesion_still_need_z0():
    material = Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, gamma=0.5)
    for law in ("dmt", "maugis-dugdale"):
        with pytest.raises(mcsim.ParameterError, match="needs material field 'z0'"):
            mcsim.gw_curves(SMOOTH, material, H, law)


def test_without_adhesion_no_law_set_is_outside_a_zone_of_the_adhesion_map():
    """lambda = 0 at w = 0 used to flag jkr as outside the JKR zone: with no adhesion every
    adhesive law set is Hertz, on no side of the map."""
    from mcsim.physics.adhesion import regime_warnings

    material = no_adhesion(0.3e-9)
    for law in ("jkr", "dmt", "maugis-dugdale"):
        assert regime_warnings(SMOOTH, material, law) == [], law
    adhesive = Material(E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, gamma=0.5, z0=0.3e-9)
    assert regime_warnings(SMOOTH, adhesive, "jkr")  # with adhesion: lambda < 5, flagged

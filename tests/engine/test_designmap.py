"""The compiled design-map path (``mcsim.engine.designmap``) against the reference:
``adhesion_summary`` and ``gw_curves`` of ``mcsim.physics``, point by point, on surfaces
drawn at random (not the ones the rule was checked on while it was written).

Tolerances, and why:

* loads and areas: 1e-13 of the curve's largest magnitude. Both are Gauss–Legendre sums of
  the same law over the same s range; the fast rule (32 nodes in u = √(Δ − δ_c/σ)) and the
  reference (8 × 24 nodes per panel) each sit within ~1e-15 of the integral (measured
  2e-14 apart at worst over σ = 0.3–10 nm, w = 0.05–1 J/m²), 1e-13 leaves a factor 5;
* turn: 1e-10 in h. Both are Brent roots to 1e-12 of loads that agree to 1e-13 relative,
  and the load's slope at its zero is of the order of its scale;
* pull-off, work of separation, hysteresis: 1e-9 relative. The work and hysteresis are
  the same 8-node panel rule (the approach part on 16 panels, analytic: rounding) of loads
  within 1e-13; the pull-off is the load at the minimum, where a location error Δh costs
  ½|L''|Δh² (≤ 1e-12 relative for Δh ≤ 4e-7), or nothing at a kink, which both paths
  hold as a panel edge;
* pull-off location: the reference's bounded Brent stops within
  2(√ε|h| + 1e-7/3) of the minimum (SciPy's stop rule, ``xatol`` = 1e-7), the fast path
  within 1e-8 (its ``xatol``, counted from the bracket's start); and on the reference's
  own curve the fast location is a minimum to 1e-7: the load 1e-7 either side is not
  lower (up to 1e-14 of the pull-off, rounding).
"""

import dataclasses
import math
import warnings

import numpy as np
import pytest

from mcsim.engine.designmap import NO_REST, OK, jkr_summaries
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.adhesion import RegimeWarning, adhesion_summary
from mcsim.physics.analytic import gw_curves
from mcsim.studies.sweeps import DEFAULT_H, sweep

SMOOTH, SILICON = SURFACES["smooth"], MATERIALS["silicon"]
H = np.asarray(DEFAULT_H)
CURVE_RTOL, TURN_ATOL, SUMMARY_RTOL = 1e-13, 1e-10, 1e-9
SUMMARY = ("pull_off", "work_of_separation", "hysteresis")


def random_points(n: int, seed: int):
    """``n`` (surface, material) pairs: σ log-uniform 0.3–6 nm, R 0.5–5 µm, w 0.05–1 J/m²,
    E 60–300 GPa: pull-offs from the JKR zone to the far tail of the heights."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        surface = dataclasses.replace(SMOOTH, sigma=math.exp(rng.uniform(math.log(0.3e-9), math.log(6e-9))),
                                      R=rng.uniform(0.5e-6, 5e-6))  # fmt: skip
        material = dataclasses.replace(SILICON, gamma=rng.uniform(0.05, 1.0),
                                       E1=rng.uniform(60e9, 300e9), E2=rng.uniform(60e9, 300e9))  # fmt: skip
        out.append((surface, material))
    return out


def fast(points, turn=None) -> dict:
    s = [p[0] for p in points]
    m = [p[1] for p in points]
    return jkr_summaries([x.sigma for x in s], [x.R for x in s], [x.eta for x in s],
                         [x.E_star for x in m], [x.K for x in m], [x.gamma for x in m], H, turn)  # fmt: skip


def reference(surface, material, turn=None):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RegimeWarning)
        return adhesion_summary(surface, material, "jkr", turn=turn)


@pytest.fixture(scope="module")
def batch():
    points = random_points(12, seed=20251125)
    return points, fast(points)


def test_the_fast_approach_curves_equal_gw_curves_to_1e_13_of_their_scale(batch):
    points, result = batch
    for i, (surface, material) in enumerate(points):
        curves = gw_curves(surface, material, H, "jkr")
        for q in ("load", "area"):
            scale = np.max(np.abs(curves.values[q]))
            np.testing.assert_allclose(result[q][i], curves.values[q], rtol=0, atol=CURVE_RTOL * scale,
                                       err_msg=f"{q} at point {i}")  # fmt: skip


def test_the_fast_turn_pull_off_work_and_hysteresis_equal_adhesion_summary(batch):
    points, result = batch
    assert np.any(result["status"] == OK) and np.any(result["pull_off"] > 1e-6)
    for i, (surface, material) in enumerate(points):
        ref = reference(surface, material)
        assert result["turn"][i] == pytest.approx(ref.turn, rel=0, abs=TURN_ATOL), i
        for k in SUMMARY:
            assert result[k][i] == pytest.approx(getattr(ref, k), rel=SUMMARY_RTOL, abs=0), (k, i)


def test_the_fast_pull_off_is_located_to_1e_7_in_h_on_the_reference_curve(batch):
    points, result = batch
    checked = 0
    for i, (surface, material) in enumerate(points):
        if result["pull_off"][i] == 0:
            continue
        ref = reference(surface, material)
        h = result["h_pull_off"][i]
        stop = 2 * (math.sqrt(np.finfo(float).eps) * abs(ref.h_pull_off) + 1e-7 / 3) + 1e-8
        assert abs(h - ref.h_pull_off) <= stop, i
        turn = result["turn"][i]
        load = gw_curves(surface, material, [h - 1e-7, h, h + 1e-7], "jkr", branch="retract",
                         turn=min(turn, h - 1e-7)).load  # fmt: skip
        assert np.all(load[[0, 2]] >= load[1] - 1e-14 * abs(load[1])), i
        checked += 1
    assert checked >= 6


def test_a_given_turn_gives_the_summary_after_that_turn():
    points = random_points(4, seed=7)
    result = fast(points, turn=-0.5)
    for i, (surface, material) in enumerate(points):
        ref = reference(surface, material, turn=-0.5)
        assert result["turn"][i] == -0.5
        for k in SUMMARY:
            assert result[k][i] == pytest.approx(getattr(ref, k), rel=SUMMARY_RTOL, abs=0), (k, i)


def test_without_a_tensile_approach_load_the_surfaces_rest_apart_as_in_adhesion_summary():
    surface = dataclasses.replace(SMOOTH, sigma=5e-9)
    material = dataclasses.replace(SILICON, gamma=0.05)
    result = fast([(surface, material)])
    ref = reference(surface, material)
    assert result["status"][0] == NO_REST and ref.turn_from.startswith("none")
    assert result["turn"][0] == ref.turn
    assert (result["pull_off"][0], result["work_of_separation"][0]) == (0.0, 0.0)
    assert math.isnan(result["h_pull_off"][0])


def test_a_point_gives_the_same_bits_alone_and_in_a_batch(batch):
    points, result = batch
    alone = fast(points[5:6])
    for k, v in alone.items():
        np.testing.assert_array_equal(v[0], result[k][5], err_msg=k)


def test_a_jkr_sweep_stores_the_fast_summaries_and_friction_within_their_tolerances():
    material = dataclasses.replace(SILICON, tau=50e6)
    result = sweep(SMOOTH, material, {"sigma": "0.5nm,1nm,2nm", "gamma": "0.3,0.9"}, law="jkr",
                   workers=2)  # fmt: skip
    assert not result.failed
    for i, sigma in enumerate(result.coords["sigma"]):
        for j, gamma in enumerate(result.coords["gamma"]):
            surface = dataclasses.replace(SMOOTH, sigma=sigma)
            mat = dataclasses.replace(material, gamma=gamma)
            ref = reference(surface, mat)
            for k in SUMMARY:
                assert result.data[k][i, j] == pytest.approx(getattr(ref, k), rel=SUMMARY_RTOL), k
            curves = gw_curves(surface, mat, H, "jkr")
            for q in ("load", "friction"):
                scale = np.max(np.abs(curves.values[q]))
                np.testing.assert_allclose(result.data[q][i, j], curves.values[q], rtol=0,
                                           atol=CURVE_RTOL * scale, err_msg=q)  # fmt: skip
            np.testing.assert_array_equal(result.data["contact_fraction"][i, j],
                                          curves.contact_fraction)  # fmt: skip


_BATCH_SCRIPT = """
import sys
import numpy as np
from mcsim.engine import designmap
from mcsim.physics.environment import Environment
sigma = np.geomspace(0.3e-9, 20e-9, 12)
out = {}
for kind, env in (("dry", None), ("environment", Environment(hamaker=1.6e-19, rh=0.6))):
    got = designmap.jkr_summaries(sigma, 1.7e-6, 17e12, 8.7e10, 1.16e11, 0.1,
                                  np.linspace(4, -1, 51), environment=env)
    out |= {f"{kind}/{k}": np.asarray(v, float) for k, v in got.items()}
for entry in ("_batch", "_batch_net"):
    assert not getattr(designmap._compiled(), entry).stats.cache_misses, "compiled here"
np.savez(sys.argv[1], **out)
"""


def test_the_first_process_after_an_install_gives_the_bits_of_every_later_one(tmp_path):
    """Compiled in this process, the kernels' numbers differed by up to 5e-14 from those of
    a process loading them from numba's cache: they are compiled in a child and loaded, so a
    fresh cache's first run and a later run agree bit for bit, dry and with an environment."""
    import os
    import subprocess
    import sys

    env = os.environ | {"MCSIM_CACHE_DIR": str(tmp_path / "cache")}

    def run(name):
        subprocess.run([sys.executable, "-c", _BATCH_SCRIPT, str(tmp_path / f"{name}.npz")],
                       env=env, check=True)  # fmt: skip
        return np.load(tmp_path / f"{name}.npz")

    first, later = run("first"), run("later")
    assert sorted(first.files) == sorted(later.files)
    for k in first.files:
        np.testing.assert_array_equal(first[k], later[k], err_msg=k)
    # A cache that holds the kernels without their markers (an earlier mcsim's) gets the
    # markers back from the child, which then finds the kernels there: no child later.
    markers = sorted((tmp_path / "cache" / "kernels").glob("*.compiled"))
    assert len(markers) == 2
    for marker in markers:
        marker.unlink()
    again = run("again")
    assert all(marker.exists() for marker in markers)
    for k in first.files:
        np.testing.assert_array_equal(first[k], again[k], err_msg=k)

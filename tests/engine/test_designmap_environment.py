"""The compiled design-map path with an environment (``jkr_summaries(..., environment=...)``)
against the reference: ``adhesion_summary`` and ``gw_curves`` with the same environment, point
by point, on surfaces, humidities, Hamaker constants, contact angles and cutoffs drawn at
random (not the ones the rule was checked on while it was written), and on the corners:
van der Waals alone, condensation alone, a deep turn, condensation off (θ >= 90°, RH = 0),
nothing acting.

Tolerances, and why (the dry ones of tests/engine/test_designmap.py, whose reasons hold;
each constant below gives its own):

* curves (net load, area, vdw, capillary): 1e-13 of the curve's largest magnitude. The
  contact parts are the dry fast rule at 64 nodes; each attraction is the summits' caps
  plus the open gaps: closed forms (normal tails by erfc against the reference's ndtr and
  erfcx), the open gaps' van der Waals moment by a 96-node rule against the reference's
  144 nodes, and the caps' bounded moment against the reference's panelled GW quadrature
  of the per-summit law, each within ~1e-14 relative of the integral: rounding;
* turn: 3e-12 in h (Brent roots to 1e-12 of net loads within 1e-13);
* pull-off, work of separation and its parts, hysteresis: 2e-10 relative. The contact
  work after a deep turn moves with the turn (δ_max = σ(s − turn)), ~40× the turn's error
  at worst; the attraction's works are the reference's own function at the fast turn;
  zeros (no term, or the surfaces apart) are exact;
* kelvin_radius, rq, summit_offset: equal (the same functions of the same inputs).

Measured on 113 points (the random draws of nine seeds and the corners, turns down to
h = −6.3): curves 5.4e-15 of their scale, turn 5.8e-13, summary 1.5e-11 relative.
"""

import dataclasses
import math
import warnings

import numpy as np
import pytest
from designmap_checks import assert_agree, inputs, run_elsewhere, summaries

from mcsim.engine.maps.designmap import NO_REST, OK, jkr_summaries
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.adhesion import RegimeWarning, adhesion_summary
from mcsim.physics.analytic import gw_curves
from mcsim.physics.environment import Environment
from mcsim.physics.gapheights import gap_heights
from mcsim.physics.surfaceenvironment import vdw_share
from mcsim.studies.sweeps import DEFAULT_H

SMOOTH, SILICON = SURFACES["smooth"], MATERIALS["silicon"]
H = np.asarray(DEFAULT_H)
# The fast kernel against gw_curves and adhesion_summary (the reasons of AGREE in
# tests/designmap_checks.py, which compares the kernel with itself):
#: curves: the same quadrature terms in other orders and numba's libm against NumPy's,
#: absolute in units of the curve's largest value (the load crosses zero); measured 5.4e-15
#: of it, and a first compile may differ from cached runs by 5e-14 (issue 29).
CURVE_RTOL = 1e-13
#: turn, in h (absolute, h crosses zero): the reference's brentq stops within xtol = 1e-12
#: (mcsim/physics/adhesion.py), the kernel's root within AGREE["turn"]; measured 5.8e-13
#: (a turn where the net load's slope is small).
TURN_ATOL = 3e-12
#: pull-off, works, hysteresis (≥ 0, relative): the retraction moves with the turn, up to
#: 40× its error: AGREE["summary"]; measured 1.5e-11.
SUMMARY_RTOL = 2e-10
SUMMARY = ("pull_off", "work_of_separation", "hysteresis", "work_of_separation_contact",
           "work_of_separation_vdw", "work_of_separation_capillary")  # fmt: skip
EXACT = ("kelvin_radius", "rq", "summit_offset")
CURVES = ("load", "area", "vdw", "capillary")


def random_cases(n: int, seed: int):
    """``n`` (surface, material, environment): σ log-uniform 0.3–6 nm, R 0.5–5 µm, w
    0.05–1 J/m² above the van der Waals share A/(12πD0²) (one interface: w includes it), E
    60–300 GPa; A 0.3–3e-19 J or none, RH 0–0.95 or 0, θ 0–80°, D0 0.12–0.3 nm."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        surface = dataclasses.replace(SMOOTH, sigma=math.exp(rng.uniform(math.log(0.3e-9), math.log(6e-9))),
                                      R=rng.uniform(0.5e-6, 5e-6))  # fmt: skip
        material = dataclasses.replace(SILICON, gamma=rng.uniform(0.05, 1.0),
                                       E1=rng.uniform(60e9, 300e9), E2=rng.uniform(60e9, 300e9))  # fmt: skip
        hamaker = rng.uniform(0.3e-19, 3e-19) if rng.uniform() < 0.75 else None
        rh = rng.uniform(0.05, 0.95) if rng.uniform() < 0.75 else 0.0
        env = Environment(hamaker=hamaker, rh=rh, contact_angle=rng.uniform(0, math.radians(80)),
                          cutoff=rng.uniform(0.12e-9, 0.3e-9))  # fmt: skip
        material = dataclasses.replace(material, gamma=material.gamma + vdw_share(0.0, env))
        out.append((surface, material, env))
    return out


#: The corners: van der Waals alone, condensation alone, both, a turn deep below the summits
#: (h = −6.3: the menisci of the caps of a very smooth, sticky surface pull every summit in;
#: there the dry kernel's 32-node contact rule is 2e-11 off in the turn), condensation off by
#: the contact angle and by a dry vapour, on the smooth surface and rougher or smoother ones;
#: van der Waals non-retarded and strongly retarded (the random draws: λ = 100 nm).
CORNERS = [
    (SMOOTH, SILICON, Environment(hamaker=1.6e-19)),
    (SMOOTH, SILICON, Environment(rh=0.7, contact_angle=math.radians(20))),
    (dataclasses.replace(SMOOTH, sigma=4e-9), SILICON, Environment(hamaker=1.6e-19, rh=0.5)),
    (
        dataclasses.replace(SMOOTH, sigma=0.3e-9, R=4e-6),
        dataclasses.replace(SILICON, gamma=0.8, E1=90e9, E2=160e9),
        Environment(rh=0.6, contact_angle=math.radians(50), cutoff=0.21e-9),
    ),
    # van der Waals without retardation, and strongly retarded (λ = 5 nm; default 100 nm)
    (SMOOTH, SILICON, Environment(hamaker=1.6e-19, rh=0.6, retardation_wavelength=None)),
    (
        dataclasses.replace(SMOOTH, sigma=4e-9),
        SILICON,
        Environment(hamaker=2.5e-19, rh=0.9, retardation_wavelength=5e-9),
    ),
    (SMOOTH, SILICON, Environment(hamaker=6.5e-20, rh=0.8, contact_angle=math.radians(100))),
    (dataclasses.replace(SMOOTH, sigma=2.5e-9), SILICON, Environment(hamaker=2e-19, rh=0.0)),
]


def fast(cases, turn=None) -> dict:
    s, m, e = zip(*cases)
    gaps = [gap_heights(x) for x in s]
    return jkr_summaries([x.sigma for x in s], [x.R for x in s], [x.eta for x in s],
                         [x.E_star for x in m], [x.K for x in m], [x.gamma for x in m], H, turn,
                         environment=e, rq=[g.rq for g in gaps],
                         summit_offset=[g.summit_offset for g in gaps])  # fmt: skip


def reference(surface, material, env, turn=None):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RegimeWarning)
        return adhesion_summary(surface, material, "jkr", turn=turn, environment=env)


def assert_summary_equal(result, i, ref):
    assert result["turn"][i] == pytest.approx(ref.turn, rel=0, abs=TURN_ATOL), i
    for k in SUMMARY:
        assert result[k][i] == pytest.approx(getattr(ref, k), rel=SUMMARY_RTOL, abs=0), (k, i)
    for k in EXACT:
        assert result[k][i] == getattr(ref, k), (k, i)


@pytest.fixture(scope="module")
def batch():
    cases = random_cases(10, seed=20251126) + CORNERS
    return cases, fast(cases)


@pytest.fixture(scope="module")
def references(batch):
    """:func:`reference` at each point of the batch, computed once for the tests that read it."""
    return [reference(*case) for case in batch[0]]


def test_the_fast_curves_with_an_environment_equal_gw_curves_to_1e_13_of_their_scale(batch):
    cases, result = batch
    for i, (surface, material, env) in enumerate(cases):
        curves = gw_curves(surface, material, H, "jkr", environment=env)
        for q in CURVES:
            scale = np.max(np.abs(curves.values[q]))
            np.testing.assert_allclose(result[q][i], curves.values[q], rtol=0, atol=CURVE_RTOL * scale,
                                       err_msg=f"{q} at point {i}")  # fmt: skip


def test_the_fast_summary_with_an_environment_equals_adhesion_summary(batch, references):
    result = batch[1]
    assert np.all(result["status"] == OK)
    assert np.sum(result["work_of_separation_vdw"] > 0) >= 5
    assert np.sum(result["work_of_separation_capillary"] > 0) >= 5
    for i, ref in enumerate(references):
        assert_summary_equal(result, i, ref)


def test_without_condensation_the_capillary_terms_are_zero_as_in_adhesion_summary(batch):
    cases, result = batch
    for i in (len(cases) - 2, len(cases) - 1):  # θ = 100°, RH = 0
        assert not cases[i][2].has_capillary
        assert result["work_of_separation_capillary"][i] == 0.0
        assert np.all(result["capillary"][i] == 0.0)
        assert result["work_of_separation_vdw"][i] > 0


def test_the_fast_pull_off_is_located_to_1e_7_in_h_on_the_reference_net_curve(batch, references):
    cases, result = batch
    checked = 0
    for i, ((surface, material, env), ref) in enumerate(zip(cases, references, strict=True)):
        if result["pull_off"][i] == 0:
            continue
        h = result["h_pull_off"][i]
        stop = 2 * (math.sqrt(np.finfo(float).eps) * abs(ref.h_pull_off) + 1e-7 / 3) + 1e-8
        assert abs(h - ref.h_pull_off) <= stop, i
        turn = result["turn"][i]
        load = gw_curves(surface, material, [h - 1e-7, h, h + 1e-7], "jkr", branch="retract",
                         turn=min(turn, h - 1e-7), environment=env).load  # fmt: skip
        assert np.all(load[[0, 2]] >= load[1] - 1e-14 * abs(load[1])), i
        checked += 1
    assert checked >= 10


def test_a_given_turn_gives_the_summary_after_that_turn():
    cases = random_cases(3, seed=8)
    result = fast(cases, turn=-0.5)
    for i, case in enumerate(cases):
        assert result["turn"][i] == -0.5
        assert_summary_equal(result, i, reference(*case, turn=-0.5))


def test_given_heights_whose_environment_top_lies_below_the_summits_top():
    # rq = σ and y_s = 3σ: every gap is open and wider than g_K below the summits' top,
    # so the grid above the summits runs downwards and the pull-off grid is sorted.
    surface = dataclasses.replace(SMOOTH, rq=SMOOTH.sigma, summit_offset=3 * SMOOTH.sigma)
    case = (surface, SILICON, Environment(hamaker=1.6e-19, rh=0.6))
    result = fast([case])
    assert_summary_equal(result, 0, reference(*case))
    assert result["rq"][0] == SMOOTH.sigma


def test_with_nothing_acting_and_no_tensile_load_the_surfaces_rest_apart_as_in_adhesion_summary():
    surface = dataclasses.replace(SMOOTH, sigma=5e-9)
    case = (surface, dataclasses.replace(SILICON, gamma=0.05), Environment(rh=0.0))
    result = fast([case])
    ref = reference(*case)
    assert result["status"][0] == NO_REST and ref.turn_from.startswith("none")
    assert result["turn"][0] == ref.turn
    for k in SUMMARY:
        assert result[k][0] == getattr(ref, k) == 0.0, k
    assert math.isnan(result["h_pull_off"][0])


def test_a_point_gives_the_same_bits_alone_and_in_a_batch(batch):
    cases, result = batch
    alone = fast(cases[3:4])
    for k, v in alone.items():
        np.testing.assert_array_equal(v[0], result[k][3], err_msg=k)


def test_one_environment_for_every_point_and_nayak_heights_by_default():
    s, m, _ = zip(*random_cases(3, seed=9))
    env = Environment(hamaker=1.6e-19, rh=0.5)
    m = [dataclasses.replace(x, gamma=x.gamma + vdw_share(0.0, env)) for x in m]  # w >= share
    short = jkr_summaries([x.sigma for x in s], [x.R for x in s], [x.eta for x in s],
                          [x.E_star for x in m], [x.K for x in m], [x.gamma for x in m], H,
                          environment=env)  # fmt: skip
    full = fast([(a, b, env) for a, b in zip(s, m)])
    for k, v in full.items():
        np.testing.assert_array_equal(short[k], v, err_msg=k)


def test_the_kernel_with_an_environment_run_by_the_interpreter_agrees_with_the_compiled_one(
    tmp_path,
):
    """With ``NUMBA_DISABLE_JIT=1`` the interpreter runs every function of the kernel, and
    gets the compiled numbers within rounding (tests/designmap_checks.py: ``AGREE``)."""
    cases = random_cases(2, seed=13) + CORNERS[:3]
    s, m, e = zip(*cases)
    arguments = inputs(list(zip(s, m)), H, e)
    compiled = summaries(arguments)
    assert np.all(compiled["status"] == OK)
    interpreted = run_elsewhere(arguments, tmp_path, "interpreted", NUMBA_DISABLE_JIT="1")
    assert_agree(interpreted, compiled)

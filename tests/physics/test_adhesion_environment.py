"""adhesion_summary with an environment (issue 22): the works of the attraction from the turn
to infinity against an independent quadrature, their limits and trends, and the pull-off of
the net load."""

import dataclasses
import math
import warnings

import numpy as np
import pytest
from scipy import integrate
from tolerances import QUAD_RTOL

from mcsim import gw_curves
from mcsim.model.params import Material, Surface
from mcsim.physics.adhesion import RegimeWarning, adhesion_summary
from mcsim.physics.environment import Environment
from mcsim.physics.gapheights import gap_heights

SURFACE = Surface(sigma=1.9e-9, R=1.2e-6, eta=14e12, rq=2.4e-9, summit_offset=2.1e-9, name="s")
MATERIAL = Material(E1=150e9, E2=150e9, nu1=0.25, nu2=0.25, gamma=0.3, z0=0.3e-9)
ENV = Environment(hamaker=1.3e-19, cutoff=0.19e-9, rh=0.7, contact_angle=math.radians(12))
LAW = "maugis-dugdale"


def summary(surface=SURFACE, env=ENV, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RegimeWarning)
        return adhesion_summary(surface, MATERIAL, LAW, environment=env, **kw)


def quad_works(D_t, rq, env):
    """W_vdW = (A/12π) E[max(D_t − z, D0)⁻²] and W_cap = (γ_L/r_K) E[(g_K − max(D0, D_t − z))⁺]
    over Gaussian z by scipy quad (docs/physics.md, section 'The environment')."""

    def density(z):
        return math.exp(-0.5 * (z / rq) ** 2) / (rq * math.sqrt(2 * math.pi))

    knee = D_t - env.cutoff
    opts = {"epsabs": 0, "epsrel": 1e-12, "limit": 400}
    open_part, _ = integrate.quad(lambda z: (D_t - z) ** -2 * density(z), -14 * rq, knee, **opts)
    closed, _ = integrate.quad(density, knee, 14 * rq, **opts)
    vdw = env.hamaker / (12 * math.pi) * (open_part + closed / env.cutoff**2)
    g_k = env.condensation_gap
    filled, _ = integrate.quad(lambda z: (g_k - (D_t - z)) * density(z), D_t - g_k, knee, **opts)
    cap = env.surface_tension / env.kelvin_radius * (filled + (g_k - env.cutoff) * closed)
    return vdw, cap


@pytest.mark.parametrize("surface", [SURFACE, Surface(sigma=3.3e-9, R=2.1e-6, eta=9e12, name="nayak")],
                         ids=lambda s: s.name)  # fmt: skip
def test_environment_works_agree_with_quad_and_add_into_the_total(surface):
    s = summary(surface)
    gap = gap_heights(surface)
    vdw, cap = quad_works(s.turn * surface.sigma + gap.summit_offset, gap.rq, ENV)
    assert s.work_of_separation_vdw == pytest.approx(vdw, rel=QUAD_RTOL)
    assert s.work_of_separation_capillary == pytest.approx(cap, rel=QUAD_RTOL)
    total = s.work_of_separation_contact + s.work_of_separation_vdw + s.work_of_separation_capillary
    assert s.work_of_separation == total
    assert (s.rq, s.summit_offset, s.kelvin_radius) == (
        gap.rq,
        gap.summit_offset,
        ENV.kelvin_radius,
    )
    assert s.heights_source == gap.source


def test_the_turn_is_where_the_net_approach_load_vanishes():
    s = summary()
    load = gw_curves(SURFACE, MATERIAL, [s.turn], LAW, environment=ENV).load[0]
    contact = gw_curves(SURFACE, MATERIAL, [s.turn], LAW).load[0]
    assert abs(load) < 1e-9 * abs(contact)


def test_pull_off_is_the_most_tensile_net_retraction_load():
    s = summary()
    h = np.linspace(s.turn, s.turn + 12, 4001)
    net = gw_curves(SURFACE, MATERIAL, h, LAW, branch="retract", turn=s.turn, environment=ENV).load
    assert s.pull_off >= -net.min()
    # the pull-off is the minimum of a smooth curve: the 4001-point grid's minimum
    # is within second order of it (measured 6.4e-8); 1e-5 covers a grid step of 3e-3
    assert s.pull_off == pytest.approx(-net.min(), rel=1e-5)
    assert s.pull_off > summary(env=None).pull_off  # the attraction adds to the pull-off


def test_capillary_work_rises_with_rh_and_stays_below_the_ceiling():
    ceiling = 2 * ENV.surface_tension * math.cos(ENV.contact_angle)
    works = [summary(env=dataclasses.replace(ENV, rh=rh)).work_of_separation_capillary
             for rh in (0.2, 0.5, 0.8, 0.95, 0.99)]  # fmt: skip
    assert np.all(np.diff(works) > 0), works
    assert max(works) < ceiling


def test_vdw_work_falls_with_roughness_and_stays_below_the_flat_limit():
    flat = ENV.hamaker / (12 * math.pi * ENV.cutoff**2)
    works = []
    for scale in (1, 2, 4, 8):
        surface = dataclasses.replace(SURFACE, sigma=SURFACE.sigma * scale, rq=SURFACE.rq * scale,
                                      summit_offset=SURFACE.summit_offset * scale)  # fmt: skip
        works.append(summary(surface, dataclasses.replace(ENV, rh=0.0)).work_of_separation_vdw)
    assert np.all(np.diff(works) < 0), works
    assert works[0] < flat


def test_without_environment_the_new_fields_are_none():
    dry = summary(env=None)
    assert dry.work_of_separation_vdw is None and dry.kelvin_radius is None and dry.rq is None

"""On an ingested map the environment covers the map's own gap field once.

Specification (docs/physics.md, section 'The environment covers the surface once'): an
ingested surface carries its map's height histogram; the whole surface's attraction at a
separation h is the proximity model over those heights, and it must agree with the same local
laws summed pixel by pixel over the map's own gaps g = D − z (D = hσ + y_s). The histogram
is piecewise constant, so the two differ by at most what each bin can move: the bound used
here is computed from the bins, not chosen.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from mcsim.physics.environment import Environment
from mcsim.physics.surfaceenvironment import environment_curves, environment_works
from mcsim.studies.maps.ingest import ingest_file
from mcsim.topography.maps import LEVELS
from mcsim.topography.readers import read_height_map
from mcsim.topography.summits import level

SCAN = Path(__file__).resolve().parents[2] / "examples" / "scan.npy"
A, D0 = 1.6e-19, 0.2e-9
HUMID = Environment(hamaker=A, cutoff=D0, rh=0.95)


@pytest.fixture(scope="module")
def scan():
    """The ingested surface and its levelled pixels about the mean plane, m."""
    result = ingest_file(SCAN, unit="m", pixel_size=10e-9)
    heights = read_height_map(SCAN, unit="m", pixel_size=10e-9).heights
    levelled = level(heights, LEVELS[result.level])
    pixels = levelled[np.isfinite(levelled)]
    return result.surface, pixels - pixels.mean()


def bin_bound(surface, D, f):
    """Largest difference between the pixel mean of f(D − z) and its integral against the
    map's piecewise-constant height density: Σ over bins of the bin's mass times the range
    of f over the bin (f monotone in z on each side of its kinks)."""
    shape = surface.map_heights
    edges = np.asarray(shape.edges) * surface.rq
    mass = np.asarray(shape.densities) * np.diff(np.asarray(shape.edges))
    z = np.linspace(edges[:-1], edges[1:], 65)  # dense inside each bin
    values = f(D - z)
    return float(np.sum(mass * (values.max(axis=0) - values.min(axis=0))))


@pytest.mark.parametrize("h", [-1.0, 0.0, 1.5, 3.0])
def test_the_wetted_area_and_the_van_der_waals_pull_are_the_maps_own(scan, h):
    surface, z = scan
    D = h * surface.sigma + surface.summit_offset
    got = environment_curves(np.float64(h), surface, HUMID)
    g_k = HUMID.condensation_gap

    def wet(g):  # menisci between the adsorbed films: wet floor f = max(D0, 2t)
        return ((g >= HUMID.wet_floor) & (g < g_k)) * 1.0

    def vdw(g):
        with np.errstate(divide="ignore"):
            return np.where(g >= D0, A / (6 * math.pi * np.maximum(g, D0) ** 3), 0.0)

    wetted = HUMID.laplace_pressure * np.mean(wet(D - z))
    bound = HUMID.laplace_pressure * bin_bound(surface, D, wet) + 1e-12 * wetted
    assert abs(got["capillary"] - wetted) <= bound
    pull = np.mean(vdw(D - z))
    assert abs(got["vdw"] - pull) <= bin_bound(surface, D, vdw) + 1e-12 * pull


def test_at_rh_near_one_the_map_is_wetted_wherever_its_gap_is_below_g_k(scan):
    surface, z = scan
    env = Environment(cutoff=D0, rh=0.999)
    for h in (0.0, 2.0):
        D = h * surface.sigma + surface.summit_offset
        wetted = environment_curves(np.float64(h), surface, env)["capillary"] / env.laplace_pressure
        contact = np.mean(D - z < env.wet_floor)  # in contact or pressed films
        below = np.mean(D - z < env.condensation_gap)
        mass = np.asarray(surface.map_heights.densities) * np.diff(surface.map_heights.edges)
        assert abs(contact + wetted - below) <= 2 * mass.max() + 1e-12


def test_the_capillary_work_of_the_map_never_passes_two_gamma(scan):
    surface, _ = scan
    works = environment_works(np.linspace(-4.0, 6.0, 21), surface, HUMID)["capillary"]
    assert works.max() <= 2 * HUMID.surface_tension * (1 + 1e-12)

"""The seed law set's numbers are frozen: bit-identical to mcsim 0.1.

``tests/data/seed_golden.npz`` was written by ``tests/make_seed_golden.py`` from mcsim 0.1
(checked equal to a run of the 0.1 commit itself). Any change to the kernel, the
sampler, the quadrature or the statistics that moves a single bit of the paper's law set
fails here.
"""

from pathlib import Path

import numpy as np
import pytest
from make_seed_golden import cases

GOLDEN = np.load(Path(__file__).parents[1] / "data" / "seed_golden.npz")


@pytest.fixture(scope="module")
def current():
    return cases()


@pytest.mark.parametrize("key", sorted(GOLDEN))
def test_seed_numbers_are_bit_identical_to_0_1(current, key):
    np.testing.assert_array_equal(current[key], GOLDEN[key], strict=True)

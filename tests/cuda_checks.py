"""Checks of the GPU path (mcsim.engine.cuda), run in a process of their own.

``python tests/cuda_checks.py`` prints one JSON object. tests/test_cuda.py runs it
under numba's CUDA simulator (``NUMBA_ENABLE_CUDASIM=1``, small populations) and, where
a GPU is available, on the GPU: the simulator must be switched on before numba.cuda
is first imported, hence the separate process.
"""

from __future__ import annotations

import dataclasses
import json
import os
import sys

import numpy as np
from lawset_toy import TOY

from mcsim.engine import cuda as mc
from mcsim.engine.kernels import block_sums_numpy, sum_columns
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.environment import Environment
from mcsim.physics.laws import LAW_SETS
from mcsim.physics.surfaceenvironment import with_environment
from mcsim.topography.empirical import Empirical

SURFACE = SURFACES["smooth"]
#: Silicon with the optional fields some law sets require.
MATERIAL = dataclasses.replace(MATERIALS["silicon"], z0=3e-10, tau=1e8)


#: Humid air: the jkr law set with the environment's caps (per-summit van der Waals, menisci).
HUMID = Environment(hamaker=1.6e-19, cutoff=0.2e-9, rh=0.7)


def law_sets() -> dict:
    """Every registered law set, the toy, and jkr with the environment's caps, by name."""
    humid = with_environment(LAW_SETS["jkr"], HUMID)
    return {**LAW_SETS, TOY.name: TOY, "jkr+environment": humid}


def relative_error(got: np.ndarray, ref: np.ndarray) -> float:
    """Largest |got − ref| / |ref| (|got| where ref is 0)."""
    scale = np.where(ref != 0, np.abs(ref), 1.0)
    return float(np.max(np.abs(got - ref) / scale))


def block_sums_against_numpy(n: int) -> dict:
    """GPU block sums against block_sums_numpy on the same heights, every law set and
    the toy (tests/lawset_toy.py: helpers calling helpers, a table), every branch
    (retraction: turned at the lowest row)."""
    rng = np.random.default_rng(12)
    z = rng.standard_normal(n) * SURFACE.sigma
    d = np.array([2.0, -0.5, 1.0, 0.25, 3.0]) * SURFACE.sigma  # any order
    out = {}
    for name, law in law_sets().items():
        args = law.arguments(SURFACE, MATERIAL)
        edges = law.edges_for(SURFACE, MATERIAL)
        for branch in ("approach", "retract") if law.retract else ("approach",):
            turn = None if branch == "approach" else np.full(d.size, d.min())
            got = mc.block_sums_cuda(z, d, law, args, d_turn=turn, edges=edges)
            ref = block_sums_numpy(z, d, law, args, d_turn=turn, edges=edges)
            out[f"{name}/{branch}"] = {
                "error": relative_error(got, ref),
                "n_contact": got[:, 0].tolist(),
                "ref_n_contact": ref[:, 0].tolist(),
            }
    return out


def patch(heights, sizes, *, entropy=7, launch_blocks=mc.LAUNCH_BLOCKS, grid=None, s_min=-0.5,
          h=(-0.5, 0.0, 1.0, 2.0)):  # fmt: skip
    law = LAW_SETS["seed"]
    parts = mc.patch_block_sums_cuda(
        law=law, args=law.arguments(SURFACE, MATERIAL), heights=heights, sigma=SURFACE.sigma,
        s_min=s_min, entropy=entropy, realization=1, block_sizes=sizes, first_block=3,
        d=np.asarray(h) * SURFACE.sigma, launch_blocks=launch_blocks, grid=grid,
    )  # fmt: skip
    return np.concatenate(list(parts))


def rows_split(sizes: list[int]) -> bool:
    """More rows than one group of the kernel's reduction holds, in one launch or split
    between two: bit-identical sums (the groups' barriers change no order)."""
    h = np.linspace(2.0, -0.5, 2 * mc.group_rows(len(sum_columns(LAW_SETS["seed"]))) + 3)
    whole = patch(SURFACE.heights, sizes[:1], h=h)
    cut = h.size // 3
    parts = np.concatenate(
        [
            patch(SURFACE.heights, sizes[:1], h=h[:cut]),
            patch(SURFACE.heights, sizes[:1], h=h[cut:]),
        ],
        axis=1,
    )
    return bool(np.array_equal(whole, parts))


def sampling(sizes: list[int]) -> dict:
    """Reproducibility across launches and grids, and the contact counts against the
    exact tail probabilities (z-scores) for Gaussian and histogram heights."""
    gauss = SURFACE.heights
    rng = np.random.default_rng(3)
    hist = Empirical.from_samples(rng.gamma(4.0, size=20000), bins=40)
    out = {}
    for label, heights in (("gaussian", gauss), ("empirical", hist)):
        a = patch(heights, sizes)
        b = patch(heights, sizes, launch_blocks=1, grid=1)
        c = patch(heights, sizes[:1], entropy=8)
        n = a[:, :, 0].sum(axis=0)
        total = sum(sizes)
        s_min = -0.5
        p = np.array([heights.sf(h) for h in (-0.5, 0.0, 1.0, 2.0)]) / heights.sf(s_min)
        z = (n - total * p) / np.sqrt(total * p * (1 - p) + 1e-300)
        out[label] = {
            "identical_across_launches": bool(np.array_equal(a, b)),
            "other_seed_differs": not np.array_equal(a[:1], c),
            "z_scores": z.tolist(),
            "all_contact_at_s_min": bool(n[0] == total),
        }
    return out


def _equal(x, y) -> bool:
    x, y = np.asarray(x), np.asarray(y)
    return np.array_equal(x, y, equal_nan=x.dtype.kind == "f" and y.dtype.kind == "f")


def simulated_runs(folder: str) -> dict:
    """``simulate(device="cuda")`` twice with the same seed (other chunk sizes): the run
    files' datasets, the device they record, and the z-scores against the GW curves."""
    import h5py

    from mcsim.studies.simulation import simulate

    kw = dict(realizations=2, seed=3, count="fixed", device="cuda", overwrite=True)
    area = 900 / SURFACE.eta
    run = simulate(SURFACE, MATERIAL, [0.0, 1.0, 2.0], area, out=f"{folder}/a.h5", **kw)
    z = run.compare()["z"].to_numpy()
    simulate(SURFACE, MATERIAL, [0.0, 1.0, 2.0], area, out=f"{folder}/b.h5", chunk_size=1, **kw)
    with h5py.File(f"{folder}/a.h5") as a, h5py.File(f"{folder}/b.h5") as b:
        names = []
        a.visit(lambda n: names.append(n) if isinstance(a[n], h5py.Dataset) else None)
        same = all(_equal(a[n][()], b[n][()]) for n in names)
        a_device, n_datasets = a.attrs["device"], len(names)
    humid = simulate(SURFACE, MATERIAL, [0.0, 1.0, 2.0], area, law="jkr", environment=HUMID,
                     out=f"{folder}/humid.h5", **kw).compare()  # fmt: skip
    caps = humid[humid.quantity.isin(["vdw", "capillary"])]["z"].to_numpy()
    return {"device": str(a_device), "identical": same, "datasets": n_datasets,
            "z": [float(v) for v in z if np.isfinite(v)],
            "z_caps": [float(v) for v in caps if np.isfinite(v)]}  # fmt: skip


def one_core() -> None:
    """Keep this process on one core, at low priority. The simulator runs each CUDA
    thread as a Python thread; handing the GIL among 256 of them across cores takes
    twice the time (and more than one core) that it takes on one. tests/conftest.py
    runs these checks beside the other tests: they take a core left idle and give way
    to the tests on a busy one."""
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {max(os.sched_getaffinity(0))})
    if hasattr(os, "nice"):
        os.nice(10)


def main() -> None:
    if mc.simulating():
        one_core()
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 600
    sizes = [int(s) for s in sys.argv[2].split(",")] if len(sys.argv) > 2 else [500, 200]
    result = {
        "simulator": mc.simulating(),
        "block_sums": block_sums_against_numpy(n),
        "sampling": sampling(sizes),
        "rows_split_identical": rows_split(sizes),
    }
    if len(sys.argv) > 3:
        result["simulate"] = simulated_runs(sys.argv[3])
    print(json.dumps(result))


if __name__ == "__main__":
    main()

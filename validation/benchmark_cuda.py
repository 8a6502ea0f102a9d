"""Speed of the GPU backend (``mcsim.engine.cuda``) against a bare CUDA kernel and the CPU engine.

Seed law set, smooth surface, silicon, one patch of N summits (fixed count), the sweep
h = d/σ = 4 … −1 (51 values), heights drawn above h_min = −1. Cases, in one process:

* **mcsim cuda, kernel**: the launches of :func:`mcsim.engine.cuda.patch_block_sums_cuda`
  (sampling on the GPU fused into the kernel, per-block sums copied back), timed
  between synchronisations, compilation excluded (a warm-up run first);
* **mcsim cuda, end to end**: the summit counts drawn (:func:`mcsim.engine.montecarlo.plan_patch`),
  the launches, and the per-block sums added on the host in block order, as the engine
  does;
* **bare kernel**: the ceiling, a plain numba-cuda kernel written for the seed alone:
  the same Philox heights, the three laws written inline, warp-shuffle reductions and
  atomic additions (not reproducible), nothing copied back but the 51 × 10 sums;
* **CPU engine**: ``run_sums`` on all cores at N_cpu summits.

A pair is a (summit, separation) with the summit in contact (Σ n_contact). Run:
``python validation/benchmark_cuda.py [N] [N_cpu]`` (defaults 1e9 and 2e7) or
``python validation/benchmark.py --device cuda``; prints a markdown table.

Criteria (PASS/FAIL lines, exit status 1 on a FAIL): the bare kernel's contact counts equal
mcsim's (the same Philox heights), and the same seed twice gives bit-identical sums.
Speeds are measured, not judged.
"""

from __future__ import annotations

import math
import sys
import time

import numpy as np
from numba import cuda
from reporting import Checks

from mcsim.engine import cuda as mc
from mcsim.engine.cudaheights import philox_key
from mcsim.engine.montecarlo import BLOCK, default_workers, plan_patch, run_sums
from mcsim.engine.spec import MonteCarloSpec
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.laws import SEED

SURFACE, MATERIAL = SURFACES["smooth"], MATERIALS["silicon"]
H = np.linspace(4.0, -1.0, 51)


def spec_for(n: int) -> MonteCarloSpec:
    return MonteCarloSpec(SURFACE, MATERIAL, H, area=n / SURFACE.eta, realizations=1,
                          entropy=2026, count="fixed")  # fmt: skip


def gpu_end_to_end(spec: MonteCarloSpec):
    """Sums of realization 0 as the engine would add them; returns (sums, kernel seconds)."""
    plan = plan_patch(spec, 0)
    sizes = [min(BLOCK, plan.n_above - b * BLOCK) for b in range(-(-plan.n_above // BLOCK))]
    sums = np.zeros((spec.h.size, 10))
    kernel = 0.0
    parts = mc.patch_block_sums_cuda(
        law=SEED, args=SEED.arguments(SURFACE, MATERIAL), heights=SURFACE.heights,
        sigma=SURFACE.sigma, s_min=float(spec.h.min()), entropy=spec.entropy, realization=0,
        block_sizes=sizes, first_block=0, d=spec.d,
    )  # fmt: skip
    while True:
        t = time.perf_counter()
        part = next(parts, None)
        kernel += time.perf_counter() - t
        if part is None:
            break
        for block in part:  # in block order
            sums += block
    return sums, kernel


_M = 51


def bare_kernel():
    """The ceiling: seed laws inline, Philox heights, shuffles and atomics."""
    ns = mc._namespace(SEED)
    height = ns["_height"]
    per = mc.PER_THREAD

    @cuda.jit
    def bare(n, k0, k1, tail, sigma, d, out, R, K, G, gamma):
        tid = cuda.threadIdx.x
        lane = tid % 32
        base = cuda.blockIdx.x * mc.TILE
        zk = cuda.local.array(per, np.float64)
        cum = cuda.local.array(1, np.float64)
        for k in range(per):
            i = base + k * mc.THREADS + tid
            if i < n:
                zk[k] = sigma * height(i % BLOCK, i // BLOCK, k0, k1, 0, tail, cum, cum, cum)
            else:
                zk[k] = -math.inf
        c = 3.0 * math.pi * gamma * R
        a = math.pi * gamma * R
        sr = K * math.sqrt(R)
        g4 = 4.0 * math.sqrt(G / K)
        for j in range(d.size):
            dj = d[j]
            nc = sp = sf = st = spp = sff = stt = spf = spt = sft = 0.0
            for k in range(per):
                delta = zk[k] - dj
                if delta > 0:
                    p = sr * delta * math.sqrt(delta)
                    f = c + math.sqrt(2.0 * c * p + c * c)
                    t = g4 * math.sqrt(2.0 * a * p + 3.0 * a * a)
                    nc += 1.0
                    sp += p
                    sf += f
                    st += t
                    spp += p * p
                    sff += f * f
                    stt += t * t
                    spf += p * f
                    spt += p * t
                    sft += f * t
            off = 16
            while off > 0:
                nc += cuda.shfl_down_sync(0xFFFFFFFF, nc, off)
                sp += cuda.shfl_down_sync(0xFFFFFFFF, sp, off)
                sf += cuda.shfl_down_sync(0xFFFFFFFF, sf, off)
                st += cuda.shfl_down_sync(0xFFFFFFFF, st, off)
                spp += cuda.shfl_down_sync(0xFFFFFFFF, spp, off)
                sff += cuda.shfl_down_sync(0xFFFFFFFF, sff, off)
                stt += cuda.shfl_down_sync(0xFFFFFFFF, stt, off)
                spf += cuda.shfl_down_sync(0xFFFFFFFF, spf, off)
                spt += cuda.shfl_down_sync(0xFFFFFFFF, spt, off)
                sft += cuda.shfl_down_sync(0xFFFFFFFF, sft, off)
                off //= 2
            if lane == 0 and nc > 0:
                cuda.atomic.add(out, (j, 0), nc)
                cuda.atomic.add(out, (j, 1), sp)
                cuda.atomic.add(out, (j, 2), sf)
                cuda.atomic.add(out, (j, 3), st)
                cuda.atomic.add(out, (j, 4), spp)
                cuda.atomic.add(out, (j, 5), sff)
                cuda.atomic.add(out, (j, 6), stt)
                cuda.atomic.add(out, (j, 7), spf)
                cuda.atomic.add(out, (j, 8), spt)
                cuda.atomic.add(out, (j, 9), sft)

    return bare


def run_bare(bare, spec: MonteCarloSpec, n_above: int):
    tail = float(SURFACE.heights.sf(spec.h.min()))
    d = cuda.to_device(spec.d)
    out = cuda.to_device(np.zeros((spec.h.size, 10)))
    args = SEED.arguments(SURFACE, MATERIAL)
    R, K = args[0]
    G = args[2][2]
    gamma = args[1][2]
    k0, k1 = philox_key(spec.entropy, 0)
    cuda.synchronize()
    t = time.perf_counter()
    bare[-(-n_above // mc.TILE), mc.THREADS](
        np.int64(n_above), np.uint64(k0), np.uint64(k1), tail, SURFACE.sigma, d, out, R, K, G, gamma
    )
    cuda.synchronize()
    return out.copy_to_host(), time.perf_counter() - t


def main(n: int = 10**9, n_cpu: int = 2 * 10**7) -> None:
    device = cuda.get_current_device()
    print(f"GPU: {device.name.decode() if isinstance(device.name, bytes) else device.name}")
    spec = spec_for(n)
    warm = spec_for(10**6)
    t = time.perf_counter()
    gpu_end_to_end(warm)
    print(f"compile + first small run: {time.perf_counter() - t:.1f} s")
    rows = []
    best = None
    for _ in range(3):
        t = time.perf_counter()
        sums, kernel = gpu_end_to_end(spec)
        e2e = time.perf_counter() - t
        if best is None or e2e < best[1]:
            best = (sums, e2e, kernel)
    sums, e2e, kernel = best
    pairs = float(sums[:, 0].sum())
    rows.append(("mcsim cuda, kernel (sampling fused)", n, kernel, pairs))
    rows.append(("mcsim cuda, end to end", n, e2e, pairs))
    bare = bare_kernel()
    n_above = plan_patch(spec, 0).n_above
    run_bare(bare, warm, plan_patch(warm, 0).n_above)
    bare_best = min((run_bare(bare, spec, n_above) for _ in range(3)), key=lambda r: r[1])
    rows.append(("bare kernel (ceiling)", n, bare_best[1], float(bare_best[0][:, 0].sum())))
    same = np.array_equal(bare_best[0][:, 0], sums[:, 0])
    cpu_spec = spec_for(n_cpu)
    run_sums(spec_for(10**5))
    t = time.perf_counter()
    cpu = run_sums(cpu_spec)
    cpu_s = time.perf_counter() - t
    rows.append((f"CPU engine, {default_workers()} workers", n_cpu, cpu_s,
                 float(cpu.sums[0, :, 0].sum())))  # fmt: skip
    print("| case | N | s | contacting pairs/s |\n| --- | --- | --- | --- |")
    for label, size, seconds, p in rows:
        print(f"| {label} | {size:.3g} | {seconds:.3f} | {p / seconds:.3g} |")
    print(f"kernel / bare = {bare_best[1] / kernel:.2f}")
    again, _ = gpu_end_to_end(spec)
    checks = Checks()
    checks.holds(
        "bare kernel's contact counts equal mcsim's", same, "equal" if same else "DIFFERENT"
    )
    identical = np.array_equal(again, sums)
    checks.holds(
        "same seed twice bit-identical", identical, "identical" if identical else "DIFFERENT"
    )
    print("\n".join(checks.summary()))
    checks.exit()


if __name__ == "__main__":
    main(*(int(float(a)) for a in sys.argv[1:3]))

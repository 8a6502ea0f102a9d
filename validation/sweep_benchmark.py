"""Speed of parameter sweeps (issue 11 §3): analytic points per second, Dask scaling.

Cases, each in its own Python process (``--case``) so that its peak resident memory
(``ru_maxrss``) is its own:

* **analytic**: ``mcsim.sweep`` of the smooth surface on silicon over σ (log grid) × w
  (linear grid), 40 × 5 points by default, with the ``jkr`` and ``dmt`` law sets: at
  each point the approach curves at 51 separations, the regime numbers and the adhesion
  summary (zero-load rest, pull-off, work of separation). Serial (``workers=1``) and
  on threads (``workers=`` all cores). On the rough side of the grid the surfaces rest
  apart (no tensile approach load): those points are cheaper (pull-off 0 without a
  retraction) and count as points, as in every real sweep.
* **Monte Carlo**: σ = 0.5–3 nm × w = 0.5–1 J/m² (every point in contact at rest) with
  ``mc=True`` (``dmt``, one Monte Carlo run of 20 patches of 1000 µm², ``--quick``, or
  10⁴ µm² per point) on a local Dask cluster of N = 1
  … all cores worker processes (``LocalCluster(processes=True,
  threads_per_worker=1)``), after a two-point warm-up that loads the compiled kernels
  on every worker; the cluster's start-up is not timed. The results of every N are
  checked bit for bit against N = 1 (every variable, NaN where NaN). Peak RSS: the
  client process plus the sum of the workers' ``ru_maxrss``.

Timings are the best of ``--repeats`` sweeps (in memory: no file written). Run:
``python validation/sweep_benchmark.py`` (several minutes on 2 cores) or ``--quick`` (10 × 2
analytic points, 8 Monte Carlo points, about a minute). Prints a markdown table and
writes it to ``validation/out/sweep_benchmark.md``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
import warnings

import numpy as np
from benchmark import MIB, best_of, machine, peak_rss
from reporting import parser, provenance

from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.adhesion import RegimeWarning
from mcsim.studies.sweeps import sweep

SURFACE, MATERIAL = SURFACES["smooth"], MATERIALS["silicon"]


def grid(n_sigma: int, n_gamma: int) -> dict[str, str]:
    """The analytic grid: σ log-spaced over 0.3–20 nm, w over 0.05–1 J/m²."""
    return {"sigma": f"0.3nm:20nm:{n_sigma}:log", "gamma": f"0.05:1:{n_gamma}"}


def mc_grid(n_sigma: int, n_gamma: int) -> dict[str, str]:
    """The Monte Carlo grid: σ over 0.5–3 nm (log), w over 0.5–1 J/m², where every point
    rests in contact at zero load (so every point runs its Monte Carlo patches)."""
    return {"sigma": f"0.5nm:3nm:{n_sigma}:log", "gamma": f"0.5:1:{n_gamma}"}


def run_analytic(law: str, workers: int, n_sigma: int, n_gamma: int, repeats: int) -> dict:
    """Best wall time of an analytic sweep in this process."""
    vary = grid(n_sigma, n_gamma)
    sweep(SURFACE, MATERIAL, {"sigma": "1nm,2nm"}, law=law, workers=1)  # warm-up (imports)
    wall, result = best_of(
        repeats, lambda: sweep(SURFACE, MATERIAL, vary, law=law, workers=workers)
    )
    return {"points": int(np.prod(result.shape)), "failed": len(result.failed), "wall": wall,
            "rss": peak_rss()}  # fmt: skip


def _worker_rss() -> int:
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def run_dask(n_workers: int, n_sigma: int, n_gamma: int, area: str, realizations: int,
             repeats: int, seed: int, out: str) -> dict:  # fmt: skip
    """Best wall time of a Monte Carlo sweep on ``n_workers`` local Dask processes;
    the result's variables are saved to ``out`` (.npz) for the bit-identity check."""
    from distributed import Client, LocalCluster

    vary = mc_grid(n_sigma, n_gamma)
    options = {"law": "dmt", "mc": True, "area": area, "realizations": realizations, "seed": seed}
    with (
        LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True,
                     dashboard_address=None) as cluster,
        Client(cluster) as client,
    ):  # fmt: skip
        sweep(SURFACE, MATERIAL, {"sigma": "1nm,2nm"}, scheduler=client, **options)  # warm-up
        wall, result = best_of(
            repeats, lambda: sweep(SURFACE, MATERIAL, vary, scheduler=client, **options)
        )
        rss = peak_rss() + sum(client.run(_worker_rss).values())
    arrays = {
        k: np.asarray(v, dtype=float)
        for k, v in result.data.items()
        if np.asarray(v).dtype.kind == "f"
    }
    np.savez(out, **arrays, error=np.asarray(result.data["error"], dtype=str))
    return {
        "points": int(np.prod(result.shape)),
        "failed": len(result.failed),
        "wall": wall,
        "rss": rss,
    }


def spawn(args: argparse.Namespace, case: list[str]) -> dict:
    """Run one case in a fresh process; return its numbers."""
    cmd = [sys.executable, __file__, "--case", *case, "--repeats", str(args.repeats)]
    cmd += ["--seed", str(args.seed)] + (["--quick"] if args.quick else [])
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f"case {case} failed:\n{proc.stderr}")
    result = json.loads(proc.stdout.strip().splitlines()[-1])
    print(f"  {' '.join(case[:2]):14s} done in {time.perf_counter() - t0:5.1f} s", flush=True)
    return result


def identical(a: str, b: str) -> bool:
    """Whether two saved sweeps hold the same bits in every variable (NaN equal to NaN)."""
    x, y = np.load(a), np.load(b)
    return set(x) == set(y) and all(
        np.array_equal(x[k], y[k], equal_nan=x[k].dtype.kind == "f") for k in x
    )


def sizes(quick: bool) -> dict:
    if quick:
        return {"analytic": (10, 2), "mc": (4, 2), "area": "1000um^2", "realizations": 20}
    return {"analytic": (40, 5), "mc": (8, 2), "area": "10000um^2", "realizations": 20}


def main() -> None:
    p = parser(__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=1, help="timing repeats (default %(default)s)")
    p.add_argument("--case", nargs="+", help=argparse.SUPPRESS)
    args = p.parse_args()
    size = sizes(args.quick)
    warnings.simplefilter("ignore", RegimeWarning)
    if args.case:
        kind, *rest = args.case
        if kind == "analytic":
            out = run_analytic(rest[0], int(rest[1]), *size["analytic"], args.repeats)
        else:
            out = run_dask(int(rest[0]), *size["mc"], size["area"], size["realizations"],
                           args.repeats, args.seed, rest[1])  # fmt: skip
        print(json.dumps(out))
        return
    args.out.mkdir(parents=True, exist_ok=True)
    info = machine()
    cores = info["cores"]
    print(f"machine: {info['cpu']}, {cores} cores, load {info['load']}", flush=True)
    res = {}
    for law in ("jkr", "dmt"):
        for workers in sorted({1, cores}):
            res[("analytic", law, workers)] = spawn(args, ["analytic", law, str(workers)])
    files = {}
    for n in sorted({1, 2, cores}):
        files[n] = str(args.out / f"sweep_benchmark_dask{n}.npz")
        res[("dask", n)] = spawn(args, ["dask", str(n), files[n]])
    same = {n: identical(files[1], f) for n, f in files.items()}
    for f in files.values():
        os.unlink(f)
    lines = report(res, same, info, args, size)
    text = "\n".join(lines)
    print()
    print(text)
    prov = provenance(args)
    header = "".join(f"<!-- {k}: {v} -->\n" for k, v in prov.items())
    path = args.out / "sweep_benchmark.md"
    path.write_text(header + text + "\n")
    print(f"wrote {path}")


def report(res: dict, same: dict, info: dict, args, size: dict) -> list[str]:
    a, m = size["analytic"], size["mc"]
    lines = [
        f"Sweep benchmark: smooth surface on silicon, σ = 0.3–20 nm (log) × w = 0.05–1 J/m², "
        f"51 separations; analytic {a[0]} × {a[1]} points (curves, regime numbers, adhesion "
        f"summary); Monte Carlo σ = 0.5–3 nm × w = 0.5–1 J/m², {m[0]} × {m[1]} points, dmt, "
        f"{size['realizations']} patches of {size['area']} per point. Wall = best of "
        f"{args.repeats}, in memory, start-up excluded.",
        "",
        "| case | points | failed | wall (s) | points/s | speed-up | peak RSS (MiB) | bit-identical |",
        "|---|---:|---:|---:|---:|---:|---:|---|",
    ]
    for law in ("jkr", "dmt"):
        base = res[("analytic", law, 1)]["wall"]
        for (kind, *key), r in res.items():
            if kind != "analytic" or key[0] != law:
                continue
            lines.append(
                f"| analytic {law}, {key[1]} thread(s) | {r['points']} | {r['failed']} | "
                f"{r['wall']:.2f} | {r['points'] / r['wall']:.1f} | {base / r['wall']:.2f}× | "
                f"{r['rss'] / MIB:.0f} | – |"
            )
    base = res[("dask", 1)]["wall"]
    for (kind, *key), r in res.items():
        if kind != "dask":
            continue
        n = key[0]
        lines.append(
            f"| Monte Carlo, Dask {n} worker process(es) | {r['points']} | {r['failed']} | "
            f"{r['wall']:.2f} | {r['points'] / r['wall']:.2f} | {base / r['wall']:.2f}× | "
            f"{r['rss'] / MIB:.0f} (client + workers) | {'yes' if same[n] else 'NO'} (vs 1 worker) |"
        )
    lines += [
        "",
        f"Machine: {info['cpu']}, {info['cores']} cores, Python {info['python']}, NumPy "
        f"{info['numpy']}, numba {info['numba']}, load average {info['load'][0]:.2f} at the start.",
    ]
    return lines


if __name__ == "__main__":
    main()

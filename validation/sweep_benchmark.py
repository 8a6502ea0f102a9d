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
* **environment** (issue 22): ``mcsim.sweep`` of the intermediate surface on silicon, jkr,
  with van der Waals (A = 1.6e-19 J) and capillary condensation (water, θ = 0) over
  RH = 0.05–0.95 × σ = 1–10 nm, 40 × 50 points by default, on threads (``workers=`` all
  cores): the compiled fast path (:func:`mcsim.engine.maps.designmap.jkr_summaries` with the
  environment). The reference path (``adhesion_summary`` and ``gw_curves`` with the
  environment, :func:`mcsim.studies.sweeppoint.evaluate`) is timed on 6 points of the same
  grid, serially, for the per-point ratio. Then the same sweep as a whole ``mcsim sweep``
  process writing its file (start-up, imports and writing included): once with an empty
  kernel cache (cold: numba compiles the kernel) and once more with the cache it left (warm).
* **Monte Carlo**: σ = 0.5–3 nm × w = 0.5–1 J/m² (every point in contact at rest) with
  ``mc=True`` (``dmt``, one Monte Carlo run of 20 patches of 1000 µm², ``--quick``, or
  10⁴ µm² per point) on a local Dask cluster of N = 1
  … all cores worker processes (``LocalCluster(processes=True,
  threads_per_worker=1)``), after a two-point warm-up that loads the compiled kernels
  on every worker; the cluster's start-up is not timed. The results of every N are
  checked bit for bit against N = 1 (every variable, NaN where NaN). Peak RSS: the
  client process plus the sum of the workers' ``ru_maxrss``.

Timings are the best of ``--repeats`` sweeps (in memory: no file written), but for the
``mcsim sweep`` processes. Run: ``python validation/sweep_benchmark.py`` (several minutes on 2
cores) or ``--quick`` (10 × 2 analytic points, 8 Monte Carlo points, 8 × 10 environment
points, about a minute); ``--cases environment`` (or ``analytic``, ``mc``) runs only those.
Prints a markdown table and writes it to ``validation/out/sweep_benchmark.md``.

Criteria (PASS/FAIL lines, exit status 1 on a FAIL): no failed point in any case, and the
Monte Carlo sweep bit-identical on every number of Dask workers. Speeds are measured, not
judged (no target).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np
from benchmark import MIB, best_of, machine, peak_rss
from reporting import Checks, parser, provenance

from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.adhesion import RegimeWarning
from mcsim.physics.environment import Environment
from mcsim.studies.sweeps import sweep

SURFACE, MATERIAL = SURFACES["smooth"], MATERIALS["silicon"]
#: The environment case: surface, environment (A = 1.6e-19 J, water at RH 0.5, θ = 0) and
#: the same as ``mcsim sweep`` options.
ENV_SURFACE = SURFACES["intermediate"]
ENVIRONMENT = Environment(hamaker=1.6e-19, rh=0.5)
ENV_OPTIONS = ["--surface", "intermediate", "--law", "jkr", "--hamaker", "1.6e-19J", "--rh", "0.5"]


def grid(n_sigma: int, n_gamma: int) -> dict[str, str]:
    """The analytic grid: σ log-spaced over 0.3–20 nm, w over 0.05–1 J/m²."""
    return {"sigma": f"0.3nm:20nm:{n_sigma}:log", "gamma": f"0.05:1:{n_gamma}"}


def mc_grid(n_sigma: int, n_gamma: int) -> dict[str, str]:
    """The Monte Carlo grid: σ over 0.5–3 nm (log), w over 0.5–1 J/m², where every point
    rests in contact at zero load (so every point runs its Monte Carlo patches)."""
    return {"sigma": f"0.5nm:3nm:{n_sigma}:log", "gamma": f"0.5:1:{n_gamma}"}


def env_grid(n_rh: int, n_sigma: int) -> dict[str, str]:
    """The environment grid: RH over 0.05–0.95, σ over 1–10 nm (linear)."""
    return {"rh": f"0.05:0.95:{n_rh}", "sigma": f"1nm:10nm:{n_sigma}"}


def run_environment(workers: int, n_rh: int, n_sigma: int, repeats: int) -> dict:
    """Best wall time of the environment sweep in this process (fast path), and the
    reference path's time per point on 6 points of the grid (serial)."""
    from mcsim.studies.sweeppoint import Config, Point, evaluate

    vary = env_grid(n_rh, n_sigma)
    options = {"law": "jkr", "environment": ENVIRONMENT}
    sweep(ENV_SURFACE, MATERIAL, {"rh": "0.3,0.6"}, workers=1, **options)  # warm-up (kernel)
    cpu = time.process_time()
    wall, result = best_of(
        repeats, lambda: sweep(ENV_SURFACE, MATERIAL, vary, workers=workers, **options)
    )
    cpu = (time.process_time() - cpu) / repeats
    config = Config(h=tuple(result.coords["h"]), turn=None, mc=False, realizations=1, entropy=None)
    cases = [(rh, sigma) for rh in (0.05, 0.5, 0.95) for sigma in (1e-9, 10e-9)]
    t0, cpu0 = time.perf_counter(), time.process_time()
    for i, (rh, sigma) in enumerate(cases):
        point = Point(i, dataclasses.replace(ENV_SURFACE, sigma=sigma), MATERIAL, "jkr", None,
                      dataclasses.replace(ENVIRONMENT, rh=rh))  # fmt: skip
        assert "error" not in evaluate(point, config)
    reference = (time.perf_counter() - t0) / len(cases)
    reference_cpu = (time.process_time() - cpu0) / len(cases)
    points = int(np.prod(result.shape))
    return {"points": points, "failed": len(result.failed), "wall": wall, "cpu": cpu / points,
            "rss": peak_rss(), "reference_per_point": reference,
            "reference_cpu": reference_cpu, "workers": workers}  # fmt: skip


def time_cli(n_rh: int, n_sigma: int) -> dict:
    """Wall time of the environment sweep as whole ``mcsim sweep`` processes writing their
    file: with an empty kernel cache (cold), then with the cache it left (warm)."""
    mcsim = shutil.which("mcsim", path=str(Path(sys.executable).parent)) or "mcsim"
    vary = env_grid(n_rh, n_sigma)
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        env = os.environ | {"MCSIM_CACHE_DIR": str(Path(tmp) / "cache")}
        for kind in ("cold", "warm"):
            path = Path(tmp) / f"{kind}.h5"
            cmd = [mcsim, "sweep", *ENV_OPTIONS, *(f"--vary={k}={v}" for k, v in vary.items()),
                   "--out", str(path), "--quiet"]  # fmt: skip
            t0, cpu0 = time.perf_counter(), _children_cpu()
            subprocess.run(cmd, env=env, check=True, capture_output=True)
            out[kind] = time.perf_counter() - t0
            out[f"{kind}_cpu"] = _children_cpu() - cpu0
    return out


def _children_cpu() -> float:
    """User plus system CPU seconds of the finished child processes."""
    import resource

    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


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
        return {"analytic": (10, 2), "mc": (4, 2), "area": "1000um^2", "realizations": 20,
                "environment": (8, 10)}  # fmt: skip
    return {"analytic": (40, 5), "mc": (8, 2), "area": "10000um^2", "realizations": 20,
            "environment": (40, 50)}  # fmt: skip


def main() -> None:
    p = parser(__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=1, help="timing repeats (default %(default)s)")
    p.add_argument("--case", nargs="+", help=argparse.SUPPRESS)
    p.add_argument("--cases", nargs="+", choices=CASES, default=list(CASES),
                   help="which cases to run (default: all)")  # fmt: skip
    args = p.parse_args()
    size = sizes(args.quick)
    warnings.simplefilter("ignore", RegimeWarning)
    if args.case:
        kind, *rest = args.case
        if kind == "analytic":
            out = run_analytic(rest[0], int(rest[1]), *size["analytic"], args.repeats)
        elif kind == "environment":
            out = run_environment(int(rest[0]), *size["environment"], args.repeats)
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
    if "analytic" in args.cases:
        for law in ("jkr", "dmt"):
            for workers in sorted({1, cores}):
                res[("analytic", law, workers)] = spawn(args, ["analytic", law, str(workers)])
    if "environment" in args.cases:
        res[("environment",)] = spawn(args, ["environment", str(cores)])
        res[("environment",)]["cli"] = time_cli(*size["environment"])
    files = {}
    if "mc" in args.cases:
        for n in sorted({1, 2, cores}):
            files[n] = str(args.out / f"sweep_benchmark_dask{n}.npz")
            res[("dask", n)] = spawn(args, ["dask", str(n), files[n]])
    same = {n: identical(files[1], f) for n, f in files.items()}
    for f in files.values():
        os.unlink(f)
    checks = Checks()
    for key, r in res.items():
        checks.at_most(f"{' '.join(map(str, key))}: failed points", r["failed"], 0)
    for n, ok in same.items():
        checks.holds(f"Monte Carlo sweep on {n} Dask worker(s) bit-identical to 1", ok,
                     "identical" if ok else "DIFFERENT")  # fmt: skip
    lines = [*report(res, same, info, args, size), "", *checks.summary()]
    text = "\n".join(lines)
    print()
    print(text)
    prov = provenance(args)
    header = "".join(f"<!-- {k}: {v} -->\n" for k, v in prov.items())
    path = args.out / "sweep_benchmark.md"
    path.write_text(header + text + "\n")
    print(f"wrote {path}")
    checks.exit()


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
        if ("analytic", law, 1) not in res:
            continue
        base = res[("analytic", law, 1)]["wall"]
        for (kind, *key), r in res.items():
            if kind != "analytic" or key[0] != law:
                continue
            lines.append(
                f"| analytic {law}, {key[1]} thread(s) | {r['points']} | {r['failed']} | "
                f"{r['wall']:.2f} | {r['points'] / r['wall']:.1f} | {base / r['wall']:.2f}× | "
                f"{r['rss'] / MIB:.0f} | – |"
            )
    for (kind, *key), r in res.items():
        if kind != "dask":
            continue
        base = res[("dask", 1)]["wall"]
        n = key[0]
        lines.append(
            f"| Monte Carlo, Dask {n} worker process(es) | {r['points']} | {r['failed']} | "
            f"{r['wall']:.2f} | {r['points'] / r['wall']:.2f} | {base / r['wall']:.2f}× | "
            f"{r['rss'] / MIB:.0f} (client + workers) | {'yes' if same[n] else 'NO'} (vs 1 worker) |"
        )
    if not any(kind in ("analytic", "dask") for kind, *_ in res):
        lines = []
    if ("environment",) in res:
        lines += environment_report(res[("environment",)], size)
    lines += [
        "",
        f"Machine: {info['cpu']}, {info['cores']} cores, Python {info['python']}, NumPy "
        f"{info['numpy']}, numba {info['numba']}, load average {info['load'][0]:.2f} at the start.",
    ]
    return lines


def environment_report(r: dict, size: dict) -> list[str]:
    n_rh, n_sigma = size["environment"]
    cli = r["cli"]
    return [
        "",
        f"Environment sweep (issue 22): intermediate surface on silicon, jkr, A = 1.6e-19 J, "
        f"water (θ = 0), RH = 0.05–0.95 × σ = 1–10 nm, {n_rh} × {n_sigma} points, 51 "
        f"separations; compiled fast path on {r['workers']} threads, reference path "
        "(adhesion_summary, gw_curves) serial on 6 points of the grid. CPU = user + system "
        "seconds of the process (all threads).",
        "",
        "| case | points | failed | wall (s) | points/s | CPU per point (ms) | peak RSS (MiB) |",
        "|---|---:|---:|---:|---:|---:|---:|",
        f"| fast path, in memory | {r['points']} | {r['failed']} | {r['wall']:.2f} | "
        f"{r['points'] / r['wall']:.0f} | {1e3 * r['cpu']:.2f} | {r['rss'] / MIB:.0f} |",
        f"| reference path | 6 | 0 | {6 * r['reference_per_point']:.2f} | "
        f"{1 / r['reference_per_point']:.1f} | {1e3 * r['reference_cpu']:.0f} | – |",
        f"| `mcsim sweep` process, warm kernel cache | {r['points']} | – | {cli['warm']:.2f} | "
        f"{r['points'] / cli['warm']:.0f} | {1e3 * cli['warm_cpu'] / r['points']:.2f} | – |",
        f"| `mcsim sweep` process, cold (compiles the kernel) | {r['points']} | – | "
        f"{cli['cold']:.2f} | – | {1e3 * cli['cold_cpu'] / r['points']:.2f} | – |",
        "",
        f"Per point the fast path takes {r['reference_cpu'] / r['cpu']:.0f}× less CPU than the "
        "reference path.",
    ]


CASES = ("analytic", "environment", "mc")


if __name__ == "__main__":
    main()

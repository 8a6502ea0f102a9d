"""``mcsim show``: a human summary of a run or sweep file."""

from __future__ import annotations

import json

from mcsim.cli.display import describe_inputs, environment_notes


def run(args) -> int:
    import numpy as np

    from mcsim.physics.adhesion import regime_warnings
    from mcsim.store.runfile import read_run, read_state
    from mcsim.store.sweepfile import is_sweep_file, read_sweep

    if is_sweep_file(args.run):
        result = read_sweep(args.run)
        print(result)
        a = result.attrs
        print(
            f"  created  {a.get('created')} by mcsim {a.get('mcsim_version')}\n  command  {a.get('command')}"
        )
        for inputs, error in result.failed[:5]:
            print(f"  failed   {inputs}: {error}")
        _sweep_results(result)
        return 0
    state, a = read_state(args.run)
    spec = state.spec
    print(f"run file      {args.run}")
    status = "complete" if a["complete"] else (
        f"INCOMPLETE: {int(state.done_blocks.sum())} of {int(state.n_blocks.sum())} blocks done, "
        f"{int(np.sum(state.done_blocks == state.n_blocks))} of {spec.realizations} realizations complete; "
        "finish it with the same `mcsim simulate` command plus --resume"
    )  # fmt: skip
    print(f"status        {status}")
    print(
        f"created       {a.get('created')} by mcsim {a.get('mcsim_version')} (schema {a.get('schema_version')})"
    )
    print(f"command       {a.get('command')}")
    print(f"seed entropy  {spec.entropy}")
    for line in describe_inputs(spec.surface, spec.material):
        print(f"input         {line}")
    if "counter_surface" in a:  # simulate --counter-surface: the parts of the surface run
        given, counter = json.loads(a["surface_as_given"]), json.loads(a["counter_surface"])
        print(f"counter       the surface run is the gap's: {given['name'] or '(file)'} (sigma = "
              f"{given['sigma'] * 1e9:.4g} nm) facing {counter['name'] or '(file)'} (sigma = "
              f"{counter['sigma'] * 1e9:.4g} nm), correlation {float(a['correlation']):g}")  # fmt: skip
    print(f"law set       {spec.law}" + (f" (cycle: approach, then retraction from h = {spec.turn:g})"
                                          if spec.cycle else ""))  # fmt: skip
    for warning in regime_warnings(spec.surface, spec.material, spec.law):
        print(f"regime        warning: {warning}")
    for line in environment_notes(spec.surface, spec.environment, material=spec.material):
        print(f"environment   {line.removeprefix('environment: ').removeprefix('environment ')}")
    preload = a.get("preload")
    if preload is not None and np.isfinite(preload):  # force control of each pad
        print(f"preload       {preload:g} Pa: each pad pressed until its own net load reaches P A")
    print(f"device        {spec.device}")
    print(
        f"patch         A = {spec.area * 1e12:.6g} um^2, N ~ {spec.count}, E[N] = {spec.expected_summits:.6g}"
    )
    print(f"realizations  {spec.realizations}: N = {', '.join(str(int(n)) for n in state.n_summits[:8])}"
          f"{' ...' if spec.realizations > 8 else ''}")  # fmt: skip
    print(f"separations   {spec.h.size}: h = {spec.h.min():g} .. {spec.h.max():g}")
    if "load_control" in a:  # simulate --pressure/--load: the pressures those separations balance
        p = json.loads(a["load_control"])["pressure"]
        print(f"load control  nominal pressure p = {min(p):g} .. {max(p):g} Pa ({len(p)} values)")
    if not np.any(state.done_blocks == state.n_blocks):
        return 0
    rows = read_run(args.run, allow_incomplete=True).compare_rows()  # compare(), without pandas
    z = np.array([row["z"] for row in rows], dtype=float)
    finite = z[np.isfinite(z)]
    if finite.size:
        part = "" if a["complete"] else " (completed realizations only)"
        print(f"vs GW         max |z| = {np.max(np.abs(finite)):.2f} over {finite.size} (h, quantity) pairs "
              f"with enough contacts{part}; details: mcsim compare {args.run}")  # fmt: skip
    return 0


#: Outputs of a sweep that ``mcsim show`` prints per point, in this order, where the file
#: has them (the pads' p_stick and p_slip with their 95 % intervals); the rest: ``mcsim plot``
#: or :meth:`~mcsim.store.sweepfile.Sweep.table`.
SHOWN = ("law_used", "pull_off_pressure", "work_of_separation", "hysteresis", "pull_off_mean",
         "pull_off_std", "p_stick", "p_stick_model", "static_friction_mean", "mu_static_mean",
         "p_slip")  # fmt: skip


def _sweep_results(result) -> None:
    """Each point's inputs and main outputs (:data:`SHOWN`), one row each, units in the
    header; p_stick and p_slip as ``p [low, high]``."""
    from mcsim.cli.display import print_rows

    table = result.table()
    units = table.attrs["units"]
    columns = [*result.grid, *(c for c in SHOWN if c in table.columns)]
    rows = table.to_dict("records")
    for row in rows:
        for name in ("p_stick", "p_slip"):
            if name in row:
                low, high = row[f"{name}_low"], row[f"{name}_high"]
                row[name] = f"{row[name]:.3g} [{low:.3g}, {high:.3g}]"
    fractions = [c for c in ("p_stick", "p_slip") if c in columns]
    said = ", ".join(f"{c} {units[c]}" for c in columns if units[c] != "1")
    if fractions:
        said += f"; {', '.join(fractions)}: fraction of pads [95 % interval]"
    print()
    print_rows(rows, columns, "table", header=[f"results per point ({said})"])


def add_parser(sub) -> None:
    p = sub.add_parser(
        "show",
        help="human summary of a run or sweep file",
        description="Summarise a run or sweep file.",
    )
    p.add_argument("run", help="run file or sweep file (.h5)")
    p.set_defaults(func=run)

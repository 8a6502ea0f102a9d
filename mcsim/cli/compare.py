"""``mcsim compare``: Monte Carlo against the analytic curves, with z-scores."""

from __future__ import annotations

import sys

from mcsim.cli.display import print_rows
from mcsim.cli.options import FORMATS


def run(args) -> int:
    from mcsim.store.runfile import read_run

    run = read_run(args.run, allow_incomplete=args.partial)
    rows = run.compare().to_dict("records")
    columns = ["h", "branch", "quantity", "mc_mean", "mc_se", "analytic", "z"]
    notes = sorted({(r["h"], r["note"]) for r in rows if r["note"]}, key=lambda t: -t[0])
    if args.format == "table":
        columns.append("note")
        for r in rows:
            r["note"] = r["note"].split(":")[0]
    print_rows(
        rows, columns, args.format, header=[f"run {run.path}", "z = (mc_mean - analytic)/mc_se"]
    )
    if not run.complete:
        print(f"mcsim: note: {run.path} is incomplete: compared over its {run.spec.realizations} "
              "completed realization(s)", file=sys.stderr)  # fmt: skip
    if args.format == "csv" and notes:
        for h, note in notes:
            print(f"mcsim: note: h = {h:g}: z left empty: {note}", file=sys.stderr)
    return 0


def add_parser(sub) -> None:
    p = sub.add_parser("compare", help="Monte Carlo versus analytic, with z-scores",
                       description="For every h and quantity: MC mean, its standard error, the analytic value and "
                       "z = (mc - analytic)/se.")  # fmt: skip
    p.add_argument("run", help="run file (.h5)")
    p.add_argument("--format", choices=FORMATS, default="table")
    p.add_argument(
        "--partial",
        action="store_true",
        help="accept an incomplete run: use its completed realizations",
    )
    p.set_defaults(func=run)

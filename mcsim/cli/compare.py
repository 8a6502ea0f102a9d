"""``mcsim compare``: Monte Carlo against the analytic curves, with z-scores."""

from __future__ import annotations

import sys

from mcsim.cli.display import print_rows
from mcsim.cli.options import FORMATS


def run(args) -> int:
    from mcsim.store.runfile import read_run

    run = read_run(args.run, allow_incomplete=args.partial)
    rows = run.compare_rows()  # compare()'s records, without importing pandas
    columns = ["h", "branch", "quantity", "mc_mean", "mc_se", "analytic", "z"]
    notes = [(r["h"], r["note"]) for r in rows if r["note"]]
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
    if args.format == "csv":  # the table and json carry the notes in their rows
        for line in _note_lines(notes):
            print(line, file=sys.stderr)
    return 0


def _note_lines(notes: list[tuple[float, str]]) -> list[str]:
    """One stderr line per kind of note (the text before its first parenthesis or colon):
    how many rows, over which separations, and the first such note."""
    kinds: dict[str, list[tuple[float, str]]] = {}
    for h, note in notes:
        kinds.setdefault(note.split(":")[0].split(" (")[0], []).append((h, note))
    return [f"mcsim: note: z left empty in {len(group)} row(s) at h = "
            f"{min(h for h, _ in group):g} .. {max(h for h, _ in group):g}: {kind}, e.g. "
            f"{group[0][1]} (the note column of --format table or json says it per row)"
            for kind, group in kinds.items()]  # fmt: skip


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

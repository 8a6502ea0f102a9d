"""``mcsim paper``: reproduce the paper's Figs. 2-6 and its table of mu."""

from __future__ import annotations

from pathlib import Path

from mcsim.cli.display import announce
from mcsim.cli.options import seed_type


def run(args) -> int:
    from mcsim.store.outputs import check_output
    from mcsim.studies.paper import paper_monte_carlo, paper_outputs, reproduce_paper

    if Path(args.out).is_dir():  # refuse before the Monte Carlo work, not after it
        for path in paper_outputs(args.out, monte_carlo=not args.no_mc):
            check_output(path, overwrite=args.overwrite)
    mc = None
    if not args.no_mc:
        mc = paper_monte_carlo(args.out, seed=args.seed, overwrite=args.overwrite,
                              command=args.command_line)  # fmt: skip
    result = reproduce_paper(out_dir=args.out, mc=mc, overwrite=args.overwrite,
                             command=args.command_line)  # fmt: skip
    for path in [*result["figures"].values(), result["curves_csv"], result["mu_table_csv"]]:
        announce(path, quiet=args.quiet)
    return 0


def add_parser(sub) -> None:
    p = sub.add_parser("paper", help="reproduce the paper's Figs. 2-6", description="Reproduce the paper's Figs. 2-6 "
                       "(analytic curves with Monte Carlo points), a CSV of the curves and a table of mu.")  # fmt: skip
    p.add_argument("--out", default="runs/paper", help="output folder (default: runs/paper)")
    p.add_argument("--no-mc", action="store_true", help="analytic curves only")
    p.add_argument(
        "--seed",
        type=seed_type,
        default=2026,
        help="seed of the Monte Carlo patches (default: 2026)",
    )
    p.add_argument("--overwrite", action="store_true",
                   help="replace the files of an earlier reproduction in --out")  # fmt: skip
    p.add_argument("--quiet", action="store_true", help="no 'wrote FILE' line")
    p.set_defaults(func=run)

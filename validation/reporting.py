"""Output helpers shared by the validation scripts: folder, provenance, figures, summaries."""

from __future__ import annotations

import argparse
import shlex
import sys
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

import mcsim

#: Where every validation script writes (git-ignored).
OUT = Path(__file__).resolve().parent / "out"


def parser(description: str) -> argparse.ArgumentParser:
    """Command line common to the scripts: ``--quick``, ``--out``, ``--seed``."""
    p = argparse.ArgumentParser(description=description)
    p.add_argument("--quick", action="store_true", help="fast smoke run (seconds, coarse numbers)")
    p.add_argument("--out", type=Path, default=OUT, help=f"output folder (default {OUT})")
    p.add_argument("--seed", type=int, default=20240611, help="root seed (default %(default)s)")
    return p


def child_seeds(root: int, n: int) -> list[int]:
    """``n`` independent integer seeds from ``SeedSequence(root).spawn`` (never ``root + i``)."""
    return [int(c.generate_state(1, np.uint64)[0]) for c in np.random.SeedSequence(root).spawn(n)]


def provenance(args: argparse.Namespace) -> dict[str, str]:
    """Package version, time, command line and seed, written into every output."""
    return {
        "mcsim": mcsim.__version__,
        "created": datetime.now(UTC).isoformat(timespec="seconds"),
        "command": " ".join(shlex.quote(a) for a in [sys.executable, *sys.argv]),
        "seed": str(args.seed),
        "mode": "quick" if args.quick else "full",
    }


def save_figure(fig, path: Path, args: argparse.Namespace) -> None:
    """PNG with the provenance in its text chunks."""
    meta = {"Software": f"mcsim {mcsim.__version__}", "Description": provenance(args)["command"]}
    fig.savefig(path, dpi=130, format="png", metadata=meta)
    print(f"wrote {path}")


def write_summary(path: Path, lines: list[str], args: argparse.Namespace) -> None:
    """Print the summary and save it with a provenance header."""
    text = "\n".join(lines)
    print(text)
    header = "".join(f"# {k}: {v}\n" for k, v in provenance(args).items())
    path.write_text(header + text + "\n")
    print(f"wrote {path}")

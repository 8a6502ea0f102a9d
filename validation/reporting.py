"""Shared by the validation scripts: command line, output folder, provenance, figures,
summaries, and the PASS/FAIL lines of their criteria (:class:`Checks`)."""

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
    p.add_argument("--quick", action="store_true",
                   help="smaller run (seconds) that still checks the criteria")  # fmt: skip
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


class Checks:
    """A script's pass/fail criteria: one ``PASS``/``FAIL`` line each, exit status 1 on a FAIL.

    Each line states the measured value and its bound. A timing criterion (``timing=True``)
    is reported but not judged when ``timing_judged`` is False (a ``--quick`` run of a
    benchmark measures too little for its target): its line starts with ``INFO``.
    """

    def __init__(self, timing_judged: bool = True) -> None:
        self.lines: list[str] = []
        self.failed = 0
        self.timing_judged = timing_judged

    def judge(self, ok: bool, text: str, timing: bool = False) -> str:
        """Record one criterion, ``text`` saying what was measured against what bound;
        returns its line, ``"PASS: text"``, ``"FAIL: text"`` or (an unjudged timing) ``"INFO ..."``."""
        if timing and not self.timing_judged:
            verdict = "INFO (timing, not judged with --quick)"
        else:
            verdict = "PASS" if ok else "FAIL"
            self.failed += not ok
        line = f"{verdict}: {text}"
        self.lines.append(line)
        return line

    def at_most(self, name: str, value: float, bound: float, fmt=".3g", timing=False) -> None:
        """PASS if ``value <= bound`` (NaN fails)."""
        text = f"{name}: {value:{fmt}} (bound <= {bound:{fmt}})"
        self.judge(bool(value <= bound), text, timing)

    def at_least(self, name: str, value: float, bound: float, fmt=".3g", timing=False) -> None:
        """PASS if ``value >= bound`` (NaN fails)."""
        text = f"{name}: {value:{fmt}} (bound >= {bound:{fmt}})"
        self.judge(bool(value >= bound), text, timing)

    def holds(self, name: str, ok: bool, measured: str) -> None:
        """PASS if ``ok``; ``measured`` says what was seen."""
        self.judge(bool(ok), f"{name}: {measured}")

    def summary(self) -> list[str]:
        """The criteria's lines and a last line counting the failures."""
        judged = sum(not line.startswith("INFO") for line in self.lines)
        last = f"criteria: {judged - self.failed} of {judged} PASS"
        return [
            "## Criteria",
            "",
            *self.lines,
            "",
            last + (f", {self.failed} FAIL" if self.failed else ""),
        ]

    def exit(self) -> None:
        """Exit with status 1 if any criterion failed, else 0."""
        sys.exit(1 if self.failed else 0)

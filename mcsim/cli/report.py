"""``mcsim report SCAN``: from a height scan to a stiction report (HTML and JSON)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from mcsim.cli.display import announce
from mcsim.cli.options import add_environment, add_parallel, integer, scheduler_of
from mcsim.model.errors import ParameterError


def _outputs(args) -> tuple[Path, Path]:
    """The HTML file and the JSON file beside it (same stem)."""
    html = Path(args.out) if args.out else Path(f"{Path(args.file).stem}-report.html")
    if html.suffix.lower() != ".html":
        raise ParameterError(f"--out: {html}: the report is an HTML file, its name must end in "
                             ".html (the JSON file goes beside it)")  # fmt: skip
    return html, html.with_suffix(".json")


def run(args) -> int:
    import argparse as _argparse

    from mcsim.cli.options import environment_of
    from mcsim.engine import interrupt
    from mcsim.store.outputs import check_output, write_atomic
    from mcsim.studies.report import report
    from mcsim.studies.reportpage import shown

    html, json_path = _outputs(args)
    for path in (html, json_path):  # refused before any work
        check_output(path, inputs=[args.file], overwrite=args.overwrite)
    options = {k: v for k, v in vars(args).items() if k != "rh"}  # --rh: the pads' values
    environment = environment_of(_argparse.Namespace(**options, rh=None, surface=None))
    result = report(
        args.file, pad_area=args.pad_area, restoring_force=args.restoring_force,
        stiffness=args.stiffness, gap=args.gap, preload=args.preload, material=args.material,
        rh=args.rh, devices=args.devices, law=args.law, pads=args.pads,
        environment=environment,
        unit=args.unit, pixel_size=args.pixel_size, channel=args.channel, seed=args.seed,
        workers=args.workers, scheduler=scheduler_of(args, processes=True), progress=not args.quiet,
        command=args.command_line,
    )  # fmt: skip
    texts = {json_path: result.to_json(), html: result.to_html()}
    fresh = [path for path in texts if not path.exists()]
    with interrupt.interruptible():  # both files or neither: a signal waits for check()
        try:
            for path, text in texts.items():
                write_atomic(path, lambda tmp, t=text: Path(tmp).write_text(t, encoding="utf-8"),
                             inputs=[args.file], overwrite=args.overwrite)  # fmt: skip
            interrupt.check()
        except BaseException:
            for path in fresh:
                path.unlink(missing_ok=True)
            raise
    for path in texts:
        announce(path, quiet=args.quiet)
    for i, row in enumerate(result.rows):  # the results on standard output
        p, p_any = (", ".join(shown(row[k + x], 3) for x in ("_low", "_high"))
                    for k in ("p_stick", "p_any"))  # fmt: skip
        print(f"RH {row['rh']:g}: p_stick {shown(row['p_stick'], 3)} [{p}], P(any of "
              f"{result.device['devices']} stuck) {shown(row['p_any'], 3)} [{p_any}]"
              + ("" if i else f"  (report made in {result.elapsed:.1f} s)"),
              file=sys.stdout)  # fmt: skip
    return 0


def add_parser(sub) -> None:
    p = sub.add_parser(
        "report", help="from a height scan to a stiction report (HTML and JSON)",
        description="One command from a measured scan to a device's stiction report: ingest "
        "and calibrate GW on the scan's exact contact, the exact contact beside GW with the "
        "stickiness diagnostics, pads at each relative humidity (importance sampling where "
        "the answer is rare), p_stick with its interval, the lot's expected stuck devices and "
        "P(any of N stuck) with intervals, the margin to the critical humidity and the static "
        "friction where the law set gives it. Writes one self-contained HTML file and a JSON "
        "file with the same numbers.",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter,
    )  # fmt: skip
    p.add_argument("file", help="height map (.gwy .ibw .nid .npy .xyz or a text matrix)")
    p.add_argument("--unit", help="height unit for files that store none (e.g. nm)")
    p.add_argument("--pixel-size", metavar="DX", help="pixel size for files that store none "
                   "(m unless a unit is given: '10nm')")  # fmt: skip
    p.add_argument("--channel", help="channel of a multi-channel file")
    d = p.add_argument_group("device")
    d.add_argument("--pad-area", metavar="A", default="10um^2",
                   help="nominal area of one contact pad (m^2 unless a unit is given)")  # fmt: skip
    d.add_argument("--preload", metavar="P", default="0",
                   help="nominal pressure pressing each pad, >= 0 (Pa unless a unit is given); "
                   "0: the pad rests on its own summits")  # fmt: skip
    d.add_argument("--restoring-force", metavar="F",
                   help="force pulling a pad off (N unless a unit is given: '20uN'); or "
                   "--stiffness and --gap")  # fmt: skip
    d.add_argument("--stiffness", metavar="K", help="the suspension's spring constant (N/m "
                   "unless a unit is given), with --gap: restoring force K x GAP")  # fmt: skip
    d.add_argument("--gap", metavar="G", help="the gap the suspension closes to touch (m unless "
                   "a unit is given: '2um')")  # fmt: skip
    d.add_argument("--material", default="silicon", help="preset name or TOML file")
    d.add_argument("--devices", metavar="N", type=integer(1), default=1000,
                   help="devices in the lot, >= 1")  # fmt: skip
    d.add_argument("--rh", metavar="VALUES", default="0,0.3,0.5,0.7,0.9",
                   help="relative humidities, each 0 <= RH < 1: 'a,b,c' or 'start:stop:num'")  # fmt: skip
    d.add_argument("--law", default="auto", help="law set of the pads, or auto (the adhesion "
                   "map's choice)")  # fmt: skip
    d.add_argument("--pads", metavar="N", type=integer(1), default=100,
                   help="pads per RH (>= 100: importance sampling where the answer is rare)")  # fmt: skip
    d.add_argument("--seed", type=integer(0), help="root seed of the pads (recorded)")
    add_parallel(d, "worker processes of the pads (1: in this process), or with --dask local "
                 "a local Dask cluster's")  # fmt: skip
    add_environment(p, rh=False)
    p.add_argument("--out", metavar="FILE.html", help="the report (default SCAN-report.html in "
                   "the current folder); the JSON file goes beside it, FILE.json")  # fmt: skip
    p.add_argument("--overwrite", action="store_true", help="replace existing report files")
    p.add_argument("--quiet", action="store_true", help="no progress and no 'wrote FILE' lines")
    p.set_defaults(func=run)

"""The HTML page of a :class:`mcsim.studies.report.Report`: one self-contained file.

Figures are inline base64 PNG, the style sheet is inline, there is no script. Every number
in a table sits in a cell with a ``data-key`` attribute, the dotted path of the same number
in the report's JSON (``rows.2.p_stick``), and a ``data-scale`` where it is shown in another
unit than the JSON's SI one (shown × scale = the JSON's value): a reader, or a test, can
check every number of the page against the JSON. A warning sits beside the number it
qualifies: under the table row or the table it belongs to.
"""

from __future__ import annotations

import base64
import html
import math

#: Significant digits of the numbers shown.
DIGITS = 4

_STYLE = """
body { font-family: sans-serif; margin: 1.5em auto; max-width: 1100px; padding: 0 1em;
       color: #222; line-height: 1.4; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 1.6em; }
table { border-collapse: collapse; margin: 0.6em 0; font-size: 0.9em; }
th, td { border: 1px solid #bbb; padding: 0.25em 0.5em; text-align: right; vertical-align: top; }
th { background: #eee; } td.text, th.text { text-align: left; }
tr.warning td { text-align: left; background: #fff4e0; color: #7a4b00; font-size: 0.9em; }
ul.warnings { background: #fff4e0; color: #7a4b00; padding: 0.5em 0.5em 0.5em 2em; }
img { max-width: 100%; height: auto; display: block; margin: 0.6em 0; }
p.meta { color: #555; font-size: 0.9em; }
"""


def shown(p: float, digits: int = DIGITS) -> str:
    """A probability ``p`` to ``digits`` significant digits; within 1e-3 of 1 (not 1) as
    ``1 − q``, q = 1 − p to those digits, which p's own digits would round away (p_stick
    bounded at 1 − 9.553e-06 would show as 1)."""
    if 1 - 1e-3 < p < 1:
        return f"1 − {1 - p:.{digits}g}"
    return f"{p:.{digits}g}"


def _number(value, key: str, scale: float = 1.0, probability: bool = False) -> str:
    """A table cell for the JSON value at ``key``, shown divided by ``scale`` (a
    ``probability`` near 1 as 1 − q, :func:`shown`)."""
    attrs = f' data-key="{html.escape(key)}"'
    if scale != 1.0:
        attrs += f' data-scale="{scale:g}"'
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return f"<td{attrs}>n/a</td>"
    if probability:
        return f"<td{attrs}>{shown(value)}</td>"
    return f"<td{attrs}>{value / scale:.{DIGITS}g}</td>"


def _text(value) -> str:
    return f'<td class="text">{html.escape(str(value))}</td>'


def _warnings(lines) -> str:
    if not lines:
        return ""
    items = "".join(f"<li>warning: {html.escape(w)}</li>" for w in lines)
    return f'<ul class="warnings">{items}</ul>'


def _table(header, rows) -> str:
    head = "".join(f'<th class="text">{html.escape(h)}</th>' if i == 0 else f"<th>{html.escape(h)}</th>"
                   for i, h in enumerate(header))  # fmt: skip
    return f"<table><tr>{head}</tr>{''.join(rows)}</table>"


def _pairs(data: dict, prefix: str, entries) -> str:
    """A two-column table: (label, key, scale) entries of ``data``."""
    rows = [f"<tr>{_text(label)}{_number(data.get(key), f'{prefix}.{key}', scale)}</tr>"
            for label, key, scale in entries]  # fmt: skip
    return _table(["quantity", "value"], rows)


def _image(png: bytes, alt: str) -> str:
    data = base64.b64encode(png).decode("ascii")
    return f'<img alt="{html.escape(alt)}" src="data:image/png;base64,{data}">'


def _devices(report) -> str:
    d = report.device
    n = d["devices"]
    friction = "static_friction_mean" in (report.rows[0] if report.rows else {})
    header = ["RH", "p_stick", "95 % low", "95 % high", "method", f"stuck of {n}",
              "low", "high", f"P(any of {n} stuck)", "low", "high", "RH_cr - RH",
              "pull-off mean (µN)", "work of separation mean (mJ/m²)"]  # fmt: skip
    if friction:
        header += ["T_s mean (µN)", "μ_s mean"]
    rows = []
    for i, r in enumerate(report.rows):
        k = f"rows.{i}"
        cells = [_number(r["rh"], f"{k}.rh")]
        cells += [_number(r[x], f"{k}.{x}", probability=True)
                  for x in ("p_stick", "p_stick_low", "p_stick_high")]  # fmt: skip
        cells.append(_text(r["p_stick_method"]))
        cells += [_number(r[x], f"{k}.{x}")
                  for x in ("expected_stuck", "expected_stuck_low", "expected_stuck_high")]  # fmt: skip
        cells += [_number(r[x], f"{k}.{x}", probability=True)
                  for x in ("p_any", "p_any_low", "p_any_high")]  # fmt: skip
        cells.append(_number(r["rh_margin"], f"{k}.rh_margin"))
        cells.append(_number(r["pull_off_mean"], f"{k}.pull_off_mean", 1e-6))
        cells.append(_number(r["work_of_separation_mean"], f"{k}.work_of_separation_mean", 1e-3))
        if friction:
            cells.append(_number(r["static_friction_mean"], f"{k}.static_friction_mean", 1e-6))
            cells.append(_number(r["mu_static_mean"], f"{k}.mu_static_mean"))
        rows.append(f"<tr>{''.join(cells)}</tr>")
        if r["warnings"]:
            text = "; ".join(f"warning: {w}" for w in r["warnings"])
            rows.append(f'<tr class="warning"><td colspan="{len(header)}">RH {r["rh"]:g}: '
                        f"{html.escape(text)}</td></tr>")  # fmt: skip
    return _table(header, rows)


def _contact(report) -> str:
    c = report.contact
    header = ["p/E*", "p (MPa)", "exact A_r/A_n", "GW A_r/A_n (measured R)",
              "GW A_r/A_n (calibrated)", "exact mean gap (nm)", "patches"]  # fmt: skip
    rows = []
    for i in range(len(c["pressure"])):
        cells = [_number(c["load"][i], f"contact.load.{i}"),
                 _number(c["pressure"][i], f"contact.pressure.{i}", 1e6),
                 _number(c["exact_area"][i], f"contact.exact_area.{i}"),
                 _number(c["gw_area"][i], f"contact.gw_area.{i}"),
                 _number(c["gw_calibrated_area"][i], f"contact.gw_calibrated_area.{i}"),
                 _number(c["exact_mean_gap"][i], f"contact.exact_mean_gap.{i}", 1e-9),
                 _number(c["patches"][i], f"contact.patches.{i}")]  # fmt: skip
        rows.append(f"<tr>{''.join(cells)}</tr>")
    return _table(header, rows)


def body(report) -> str:
    """The report as an HTML fragment (no ``<html>``; Jupyter shows it)."""
    d, h, s = report.device, report.humidity, report.scan
    source = html.escape(str(report.inputs.get("scan")))
    parts = [
        f"<h1>Stiction report: {source}</h1>",
        f'<p class="meta">mcsim {html.escape(report.version)}, made {html.escape(report.created)}'
        f" in <span data-key=\"elapsed\">{report.elapsed:.{DIGITS}g}</span> s"
        + (f"; command: <code>{html.escape(report.inputs['command'])}</code>"
           if report.inputs.get("command") else "") + "</p>",
        "<h2>The devices at each relative humidity</h2>",
        f"<p>{d['pads']} pads of {d['pad_area'] * 1e12:.{DIGITS}g} µm² per RH (law set "
        f"{html.escape(d['law'])}); a pad sticks when its pull-off exceeds the restoring force. "
        "p_stick with its 95 % interval (Clopper–Pearson; on the effective sample size where "
        f"the method is importance sampling); a lot of N = {d['devices']} devices: N·p stuck and "
        "P(any stuck) = 1 − (1 − p)<sup>N</sup>, each interval the image of p's (both grow with "
        "p). RH_cr − RH: the margin to the critical humidity where menisci spread.</p>",
        _devices(report),
        _warnings(report.warnings.get("friction")),
        _image(report.figures["stiction"], "p_stick against RH") if "stiction" in report.figures
        else "",
        _pairs(h, "humidity", [("RH_dry (bridges form)", "rh_dry", 1.0),
                               ("RH_cr (menisci spread)", "rh_cr", 1.0)]),
        "<h2>The device</h2>",
        _pairs(d, "device", [
            ("pad area (µm²)", "pad_area", 1e-12), ("preload (MPa)", "preload", 1e6),
            ("restoring force (µN)", "restoring_force", 1e-6), ("devices N", "devices", 1.0),
            ("pads per RH", "pads", 1.0), ("expected summits per pad", "expected_summits", 1.0),
            ("contact modulus E* (GPa)", "E_star", 1e9), ("work of adhesion w (J/m²)", "w", 1.0),
        ]),
        f"<p>Restoring force: {html.escape(d['restoring_force_from'])}. Law set: "
        f"{html.escape(d['law'])}{'; ' + html.escape(d['law_choice']) if d['law_choice'] else ''}."
        "</p>",
        "<h2>The scan and GW calibrated on it</h2>",
        _pairs(s, "scan", [
            ("pixel size (nm)", "dx", 1e-9), ("summits", "summits", 1.0),
            ("summit sigma (nm)", "sigma", 1e-9), ("R measured (µm)", "R_measured", 1e-6),
            ("R calibrated (µm)", "R", 1e-6), ("eta (µm⁻²)", "eta", 1e12),
            ("radius scale", "radius_scale", 1.0),
            ("area error in sample, worst", "calibration_in_sample_worst", 1.0),
            ("area error leave-one-out, worst", "calibration_loo_worst", 1.0),
            ("area error at p/E* = 3e-2", "calibration_extrapolated_error", 1.0),
        ]),
        _warnings(report.warnings.get("scan")),
        "<h2>Exact contact beside GW</h2>",
        "<p>Frictionless elastic contact of the scan against a rigid flat, solved exactly (FFT "
        "boundary elements; exact at the scan's pixel size), beside GW's Hertz summits.</p>",
        _contact(report),
        _warnings(report.warnings.get("contact")),
        _image(report.figures["contact"], "exact contact and GW") if "contact" in report.figures
        else "",
        "<h2>Is the scan sticky?</h2>",
        _pairs(report.stickiness, "stickiness", [
            ("Pastewka–Robbins parameter (> 1: not sticky)", "pr_parameter", 1.0),
            ("range over gap scale (< 0.1: valid)", "range_over_gap", 1.0),
            ("Tabor parameter", "tabor", 1.0), ("mesh criterion (< 0.5: resolved)", "mesh", 1.0),
        ]),
        _warnings(report.warnings.get("stickiness")),
        "<h2>Inputs</h2>",
        _table(["environment (SI)", "value"], [
            f"<tr>{_text(k)}{_text(v)}</tr>" for k, v in h.get("environment", {}).items()]),
        _table(["input", "value"], [f"<tr>{_text(k)}{_text(v)}</tr>"
                                    for k, v in report.inputs.items() if v is not None]),
    ]  # fmt: skip
    return "\n".join(p for p in parts if p)


def page(report) -> str:
    """The report as one self-contained HTML document."""
    title = html.escape(f"mcsim stiction report: {report.inputs.get('scan')}")
    return (f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>{title}</title>'
            f"<style>{_STYLE}</style></head><body>\n{body(report)}\n</body></html>\n")  # fmt: skip

"""mcsim.report: a scan's stiction report, its JSON and its self-contained HTML page."""

from __future__ import annotations

import base64
import dataclasses
import json
import math
import os
import shutil
import subprocess
import warnings
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest
from conftest import run_cli

import mcsim
from mcsim.model.errors import MCSimError, ParameterError
from mcsim.studies.intervals import clopper_pearson
from mcsim.studies.report import RESOLUTION, lot
from mcsim.studies.reportpage import shown

SCAN = Path(__file__).resolve().parents[2] / "examples" / "scan.npy"

#: A small device on the shipped scan: 20 pads of 1 µm² (113 summits) at two humidities.
SMALL = {"unit": "m", "pixel_size": "10nm", "pad_area": "1um^2", "restoring_force": "1uN",
         "rh": (0.0, 0.5), "pads": 20, "devices": 100, "seed": 1, "law": "jkr", "workers": 1}  # fmt: skip


@pytest.fixture(scope="module")
def small_and_warnings():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        report = mcsim.report(SCAN, **SMALL)
    return report, caught


@pytest.fixture(scope="module")
def small(small_and_warnings):
    return small_and_warnings[0]


def test_the_pads_sweep_leaves_gws_area_to_the_contact_section(small_and_warnings):
    # GW's A_r/A_n on the pads' grid of separations is no warning of the report's own: the
    # contact section sets GW's area beside the exact one (`mcsim report` printed it as a
    # Python warning with its source line)
    from mcsim.physics.adhesion import ValidityWarning

    _, caught = small_and_warnings
    assert not [w for w in caught if issubclass(w.category, ValidityWarning)]


class _Cells(HTMLParser):
    """Every element with a ``data-key``: (key, scale, text); and every image's source."""

    def __init__(self):
        super().__init__()
        self.cells, self.images, self._open = [], [], None

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "img":
            self.images.append(attrs["src"])
        if "data-key" in attrs:
            self._open = [attrs["data-key"], float(attrs.get("data-scale", 1)), ""]

    def handle_data(self, data):
        if self._open is not None:
            self._open[2] += data

    def handle_endtag(self, tag):
        if self._open is not None and tag in ("td", "span"):
            self.cells.append(tuple(self._open))
            self._open = None


def _at(data, key: str):
    for part in key.split("."):
        data = data[int(part)] if isinstance(data, list) else data[part]
    return data


def test_every_number_of_the_page_is_the_jsons(small):
    data = json.loads(small.to_json())
    parser = _Cells()
    parser.feed(small.to_html())
    assert len(parser.cells) > 60  # the tables are there: each row of numbers has its keys
    for key, scale, text in parser.cells:
        value = _at(data, key)
        if value is None:
            assert text == "n/a", key
            continue
        if text.startswith("1 − "):  # a probability near 1: its complement to 4 digits
            assert 1 - value == pytest.approx(float(text[4:]), rel=5.1e-4), f"{key}: {text}"
            continue
        shown = float(text) * scale  # 4 significant digits: within half a unit of the 4th
        assert shown == pytest.approx(value, rel=5.1e-4, abs=1e-300), f"{key}: {text} vs {value}"


def test_a_probability_near_one_shows_its_complement():
    # p_stick bounded at 1 − 9.553e-06 would show as 1 to 4 digits, its bound lost.
    assert shown(0.9999904467778564) == "1 − 9.553e-06"
    assert shown(0.998) == "0.998" and shown(1.0) == "1" and shown(0.0) == "0"
    assert shown(0.99999, 3) == "1 − 1e-05"


def test_the_page_is_self_contained(small):
    page = small.to_html()
    parser = _Cells()
    parser.feed(page)
    assert len(parser.images) == 2
    for src in parser.images:
        assert src.startswith("data:image/png;base64,")
        assert base64.b64decode(src.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n"
    for external in ("<script", "<link", "http://", "https://", "@import", "url("):
        assert external not in page


def test_the_page_names_the_version_the_time_and_every_input(small):
    page = small.to_html()
    assert f"mcsim {mcsim.__version__}" in page
    assert 'data-key="elapsed"' in page
    for value in ("1um^2", "1uN", "jkr", "10nm"):
        assert value in page


def test_a_rows_warnings_sit_under_its_numbers(small):
    page = small.to_html()
    for i, row in enumerate(small.rows):
        assert row["warnings"], "a pad of 113 summits touches with fewer than 10: warned"
        start = page.index(f'data-key="rows.{i}.rh"')
        warning = page.index(f"RH {row['rh']:g}: warning:", start)
        assert page.find("<tr>", start, warning) == -1  # no other row in between


def test_p_stick_is_the_pads_fraction_with_its_clopper_pearson_interval(small):
    for row in small.rows:
        k = round(row["p_stick"] * SMALL["pads"])
        assert row["p_stick_method"] == "pads"
        assert (row["p_stick_low"], row["p_stick_high"]) == pytest.approx(
            clopper_pearson(k, SMALL["pads"]), rel=1e-12
        )


def test_the_lot_carries_p_sticks_interval_through():
    out = lot(0.01, 0.002, 0.03, 200)
    assert out["expected_stuck"] == pytest.approx(2.0)
    assert (out["expected_stuck_low"], out["expected_stuck_high"]) == pytest.approx((0.4, 6.0))
    for key, p in (("p_any", 0.01), ("p_any_low", 0.002), ("p_any_high", 0.03)):
        assert out[key] == pytest.approx(1 - (1 - p) ** 200, rel=1e-12)
    assert lot(1e-12, 0, 1, 1000)["p_any"] == pytest.approx(1e-9, rel=1e-6)  # no cancellation
    assert lot(0.5, 0.0, 1.0, 3)["p_any_low"] == 0.0
    assert lot(0.5, 0.0, 1.0, 3)["p_any_high"] == 1.0


def test_the_lot_of_each_row_is_its_p_stick_carried_to_n_devices(small):
    for row in small.rows:
        expected = lot(row["p_stick"], row["p_stick_low"], row["p_stick_high"], SMALL["devices"])
        assert {k: row[k] for k in expected} == pytest.approx(expected, rel=1e-12)


def test_the_menisci_warning_sits_where_the_menisci_act():
    # At RH_cr itself (0.30: the film no thicker than its structured layers) no bridge forms,
    # and the pads there are the dry ones: no "menisci spread" warning. Above it, one.
    from mcsim.physics.environment import Environment
    from mcsim.studies.report import _rows

    env = Environment(hamaker=1.6e-19)
    rh = (0.0, env.critical_rh, 0.5)
    keys = ("p_stick", "p_stick_low", "p_stick_high", "p_stick_ess", "contacting_summits")
    data = {k: np.full(3, 0.5) for k in keys} | {"p_stick_method": np.array(["pads"] * 3),
                                                  "regime_warning": np.array([""] * 3)}  # fmt: skip
    data["contacting_summits"] = np.full(3, 100.0)
    rows = _rows(type("Sweep", (), {"data": data})(), rh, env, 10)
    spread = [any("menisci spread" in w for w in r["warnings"]) for r in rows]
    assert spread == [False, False, True]
    assert [dataclasses.replace(env, rh=r).has_capillary for r in rh] == spread


def test_the_margin_is_the_critical_rh_minus_each_rh(small):
    rh_cr = small.humidity["rh_cr"]
    assert rh_cr == pytest.approx(0.30, abs=0.005)  # DelRio's RH_dry: smooth asperities
    assert [r["rh_margin"] for r in small.rows] == pytest.approx([rh_cr - 0.0, rh_cr - 0.5])


def test_humid_pads_stick_more_than_dry_ones(small):
    dry, humid = small.rows  # beyond RH_cr menisci pull: several times the work (9x, seed 1)
    assert humid["work_of_separation_mean"] > 3 * dry["work_of_separation_mean"]
    assert humid["p_stick"] >= dry["p_stick"]


def test_jkr_pads_get_their_static_friction(small):
    for row in small.rows:
        assert (
            row["static_friction_q05"] <= row["static_friction_mean"] <= row["static_friction_q95"]
        )
        assert row["static_friction_mean"] > 0
    assert small.warnings["friction"] == []


def test_the_exact_contact_and_the_calibration_are_the_scans(small):
    c, s = small.contact, small.scan
    assert s["radius_scale"] == pytest.approx(1.710, abs=5e-4)  # README, "How good is GW"
    assert c["load"] == pytest.approx([1e-4, 10**-3.5, 1e-3, 10**-2.5, 1e-2])
    worst = max(abs(g / e - 1) for g, e in zip(c["gw_calibrated_area"], c["exact_area"]))
    assert worst == pytest.approx(s["calibration_in_sample_worst"], rel=1e-9)


def test_the_json_has_no_nan_and_reads_back(small):
    data = json.loads(small.to_json())
    assert data["version"] == mcsim.__version__
    assert data["device"]["expected_summits"] == pytest.approx(113.0)
    assert "figures" not in data


def test_jupyter_shows_the_pages_body(small):
    fragment = small._repr_html_()
    assert fragment.startswith("<h1>") and "<html" not in fragment
    assert fragment in small.to_html()


def test_files_follow_the_output_rule(small, tmp_path):
    path = tmp_path / "r.json"
    small.to_json(path)
    before = path.read_bytes()
    with pytest.raises(MCSimError, match="file exists"):
        small.to_json(path)
    assert path.read_bytes() == before
    small.to_html(tmp_path / "r.html")
    small.to_html(tmp_path / "r.html", overwrite=True)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.html", "r.json"]


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"devices": 0}, r"devices = 0: .*integer >= 1"),
        ({"devices": -3}, r"devices = -3"),
        ({"devices": 2.5}, r"devices = 2.5"),
        ({"rh": (0.2, 1.0)}, r"rh = 1.0: out of range \(allowed: 0 <= RH < 1\)"),
        ({"rh": ()}, r"rh = \(\): give 1 to 50"),
        ({"pad_area": "0um^2"}, r"pad_area = '0um\^2': out of range"),
        ({"restoring_force": "-1uN"}, r"restoring_force = -1e-06 N: out of range"),
        ({"preload": "-1kPa"}, r"preload = '-1kPa': out of range"),
        ({"pad_area": "1nm^2"}, r"pad_area = 1e-18 m\^2: a pad holds 0.000113 .*cannot touch"),
        ({"preload": "100GPa"}, r"preload = 1e\+11 Pa: out of range \(allowed: below E\*"),
    ],
)
def test_bad_inputs_get_one_line(change, message):
    with pytest.raises(ParameterError, match=message) as err:
        mcsim.report(SCAN, **(SMALL | change))
    assert "\n" not in str(err.value)


def test_importance_sampling_resolves_p_stick_to_a_hundredth_of_a_device(monkeypatch):
    # The lot's resolution (RESOLUTION devices of N) is the sweep's floor: importance
    # sampling stops where it shows fewer than 0.01 of the N devices on the rarer side.
    import mcsim.studies.sweeps

    asked = []

    def stop(*args, **options):
        asked.append(options["floor"])
        raise KeyboardInterrupt  # the floor is all this test needs

    monkeypatch.setattr(mcsim.studies.sweeps, "sweep", stop)
    with pytest.raises(KeyboardInterrupt):
        mcsim.report(SCAN, **(SMALL | {"devices": 400}))
    assert asked == [RESOLUTION / 400] == [2.5e-5]


@pytest.mark.parametrize(
    ("options", "scheduler", "workers"),
    [
        (["--dask", "local", "--workers", "2"], "local", 2),
        (["--scheduler", "tcp://host:8786"], "tcp://host:8786", None),
        ([], "processes", None),  # worker processes of this machine, one per core
        (["--workers", "2"], "processes", 2),
        (["--workers", "1"], None, 1),  # in this process
    ],
)
def test_the_rh_values_run_where_asked(monkeypatch, capsys, options, scheduler, workers):
    # --dask local / --scheduler reach the pads' sweep, which runs its points there; by
    # default worker processes (the sweep's own tests check that Dask and processes give
    # the same numbers as threads)
    import mcsim.studies.sweeps

    asked = []

    def stop(*args, **options):
        asked.append((options["scheduler"], options["workers"]))
        raise KeyboardInterrupt

    monkeypatch.setattr(mcsim.studies.sweeps, "sweep", stop)
    code, _, _ = run_cli(capsys, "report", SCAN, "--unit", "m", "--pixel-size", "10nm",
                         "--pad-area", "10um^2", "--restoring-force", "10uN", *options,
                         "--rh", 0)  # fmt: skip
    assert code == 130 and asked == [(scheduler, workers)]


def test_a_spring_gives_the_restoring_force():
    from mcsim.studies.report import restoring_force_of

    assert restoring_force_of(stiffness="2 N/m", gap="1.5um")[0] == pytest.approx(3e-6)
    with pytest.raises(ParameterError, match="not both"):
        restoring_force_of("1uN", stiffness="2 N/m", gap="1um")
    with pytest.raises(ParameterError, match=r"gap = 0\.0 m: out of range"):
        restoring_force_of(stiffness="2 N/m", gap="0um")


def test_a_scan_that_does_not_read_is_one_line(tmp_path):
    bad = tmp_path / "bad.npy"
    bad.write_bytes(b"not a map")
    with pytest.raises(MCSimError) as err:
        mcsim.report(bad, **SMALL)
    assert str(err.value).startswith(str(bad)) and "\n" not in str(err.value)


def _browser() -> str | None:
    for name in (os.environ.get("MCSIM_CHROMIUM"), "chromium", "chromium-browser", "google-chrome"):
        if name and shutil.which(name):
            return shutil.which(name)
    return None


#: Reads the page's layout in the browser and writes it into the title, for --dump-dom.
_PROBE = """<script>
window.addEventListener("load", () => {
  const cell = getComputedStyle(document.querySelector("td"));
  document.title = "LAYOUT" + JSON.stringify({
    width: document.documentElement.scrollWidth, viewport: window.innerWidth,
    images: [...document.images].map(i => [i.complete, i.naturalWidth, i.width]),
    tables: [...document.querySelectorAll("table")].map(t => t.getBoundingClientRect().right),
    font: parseFloat(cell.fontSize)}) + "END";
});
</script>"""


@pytest.mark.skipif(_browser() is None, reason="no headless Chromium (apt-get install chromium)")
def test_the_page_renders_in_a_real_browser(small, tmp_path):
    from PIL import Image

    page = small.to_html()
    (tmp_path / "report.html").write_text(page, encoding="utf-8")
    (tmp_path / "probe.html").write_text(page.replace("</body>", _PROBE + "</body>"), "utf-8")
    flags = [_browser(), "--headless=new", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
             "--window-size=1280,6000", f"--user-data-dir={tmp_path / 'profile'}"]  # fmt: skip
    shot = tmp_path / "shot.png"
    subprocess.run([*flags, f"--screenshot={shot}", (tmp_path / "report.html").as_uri()],
                   check=True, capture_output=True, timeout=120)  # fmt: skip
    dom = subprocess.run([*flags, "--dump-dom", (tmp_path / "probe.html").as_uri()],
                         check=True, capture_output=True, text=True, timeout=120).stdout  # fmt: skip
    layout = json.loads(dom.split("LAYOUT", 1)[1].split("END", 1)[0])
    assert layout["width"] <= layout["viewport"]  # nothing wider than the window: no clipping
    assert all(right <= layout["viewport"] for right in layout["tables"])
    assert len(layout["images"]) == 2
    for complete, natural, drawn in layout["images"]:
        assert complete and natural > 0 and 0.5 * min(natural, 1000) < drawn <= natural
    assert layout["font"] >= 12  # table text in readable pixels
    image = np.asarray(Image.open(shot).convert("RGB"), dtype=int)
    ink = np.any(image < 200, axis=2)
    rows = np.nonzero(ink.any(axis=1))[0]
    assert rows.size and rows[-1] < image.shape[0] - 50  # the page ends inside the shot
    colours = (image.max(axis=2) - image.min(axis=2)) > 80  # the figures' coloured lines/maps
    assert colours.sum() > 5000
    assert not ink[:, -20:].any()  # a white margin on the right: nothing runs off the page
    assert math.isfinite(small.elapsed)


@pytest.mark.skipif(not os.path.isdir("/proc/self"), reason="reads /proc (Linux)")
def test_ctrl_c_ends_the_worker_processes_and_leaves_nothing(tmp_path):
    # `mcsim report` runs the RH values on worker processes by default. A terminal's Ctrl-C
    # reaches them too, but they ignore it (blocked from their start until then): the
    # command ends them without waiting for their pads, prints one line and writes nothing.
    import signal
    import sys
    import time

    out = tmp_path / "r.html"
    cmd = [sys.executable, "-m", "mcsim", "report", str(SCAN), "--unit", "m", "--pixel-size",
           "10nm", "--pad-area", "1um^2", "--restoring-force", "1uN", "--rh", "0,0.5",
           "--pads", "2000", "--devices", "100", "--seed", "1", "--law", "jkr", "--workers", "2",
           "--out", str(out)]  # fmt: skip
    env = {**os.environ, "PYTHONFAULTHANDLER": "1"}
    proc = subprocess.Popen(
        cmd, stderr=subprocess.PIPE, text=True, env=env, start_new_session=True
    )  # its own group, as under a terminal
    children = f"/proc/{proc.pid}/task/{proc.pid}/children"
    workers: list[int] = []
    deadline = time.monotonic() + 120
    while len(workers) < 2 and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.2)  # until both workers run (a third child: multiprocessing's tracker)
        with open(children) as f:
            workers = [int(pid) for pid in f.read().split()]
    assert proc.poll() is None, proc.communicate()[1]
    time.sleep(2.0)  # the workers import mcsim and take their first points
    os.killpg(proc.pid, signal.SIGINT)  # as a terminal's Ctrl-C: to the whole group
    try:  # its pads would take minutes: a wait for them is a hang
        _, err = proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        proc.send_signal(signal.SIGABRT)  # every thread's stack (PYTHONFAULTHANDLER)
        pytest.fail(f"no exit 60 s after Ctrl-C:\n{proc.communicate(timeout=30)[1]}")
    assert proc.returncode == 130, err
    lines = [line for line in err.replace("\r", "\n").splitlines()
             if line.strip() and not line.startswith("mcsim: report:") and "points" not in line]  # fmt: skip
    assert lines == ["mcsim: interrupted (SIGINT); no output written"], err
    assert list(tmp_path.iterdir()) == []
    time.sleep(0.5)
    for pid in workers:  # ended (gone, or a zombie no one reaps), not left running their pads
        try:
            with open(f"/proc/{pid}/stat") as f:
                state = f.read().rsplit(")", 1)[1].split()[0]
        except FileNotFoundError:
            continue
        assert state in ("Z", "X"), f"worker {pid} still running (state {state})"

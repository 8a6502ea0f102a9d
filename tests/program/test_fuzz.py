"""Hostile input: every reader and the TOML parser fail with an MCSimError, never a crash.

Property tested on generated inputs (random bytes; real sample files and small valid
files with bit flips, truncations, insertions and overwritten header fields; text
formats with NaN, inf, negative, huge, empty, non-UTF-8 cells; TOML with wrong types
and units): reading either succeeds with a sane result (finite heights except NaN
pixels, pixel sizes finite and > 0; finite, increasing histogram edges) or raises an
:class:`~mcsim.model.errors.MCSimError` whose message is one line and names the file.

The suite runs a bounded number of examples per test (``MCSIM_FUZZ_EXAMPLES``, 25 by
default; tests on the multi-megabyte real files run a tenth of it); a campaign scales
it up, e.g. ``MCSIM_FUZZ_EXAMPLES=5000 pytest tests/program/test_fuzz.py``. Examples are
derandomized, so a run is reproducible. Files that declare huge sizes are read under
an address-space limit and a traced-memory bound, so a blow-up fails the test instead
of exhausting the machine.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import os
import random
import re
import resource
import shutil
import struct
import tracemalloc
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from mcsim.cli import main as cli
from mcsim.model.errors import MCSimError
from mcsim.model.params import Material, Surface
from mcsim.model.units import parse_quantity
from mcsim.store.config import load_material, load_surface, material_from_table, surface_from_table
from mcsim.topography.empirical import Empirical
from mcsim.topography.readers import HeightMap, read_height_map, read_histogram
from mcsim.topography.readers.base import MAX_PIXELS

EXAMPLES = int(os.environ.get("MCSIM_FUZZ_EXAMPLES", "25"))
_COMMON = dict(
    deadline=None,
    derandomize=True,
    database=None,
    suppress_health_check=[
        HealthCheck.too_slow,
        HealthCheck.function_scoped_fixture,
        HealthCheck.data_too_large,
        HealthCheck.large_base_example,
    ],
)
FUZZ = settings(max_examples=EXAMPLES, **_COMMON)
#: Mutations of the multi-megabyte real files: each example writes and parses megabytes.
FUZZ_LARGE = settings(max_examples=max(5, EXAMPLES // 10), **_COMMON)
#: Headers that declare huge sizes may make a reader allocate at most this much.
MEMORY_BOUND = 64 * 2**20

MAP_SUFFIXES = (".txt", ".xyz", ".npy", ".gwy", ".ibw", ".nid")
HOSTILE_CELLS = (
    "nan", "NaN", "inf", "-inf", "-1", "0", "-0", "1e308", "-1e308", "1e400", "1e-320",
    "", "x", "1e", "-", ".", "1,5", "0x10", "١", "µ", "\u2028", "\x85", "\x00", "1" * 400,
)  # fmt: skip
HOSTILE_UNITS = (
    "nm", "um", "µm", "m", "", "?", "s", "V", "deg", "nm^2", "1/nm", "m^-2", "N/m",
    "Å", "A", "kg", "%", "nm " * 50, "(nm)", "[nm]", "\ufffd", "n\u200bm", "1" * 5000,
)  # fmt: skip
HUGE_INTS = (0, -1, 1, 2, 3, 2**15, 2**16 - 1, 2**31 - 1, -(2**31), 2**32 - 1, 10**6, 10**12)
HOSTILE_FLOATS = (0.0, -0.0, -1.0, math.nan, math.inf, -math.inf, 1e308, 1e-320, 1e-9, 1.0)


# -- the property --------------------------------------------------------------------------


def one_line(message: str) -> bool:
    return message.splitlines() == [message] and "\r" not in message


def assert_refused_cleanly(err: MCSimError, name: str) -> None:
    message = str(err)
    assert one_line(message), f"not one line: {message!r}"
    assert name in message, f"message does not name {name!r}: {message!r}"


def assert_sane_map(hmap: HeightMap) -> None:
    z = hmap.heights
    assert z.ndim == 2 and min(z.shape) >= 3 and z.size <= MAX_PIXELS
    assert z.dtype == np.float64
    assert not np.any(np.isinf(z)), "infinite heights"
    assert np.any(np.isfinite(z))
    for pitch in (hmap.dx, hmap.dy):
        assert isinstance(pitch, float) and math.isfinite(pitch) and pitch > 0, pitch


def check_map(path: Path, **options) -> None:
    """Read ``path`` as a height map: a sane map or a clean refusal."""
    try:
        hmap = read_height_map(path, **options)
    except MCSimError as err:
        assert_refused_cleanly(err, path.name)
        return
    assert_sane_map(hmap)


def check_histogram(path: Path, unit: str | None = None) -> None:
    """Read ``path`` as a histogram and standardize it: sane values or a clean refusal."""
    try:
        hist = read_histogram(path, unit=unit)
        edges, weights = hist.edges, hist.weights
        assert np.all(np.isfinite(edges)) and np.all(np.diff(edges) > 0)
        assert np.all(np.isfinite(weights)) and np.all(weights >= 0) and np.any(weights > 0)
        emp = hist.to_empirical()
    except MCSimError as err:
        assert_refused_cleanly(err, path.name)
        return
    assert math.isfinite(emp.sigma) and emp.sigma > 0 and math.isfinite(emp.mean)


@contextlib.contextmanager
def bounded_memory():
    """Fail with MemoryError past 2 GB more address space; assert a traced peak < MEMORY_BOUND."""
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    with open("/proc/self/statm") as f:
        used = int(f.read().split()[0]) * resource.getpagesize()
    limit = used + 2 * 2**30
    if hard != resource.RLIM_INFINITY:
        limit = min(limit, hard)
    resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    tracemalloc.start()
    try:
        yield
        peak = tracemalloc.get_traced_memory()[1]
        assert peak < MEMORY_BOUND, f"reading allocated {peak / 2**20:.0f} MiB"
    finally:
        tracemalloc.stop()
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


# -- seeds: small valid files and the real sample files ---------------------------------------


def npy_bytes(a: np.ndarray) -> bytes:
    import io

    buf = io.BytesIO()
    np.save(buf, a)
    return buf.getvalue()


def small_map(rows: int = 6, cols: int = 7) -> np.ndarray:
    y, x = np.mgrid[0:rows, 0:cols]
    return np.sin(x * 1.3) * np.cos(y * 0.7) + 0.1 * x


def gwy_bytes(
    data=None, xreal=5e-6, yreal=5e-6, unit_xy="m", unit_z="m", title="Height", **override
) -> bytes:
    import io

    from gwyfile.objects import GwyContainer, GwyDataField, GwySIUnit

    field = GwyDataField(
        small_map() if data is None else data,
        xreal=xreal,
        yreal=yreal,
        si_unit_xy=GwySIUnit(unitstr=unit_xy),
        si_unit_z=GwySIUnit(unitstr=unit_z),
    )
    field.update(override)
    container = GwyContainer()
    container["/0/data/title"] = title
    container["/0/data"] = field
    buf = io.BytesIO()
    container.tofile(buf)
    return buf.getvalue()


#: Byte offsets in an Igor binary wave, version 5 (BinHeader5 is 64 bytes; WaveHeader5 follows).
IBW_WFM_SIZE, IBW_NPNTS, IBW_TYPE, IBW_NDIM, IBW_SFA = 4, 64 + 12, 64 + 16, 64 + 68, 64 + 84
IBW_HEADER = 64 + 320


def small_ibw(real: bytes, rows: int = 8, cols: int = 8) -> bytes:
    """The real Asylum wave cropped to rows × cols pixels: its header, note and labels kept."""
    (wfm_size,) = struct.unpack_from("<l", real, IBW_WFM_SIZE)
    _, _, layers, _ = struct.unpack_from("<4l", real, IBW_NDIM)
    assert struct.unpack_from("<h", real, IBW_TYPE) == (2,)  # float32
    head = bytearray(real[:IBW_HEADER])
    data = np.tile(small_map(rows, cols).T[:, :, None], (1, 1, layers)).astype("<f4")
    struct.pack_into("<l", head, IBW_WFM_SIZE, 320 + data.nbytes)
    struct.pack_into("<l", head, IBW_NPNTS, data.size)
    struct.pack_into("<4l", head, IBW_NDIM, cols, rows, layers, 0)
    return bytes(head) + data.tobytes(order="F") + real[64 + wfm_size :]


def small_nid(real: bytes, points: int = 8, lines: int = 8) -> bytes:
    """The real Nanosurf file with every channel cropped to points × lines."""
    marker = real.find(b"#!")
    header = real[:marker].decode("latin-1")
    header = re.sub(r"(?m)^Points=\d+", f"Points={points}", header)
    header = re.sub(r"(?m)^Lines=\d+", f"Lines={lines}", header)
    bits = [int(b) for b in re.findall(r"(?m)^SaveBits=(\d+)", header)]
    rng = np.random.default_rng(0)
    blocks = [
        rng.integers(-(2 ** (b - 1)), 2 ** (b - 1), points * lines).astype(f"<i{b // 8}").tobytes()
        for b in bits
    ]
    return header.encode("latin-1") + b"#!" + b"".join(blocks)


HIST_TEXT = "# Height distribution\nz [nm], count\n-1.5, 2\n-0.5, 7\n0.5, 9\n1.5, 3\n"
HIST3_TEXT = "left [um]\tright [um]\tdensity [1/um]\n0\t1\t0.2\n1\t2\t0.5\n2\t3\t0.3\n"
MATRIX_TEXT = (
    "# Channel: Topography\n# Width: 5.000 µm\n# Height: 4.000 µm\n# Value units: m\n"
    + "\n".join("\t".join(f"{v:.6e}" for v in row) for row in 1e-9 * small_map())
    + "\n"
)
XYZ_TEXT = "\n".join(f"{x * 10.0} {y * 10.0} {z}" for (y, x), z in np.ndenumerate(small_map(4, 5)))
SURFACE_TOML = 'name = "s"\nsigma = "1.4 nm"\nR = "1.7 um"\neta = "17 um^-2"\n'
MATERIAL_TOML = 'E = "160 GPa"\nnu = 0.22\ngamma = "0.5 J/m^2"\nH = "12.5 GPa"\n'


class Seeds(dict):
    """Seed files by suffix, with a short repr for Hypothesis' failure reports."""

    def __repr__(self) -> str:
        return f"<seed files {', '.join(self)}>"


@pytest.fixture(scope="module")
def seeds(afm_resources, nid_files) -> Seeds:
    """Small valid files of every format, most derived from the real sample files."""
    ibw = (afm_resources / "sample_0.ibw").read_bytes()
    nid = nid_files["circles"].read_bytes()
    return Seeds(
        {
            ".csv": HIST_TEXT.encode(),
            ".tsv": HIST3_TEXT.encode(),
            ".txt": MATRIX_TEXT.encode(),
            ".xyz": XYZ_TEXT.encode(),
            ".npy": npy_bytes(small_map()),
            ".gwy": gwy_bytes(),
            ".ibw": small_ibw(ibw),
            ".nid": small_nid(nid),
            ".toml": f"[surface]\n{SURFACE_TOML}\n[material]\n{MATERIAL_TOML}".encode(),
        }
    )


def test_seeds_are_valid(seeds, tmp_path):
    """The unmutated seeds read: the mutations start from valid files."""
    for suffix, options in [
        (".txt", {}),
        (".xyz", {"unit": "nm"}),
        (".npy", {"unit": "nm", "pixel_size": 1e-8}),
        (".gwy", {}),
        (".ibw", {}),
        (".nid", {}),
    ]:
        path = tmp_path / f"seed{suffix}"
        path.write_bytes(seeds[suffix])
        assert_sane_map(read_height_map(path, **options))
    for suffix in (".csv", ".tsv"):
        path = tmp_path / f"seed{suffix}"
        path.write_bytes(seeds[suffix])
        read_histogram(path).to_empirical()
    path = tmp_path / "seed.toml"
    path.write_bytes(seeds[".toml"])
    assert isinstance(load_surface(path), Surface) and isinstance(load_material(path), Material)


# -- strategies ------------------------------------------------------------------------------


@st.composite
def mutated(draw, seed: bytes, focus: int = 4096) -> bytes:
    """``seed`` with 1–4 bit flips, truncations, insertions, deletions or overwritten words.

    Half of the positions fall in the first ``focus`` bytes, where the headers are.
    """
    data = bytearray(seed)
    for _ in range(draw(st.integers(1, 4))):
        limit = len(data) if draw(st.booleans()) else min(len(data), focus)
        pos = draw(st.integers(0, limit))
        kind = draw(st.sampled_from(["flip", "truncate", "insert", "delete", "word", "byte"]))
        if kind == "truncate":
            del data[pos:]
        elif kind == "insert":
            data[pos:pos] = draw(st.binary(min_size=1, max_size=16))
        elif kind == "delete":
            del data[pos : pos + draw(st.integers(1, 64))]
        elif pos < len(data) and kind == "flip":
            data[pos] ^= 1 << draw(st.integers(0, 7))
        elif pos < len(data) and kind == "byte":
            data[pos] = draw(st.sampled_from([0, 0x7F, 0x80, 0xFF, ord("S"), ord("O"), 0x0A]))
        elif kind == "word":
            word = draw(st.sampled_from(HUGE_INTS))
            data[pos : pos + 4] = (word % 2**32).to_bytes(
                4, draw(st.sampled_from(["little", "big"]))
            )
    return bytes(data)


def random_bytes(prefix: bytes = b"") -> st.SearchStrategy[bytes]:
    """Random bytes, optionally after a format's magic bytes (to get past detection)."""
    return st.binary(max_size=2048).map(lambda b: prefix + b)


def encoded(text: st.SearchStrategy[str]) -> st.SearchStrategy[bytes]:
    """Text as UTF-8, Latin-1, UTF-16 or with invalid UTF-8 bytes spliced in."""

    def encode(pair):
        s, how = pair
        if how == "utf-16":
            return s.encode("utf-16")
        if how == "latin-1":
            return s.encode("latin-1", errors="replace")
        if how == "broken":
            return s.encode("utf-8", errors="replace").replace(b"\n", b"\xff\xfe\n", 1)
        return s.encode("utf-8", errors="surrogatepass")

    return st.tuples(text, st.sampled_from(["utf-8", "latin-1", "utf-16", "broken"])).map(encode)


def cells() -> st.SearchStrategy[str]:
    return st.one_of(
        st.sampled_from(HOSTILE_CELLS),
        st.floats(allow_nan=True, allow_infinity=True).map(repr),
        st.integers(-(10**30), 10**30).map(str),
        st.text(max_size=8),
    )


@st.composite
def hostile_table_text(draw, columns: st.SearchStrategy[int]) -> str:
    """Rows of cells with hostile values, after a header that may name a unit."""
    header = draw(
        st.lists(
            st.one_of(
                st.sampled_from(HOSTILE_UNITS).map(lambda u: f"z [{u}], count"),
                st.sampled_from(HOSTILE_UNITS).map(lambda u: f"# Value units: {u}"),
                st.tuples(
                    st.sampled_from(["Width", "Height"]), cells(), st.sampled_from(HOSTILE_UNITS)
                ).map(lambda t: f"# {t[0]}: {t[1]} {t[2]}"),
                st.text(max_size=40),
                st.just("(" * 3000 + "x"),
                st.just("# Width: " + "1" * 3000 + " a b"),
            ),
            max_size=4,
        )
    )
    n_rows = draw(st.integers(0, 8))
    width = draw(columns)
    sep = draw(st.sampled_from([", ", "\t", " ", ";", ",,", "  \t "]))
    rows = [sep.join(draw(cells()) for _ in range(width)) for _ in range(n_rows)]
    return "\n".join(header + rows) + draw(st.sampled_from(["\n", "", "\r\n", "\x00"]))


@st.composite
def numeric_table_text(draw, columns: int) -> str:
    """A valid-looking numeric table whose values may be extreme, unordered or non-finite."""
    n_rows = draw(st.integers(1, 12))
    value = st.one_of(st.sampled_from(HOSTILE_FLOATS), st.floats(-1e300, 1e300))
    rows = [", ".join(repr(draw(value)) for _ in range(columns)) for _ in range(n_rows)]
    return "z [nm], count\n" + "\n".join(rows) + "\n"


# -- histograms and text maps ------------------------------------------------------------------


@FUZZ
@given(data=st.one_of(random_bytes(), encoded(hostile_table_text(st.integers(1, 4)))))
def test_histogram_reader_survives_hostile_text(tmp_path_factory, data):
    path = tmp_path_factory.mktemp("h") / "h.csv"
    path.write_bytes(data)
    check_histogram(path)


@FUZZ
@given(data=st.integers(2, 3).flatmap(numeric_table_text), unit=st.sampled_from(HOSTILE_UNITS))
def test_histogram_reader_survives_extreme_values(tmp_path_factory, data, unit):
    path = tmp_path_factory.mktemp("h") / "h.hist"
    path.write_text(data, encoding="utf-8")
    check_histogram(path, unit=unit)


@FUZZ
@given(data=st.data())
def test_histogram_reader_survives_mutations(seeds, tmp_path_factory, data):
    suffix = data.draw(st.sampled_from([".csv", ".tsv"]))
    path = tmp_path_factory.mktemp("h") / f"h{suffix}"
    path.write_bytes(data.draw(mutated(seeds[suffix])))
    check_histogram(path)


@FUZZ
@given(
    data=st.one_of(random_bytes(), encoded(hostile_table_text(st.integers(1, 8)))),
    unit=st.sampled_from((None, "nm", "m", "s", "")),
    pixel_size=st.sampled_from((None, 1e-8, (1e-8, 2e-8))),
)
def test_matrix_reader_survives_hostile_text(tmp_path_factory, data, unit, pixel_size):
    path = tmp_path_factory.mktemp("m") / "m.txt"
    path.write_bytes(data)
    check_map(path, unit=unit, pixel_size=pixel_size)


@FUZZ
@given(data=st.data())
def test_matrix_and_xyz_readers_survive_mutations(seeds, tmp_path_factory, data):
    suffix = data.draw(st.sampled_from([".txt", ".xyz"]))
    path = tmp_path_factory.mktemp("m") / f"m{suffix}"
    path.write_bytes(data.draw(mutated(seeds[suffix])))
    check_map(path, unit=data.draw(st.sampled_from(("nm", None))))


@FUZZ
@given(data=st.one_of(random_bytes(), encoded(hostile_table_text(st.integers(1, 4)))))
def test_xyz_reader_survives_hostile_text(tmp_path_factory, data):
    path = tmp_path_factory.mktemp("m") / "m.xyz"
    path.write_bytes(data)
    check_map(path, unit="um")


@FUZZ
@given(
    points=st.lists(
        st.tuples(*[st.sampled_from((*HOSTILE_FLOATS, 10.0, 20.0, 30.0))] * 3), max_size=30
    )
)
def test_xyz_reader_survives_hostile_coordinates(tmp_path_factory, points):
    path = tmp_path_factory.mktemp("m") / "m.xyz"
    path.write_text("\n".join(" ".join(repr(v) for v in p) for p in points), encoding="utf-8")
    check_map(path, unit="nm")


# -- binary map formats ------------------------------------------------------------------------


@FUZZ
@given(data=st.data())
def test_binary_readers_survive_random_bytes(tmp_path_factory, data):
    suffix, magic = data.draw(
        st.sampled_from(
            [(".npy", b"\x93NUMPY"), (".gwy", b"GWYP"), (".ibw", b"\x05\x00"),
             (".ibw", b"\x00\x02"), (".nid", b"[DataSet]\r\n"), (".gwy", b"")]
        )
    )  # fmt: skip
    path = tmp_path_factory.mktemp("b") / f"b{suffix}"
    path.write_bytes(data.draw(random_bytes(magic)))
    check_map(path, unit="nm", pixel_size=1e-8)


@FUZZ
@given(data=st.data())
def test_binary_readers_survive_mutated_small_files(seeds, tmp_path_factory, data):
    suffix = data.draw(st.sampled_from([".npy", ".gwy", ".ibw", ".nid"]))
    path = tmp_path_factory.mktemp("b") / f"b{suffix}"
    path.write_bytes(data.draw(mutated(seeds[suffix], focus=1024 if suffix != ".nid" else 6000)))
    check_map(path, unit="nm", pixel_size=1e-8)


@FUZZ_LARGE
@given(data=st.data())
def test_binary_readers_survive_mutated_real_files(
    afm_resources, nid_files, tmp_path_factory, data
):
    source = data.draw(
        st.sampled_from(
            [afm_resources / "sample_0.gwy", afm_resources / "sample_0.ibw",
             nid_files["circles"], nid_files["thermal"], nid_files["spectroscopy"]]
        )
    )  # fmt: skip
    path = tmp_path_factory.mktemp("r") / source.name
    path.write_bytes(data.draw(mutated(source.read_bytes(), focus=8192)))
    check_map(path)


def npy_header(descr: str, fortran: bool, shape: tuple) -> bytes:
    header = repr({"descr": descr, "fortran_order": fortran, "shape": shape}).encode()
    header += b" " * (63 - (len(header) + 10) % 64) + b"\n"
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header


@FUZZ
@given(
    descr=st.sampled_from(["<f8", ">f4", "<i2", "|b1", "<c16", "|O", "<U8", "|V8", "<M8[s]", "xx"]),
    fortran=st.booleans(),
    shape=st.one_of(
        st.lists(st.sampled_from(HUGE_INTS), min_size=0, max_size=4).map(tuple),
        st.sampled_from([(10**6, 10**6), (2**31, 2**31), (3, -3), (2**63, 2)]),
    ),
    payload=st.binary(max_size=512),
)
def test_npy_reader_refuses_hostile_headers_without_allocating(
    tmp_path_factory, descr, fortran, shape, payload
):
    path = tmp_path_factory.mktemp("n") / "n.npy"
    path.write_bytes(npy_header(descr, fortran, shape) + payload)
    with bounded_memory():
        check_map(path, unit="nm", pixel_size=1e-8)


@FUZZ
@given(
    field=st.sampled_from(["Points", "Lines", "SaveBits", "Dim0Range", "Dim1Range", "Dim2Range",
                           "Dim2Min", "Dim0Unit", "Dim2Unit", "GroupCount", "Gr0-Count",
                           "SaveOrder", "Frame", "Dim2Name"]),
    value=st.one_of(st.sampled_from(HOSTILE_CELLS + HOSTILE_UNITS),
                    st.sampled_from(HUGE_INTS).map(str)),
)  # fmt: skip
def test_nid_reader_refuses_hostile_header_values(seeds, tmp_path_factory, field, value):
    raw = seeds[".nid"]
    marker = raw.find(b"#!")
    header = re.sub(
        rf"(?m)^{re.escape(field)}=[^\r\n]*",
        lambda _: f"{field}={value}",
        raw[:marker].decode("latin-1"),
        count=99,
    )
    path = tmp_path_factory.mktemp("n") / "n.nid"
    path.write_bytes(header.encode("utf-8", errors="replace") + raw[marker:])
    with bounded_memory():
        check_map(path)


@FUZZ
@given(
    offset=st.sampled_from(
        [IBW_WFM_SIZE, 8, 12, 16, 20, 36, 44, IBW_NPNTS, IBW_NDIM, IBW_NDIM + 4, IBW_NDIM + 8]
    ),
    value=st.sampled_from(HUGE_INTS),
    wave_type=st.sampled_from([None, 0, 1, 2, 3, 4, 8, 0x10, 0x20, 0x48, 0x60, 0x99]),
    sfa=st.sampled_from((None, *HOSTILE_FLOATS)),
)
def test_ibw_reader_refuses_hostile_header_values(
    seeds, tmp_path_factory, offset, value, wave_type, sfa
):
    raw = bytearray(seeds[".ibw"])
    struct.pack_into("<L", raw, offset, value % 2**32)
    if wave_type is not None:
        struct.pack_into("<h", raw, IBW_TYPE, wave_type)
    if sfa is not None:
        struct.pack_into("<d", raw, IBW_SFA, sfa)
    path = tmp_path_factory.mktemp("i") / "i.ibw"
    path.write_bytes(bytes(raw))
    with bounded_memory():
        check_map(path)


@FUZZ
@given(
    xreal=st.sampled_from(HOSTILE_FLOATS),
    yreal=st.sampled_from(HOSTILE_FLOATS),
    units=st.tuples(st.sampled_from(HOSTILE_UNITS), st.sampled_from(HOSTILE_UNITS)),
    title=st.sampled_from(["Height", "Topography", "Phase", "line\nbreak", "\x85", ""]),
    res=st.sampled_from([None, (0, 0), (7, 6), (6, 7), (10**6, 10**6), (2**31 - 1, 2), (-1, -42)]),
    values=st.sampled_from(["map", "nan", "inf", "tiny", "huge"]),
)
def test_gwy_reader_refuses_hostile_fields(
    tmp_path_factory, xreal, yreal, units, title, res, values
):
    data = {
        "map": small_map(),
        "nan": np.full((6, 7), np.nan),
        "inf": np.where(small_map() > 0, np.inf, 1.0),
        "tiny": small_map() * 1e-320,
        "huge": small_map() * 1e308,
    }[values]
    override = {} if res is None else {"xres": res[0], "yres": res[1]}
    raw = gwy_bytes(data, xreal, yreal, *units, title=title, **override)
    path = tmp_path_factory.mktemp("g") / "g.gwy"
    path.write_bytes(raw)
    with bounded_memory():
        check_map(path)


# -- the surface and material file parser ----------------------------------------------------

toml_scalars = st.one_of(
    st.sampled_from(["1.4 nm", "17 um^-2", "160 GPa", "0.5 J/m^2", "gaussian", "h.csv", ""]),
    st.tuples(
        st.sampled_from(HOSTILE_CELLS[:16]), st.sampled_from((*HOSTILE_UNITS, "GPa", "J/m^2"))
    ).map(" ".join),
    st.text(max_size=20),
    st.integers(-(2**63), 2**63 - 1),
    st.floats(),
    st.booleans(),
)
toml_values = st.recursive(
    toml_scalars,
    lambda inner: st.one_of(
        st.lists(inner, max_size=4),
        st.dictionaries(st.sampled_from(["file", "edges", "counts", "densities", "unit", "x"]),
                        inner, max_size=4),
    ),
    max_leaves=12,
)  # fmt: skip
SURFACE_KEYS = ["name", "sigma", "R", "eta", "heights", "combine", "extra"]
MATERIAL_KEYS = ["name", "E", "nu", "E1", "E2", "nu1", "nu2", "gamma", "H", "extra"]


def toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, float):
        return {"nan": "nan", "inf": "inf", "-inf": "-inf"}.get(repr(value), repr(value))
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k} = {toml_value(v)}" for k, v in value.items()) + "}"
    return str(value)


def toml_table(name: str, table: dict) -> str:
    return f"[{name}]\n" + "".join(f"{k} = {toml_value(v)}\n" for k, v in table.items())


def check_config(path: Path) -> None:
    for load, kind in ((load_surface, Surface), (load_material, Material)):
        try:
            result = load(path)
        except MCSimError as err:
            assert_refused_cleanly(err, path.name)
            continue
        assert isinstance(result, kind)
        numbers = (
            (result.sigma, result.R, result.eta) if kind is Surface else (result.E1, result.E2)
        )
        assert all(math.isfinite(v) and v > 0 for v in numbers), result


@FUZZ
@given(
    surface=st.dictionaries(st.sampled_from(SURFACE_KEYS), toml_values, max_size=6),
    material=st.dictionaries(st.sampled_from(MATERIAL_KEYS), toml_values, max_size=8),
)
def test_config_parser_survives_wrong_types_and_units(tmp_path_factory, surface, material):
    folder = tmp_path_factory.mktemp("c")
    (folder / "h.csv").write_text(HIST_TEXT, encoding="utf-8")
    path = folder / "s.toml"
    text = toml_table("surface", surface) + toml_table("material", material)
    path.write_text(text, encoding="utf-8")
    check_config(path)


@FUZZ
@given(data=st.data())
def test_config_parser_survives_mutations_and_random_bytes(seeds, tmp_path_factory, data):
    path = tmp_path_factory.mktemp("c") / "s.toml"
    path.write_bytes(
        data.draw(st.one_of(random_bytes(), mutated(seeds[".toml"]), encoded(st.text())))
    )
    check_config(path)


@FUZZ
@given(
    table=st.dictionaries(st.sampled_from(SURFACE_KEYS + MATERIAL_KEYS), toml_values, max_size=6)
)
def test_tables_from_other_sources_survive_wrong_types(table):
    for build in (surface_from_table, material_from_table):
        try:
            build(table, where="here")
        except MCSimError as err:
            assert_refused_cleanly(err, "here")


@FUZZ
@given(
    value=st.one_of(toml_scalars, st.none(), st.lists(st.integers()), st.text()),
    dimension=st.sampled_from(
        ["length", "area", "density", "pressure", "energy_per_area", "dimensionless"]
    ),
)
def test_parse_quantity_survives_hostile_values(value, dimension):
    try:
        result = parse_quantity(value, dimension, "field")
    except MCSimError as err:
        assert_refused_cleanly(err, "field")
        return
    assert isinstance(result, float) and math.isfinite(result)


@FUZZ
@given(
    data=st.dictionaries(
        st.sampled_from(["schema", "edges", "densities", "sigma", "mean", "source"]),
        st.one_of(toml_values, st.none(), st.just("mcsim.empirical/1")),
    )
)
def test_stored_empirical_distribution_survives_hostile_dicts(data):
    with contextlib.suppress(MCSimError):
        Empirical.from_dict(data)


# -- the command line --------------------------------------------------------------------------

CLI_FILES = {
    "random.gwy": b"GWYP" + bytes(range(256)) * 4,
    "huge.npy": npy_header("<f8", False, (10**6, 10**6)),
    "truncated.nid": b"[DataSet]\r\nVersion=2\r\nGroupCount=1\r\n",
    "binary.csv": b"\xff\xfe\x00\x01",
    "nan.csv": b"z [nm], count\nnan, 1\n1, 2\n",
    "latin1.txt": "# Value units: µm\n1 2 3\n".encode("latin-1"),
    "flat.txt": b"1 1 1\n1 1 1\n1 1 1\n",
    "empty.xyz": b"",
    "version.ibw": b"\x05\x00" + b"\xff" * 500,
}


@pytest.mark.parametrize("name", sorted(CLI_FILES))
def test_ingest_command_refuses_hostile_files_in_one_line(tmp_path, capsys, name):
    path = tmp_path / name
    path.write_bytes(CLI_FILES[name])
    options = ["--unit", "nm", "--pixel-size", "10nm"]
    status = cli.main(["ingest", str(path), "--out", str(tmp_path / "out.toml"), *options])
    err = capsys.readouterr().err
    assert status == 2
    assert "Traceback" not in err
    assert err.startswith("mcsim: error: ") and err.count("\n") == 1, err
    assert name in err


# -- regressions: inputs the fuzzing found, one test each -------------------------------------


def test_npy_with_broken_header_length_is_refused(tmp_path):
    raw = bytearray(npy_bytes(small_map()))
    raw[8] ^= 1  # header length: numpy's parser raised tokenize.TokenError
    path = tmp_path / "m.npy"
    path.write_bytes(bytes(raw))
    with pytest.raises(MCSimError, match=r"m.npy: not a readable .npy array"):
        read_height_map(path, unit="nm", pixel_size=1e-8)


def test_npy_declaring_a_trillion_pixels_is_refused_by_the_cap(tmp_path):
    path = tmp_path / "m.npy"
    path.write_bytes(npy_header("<f8", False, (10**6, 10**6)))
    with pytest.raises(MCSimError, match=r"more than the limit of 268435456"):
        read_height_map(path, unit="nm", pixel_size=1e-8)


def test_npy_with_negative_shape_is_refused(tmp_path):
    path = tmp_path / "m.npy"
    path.write_bytes(npy_header("<f8", False, (3, -3)))
    with pytest.raises(MCSimError, match=r"needs a 2-D array, got shape"):
        read_height_map(path, unit="nm", pixel_size=1e-8)


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("Dim0Range", "", "Dim0Range='' is not a number"),
        ("Dim0Range", "nan", "Dim0Range=nan is not finite"),
        ("Points", "-8", "Points=-8 is negative"),
        ("Lines", "x", "Lines='x' is not an integer"),
        ("Points", "100000000", "more than the limit"),
    ],
)
def test_nid_with_bad_header_value_is_refused(seeds, tmp_path, field, value, message):
    raw = seeds[".nid"]
    marker = raw.find(b"#!")
    header = re.sub(rf"(?m)^{field}=[^\r\n]*", f"{field}={value}", raw[:marker].decode("latin-1"))
    path = tmp_path / "m.nid"
    path.write_bytes(header.encode("latin-1") + raw[marker:])
    with bounded_memory(), pytest.raises(MCSimError, match=f"m.nid: .*{re.escape(message)}"):
        read_height_map(path)


def test_nid_with_a_huge_group_count_reads_without_looping_over_it(seeds, tmp_path):
    raw = seeds[".nid"]
    path = tmp_path / "m.nid"
    path.write_bytes(raw.replace(b"GroupCount=2", b"GroupCount=1000000000000", 1))
    assert read_height_map(path).shape == (8, 8)  # used to loop 10^12 times


def test_ibw_declaring_a_2_gb_wave_is_refused_before_igor2_allocates(seeds, tmp_path):
    raw = bytearray(seeds[".ibw"])
    struct.pack_into("<l", raw, IBW_WFM_SIZE, 2**31 - 1)
    path = tmp_path / "m.ibw"
    path.write_bytes(bytes(raw))
    with bounded_memory(), pytest.raises(MCSimError, match=r"m.ibw: not a readable .*truncated"):
        read_height_map(path)


def test_gwy_channel_title_with_a_line_break_stays_on_one_line(tmp_path):
    path = tmp_path / "m.gwy"
    path.write_bytes(gwy_bytes(title="line\nbreak", unit_z="V"))
    with pytest.raises(MCSimError) as err:
        read_height_map(path)
    assert one_line(str(err.value)) and "'line\\nbreak'" in str(err.value)


def test_gwy_with_zero_width_is_refused(tmp_path):
    path = tmp_path / "m.gwy"
    path.write_bytes(gwy_bytes(xreal=0.0))
    with pytest.raises(MCSimError, match=r"m.gwy: pixel size dx = 0.0 m: must be positive"):
        read_height_map(path)


def test_infinite_heights_become_nan_pixels(tmp_path):
    path = tmp_path / "m.npy"
    path.write_bytes(npy_bytes(np.where(small_map() > 0.5, np.inf, small_map())))
    hmap = read_height_map(path, unit="nm", pixel_size=1e-8)
    assert np.isnan(hmap.heights).any() and not np.isinf(hmap.heights).any()


def test_empirical_from_incomplete_dict_is_refused():
    with pytest.raises(MCSimError, match=r"lacks densities, edges, mean, sigma"):
        Empirical.from_dict({"schema": "mcsim.empirical/1"})


def test_matrix_header_width_that_is_not_a_number_is_refused(tmp_path):
    path = tmp_path / "m.txt"
    path.write_text("# Width: 1e nm\n# Height: 1 nm\n1 2 3\n4 5 6\n7 8 9\n", encoding="utf-8")
    with pytest.raises(MCSimError, match=r"m.txt: cannot read '# Width: 1e nm': not a number"):
        read_height_map(path, unit="nm")


def test_xyz_with_nan_coordinates_is_refused(tmp_path):
    path = tmp_path / "m.xyz"
    points = [(x, y, 1.0) for x in (0.0, 1.0, math.nan) for y in (0.0, 1.0, 2.0)]
    path.write_text("\n".join(f"{x} {y} {z}" for x, y, z in points), encoding="utf-8")
    with pytest.raises(MCSimError, match=r"m.xyz: x and y must be finite"):
        read_height_map(path, unit="nm")


def test_histogram_whose_edges_overflow_is_refused(tmp_path):
    path = tmp_path / "h.csv"
    path.write_text("z [m], n\n-1e308, 1\n1e308, 1\n", encoding="utf-8")
    with pytest.raises(MCSimError, match=r"h.csv: bin edges overflow"):
        read_histogram(path)


@pytest.mark.parametrize(
    "text",
    ["(" * 100_000 + "x\n0, 1\n1, 1\n", "# Width: " + "1" * 100_000 + " a b\n1 2 3\n"],
)
def test_long_header_lines_are_parsed_in_linear_time(tmp_path, text):
    path = tmp_path / "h.csv"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(MCSimError):  # used to backtrack for minutes
        read_height_map(path, unit="nm")
    with pytest.raises(MCSimError):
        read_histogram(path)


@pytest.mark.parametrize("value", ["1 " + " " * 100_000 + "x", "1 m^" + "1" * 5000])
def test_parse_quantity_refuses_long_units_quickly(value):
    with pytest.raises(MCSimError, match=r"field: unknown unit"):
        parse_quantity(value, "length", "field")


@pytest.mark.parametrize(
    ("heights", "message"),
    [
        ({"edges": "abc", "counts": [1, 2]}, "edges must be a list of numbers"),
        ({"edges": 5, "counts": [1, 2]}, "edges must be a list of numbers"),
        ({"file": 5}, "file must be a string"),
        ({"file": "h.csv", "unit": 3}, "unit must be a string"),
        ({"file": "h\x00.csv"}, "not a valid file name"),
    ],
)
def test_heights_table_with_wrong_types_is_refused(tmp_path, heights, message):
    table = {"sigma": "1 nm", "R": "1 um", "eta": "1 um^-2", "heights": heights}
    with pytest.raises(MCSimError, match=re.escape(message)):
        surface_from_table(table, where="here", base_dir=tmp_path)


def test_surface_files_that_combine_each_other_are_refused(tmp_path):
    path = tmp_path / "a.toml"
    path.write_text('[surface]\ncombine = ["a.toml", "a.toml"]\neta = "1 um^-2"\n')
    with pytest.raises(MCSimError, match=r"a.toml: combine: the surface files include each other"):
        load_surface(path)


def test_deeply_nested_toml_is_refused(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text("x = " + "[" * 100_000 + "]" * 100_000 + "\n")
    with pytest.raises(MCSimError, match=r"s.toml: not a valid TOML file"):
        load_surface(path)


def test_histogram_whose_counts_overflow_their_sum_is_standardized():
    emp = Empirical.from_histogram([-0.5e-18, 0.5e-18, 1.5e-18], [1e308, 1e308])
    assert emp.sigma == pytest.approx(np.sqrt(1 / 3) * 1e-18, rel=1e-12)  # the sum overflows


def test_histogram_file_whose_counts_overflow_their_sum_is_refused(tmp_path):
    path = tmp_path / "h.csv"
    path.write_text("z [nm], count\n0.0, 1e308\n1e-09, 1e308\n", encoding="utf-8")
    with pytest.raises(MCSimError, match=r"h.csv: the counts add up to more than the largest"):
        read_histogram(path)  # `mcsim ingest` raised OverflowError on the total count


def test_histogram_whose_edges_underflow_in_metres_is_refused(tmp_path):
    path = tmp_path / "h.csv"
    path.write_text("z [nm], count\n0, 1\n1e-320, 1\n2e-320, 1\n", encoding="utf-8")
    with pytest.raises(MCSimError, match=r"h.csv: bin edges overflow or collapse"):
        read_histogram(path)


def test_gwy_with_a_huge_string_array_count_is_refused_quickly(tmp_path):
    body = b"t\x00S" + struct.pack("<I", 2**32 - 1) + b"a\x00" * 8
    path = tmp_path / "m.gwy"
    path.write_bytes(b"GWYPGwyContainer\x00" + struct.pack("<I", len(body)) + body)
    with bounded_memory(), pytest.raises(MCSimError, match=r"m.gwy: not a readable Gwyddion"):
        read_height_map(path)  # gwyfile looped over the 4e9 declared strings


def test_histogram_file_name_with_a_line_break_stays_on_one_line(tmp_path):
    with pytest.raises(MCSimError) as err:
        surface_from_table({"R": "1 um", "eta": "1 um^-2", "heights": "a\rb.csv"}, where="here")
    assert one_line(str(err.value)) and "a\\rb.csv" in str(err.value)


# -- run files: byte flips, truncations and crafted headers ------------------------------------
#
# A run file carries a SHA-256 checksum over every dataset (name, shape, dtype, bytes) and
# every attribute, checked on every read; what it does not cover is HDF5's own metadata
# (superblock, object headers, B-trees, heaps), where a flip either breaks the file's
# structure (h5py raises) or changes nothing that is read. So every mutated run file
# must either be refused with a one-line RunFileError naming it, or read back exactly.
# A campaign: ``MCSIM_FUZZ_EXAMPLES=300 pytest tests/program/test_fuzz.py -k run_files
# --hypothesis-show-statistics`` (the statistics count the outcomes).

RUNFILE = settings(max_examples=max(EXAMPLES, 30), **_COMMON)


class RunSeeds(dict):
    def __repr__(self) -> str:
        return f"<run files {', '.join(self)}>"


@pytest.fixture(scope="module")
def run_files(tmp_path_factory) -> RunSeeds:
    """A complete run with kept heights and an incomplete checkpoint, as bytes."""
    from mcsim.engine.montecarlo import EnsembleSums, run_sums
    from mcsim.engine.spec import MonteCarloSpec
    from mcsim.model.presets import MATERIALS, SURFACES
    from mcsim.store.runfile import write_checkpoint
    from mcsim.studies.simulation import simulate

    folder = tmp_path_factory.mktemp("runs")
    surface, material = SURFACES["smooth"], MATERIALS["silicon"]
    simulate(surface, material, [2.0, 0.0, -1.0], "2 um^2", realizations=2, seed=5,
             out=folder / "complete.h5", keep_heights=True, workers=1)  # fmt: skip
    spec = MonteCarloSpec(surface, material, np.array([1.0, 0.0]), 2e-12, 3, 9)
    full = run_sums(spec, workers=1)
    partial = EnsembleSums.start(spec)
    partial.sums[:1], partial.done_blocks[:1] = full.sums[:1], full.n_blocks[:1]
    write_checkpoint(folder / "partial.h5", partial, command="test")
    return RunSeeds({name: (folder / name).read_bytes() for name in ("complete.h5", "partial.h5")})


def run_fingerprint(run) -> dict:
    """Everything a read returns, as plain values to compare exactly."""
    out = {"h": run.h, "N": run.n_summits, "sums": run.sums, "attrs": dict(run.attrs)}
    out |= {f"real/{q}": v for q, v in run.realizations.items()}
    out |= {f"analytic/{q}": v for q, v in run.analytic.items()}
    out |= {f"heights/{i}": z for i, z in enumerate(run.heights or [])}
    out["spec"] = repr(run.spec)
    return out


def assert_same(a: dict, b: dict) -> None:
    assert a.keys() == b.keys()
    for key in a:
        if isinstance(a[key], np.ndarray):
            np.testing.assert_array_equal(a[key], b[key], err_msg=key)
        else:
            assert a[key] == b[key], key


def check_run_file(path: Path, original: Path) -> None:
    """Read ``path`` (a mutation of ``original``): a clean refusal or exactly the original."""
    from mcsim.model.errors import RunFileError
    from mcsim.store.runfile import read_run, read_state

    expected = run_fingerprint(read_run(original, allow_incomplete=True))
    try:
        with bounded_memory():
            state, _ = read_state(path)
            run = read_run(path, allow_incomplete=True)
    except RunFileError as err:
        assert_refused_cleanly(err, path.name)
        reason = str(err).split(f"{path}: ", 1)[-1].removeprefix("damaged run file")
        error = re.search(r"\(([A-Za-z]+Error)", reason)
        event(
            f"refused: {error[1] if error else re.split(r'[(:]', reason.lstrip(': '))[0].strip()}"
        )
        return
    event("read exactly")
    got = run_fingerprint(run)
    got["attrs"].pop("checksum"), expected["attrs"].pop("checksum")
    assert_same(got, expected)
    np.testing.assert_array_equal(state.sums, read_state(original)[0].sums)


@st.composite
def flipped(draw, seed: bytes) -> bytes:
    """``seed`` with 1–8 bit flips or overwritten bytes, its length kept (HDF5's offsets hold)."""
    data = bytearray(seed)
    for _ in range(draw(st.integers(1, 8))):
        pos = draw(st.integers(0, len(data) - 1))
        if draw(st.booleans()):
            data[pos] ^= 1 << draw(st.integers(0, 7))
        else:
            data[pos] = draw(st.sampled_from([0, 0x7F, 0x80, 0xFF]))
    return bytes(data)


DAMAGE = {
    "mutated": lambda seed: mutated(seed, focus=4096),  # flips, insertions, deletions, truncations
    "byte-flipped": flipped,  # length kept, so HDF5's offsets still point somewhere
}


@pytest.mark.parametrize("damage", sorted(DAMAGE))
@RUNFILE
@given(data=st.data())
def test_damaged_run_files_are_refused_in_one_line_or_read_exactly(
    run_files, tmp_path_factory, data, damage
):
    name = data.draw(st.sampled_from(sorted(run_files)))
    folder = tmp_path_factory.mktemp("rf")
    original = folder / f"original-{name}"
    original.write_bytes(run_files[name])
    path = folder / name
    path.write_bytes(data.draw(DAMAGE[damage](run_files[name])))
    check_run_file(path, original)


@pytest.mark.parametrize("name", ["complete.h5", "partial.h5"])
@pytest.mark.parametrize("keep", [0.0, 0.1, 0.5, 0.9, 0.99])
def test_truncated_run_files_are_refused_in_one_line(run_files, tmp_path, name, keep):
    from mcsim.model.errors import RunFileError
    from mcsim.store.runfile import read_run

    path = tmp_path / name
    path.write_bytes(run_files[name][: int(len(run_files[name]) * keep)])
    with pytest.raises(RunFileError) as err:
        read_run(path, allow_incomplete=True)
    assert_refused_cleanly(err.value, name)


@pytest.mark.parametrize(
    ("value", "shown"), [("1", "'1'"), (1.5, "1.5"), ([1, 1], "[1, 1]"), (b"x" * 99, "b'xxx")]
)
def test_schema_version_of_the_wrong_type_is_refused_in_one_line(run_files, tmp_path, value, shown):
    import h5py

    from mcsim.model.errors import RunFileError
    from mcsim.store.runfile import read_run

    path = tmp_path / "r.h5"
    path.write_bytes(run_files["complete.h5"])
    with h5py.File(path, "r+") as f:
        f.attrs["schema_version"] = np.void(value) if isinstance(value, bytes) else value
    with pytest.raises(
        RunFileError, match=rf"r.h5: damaged run file: schema_version is {re.escape(shown)}"
    ):
        read_run(path)


def test_a_dataset_declaring_a_huge_shape_in_a_tiny_file_is_refused_before_reading(
    run_files, tmp_path
):
    import h5py

    from mcsim.model.errors import RunFileError
    from mcsim.store.runfile import read_run

    path = tmp_path / "r.h5"
    path.write_bytes(run_files["complete.h5"])
    with h5py.File(path, "r+") as f:
        del f["analytic/P"]
        f.create_dataset("analytic/P", shape=(2 * 10**9,), dtype="f8")  # no storage written
    assert path.stat().st_size < 10**6
    with (
        bounded_memory(),
        pytest.raises(
            RunFileError,
            match=r"r.h5: damaged run file: dataset analytic/P declares 16000000000 bytes",
        ),
    ):
        read_run(path)


def test_a_dataset_of_strings_is_refused_before_reading(run_files, tmp_path):
    import h5py

    from mcsim.model.errors import RunFileError
    from mcsim.store.runfile import read_state

    path = tmp_path / "r.h5"
    path.write_bytes(run_files["partial.h5"])
    with h5py.File(path, "r+") as f:
        f.create_dataset(
            "extra", data=np.array([b"a", b"b"], dtype=object), dtype=h5py.string_dtype()
        )
    with pytest.raises(RunFileError, match=r"r.h5: damaged run file: dataset extra holds object"):
        read_state(path)


def test_show_of_a_byte_flipped_run_is_one_line(run_files, tmp_path, capsys):
    path = tmp_path / "r.h5"
    raw = bytearray(run_files["complete.h5"])
    at = raw.find(np.array([2.0, 0.0, -1.0]).tobytes())  # the dataset h
    assert at > 0
    raw[at + 7] ^= 0x10
    path.write_bytes(bytes(raw))
    status = cli.main(["show", str(path)])
    err = capsys.readouterr().err
    assert status == 2 and err.startswith("mcsim: error: ") and err.count("\n") == 1, err
    assert "r.h5: damaged run file: checksum mismatch" in err


# -- files rewritten elsewhere, checksum included: every command that reads them --------------
#
# A run or sweep file edited by a hand or another tool that recomputes the checksum (or
# written by another writer) passes the checksum: the readers' schema checks must refuse
# it. Each mutation below edits one attribute or dataset of a real file (delete; retype
# to text, number or array; empty or reshape; JSON text made invalid or of the wrong
# shape) and re-signs it with mcsim.store.files.checksum; raw byte flips are not re-signed.
# Every command that reads that file kind then runs in this process on it and must exit
# with 2 and one line on stderr naming the file, having written nothing and left the file
# as it was, or exit 0 (a harmless edit) with output.
#
# Cases: per HDF5 file kind (complete run, run checkpoint, complete sweep, sweep
# checkpoint) HDF5_SAMPLE mutations drawn with a seeded RNG from the full list (several
# hundred per kind) plus FLIPS byte-flipped copies, each run through the kind's 2-5
# commands: (8 + 2) x (4 + 5 + 2 + 3) = 140 command runs; text inputs (surface and
# material TOML, histogram CSV, each AFM map format) TEXT_SAMPLE seeded mutations each,
# each through its command: 10 x 9 = 90 runs. ``MCSIM_FUZZ_EXAMPLES`` scales both.

HDF5_SAMPLE = max(8, EXAMPLES // 3)
FLIPS = 2
TEXT_SAMPLE = max(10, EXAMPLES // 2)
SIMULATE = ["simulate", "--surface", "smooth", "--law", "jkr", "--cycle", "--h=1,0", "--area",
            "1um^2", "--realizations", "3", "--seed", "9", "--workers", "1"]  # fmt: skip
SWEEP = ["sweep", "--surface", "smooth", "--law", "dmt", "--vary", "sigma=1nm,2nm", "--vary",
         "gamma=0.1,0.5", "--h=2,0", "--workers", "1"]  # fmt: skip
#: Commands that read each file kind (FILE: the file, its folder holds the outputs).
HDF5_COMMANDS = {
    "run.h5": [["show"], ["compare"], ["plot", "--out", "o.png"], ["pads"]],
    "run.partial.h5": [["show"], ["compare", "--partial"], ["plot", "--partial", "--out", "o.png"],
                       ["pads", "--partial"], [*SIMULATE, "--out", "run.h5", "--resume"]],
    "sweep.h5": [["show"], ["plot", "--out", "o.png"]],
    "sweep.partial.h5": [["show"], ["plot", "--partial", "--out", "o.png"],
                         [*SWEEP, "--out", "sweep.h5", "--resume"]],
}  # fmt: skip


def quiet_cli(*argv) -> tuple[int, str, str]:
    """``mcsim ARGV`` in this process, outside pytest's capture (a module fixture)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = cli.main([str(a) for a in argv])
    return code, out.getvalue(), err.getvalue()


@pytest.fixture(scope="module")
def written(tmp_path_factory) -> dict[str, bytes]:
    """A complete cycle run, its checkpoint, a complete sweep and its checkpoint, as bytes."""
    from mcsim.engine.montecarlo import EnsembleSums
    from mcsim.store.runfile import read_state, write_checkpoint
    from mcsim.store.sweepfile import read_sweep, write_sweep

    folder = tmp_path_factory.mktemp("written")
    assert quiet_cli(*SIMULATE, "--out", folder / "run.h5")[0] == 0
    assert quiet_cli(*SWEEP, "--out", folder / "sweep.h5")[0] == 0
    state, _ = read_state(folder / "run.h5")
    partial = EnsembleSums.start(state.spec)
    partial.sums[:1], partial.done_blocks[:1] = state.sums[:1], state.n_blocks[:1]
    write_checkpoint(folder / "run.partial.h5", partial, command="test")
    sweep = read_sweep(folder / "sweep.h5")
    attrs = {k: v for k, v in sweep.attrs.items() if k not in ("checksum", "complete")}
    done = np.zeros(sweep.shape, dtype=bool)
    done.flat[:2] = True
    write_sweep(folder / "sweep.partial.h5", sweep, attrs, complete=False, done=done)
    return {name: (folder / name).read_bytes() for name in HDF5_COMMANDS}


#: Replacement values of an attribute: retyped, emptied, out of range.
ATTRIBUTE_VALUES = {"text": "x", "number": 1.5, "integer": 7, "negative": -1.0, "nan": math.nan,
                    "array": np.array([1.0, 2.0]), "empty": np.array([], dtype=float)}  # fmt: skip
#: Replacement texts of a JSON attribute: invalid, or JSON of the wrong shape.
JSON_VALUES = {"invalid JSON": "{not json", "JSON list": "[]", "JSON object": "{}",
               "JSON number": "1", "JSON text": '"x"'}  # fmt: skip
#: Replacements of a dataset, from its values.
DATASET_VALUES = {
    "text": lambda v: np.array([b"x", b"y"]),
    "scalar": lambda v: np.float64(1.5),
    "empty": lambda v: np.array([], dtype=float),
    "one short": lambda v: np.ravel(v)[:-1],
    "extra axis": lambda v: np.repeat(np.asarray(v)[..., None], 2, axis=-1),
    "integers": lambda v: np.zeros(np.shape(v), "i8" if np.asarray(v).dtype.kind != "i" else "f8"),
}
#: HDF5's own attributes (dimension scales) and the checksum: not mcsim's schema.
HDF5_OWN = {"checksum", "DIMENSION_LIST", "REFERENCE_LIST", "CLASS", "NAME", "_Netcdf4Dimid"}


def hdf5_mutations(path: Path) -> list[tuple[str, str, str, object]]:
    """Every (object, attribute or None, mutation, value) of the file at ``path``."""
    import h5py

    out = []
    with h5py.File(path, "r") as f:
        objects = [("", f)]
        f.visititems(lambda name, obj: objects.append((name, obj)))
        for name, obj in objects:
            for key in sorted(set(obj.attrs) - HDF5_OWN):
                out.append((name, key, "delete", None))
                out += [(name, key, m, v) for m, v in ATTRIBUTE_VALUES.items()]
                value = obj.attrs[key]
                if isinstance(value, str) and value[:1] in "[{":
                    out += [(name, key, m, v) for m, v in JSON_VALUES.items()]
                    parsed = json.loads(value)
                    wrong = {k: "x" for k in parsed} if isinstance(parsed, dict) else [{}] * 2
                    out.append((name, key, "JSON of wrong values", json.dumps(wrong)))
            if isinstance(obj, h5py.Dataset):
                out.append((name, None, "delete", None))
                out += [(name, None, m, v) for m, v in DATASET_VALUES.items()]
    return out


def mutate_and_resign(path: Path, name: str, key: str | None, mutation: str, value) -> None:
    import h5py

    from mcsim.store.files import checksum

    with h5py.File(path, "r+") as f:
        obj = f[name] if name else f
        if key is not None and mutation == "delete":
            del obj.attrs[key]
        elif key is not None:
            obj.attrs[key] = value
        else:
            old = obj[()]
            del f[name]
            if mutation != "delete":
                f.create_dataset(name, data=value(old))
        f.attrs["checksum"] = checksum(f)


def byte_flipped(raw: bytes, rng: random.Random) -> bytes:
    data = bytearray(raw)
    for _ in range(rng.randint(1, 8)):
        data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
    return bytes(data)


def hdf5_cases() -> list[tuple[str, int]]:
    """(file kind, case number): HDF5_SAMPLE mutations and FLIPS byte flips per kind."""
    return [(name, i) for name in HDF5_COMMANDS for i in range(HDF5_SAMPLE + FLIPS)]


def assert_refused_or_sane(folder: Path, path: Path, argv: list, code: int, out: str, err: str):
    """The command's contract on a hostile file (see the section comment)."""
    assert "Traceback" not in err, err
    if code == 0:
        # results on stdout, or a file written (announced on stderr) from a harmless edit
        written = "mcsim: wrote " in err or list(folder.glob("*.png"))
        assert out.strip() or written, f"{argv}: exit 0 and no output"
        return
    assert code == 2, f"{argv}: exit {code}: {err}"
    assert err.startswith("mcsim: error: ") and err.count("\n") == 1, f"{argv}: {err!r}"
    assert path.name in err, f"{argv}: the message does not name {path.name}: {err!r}"


@pytest.mark.parametrize(("name", "case"), hdf5_cases())
def test_run_and_sweep_files_edited_elsewhere_are_refused_in_one_line(
    written, tmp_path, name, case
):
    rng = random.Random(f"{name}/{case}")
    source = tmp_path / "source" / name
    source.parent.mkdir()
    source.write_bytes(written[name])
    folder = tmp_path / "work"
    folder.mkdir()
    path = folder / name
    if case < HDF5_SAMPLE:
        mutations = hdf5_mutations(source)
        mutation = random.Random(f"{name}").sample(mutations, HDF5_SAMPLE)[case]
        label = f"{mutation[0] or '/'}@{mutation[1]}: {mutation[2]}"
    else:
        label = "byte flips"
    for command in HDF5_COMMANDS[name]:
        for stale in folder.iterdir():
            stale.unlink()
        shutil.copy(source, path)
        if case < HDF5_SAMPLE:
            mutate_and_resign(path, *mutation)
        else:
            path.write_bytes(byte_flipped(written[name], rng))
        before, listing = path.read_bytes(), sorted(folder.iterdir())
        argv = [*command, *([path] if command[0] not in ("simulate", "sweep") else [])]
        argv = [folder / a if str(a).endswith((".png", ".h5")) and a != path else a for a in argv]
        code, out, err = quiet_cli(*argv)
        note = f"{name}, {label}, mcsim {' '.join(map(str, command))}"
        try:
            assert_refused_or_sane(folder, path, argv, code, out, err)
        except AssertionError as failure:
            raise AssertionError(f"{note}: {failure}") from None
        if code == 2:
            assert sorted(folder.iterdir()) == listing, f"{note}: wrote files"
            assert path.read_bytes() == before, f"{note}: changed the file"


#: Text and AFM inputs: seed file (from ``seeds``), name and the command that reads it.
TEXT_COMMANDS = {
    "surface": (".toml", ["analytic", "--surface", "FILE", "--h=1,0"]),
    "material": (".toml", ["analytic", "--surface", "smooth", "--material", "FILE", "--h=1,0"]),
    "histogram": (".csv", ["ingest", "FILE", "--R", "1.7um", "--eta", "17um^-2"]),
    **{
        s: (s, ["ingest", "FILE", "--unit", "nm", "--pixel-size", "10nm"]) for s in (".npy", ".xyz")
    },
    **{s: (s, ["ingest", "FILE"]) for s in (".txt", ".gwy", ".ibw", ".nid")},
}


def text_mutation(raw: bytes, rng: random.Random) -> bytes:
    """A line deleted, a value retyped (text, number, array, empty), a truncation or flips."""
    lines = raw.split(b"\n")
    at = rng.randrange(len(lines))
    kind = rng.choice(["delete line", "retype", "truncate", "flips"])
    if kind == "delete line":
        del lines[at]
    elif kind == "retype":
        head, sep, _ = lines[at].partition(b"=")
        value = rng.choice([b'"x"', b"1.5", b"[1, 2]", b'""', b"-1", b"nan", b"x", b""])
        lines[at] = head + sep + b" " + value if sep else value
    elif kind == "truncate":
        return raw[: rng.randrange(len(raw))]
    else:
        return byte_flipped(raw, rng)
    return b"\n".join(lines)


@pytest.mark.parametrize("kind", sorted(TEXT_COMMANDS))
def test_text_and_map_files_edited_elsewhere_are_refused_in_one_line(seeds, tmp_path, kind):
    suffix, command = TEXT_COMMANDS[kind]
    raw = seeds[suffix]
    if kind == "surface":
        raw = f"[surface]\n{SURFACE_TOML}".encode()
    elif kind == "material":
        raw = f"[material]\n{MATERIAL_TOML}".encode()
    rng = random.Random(kind)
    for case in range(TEXT_SAMPLE):
        folder = tmp_path / str(case)
        folder.mkdir()
        path = folder / f"in{suffix}"
        path.write_bytes(text_mutation(raw, rng))
        argv = [str(path) if a == "FILE" else a for a in command]
        if command[0] == "ingest":
            argv += ["--out", str(folder / "out.toml")]
        before, listing = path.read_bytes(), sorted(folder.iterdir())
        code, out, err = quiet_cli(*argv)
        note = f"{kind} case {case}, mcsim {' '.join(command)}"
        try:
            assert_refused_or_sane(folder, path, argv, code, out, err)
        except AssertionError as failure:
            raise AssertionError(f"{note}: {failure}") from None
        if code == 2:
            assert sorted(folder.iterdir()) == listing, f"{note}: wrote files"
        assert path.read_bytes() == before, f"{note}: changed the file"


@pytest.mark.parametrize(
    ("value", "message"),
    [
        ("{not json", "attribute varied is '{not json', not a JSON list"),
        ('{"sigma": 1}', "attribute varied is '{\"sigma\": 1}', not a JSON list"),
        ('["sigma", "nope"]', 'attribute varied is \'["sigma", "nope"]\', not a list of distinct'),
        ('["sigma", "sigma"]', 'attribute varied is \'["sigma", "sigma"]\', not a list of'),
        ("[1]", "attribute varied is '[1]', not a list of distinct names"),
        ("[]", "attribute varied is '[]', not a list of distinct names"),
    ],
)
@pytest.mark.parametrize("command", ["show", "plot"])
def test_a_sweep_whose_varied_was_edited_and_resigned_is_refused(
    written, tmp_path, value, message, command
):
    path = tmp_path / "sweep.h5"
    path.write_bytes(written["sweep.h5"])
    mutate_and_resign(path, "", "varied", "edited", value)
    code, _, err = quiet_cli(command, path)  # used to raise KeyError, JSONDecodeError, ...
    assert code == 2 and err.count("\n") == 1
    assert f"{path}: damaged sweep file: {message}" in err


def test_resuming_a_sweep_checkpoint_that_lacks_a_variable_is_refused(written, tmp_path):
    path = tmp_path / "sweep.partial.h5"
    path.write_bytes(written["sweep.partial.h5"])
    mutate_and_resign(path, "load", None, "delete", None)
    code, _, err = quiet_cli(*SWEEP, "--out", tmp_path / "sweep.h5", "--resume")
    assert code == 2  # used to raise KeyError: 'load'
    assert f"{path}: damaged sweep file: dataset load is missing" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["sweep.partial.h5"]

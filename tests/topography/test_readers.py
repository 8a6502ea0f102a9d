"""Readers: histograms and height maps, extension/magic dispatch, errors naming the file."""

from pathlib import Path

import numpy as np
import pytest
from tolerances import ROUNDING_FEW, ROUNDING_FORMULA

from mcsim.topography.readers import ReaderError, read_height_map, read_histogram


def write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


# -- histograms ------------------------------------------------------------------------


def test_two_column_csv_with_unit_header(tmp_path):
    hist = read_histogram(write(tmp_path, "h.csv", "height (nm), count\n-1, 2\n0, 5\n1, 3\n"))
    # bin centres ± half a width, times the unit factor: a few roundings
    np.testing.assert_allclose(
        hist.edges, [-1.5e-9, -0.5e-9, 0.5e-9, 1.5e-9], rtol=ROUNDING_FORMULA
    )
    assert hist.weights.tolist() == [2, 5, 3] and not hist.density


def test_three_column_whitespace_with_comments(tmp_path):
    text = "# measured\n# z [um] count\n0 1 4\n1 3 2\n"
    hist = read_histogram(write(tmp_path, "h.txt", text))
    np.testing.assert_allclose(hist.edges, [0, 1e-6, 3e-6], rtol=1e-14)


def test_gwyddion_height_distribution_export_is_density(tmp_path):
    text = "Height distribution\nz [µm]  ρ [1/µm]\n-0.1 1.5\n0.0 3.0\n0.1 1.5\n"
    hist = read_histogram(write(tmp_path, "h.txt", text))
    assert hist.density and hist.edges[0] == pytest.approx(-0.15e-6, rel=ROUNDING_FORMULA)


def test_unit_argument_overrides_header(tmp_path):
    hist = read_histogram(write(tmp_path, "h.tsv", "z [nm]\tn\n0\t1\n1\t1\n"), unit="um")
    assert hist.edges[-1] == pytest.approx(1.5e-6, rel=ROUNDING_FORMULA)


def test_histogram_converts_to_empirical(tmp_path):
    emp = read_histogram(write(tmp_path, "h.csv", "z [nm],n\n0,1\n1,1\n")).to_empirical()
    assert emp.sigma == pytest.approx(np.sqrt(1 / 3) * 1e-9, rel=1e-14)  # uniform on 2 nm


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "no histogram data"),
        ("# z [nm] n\n", "no histogram data"),
        ("z [nm], n\n0, 1\n", "at least two bins, found 1"),
        ("z [nm], n\n0, 1\n1, -2\n", "negative count in bin 2"),
        ("z [nm], n\n0, 1\n1, x2\n", "line 3: cannot read 'x2' as a number"),
        ("z [nm], n\n0, 0\n1, 0\n", "all counts are zero"),
        ("0, 1\n1, 1\n", "missing height unit: pass --unit"),
        ("z [nm], n\n1, 1\n0, 1\n", "centres must be strictly increasing"),
        ("z [nm]\n0, 1, 2, 3\n", "expected 2 columns"),
    ],
)
def test_bad_histogram_files_are_refused(tmp_path, text, message):
    path = write(tmp_path, "bad.csv", text)
    with pytest.raises(ReaderError, match=f"bad.csv: .*{message}"):
        read_histogram(path)


def test_histogram_with_unknown_extension_is_refused(tmp_path):
    with pytest.raises(ReaderError, match=r"unknown file type '\.xlsx'"):
        read_histogram(write(tmp_path, "h.xlsx", "0 1\n"))


def test_binary_file_is_not_a_text_histogram(tmp_path):
    path = tmp_path / "h.csv"
    path.write_bytes(b"\x00\x01\x02")
    with pytest.raises(ReaderError, match="does not look like a text histogram"):
        read_histogram(path)


# -- height maps -----------------------------------------------------------------------

PATTERN = np.arange(12.0).reshape(3, 4)  # rows along y, columns along x; [0, 1] = 1


def test_ascii_matrix_keeps_file_row_order(tmp_path):
    text = "\n".join(" ".join(f"{v:g}" for v in row) for row in PATTERN)
    m = read_height_map(write(tmp_path, "m.txt", text), unit="nm", pixel_size=2e-9)
    np.testing.assert_allclose(m.heights, PATTERN * 1e-9, rtol=1e-14)
    assert (m.dx, m.dy) == (2e-9, 2e-9)


def test_ascii_matrix_reads_gwyddion_header(tmp_path):
    text = "# Channel: Height\n# Width: 4.000 µm\n# Height: 3.000 µm\n# Value units: m\n"
    text += "\n".join("\t".join(f"{v:g}" for v in row) for row in PATTERN)
    m = read_height_map(write(tmp_path, "m.txt", text))
    assert (m.dx, m.dy) == pytest.approx((1e-6, 1e-6), rel=ROUNDING_FEW)
    assert m.heights[0, 1] == 1.0


def test_ascii_matrix_without_pixel_size_is_refused(tmp_path):
    with pytest.raises(ReaderError, match="missing pixel size: pass --pixel-size"):
        read_height_map(write(tmp_path, "m.txt", "0 1 2\n3 4 5\n6 7 8\n"), unit="nm")


def test_a_pixel_size_is_taken_as_users_write_it_and_a_bad_one_is_refused_by_name(tmp_path):
    path = write(tmp_path, "m.txt", "0 1 2\n3 4 5\n6 7 8\n")
    for given in ("10nm", "10 nm", 1e-8, np.float64(1e-8), ("10 nm", "0.01 um")):
        m = read_height_map(path, unit="nm", pixel_size=given)
        assert (m.dx, m.dy) == pytest.approx((1e-8, 1e-8), rel=ROUNDING_FEW), given
    assert read_height_map(path, unit="nm", pixel_size=("10nm", "20nm")).dy == 2e-8
    for bad, message in (("10 s", "pixel size"), ("-1nm", "positive"), ((1e-8,) * 3, "a pair"),
                         (True, "pixel size"), (float("inf"), "pixel size")):  # fmt: skip
        with pytest.raises(ReaderError, match=message):
            read_height_map(path, unit="nm", pixel_size=bad)


def test_ascii_matrix_without_unit_is_refused(tmp_path):
    with pytest.raises(ReaderError, match="missing height unit: pass --unit"):
        read_height_map(write(tmp_path, "m.txt", "0 1 2\n3 4 5\n6 7 8\n"), pixel_size=1e-9)


def test_ragged_matrix_is_refused(tmp_path):
    with pytest.raises(ReaderError, match="rows have different lengths"):
        read_height_map(write(tmp_path, "m.txt", "0 1 2\n3 4\n6 7 8\n"), unit="nm", pixel_size=1)


def test_xyz_rows_are_increasing_y(tmp_path):
    ys, xs = np.mgrid[0:3, 0:4]
    lines = [
        f"{x * 1e-8:g} {y * 2e-8:g} {v:g}"
        for x, y, v in zip(xs.ravel(), ys.ravel(), PATTERN.ravel())
    ]
    m = read_height_map(write(tmp_path, "m.xyz", "\n".join(lines[::-1])), unit="m")
    np.testing.assert_array_equal(m.heights, PATTERN)
    assert (m.dx, m.dy) == pytest.approx((1e-8, 2e-8), rel=ROUNDING_FEW)


def test_xyz_off_grid_is_refused(tmp_path):
    with pytest.raises(ReaderError, match="not a full regular grid"):
        read_height_map(write(tmp_path, "m.xyz", "0 0 1\n1 0 1\n2 1 1\n"), unit="m")


def test_npy_round_trip(tmp_path):
    np.save(tmp_path / "m.npy", PATTERN)
    m = read_height_map(tmp_path / "m.npy", unit="nm", pixel_size=(1e-9, 2e-9))
    # heights times the unit factor: one rounding
    np.testing.assert_allclose(m.heights, PATTERN * 1e-9, rtol=ROUNDING_FEW)
    assert (m.dx, m.dy) == (1e-9, 2e-9)


def test_npy_with_wrong_magic_is_refused(tmp_path):
    (tmp_path / "m.npy").write_text("hello")
    with pytest.raises(ReaderError, match=r"m\.npy: does not look like a NumPy \.npy file"):
        read_height_map(tmp_path / "m.npy", unit="nm", pixel_size=1e-9)


def test_gwy_round_trip_keeps_rows_and_size(tmp_path):
    objects = pytest.importorskip("gwyfile.objects", reason="gwyfile (extra 'afm') not installed")
    container = objects.GwyContainer()
    container["/0/data"] = objects.GwyDataField(
        PATTERN * 1e-9, xreal=4e-6, yreal=3e-6, si_unit_xy="m", si_unit_z="m"
    )
    container["/0/data/title"] = "Height"
    container.tofile(str(tmp_path / "m.gwy"))
    m = read_height_map(tmp_path / "m.gwy")
    np.testing.assert_allclose(m.heights, PATTERN * 1e-9, rtol=ROUNDING_FEW)
    assert (m.dx, m.dy, m.channel) == (1e-6, 1e-6, "Height")


def _nid_files() -> list[Path]:
    try:
        import NSFopen
    except ImportError:
        return []
    return sorted(Path(NSFopen.__file__).parent.glob("example/*/*.nid"))


@pytest.mark.parametrize(
    "path", _nid_files()[:3] or [None], ids=lambda p: getattr(p, "name", "none")
)
def test_nid_matches_nanosurf_reader_on_real_files(path):
    if path is None:
        pytest.skip("NSFopen (ships the real .nid sample files) not installed")
    from NSFopen.read import read

    m = read_height_map(path)
    reference = read(str(path)).data["Image"]["Forward"]["Z-Axis"]
    np.testing.assert_array_equal(m.heights, reference)
    assert m.dx > 0 and m.dy > 0


def test_nid_with_wrong_magic_is_refused(tmp_path):
    with pytest.raises(ReaderError, match=r"does not look like a Nanosurf \.nid file"):
        read_height_map(write(tmp_path, "m.nid", "hello"))


def test_ibw_with_wrong_magic_is_refused(tmp_path):
    (tmp_path / "m.ibw").write_bytes(b"\x09\x00rest")
    with pytest.raises(ReaderError, match="does not look like a Igor binary wave file"):
        read_height_map(tmp_path / "m.ibw")


def test_unknown_map_extension_is_refused(tmp_path):
    with pytest.raises(ReaderError, match=r"unknown file type '\.tif'"):
        read_height_map(write(tmp_path, "m.tif", "x"))


def test_missing_file_is_named(tmp_path):
    with pytest.raises(ReaderError, match=r"nope\.npy: no such file"):
        read_height_map(tmp_path / "nope.npy", unit="nm", pixel_size=1)


# -- real files from AFMReader 0.0.7 (tests/conftest.py fetches them) ------------------


def test_ibw_reads_asylum_height_in_metres_like_igor2_and_afmreader(afm_resources):
    from igor2 import binarywave

    path = afm_resources / "sample_0.ibw"
    m = read_height_map(path)
    wave = binarywave.load(str(path))["wave"]
    # layer 0 is 'HeightTracee'; Igor stores w[x, y]: transposed to rows along y
    np.testing.assert_array_equal(m.heights, wave["wData"][:, :, 0].T.astype(float))
    assert m.channel == "HeightTracee" and m.shape == (512, 512)
    # AFMReader's own test: the same layer read as metres sums to -218091520 nm (float32 sum)
    assert m.heights.sum() * 1e9 == pytest.approx(-218091520.0, rel=1e-6)
    # Asylum's wave scaling: ScanSize (8e-7 m, in the note) over points - 1
    assert m.dx == pytest.approx(8e-7 / 511, rel=1e-7) and m.dy == m.dx


def test_ibw_caller_unit_overrides_the_asylum_default(afm_resources):
    in_nm = read_height_map(afm_resources / "sample_0.ibw", unit="nm")
    in_m = read_height_map(afm_resources / "sample_0.ibw")
    np.testing.assert_allclose(in_nm.heights, in_m.heights * 1e-9, rtol=ROUNDING_FEW)
    assert "caller" in in_nm.notes[0]


def test_gwy_matches_afmreader_on_a_real_file(afm_resources):
    from mcsim.topography.readers import gwy

    m = gwy.read(afm_resources / "sample_0.gwy", channel="ZSensor")
    # AFMReader's own .gwy parser (its test_load_gwy): sum in nm and pixel size in nm
    assert m.heights.sum() * 1e9 == pytest.approx(33836850.232917726, rel=1e-9)
    assert m.dx * 1e9 == pytest.approx(0.8468632812499975, rel=1e-12)
    assert m.shape == (512, 512)


def test_gwy_default_channel_is_height(afm_resources):
    assert read_height_map(afm_resources / "sample_0.gwy").channel == "Height"


@pytest.mark.parametrize("name", ["sample_0.gwy", "sample_0.ibw"])
def test_truncated_real_binary_file_is_refused(afm_resources, tmp_path, name):
    data = (afm_resources / name).read_bytes()
    cut = tmp_path / name
    cut.write_bytes(data[: len(data) // 3])
    with pytest.raises(ReaderError, match=f"{name}: not a readable"):
        read_height_map(cut)


@pytest.mark.parametrize("layout", ["z [nm], count\n{}", "left [nm], right [nm], count\n{}"])
def test_histogram_whose_counts_add_up_past_the_largest_float_is_refused(tmp_path, layout):
    rows = ["0, 1e308\n1, 1.5e308\n2, 1.7e308\n", "0, 1, 1e308\n1, 2, 1.5e308\n2, 3, 1.7e308\n"]
    path = tmp_path / "h.csv"
    path.write_text(layout.format(rows[layout.startswith("left")]), encoding="utf-8")
    with pytest.raises(
        ReaderError, match=r"h.csv: the counts add up to more than the largest float"
    ):
        read_histogram(path)


def gwy_file(xres=("i", 3), unit=None) -> bytes:
    """A minimal Gwyddion file built component by component (gwyfile cannot write bad types)."""
    import struct

    def comp(key, code, value):
        head = key.encode() + b"\0" + code.encode()
        packed = {
            "d": lambda: struct.pack("<d", value),
            "i": lambda: struct.pack("<i", value),
            "s": lambda: value.encode() + b"\0",
            "o": lambda: value,
            "D": lambda: struct.pack("<I", len(value)) + np.asarray(value, "<f8").tobytes(),
        }
        return head + packed[code]()  # fmt: skip

    def obj(name, comps):
        body = b"".join(comps)
        return name.encode() + b"\0" + struct.pack("<I", len(body)) + body

    metre = ("o", obj("GwySIUnit", [comp("unitstr", "s", "m")]))
    field = obj("GwyDataField", [
        comp("xres", *xres), comp("yres", "i", 3), comp("xreal", "d", 1e-6),
        comp("yreal", "d", 1e-6), comp("si_unit_xy", *metre), comp("si_unit_z", *(unit or metre)),
        comp("data", "D", np.arange(9.0)),
    ])  # fmt: skip
    return b"GWYP" + obj(
        "GwyContainer", [comp("/0/data/title", "s", "Height"), comp("/0/data", "o", field)]
    )


def test_hand_built_gwyddion_file_reads(tmp_path):
    path = tmp_path / "m.gwy"
    path.write_bytes(gwy_file())
    assert read_height_map(path).shape == (3, 3)


@pytest.mark.parametrize(
    ("kw", "message"),
    [
        ({"xres": ("d", float("inf"))}, "channel 'Height' is not a complete data field"),
        ({"xres": ("d", 1e300)}, "channel 'Height' is not a complete data field"),
        ({"unit": ("i", 3)}, "channel 'Height': unknown unit '?'"),
        ({"unit": ("s", "m")}, "channel 'Height': unknown unit '?'"),
    ],
)
def test_gwyddion_file_with_crafted_field_types_is_refused_in_one_line(tmp_path, kw, message):
    path = tmp_path / "m.gwy"
    path.write_bytes(gwy_file(**kw))
    with pytest.raises(ReaderError, match=f"m.gwy: {message}"):
        read_height_map(path)

"""Tests of the paper's Table 1 sections (railhunt.studies.sections), Figs. 10-12 and the
``railhunt sections`` / ``railhunt plot`` commands."""

import csv
import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import railhunt
from railhunt.plots import plot_sections, plot_sweep
from railhunt.studies.sections import (
    SectionTable,
    Table1Parameter,
    load_table1,
    section_changes,
    sweep_line,
    table1_values,
)
from test_cli import assert_input_error, run

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
#: Table 1 of the paper, as printed (display units).
PAPER_TABLE1 = {
    "C_d1": ([20, 300, 600, 1000], "kN*s/m"),
    "K_d": ([0.1, 6, 12, 20], "MN/m"),
    "C_d2": ([0, 40, 80, 120], "kN*s/m"),
    "mu": ([0.05, 0.2, 0.35, 0.5], "-"),
    "K_px": ([10, 30, 50, 80], "MN/m"),
    "f11": ([2, 5, 8, 11], "MN"),
    "C_sy": ([0, 20, 40, 60], "kN*s/m"),
}
OUTPUTS = ["critical_speed_kmh", "linear_critical_speed_kmh", "linear_frequency_hz",
           "frequency_speed_kmh", "hunting_frequency_hz", "frequency_source", "status",
           "message"]  # fmt: skip


def write_results(path, rows, parameters):
    """A results CSV in the issue 5 schema (point, line, parameters, outputs)."""
    columns = ["point", "line", *parameters, *OUTPUTS]
    with open(path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, columns)
        writer.writeheader()
        for k, row in enumerate(rows):
            out = {"point": k, "status": "ok", "message": "", **row}
            writer.writerow(
                {c: repr(float(v)) if isinstance(v, float) else v for c, v in out.items()}
            )
    return path


def line_rows(name, values, speeds, freqs=None, sources=None, frequency_speed=300.0, **nominal):
    """Rows of one synthetic line (frequencies default to 3 Hz from the eigenvalue)."""
    n = len(values)
    freqs = [3.0] * n if freqs is None else freqs
    sources = ["eigenvalue"] * n if sources is None else sources
    rows = []
    for x, v, f, s in zip(values, speeds, freqs, sources, strict=True):
        row = {"line": name, **nominal, name: float(x), "critical_speed_kmh": float(v),
               "linear_critical_speed_kmh": 400.0, "linear_frequency_hz": 4.0,
               "frequency_speed_kmh": frequency_speed, "hunting_frequency_hz": float(f),
               "frequency_source": s}  # fmt: skip
        if math.isnan(v):
            row["status"] = "no-critical-speed"
        rows.append(row)
    return rows


def assert_png(path, min_bytes=15_000):
    data = path.read_bytes()
    assert data.startswith(PNG_SIGNATURE)
    assert len(data) > min_bytes, len(data)
    from matplotlib.image import imread

    image = imread(path)
    assert image[..., :3].std() > 0.05  # something is drawn, not a blank canvas


# --------------------------------------------------------------------------- Table 1


def test_table1_is_the_papers():
    table = load_table1()
    assert list(table) == list(PAPER_TABLE1)  # the paper's order
    for name, (boundaries, unit) in PAPER_TABLE1.items():
        entry = table[name]
        assert entry.unit == unit
        shown = entry.paper_boundaries or entry.display_boundaries
        assert shown == tuple(float(b) for b in boundaries), name
        assert np.allclose(entry.boundaries, np.array(entry.display_boundaries) * entry.scale)
    assert {n: e.figure for n, e in table.items()} == {
        "C_d1": "10a", "C_d2": "10b", "K_d": "10c",
        "mu": "11a", "f11": "11b", "K_px": "11c", "C_sy": "11d",
    }  # fmt: skip
    for name, entry in table.items():
        assert entry.frequency_speed_kmh == (300.0 if entry.figure.startswith("10") else 350.0)
        assert entry.ties == (("f22",) if name == "f11" else ())
    assert table["C_d1"].boundaries == (20e3, 300e3, 600e3, 1000e3)
    assert table["K_d"].boundaries[0] == 0.1e6 and table["f11"].boundaries[-1] == 11e6


def test_c_d2_lower_end_is_positive_and_explained():
    entry = load_table1()["C_d2"]
    assert entry.paper_boundaries[0] == 0.0
    assert entry.boundaries[0] == 1e3  # 1 kN*s/m stands for the paper's 0
    assert "C_d2 must be positive" in entry.note and "1 kN*s/m" in entry.note
    with pytest.raises(ValueError):
        railhunt.Vehicle.paper2019().replace(C_d2=0.0)


def test_every_section_end_is_a_valid_vehicle():
    vehicle = railhunt.Vehicle.paper2019()
    for name, entry in load_table1().items():
        for value in (entry.boundaries[0], entry.boundaries[-1]):
            changed = vehicle.replace(**{name: value, **dict.fromkeys(entry.ties, value)})
            assert getattr(changed, name) == value


def test_table1_values_cover_the_sections():
    for name, entry in load_table1().items():
        values = table1_values(name, 4)
        assert values.size == 3 * 3 + 1
        assert np.all(np.diff(values) > 0)  # ascending, no duplicates
        for boundary in entry.boundaries:
            assert np.count_nonzero(values == boundary) == 1, (name, boundary)
        for lower, upper in entry.sections:
            inside = values[(values >= lower) & (values <= upper)]
            assert inside.size == 4
    assert np.array_equal(table1_values("C_d1", 2), [20e3, 300e3, 600e3, 1000e3])


@pytest.mark.parametrize(
    ("name", "points", "fragment"),
    [("f22", 3, "follows 'f11'"), ("F_u", 3, "valid: C_d1, K_d"), ("C_d1", 1, "integer >= 2")],
)
def test_table1_values_rejects(name, points, fragment):
    with pytest.raises(ValueError, match=fragment):
        table1_values(name, points)


# --------------------------------------------------------------------------- ΔV_cr and Δf


def test_monotone_line_gives_end_minus_start():
    values = table1_values("C_d1", 5)
    speeds = 200 + 40 * np.log(values / 10e3)  # increasing, like Fig. 10a
    result = section_changes(line_rows("C_d1", values, speeds))
    entry = result["C_d1"]
    ends = {v: s for v, s in zip(values, speeds, strict=True)}
    for s in entry.sections:
        assert s.speed_change_kmh == pytest.approx(abs(ends[s.upper] - ends[s.lower]))
        assert s.coverage == 1.0 and s.points == 5 and s.jumps_removed == 0
        assert s.speed_net_change_kmh == pytest.approx(s.speed_change_kmh)
    assert entry.speed_change_kmh == pytest.approx(speeds[-1] - speeds[0])
    assert sum(s.speed_share for s in entry.sections) == pytest.approx(1.0)
    assert entry.sections[0].speed_share > 0.5  # the logarithm rises fastest at first
    assert entry.frequency_change_hz == 0.0 and entry.complete and not entry.notes


def test_rise_and_fall_both_count():
    values = table1_values("K_d", 3)
    speeds = [250, 320, 300, 310, 290, 285, 285]  # up and down within sections
    entry = section_changes(line_rows("K_d", values, speeds))["K_d"]
    assert [s.speed_change_kmh for s in entry.sections] == pytest.approx([90, 30, 5])
    assert entry.speed_change_kmh == pytest.approx(125)  # not |285 - 250| = 35
    assert [s.speed_net_change_kmh for s in entry.sections] == pytest.approx([50, 10, 5])


def test_boundary_between_points_is_interpolated():
    values = np.array([20, 150, 450, 800, 1000]) * 1e3  # no point on 300 or 600
    speeds = [200, 260, 290, 300, 306]
    entry = section_changes(line_rows("C_d1", values, speeds))["C_d1"]
    s1, s2, s3 = (s.speed_change_kmh for s in entry.sections)
    assert s1 == pytest.approx(60 + 30 * 150 / 300)
    assert s2 == pytest.approx(30 * 150 / 300 + 10 * 150 / 350)
    assert s3 == pytest.approx(10 * 200 / 350 + 6)
    assert s1 + s2 + s3 == pytest.approx(106)


def test_frequency_jump_is_removed():
    values = table1_values("C_d1", 3)  # 20, 160, 300, 450, 600, 800, 1000 kN*s/m
    freqs = [4.6, 4.5, 3.2, 3.0, 2.5, 2.2, 1.9]
    sources = ["limit-cycle", "limit-cycle", "eigenvalue", *["eigenvalue"] * 4]
    entry = section_changes(line_rows("C_d1", values, np.linspace(220, 310, 7), freqs,
                                      sources))["C_d1"]  # fmt: skip
    s1, s2, s3 = entry.sections
    assert s1.frequency_change_hz == pytest.approx(0.1)  # 4.5 -> 3.2 is the jump
    assert s1.jumps_removed == 1 and s2.jumps_removed == s3.jumps_removed == 0
    assert s2.frequency_change_hz == pytest.approx(0.7)
    assert s3.frequency_change_hz == pytest.approx(0.6)
    assert entry.frequency_change_hz == pytest.approx(1.4)
    assert sweep_line(line_rows("C_d1", values, values, freqs, sources), "C_d1").jumps() == [1]


def test_nan_points_are_skipped_and_reported():
    values = table1_values("C_d1", 3)
    speeds = [220, math.nan, 300, 305, 307, 309, 310]
    entry = section_changes(line_rows("C_d1", values, speeds))["C_d1"]
    assert entry.sections[0].speed_change_kmh == pytest.approx(80)  # 220 -> 300 joined
    assert entry.skipped == (160e3,)
    assert not entry.complete
    assert any("160 kN*s/m" in note and "no-critical-speed" in note for note in entry.notes)


def test_partial_line_and_other_lines_are_flagged():
    rows = line_rows("mu", [0.1, 0.2, 0.3], [330, 300, 280], frequency_speed=300.0)
    rows += line_rows("F_u", [2e3, 4e3], [290, 310])
    result = section_changes(rows)
    assert result.names == ["mu"]
    assert any("F_u" in note for note in result.notes)
    s1, s2, s3 = result["mu"].sections
    assert s1.coverage == pytest.approx(2 / 3) and s1.speed_change_kmh == pytest.approx(30)
    assert s2.coverage == pytest.approx(2 / 3) and s2.speed_change_kmh == pytest.approx(20)
    assert s3.coverage == 0.0 and math.isnan(s3.speed_change_kmh)
    notes = " ".join(result["mu"].notes)
    assert "section 3" in notes and "not covered" in notes
    assert "uses 350 km/h" in notes  # frequencies at 300 km/h, the paper's at 350
    data = json.loads(json.dumps(result.to_dict(), allow_nan=False))
    assert data["parameters"][0]["sections"][2]["speed_change_kmh"] is None
    assert "total variation" in data["definition"]


def test_results_that_are_not_lines_are_refused():
    rows = line_rows("C_d1", [20e3, 300e3], [220, 300])
    for row in rows:
        row["line"] = "grid"
    with pytest.raises(ValueError, match="'grid' design"):
        section_changes(rows)
    with pytest.raises(ValueError, match="'grid' design"):
        plot_sweep(rows, "never.png")
    with pytest.raises(ValueError, match="no line of the results is a Table 1 parameter"):
        section_changes(line_rows("F_u", [2e3, 4e3], [290, 310]))


SMALL_TABLE = {
    "C_d1": Table1Parameter("C_d1", "test", "-", 1.0, (0.0, 1.0, 2.0, 3.0), "10a", 300.0)
}


@settings(max_examples=60, deadline=None)
@given(
    points=st.lists(
        st.tuples(
            st.floats(-0.5, 3.5, allow_nan=False),
            st.one_of(st.floats(100, 500), st.just(math.nan)),
            st.floats(0.5, 8),
            st.sampled_from(["eigenvalue", "limit-cycle"]),
        ),
        min_size=2,
        max_size=12,
        unique_by=lambda p: p[0],
    )
)
def test_section_changes_invariants(points):
    x, v, f, src = map(list, zip(*sorted(points), strict=True))
    entry = section_changes(line_rows("C_d1", x, v, f, src), SMALL_TABLE)["C_d1"]
    for total, attr in ((entry.speed_change_kmh, "speed_change_kmh"),
                        (entry.frequency_change_hz, "frequency_change_hz")):  # fmt: skip
        parts = [getattr(s, attr) for s in entry.sections]
        known = [p for p in parts if not math.isnan(p)]
        assert all(p >= 0 for p in known)
        if known:
            assert total == pytest.approx(math.fsum(known), abs=1e-9)  # additive
        else:
            assert math.isnan(total)
    # never more than the total variation of all finite points, the jump included
    xa, fa, va = np.array(x), np.array(f), np.array(v)
    finite = np.isfinite(va)
    assert not entry.frequency_change_hz > np.abs(np.diff(fa)).sum() + 1e-9
    assert not entry.speed_change_kmh > np.abs(np.diff(va[finite])).sum() + 1e-9
    inside = (xa >= 0) & (xa <= 3)
    if np.all(inside) and np.all(finite) and np.all(np.array(src) == src[0]):
        assert entry.frequency_change_hz == pytest.approx(np.abs(np.diff(fa)).sum())
        assert entry.speed_change_kmh == pytest.approx(np.abs(np.diff(va)).sum())


# --------------------------------------------------------------------------- a real C_d1 line

#: C_d1 (kN*s/m): three points in section 1 (the blow-off region), then 450, 600, 1000.
C_D1_LINE = [20.0, 140.0, 300.0, 450.0, 600.0, 1000.0]


@pytest.fixture(scope="module")
def c_d1_results(tmp_path_factory):
    """A results file of the paper's C_d1 line computed point by point (Fig. 10a)."""
    vehicle = railhunt.Vehicle.paper2019()
    rows = []
    for kns in C_D1_LINE:
        changed = vehicle.replace(C_d1=kns * 1e3)
        nonlinear = railhunt.critical_speed(changed)
        linear = railhunt.linear_critical_speed(changed)
        hf = railhunt.hunting_frequency(changed, 300.0)
        rows.append({"line": "C_d1", "C_d1": kns * 1e3, "critical_speed_kmh": nonlinear.speed_kmh,
                     "linear_critical_speed_kmh": linear.speed_kmh,
                     "linear_frequency_hz": linear.frequency_hz, "frequency_speed_kmh": 300.0,
                     "hunting_frequency_hz": hf.frequency_hz, "frequency_source": hf.source,
                     "status": "ok" if nonlinear.bracketed else "no-critical-speed"})  # fmt: skip
    return write_results(tmp_path_factory.mktemp("sweep") / "c_d1.csv", rows, ["C_d1"])


def test_real_c_d1_line_first_section_dominates(c_d1_results):
    line = sweep_line(c_d1_results, "C_d1")
    assert np.all(np.diff(line.critical_speed_kmh) >= 0)  # V_cr rises with C_d1 (Fig. 10a)
    assert line.critical_speed_kmh[0] == pytest.approx(222, abs=3)
    assert line.critical_speed_kmh[-1] == pytest.approx(310, abs=3)
    assert line.frequency_source[:2] == ("limit-cycle", "limit-cycle")
    assert line.frequency_source[2:] == ("eigenvalue",) * 4
    assert line.jumps() == [1]  # the jump between 140 and 300 kN*s/m
    entry = section_changes(c_d1_results)["C_d1"]
    s1, s2, s3 = entry.sections
    # "the first section plays a decisive role in C_d1"
    assert s1.speed_share > 0.75 and s1.speed_change_kmh > s2.speed_change_kmh + s3.speed_change_kmh
    assert entry.speed_change_kmh == pytest.approx(line.critical_speed_kmh[-1]
                                                   - line.critical_speed_kmh[0])  # fmt: skip
    assert s1.jumps_removed == 1
    assert s1.frequency_change_hz == pytest.approx(abs(line.frequency_hz[1] - line.frequency_hz[0]))
    assert entry.complete


def test_figures_are_drawn(c_d1_results, tmp_path):
    assert_png(plot_sweep(c_d1_results, tmp_path / "fig10.png"))
    assert_png(plot_sections(section_changes(c_d1_results), tmp_path / "fig12.png"))
    with pytest.raises(ValueError, match="no line 'K_d'.*lines: C_d1"):
        plot_sweep(c_d1_results, tmp_path / "x.png", ["K_d"])


def test_figures_of_several_lines(tmp_path):
    rows = []
    for name, entry in load_table1().items():
        values = table1_values(name, 3)
        speeds = 250 + 60 * np.sqrt(np.arange(values.size))
        sources = ["limit-cycle"] * 2 + ["eigenvalue"] * (values.size - 2)
        rows += line_rows(name, values, speeds, np.linspace(5, 3, values.size), sources,
                          frequency_speed=entry.frequency_speed_kmh)  # fmt: skip
    table = section_changes(rows)
    assert isinstance(table, SectionTable) and table.names == list(PAPER_TABLE1)
    assert_png(plot_sweep(rows, tmp_path / "all.png"), 40_000)
    assert_png(plot_sections(table, tmp_path / "fig12.png"))


# --------------------------------------------------------------------------- command line


@pytest.fixture
def two_lines(tmp_path):
    rows = line_rows("C_d1", table1_values("C_d1", 3), [220, 260, 300, 305, 307, 309, 310],
                     [4.6, 4.5, 3.2, 3.0, 2.5, 2.2, 1.9],
                     ["limit-cycle"] * 2 + ["eigenvalue"] * 5, K_d=10e6)  # fmt: skip
    rows += line_rows("K_d", table1_values("K_d", 2), [250, 320, 300, 290], C_d1=300e3)
    for row in rows:
        row.setdefault("K_d", 10e6)
        row.setdefault("C_d1", 300e3)
    return write_results(tmp_path / "lines.csv", rows, ["C_d1", "K_d"])


def test_cli_sections(two_lines, tmp_path):
    png, table_csv = tmp_path / "fig12.png", tmp_path / "sections.csv"
    result = run("sections", str(two_lines), "--png", str(png), "--csv", str(table_csv))
    assert result.exit_code == 0, result.stderr
    for text in ("C_d1", "(kN*s/m)", "K_d", "total", "ΔV_cr", "20–300", "jump", "wrote"):
        assert text in result.stdout, text
    assert_png(png, 10_000)
    with open(table_csv, newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert [(r["parameter"], r["section"]) for r in rows] == [
        (p, str(k)) for p in ("C_d1", "K_d") for k in (1, 2, 3)
    ]
    assert float(rows[0]["speed_change_kmh"]) == pytest.approx(80)
    assert float(rows[3]["speed_change_kmh"]) == pytest.approx(70)
    data = json.loads(run("sections", str(two_lines), "--json").stdout)
    c_d1 = data["parameters"][0]
    assert c_d1["parameter"] == "C_d1" and c_d1["speed_change_kmh"] == pytest.approx(90)
    assert c_d1["sections"][0]["jumps_removed"] == 1


def test_cli_plot(two_lines, tmp_path):
    out = tmp_path / "fig10.png"
    result = run("plot", str(two_lines), "--out", str(out), "--parameter", "K_d")
    assert result.exit_code == 0, result.stderr
    assert "K_d" in result.stdout and "C_d1" not in result.stdout
    assert_png(out)


def test_cli_errors(two_lines, tmp_path):
    assert_input_error(run("sections", str(tmp_path / "none.csv")), "none.csv",
                          "does not exist")  # fmt: skip
    assert_input_error(run("plot", str(two_lines), "--out", str(tmp_path / "f.png"),
                              "--parameter", "mu"),
                          "--parameter mu", "lines: C_d1, K_d")  # fmt: skip
    assert_input_error(run("plot", str(two_lines), "--out", str(tmp_path / "no" / "f.png")),
                          "folder")  # fmt: skip
    assert_input_error(run("plot", str(two_lines)), "--out")
    rows = line_rows("C_d1", [20e3, 300e3], [220, 300])
    for row in rows:
        row["line"] = "random"
    grid = write_results(tmp_path / "random.csv", rows, ["C_d1"])
    for command in (["sections"], ["plot", "--out", str(tmp_path / "g.png")]):
        assert_input_error(run(*command, str(grid)), "random.csv", "'random' design",
                              "design 'lines'")  # fmt: skip
    other = write_results(tmp_path / "fu.csv", line_rows("F_u", [2e3, 4e3], [290, 310]), ["F_u"])
    assert_input_error(run("sections", str(other)), "fu.csv", "lines: F_u",
                          "Table 1: C_d1, K_d")  # fmt: skip
    junk = tmp_path / "junk.csv"
    junk.write_text("speed,frequency\n1,2\n")
    assert_input_error(run("sections", str(junk)), "junk.csv", "'point'")


def test_a_jump_across_a_boundary_is_counted_once():
    """A frequency jump between 200 and 400 kN*s/m (across the 300 boundary of C_d1) is
    left out of both sections' Δf but counted once, in the section of its midpoint."""
    from railhunt.studies.sections import _variation

    x = np.array([100e3, 200e3, 400e3, 500e3])
    y = np.array([4.0, 3.8, 3.2, 3.1])
    src = ["limit-cycle", "limit-cycle", "eigenvalue", "eigenvalue"]
    counts = [_variation(x, y, lo, hi, src)[1] for lo, hi in ((20e3, 300e3), (300e3, 600e3))]
    assert sum(counts) == 1
    assert _variation(x, y, 20e3, 300e3, src)[0] == pytest.approx(0.2)


def test_plot_needs_a_critical_speed_or_a_frequency(tmp_path):
    """A study of the Hopf point alone has nothing for Figs. 10/11: a clear error, no
    traceback; one with the critical speed only draws V_cr alone."""
    from railhunt import Vehicle, sweep

    v = Vehicle.paper2019()
    linear = sweep(v, {"K_px": [2e7, 4e7]}, ("linear_critical_speed",), workers=1,
                   out=tmp_path / "lin.csv")  # fmt: skip
    assert len(linear) == 2
    assert_input_error(run("plot", str(tmp_path / "lin.csv"), "--out", str(tmp_path / "a.png")),
                       "neither critical_speed nor hunting_frequency")  # fmt: skip
    sweep(v, {"K_px": [2e7, 4e7]}, ("critical_speed",), workers=1, out=tmp_path / "cs.csv")
    result = run("plot", str(tmp_path / "cs.csv"), "--out", str(tmp_path / "b.png"))
    assert result.exit_code == 0, result.stderr
    assert_png(tmp_path / "b.png", min_bytes=5_000)

"""The main figures compared pixel by pixel with committed baselines (pytest-mpl).

Each ``test_*_image`` draws one figure from small synthetic inputs built here (no
simulation, no continuation: the whole file runs in seconds) and returns it; pytest-mpl
renders it at :data:`DPI` and compares it with ``tests/baseline/<test name>.png`` within
:data:`TOLERANCE` (RMS of the pixel difference, 0-255). pyproject.toml passes ``--mpl``, so
a plain ``python -m pytest`` compares; on a failure pytest-mpl names a folder with the
baseline, the result and their difference.

After an intended change of a figure, regenerate the baselines and look at each one
before committing::

    python -m pytest tests/test_figures.py --mpl-generate-path=tests/baseline

The style is frozen (matplotlib's defaults after a reset, DejaVu Sans, no font hinting),
so the images do not depend on a user's matplotlibrc.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import railhunt
from railhunt.analysis.branches import BifurcationDiagram, Branch, Fold
from railhunt.analysis.linear import EigenResult, LinearCriticalSpeed
from railhunt.analysis.spectrogram import dominant_bands, stft
from railhunt.contact.geometry import ContactGeometry
from railhunt.kernel.layout import STATE_NAMES
from railhunt.paper2019 import NO_BLOWOFF
from railhunt.plots import (
    bifurcation_family_figure,
    bifurcation_figure,
    contact_geometry_figure,
    creep_figure,
    curve_entry_figure,
    hunting_frequency_figure,
    root_locus_figure,
    sections_figure,
    spectrogram_figure,
    stability_map_figure,
    sweep_figure,
    time_history_figure,
)
from railhunt.simulation import SimulationResult
from railhunt.studies.sections import load_table1, section_changes, table1_values
from railhunt.studies.store import SweepResults
from railhunt.units import kmh_to_ms
from test_sections import line_rows

#: Resolution of the compared images (dots per inch): small files, still every line.
DPI = 50
#: Largest RMS difference (0-255) accepted: anti-aliasing and font rasterisation may
#: differ a little between machines; a moved curve, legend or label exceeds it.
TOLERANCE = 2
#: The frozen style: matplotlib's defaults (pytest-mpl resets them first) and a fixed font.
STYLE = {"font.family": "DejaVu Sans", "text.hinting": "none", "svg.hashsalt": "railhunt",
         "svg.fonttype": "path"}  # fmt: skip

compare = pytest.mark.mpl_image_compare(baseline_dir="baseline", style=STYLE,
                                        tolerance=TOLERANCE, savefig_kwargs={"dpi": DPI},
                                        deterministic=True)  # fmt: skip


# --------------------------------------------------------------------------- synthetic inputs


def _run(speed_kmh: float = 330.0, duration: float = 6.0) -> SimulationResult:
    """A run whose wheelsets settle from 8 mm on a 5 mm cycle at 4.5 Hz."""
    t = np.arange(0.0, duration, 0.005)
    w = 2 * math.pi * 4.5
    x = np.zeros((t.size, len(STATE_NAMES)))
    for k in range(1, 5):
        a = 5e-3 + 3e-3 * np.exp(-t) * (1.0 - 0.1 * k)
        da = -3e-3 * np.exp(-t) * (1.0 - 0.1 * k)
        phase = w * t - 0.6 * k
        x[:, STATE_NAMES.index(f"y_w{k}")] = a * np.sin(phase)
        x[:, STATE_NAMES.index(f"dy_w{k}")] = da * np.sin(phase) + a * w * np.cos(phase)
    return SimulationResult(t=t, x=x, speed=kmh_to_ms(speed_kmh), status="ok",
                            message="reached the end time", damper_velocity=np.zeros((t.size, 4)),
                            excitation_end=0.4)  # fmt: skip


def _entry_run(curve: railhunt.Curve, speed_kmh: float = 80.0) -> SimulationResult:
    """A curve entry: each wheelset moves out 4-7 mm through the transition (the later
    wheelsets 2.5 m, 17.5 m and 20 m behind), a yaw damper pulse, Y/Q of the outer wheel
    rising to 0.5."""
    v = kmh_to_ms(speed_kmh)
    t = np.arange(0.0, 120.0 / v, 0.02)
    x = np.zeros((t.size, len(STATE_NAMES)))
    lag = (0.0, 2.5, 17.5, 20.0)
    for k in range(1, 5):
        u = np.clip((v * t - lag[k - 1] - curve.start) / curve.transition, 0.0, 1.0)
        ramp = u * u * (3.0 - 2.0 * u)
        x[:, STATE_NAMES.index(f"y_w{k}")] = (4e-3 + 1e-3 * k) * ramp
        x[:, STATE_NAMES.index(f"F_d{k}")] = (-1) ** k * 3e3 * 6.0 * u * (1.0 - u)
    u = np.clip((v * t - curve.start) / curve.transition, 0.0, 1.0)
    derived = {"YQ_w1L": 0.5 * u * u * (3 - 2 * u), "YQ_w1R": -0.2 * u}
    return SimulationResult(t=t, x=x, speed=v, status="ok", message="reached the end time",
                            damper_velocity=np.zeros((t.size, 4)), derived=derived)


def _eigen() -> tuple[EigenResult, LinearCriticalSpeed]:
    """A hunting mode that crosses into the right half plane at 400 km/h, 2.5-4 Hz, and
    nine other pairs, two of them outside the zoomed view."""
    speeds = np.arange(200.0, 520.0, 20.0)
    s = (speeds - 200.0) / 300.0
    hunting = (-2.0 + 3.0 * s) + 1j * 2 * math.pi * (2.5 + 1.5 * s)
    others = [(-5.0 + 0.5 * k) + 1j * 2 * math.pi * (0.5 + 0.4 * k) for k in range(7)]
    others += [-40.0 + 1j * 2 * math.pi * 25.0, -60.0 + 1j * 2 * math.pi * 40.0]
    rows = []
    for h, sk in zip(hunting, s, strict=True):
        pairs = [h] + [o * (1.0 + 0.1 * sk) for o in others]
        lam = np.array([p for q in pairs for p in (q, q.conjugate())])
        rows.append(lam[np.argsort(-lam.real, kind="stable")])
    result = EigenResult(speeds_kmh=speeds, eigenvalues=np.array(rows), hunting=hunting)
    linear = LinearCriticalSpeed(400.0, 2.5 + 1.5 * 200.0 / 300.0, 1j * 2 * math.pi * 3.5, True)
    return result, linear


def _branch(origin: str, speed: np.ndarray, leading: np.ndarray, rear_factor: float,
            stable: np.ndarray) -> Branch:  # fmt: skip
    """A branch whose wheelsets 3-4 swing ``rear_factor`` times the leading wheelset's."""
    wheelsets = np.column_stack([leading, 1.05 * leading, rear_factor * leading,
                                 rear_factor * 1.02 * leading])  # fmt: skip
    turns = [i for i in range(1, speed.size - 1)
             if (speed[i] - speed[i - 1]) * (speed[i + 1] - speed[i]) < 0]  # fmt: skip
    return Branch(speed_kmh=speed, amplitude=leading, period=np.full(speed.size, 0.22),
                  stable=stable, max_multiplier=np.full(speed.size, 0.9),
                  wheelset_amplitudes=wheelsets, origin=origin,
                  folds=[Fold(float(speed[i]), float(leading[i]), i) for i in turns])


def _diagram(fold_kmh: float = 300.0, hopf_kmh: float = 440.0,
             hopf_type: str = "subcritical") -> BifurcationDiagram:  # fmt: skip
    """A Hopf branch turning at ``fold_kmh`` (unstable below the fold, stable above; both
    bogies hunt), and a second branch on which the rear bogie hunts at 8 mm while the
    leading wheelset moves 0.4 mm. ``supercritical-a``: the Hopf branch rises stable."""
    s = np.linspace(0.0, 1.0, 61)
    if hopf_type == "subcritical":
        k = 27
        speed = np.where(s <= s[k], fold_kmh + (hopf_kmh - fold_kmh) * ((s - s[k]) / s[k]) ** 2,
                         fold_kmh + (500.0 - fold_kmh) * ((s - s[k]) / (1 - s[k])) ** 2)
        stable = s > s[k]
    else:
        speed = hopf_kmh + (500.0 - hopf_kmh) * s**2
        stable = np.ones(s.size, dtype=bool)
    hopf = _branch("hopf", speed, 9e-3 * s**0.7, 0.9, stable)
    v2 = np.linspace(max(fold_kmh, 320.0), 500.0, 25)
    rear = _branch("simulation", v2, 4e-4 + 0.2e-3 * (v2 - v2[0]) / 180.0, 20.0,
                   np.ones(v2.size, dtype=bool))
    return BifurcationDiagram(branches=[hopf, rear], hopf_speed_kmh=hopf_kmh,
                              hopf_speed_from_orbits_kmh=hopf_kmh, hopf_frequency_hz=4.0,
                              fold_speed_kmh=min(fold_kmh, hopf_kmh), hopf_type=hopf_type,
                              speed_range_kmh=(200.0, 500.0), complete=True, message="")


def _contact() -> ContactGeometry:
    """A conical tread (Delta r = 0.1 y) with flange contact from |y| = 5 mm (a jump of the
    contact point onto the flange), mirrored between left and right."""
    y = np.linspace(-12e-3, 12e-3, 241)

    def side(u: np.ndarray) -> dict[str, np.ndarray]:
        flange = u > 5e-3
        return {"r": 0.43 + 0.05 * u + np.where(flange, 2e-3 + 1.2 * (u - 5e-3), 0.0),
                "delta": np.arctan(0.05) + np.where(flange, 1.1 - 40.0 * (u - 5e-3), 0.0),
                "wheel": -3.0 * u + np.where(flange, -20e-3, 0.0),
                "rail": -1.0 * u + np.where(flange, -15e-3, 0.0)}  # fmt: skip

    left, right = side(y), side(-y)
    jump = np.zeros(y.size, dtype=bool)
    jump[np.searchsorted(y, 5e-3, side="right")] = True
    jump[np.searchsorted(y, -5e-3)] = True
    return ContactGeometry(
        y=y, r_left=left["r"], r_right=right["r"], delta_left=left["delta"],
        delta_right=right["delta"], roll=-(left["r"] - right["r"]) / 1.5,
        contact_left=np.zeros((y.size, 2)), contact_right=np.zeros((y.size, 2)),
        wheel_left=left["wheel"], wheel_right=right["wheel"], rail_left=left["rail"],
        rail_right=right["rail"], jump=jump, r0=0.43,
        params={"wheel": "synthetic wheel", "rail": "synthetic rail",
                "rail_inclination": 0.025, "gauge": 1.435},
    )  # fmt: skip


def _sweep_rows() -> list[dict]:
    """Every Table 1 line: V_cr rising, f falling, a frequency jump after two points."""
    rows = []
    for name, entry in load_table1().items():
        values = table1_values(name, 3)
        speeds = 250 + 60 * np.sqrt(np.arange(values.size))
        sources = ["limit-cycle"] * 2 + ["eigenvalue"] * (values.size - 2)
        freqs = np.linspace(5, 3, values.size)
        rows += line_rows(name, values, speeds, freqs, sources,
                          frequency_speed=entry.frequency_speed_kmh)  # fmt: skip
    return rows


def _switching_signal() -> tuple[np.ndarray, np.ndarray]:
    """1 kHz record: 4.5 Hz hunting for 12 s, then 10 Hz (a damper blown off), 24 s."""
    t = np.arange(0.0, 24.0, 1e-3)
    y = np.where(t < 12.0, 1.0 * np.sin(2 * np.pi * 4.5 * t), 0.6 * np.sin(2 * np.pi * 10 * t))
    return t, y + 0.05 * np.sin(2 * np.pi * 1.1 * t)


def _stability_map() -> SweepResults:
    radii = [1000.0, 2000.0, 4000.0, 8000.0, math.inf]
    nonlinear = [180.0, 230.0, 280.0, math.nan, 301.0]
    linear = [250.0, 330.0, 400.0, 430.0, 441.3]
    rows = [{"point": k, "line": "", "radius_m": r, "cant_m": 0.15 if math.isfinite(r) else 0.0,
             "critical_speed_kmh": v, "linear_critical_speed_kmh": lin,
             "status": "ok" if math.isfinite(v) else "no-critical-speed", "message": ""}
            for k, (r, v, lin) in enumerate(zip(radii, nonlinear, linear, strict=True))]
    return SweepResults(rows, {"cant_m": 0.15})


# --------------------------------------------------------------------------- the images


@compare
def test_time_history_image():
    return time_history_figure(_run())


@compare
def test_root_locus_image():
    eig, linear = _eigen()
    return root_locus_figure(eig, linear)


@compare
def test_bifurcation_image():
    return bifurcation_figure(_diagram(), 3e-3)


@compare
def test_bifurcation_largest_wheelset_image():
    return bifurcation_figure(_diagram(), 3e-3, wheelset="largest")


@compare
def test_bifurcation_family_image():
    family = [(1e3, _diagram(260.0)), (3e3, _diagram(300.0)),
              (NO_BLOWOFF, _diagram(440.0, hopf_type="supercritical-a"))]  # fmt: skip
    return bifurcation_family_figure(family, wheelset="largest")


@compare
def test_hunting_frequency_image():
    speeds = np.arange(300.0, 410.0, 10.0)
    sources = ["eigenvalue"] * 7 + ["limit-cycle"] * 4
    freqs = np.where(speeds < 370.0, 3.4 + 0.01 * (speeds - 300.0), 4.8 + 0.005 * (speeds - 370))
    return hunting_frequency_figure(speeds, freqs, sources, 3e-3)


@compare
def test_contact_geometry_image():
    return contact_geometry_figure(_contact())


@compare
def test_sweep_lines_image():
    return sweep_figure(_sweep_rows(), ["C_d1", "K_px", "mu"])


@compare
def test_sections_image():
    return sections_figure(section_changes(_sweep_rows()))


@compare
def test_spectrogram_image():
    t, y = _switching_signal()
    spec = stft(t, y, window=2.0)
    return spectrogram_figure(spec, "STFT of acc", "m/s^2", dominant_bands(spec))


@compare
def test_stability_map_image():
    return stability_map_figure(_stability_map())


def _creep_curves():
    """Creep curves of three laws written by hand (tanh, a cubic, a line): no solver runs."""
    from railhunt.mechanics.curves import CreepCurves

    eta = np.linspace(0.0, 6e-3, 25)
    mu_n = 0.3 * 5e4
    cv = CreepCurves("eta", eta, {"xi": 0.0, "phi": 0.5}, 6e-3, 4e-3, 5e4, 0.3, 8.2e10, 0.28)
    s = eta / 2e-3
    for law, f, m in (("exact", -np.tanh(s), 0.1 * s * np.exp(-s)),
                      ("fastsim-modified", -np.minimum(1.0, s - s**2 / 3 + s**3 / 27),
                       0.08 * s * np.exp(-0.8 * s)),
                      ("linear", -s, 0.2 * s)):  # fmt: skip
        cv.fx[law] = 0.0 * eta
        cv.fy[law] = f * mu_n
        cv.mz[law] = m * mu_n * cv.c
    return cv


@compare
def test_creep_curves_image():
    return creep_figure(_creep_curves())


@compare
def test_curve_entry_image():
    curve = railhunt.Curve(300.0, cant=0.15, transition=40.0, start=30.0)
    return curve_entry_figure(_entry_run(curve), railhunt.Vehicle.paper2019(), curve=curve)


# --------------------------------------------------------------------------- what they show


def _legends_clear_of_axes(fig) -> None:
    """Every figure-level legend lies outside every (visible) axes."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    assert fig.legends, "the figure has no legend"
    for legend in fig.legends:
        box = legend.get_window_extent(renderer)
        for ax in fig.axes:
            if ax.get_visible():
                assert not box.overlaps(ax.get_window_extent(renderer)), ax.get_title()


def _line_top_mm(ax) -> float:
    return max(float(np.nanmax(line.get_ydata())) for line in ax.get_lines()
               if len(line.get_ydata()))  # fmt: skip


def test_bifurcation_amplitude_choices():
    d = _diagram()
    # Leading wheelset: the Hopf branch reaches 9 mm (9 mm * s**0.7 at s = 1).
    ax = bifurcation_figure(d, 3e-3).axes[0]
    assert _line_top_mm(ax) == pytest.approx(9.0)
    assert ax.get_ylim()[0] == 0.0
    # Largest wheelset: the second branch's rear wheelset 4 swings 20 * 1.02 times the
    # leading wheelset's 0.6 mm at 500 km/h; the Hopf branch's wheelset 2, 1.05 * 9 mm.
    fig = bifurcation_figure(d, 3e-3, wheelset="largest")
    assert _line_top_mm(fig.axes[0]) == pytest.approx(20 * 1.02 * 0.6)
    assert "largest wheelset" in fig.axes[0].get_ylabel()
    texts = [t.get_text() for t in fig.legends[0].get_texts()]
    assert any(t.startswith("Hopf branch (both bogies hunt)") for t in texts), texts
    assert any(t.startswith("branch 2 (rear bogie hunts)") for t in texts), texts
    _legends_clear_of_axes(fig)


def test_point_p_sits_on_its_branch_in_both_views():
    from railhunt.plots.stability import _point_p, branch_amplitude, hunting_bogie

    d = _diagram()
    # y_w1 = 9 mm * s**0.7 = 3 mm at s = (1/3)**(1/0.7), on the unstable part (s < 0.45)
    # where the speed is 300 + 140 ((s - 0.45) / 0.45)**2 km/h.
    s_p = (1 / 3) ** (1 / 0.7)
    v_p = 300 + 140 * ((s_p - 0.45) / 0.45) ** 2
    speed, leading = _point_p(d, 3e-3, "leading")
    assert speed == pytest.approx(v_p, abs=1.0) and leading == pytest.approx(3e-3)
    assert speed == pytest.approx(d.point_p_kmh(3e-3))
    speed, largest = _point_p(d, 3e-3, "largest")
    assert largest == pytest.approx(1.05 * 3e-3)  # wheelset 2 is the largest on that branch
    assert np.array_equal(branch_amplitude(d.branches[1], "largest"),
                          d.branches[1].wheelset_amplitudes[:, 3])  # fmt: skip
    assert [hunting_bogie(b) for b in d.branches] == ["both", "rear"]


def test_wheelset_choice_is_checked():
    with pytest.raises(ValueError, match="wheelset = 'rear' is invalid: must be one of "
                       "'leading', 'largest'"):  # fmt: skip
        bifurcation_figure(_diagram(), wheelset="rear")
    with pytest.raises(ValueError, match="family is empty"):
        bifurcation_family_figure([])


def test_family_shares_one_scale_from_zero():
    family = [(1e3, _diagram(260.0)), (NO_BLOWOFF, _diagram(440.0, hopf_type="supercritical-a"))]
    fig = bifurcation_family_figure(family)
    limits = {ax.get_ylim() for ax in fig.axes if ax.get_visible()}
    assert len(limits) == 1
    low, top = limits.pop()
    assert low == 0.0 and top >= 9.0  # the largest y_w1 of either member is 9 mm
    assert "one scale" in fig._suptitle.get_text()
    assert [ax.get_title() for ax in fig.axes][1] == (
        "F_u = no blow-off: supercritical-a, V_nl 440 km/h")
    _legends_clear_of_axes(fig)


def test_contact_figure_has_one_unit_per_axis_and_labelled_jumps():
    import re

    geo = _contact()
    fig = contact_geometry_figure(geo)
    for ax in fig.axes:
        title = ax.get_title(loc="left")
        assert len(re.findall(r"\((mm|deg|mrad)\)", title)) == 1, title
    for ax in fig.axes[:2]:  # the top panels carry the jumps' positions (mm), at +-5 mm
        labels = sorted(float(t.get_text()) for t in ax.texts)
        assert labels == pytest.approx([-5.0, 5.0], abs=0.11)  # the 0.1 mm grid
    _legends_clear_of_axes(fig)


def test_spectrogram_view():
    from railhunt.plots.spectrogram import DEFAULT_FMAX, default_fmax

    t, y = _switching_signal()
    spec = stft(t, y, window=2.0)
    bands = dominant_bands(spec)
    ax = spectrogram_figure(spec, bands=bands).axes[0]
    assert ax.get_ylim() == (0.0, DEFAULT_FMAX) == (0.0, 20.0)
    assert ax.collections[0].get_cmap().name == "viridis"
    assert "dominant frequency" in ax.get_legend().get_texts()[0].get_text()
    full = spectrogram_figure(spec, bands=bands, full_range=True).axes[0].get_ylim()
    assert full == pytest.approx((0.0, 500.0))  # the Nyquist frequency of 1 kHz sampling
    assert spectrogram_figure(spec, bands=bands, fmax=8.0).axes[0].get_ylim() == (0, 8)
    # A strong 40 Hz band: twice its upper edge (40 Hz, on a bin of the 2 s window).
    strong = stft(t, np.sin(2 * np.pi * 40.0 * t), window=2.0)
    assert default_fmax(strong, dominant_bands(strong)) == 80.0
    with pytest.raises(ValueError, match="fmax = -1 Hz is invalid"):
        spectrogram_figure(spec, fmax=-1)


# --------------------------------------------------------------------------- report.html


def test_report_table_fits_and_figures_keep_their_shape(tmp_path):
    from html.parser import HTMLParser

    from railhunt.plots import new_figure, save_figure
    from railhunt.studies.records import Headline, Report, Step
    from railhunt.studies.report import _CSS, build_html, compact_difference, png_size

    fig = new_figure(3.0, 1.5)
    fig.add_subplot(1, 1, 1).plot([0, 1], [0, 1])
    png = save_figure(fig, tmp_path / "a.png")  # 3 x 1.5 in at 120 dpi
    assert png_size(png) == (360, 180)
    row = Headline("k", "a quantity", "Fig. 6", "km/h", 321.0, 301.0, "-20 km/h (-6.2 %)",
                   False, "The paper's sentence.", "why " * 80)  # fmt: skip
    assert compact_difference(row) == "-20 (-6.2 %)"
    step = Step("fig6", "Fig. 6", "caption", figures=[png], headline=[row])
    report = Report(tmp_path, tmp_path / "r.html", tmp_path / "h.json", [step], "paper2019",
                    "0.1.0", "2026-01-01T00:00:00+00:00", False, 1.0)  # fmt: skip
    text = build_html(report)

    class Tags(HTMLParser):
        def __init__(self) -> None:
            super().__init__()
            self.tags: list[tuple[str, dict]] = []

        def handle_starttag(self, tag, attrs):
            self.tags.append((tag, dict(attrs)))

    doc = Tags()
    doc.feed(text)
    images = [a for t, a in doc.tags if t == "img"]
    assert [(a["width"], a["height"]) for a in images] == [("360", "180")]
    cols = [a["class"] for t, a in doc.tags if t == "col"]
    assert cols == ["quantity", "value", "value", "diff", "unit", "where", "why"]
    assert "-20 (-6.2&nbsp;%)" in text
    assert "table.headline { width: 100%; table-layout: fixed;" in _CSS
    assert "figure img { max-width: 100%; height: auto;" in _CSS
    assert not any(t in ("script", "link") for t, _ in doc.tags)


# --------------------------------------------------------------------------- command line


def test_spectrogram_cli_range_flags(tmp_path):
    from test_cli import PNG_SIGNATURE, assert_input_error, run

    t, y = _switching_signal()
    path = tmp_path / "sig.csv"
    np.savetxt(path, np.column_stack([t[::5], y[::5]]), delimiter=",", header="t [s],acc",
               comments="", fmt="%.10g")  # fmt: skip
    png = tmp_path / "full.png"
    result = run("spectrogram", str(path), "--channel", "acc", "--png", str(png), "--full-range")
    assert result.exit_code == 0, result.stderr
    assert png.read_bytes().startswith(PNG_SIGNATURE)
    assert_input_error(run("spectrogram", str(path), "--channel", "acc", "--full-range"),
                       "--full-range only applies with --png")  # fmt: skip
    assert_input_error(run("spectrogram", str(path), "--channel", "acc", "--png", str(png),
                           "--full-range", "--fmax", "30"),
                       "--full-range and --fmax exclude each other", "30 Hz")  # fmt: skip


def test_bifurcation_cli_wheelset_choice():
    from test_cli import run

    result = run("bifurcation", "--wheelset", "rear")
    assert result.exit_code == 2 and "Traceback" not in result.stderr
    assert "--wheelset" in result.stderr and "'leading', 'largest'" in result.stderr

"""``railhunt spectrogram`` and the STFT analysis behind it, on synthetic signals."""

import json

import numpy as np
import pytest

from railhunt.analysis.spectrogram import dominant_frequency_track, read_channel, stft
from test_cli import PNG_SIGNATURE, assert_input_error, run


def write_csv(path, t, y, header="t [s],acc [m/s^2]"):
    np.savetxt(path, np.column_stack([t, y]), delimiter=",", header=header, comments="",
               fmt="%.10g")  # fmt: skip
    return path


def switching_sine(fs=200.0, f1=3.0, f2=7.25, t_switch=20.0, duration=40.0):
    t = np.arange(0.0, duration, 1.0 / fs)
    y = np.where(t < t_switch, 1.0 * np.sin(2 * np.pi * f1 * t), 0.5 * np.sin(2 * np.pi * f2 * t))
    return t, y


def test_switching_sine_bands_within_one_bin(tmp_path):
    # 3 Hz then 7.25 Hz (between the 0.5 Hz bins of a 2 s window): each stretch is found,
    # the switch time within one window, the frequency within one bin, amplitudes ~1, 0.5.
    t, y = switching_sine()
    path = write_csv(tmp_path / "sig.csv", t, y)
    result = run("spectrogram", str(path), "--channel", "acc", "--json")
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["resolution_hz"] == pytest.approx(0.5)
    bands = [b for b in data["bands"] if b["end_s"] - b["start_s"] >= 2.0]
    assert len(bands) == 2, data["bands"]
    first, second = bands
    assert first["frequency_hz"] == pytest.approx(3.0, abs=0.5)
    assert second["frequency_hz"] == pytest.approx(7.25, abs=0.5)
    assert first["end_s"] == pytest.approx(20.0, abs=2.0)
    assert second["start_s"] == pytest.approx(20.0, abs=2.0)
    assert first["low_hz"] <= 3.0 <= first["high_hz"]
    assert first["amplitude"] == pytest.approx(1.0, rel=0.1)
    assert 0.3 < second["amplitude"] < 0.55  # off-bin: Hann scalloping loses up to 15 %


def test_chirp_dominant_frequency_follows_instantaneous_frequency():
    fs, duration = 250.0, 60.0
    t = np.arange(0.0, duration, 1 / fs)
    f0, f1 = 1.0, 10.0
    rate = (f1 - f0) / duration
    y = np.sin(2 * np.pi * (f0 * t + 0.5 * rate * t**2))
    spec = stft(t, y, window=2.0)
    peak, low, high, amp = dominant_frequency_track(spec)
    inst = f0 + rate * spec.times
    assert np.max(np.abs(peak - inst)) <= spec.resolution
    assert np.all((low <= inst + spec.resolution) & (high >= inst - spec.resolution))


def test_reads_simulate_csv_columns_without_unit(tmp_path):
    t = np.arange(0, 10, 0.01)
    path = tmp_path / "run.csv"
    np.savetxt(path, np.column_stack([t, np.sin(2 * np.pi * 4 * t), t]), delimiter=",",
               header="t [s],y_w1 [m],other", comments="")  # fmt: skip
    tt, yy, name = read_channel(path, "y_w1")
    assert name == "y_w1 [m]" and tt.size == 1000
    result = run("spectrogram", str(path), "--channel", "y_w1 [m]", "--window", "1")
    assert result.exit_code == 0, result.stderr
    assert "4 " in result.stdout and "strongest: 4 Hz" in result.stdout


def test_png(tmp_path):
    t, y = switching_sine()
    path = write_csv(tmp_path / "sig.csv", t, y)
    png = tmp_path / "stft.png"
    result = run("spectrogram", str(path), "--channel", "acc", "--png", str(png), "--fmax", "20")
    assert result.exit_code == 0, result.stderr
    assert png.read_bytes().startswith(PNG_SIGNATURE)


def test_fmin_fmax_restrict_the_search(tmp_path):
    t = np.arange(0.0, 20.0, 0.005)
    y = 1.0 * np.sin(2 * np.pi * 1.0 * t) + 0.2 * np.sin(2 * np.pi * 10.0 * t)
    path = write_csv(tmp_path / "two.csv", t, y)
    result = run("spectrogram", str(path), "--channel", "acc", "--fmin", "5", "--json")
    data = json.loads(result.stdout)
    assert all(b["frequency_hz"] == pytest.approx(10.0, abs=0.5) for b in data["bands"])


# --------------------------------------------------------------------------- errors


def test_missing_column_lists_available(tmp_path):
    t, y = switching_sine()
    path = write_csv(tmp_path / "sig.csv", t, y)
    result = run("spectrogram", str(path), "--channel", "ay")
    assert_input_error(result, "no column 'ay'", "available columns: t [s], acc [m/s^2]")


def test_missing_time_column(tmp_path):
    path = tmp_path / "x.csv"
    path.write_text("a,b\n1,2\n2,3\n")
    assert_input_error(run("spectrogram", str(path), "--channel", "b"),
                       "no time column", "columns are: a, b")  # fmt: skip


def test_non_uniform_record(tmp_path):
    t, y = switching_sine()
    t = t.copy()
    t[500:] += 0.002  # one step of 7 ms instead of 5 ms
    path = write_csv(tmp_path / "jit.csv", t, y)
    assert_input_error(run("spectrogram", str(path), "--channel", "acc"),
                       "non-uniform sampling", "resample")  # fmt: skip


def test_too_short_record(tmp_path):
    t = np.arange(0, 3, 0.01)
    path = write_csv(tmp_path / "short.csv", t, np.sin(t))
    assert_input_error(run("spectrogram", str(path), "--channel", "acc"),
                       "too short", "two windows of 2 s")  # fmt: skip


@pytest.mark.parametrize(
    "text, fragments",
    [
        ("t,acc\n0,1\n0.01,x\n", ["line 3", "'x' is not a number"]),
        ("t,acc\n0,1\n0,1\n0.01,2\n", ["time must increase"]),
        ("", ["empty"]),
    ],
)
def test_bad_files(tmp_path, text, fragments):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    assert_input_error(run("spectrogram", str(path), "--channel", "acc"), *fragments)


def test_missing_file_and_bad_options(tmp_path):
    assert_input_error(run("spectrogram", str(tmp_path / "none.csv"), "--channel", "a"),
                       "none.csv", "no such file")  # fmt: skip
    t, y = switching_sine()
    path = write_csv(tmp_path / "sig.csv", t, y)
    assert_input_error(run("spectrogram", str(path), "--channel", "acc", "--window", "0"),
                       "--window")  # fmt: skip
    assert_input_error(run("spectrogram", str(path), "--channel", "acc", "--fmin", "9",
                           "--fmax", "3"), "--fmin")  # fmt: skip
    assert_input_error(run("spectrogram", str(path), "--channel", "acc", "--window", "0.01"),
                       "at least 8")  # fmt: skip
    assert_input_error(run("spectrogram", str(path)), "--channel")


@pytest.mark.parametrize("unit, factor", [("ms", 1e3), ("min", 1.0 / 60.0), ("s", 1.0)])
def test_time_column_units_are_converted_to_seconds(tmp_path, unit, factor):
    # The same 3 Hz sine recorded with its time in ms, min or s: the same frequency.
    t = np.arange(0.0, 20.0, 0.005)
    path = write_csv(tmp_path / "u.csv", t * factor, np.sin(2 * np.pi * 3.0 * t),
                     header=f"t [{unit}],acc [m/s^2]")  # fmt: skip
    result = run("spectrogram", str(path), "--channel", "acc", "--json")
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["sampling_hz"] == pytest.approx(200.0, rel=1e-6)
    assert [b["frequency_hz"] for b in data["bands"]] == [pytest.approx(3.0, abs=0.5)]


@pytest.mark.parametrize("unit", ["h", "samples", "m"])
def test_a_time_unit_other_than_seconds_is_refused(tmp_path, unit):
    t = np.arange(0.0, 20.0, 0.005)
    path = write_csv(tmp_path / "u.csv", t, np.sin(t), header=f"time [{unit}],acc")
    assert_input_error(run("spectrogram", str(path), "--channel", "acc"),
                       f"'time [{unit}]' is in '{unit}'", "expected seconds")  # fmt: skip


def test_a_byte_order_mark_is_skipped(tmp_path):
    t = np.arange(0.0, 10.0, 0.01)
    path = tmp_path / "bom.csv"
    write_csv(path, t, np.sin(2 * np.pi * 2.0 * t))
    path.write_bytes(b"\xef\xbb\xbf" + path.read_bytes())
    tt, _, _ = read_channel(path, "acc")
    assert tt[1] == pytest.approx(0.01)


@pytest.mark.parametrize("level", [0.0, 9.81])
def test_a_constant_signal_is_no_signal(tmp_path, level):
    # All zeros, or a constant (gravity): nothing vibrates, so no band dominates.
    t = np.arange(0.0, 10.0, 0.01)
    path = write_csv(tmp_path / "flat.csv", t, np.full(t.size, level))
    result = run("spectrogram", str(path), "--channel", "acc", "--json")
    assert result.exit_code == 0, result.stderr
    bands = json.loads(result.stdout)["bands"]
    assert [b["no_signal"] for b in bands] == [True]
    assert bands[0]["frequency_hz"] is None
    table = run("spectrogram", str(path), "--channel", "acc")
    assert "no signal" in table.stdout and "strongest" not in table.stdout


def test_a_silent_stretch_is_its_own_band(tmp_path):
    t = np.arange(0.0, 30.0, 0.01)
    y = np.where(t < 15.0, np.sin(2 * np.pi * 4.0 * t), 0.0)
    spec = stft(t, y)
    from railhunt.analysis.spectrogram import dominant_bands

    bands = dominant_bands(spec)
    assert not bands[0].no_signal and bands[0].frequency == pytest.approx(4.0, abs=0.5)
    assert bands[-1].no_signal and bands[-1].start > 15.0

"""Stochastic track irregularities: PSD of generated profiles, seeds, measured files."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.signal import welch

from railhunt.irregularity import (
    SPECTRA,
    load_irregularity,
    track_irregularity,
    track_spectrum,
)
from railhunt.track import SampledTrack


def welch_rad(track, nperseg=2048):
    """One-sided PSD estimate in m^2/(rad/m) versus Omega (rad/m), from Welch in cycles/m."""
    f, p = welch(track.alignment[:-1], fs=1.0 / track.ds, nperseg=nperseg)
    return 2 * np.pi * f, p / (2 * np.pi)


@pytest.mark.parametrize("name", ["german-low", "german-high", "fra-6", "fra-4"])
@pytest.mark.parametrize("seed", [1, 2])
def test_welch_psd_follows_target_over_band(name, seed):
    # Six log-spaced bands inside the 3-150 m wavelength band (kept a factor 2 away from the
    # long-wavelength edge and 1.2 from the short one, where the Hann window smears the
    # band's hard edges): the Welch estimate averaged over each band must match the
    # target within 20 % (the spread over 40 seeds is at most 25 %, mostly in the lowest
    # band with ~5 bins). A one-/two-sided mix-up (x2) or cycles/m vs rad/m (x2*pi) fails.
    track = track_irregularity(name, length=3000.0, dx=0.25, seed=seed, taper=0.0)
    omega, s_est = welch_rad(track)
    spec = track_spectrum(name)
    lo, hi = track.band
    edges = np.geomspace(2 * 2 * np.pi / hi, 2 * np.pi / lo / 1.2, 7)
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        m = (omega >= a) & (omega < b)
        assert m.sum() >= 4
        ratio = s_est[m].mean() / spec.psd(omega[m]).mean()
        assert 0.8 < ratio < 1.25, (name, a, b, ratio)


@pytest.mark.parametrize("name", ["german-low", "fra-5"])
def test_variance_equals_integral_of_psd_over_band(name):
    # Random-phase synthesis: the profile's variance is the quadrature of the target PSD
    # over the band. Within 2 %: the FFT grid's rectangle rule (spacing 2*pi/L) against a
    # fine trapezoid; with L = 12 km its bias at the steep long-wavelength edge is ~0.6 %
    # (with L = 3 km it is 2.5 %).
    track = track_irregularity(name, length=12000.0, dx=0.25, seed=7, taper=0.0)
    var = np.mean(track.alignment[:-1] ** 2)
    assert var == pytest.approx(track_spectrum(name).variance(track.band), rel=0.02)


def test_nothing_outside_band():
    track = track_irregularity("german-high", length=3000.0, dx=0.25, seed=3, taper=0.0,
                               band=(10.0, 50.0))  # fmt: skip
    spectrum = np.abs(np.fft.rfft(track.alignment[:-1])) ** 2
    k = np.arange(spectrum.size)
    wavelength = np.divide(3000.0, k, out=np.full(k.size, np.inf), where=k > 0)
    inside = (wavelength >= 10.0) & (wavelength <= 50.0)
    assert spectrum[~inside].sum() < 1e-20 * spectrum[inside].sum()


def test_published_constants_and_ordering():
    low, high = SPECTRA["german-low"], SPECTRA["german-high"]
    # German spectra: same corner frequencies, A_a ratio 6.125/2.119.
    assert low.omega_c == high.omega_c == 0.8246 and low.omega_r == 0.0206
    w = np.geomspace(0.01, 10, 50)
    assert np.allclose(high.psd(w) / low.psd(w), 6.125 / 2.119)
    # The formula by hand at Omega = 0.1 rad/m (m^2/(rad/m)).
    wc, wr = 0.8246, 0.0206
    by_hand = 2.119e-7 * wc**2 / ((0.1**2 + wr**2) * (0.1**2 + wc**2))
    assert low.psd(0.1) == pytest.approx(by_hand, rel=1e-12)
    # FRA: class 6 (best) smoother than class 1 (worst); k*A_a/Omega^2 below Omega_c.
    rms = [math.sqrt(SPECTRA[f"fra-{c}"].variance()) for c in range(1, 7)]
    assert all(a > b for a, b in zip(rms, rms[1:], strict=False))
    assert SPECTRA["fra-6"].psd(0.05) == pytest.approx(0.25 * 0.0339e-4 / 0.05**2, rel=0.01)
    # German high-speed low disturbance is better track than FRA class 6.
    assert low.variance() < SPECTRA["fra-6"].variance()


def test_same_seed_same_track_different_seed_different():
    a = track_irregularity("german-low", length=500.0, seed=11)
    b = track_irregularity("german-low", length=500.0, seed=11)
    c = track_irregularity("german-low", length=500.0, seed=12)
    assert np.array_equal(a.alignment, b.alignment)
    assert not np.allclose(a.alignment, c.alignment)
    assert abs(np.corrcoef(a.alignment, c.alignment)[0, 1]) < 0.3


def test_is_a_sampled_track_with_smooth_ends():
    track = track_irregularity("german-low", length=500.0, dx=0.25, seed=1, start=5.0)
    assert isinstance(track, SampledTrack)
    assert track.alignment[0] == 0.0 and track.alignment[-1] == pytest.approx(0.0, abs=1e-15)
    assert track.end() == pytest.approx(505.0)
    assert track.distance[0] == 5.0 and track.length == pytest.approx(500.0)
    assert 0.5e-3 < track.rms < 5e-3


def test_scale_scales_amplitude():
    a = track_irregularity("german-low", length=500.0, seed=4)
    b = track_irregularity("german-low", length=500.0, seed=4, scale=2.0)
    assert np.allclose(b.alignment, 2 * a.alignment)


@pytest.mark.parametrize(
    "kwargs, fragment",
    [
        ({"spectrum": "german"}, "spectrum = 'german'"),
        ({"length": 5.0}, "length = 5.0"),
        ({"dx": 0.0}, "dx = 0.0"),
        ({"dx": 1.0}, "quarter of the shortest"),
        ({"band": (50.0, 10.0)}, "band"),
        ({"length": 100.0}, "longest wavelength"),
        ({"taper": -1.0}, "taper"),
    ],
)
def test_invalid_arguments(kwargs, fragment):
    with pytest.raises(ValueError, match=None) as err:
        track_irregularity(**kwargs)
    assert fragment in str(err.value)


@settings(max_examples=25, deadline=None)
@given(length=st.floats(150.0, 1500.0), dx=st.floats(0.05, 0.75),
       seed=st.integers(0, 2**32 - 1))  # fmt: skip
def test_generated_track_invariants(length, dx, seed):
    track = track_irregularity("fra-6", length=length, dx=dx, seed=seed)
    assert np.all(np.isfinite(track.alignment))
    assert track.length == pytest.approx(length, abs=dx)
    assert np.max(np.abs(track.alignment)) < 0.05


# --------------------------------------------------------------------------- measured files


def test_load_measured_file_resamples_and_converts_units(tmp_path):
    s = np.array([0.0, 0.5, 1.0, 1.5, 2.5, 3.0])
    y = np.array([0.0, 1.0, 2.0, 1.0, -1.0, 0.0])  # mm
    path = tmp_path / "meas.csv"
    lines = ["distance [m],gauge [mm],alignment [mm]"]
    lines += [f"{a},0,{b}" for a, b in zip(s, y, strict=True)]
    path.write_text("\n".join(lines) + "\n")
    track = load_irregularity(path)
    assert track.spectrum == "measured" and track.ds == 0.5
    assert np.allclose(track.distance, np.arange(0.0, 3.01, 0.5))
    assert np.allclose(track.alignment, np.interp(track.distance, s, y) * 1e-3)


def test_round_trip_of_generated_track(tmp_path):
    track = track_irregularity("german-high", length=300.0, dx=0.5, seed=2, start=10.0)
    path = tmp_path / "track.csv"
    np.savetxt(path, np.column_stack([track.distance, track.alignment]), delimiter=",",
               header="distance,alignment", comments="")  # fmt: skip
    back = load_irregularity(path, start=None)
    assert back.s0 == 10.0 and back.ds == pytest.approx(0.5)
    assert np.allclose(back.alignment, track.alignment, atol=1e-12)
    assert load_irregularity(path).s0 == 0.0  # by default the record starts at 0


def test_measured_file_taper(tmp_path):
    s = np.arange(0.0, 100.01, 0.5)
    path = tmp_path / "flat.csv"
    np.savetxt(path, np.column_stack([s, np.full(s.size, 0.002)]), delimiter=",",
               header="distance,alignment", comments="")  # fmt: skip
    track = load_irregularity(path, taper=10.0)
    assert track.alignment[0] == 0.0 and track.alignment[-1] == pytest.approx(0.0, abs=1e-18)
    assert np.allclose(track.alignment[20:-20], 0.002)  # untouched beyond 10 m
    assert 0.0 < track.alignment[10] < 0.002
    with pytest.raises(ValueError, match="taper"):
        load_irregularity(path, taper=80.0)


@pytest.mark.parametrize(
    "text, fragment",
    [
        ("s,y\n0,0\n1,0\n", "no 'distance' column; columns are: s, y"),
        ("distance,alignment\n0,0\n", "at least 2 data rows"),
        ("distance,alignment\n0,0\n1,x\n", "line 3: alignment 'x' is not a number"),
        ("distance,alignment\n0,0\n1,0\n1,0\n", "line 4: distances must increase"),
        ("distance,alignment\n0,0\n1,3\n", "within ±0.05 m"),
        ("distance [ft],alignment\n0,0\n1,0\n", "unit 'ft'"),
        ("", "empty"),
    ],
)
def test_bad_measured_files(tmp_path, text, fragment):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(ValueError) as err:
        load_irregularity(path)
    assert fragment in str(err.value)

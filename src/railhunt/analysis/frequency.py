"""Hunting frequency: from the hunting eigenvalue below the jump, from the limit cycle above.

The paper (Sec. 3.3) computes the hunting frequency of the leading wheelset in two ways:
where a disturbance of the wheelsets dies out, from the imaginary part of the hunting
eigenvalue of the linearised model; where it grows to a limit cycle, from the spectrum of
the simulated displacement after the transient. :func:`hunting_frequency` does both: it
simulates the vehicle released from an initial lateral displacement of its wheelsets,
judges the run (decay or limit cycle, :func:`railhunt.analysis.critical.judge`) and
reports the matching frequency. For a limit cycle it also refines the orbit by shooting
(:func:`railhunt.analysis.periodic.periodic_orbit`) from the state at the end of the run,
settled or not, and reports ``1 / period``, which is exact where the FFT is limited by
its resolution. ``source`` says which estimate was used: ``"limit-cycle"`` (the orbit) or
``"limit-cycle-fft"`` (the FFT's peak, when no orbit was accepted; ``orbit_rejected`` says
why); :func:`frequency_kind` groups both as the limit cycle's frequency.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from railhunt.analysis.critical import HUNTING, STABLE, Judgement, run_until_verdict
from railhunt.analysis.hunting_branch import hunting_mode_at
from railhunt.analysis.modes import eigenvalues
from railhunt.analysis.periodic import phase_origin, shoot_orbit
from railhunt.model import Model
from railhunt.results import Columns, ResultDisplay, Row
from railhunt.simulation import auto_step, excitation_end_time, integrate_model
from railhunt.track import SampledTrack, SingleDefect, check_excitation
from railhunt.units import kmh_to_ms
from railhunt.vehicle import Vehicle

#: Sources of a limit cycle's frequency: the orbit found by shooting, the FFT's peak.
LIMIT_CYCLE_SOURCES = ("limit-cycle", "limit-cycle-fft")


def frequency_kind(source: str) -> str:
    """What a frequency ``source`` measures: ``"limit-cycle"`` for both of the limit cycle's
    estimates (:data:`LIMIT_CYCLE_SOURCES`), else the source itself (``"eigenvalue"``,
    ``"limit-exceeded"``). A frequency jump is a change of kind, not of estimate."""
    return "limit-cycle" if source in LIMIT_CYCLE_SOURCES else source


def dominant_frequency(y: np.ndarray, dt: float) -> tuple[float, np.ndarray, np.ndarray]:
    """Main frequency of a uniformly sampled signal, refined between FFT bins (Hz).

    The signal's mean is removed and a Hann window applied; the largest bin of the
    one-sided amplitude spectrum (DC excluded) is refined by fitting a parabola to the
    logarithm of the three bins around it (exact for a Gaussian peak; for a Hann-windowed
    sine the error is below 2 % of a bin).

    Parameters
    ----------
    y : numpy.ndarray
        Samples.
    dt : float
        Sampling interval (s).

    Returns
    -------
    frequency : float
        Refined peak frequency (Hz); NaN for a constant or too short signal.
    freqs, amplitude : numpy.ndarray
        The spectrum (Hz, signal units).
    """
    y = np.asarray(y, dtype=float)
    if y.size < 8 or not (math.isfinite(dt) and dt > 0):
        return math.nan, np.empty(0), np.empty(0)
    w = np.hanning(y.size)
    spec = np.abs(np.fft.rfft((y - y.mean()) * w)) * 2.0 / w.sum()
    freqs = np.fft.rfftfreq(y.size, dt)
    if spec.size < 3 or np.max(spec[1:]) <= 0:
        return math.nan, freqs, spec
    k = 1 + int(np.argmax(spec[1:]))
    f = freqs[k]
    if 1 <= k < spec.size - 1 and spec[k - 1] > 0 and spec[k + 1] > 0:
        a, b, c = np.log(spec[k - 1]), np.log(spec[k]), np.log(spec[k + 1])
        den = a - 2 * b + c
        if den < 0:
            f += 0.5 * (a - c) / den * (freqs[1] - freqs[0])
    return float(f), freqs, spec


@dataclass(repr=False)
class HuntingFrequency(ResultDisplay):
    """Outcome of :func:`hunting_frequency`.

    Attributes
    ----------
    speed_kmh : float
        Speed (km/h).
    frequency_hz : float
        The hunting frequency (Hz): ``eigen_frequency_hz`` when the disturbance decays,
        else the limit cycle's (``orbit_frequency_hz`` where shooting converged, otherwise
        ``fft_frequency_hz``).
    source : str
        Which estimate ``frequency_hz`` is: ``"eigenvalue"``; ``"limit-cycle"`` (``1 /
        period`` of the orbit found by shooting from the end of the run);
        ``"limit-cycle-fft"`` (the FFT's peak: no orbit was accepted, ``orbit_rejected``
        says why); or ``"limit-exceeded"`` when the run left the derailment limit (or
        diverged) before settling: no frequency (NaN).
    verdict : str
        ``"stable"`` (the disturbance decays), ``"hunting"``, ``"undecided"``,
        ``"derailed"`` or ``"blow-up"`` (:mod:`railhunt.verdicts`).
    amplitude : float
        Amplitude of the leading wheelset on the limit cycle (m); 0 when stable.
    eigen_frequency_hz : float
        Frequency of the hunting eigenvalue at this speed (Hz).
    eigen_damping_ratio : float
        Its damping ratio (dimensionless; negative when the equilibrium is unstable).
    fft_frequency_hz : float
        Spectral peak of the leading wheelset's displacement after the transient (Hz);
        NaN when stable.
    orbit_frequency_hz : float
        ``1 / period`` of the limit cycle refined by shooting (Hz); NaN when stable or
        when shooting did not converge.
    t, y, damper_velocity : numpy.ndarray
        The simulated history: time (s), leading wheelset displacement (m) and the
        velocities of the four yaw dampers' viscous parts (m/s), for plots such as Fig. 8.
    blowoff_velocity : float
        The dampers' blow-off velocity ``v_u`` (m/s).
    orbit_rejected : str
        Why the shooting's orbit was not used ("" when it was, or when the motion decays):
        shooting did not converge, fell onto the equilibrium, or found another orbit than
        the simulated cycle.
    """

    speed_kmh: float
    frequency_hz: float
    source: str
    verdict: str
    amplitude: float
    eigen_frequency_hz: float
    eigen_damping_ratio: float
    fft_frequency_hz: float
    orbit_frequency_hz: float
    t: np.ndarray
    y: np.ndarray
    damper_velocity: np.ndarray
    blowoff_velocity: float
    orbit_rejected: str = ""

    def _summary(self) -> list[Row]:
        return [("speed", self.speed_kmh, "km/h"), ("hunting frequency", self.frequency_hz, "Hz"),
                ("source", self.source, ""), ("verdict", self.verdict, ""),
                ("limit-cycle amplitude", self.amplitude, "m"),
                ("eigenvalue frequency", self.eigen_frequency_hz, "Hz"),
                ("eigenvalue damping ratio", self.eigen_damping_ratio, ""),
                ("FFT frequency", self.fft_frequency_hz, "Hz"),
                ("orbit frequency", self.orbit_frequency_hz, "Hz"),
                ("orbit rejected because", self.orbit_rejected or "-", ""),
                ("blow-off velocity", self.blowoff_velocity, "m/s")]  # fmt: skip

    def _columns(self) -> Columns:
        """One row: the numbers of :meth:`to_dict` (the histories ``t, y`` stay arrays)."""
        units = {"speed_kmh": "km/h", "amplitude": "m", "eigen_damping_ratio": "1",
                 "source": "", "verdict": "", "orbit_rejected": ""}  # fmt: skip
        return {key: (getattr(self, key), units.get(key, "Hz")) for key in self.to_dict()}

    def to_dict(self) -> dict:
        """JSON-ready numbers (no histories)."""
        out = {}
        for key in ("speed_kmh", "frequency_hz", "source", "verdict", "amplitude",
                    "eigen_frequency_hz", "eigen_damping_ratio", "fft_frequency_hz",
                    "orbit_frequency_hz", "orbit_rejected"):  # fmt: skip
            value = getattr(self, key)
            out[key] = None if isinstance(value, float) and math.isnan(value) else value
        return out


def hunting_frequency(
    vehicle: Vehicle,
    speed_kmh: float,
    initial_amplitude: float = 3e-3,
    judgement: Judgement | None = None,
    fft_window: float = 8.0,
    sample_rate: float = 200.0,
    refine: bool = True,
    creep_law: str | None = None,
    model: Model | None = None,
    excitation: object = None,
) -> HuntingFrequency:
    """Hunting frequency of the leading wheelset at one speed (the paper's Sec. 3.3).

    Parameters
    ----------
    vehicle : Vehicle
        Vehicle description.
    speed_kmh : float
        Speed (km/h), in (0, 1000].
    initial_amplitude : float
        Initial lateral displacement of every wheelset (m), in (0, 0.02]; the paper uses
        3 mm.
    judgement : Judgement, optional
        Decay/limit-cycle thresholds (defaults of :class:`Judgement`).
    fft_window : float
        Length of the record's end analysed by the FFT (s), at least 4 s (about 15 cycles:
        the peak refinement is then accurate to a few % of a bin) and at most the longest
        record.
    sample_rate : float
        Fixed rate the record is resampled to by linear interpolation before the FFT (Hz).
    refine : bool
        Refine the limit cycle by shooting and report ``1 / period``.
    creep_law : str
        See :class:`railhunt.model.Model`.
    model : Model, optional
        A prebuilt model of ``vehicle`` (saves rebuilding it in loops).
    excitation : SingleDefect, optional
        Run from the centred state over this track defect instead of releasing the
        wheelsets from ``initial_amplitude`` (which is then ignored). With the defect of
        :func:`railhunt.critical_speed`, the frequency is the limit cycle's exactly when
        that search would judge this speed hunting: the paper's Sec. 3.3 definition
        (eigenvalue below V_cr, limit cycle above).

    Returns
    -------
    HuntingFrequency
    """
    speed_kmh = float(speed_kmh)
    if not (math.isfinite(speed_kmh) and 0 < speed_kmh <= 1000):
        raise ValueError(f"speed_kmh = {speed_kmh!r} km/h is invalid: must be in (0, 1000] km/h")
    initial_amplitude = float(initial_amplitude)
    if not (math.isfinite(initial_amplitude) and 0 < initial_amplitude <= 0.02):
        raise ValueError(
            f"initial_amplitude = {initial_amplitude!r} m is invalid: must be in (0, 0.02] m"
        )
    check_excitation(excitation, (SingleDefect, SampledTrack))
    judgement = judgement or Judgement()
    if not (math.isfinite(fft_window) and 4 <= fft_window <= judgement.max_duration):
        raise ValueError(f"fft_window = {fft_window!r} s is invalid: must be in [4, "
                         f"{judgement.max_duration:g}] s")  # fmt: skip
    if not (math.isfinite(sample_rate) and sample_rate >= 20):
        raise ValueError(f"sample_rate = {sample_rate!r} Hz is invalid: must be >= 20 Hz")
    model = model or Model(vehicle, creep_law=creep_law)
    speed = kmh_to_ms(speed_kmh)
    # The least-damped wheelset mode at this speed: the oscillation a small disturbance
    # leaves (the paper's Fig. 10a trend of f falling with C_d1 above the jump). Followed
    # down from the Hopf point instead, the mode that goes unstable there is a different,
    # heavily damped one at 300 km/h for C_d1 > 500 kN*s/m (docs/studies.md).
    # Where the mode that crosses at the Hopf point is not a wheelset mode (a frame
    # hunting with its wheelsets, the Cooperrider bogie), its continuation in speed is
    # a candidate too (railhunt.analysis.hunting_branch).
    w, vecs = eigenvalues(model, speed)
    lam = complex(w[hunting_mode_at(model, speed_kmh, w, vecs)])
    f_eig = lam.imag / (2 * math.pi)
    zeta = -lam.real / abs(lam)
    dt = auto_step(model, speed)
    layout = model.layout
    y_w1, forces = layout.y_w1, layout.forces
    x0 = np.zeros(layout.n_state)
    if excitation is None:
        x0[layout.wheelset_y] = initial_amplitude
    verdict, t, x, code, _, _, _ = run_until_verdict(model, speed_kmh, judgement, excitation,
                                                     x0, dt=dt)  # fmt: skip
    y = x[:, y_w1]
    vd = (model.damper_velocities(x[:, forces]) if x.size
          else np.empty((0, layout.n_damper)))  # fmt: skip
    v_u = _blowoff_velocity(model)
    if verdict == STABLE:
        return HuntingFrequency(speed_kmh, f_eig, "eigenvalue", STABLE, 0.0, f_eig, zeta,
                                math.nan, math.nan, t, y, vd, v_u)  # fmt: skip
    f_fft, f_orbit = math.nan, math.nan
    if code == 0:
        f_fft, amp = _spectrum_peak(t, y, fft_window, sample_rate)
        rejected = "not refined (refine=False)" if refine else "the FFT found no peak"
        if refine and math.isfinite(f_fft) and f_fft > 0:
            settle = excitation_end_time(model, excitation, speed) + SETTLE - float(t[-1])
            if settle > dt:
                # A run judged early may still be passing a saddle cycle (over the defect
                # at 350 km/h the paper's car lingers at one for 3 s): run on to SETTLE s
                # before shooting for the cycle it hunts on.
                t, x, ok = _run_on(model, speed, settle, t, x, excitation, dt)
                if ok:
                    f_fft, amp = _spectrum_peak(t, x[:, y_w1], fft_window, sample_rate)
            orbit, rejected = _refine_orbit(model, speed_kmh, t, x, dt, f_fft, amp)
            extended = 0.0
            while orbit is None and extended < REFINE_EXTENSION:
                # Not yet close enough to the cycle for Newton: run on, and shoot again.
                t, x, ok = _run_on(model, speed, REFINE_CHUNK, t, x, excitation, dt)
                if not ok:
                    break
                extended += REFINE_CHUNK
                f_fft, amp = _spectrum_peak(t, x[:, y_w1], fft_window, sample_rate)
                orbit, _ = _refine_orbit(model, speed_kmh, t, x, dt, f_fft, amp)
            if orbit is not None:
                f_orbit, amp, rejected = orbit.frequency_hz, orbit.amplitude, ""
            elif extended:
                rejected += f" (and again after running {extended:g} s longer)"
        y = x[:, y_w1]
        vd = model.damper_velocities(x[:, forces])
        f, source = (f_orbit, "limit-cycle") if math.isfinite(f_orbit) else (f_fft,
                                                                              "limit-cycle-fft")
        # A cycle shooting converged on is hunting, whatever the run's envelope said.
        found = HUNTING if math.isfinite(f_orbit) else verdict
        return HuntingFrequency(speed_kmh, f, source, found, amp, f_eig, zeta, f_fft,
                                f_orbit, t, y, vd, v_u, rejected)  # fmt: skip
    # The run left the track (derailed) or blew up (numerics): no frequency.
    return HuntingFrequency(speed_kmh, math.nan, "limit-exceeded", verdict, math.nan, f_eig,
                            zeta, math.nan, math.nan, t, y, vd, v_u)  # fmt: skip


def _run_on(model: Model, speed: float, span: float, t: np.ndarray, x: np.ndarray,
            excitation: object, dt: float) -> tuple[np.ndarray, np.ndarray, bool]:  # fmt: skip
    """The record ``(t, x)`` run on by ``span`` s at ``speed`` (m/s), stored every 2 ms,
    and whether the run went on cleanly (else the record as it was)."""
    tt, xx, code, _ = integrate_model(model, speed, span, x[-1], t0=float(t[-1]),
                                      excitation=excitation, dt=dt, output_dt=2e-3)  # fmt: skip
    if code != 0:
        return t, x, False
    return np.concatenate([t, tt[1:]]), np.concatenate([x, xx[1:]]), True


def _blowoff_velocity(model: Model) -> float:
    """The first yaw damper's blow-off velocity ``F_u / C_d1`` (m/s); NaN without one."""
    from railhunt.kernel.layout import DamperParam

    if model.dpar.shape[0] == 0:
        return math.nan
    return float(model.dpar[0, DamperParam.F_U] / model.dpar[0, DamperParam.C_D1])


#: When shooting from the end of a run fails, the run goes on in chunks of this many
#: seconds, up to this many in all, and shooting is tried again after each (s).
REFINE_CHUNK, REFINE_EXTENSION = 5.0, 10.0
#: A hunting run is shot from no earlier than this many seconds after its excitation (s).
SETTLE = 8.0


def _spectrum_peak(t: np.ndarray, y: np.ndarray, window: float,
                   rate: float) -> tuple[float, float]:  # fmt: skip
    """The FFT's peak frequency of the last ``window`` s of ``y`` (Hz), resampled to ``rate``
    (Hz) by linear interpolation (the paper's), and the largest ``|y|`` of the last 2 s."""
    t_end = t[-1]
    t_fix = np.arange(max(t[0], t_end - window), t_end, 1.0 / rate)
    f_fft, _, _ = dominant_frequency(np.interp(t_fix, t, y), 1.0 / rate)
    return f_fft, float(np.max(np.abs(y[t >= t_end - 2.0])))


def _extremum_state(model: Model, speed_kmh: float, t: np.ndarray, x: np.ndarray, k: int,
                    dt: float) -> np.ndarray:  # fmt: skip
    """The state at the maximum of ``y_w1`` near sample ``k`` of a record, located to the
    integration step: the record is stored at a coarser interval, and shooting's phase
    condition (``dy_w1/dt = 0``) needs the state right at the extremum."""
    if k < 1 or k + 1 >= t.size:
        return x[k]
    span = float(t[k + 1] - t[k - 1])
    tt, xx, code, _ = integrate_model(model, kmh_to_ms(speed_kmh), span, x[k - 1],
                                      t0=float(t[k - 1]), dt=dt)  # fmt: skip
    if code != 0 or tt.size < 3:
        return x[k]
    y_w1 = model.layout.y_w1
    rate = xx[:, model.layout.rate0 + y_w1]
    j = int(np.argmin(np.abs(rate) + np.where(xx[:, y_w1] > 0, 0.0, np.inf)))
    return xx[j] if math.isfinite(rate[j]) else x[k]


def _maxima(y: np.ndarray, count: int) -> list[int]:
    """Indices of the last ``count`` local maxima of ``y``, the latest first."""
    k = np.flatnonzero((y[1:-1] >= y[:-2]) & (y[1:-1] > y[2:])) + 1
    return [int(i) for i in k[::-1][:count]] or [phase_origin(np.arange(y.size), y)]


def _refine_orbit(model: Model, speed_kmh: float, t: np.ndarray, x: np.ndarray, dt: float,
                  f_fft: float, amp: float) -> tuple[object | None, str]:  # fmt: skip
    """Shoot the limit cycle from the end of a run (settled or not).

    Tries the last three maxima of ``y_w1``, each located to the step. An orbit is the
    cycle the vehicle hunts on when its frequency is within 10 % of the FFT's and it is
    stable: the attractor the run is on or heads for. An unstable orbit with the run's own
    amplitude (within 20 %) is a saddle cycle the run is passing: none is accepted, and the
    caller runs on.

    Returns
    -------
    orbit : PeriodicOrbit or None
        The accepted orbit.
    rejected : str
        Why no orbit was accepted ("" when one was).
    """
    reasons: list[str] = []
    jacobians: list[np.ndarray] = []  # each shot's Newton starts from the last one's
    for k in _maxima(x[:, model.layout.y_w1], 3):
        start = _extremum_state(model, speed_kmh, t, x, k, dt)
        try:
            shot = shoot_orbit(model, speed_kmh, start, 1.0 / f_fft, dt=dt, krylov=True,
                               jacobians=jacobians)  # fmt: skip
        except RuntimeError as exc:
            reasons.append(str(exc))
            continue
        same_f = abs(shot.frequency_hz - f_fft) < 0.1 * f_fft
        orbit = shot.orbit()
        if same_f and orbit.stable:
            return orbit, ""
        if same_f and abs(shot.amplitude - amp) < 0.2 * amp:
            # The run's own cycle, but unstable: the run is passing a saddle cycle (over
            # the defect at 350 km/h the paper's car lingers at one for 3 s before it
            # settles on the stable cycle it hunts on); the run goes on.
            return None, (f"the orbit found ({orbit.frequency_hz:.4g} Hz, "
                          f"{orbit.amplitude * 1e3:.3g} mm) is the run's but unstable: the "
                          "run is passing a saddle cycle, or hunts on no periodic cycle "
                          "near it")  # fmt: skip
        reasons.append(f"the orbit found ({orbit.frequency_hz:.4g} Hz, "
                       f"{orbit.amplitude * 1e3:.3g} mm, {'stable' if orbit.stable else 'unstable'}"
                       f") is not the simulated cycle (FFT {f_fft:.4g} Hz, last amplitude "
                       f"{amp * 1e3:.3g} mm)")  # fmt: skip
    return None, reasons[0] if reasons else "no maximum to shoot from"


def frequency_jump(speeds_kmh: np.ndarray, frequency_hz: np.ndarray,
                   sources: list[str]) -> tuple[float, float, float] | None:  # fmt: skip
    """Where the frequency source switches from eigenvalue to limit cycle (Fig. 7b).

    Returns ``(speed_kmh, f_before_hz, f_after_hz)`` at the first switch (the speed is the
    midpoint of the two neighbouring speeds), or None when there is none. Either estimate
    of the limit cycle (:func:`frequency_kind`) counts.
    """
    for i in range(1, len(sources)):
        if sources[i - 1] == "eigenvalue" and frequency_kind(sources[i]) == "limit-cycle":
            return (0.5 * (speeds_kmh[i - 1] + speeds_kmh[i]), float(frequency_hz[i - 1]),
                    float(frequency_hz[i]))  # fmt: skip
    return None

"""Run-up / run-down of the loose-support rotor with time-varying speed, and its time–frequency cascade.

Dai et al. 2025 study steady states only and leave transient speed as future work. Here the
speed follows a linear ramp ``Ω(t) = Ω_0 + Ω̇ t``. The production integrator
(:func:`rotor.dynamics.production.simulate_production`) is built for a constant spin speed, so the ramp
is integrated as a sequence of short segments (default 5 ms, 1.5 revolutions at
18 000 rpm) with the state, the end-face modes *and the rotation angle*
carried across segments:

* in segment ``j`` the speed is ``Ω_j = Ω(t_mid)``; the gyroscopic term is ``Ω_j G`` and the
  loads are those of :func:`rotor.dynamics.build.system_from_model` at ``Ω_j``;
* the excitation phase is the accumulated rotation angle ``φ(t) = ∫Ω dt`` (not ``Ω t``), by
  starting each segment at the local time ``φ_j/Ω_j``: the harmonic loads ``cos(kφ)``,
  ``sin(kφ)`` stay continuous through every speed change;
* the unbalance force of an accelerating rotor has a tangential part
  ``m e Ω̇ (sin φ, −cos φ)`` besides ``m e Ω² (cos φ, sin φ)``; it is added to the 1X load
  (``a cos φ + b sin φ → (a − εb) cos φ + (b + εa) sin φ`` with ``ε = Ω̇/Ω²``). The 2X
  misalignment load is taken at the instantaneous speed without a rate term.

The piecewise-constant speed changes Ω by ``Ω̇ × 5 ms`` per segment (4.4 rpm for a
0→18 000 rpm run-up in 20 s), far below any resonance width.
"""
from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import numpy as np

from contact.errors import InputError
from contact import plausible
from contact.units import check_positive
from rotor.dynamics import constraints as cons
from rotor.dynamics.system import HarmonicForce, NewmarkOptions, largest_stable_step
from rotor.dynamics.production import prepare, simulate_production
from rotor.dynamics.support_record import contact_summary

#: the shortest window of the time-frequency cascade (s, :func:`stft_cascade`); a run-up needs two of them
SHORTEST_WINDOW_S = 0.1
SHORTEST_DURATION_S = 2 * SHORTEST_WINDOW_S


@dataclass(frozen=True)
class RunupSpec:
    """A linear speed ramp.

    scene : scene name or TOML path; rpm_start, rpm_end : speeds (rpm, > 0);
    duration_s : ramp duration (s); segment_s : piecewise-constant speed segment (s);
    sample_rate_hz : recorded samples per second; steps_per_rev : minimum steps per revolution
    at the highest speed; clearance_m, misalignment_m, tilt_ignored, mu (end-face friction
    coefficient), preload_n (N), law (as a scene's ``law`` key) : overrides (None = scene).
    """

    scene: str = "paper-table4"
    rpm_start: float = 600.0
    rpm_end: float = 18000.0
    duration_s: float = 20.0
    segment_s: float = 5e-3
    sample_rate_hz: float = 8000.0
    steps_per_rev: int = 256
    clearance_m: float | None = None
    misalignment_m: float | None = None
    tilt_ignored: bool = False
    mu: float | None = None
    preload_n: float | None = None
    law: str | None = None

    def __post_init__(self):
        check_positive("rpm_start", self.rpm_start, "rpm", upper=plausible.top("run_speed_rpm"))
        check_positive("rpm_end", self.rpm_end, "rpm", upper=plausible.top("run_speed_rpm"))
        check_positive("duration_s", self.duration_s, "s", upper=plausible.top("duration_s"))
        check_positive("segment_s", self.segment_s, "s", upper=1.0)
        check_positive("sample_rate_hz", self.sample_rate_hz, "Hz", upper=1e7)
        if self.steps_per_rev < 16:
            raise InputError(f"steps_per_rev = {self.steps_per_rev}: must be >= 16")


def simulate_runup(spec: RunupSpec, *, progress=None) -> dict:
    """Integrate the ramp; returns arrays (t s, rpm, q m, v m/s, u, r1/r2 m, modes, ``f_contact`` (N, N m) and
    ``face_force`` (N) on the bearing, :mod:`rotor.dynamics.support_record`) and info, with the contact summary
    over the whole ramp (:func:`rotor.dynamics.support_record.contact_summary`: ``peak_contact_force_N`` at
    ``peak_contact_force_t_s`` from the ramp's start, ``contact_share``, ``stick_share_right_face`` …).

    ``progress(fraction)`` is called after each segment if given.
    """
    from rotor.studies.steady_state import point_system

    t_wall = time.perf_counter()
    w0 = spec.rpm_start * math.pi / 30
    w1 = spec.rpm_end * math.pi / 30
    wdot = (w1 - w0) / spec.duration_s
    kw = dict(clearance_m=spec.clearance_m, misalignment_m=spec.misalignment_m, tilt_ignored=spec.tilt_ignored,
              mu=spec.mu, preload_n=spec.preload_n, law=spec.law)
    sc, model, sys_hi = point_system(spec.scene, max(spec.rpm_start, spec.rpm_end), **kw)
    dt_max, _ = largest_stable_step(sys_hi)
    dt = min(2 * math.pi / max(w0, w1) / spec.steps_per_rev, 0.5 * dt_max)
    rec = max(1, int(round(1.0 / (spec.sample_rate_hz * dt))))
    seg_steps = max(rec, int(round(spec.segment_s / dt / rec)) * rec)
    n_seg = int(math.ceil(spec.duration_s / (seg_steps * dt)))
    stations = model.response_stations()  # every disk, bearing and support station, by the scene's names
    idx = [model.dof_index(f"{s}.{c}") for s in stations for c in ("y", "z")]
    channels = tuple(f"{s}.{c}" for s in stations for c in ("y", "z"))
    _, _, sys0 = point_system(spec.scene, spec.rpm_start, **kw)
    q = sys0.offset.copy()
    v = np.zeros(sys0.n)
    modes = (cons.STICK, cons.STICK)
    phi = 0.0
    t_real = 0.0
    out = {k: [] for k in ("t", "rpm", "q", "v", "u", "modes", "f_contact", "face_force")}
    unconv = 0
    pre_cache = None
    for j in range(n_seg):
        tm = t_real + 0.5 * seg_steps * dt
        w = w0 + wdot * min(tm, spec.duration_s)
        _, _, system = point_system(spec.scene, w * 30 / math.pi, **kw)
        f = system.force
        cos, sin = f.cos.copy(), f.sin.copy()
        eps = wdot / (w * w)
        for h, order in enumerate(f.orders):
            if order == 1.0:
                a, b = f.cos[h].copy(), f.sin[h].copy()
                cos[h], sin[h] = a - eps * b, b + eps * a
        system = dataclasses.replace(system, force=HarmonicForce(f.static, f.orders, cos, sin, f.omega_rad_s))
        pre = prepare(system, dt)
        t0 = phi / w
        tr = simulate_production(system, dt, seg_steps, q0=q, v0=v, t0=t0, modes0=modes, record_every=rec,
                                 prepared=pre, check_step=False)
        unconv += tr.unconverged_steps
        sl = slice(0 if j == 0 else 1, None)
        n_r = tr.t[sl].size
        out["t"].append(t_real + (tr.t[sl] - t0))
        out["rpm"].append(np.full(n_r, w * 30 / math.pi))
        out["q"].append(tr.q[sl][:, idx])
        out["v"].append(tr.v[sl][:, idx])
        out["u"].append(tr.u[sl])
        out["modes"].append(tr.modes[sl])
        out["f_contact"].append(tr.f_contact[sl])
        out["face_force"].append(tr.face_force[sl])
        q, v = tr.q[-1].copy(), tr.v[-1].copy()
        modes = tuple(int(m) for m in tr.modes[-1])
        phi += w * seg_steps * dt
        t_real += seg_steps * dt
        if progress is not None:
            progress((j + 1) / n_seg)
    arrays = {k: np.concatenate(vv) for k, vv in out.items()}
    width = sys0.support.width_m
    arrays["r1"], arrays["r2"] = cons.edge_offsets(arrays["u"], width)
    arrays["channels"] = np.array(channels)
    info = {"dt_s": dt, "record_every": rec, "sample_rate_hz": 1.0 / (rec * dt), "segments": n_seg,
            "segment_steps": seg_steps, "steps": n_seg * seg_steps, "least_residual_steps": int(unconv),
            "clearance_m": float(sys0.support.law.clearance_m), "accel_rpm_per_s": wdot * 30 / math.pi,
            "wall_s": time.perf_counter() - t_wall, "law": sys0.support.law.name,
            "integrator": dataclasses.asdict(NewmarkOptions()), "reading": _reading_name(sc),
            **(sc.loose_support.law_note() if sc.loose_support is not None else {}),   # a calibrated law's file
            **contact_summary(arrays["t"], arrays["f_contact"], arrays["modes"], arrays["face_force"],
                              sys0.support.faces()[2])}
    return {"arrays": arrays, "info": info}


def _reading_name(scene) -> str | None:
    from rotor.studies.readings import scene_reading
    return scene_reading(scene) if getattr(scene, "misalignment", None) is not None else None


def _runup_task(**params):
    r = simulate_runup(RunupSpec(**params))
    return r["arrays"], r["info"]


def run_runup(spec: RunupSpec, out, executor=None) -> dict:
    """Simulate (unless a verified result with the same spec is in ``out``) and store as point ``runup``;
    ``executor``: where to run it (e.g. a dask client; default a thread here)."""
    from sweep import ResultStore, Task, run_sweep

    params = {k: v for k, v in dataclasses.asdict(spec).items() if not (k == "law" and v is None)}  # as stored before
    task = Task("runup", _runup_task, params)
    import concurrent.futures as cf

    local = cf.ThreadPoolExecutor(max_workers=1)  # one task: no process start-up
    try:
        s = run_sweep([task], out, executor=executor or local, manifest={"study": "runup", "spec": params})
    finally:   # interrupted: do not wait here for the simulation still running in the thread
        local.shutdown(wait=False, cancel_futures=True)
    if s.failed:
        raise InputError(f"run-up failed: {s.failed['runup']}")
    return ResultStore(out).load("runup", params).info


def load_runup(out) -> dict:
    """The stored run-up as a dict of arrays plus ``clearance_m``."""
    from sweep import ResultStore

    p = ResultStore(out).load("runup")
    d = dict(p.arrays)
    d["clearance_m"] = p.info["clearance_m"]
    d["info"] = p.info
    return d


def stft_cascade(r: dict, channel: str, window_s: float | None = None, overlap: float = 0.5):
    """Short-time amplitude spectra of the y velocity of ``channel`` (m/s).

    Hann windows of ``window_s`` (default: 1/40 of the run, at least 0.1 s), amplitude-corrected
    (a sinusoid of amplitude A inside a window reads A at its bin). Returns
    ``(t_centres (W,), freq_hz (F,), amp (W, F) m/s, rpm_centres (W,))``.
    """
    c = list(r["channels"]).index(channel)
    x = r["v"][:, c]
    t = r["t"]
    fs = 1.0 / float(np.median(np.diff(t)))
    T = t[-1] - t[0]
    win_s = window_s if window_s is not None else max(SHORTEST_WINDOW_S, T / 40)
    n = int(round(win_s * fs))
    if n < 16 or n > x.size:
        raise InputError(f"window_s = {win_s:g} s: needs 16..{x.size} samples at {fs:g} Hz")
    hop = max(1, int(n * (1 - overlap)))
    w = np.hanning(n)
    starts = np.arange(0, x.size - n + 1, hop)
    frames = np.stack([x[s:s + n] - x[s:s + n].mean() for s in starts]) * w
    amp = 2 * np.abs(np.fft.rfft(frames, axis=1)) / w.sum()
    freq = np.fft.rfftfreq(n, 1 / fs)
    mid = starts + n // 2
    return t[mid], freq, amp, r["rpm"][mid]

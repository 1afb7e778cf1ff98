"""Steady-state response of the loose-support rotor at one operating point, and its spectra.

The two pieces a speed sweep needs (DESIGN.md "Steady state is detected, not guessed"):

1. **Steady-state detection.** The rotor is integrated in chunks of revolutions with the
   production scheme (:func:`rotor.dynamics.production.simulate_production`). Once per revolution, at
   the same phase of the excitation, the lateral displacements of a few stations are sampled
   (a Poincaré section). The response is steady with period ``m`` revolutions when
   ``|P_k − P_{k−m}|`` — divided by the peak-to-peak dynamic amplitude — stays below ``tol``
   over a window of revolutions *and* what may be left of a transient, estimated from the decay of
   those differences or bounded by the change over long spans of revolutions, is below ``tol`` too
   (so a slowly decaying transient with small per-revolution change is not mistaken for a steady
   state, and a stuck linear state repeating within ``tol`` is not refused;
   :func:`rotor.studies.periodicity.poincare_convergence`). ``m = 1`` is a synchronous
   (1X-periodic) response; ``m > 1`` a subharmonic one. A response that meets neither by
   ``max_revs`` (quasi-periodic or chaotic) is reported as ``converged = False``, never
   silently passed as steady.
2. **Exact-bin spectra.** The steady response is then recorded over ``N`` whole revolutions,
   ``N`` a multiple of the period, ``s`` samples per revolution. The DFT of that record has
   bin ``j`` at ``j/N`` times the rotation frequency, so ``h·f`` is bin ``h·N`` exactly: no
   leakage, no window, the amplitude of a pure harmonic is exact (``2|X_j|/(N s)``).

Everything is SI; speeds are rad/s inside (rpm only in names ending ``_rpm``). Dai et al. 2025 §5 for the quantities.
"""
from __future__ import annotations

import dataclasses
import hashlib
import math
import os
import time
from dataclasses import dataclass

import numpy as np

from contact import plausible
from contact.errors import InputError, OutsideDomainError
from contact.units import check_positive
from rotor.dynamics import constraints as cons
from rotor.dynamics.system import NewmarkOptions, RotorSystem, largest_stable_step
from rotor.dynamics.production import prepare, simulate_production
from rotor.dynamics.support_record import contact_summary
from sweep.progress import report
from rotor.periodic.shooting import TRANSIENT_SAMPLES_PER_REV
from rotor.studies.periodicity import Convergence, poincare_convergence  # noqa: F401  (re-exported)
from rotor.studies.scene_digest import check_digest, scene_digest

# Stations come from the scene (RotorModel.response_stations): every disk, bearing and support station is
# recorded, the primary ones (for Table 4 the paper's disk1, disk2, 5, s) form the Poincaré section.

#: the fewest samples a revolution that resolve the 5X harmonic (above its Nyquist rate of 10 with a margin)
SAMPLES_FOR_5X = 12


@dataclass(frozen=True)
class SteadyStateOptions:
    """Controls of :func:`steady_state`.

    Attributes
    ----------
    steps_per_rev : int
        Minimum time steps per revolution (–); raised at low speed so that the step stays
        below ``stable_fraction`` times the largest stable contact step
        (:func:`rotor.dynamics.system.largest_stable_step`). Default 256: against 512, the 1X–3X
        velocity amplitudes of the Table 4 rotor at 4 500 and 10 500 rpm differ by ≤ 0.4 %,
        4X–5X by ≤ 2 % (measured at disk 1, disk 2 and the support).
    stable_fraction : float
        Step as a fraction of the largest stable contact step (–).
    samples_per_rev : int or None
        Recorded samples per revolution of the spectrum record (–); must divide the steps
        per revolution (it is rounded so). Spectra reach ``samples_per_rev/2`` × f. None (default):
        every time step, so that nothing above the record's Nyquist order folds onto the
        harmonics; impacts put energy far up the spectrum, and a record of 64 samples/rev moved
        the 5X velocity amplitude of the support at 10 500 rpm by 0.63 % (4X 0.03 %; Table 4
        rotor, 256 steps/rev, measured against the every-step record).
        The transient is always sampled at :data:`TRANSIENT_SAMPLES_PER_REV` (Poincaré points
        and amplitude scale only).
    chunk_s : float
        Target duration of one detection chunk (s); clamped to [min_chunk_revs, max_chunk_revs].
    min_revs, max_revs : int
        Bounds on the transient (revolutions).
    tol : float
        Relative Poincaré tolerance (–), against the peak-to-peak dynamic amplitude.
    max_period : int
        Largest period (revolutions) tried for subharmonic responses.
    spectrum_revs : int
        Revolutions in the spectrum record (rounded up to a multiple of the period).
    """

    steps_per_rev: int = 256
    stable_fraction: float = 0.5
    samples_per_rev: int | None = None
    chunk_s: float = 0.25
    min_chunk_revs: int = 8
    max_chunk_revs: int = 50
    min_revs: int = 24
    max_revs: int = 1500
    tol: float = 1e-4
    max_period: int = 8
    spectrum_revs: int = 32

    def __post_init__(self):
        for name in ("steps_per_rev", "samples_per_rev", "min_chunk_revs", "max_chunk_revs", "max_revs",
                     "max_period", "spectrum_revs"):
            v = getattr(self, name)
            if v is None and name == "samples_per_rev":
                continue
            if int(v) != v or v < 1:
                raise InputError(f"{name} = {v}: must be a positive integer")
        if self.samples_per_rev is not None and self.samples_per_rev < SAMPLES_FOR_5X:
            raise InputError(f"samples_per_rev = {self.samples_per_rev}: need >= {SAMPLES_FOR_5X} to resolve 5X")
        check_positive("stable_fraction", self.stable_fraction, "-", upper=1.0)
        check_positive("chunk_s", self.chunk_s, "s", upper=100.0)
        check_positive("tol", self.tol, "-", upper=0.1)
        if self.min_revs > self.max_revs:
            raise InputError(f"min_revs = {self.min_revs} > max_revs = {self.max_revs}")


def harmonic_amplitudes(x, revolutions: int, orders=(1, 2, 3, 4, 5)) -> np.ndarray:
    """Complex amplitudes of the harmonics ``h·f`` of a record of whole revolutions.

    Parameters
    ----------
    x : (N,) or (N, c) array
        Samples equally spaced over exactly ``revolutions`` revolutions (the last sample is
        one step before the first sample of the next revolution), any unit.
    revolutions : int
        Number of whole revolutions covered.
    orders : sequence of int
        Harmonic orders h (1 = rotation frequency).

    Returns
    -------
    (len(orders),) or (len(orders), c) complex array ``a_h`` with
    ``x(t) ≈ x̄ + Σ Re(a_h e^{i h Ω t'})`` (``t'`` from the first sample); ``|a_h|`` is the
    amplitude (same unit as x). Bin ``h·revolutions`` of the DFT, exact for a periodic record.
    """
    x = np.asarray(x, dtype=float)
    n = x.shape[0]
    revolutions = int(revolutions)
    if revolutions < 1 or n % revolutions:
        raise InputError(f"harmonic_amplitudes: {n} samples are not a whole number of samples per revolution "
                         f"over {revolutions} revolutions")
    X = np.fft.rfft(x, axis=0) / n
    bins = [int(h) * revolutions for h in orders]
    if max(bins) >= X.shape[0]:
        raise InputError(f"harmonic order {max(orders)} is above the Nyquist order "
                         f"{n // revolutions // 2} of {n // revolutions} samples per revolution")
    a = 2.0 * X[bins]
    return a


def spectrum(x, revolutions: int, max_order: float = 6.0):
    """One-sided amplitude spectrum of a whole-revolution record, frequency in orders of f.

    Returns ``(orders (J,), amplitude (J,) or (J, c))`` with bins at ``j/revolutions`` × f
    up to ``max_order`` (0 excluded). Amplitudes as in :func:`harmonic_amplitudes`.
    """
    x = np.asarray(x, dtype=float)
    n = x.shape[0]
    X = np.fft.rfft(x, axis=0) / n
    orders = np.arange(X.shape[0]) / float(revolutions)
    keep = (orders > 0) & (orders <= max_order + 1e-12)
    return orders[keep], 2.0 * np.abs(X[keep])


@dataclass
class SteadyResult:
    """Steady response of one operating point.

    Attributes
    ----------
    speed_rad_s : float
    channels : tuple of str, names of the recorded columns (``disk1.y`` …)
    t : (N,) s, time of the spectrum record (N = revolutions × samples_per_rev)
    q, v : (N, c) displacement (m) and velocity (m/s) of the channels
    u : (N, 4) relative bearing − support (y, z m; θy, θz rad)
    r1, r2 : (N,) relative edge offsets (m), docs/reference/contact-laws.md §8
    modes : (N, 2) end-face modes (1 stick / 0 slip)
    f_contact : (N, 4) radial contact force/moment on the bearing (N, N m)
    revolutions : int, length of the record (a multiple of ``period``)
    samples_per_rev, steps_per_rev : int
    transient_revs : int, revolutions integrated before the record
    convergence : Convergence
    clearance_m : float
    unconverged_steps : int, Newton steps accepted at least residual (whole run)
    wall_s : float
    static : bool, True at zero speed (no dynamics: the static equilibrium is the answer)
    q_all : (N, n) all generalised coordinates over the record (m, rad), for deflection shapes
    n_faces : int, active end faces (1 with the tilt ignored: one centred face, the second slot unused)
    q_end, v_end : (n,) state one step after the record, at a whole revolution (phase 0): a
        starting state for a neighbouring operating point (continuation)
    """

    speed_rad_s: float
    channels: tuple
    t: np.ndarray
    q: np.ndarray
    v: np.ndarray
    u: np.ndarray
    r1: np.ndarray
    r2: np.ndarray
    modes: np.ndarray
    f_contact: np.ndarray
    revolutions: int
    samples_per_rev: int
    steps_per_rev: int
    transient_revs: int
    convergence: Convergence
    clearance_m: float
    unconverged_steps: int = 0
    wall_s: float = 0.0
    static: bool = False
    q_all: np.ndarray | None = None
    q_end: np.ndarray | None = None
    v_end: np.ndarray | None = None
    n_faces: int = 2

    def channel(self, name: str) -> int:
        try:
            return self.channels.index(name)
        except ValueError:
            raise InputError(f"channel {name!r}: not recorded; have {', '.join(self.channels)}") from None

    def harmonics(self, quantity: str = "q", orders=(1, 2, 3, 4, 5)) -> np.ndarray:
        """Amplitude (magnitude) of orders h for every channel: ``(len(orders), c)``; quantity 'q' (m),
        'v' (m/s) or 'u' (relative y, z m and θy, θz rad)."""
        x = {"q": self.q, "v": self.v, "u": self.u}[quantity]
        if self.static:
            return np.zeros((len(orders), x.shape[1]))
        return np.abs(harmonic_amplitudes(x - x.mean(axis=0), self.revolutions, orders))

    def regime(self) -> dict:
        """Where the loose support sticks, slips and impacts (fractions of the record, –).

        ``contact``: r1 or r2 beyond the clearance; ``stick``: every active face stuck;
        ``label``: 'stick' (faces stuck throughout, no contact), 'slip' (slip, no contact),
        'impact' (contact part of the time), 'contact' (contact throughout).
        """
        d0 = self.clearance_m
        contact = (self.r1 > d0) | (self.r2 > d0)
        stick = np.all(self.modes[:, :max(self.n_faces, 1)] == cons.STICK, axis=1)
        cf, sf = float(contact.mean()), float(stick.mean())
        if cf >= 1.0:
            label = "contact"
        elif cf > 0.0:
            label = "impact"
        elif sf >= 1.0:
            label = "stick"
        else:
            label = "slip"
        return {"contact_fraction": cf, "stick_fraction": sf, "label": label,
                "max_r_over_clearance": float(max(self.r1.max(), self.r2.max()) / d0)}


def step_per_rev(system: RotorSystem, options: SteadyStateOptions) -> int:
    """Steps per revolution: at least ``options.steps_per_rev``, enough for the contact step limit,
    and a multiple of ``samples_per_rev`` and of :data:`TRANSIENT_SAMPLES_PER_REV`."""
    T = 2 * math.pi / system.omega_rad_s
    dt_max, _ = largest_stable_step(system)
    n = max(options.steps_per_rev, math.ceil(T / (options.stable_fraction * dt_max)) if math.isfinite(dt_max) else 1)
    s = math.lcm(options.samples_per_rev or 1, TRANSIENT_SAMPLES_PER_REV)
    return int(math.ceil(n / s) * s)


def _at_rest(opts: SteadyStateOptions, channels, idx, q, v, d0: float, t_start: float) -> SteadyResult:
    """No excitation and no rotation: the record is the initial (static) state."""
    spr = opts.samples_per_rev or TRANSIENT_SAMPLES_PER_REV
    N = opts.spectrum_revs * spr
    z4 = np.zeros((N, 4))
    return SteadyResult(0.0, channels, np.zeros(N), np.tile(q[idx], (N, 1)), np.zeros((N, len(idx))), z4,
                        np.zeros(N), np.zeros(N), np.ones((N, 2), np.int8), z4, opts.spectrum_revs,
                        spr, 0, 0, Convergence(True, 1, 0.0, 0.0, 0.0), d0, 0,
                        time.perf_counter() - t_start, True, np.tile(q, (N, 1)), q.copy(), v.copy())


def steady_state(system: RotorSystem, model, *, options: SteadyStateOptions | None = None,
                 stations=None, q0=None, v0=None) -> SteadyResult:
    """Integrate ``system`` to its steady state and record whole revolutions of it.

    Parameters
    ----------
    system : RotorSystem
        From :func:`rotor.dynamics.build.system_from_model` (spin speed inside, rad/s).
    model : rotor.model.assembly.RotorModel
        For station names (``model.dof_index``).
    options : SteadyStateOptions
    stations : station names recorded as ``<name>.y``, ``<name>.z`` (scene names or nodes); None: every
        disk, bearing and support station of the scene (``model.response_stations()``). The Poincaré
        section is always on the primary stations (``model.response_stations(primary_only=True)``).
    q0, v0 : initial state (default: the misalignment offset ``Δq_m`` at rest).

    Returns
    -------
    SteadyResult. ``convergence.converged`` is False when no period ≤ ``max_period`` was found
    within ``max_revs`` (quasi-periodic/chaotic response): the record is then the last
    ``spectrum_revs`` revolutions and its spectrum is not on exact bins for the non-harmonic part.
    """
    opts = options or SteadyStateOptions()
    t_start = time.perf_counter()
    stations = model.response_stations() if stations is None else tuple(stations)
    channels = tuple(f"{s}.{c}" for s in stations for c in ("y", "z"))
    idx = [model.dof_index(c) for c in channels]
    pidx = [model.dof_index(f"{s}.{c}") for s in model.response_stations(primary_only=True) for c in ("y", "z")]
    omega = float(system.omega_rad_s)
    d0 = system.support.law.clearance_m if system.support is not None else math.inf
    width = system.support.width_m if system.support is not None else 0.0
    q = system.offset.copy() if q0 is None else np.asarray(q0, float).copy()
    v = np.zeros(system.n) if v0 is None else np.asarray(v0, float).copy()
    if omega == 0.0:
        return _at_rest(opts, channels, idx, q, v, d0, t_start)
    T = 2 * math.pi / omega
    nper = step_per_rev(system, opts)
    dt = T / nper
    pre = prepare(system, dt)
    chunk = int(min(max(round(opts.chunk_s / T), opts.min_chunk_revs), opts.max_chunk_revs))
    t = 0.0
    modes = (cons.STICK, cons.STICK)
    P = []
    revs = 0
    unconv = 0
    conv = Convergence(False, 0, math.inf, math.inf, 1.0)
    sub = nper // TRANSIENT_SAMPLES_PER_REV
    spr = opts.samples_per_rev or nper           # spectrum record: samples per revolution
    sub_rec = nper // spr
    while revs < opts.max_revs:
        n_rev = min(chunk, opts.max_revs - revs)
        tr = simulate_production(system, dt, nper * n_rev, q0=q, v0=v, t0=t, modes0=modes, record_every=sub,
                                 prepared=pre, check_step=False)
        unconv += tr.unconverged_steps
        q, v, t = tr.q[-1].copy(), tr.v[-1].copy(), float(tr.t[-1])
        modes = tuple(int(m) for m in tr.modes[-1])
        P.extend(tr.q[TRANSIENT_SAMPLES_PER_REV::TRANSIENT_SAMPLES_PER_REV, pidx])
        revs += n_rev
        report("transient", revs=revs, max_revs=opts.max_revs)
        if revs < opts.min_revs:
            continue
        seg = tr.q[:, pidx]
        scale = float(np.ptp(seg, axis=0).max())
        conv = poincare_convergence(np.array(P), scale, tol=opts.tol, max_period=opts.max_period)
        if conv.converged:
            break
    period = conv.period if conv.converged else 1
    n_rec = int(math.ceil(opts.spectrum_revs / period) * period)
    tr = simulate_production(system, dt, nper * n_rec, q0=q, v0=v, t0=t, modes0=modes, record_every=sub_rec,
                             prepared=pre, check_step=False)
    unconv += tr.unconverged_steps
    sl = slice(0, -1)  # whole revolutions: drop the sample that starts the next revolution
    u = tr.u[sl]
    r1, r2 = cons.edge_offsets(u, width) if system.support is not None else (np.zeros(len(u)),) * 2
    return SteadyResult(omega, channels, tr.t[sl], tr.q[sl][:, idx], tr.v[sl][:, idx], u, r1, r2,
                        tr.modes[sl].astype(np.int8), tr.f_contact[sl], n_rec, spr, nper, revs,
                        conv, d0, unconv, time.perf_counter() - t_start, False, tr.q[sl], tr.q[-1].copy(),
                        tr.v[-1].copy(), system.support.faces()[2] if system.support is not None else 0)


# ---------------------------------------------------------------------------
# one sweep point as a picklable task function (sweep.Task)
# ---------------------------------------------------------------------------

_MODEL_CACHE: dict = {}


def _scene_key(scene):
    """What :func:`_scene_model` caches a scene under: a scene file by its resolved path and its bytes' sha256 (a
    file written again at the same path in the same process is read again: measured, the second rotor of
    tests/rotor/studies/test_grazing_family.py's ten, each written to the same file, was followed with the first
    one's model), a bundled name or a :class:`rotor.model.scene.Scene` as itself."""
    if isinstance(scene, (str, os.PathLike)) and os.path.isfile(scene):
        with open(scene, "rb") as fh:
            return os.path.realpath(scene), hashlib.sha256(fh.read()).hexdigest()
    return scene


def _scene_model(scene, elements_per_segment: int | None = None, law: str | None = None):
    """Scene and assembled model, cached per process (workers reuse them across points).
    ``scene``: a scene file's path, a bundled scene's name or a :class:`rotor.model.scene.Scene` (a
    scene built in Python, the public API's). ``elements_per_segment`` refines every shaft segment
    (None: the scene's own mesh); ``law`` replaces the scene's ``[loose_support]`` law
    (:func:`rotor.model.loose_support_scene.with_law`; None: the scene's)."""
    key = (_scene_key(scene), elements_per_segment, law)
    if key not in _MODEL_CACHE:
        from rotor.model.assembly import assemble
        from rotor.model.loose_support_scene import with_law
        from rotor.model.scene import Scene, load_scene

        if elements_per_segment is not None:
            check_positive("elements_per_segment", elements_per_segment, "elements", upper=64)
        sc = scene if isinstance(scene, Scene) else load_scene(scene)
        if law is not None:
            sc = with_law(sc, law)
        _MODEL_CACHE[key] = (sc, assemble(sc, elements_per_segment=elements_per_segment))
    return _MODEL_CACHE[key]


def point_system(scene: str, speed_rpm: float, *, clearance_m: float | None = None,
                 misalignment_m: float | None = None, tilt_ignored: bool = False, mu: float | None = None,
                 preload_n: float | None = None, elements_per_segment: int | None = None, law: str | None = None):
    """``(scene, model, system)`` of one operating point; overrides as in
    :func:`rotor.dynamics.build.system_from_model` (None keeps the scene's value), the mesh
    (``elements_per_segment``, None: the scene's) and the contact law (``law``, as a scene's ``law`` key;
    None: the scene's)."""
    from rotor.dynamics.build import system_from_model

    check_positive("speed_rpm", speed_rpm, "rpm", allow_zero=True, upper=plausible.top("run_speed_rpm"))
    sc, model = _scene_model(scene, elements_per_segment, law)
    omega = float(speed_rpm) * math.pi / 30.0
    system = system_from_model(model, sc, omega, tilt_ignored=bool(tilt_ignored), mu=mu, preload_N=preload_n,
                               clearance_m=clearance_m, misalignment_m=misalignment_m)
    return sc, model, system


def run_point(scene: str, speed_rpm: float, clearance_m: float | None = None, misalignment_m: float | None = None,
              tilt_ignored: bool = False, mu: float | None = None, preload_n: float | None = None,
              options: dict | None = None, max_order: float = 6.0, history_revs: int = 4,
              elements_per_segment: int | None = None, law: str | None = None, scene_sha256: str | None = None):
    """Steady state of one operating point, as ``(arrays, info)`` for :func:`sweep.run_sweep` (``scene_sha256``:
    the resolved scene's digest its task was made from, rotor/studies/scene_digest.py; refused if it changed).

    Arrays (SI): ``channels`` names; ``harm_q`` (5, c) complex displacement amplitudes of 1X–5X (m),
    ``harm_v`` (5, c) velocity (m/s), ``harm_u`` (5, 4) relative support motion (m, rad);
    ``spec_orders`` (J,) frequency in orders of f and ``spec_v`` (J, c) / ``spec_q`` (J, c) /
    ``spec_u`` (J, 4) amplitude spectra on exact bins; the last ``history_revs`` revolutions of
    ``t`` (s), ``q`` (m), ``v`` (m/s), ``u`` (m, rad), ``r1``/``r2`` (m), ``modes`` and
    ``f_contact`` (N, N m), ``q_all`` (all DOFs, m/rad) with ``dof_names`` and the misalignment
    offset ``offset`` (m, rad). Info: convergence, regime (stick/slip/impact), revolutions, timing, and the
    contact force and face stick over the whole record (:func:`rotor.dynamics.support_record.contact_summary`:
    ``peak_contact_force_N``, ``mean_contact_force_N``, ``contact_share``, ``stick_share_right_face`` …), and
    ``start``, how the transient started (:func:`study_start`).
    """
    opts = SteadyStateOptions(**(options or {}))
    sc, model, system = point_system(scene, speed_rpm, clearance_m=clearance_m, misalignment_m=misalignment_m,
                                     tilt_ignored=tilt_ignored, mu=mu, preload_n=preload_n,
                                     elements_per_segment=elements_per_segment, law=law)
    check_digest(scene_sha256, sc, elements_per_segment, what=f"study point at {speed_rpm:g} rpm")
    try:
        q0, v0, start = study_start(system, model)
        res = steady_state(system, model, options=opts, q0=q0, v0=v0)
    except OutsideDomainError as exc:
        return beyond_law_record(model, system, exc, speed_rpm=speed_rpm, misalignment_m=misalignment_m,
                                 tilt_ignored=tilt_ignored, elements_per_segment=elements_per_segment)
    arrays, info = point_record(res, sc, model, system, opts, speed_rpm=speed_rpm, misalignment_m=misalignment_m,
                                tilt_ignored=tilt_ignored, max_order=max_order, history_revs=history_revs,
                                elements_per_segment=elements_per_segment)
    return arrays, {**info, "start": start}


def study_start(system, model) -> tuple:
    """``(q0, v0, kind)`` of a transient study point: under gravity or ``[[static_loads]]`` the end faces cannot hold
    out of contact, the static equilibrium with the linear forced response about it
    (:func:`rotor.dynamics.static_start.periodic_start`); otherwise ``(None, None)``: rest at the misalignment offset,
    the start every published study ran from (none of the bundled scenes has gravity or static loads; the start of a
    non-periodic point's record, and of a continuum held by friction, changes its numbers)."""
    from rotor.dynamics.static_start import FORCED_KIND, periodic_start
    from rotor.model.static_load import static_load

    if np.any(static_load(model)):
        q0, v0, rec = periodic_start(system, model, 0.0)
        if rec["kind"] == FORCED_KIND:
            return q0, v0, FORCED_KIND
    return None, None, "rest at the misalignment offset"


def point_record(res: SteadyResult, sc, model, system, opts: SteadyStateOptions, *, speed_rpm: float,
                 misalignment_m: float | None, tilt_ignored: bool, max_order: float = 6.0, history_revs: int = 4,
                 elements_per_segment: int | None = None):
    """``(arrays, info)`` of :func:`run_point` from a steady record ``res`` (shared with the shooting point,
    :mod:`rotor.studies.shooting_point`)."""
    orders = (1, 2, 3, 4, 5)
    arrays = {"channels": np.array(res.channels)}
    for name, x in (("q", res.q), ("v", res.v), ("u", res.u)):
        xm = x - x.mean(axis=0)
        if res.static:
            arrays[f"harm_{name}"] = np.zeros((len(orders), x.shape[1]), complex)
        else:
            arrays[f"harm_{name}"] = harmonic_amplitudes(xm, res.revolutions, orders)
        so, sa = spectrum(xm, res.revolutions, max_order)
        arrays[f"spec_{name}"] = sa
    arrays["spec_orders"] = so
    arrays["mean_q"] = res.q.mean(axis=0)
    n_hist = min(int(history_revs), res.revolutions) * res.samples_per_rev
    for name in ("t", "q", "v", "u", "r1", "r2", "modes", "f_contact", "q_all"):
        arrays[name] = getattr(res, name)[-n_hist:]
    arrays["dof_names"] = np.array(model.dof_names)
    arrays["offset"] = system.offset
    c = res.convergence
    info = {"speed_rpm": float(speed_rpm), "converged": bool(c.converged), "period_revs": int(c.period),
            "poincare_change": float(c.change), "poincare_remaining": float(c.remaining),
            "transient_revs": int(res.transient_revs), "record_revs": int(res.revolutions),
            "steps_per_rev": int(res.steps_per_rev), "samples_per_rev": int(res.samples_per_rev),
            "clearance_m": float(res.clearance_m),
            "misalignment_m": float(misalignment_m if misalignment_m is not None
                                    else (sc.misalignment.offset_m if getattr(sc, "misalignment", None) else 0.0)),
            "tilt_ignored": bool(tilt_ignored), "least_residual_steps": int(res.unconverged_steps),
            "static": bool(res.static), "wall_s": float(res.wall_s),
            "law": system.support.law.name if system.support is not None else None,
            "elements_per_segment": elements_per_segment, "n_dofs": int(model.n_dofs),
            "options": dataclasses.asdict(opts), "integrator": dataclasses.asdict(NewmarkOptions()),
            **res.regime(), **_law_info(sc, res),
            **(contact_summary(res.t, res.f_contact, res.modes, n_faces=res.n_faces)
               if system.support is not None else {})}
    return arrays, info


def beyond_law_record(model, system, exc, *, speed_rpm: float, misalignment_m, tilt_ignored: bool,
                      elements_per_segment=None):
    """``(arrays, info)`` of a point whose load drives the ring past the contact law's neat-fit limit
    (:class:`contact.errors.OutsideDomainError`): a measured outcome of the operating point, not a failed run.
    No record exists: the harmonic amplitudes are NaN (figures leave a gap, tables say why), the point is not
    periodic, and ``info["outside_law_domain"]`` holds the law's message."""
    stations = model.response_stations()
    channels = np.array([f"{s}.{c}" for s in stations for c in ("y", "z")])
    nan = np.full((5, len(channels)), np.nan + 0j)
    arrays = {"channels": channels, "harm_q": nan, "harm_v": nan.copy(), "harm_u": np.full((5, 4), np.nan + 0j),
              "spec_orders": np.zeros(0), "spec_q": np.zeros((0, len(channels))),
              "spec_v": np.zeros((0, len(channels))), "spec_u": np.zeros((0, 4))}
    info = {"speed_rpm": float(speed_rpm), "converged": False, "period_revs": 0, "outside_law_domain": str(exc),
            "label": "beyond law", "clearance_m": float(system.support.law.clearance_m),
            "misalignment_m": float(misalignment_m if misalignment_m is not None
                                    else (model.scene.misalignment.offset_m if model.scene.misalignment else 0.0)),
            "tilt_ignored": bool(tilt_ignored), "elements_per_segment": elements_per_segment,
            "transient_revs": 0, "record_revs": 0, "integrator": dataclasses.asdict(NewmarkOptions())}
    return arrays, info


def _law_info(sc, res: SteadyResult) -> dict:
    """A calibrated law's file, checksum and validity check of a point (empty for an analytic law): the
    deepest edge penetration past the clearance over the recorded samples (m) against the law's fitted range."""
    ls = sc.loose_support
    if ls is None or ls.calibrated is None:
        return {}
    pen = max(float(max(res.r1.max(), res.r2.max())) - res.clearance_m, 0.0) if len(res.r1) else 0.0
    top = ls.validity_max_penetration_m
    return {**ls.law_note(), "max_edge_penetration_m": pen, "law_validity_max_penetration_m": top,
            "beyond_law_validity": bool(pen > top)}


def sweep_tasks(scene: str, speeds_rpm, *, prefix: str = "rpm", **overrides) -> list:
    """One :class:`sweep.Task` of :func:`run_point` per speed (rpm), same overrides for all.

    Keys are ``<prefix><speed>`` with the speed to 0.1 rpm (``rpm10500.0``); params carry the resolved scene's
    digest, so that a point stored before the scene changed is stale (rotor/studies/scene_digest.py)."""
    from sweep import Task

    ov = {k: v for k, v in overrides.items() if v is not None}
    e = ov.get("elements_per_segment")
    common = {"scene": scene, **ov, "scene_sha256": scene_digest(_scene_model(scene, e, ov.get("law"))[0], e)}
    return [Task(f"{prefix}{float(s):.1f}", run_point, {**common, "speed_rpm": float(s)}) for s in speeds_rpm]

"""Reference time integrator: the paper's Newmark-β scheme with constraints (Dai et al. 2025, §4).

Governing system (Eq. 59)::

    M q̈ + (C − ωG) q̇ + K (q − Δq_m) = Q(t) + F_sum(q, q̇) + Φᵀ-forces,   G_c = 0

with ``Q`` the harmonic loads (unbalance 1X, misalignment 2X, any static load),
``F_sum`` the loose-support force (radial contact from a law of :mod:`contact`, plus
Coulomb friction of the *slipping* end faces) and ``G_c`` the stuck-face velocity
rows and the 3a/3b lock rows (:mod:`rotor.dynamics.constraints`).

Scheme (Eqs. 64–74), as implemented here
----------------------------------------
1. Predictor (Eq. 66): ``q_pre = q_n + Δt q̇_n + Δt²(½ − β) q̈_n``,
   ``q̇_pre = q̇_n + Δt(1 − γ) q̈_n``.
2. Newton on ``z = [q̈_{n+1}; λ_{n+1}]`` (Eqs. 67–73) with the **finite-difference
   Jacobian** of Eq. 72 (one residual evaluation per unknown), started from
   ``z_0 = [q̈_n; λ_n]`` and stopped when ``‖Δz‖ ≤ ε (‖z‖ + z_floor)`` (Eq. 73).
   The constraint Jacobian Φ is also obtained by finite differences, as the paper says.
3. Correction (Eq. 74): ``q_{n+1} = q_pre + βΔt² q̈_{n+1}``, ``q̇_{n+1} = q̇_pre + γΔt q̈_{n+1}``.

Decision: **implicit reading of Eq. 69.** The flattened Eq. 69 writes the damping and
stiffness terms with ``q̇_pre, q_pre``. Read literally the scheme would be explicit
(conditionally stable, no energy conservation) and Φ = ∂G_c/∂q̈ of the velocity
constraints would vanish. Since the same notation is used for ``G_c(q̈, q̇_pre, q_pre)``
whose q̈-dependence is the whole point, we read both as "the corrected values
expressed through q̈" (Eq. 74), i.e. the standard implicit Newmark method.

Constraint rows are scaled so that the multipliers are forces: the lock rows are
``L q_{n+1}/(βΔt²)`` and the stick rows ``P_k w_{n+1}/(γΔt)``, hence ``Φ = ∂G_c/∂q̈`` is
``L`` and ``P_k B``, and the force of a stuck face on the bearing is ``−λ_k`` (N).
Everything about modes, the stick test and the traps is in :mod:`rotor.dynamics.constraints`.

The problem description both schemes share (:class:`~rotor.dynamics.system.RotorSystem`,
:class:`~rotor.dynamics.system.NewmarkOptions`, :class:`~rotor.dynamics.system.Trajectory`) and the
step-size check (:func:`rotor.dynamics.system.check_time_step`) are in :mod:`rotor.dynamics.system`.

Safeguards not in the paper (identical in both schemes, so they still agree)
----------------------------------------------------------------------------
* Backtracking on ``‖F‖`` when a full Newton step does not reduce it (kinks of the contact
  law: first touch, damping clip, edge switch).
* If Newton does not converge with a face slipping (the regularised direction
  ``w/√(|w|²+w_reg²)`` is very stiff near ``w = 0``), that face is tried in stick.
* The paper's sharp one-edge selection (docs/reference/contact-laws.md §8, Q8) is discontinuous where the two
  edge penetrations cross; there an implicit step can have no exact root. The contact layer
  regularises it by default (``LooseSupportParams.edge_transition_m``, :mod:`contact.tilt`), which
  removed every such step of the hard cases. If Newton still fails after the fallbacks, the
  least-residual iterate is accepted and counted in ``Trajectory.unconverged_steps`` (0 on the
  hard cases of ``benchmarks/bench_integrators.py`` section 4; 0–1 % of the steps with the sharp
  rule; reported by the benchmark and the ``simulate`` job).
* Initial modes: a face asked to start stuck whose holding force exceeds ``μN`` starts slipping
  (:func:`rotor.dynamics.initial.initial_state`).

This module is the *reference*: clear and faithful, not fast. Use
:mod:`rotor.dynamics.production` for real runs; the two agree to the Newton tolerance.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from contact.errors import ConvergenceError
from rotor.dynamics import constraints as cons
from rotor.dynamics.initial import initial_acceleration, initial_state
from rotor.dynamics.system import (NewmarkOptions, RotorSystem, Trajectory, check_inputs, check_time_step,
                                   coupling_force, support_forces)


def simulate_reference(system: RotorSystem, dt: float, n_steps: int, q0=None, v0=None, *, t0: float = 0.0,
                       modes0=(cons.STICK, cons.STICK), options: NewmarkOptions | None = None,
                       record_every: int = 1, check_step: bool = True) -> Trajectory:
    """Integrate ``n_steps`` steps of ``dt`` (s) with the paper's scheme (Eqs. 64–74).

    Parameters
    ----------
    system : RotorSystem
    dt : float, time step (s)
    n_steps : int
    q0, v0 : (n,) initial displacement (m, rad) and velocity (m/s, rad/s); zero by default
    modes0 : initial end-face modes (right, left); STICK by default (Section 3.3)
    options : NewmarkOptions
    record_every : keep every k-th step in the Trajectory
    check_step : raise InputError if dt exceeds the largest stable step

    Raises
    ------
    ConvergenceError if Newton does not converge within ``max_iter`` iterations
    (names the step, time and reached tolerance), InputError on bad input.
    """
    opts = options or NewmarkOptions()
    n = system.n
    q0 = np.zeros(n) if q0 is None else np.asarray(q0, dtype=float).copy()
    v0 = np.zeros(n) if v0 is None else np.asarray(v0, dtype=float).copy()
    check_inputs(system, dt, n_steps, q0, v0)
    if system.support is not None and check_step:
        check_time_step(system, dt)
    run = _ReferenceRun(system, dt, opts)
    run.start(t0, q0, v0, modes0, n_steps // record_every + 1)
    for step in range(1, n_steps + 1):
        sp = run.predict(t0 + step * dt)
        run.solve_step(sp, step)
        run.correct(sp, step)
        if step % record_every == 0:
            run.record(step // record_every, sp.t, sp.total_its, sp.passes)
    return run.tr


@dataclass
class _Step:
    """One time step: its time ``t``, the predictor (Eq. 66), the load ``Q(t)``, the start-of-step
    face velocities and forces of the stick test, and the active-set loop's flags and counters
    (``freeze[k]``: the friction force of a releasing face held at μN for a first solve)."""

    t: float
    q_pre: np.ndarray
    v_pre: np.ndarray
    Q: np.ndarray
    w_old: list
    phi_old: np.ndarray
    tried_stick: list
    stuck_at_start: list
    freeze: list = field(default_factory=lambda: [None, None])
    passes: int = 0
    total_its: int = 0


class _ReferenceRun:
    """One run of the paper's scheme: the fixed matrices and maps, the state (``q, v, a``, multipliers,
    face modes, support forces) and the named stages of a step, in the order
    :func:`simulate_reference` calls them: :meth:`predict`, :meth:`solve_step` (:meth:`newton` on
    :meth:`residual`, then :meth:`update_modes`), :meth:`correct`, :meth:`record`."""

    def __init__(self, system: RotorSystem, dt: float, opts: NewmarkOptions):
        n = system.n
        sup = system.support
        self.system, self.dt, self.opts, self.n, self.sup = system, dt, opts, n, sup
        self.M, self.K, self.D, self.L = system.M, system.K, system.D, system.lock
        self.off = system.offset
        self.B = sup.relative_map(n) if sup is not None else np.zeros((4, n))
        # face maps, friction limit per face (N) and active faces (1 with the tilt ignored)
        self.P, self.limits, self.n_faces = sup.faces() if sup is not None else (np.zeros((2, 2, 4)), np.zeros(2), 0)
        self.bdt2 = opts.beta * dt * dt
        self.gdt = opts.gamma * dt

    def start(self, t0: float, q0, v0, modes0, n_rec: int) -> None:
        """Initial state: consistent acceleration and multipliers with the stick test applied to
        ``modes0`` (:func:`rotor.dynamics.initial.initial_state`), recorded as sample 0."""
        modes = [int(m) for m in modes0][:self.n_faces] + [cons.SLIP] * (2 - self.n_faces)
        self.a, lam, self.modes = initial_state(self.system, t0, q0, v0, modes, self.opts)
        self.q, self.v = q0, v0
        self.lam_lock, self.lam_face = _split_multipliers(lam, self.L.shape[0], self.modes, self.n_faces)
        self.tr = _allocate(n_rec, self.n)
        self.tr.scheme = "reference (paper, FD-Newton)"
        self.u, self.w, self.fc, self.phi, _ = support_forces(self.system, self.q, self.v, self.modes, self.lam_face,
                                                              self.opts)
        self.record(0, t0, 0, 0)
        self.just_released = [False, False]

    def predict(self, t: float) -> _Step:
        """Predictor (Eq. 66) and the start-of-step data of the step ending at ``t``."""
        dt, beta, gamma = self.dt, self.opts.beta, self.opts.gamma
        q, v, a = self.q, self.v, self.a
        tried_stick = [self.modes[k] == cons.STICK for k in range(2)]
        return _Step(t=t, q_pre=q + dt * v + dt * dt * (0.5 - beta) * a, v_pre=v + dt * (1 - gamma) * a,
                     Q=self.system.force(t), w_old=[self.P[k] @ (self.B @ v) for k in range(2)],
                     phi_old=self.phi.copy(), tried_stick=tried_stick, stuck_at_start=list(tried_stick))

    def solve_step(self, sp: _Step, step: int) -> None:
        """The active-set loop of one step: Newton with the face modes held, then the stick/slip test,
        re-solved with the flipped modes until they are consistent (at most ``max_passes`` passes).
        Leaves the step's acceleration, multipliers and modes in ``self``."""
        opts = self.opts
        while True:
            sp.passes += 1
            stuck = [k for k in range(self.n_faces) if self.modes[k] == cons.STICK]
            z, its, ok, err = self.newton(sp, stuck)
            sp.total_its += its
            if not ok:
                # slip Newton stalls when the true answer is (near) stick: try stick on the
                # slipping faces not yet tried in this step (same rule as rotor.dynamics.production)
                flip = [k for k in range(self.n_faces) if self.modes[k] == cons.SLIP and not sp.tried_stick[k]]
                if flip and sp.passes < opts.max_passes + 4:
                    for k in flip:
                        self.modes[k] = cons.STICK
                        sp.tried_stick[k] = True
                    sp.freeze = [None, None]
                    continue
                if np.all(np.isfinite(z)):
                    # no exact root (e.g. the sharp one-edge selection of the law, edge_transition_m
                    # = 0): keep the least-residual iterate and count the step, as rotor.dynamics.production does
                    self.tr.unconverged_steps += 1
                    ok = True
            if not ok:
                raise ConvergenceError(
                    f"reference Newton (finite-difference Jacobian) did not converge at step {step}, t = {sp.t:.6g} s: "
                    f"|dz|/|z| = {err:.3e} > tol = {opts.tol:.1e} after {opts.max_iter} iterations; "
                    f"reduce dt_s = {self.dt:.3e} s")
            a_new = z[:self.n]
            if any(f is not None for f in sp.freeze):
                # second stage of a release: now with the implicit slip direction
                sp.freeze = [None, None]
                self.a = a_new
                continue
            lam_lock_new, lam_face_new = _split_multipliers(z[self.n:], self.L.shape[0], self.modes, self.n_faces)
            changed, new_modes = self.update_modes(sp, stuck, a_new, lam_face_new)
            if not changed or sp.passes >= opts.max_passes:
                self.a, self.lam_lock, self.lam_face = a_new, lam_lock_new, lam_face_new
                return
            self.modes = new_modes
            self.a = a_new if not any(f is not None for f in sp.freeze) else self.a

    def newton(self, sp: _Step, stuck: list):
        """Newton on ``z = [q̈_{n+1}; λ_{n+1}]`` with the modes held (Eqs. 67–73), from the initial
        iterate ``z0 = [q̈_n; λ_n]`` (Eq. 70), the multipliers of the current rows. Returns
        ``(z, iterations, converged, |dz|/|z|)`` of :func:`_fd_newton`."""
        Phi = self.constraint_jacobian(sp, stuck)
        freeze = sp.freeze
        lam0 = [self.lam_lock]
        for k in stuck:
            lam0.append(self.lam_face[k])
        z = np.concatenate([self.a] + lam0)
        return _fd_newton(lambda zz: self.residual(sp, stuck, Phi, freeze, zz), z, self.opts.tol, self.opts.max_iter)

    def constraints(self, sp: _Step, stuck: list, acc) -> np.ndarray:
        """``G_c`` at the corrected state of acceleration ``acc``: lock rows ``L q/(βΔt²)``, then the
        stuck faces' velocity rows ``P_k B q̇/(γΔt)``."""
        qn = sp.q_pre + self.bdt2 * acc
        vn = sp.v_pre + self.gdt * acc
        g = [self.L @ qn / self.bdt2]
        for k in stuck:
            g.append(self.P[k] @ (self.B @ vn) / self.gdt)
        return np.concatenate(g)

    def constraint_jacobian(self, sp: _Step, stuck: list) -> np.ndarray:
        """Φ = ∂G_c/∂q̈ by finite differences at the current acceleration (the paper's "analogy to Eq. 72")."""
        a = self.a
        m = self.L.shape[0] + 2 * len(stuck)
        g0 = self.constraints(sp, stuck, a)
        Phi = np.empty((m, self.n))
        for jj in range(self.n):
            h = 1e-7 * max(abs(a[jj]), 1.0)
            e = a.copy()
            e[jj] += h
            Phi[:, jj] = (self.constraints(sp, stuck, e) - g0) / h
        return Phi

    def residual(self, sp: _Step, stuck: list, Phi: np.ndarray, freeze: list, z) -> np.ndarray:
        """``F(z)`` of Eq. 69 (read implicitly) and the constraint rows, at ``z = [q̈; λ]``: slipping
        faces carry their regularised Coulomb force (or the frozen one of a release)."""
        n, sup = self.n, self.sup
        acc = z[:n]
        lam_ = z[n:]
        qn = sp.q_pre + self.bdt2 * acc
        vn = sp.v_pre + self.gdt * acc
        r = self.M @ acc + self.D @ vn + self.K @ (qn - self.off) - sp.Q + Phi.T @ lam_ - coupling_force(self.system, qn)
        if sup is not None:
            B, P = self.B, self.P
            un = B @ qn
            wn = B @ vn
            gl = np.asarray(sup.law.force(un, wn), dtype=float).copy()
            for k in range(2):
                if self.modes[k] == cons.SLIP:
                    if freeze[k] is not None:
                        gl += P[k].T @ freeze[k]
                    else:
                        gl += P[k].T @ cons.slip_force(P[k] @ wn, self.limits[k], self.opts.w_reg)[0]
            r -= B.T @ gl
        return np.concatenate([r, self.constraints(sp, stuck, acc)])

    def update_modes(self, sp: _Step, stuck: list, a_new, lam_face_new) -> tuple[bool, list]:
        """Stick/slip test of each face on the converged pass (:func:`rotor.dynamics.constraints.face_mode_update`).

        Returns ``(changed, new modes)``. A releasing face gets its friction force frozen at μN
        along the held force for a first solve (``sp.freeze``); with a stick onset in the pass the
        stuck faces' multipliers in ``lam_face_new`` are replaced by the consistent ones."""
        opts, P, B, limits, modes = self.opts, self.P, self.B, self.limits, self.modes
        v_new = sp.v_pre + self.gdt * a_new
        changed = False
        new_modes = list(modes)
        onset_trial = [modes[k] == cons.STICK and not sp.stuck_at_start[k] for k in range(self.n_faces)]
        if opts.consistent_stick_onset and any(onset_trial):
            # a face trying stick (slipping at the start of the step) is tested on its holding force
            # at the end of the step: the consistent multiplier, not the trapezoidal one; a stuck
            # other face on its consistent multiplier too (the one the step will keep)
            _, lam_c = initial_acceleration(self.system, sp.t, sp.q_pre + self.bdt2 * a_new, v_new, modes, opts)
            jj = self.L.shape[0]
            for k in stuck:
                lam_face_new[k] = lam_c[jj:jj + 2]
                jj += 2
        for k in range(self.n_faces):
            wk = P[k] @ (B @ v_new)
            if modes[k] == cons.STICK:
                fk = -lam_face_new[k]
            else:
                fk = cons.slip_force(wk, limits[k], opts.w_reg)[0]
            w_stick = 0.0 if self.just_released[k] else opts.w_stick
            nm = cons.face_mode_update(modes[k], fk, wk, sp.w_old[k], limits[k], w_stick, sp.tried_stick[k],
                                       sp.phi_old[k], opts.stick_mean_weight if sp.stuck_at_start[k] else 0.0)
            if nm != modes[k]:
                changed = True
                new_modes[k] = nm
                if nm == cons.STICK:
                    sp.tried_stick[k] = True
                else:
                    # release: first solve with the friction force frozen at μN along the held force
                    nrm = math.hypot(fk[0], fk[1])
                    sp.freeze[k] = limits[k] * fk / nrm if nrm > 0 else np.zeros(2)
        return changed, new_modes

    def correct(self, sp: _Step, step: int) -> None:
        """Correction (Eq. 74), the consistent restart after a stick onset, and the support forces
        of the new state."""
        opts = self.opts
        q = sp.q_pre + self.bdt2 * self.a
        v = sp.v_pre + self.gdt * self.a
        if not (np.all(np.isfinite(q)) and np.all(np.isfinite(v))):
            raise ConvergenceError(f"reference scheme: non-finite state at step {step}, t = {sp.t:.6g} s; "
                                   f"reduce dt_s = {self.dt:.3e} s")
        self.q, self.v = q, v
        if opts.consistent_stick_onset:
            self.just_released = [sp.stuck_at_start[k] and self.modes[k] == cons.SLIP for k in range(2)]
            if any(self.modes[k] == cons.STICK and not sp.stuck_at_start[k] for k in range(self.n_faces)):
                # stick onset: restart from the consistent acceleration and multipliers (q, v kept)
                self.a, lam = initial_acceleration(self.system, sp.t, q, v, self.modes, opts)
                self.lam_lock, self.lam_face = _split_multipliers(lam, self.L.shape[0], self.modes, self.n_faces)
        self.u, self.w, self.fc, self.phi, _ = support_forces(self.system, q, v, self.modes, self.lam_face, opts)

    def record(self, i: int, t: float, its: int, passes: int) -> None:
        """Write the current state into sample ``i`` of the trajectory."""
        tr = self.tr
        tr.t[i], tr.q[i], tr.v[i], tr.a[i] = t, self.q, self.v, self.a
        tr.u[i], tr.w[i], tr.f_contact[i] = self.u, self.w, self.fc
        if self.sup is not None:
            tr.f_elastic[i] = self.sup.law.force(self.u, np.zeros(4))
        tr.face_force[i] = self.phi
        tr.modes[i] = self.modes
        tr.newton_iters[i] = its
        tr.passes[i] = passes


def _split_multipliers(lam, n_lock: int, modes, n_faces: int):
    """``(lock multipliers, (2, 2) face multipliers)`` from the stacked vector: the lock rows first,
    then two per stuck face in face order (slipping faces carry none: zero rows)."""
    lam_face = np.zeros((2, 2))
    j = n_lock
    for k in range(n_faces):
        if modes[k] == cons.STICK:
            lam_face[k] = lam[j:j + 2]
            j += 2
    return lam[:n_lock], lam_face


def _allocate(n_rec: int, n: int) -> Trajectory:
    return Trajectory(
        t=np.zeros(n_rec), q=np.zeros((n_rec, n)), v=np.zeros((n_rec, n)), a=np.zeros((n_rec, n)),
        u=np.zeros((n_rec, 4)), w=np.zeros((n_rec, 4)), f_contact=np.zeros((n_rec, 4)),
        f_elastic=np.zeros((n_rec, 4)), face_force=np.zeros((n_rec, 2, 2)),
        modes=np.zeros((n_rec, 2), dtype=np.int8), newton_iters=np.zeros(n_rec, dtype=np.int32),
        passes=np.zeros(n_rec, dtype=np.int32))


def _fd_newton(residual, z, tol, max_iter):
    """Discrete Newton (Eqs. 71–73): Jacobian by forward differences, one column per unknown.

    Stops when ``‖Δz‖ ≤ tol (‖z‖ + 1e-12)`` (Eq. 73). Safeguard not in the paper: when a full
    step does not decrease ``‖F‖`` (a kink of the contact law or of friction), the step is
    halved until it does (Armijo backtracking), as in :mod:`rotor.dynamics.production`.
    """
    err = math.inf
    F0 = residual(z)
    nF = np.linalg.norm(F0)
    best, best_n = z, nF
    for it in range(1, max_iter + 1):
        J = np.empty((z.size, z.size))
        for j in range(z.size):
            h = 1e-7 * max(abs(z[j]), 1e-3)
            e = z.copy()
            e[j] += h
            J[:, j] = (residual(e) - F0) / h
        try:
            dz = np.linalg.solve(J, F0)
        except np.linalg.LinAlgError:
            return z, it, False, math.inf
        err = np.linalg.norm(dz) / (np.linalg.norm(z) + 1e-12)
        if not np.isfinite(err):
            return z, it, False, err
        if err <= tol:
            return z - dz, it, True, err
        lam = 1.0
        for _ in range(40):
            zt = z - lam * dz
            Ft = residual(zt)
            nFt = np.linalg.norm(Ft)
            if nFt <= (1 - 1e-4 * lam) * nF or nFt == 0.0:
                break
            lam *= 0.5
        z, F0, nF = zt, Ft, nFt
        if nF < best_n:
            best, best_n = z, nF
    return best, max_iter, False, err

"""The static equilibrium a run starts from: the rotor under its constant load with the loose support's contact
and end-face friction solved statically (``ringcontact simulate``'s start, issue 38: a record that is not a drop
transient).

:func:`static_equilibrium` holds the end faces where a run from rest starts them, lets a face whose holding force
passes its friction limit slip (it then carries :data:`HELD_SHARE` of μN against the load), and finds by Newton
where the ring's contact carries the rest. Where Newton does not settle (a tilted ring's edge entering contact has
a force whose slope starts at zero), the rotor is let down dynamically instead: the static load alone, no spin, a
mass-proportional damping critical for the slowest mode, integrated until the motion has died
(:func:`rotor.dynamics.production.simulate_production`), the end state polished by Newton with the faces' forces
as they ended. :func:`start_record` is the JSON field ``start`` of a run.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from contact.errors import ConvergenceError, OutsideDomainError
from rotor.dynamics import constraints as cons
from rotor.dynamics.system import HarmonicForce, RotorSystem, coupling_force, coupling_map, largest_stable_step


#: the share of its friction limit μN a face that could not hold the static load carries at the start
HELD_SHARE = 0.999


@dataclass(frozen=True)
class StaticStart:
    """The static equilibrium a run starts from (:func:`static_equilibrium`).

    ``q_m`` (n,) displacements (m, rad) with the lock rows met; ``modes`` the end faces' start modes (all
    :data:`~rotor.dynamics.constraints.STICK`: a face beyond its friction limit holds at the limit, ``at_limit``);
    ``face_force_N`` (2, 2) each face's force on the bearing; ``contact_force`` (4,) the ring's contact force and
    moment on the bearing (N, N m); ``iterations`` Newton iterations; ``residual_N`` the largest force residual;
    ``let_down_steps`` the time steps of :func:`_let_down` (0: Newton alone found it).
    """

    q_m: np.ndarray
    modes: tuple
    at_limit: tuple
    face_force_N: np.ndarray
    contact_force: np.ndarray
    iterations: int
    residual_N: float
    let_down_steps: int = 0


def static_equilibrium(system: RotorSystem, *, max_iter: int = 400) -> StaticStart:
    """The static equilibrium of ``system`` under its constant load: gravity, ``[[static_loads]]``, the
    misalignment offset (``K (q − Δq_m) = f_static + …``), with the loose support's contact and end-face friction.

    The end faces are first held where a run from rest starts them (the relative motion of the offset state): a
    linear solve whose face multipliers are the holding forces. A face whose holding force exceeds its limit μN
    slips: it then carries μN against the load (the direction of its holding force) and the ring moves until its
    contact carries the rest: Newton on the equilibrium with the law's analytic Jacobian (the compiled kernel,
    ``SupportLaw.kernel``), each step capped and halved until the residual falls. A face that slipped holds
    :data:`HELD_SHARE` of its limit at the start (an admissible static state: any force up to μN is; at exactly μN
    the regularised slip of the first steps would let the ring creep) and starts stuck; the first step's stick test
    (:func:`rotor.dynamics.initial.initial_state`) decides whether it stays so. Where Newton does not settle, the
    rotor is let down dynamically (:func:`_let_down`, the module docstring).
    """
    offset = np.asarray(system.offset, dtype=float)
    load = system.force.static + system.K @ offset
    if system.support is None:
        return StaticStart(_locked_static(system, load), (), (), np.zeros((2, 2)), np.zeros(4), 1, 0.0)
    try:
        try:
            return _held_then_slipping(system, load, max_iter)
        except ConvergenceError:
            return _let_down(system, load, max_iter)
    except OutsideDomainError as exc:
        raise OutsideDomainError(
            f"static equilibrium: the constant load (gravity, static loads, misalignment offset) presses the ring "
            f"past its law's domain ({exc}); a run meets the same load: a larger clearance or a smaller load, or "
            "start from rest anyway (simulate --from-rest, from_rest=True)") from None


def _held_then_slipping(system: RotorSystem, load, max_iter: int) -> StaticStart:
    """The faces held, then those past their limit slipping at it, Newton each time (:func:`static_equilibrium`)."""
    sup = system.support
    offset = np.asarray(system.offset, dtype=float)
    B = sup.relative_map(system.n)
    P, limits, n_faces = sup.faces()
    held = list(range(n_faces))
    phi = np.zeros((2, 2))
    q = offset.copy()
    its = 0
    for _ in range(n_faces + 1):              # faces that pass their limit leave the held set, one pass each
        q, lam, k = _newton(system, load, B, P, held, phi, q, offset, max_iter)
        its += k
        over = [f for j, f in enumerate(held) if np.hypot(*lam[2 * j:2 * j + 2]) > limits[f] * (1 + 1e-9)]
        for j, f in enumerate(held):
            phi[f] = -lam[2 * j:2 * j + 2]
        if not over:
            break
        for f in over:                          # slips: its limit against the load it could not hold
            h = np.hypot(*phi[f])
            phi[f] = phi[f] / h * limits[f] * HELD_SHARE if h > 0 else 0.0
        held = [f for f in held if f not in over]
    return _start(system, load, q, phi, tuple(bool(f not in held) for f in range(n_faces)), its)


def _start(system: RotorSystem, load, q, phi, at_limit, its: int) -> StaticStart:
    """The :class:`StaticStart` at ``q`` with the faces' forces ``phi``; its residual on the lock's null space."""
    B = system.support.relative_map(system.n)
    P = system.support.faces()[0]
    fc = np.asarray(system.support.law.force(B @ q, np.zeros(4)), dtype=float)
    res = cons.null_space_map(system.lock).T @ _residual(system, load, B, P, [], phi, q, fc)   # lock forces internal
    return StaticStart(q, (cons.STICK, cons.STICK), tuple(at_limit), phi, fc, its, float(np.abs(res).max()))


def _let_down(system: RotorSystem, load, max_iter: int) -> StaticStart:
    """The rotor let down onto its support dynamically: the static load alone, no spin, damping ``2 ω_1 M`` (critical
    for the slowest mode ω_1) added, integrated from rest at the offset for 30 / ω_1 (its motion e⁻³⁰ of the start)
    by :func:`rotor.dynamics.production.simulate_production`; the end state polished by Newton with the faces'
    forces as they ended (each within its limit: stuck or slipping at it)."""
    from rotor.dynamics.production import simulate_production

    n = system.n
    T = cons.null_space_map(system.lock)
    Kr, Mr = T.T @ system.K @ T, T.T @ system.M @ T
    w1 = 1.0 / math.sqrt(float(np.max(np.linalg.eigvals(np.linalg.solve(Kr, Mr)).real)))
    still = HarmonicForce(system.force.static.copy(), np.zeros(0), np.zeros((0, n)), np.zeros((0, n)), 0.0)
    damped = replace(system, C=system.C + 2.0 * w1 * system.M, omega_rad_s=0.0, force=still)
    dt = min(0.5 * largest_stable_step(damped)[0], 0.05 / w1)
    steps = int(math.ceil(30.0 / w1 / dt))
    tr = simulate_production(damped, dt, steps, q0=np.asarray(system.offset, dtype=float), record_every=steps)
    phi = np.array(tr.face_force[-1], dtype=float)
    B = system.support.relative_map(n)
    P, limits, n_faces = system.support.faces()
    at_limit = [bool(np.hypot(*phi[f]) >= limits[f] * HELD_SHARE) for f in range(n_faces)]
    for f in range(n_faces):                  # a face slipping at its limit holds HELD_SHARE of it, as above
        if at_limit[f]:
            phi[f] *= limits[f] * HELD_SHARE / np.hypot(*phi[f])
    q, _, its = _newton(system, load, B, P, [], phi, tr.q[-1], system.offset, max_iter)
    return replace(_start(system, load, q, phi, at_limit, its), let_down_steps=steps)


def _locked_static(system: RotorSystem, load) -> np.ndarray:
    T = cons.null_space_map(system.lock)
    return T @ np.linalg.solve(T.T @ system.K @ T, T.T @ load)


def _residual(system, load, B, P, held, phi, q, fc) -> np.ndarray:
    """``f_static + K Δq_m + Bᵀ(f_c + Σ_slipping Pᵀφ) + coupling − K q`` (N, N m): the force the statics leaves."""
    g = fc.copy()
    for f in range(len(phi)):
        if f not in held:
            g += P[f].T @ phi[f]
    return load + B.T @ g + coupling_force(system, q) - system.K @ q


def _newton(system, load, B, P, held, phi, q, offset, max_iter: int):
    """Newton on the statics with the ``held`` faces fixed at the offset state's relative motion (their
    multipliers returned) and the others carrying ``phi``; ``(q, face multipliers (2 per held face), iterations)``.

    Each step is capped (the ring's lateral motion at a quarter of the clearance) and halved until the residual
    (force and scaled constraint) falls: a ring's edge entering contact has a force whose slope starts at zero,
    where plain Newton steps cycle in and out of contact."""
    n = system.n
    C = np.vstack([system.lock] + [P[f] @ B for f in held]) if (system.lock.shape[0] or held) else np.zeros((0, n))
    c = np.concatenate([np.zeros(system.lock.shape[0])] + [P[f] @ B @ offset for f in held])
    m, n_l = C.shape[0], system.lock.shape[0]
    step_cap = 0.25 * system.support.law.clearance_m
    lam = np.zeros(m)
    scale = max(float(np.abs(load).max()), 1.0)
    k_scale = max(float(np.abs(np.diag(system.K)).max()), 1.0)    # constraint rows scaled to the stiffness

    def state(q, lam):
        fc, Ju = _law_at(system.support.law, B @ q)
        r = _residual(system, load, B, P, held, phi, q, fc) - C.T @ lam
        return r, Ju, float(np.linalg.norm(r) + np.linalg.norm(k_scale * (C @ q - c)))

    r, Ju, merit = state(q, lam)
    for it in range(1, max_iter + 1):
        if np.abs(r).max() <= 1e-9 * scale and np.all(np.abs(C @ q - c) <= 1e-14 * (1 + np.abs(q).max())):
            return q, lam[n_l:], it - 1
        A = np.block([[system.K - B.T @ Ju @ B - _coupling_jacobian(system, q), k_scale * C.T],
                      [k_scale * C, np.zeros((m, m))]])
        z = np.linalg.solve(A, np.concatenate([r, k_scale * (c - C @ q)]))
        dq, dlam = z[:n], k_scale * z[n:]
        du = float(np.abs((B @ dq)[:2]).max())
        a = min(1.0, step_cap / du) if du > 0 else 1.0
        while True:
            trial = state(q + a * dq, lam + a * dlam)
            if trial[2] <= merit or a < 1e-8:
                break
            a *= 0.5
        q, lam = q + a * dq, lam + a * dlam
        r, Ju, merit = trial
    raise ConvergenceError(f"static equilibrium: Newton did not converge in {max_iter} iterations (largest force "
                           f"residual {np.abs(r).max():.3g} N); start from rest instead (simulate --from-rest)")


def _law_at(law, u) -> tuple[np.ndarray, np.ndarray]:
    """The contact law's force (4,) and its Jacobian (4, 4) at the relative state ``u``, at rest: the compiled
    kernel's analytic one, else central differences."""
    zero4 = np.zeros(4)
    if law.kernel is not None:
        fc, Ju, _ = law.kernel(u, zero4, law.params)
        return np.asarray(fc, dtype=float), np.asarray(Ju, dtype=float)
    h = 1e-10
    Ju = np.column_stack([(np.asarray(law.force(u + e, zero4)) - np.asarray(law.force(u - e, zero4))) / (2 * h)
                          for e in np.eye(4) * h])
    return np.asarray(law.force(u, zero4), dtype=float), Ju


def _coupling_jacobian(system: RotorSystem, q) -> np.ndarray:
    """``∂/∂q`` of :func:`rotor.dynamics.system.coupling_force` (n, n): ``−a1 E_cᵀ (|d|² I + 2 d dᵀ) E_c``,
    ``d = E_c q`` (the cubic remainder of the transition shaft's spring; zero without one)."""
    if system.coupling is None or system.coupling[2] == 0.0:
        return np.zeros((system.n, system.n))
    Ec = coupling_map(system)
    d = Ec @ q
    return -float(system.coupling[2]) * Ec.T @ (float(d @ d) * np.eye(2) + 2.0 * np.outer(d, d)) @ Ec


def forced_start(system: RotorSystem, t0: float = 0.0, start: StaticStart | None = None):
    """``(q0, v0, start)``: the static equilibrium (:func:`static_equilibrium`, or ``start`` if given) plus the linear
    forced response about it at ``t0`` (support locked, the harmonics of
    :func:`rotor.dynamics.initial.linear_initial_state`): the start of a transient that seeks a periodic orbit
    (orbit, branch, the studies' shooting points). Where the faces hold the constant load with the ring out of
    contact (every bundled scene: no gravity or static loads) the equilibrium is the locked linear static state and
    this start is the linear periodic solution itself; under gravity it puts the ring where it rests, not floating
    in the middle of its clearance."""
    from rotor.dynamics.initial import linear_initial_state

    start = static_equilibrium(system) if start is None else start
    q, v = linear_initial_state(system, t0, static=False)
    return start.q_m + q, v, start


#: the ring positions (lateral, bearing minus support) of the equilibrium and the locked linear static state count as
#: the same within this share of the clearance (:func:`periodic_start`)
SAME_RING_POSITION = 1e-3
LINEAR_KIND = "linear periodic solution (support locked)"
FREE_KIND = "linear periodic solution (support free)"
#: phases per revolution at which :func:`_free_orbit_inside` checks the free linear orbit's ring edges
FREE_PHASES = 64
FORCED_KIND = "static equilibrium + linear forced response"


def _held_out_of_contact(system: RotorSystem, start: StaticStart, q_static) -> bool:
    """The faces hold the constant load (none at its limit), the ring is out of contact, and its position equals the
    locked linear static state's within :data:`SAME_RING_POSITION` of the clearance."""
    if system.support is None:
        return True
    d = system.support.relative_map(system.n)[:2] @ (start.q_m - q_static)
    return (not any(start.at_limit) and start.let_down_steps == 0 and not np.any(start.contact_force[:2])
            and float(np.hypot(*d)) <= SAME_RING_POSITION * system.support.law.clearance_m)


def _free_orbit_inside(system: RotorSystem, t0: float):
    """``(q0, v0)`` of the linear periodic solution with the loose support free (no contact) at ``t0`` (s), where the
    support has no friction (every end face's ``μN`` zero: nothing holds the ring, so the locked state is not a state
    of the rotor) and both ring edges stay inside the clearance at :data:`FREE_PHASES` phases of a revolution; else
    None. Such an orbit touches nothing, so it is the periodic orbit of the nonlinear rotor (up to the scheme's
    step). Measured on the first rotor of rotor/periodic/jeffcott_scene.random_family(2536238657) at 1 907.9 rpm
    (the free orbit at 0.8 of the clearance): from the locked start the transient found no orbit in 4 000
    revolutions (it met the ring and an isolated contact branch's motion), so ``ringcontact branch`` down from there
    had no start."""
    from rotor.dynamics.initial import linear_initial_state

    sup = system.support
    omega = float(system.force.omega_rad_s)
    if sup is None or np.any(np.asarray(sup.faces()[1]) > 0.0) or omega <= 0.0:
        return None
    B = sup.relative_map(system.n)
    period = 2.0 * np.pi / omega
    u = np.array([B @ linear_initial_state(system, t0 + k * period / FREE_PHASES, lock_support=False)[0]
                  for k in range(FREE_PHASES)])
    radii = np.hypot(u[:, 0], u[:, 1]) if sup.tilt_ignored else np.array(cons.edge_offsets(u, sup.width_m))
    if np.max(radii) >= sup.law.clearance_m:
        return None
    return linear_initial_state(system, t0, lock_support=False)


def periodic_start(system: RotorSystem, model, t0: float = 0.0) -> tuple:
    """``(q0, v0, record)``: the start of a transient that seeks a periodic orbit (orbit, branch,
    ``simulate --steady``); ``model`` the assembled model of ``system`` (its gravity and ``[[static_loads]]``,
    :mod:`rotor.model.static_load`).

    Under gravity or ``[[static_loads]]`` that the end faces cannot hold out of contact (a face slips, the ring rests
    on its bore) it is the static equilibrium with the linear forced response about it (:func:`forced_start`), not
    the ring floating in the middle of its clearance. Otherwise it is the linear periodic solution
    (:func:`rotor.dynamics.initial.linear_initial_state`), as before, for two measured reasons. Where the faces hold
    the constant load out of contact at the locked state's ring position (every bundled scene), that state is the
    equilibrium up to the coupling's cubic remainder, and on a continuum of orbits held by friction the member a
    transient settles on depends on the start (paper-table4-inertial at 10 500 rpm: the equilibrium with its cubic
    remainder, 1.6e-7 rad away in one joint rotation, settles on a member whose harmonics differ by 2.6e-3 from the
    published one). With neither, on a frictionless ring (no face holds anything) whose free linear orbit stays inside
    the clearance, that free orbit (:func:`_free_orbit_inside`). Where only the misalignment offset loads faces that
    cannot hold it (paper-table4 with mu = 0 at
    10 500 rpm: the ring pressed on its bore), the linear start reaches the published unstable orbit in 1 185
    revolutions and the equilibrium start finds none in 4 000. Where no equilibrium is found, the linear start, said
    so. ``record``: ``kind`` (:data:`LINEAR_KIND` or :data:`FORCED_KIND`), ``why``, and the equilibrium's fields
    (:func:`start_record`)."""
    from rotor.dynamics.initial import linear_initial_state
    from rotor.model.static_load import static_load

    q_lin, v_lin = linear_initial_state(system, t0)
    if not np.any(static_load(model)):
        free = _free_orbit_inside(system, t0)
        if free is not None:
            return (*free, {"kind": FREE_KIND, "why": "a frictionless ring whose free linear orbit stays inside its "
                            "clearance: that orbit touches nothing, so it is the orbit"})
        return q_lin, v_lin, {"kind": LINEAR_KIND, "why": "no gravity or static load"}
    try:
        start = static_equilibrium(system)
    except (ConvergenceError, OutsideDomainError) as exc:
        return q_lin, v_lin, {"kind": LINEAR_KIND, "why": "no static equilibrium found: " + " ".join(str(exc).split())}
    q_h, v_h = linear_initial_state(system, t0, static=False)
    rec = start_record(system, start)
    if _held_out_of_contact(system, start, q_lin - q_h):
        return q_lin, v_lin, {**rec, "kind": LINEAR_KIND, "why": "the faces hold the static load with the ring out "
                              "of contact: the locked linear static state is the equilibrium"}
    return start.q_m + q_h, v_h, {**rec, "kind": FORCED_KIND, "why": "a face slips or the ring touches its bore "
                                  "under gravity or a static load"}


def start_record(system: RotorSystem, start: StaticStart | None) -> dict:
    """The JSON field ``start`` of a run: ``kind`` (``static equilibrium`` or ``rest``: the misalignment offset,
    no load carried) and, from the equilibrium, the loose bearing's static deflection ``bearing_deflection_m``
    ((y, z), m), the ring's contact force ``contact_force_N`` (N), the faces held at their friction limit
    ``faces_at_friction_limit``, ``newton_iterations``, the largest force residual ``residual_N`` and
    ``let_down_steps`` (0: found by Newton from the held faces; else the time steps the rotor was let down first)."""
    if start is None:
        return {"kind": "rest"}
    out = {"kind": "static equilibrium", "newton_iterations": int(start.iterations),
           "residual_N": float(start.residual_N), "let_down_steps": int(start.let_down_steps)}
    if system.support is not None:
        y, z = system.support.bearing_dofs[:2]
        out.update(bearing_deflection_m=[float(start.q_m[y]), float(start.q_m[z])],
                   contact_force_N=float(np.hypot(*start.contact_force[:2])),
                   faces_at_friction_limit=list(start.at_limit))
    return out

"""The member of a friction-held family of orbits farthest from slipping and from the bore.

A ring whose end faces stick through the whole period makes its orbits a continuum (multipliers exactly 1,
:mod:`rotor.periodic.floquet`): every offset at which the faces could have stuck gives an orbit. Measured on
Table 4 (``paper-table4``, 2 240 steps per revolution, friction by projection, 2 420 rpm): the continuum is
affine to second order (a member moved by 1e-3 of its scale along a right null vector of ``M − I`` maps onto
itself to 3e-9, by 1e-2 to 2e-7 at 2 389.5 rpm; the end-face forces change by a constant in time, their second
difference 4e-5 N, and the part of the change varying along the period is 2e-4 to 3e-3 of it over 16 seeded
speeds of the stuck stretch, tests/rotor/periodic/test_family_centre.py). So along the family the face forces and the ring's edge offsets are ``f(t) + K c`` with ``K``
constant, and each member is held only while ``|f_k(t) + K_k c| ≤ μN`` at both faces and the edges stay inside
the clearance; the corrector closes the small curvature after the move.

Continuation keeping the previous member's offsets (the phase rows of :func:`rotor.periodic.corrector.neutral_rows`)
walks the branch into the place where one face's holding force reaches μN: there the map has a kink, Newton's
basin is tiny, and each step needs a restart (20 of the 21 restarts of the Table 4 branch by projection,
reports/published/perf-branch-switches-projection.md). :func:`centred` moves the point instead to the member
that minimises the largest of ``|f_k(t) + K_k c| / μN`` and ``|r_e(t) + E_e c| / δ0`` over the period (faces
``k``, edges ``e``, ``δ0`` the radial clearance): near the Chebyshev centre of the set of members (:func:`smoothed_offset`, the minimiser of a smooth upper
bound: its largest margin is 4.6e-4 to 2.1e-3 above the exact min-max's, :func:`chebyshev_offset`, over 16
seeded speeds, and it keeps off every near-top sample rather than balancing the top ones; the exact centre
took 5 restarts instead of 3 on the 320-steps stretch past Table 4's family end, test_family_centre.py's slow
test; the affine model's largest margin matches the corrected member's to 3e-5 over 12 seeded speeds), in which the
next steps stay stuck as long as the set is not empty. The member is one of the family like any other (the same
1X response where the stuck rotor is linear); the branch says which one it reports.
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import minimize

from rotor.periodic.branch_types import NEUTRAL_TOL, ContinuationOptions, Evaluator
from rotor.periodic.corrector import correct, neutral_rows
from rotor.periodic.period_flow import record

#: samples of the period the margins are read on (every this many steps)
RECORD_EVERY = 8
#: step along each family direction (scaled state) of the margins' finite differences; exact for the affine family
FAMILY_STEP = 1e-3
#: exponent of the smooth maximum minimised (the p-norm of the margins over the period)
P_NORM = 32.0
#: samples whose ratio is within this fraction of the largest enter the exact min-max first
NEAR_TOP = 0.5
#: a move is made only where it lowers the largest margin by at least this much
MIN_GAIN = 1e-3
#: fractions of the move tried when the corrector does not close the full one (the family is affine only
#: while the ring does not touch the bore)
FRACTIONS = (1.0, 0.5, 0.25)


def margins(ev: Evaluator, x, lam: float):
    """``(values (T, m, 2), limits (m,), stuck)``: along the period of the map at the state ``x`` (SI) and the
    parameter ``lam``, sampled every :data:`RECORD_EVERY` steps, the end-face friction forces (N) and the ring's
    two edge offsets from the bore's centre (m), their limits (μN per face, the clearance per edge), and
    whether every face sticks at every sample."""
    fl = ev.flow(lam)
    tr = record(fl, x, 0.0, ev.pb.n_steps, ev.modes0, RECORD_EVERY)
    sup = fl.system.support
    _, limits, n_faces = sup.faces()
    u = tr.q @ sup.relative_map(tr.q.shape[1]).T
    h = 0.5 * sup.width_m
    edges = np.stack([np.stack([u[:, 0] + h * u[:, 3], u[:, 1] - h * u[:, 2]], -1),
                      np.stack([u[:, 0] - h * u[:, 3], u[:, 1] + h * u[:, 2]], -1)], 1)
    values = np.concatenate([tr.face_force[:, :n_faces, :], edges], 1)
    lim = np.concatenate([limits[:n_faces], [sup.law.clearance_m] * 2])
    stuck = bool(np.all(tr.modes[:, :n_faces] == 1))
    return values, lim, stuck


def largest(values, lim, K, c) -> float:
    """The largest margin ratio ``max |v(t) + K c| / limit`` over the samples and the faces and edges."""
    return float(_ratios(values, lim, K, np.asarray(c, dtype=float))[0].max())


def _ratios(values, lim, K, c):
    """``(r (T, m), w (T, m, 2))``: each sample's margin ratio ``|v + K c| / limit`` and its scaled vector."""
    w = (values + np.einsum("mak,k->ma", K, c)[None]) / lim[None, :, None]
    return np.sqrt((w ** 2).sum(-1)), w


def smoothed_offset(values, lim, K) -> np.ndarray:
    """The family coordinate ``c`` minimising the smooth upper bound ``log ‖ratio‖_p`` of :func:`largest`
    (``p`` :data:`P_NORM`, BFGS from ``c = 0``): the member :func:`centred` moves to."""
    def merit(c):
        w = (values + np.einsum("mak,k->ma", K, c)[None]) / lim[None, :, None]
        m2 = (w ** 2).sum(-1)          # not _ratios' sqrt squared: the round-off moves the slow branch's restarts
        top = m2.max()
        weight = (m2 / top) ** (P_NORM / 2.0)
        g = np.einsum("tm,tma,mak->k", weight / m2.clip(1e-300), w / lim[None, :, None], K) * 2.0 / weight.sum()
        return 0.5 * np.log(top) + np.log(weight.mean()) / P_NORM, g / 2.0
    return minimize(merit, np.zeros(K.shape[-1]), jac=True, method="BFGS").x


def chebyshev_offset(values, lim, K) -> np.ndarray:
    """The family coordinate ``c`` minimising :func:`largest` (a convex min-max of Euclidean norms).

    Started at the smooth bound's minimiser (:func:`smoothed_offset`), whose largest ratio sits up to 2.1e-3
    above the min-max's on Table 4's stuck stretch, and finished exactly in epigraph form: minimise ``t`` subject to
    ``t ≥ |v_i + K_i c| / limit_i`` (SLSQP) over the samples within :data:`NEAR_TOP` of the largest ratio, those
    grown until no other sample exceeds ``t``. Returns the start where the finish does not lower the largest."""
    c0 = smoothed_offset(values, lim, K)
    r0, _ = _ratios(values, lim, K, c0)
    keep = r0 >= NEAR_TOP * r0.max()
    best, best_top = c0, float(r0.max())
    for _ in range(4):
        idx = np.nonzero(keep)

        def gap(z):
            r, _ = _ratios(values, lim, K, z[:-1])
            return z[-1] - r[idx]

        def gap_jac(z):
            r, w = _ratios(values, lim, K, z[:-1])
            dr = np.einsum("tma,mak->tmk", w / r.clip(1e-300)[..., None] / lim[None, :, None], K)[idx]
            return np.hstack([-dr, np.ones((dr.shape[0], 1))])

        got = minimize(lambda z: z[-1], np.append(best, best_top), jac=lambda z: np.eye(len(z))[-1],
                       method="SLSQP", constraints=[{"type": "ineq", "fun": gap, "jac": gap_jac}],
                       options={"ftol": 1e-12, "maxiter": 200})
        r, _ = _ratios(values, lim, K, got.x[:-1])
        if r.max() < best_top:
            best, best_top = got.x[:-1], float(r.max())
        over = r > got.x[-1] + 1e-9
        if not (over & ~keep).any():
            break
        keep |= over
    return best


def centred(ev: Evaluator, y, J, opts: ContinuationOptions):
    """The corrected point ``(y, J, M, iterations, residual)`` of the member of ``y``'s friction-held family
    (scaled ``y = (x/s, λ/λ_s)``, ``J`` its bordered Jacobian) farthest from slipping and from the bore, or
    None where ``y`` is no such family's member (no neutral direction, or a face slips in the period) or no
    move lowers the largest margin by :data:`MIN_GAIN`.

    The family's directions are the right null vectors of the scaled ``M − I`` (singular values below
    :data:`rotor.periodic.branch_types.NEUTRAL_TOL` of the largest); the margins' change along each is one
    finite difference (:data:`FAMILY_STEP`); the move to :func:`smoothed_offset` is then closed by the corrector
    at the fixed parameter with the moved member's levels as phase rows (the move, then half and a quarter
    of it, :data:`FRACTIONS`). ``ev.modes0`` is unchanged."""
    _, sv, vt = np.linalg.svd(J[:, :-1])
    null = sv < NEUTRAL_TOL * sv[0]
    if not null.any():
        return None
    V = vt[null].T
    x, lam = y[:-1] * ev.s, y[-1] * ev.ls
    values, lim, stuck = margins(ev, x, lam)
    if not stuck:
        return None
    K = np.empty(values.shape[1:] + (V.shape[1],))
    for j in range(V.shape[1]):
        moved, _, _ = margins(ev, x + FAMILY_STEP * V[:, j] * ev.s, lam)
        K[..., j] = (moved - values).mean(axis=0) / FAMILY_STEP
    c = smoothed_offset(values, lim, K)
    if largest(values, lim, K, c) > largest(values, lim, K, 0.0 * c) - MIN_GAIN:
        return None
    fixed = np.zeros(len(y))
    fixed[-1] = 1.0
    rows = neutral_rows(J)
    for alpha in FRACTIONS:
        y_c = y.copy()
        y_c[:-1] += alpha * (V @ c)
        got = correct(ev, y_c, fixed, opts, rows, y_c)
        if got is not None:
            return got
    return None

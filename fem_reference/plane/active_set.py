"""The contact point solved on the whole sparse system, one factorisation per active set: fine meshes.

:meth:`fem_reference.plane.solve.ContactModel.solve` condenses the contact onto its multipliers: the
compliance ``D K⁻¹ Dᵀ`` of every candidate node, one back-substitution per node. On the fine nested levels of
the independent P1 reference (:mod:`fem_reference.plane.uniform_reference`) that is 600-1 300
back-substitutions per penetration and level, about 5 min at 253k DOFs, growing eightfold a level.

Here the same frictionless conditions are solved by the primal-dual active-set method (Hintermüller, Ito &
Kunisch 2002, SIAM J. Optim. 13) on the uncondensed system: for a guessed active set ``S`` (the nodes in
contact), the bordered matrix

    [[K_ff, s·D_Sᵀ], [s·D_S, 0]]

(``K_ff`` the free stiffness, bordered by any coupling constraints as in
:class:`~fem_reference.plane.elasticity.ElasticSystem`; ``s`` scales the gap rows to the stiffness) is
factorised once and gives the displacement and the multipliers with zero weighted gap on ``S``. The next set
keeps the nodes of ``S`` whose multiplier is positive and adds the nodes outside ``S`` whose gap is negative;
when the set repeats, the point satisfies ``λ ≥ 0, g̃ ≥ 0, λ·g̃ = 0`` to round-off (checked, as the condensed
solve does). A good first set (the coarser nested level's arc) needs 1-4 factorisations (measured; from the rigid
overlap up to 27). If the sets cycle, the condensed solve answers instead.

The two solves have the same discrete solution; their forces agree to rounding (tests/fem_reference/plane/
test_active_set.py).
"""
from __future__ import annotations

import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from contact.errors import ConvergenceError
from fem_reference.plane.contact_solver import ContactSolution
from fem_reference.plane.elasticity import refined_solve
from fem_reference.plane.solve import ContactModel, contact_solution

MAX_ACTIVE_SET_CHANGES = 30


def _bordered_free(model: ContactModel) -> sp.csr_matrix:
    """The free stiffness, bordered by the model's coupling constraints as its factorised system is."""
    sysm = model.system
    Kff = sysm.K[sysm.free][:, sysm.free]
    if sysm.Q is None:
        return Kff.tocsr()
    Qf = sp.csr_matrix(np.asarray(sysm.Q)[sysm.free] * sysm.q_scale)
    m = Qf.shape[1]
    return sp.bmat([[Kff, Qf], [Qf.T, sp.csr_matrix((m, m))]]).tocsr()


def _solve_set(Kb: sp.csr_matrix, Ds: sp.csr_matrix, rhs_gap: np.ndarray, scale: float, order):
    """Displacement increment (free DOFs and constraint multipliers) and contact multipliers [Pa] with zero
    weighted gap on the set's rows ``Ds`` (``Ds u = rhs_gap``); ``order``: the stiffness factor's elimination
    order (the set's rows after it), or None for SuperLU's minimum degree."""
    n = Kb.shape[0]
    k = Ds.shape[0]
    if k == 0:
        return np.zeros(n), np.zeros(0)
    Dp = sp.csr_matrix((Ds.data, Ds.indices, Ds.indptr), shape=(k, n)) * scale
    M = sp.bmat([[Kb, Dp.T], [Dp, None]], format="csr")
    rhs = np.concatenate([np.zeros(n), rhs_gap * scale])
    if order is None:
        lu = spla.splu(M.tocsc(), permc_spec="MMD_AT_PLUS_A", options={"SymmetricMode": True})
        x = lu.solve(rhs)
    else:
        p = np.concatenate([order, np.arange(n, n + k)])
        lu = spla.splu(M[p][:, p].tocsc(), permc_spec="NATURAL", options={"SymmetricMode": True})
        x = refined_solve(lu, p, M, rhs)
    return x[:n], -x[n:] * scale


def solve_active_set(model: ContactModel, penetration_m: float, *, edge_phi_rad: float | None = None,
                     tol: float = 1e-10) -> ContactSolution:
    """One point at penetration ``Δr`` [m] by the primal-dual active-set method on the sparse system (module
    docstring).

    Parameters
    ----------
    model : ContactModel
        The meshed scene (its factorised stiffness gives the drive's response only).
    penetration_m : float
        ``Δr = t − δ0`` [m].
    edge_phi_rad : float, optional
        The first active set: the slave nodes within this angle of the load axis [rad] (e.g. a coarser
        level's contact half-angle). Default: the nodes the rigidly offset circles overlap at.
    tol : float
        Relative KKT tolerance, as :func:`fem_reference.plane.contact_solver.solve_lcp`'s.

    Raises
    ------
    InputError, ConvergenceError
        As :meth:`ContactModel.solve`.
    """
    t0 = time.perf_counter()
    sysm = model.system
    mo, u0, b_all, phi = model.gaps(penetration_m)
    active = b_all < 0 if edge_phi_rad is None else phi <= edge_phi_rad + 1e-12
    Kb = _bordered_free(model)
    Df = mo.D[:, sysm.free].tocsr()
    scale = float(np.mean(np.abs(Kb.diagonal())) / max(abs(Df).max(), 1e-300))
    gap_tol = tol * max(np.abs(b_all).max(), 1e-300)
    seen = set()
    for it in range(1, MAX_ACTIVE_SET_CHANGES + 1):
        idx = np.flatnonzero(active)
        x, lam_s = _solve_set(Kb, Df[idx], -b_all[idx], scale, sysm.order)
        lam = np.zeros(len(phi))
        lam[idx] = lam_s
        u = u0.copy()
        u[sysm.free] += x[: len(sysm.free)]
        g = mo.G + mo.D @ u
        new = (active & (lam > 0)) | (~active & (g < -gap_tol))
        if np.array_equal(new, active):
            return _checked(model, penetration_m, mo.D, lam, g, u, it, t0, tol, b_all)
        key = new.tobytes()
        if key in seen:
            break
        seen.add(key)
        active = new
    return model.solve(penetration_m, tol=tol)


def _checked(model, penetration_m, D, lam, g, u, iterations, t0, tol, b_all) -> ContactSolution:
    """The KKT residual of :func:`~fem_reference.plane.contact_solver.solve_lcp`, refused above ``tol``."""
    scale_l = max(lam.max(), 1e-300)
    scale_g = max(np.abs(b_all).max(), 1e-300)
    res = max(max(-lam.min(), 0) / scale_l, max(-g.min(), 0) / scale_g, abs(lam @ g) / (scale_l * scale_g * len(lam)))
    if res > tol:
        raise ConvergenceError(f"contact active set: KKT residual {res:.3e} > tol {tol:.1e} after {iterations} sets")
    return contact_solution(model, penetration_m, D, lam, u, iterations=iterations, method="active-set",
                            kkt_residual=res, t0=t0)

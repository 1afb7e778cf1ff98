"""Linear elasticity on a :class:`~fem_reference.plane.mesh.RingMesh` with scikit-fem (2D, SI).

Plane strain or plane stress (per unit thickness, N/m), a different material per body, Dirichlet
conditions on circles, pressure loads and the Dirichlet-condensed, LU-factorised system
(:class:`ElasticSystem`) that the contact solver reuses across a whole sweep: the stiffness does
not depend on the imposed displacement, so one factorisation per mesh serves every point.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import Basis, BilinearForm, ElementTriP1, ElementTriP2, ElementVector, FacetBasis, LinearForm
from skfem.helpers import ddot, dot, sym_grad, trace

from contact.errors import InputError
from fem_reference.plane.mesh import BEARING, SUPPORT, RingMesh, facets_on_circle
from fem_reference.plane.ordering import nested_dissection


@BilinearForm
def _elasticity(u, v, w):
    eps_u, eps_v = sym_grad(u), sym_grad(v)
    return w.lam * trace(eps_u) * trace(eps_v) + 2.0 * w.mu * ddot(eps_u, eps_v)


def vector_basis(rmesh: RingMesh) -> Basis:
    """Vector P1/P2 basis on the whole mesh (both bodies)."""
    elem = ElementTriP1() if rmesh.order == 1 else ElementTriP2()
    intorder = 2 * rmesh.order
    return Basis(rmesh.mesh, ElementVector(elem), intorder=intorder)


def stiffness(rmesh: RingMesh, basis: Basis, plane: str) -> sp.csr_matrix:
    """Global stiffness [N/m per m of thickness] with each body's own Lamé constants."""
    lam = np.empty(rmesh.mesh.nelements)
    mu = np.empty(rmesh.mesh.nelements)
    for b, mat in ((BEARING, rmesh.rings.bearing), (SUPPORT, rmesh.rings.support)):
        lam[rmesh.body == b], mu[rmesh.body == b] = mat.lame(plane)
    nq = basis.X.shape[1]
    return _elasticity.assemble(basis, lam=np.repeat(lam[:, None], nq, axis=1),
                                mu=np.repeat(mu[:, None], nq, axis=1)).tocsr()


def circle_dofs(rmesh: RingMesh, basis: Basis, radius_m: float) -> np.ndarray:
    """All DOFs (x and y, corners and mid-sides) on the boundary circle ``radius_m``, shape (2, n)."""
    facets = facets_on_circle(rmesh.mesh, radius_m)
    if len(facets) == 0:
        raise InputError(f"radius_m = {radius_m:g} m: no boundary facets on this circle")
    d = basis.get_dofs(facets=facets)
    return np.vstack([d.all("u^1"), d.all("u^2")])


def symmetry_dofs(rmesh: RingMesh, basis: Basis) -> np.ndarray:
    """x-DOFs on the symmetry line x = 0 (u_x = 0 there)."""
    from fem_reference.plane.mesh import facets_on_symmetry_line

    d = basis.get_dofs(facets=facets_on_symmetry_line(rmesh.mesh))
    return d.all("u^1")


def pressure_load(rmesh: RingMesh, basis: Basis, radius_m: float, pressure_pa: float) -> np.ndarray:
    """Load vector of a uniform pressure on the boundary circle ``radius_m`` (pushes into the body)."""
    facets = facets_on_circle(rmesh.mesh, radius_m)
    fb = FacetBasis(rmesh.mesh, basis.elem, facets=facets, intorder=2 * rmesh.order + 2)

    @LinearForm
    def load(v, w):
        return -pressure_pa * dot(w.n, v)

    return load.assemble(fb)


def circle_mean_weights(rmesh: RingMesh, basis: Basis, radius_m: float, body: int) -> np.ndarray:
    """Weights ``w`` with ``w @ u`` = mean u_y over the circle ``radius_m`` of ``body`` (arc-length mean)."""
    facets = facets_on_circle(rmesh.mesh, radius_m, element_mask=rmesh.body == body)
    fb = FacetBasis(rmesh.mesh, basis.elem, facets=facets, intorder=2 * rmesh.order + 2)

    @LinearForm
    def ey(v, w):
        return v[1]

    w = ey.assemble(fb)
    return w / w.sum()


def body_mean_weights(rmesh: RingMesh, basis: Basis, body: int) -> np.ndarray:
    """Weights ``w`` with ``w @ u`` = area-mean u_y of ``body`` (its centroid's displacement)."""
    b = Basis(rmesh.mesh, basis.elem, elements=np.flatnonzero(rmesh.body == body), intorder=2 * rmesh.order)

    @LinearForm
    def ey(v, w):
        return v[1]

    w = ey.assemble(b)
    return w / w.sum()


@dataclass
class ElasticSystem:
    """Dirichlet-condensed, factorised stiffness of one mesh and one plane assumption.

    Optional linear constraints ``Qᵀ u = c`` (one column of ``Q`` per constraint, e.g. a
    distributing coupling: mean displacement of a surface prescribed) are added by bordering:
    ``[[K_ff, Q_f], [Q_fᵀ, 0]]`` is factorised instead of ``K_ff``.

    ``solve(rhs, u_dirichlet, c)`` returns the full displacement vector.
    """

    K: sp.csr_matrix
    dirichlet: np.ndarray   # sorted DOF indices with prescribed values
    free: np.ndarray        # the other DOFs
    lu: object              # scipy SuperLU of the (bordered) free-DOF matrix
    Q: np.ndarray | None = None   # (n, m) constraint columns or None
    q_scale: float = 1.0          # the bordered rows hold Q·q_scale
    order: np.ndarray | None = None   # the factor's elimination order of the bordered unknowns (None: SuperLU's)
    bordered: sp.csr_matrix | None = None   # the factorised matrix, kept for iterative refinement when ordered

    @classmethod
    def build(cls, K: sp.csr_matrix, dirichlet: np.ndarray, Q: np.ndarray | None = None,
              points: np.ndarray | None = None) -> "ElasticSystem":
        """Condense and factorise. ``points`` (2, n): every DOF's coordinates [m]; given, the factor is ordered
        by :func:`fem_reference.plane.ordering.nested_dissection` (the fine reference levels), else by
        SuperLU's minimum degree."""
        dirichlet = np.unique(np.asarray(dirichlet, dtype=np.int64))
        free = np.setdiff1d(np.arange(K.shape[0]), dirichlet)
        Kff = K[free][:, free]
        scale = 1.0
        if Q is not None:
            # scale the constraint rows to the stiffness so the bordered pivots stay well sized
            scale = float(np.mean(np.abs(Kff.diagonal())) / np.abs(np.asarray(Q)[free]).max())
            Qf = sp.csr_matrix(np.asarray(Q)[free] * scale)
            m = Qf.shape[1]
            Kff = sp.bmat([[Kff, Qf], [Qf.T, sp.csr_matrix((m, m))]]).tocsr()
        order, bordered = None, None
        if points is None:
            # symmetric ordering: half the fill of COLAMD on the plate scene (measured, 58k DOFs)
            lu = spla.splu(Kff.tocsc(), permc_spec="MMD_AT_PLUS_A", options={"SymmetricMode": True})
        else:
            nf = len(free)
            order = np.concatenate([nested_dissection(Kff[:nf, :nf], np.asarray(points)[:, free]),
                                    np.arange(nf, Kff.shape[0])])
            lu = spla.splu(Kff.tocsr()[order][:, order].tocsc(), permc_spec="NATURAL", options={"SymmetricMode": True})
            bordered = Kff.tocsr()
        diag = lu.U.diagonal()
        if not np.all(np.isfinite(diag)) or np.min(np.abs(diag)) < 1e-12 * np.max(np.abs(diag)):
            from contact.errors import ConvergenceError

            raise ConvergenceError("elastic stiffness is singular (a body is not held: check the "
                                   "boundary-condition scene)")
        return cls(K=K, dirichlet=dirichlet, free=free, lu=lu, Q=None if Q is None else np.asarray(Q),
                   q_scale=scale, order=order, bordered=bordered)

    @property
    def ndofs(self) -> int:
        return self.K.shape[0]

    @property
    def n_constraints(self) -> int:
        return 0 if self.Q is None else self.Q.shape[1]

    def solve_free(self, b: np.ndarray, c: np.ndarray | None = None) -> np.ndarray:
        """Free-DOF solution for free-DOF right-hand side ``b`` (n_free,), constraint values ``c``."""
        m = self.n_constraints
        if m:
            b = np.concatenate([b, np.zeros(m) if c is None else np.asarray(c, dtype=float) * self.q_scale])
        if self.order is None:
            return self.lu.solve(np.ascontiguousarray(b))[: len(self.free)]
        return refined_solve(self.lu, self.order, self.bordered, b)[: len(self.free)]

    def solve(self, rhs: np.ndarray, u_dirichlet: np.ndarray | None = None,
              c: np.ndarray | None = None) -> np.ndarray:
        """Full displacement for load ``rhs`` (n,), Dirichlet values (n,) and constraint values (m,)."""
        rhs = np.asarray(rhs, dtype=float)
        u = np.zeros_like(rhs)
        r = rhs[self.free]
        if u_dirichlet is not None:
            ud = np.asarray(u_dirichlet, dtype=float)[self.dirichlet]
            u[self.dirichlet] = ud
            r = r - self.K[self.free][:, self.dirichlet] @ ud
            if self.Q is not None and c is not None:
                c = np.asarray(c, dtype=float) - self.Q[self.dirichlet].T @ ud
        u[self.free] = self.solve_free(r, c)
        return u


def refined_solve(lu, order: np.ndarray, matrix: sp.csr_matrix, b: np.ndarray) -> np.ndarray:
    """``matrix⁻¹ b`` from the factor ``lu`` of ``matrix[order][:, order]``, with one step of iterative refinement
    (the residual solved again): the nested-dissection factor's pivots are not chosen for stability, and on a coupled
    drive its multipliers differed from the minimum-degree factor's by 1.5e-9 of their largest without it."""
    x = np.empty(len(b))
    x[order] = lu.solve(np.ascontiguousarray(b[order]))
    r = b - matrix @ x
    dx = np.empty(len(b))
    dx[order] = lu.solve(np.ascontiguousarray(r[order]))
    return x + dx

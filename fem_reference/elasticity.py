"""Linear elasticity on a :class:`~fem_reference.mesh.RingMesh` with scikit-fem (2D, SI).

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
from fem_reference.mesh import BEARING, SUPPORT, RingMesh, facets_on_circle


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
    from fem_reference.mesh import facets_on_symmetry_line

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


@dataclass
class ElasticSystem:
    """Dirichlet-condensed, factorised stiffness of one mesh and one plane assumption.

    ``solve(rhs_full, u_dirichlet)`` returns the full displacement vector for a full-size load
    vector and prescribed values on the Dirichlet DOFs (zeros elsewhere).
    """

    K: sp.csr_matrix
    dirichlet: np.ndarray   # sorted DOF indices with prescribed values
    free: np.ndarray        # the other DOFs
    lu: object              # scipy SuperLU of K[free][:, free]

    @classmethod
    def build(cls, K: sp.csr_matrix, dirichlet: np.ndarray) -> "ElasticSystem":
        dirichlet = np.unique(np.asarray(dirichlet, dtype=np.int64))
        free = np.setdiff1d(np.arange(K.shape[0]), dirichlet)
        Kff = K[free][:, free].tocsc()
        lu = spla.splu(Kff, permc_spec="COLAMD")
        diag = lu.U.diagonal()
        if not np.all(np.isfinite(diag)) or np.min(np.abs(diag)) < 1e-12 * np.max(np.abs(diag)):
            from contact.errors import ConvergenceError

            raise ConvergenceError("elastic stiffness is singular (a body is not held: check the "
                                   "boundary-condition scene)")
        return cls(K=K, dirichlet=dirichlet, free=free, lu=lu)

    @property
    def ndofs(self) -> int:
        return self.K.shape[0]

    def solve(self, rhs: np.ndarray, u_dirichlet: np.ndarray | None = None) -> np.ndarray:
        """Full displacement for load ``rhs`` (n,) or (n, k) and Dirichlet values (same shape)."""
        rhs = np.asarray(rhs, dtype=float)
        u = np.zeros_like(rhs)
        r = rhs[self.free]
        if u_dirichlet is not None:
            ud = np.asarray(u_dirichlet, dtype=float)[self.dirichlet]
            u[self.dirichlet] = ud
            r = r - self.K[self.free][:, self.dirichlet] @ ud
        u[self.free] = self.lu.solve(np.asarray(r, order="F") if r.ndim == 2 else r)
        return u

"""A posteriori error estimate of a 2D contact solution: stress recovery (Zienkiewicz & Zhu 1987).

The finite-element stress ``σ_h`` of a P1/P2 displacement is discontinuous between elements. Its L2
projection onto the continuous scalar space of the same order, component by component and body by
body (the two rings share no node, so a material jump is never smoothed over), is the recovered stress
``σ*`` (Zienkiewicz & Zhu 1987, "A simple error estimator and adaptive procedure for practical
engineering analysis", Int. J. Numer. Methods Eng. 24). The indicator of element K is the energy
norm of the difference,

    η_K² = ∫_K (σ* − σ_h) : C⁻¹ (σ* − σ_h) dA          [J/m: energy per metre of thickness × 2]

with the element's own compliance ``C⁻¹`` (plane strain or stress Lamé constants), and the estimated
relative energy-norm error is ``sqrt(Σ η_K² / (uᵀ K u))``. Where the displacement is singular (the end
of a clamp, the contact arc's edge) the recovered stress is not better than ``σ_h`` and the estimate
only ranks elements: :mod:`fem_reference.plane.adapt` uses it to say where to refine, and takes the
force's error bar from the sequence of meshes it drives, not from ``η``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse.linalg as spla
from skfem import Basis, BilinearForm, ElementTriP1, ElementTriP2, LinearForm

from fem_reference.plane.mesh import BEARING, SUPPORT


@BilinearForm
def _mass(u, v, w):
    return u * v


@LinearForm
def _load(v, w):
    return w.s * v


@dataclass(frozen=True)
class ErrorEstimate:
    """Recovery-based error estimate of one solution (per metre of thickness).

    Attributes
    ----------
    eta : numpy.ndarray
        η_K per element [sqrt(J/m)]: the energy norm of ``σ* − σ_h`` on it (see module docstring).
    energy : float
        ``uᵀ K u`` [J/m], the squared energy norm of the solution.
    rel_error : float
        ``sqrt(Σ η_K² / uᵀ K u)`` [-], the estimated relative energy-norm error.
    """

    eta: np.ndarray
    energy: float
    rel_error: float


def _lame_per_element(rmesh, plane: str) -> tuple[np.ndarray, np.ndarray]:
    lam = np.empty(rmesh.mesh.nelements)
    mu = np.empty(rmesh.mesh.nelements)
    for b, mat in ((BEARING, rmesh.rings.bearing), (SUPPORT, rmesh.rings.support)):
        lam[rmesh.body == b], mu[rmesh.body == b] = mat.lame(plane)
    return lam[:, None], mu[:, None]


def fe_stress(basis, u: np.ndarray, lam: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """The finite-element stress at the basis' quadrature points, shape (3, n_el, n_q) [Pa]: xx, yy, xy."""
    g = basis.interpolate(u).grad                      # (2, 2, n_el, n_q): d u_i / d x_j
    exx, eyy, exy = g[0, 0], g[1, 1], 0.5 * (g[0, 1] + g[1, 0])
    tr = exx + eyy
    return np.stack([lam * tr + 2 * mu * exx, lam * tr + 2 * mu * eyy, 2 * mu * exy])


def recover(model, u: np.ndarray) -> ErrorEstimate:
    """The recovery-based estimate (Zienkiewicz & Zhu 1987) of displacement ``u`` [m] on ``model``.

    Parameters
    ----------
    model : fem_reference.plane.solve.ContactModel
        The mesh, basis, stiffness and scene the solution belongs to.
    u : numpy.ndarray
        The full displacement vector [m] (``ContactSolution.u``).
    """
    rmesh, basis = model.rmesh, model.basis
    lam, mu = _lame_per_element(rmesh, model.scene.plane)
    sig = fe_stress(basis, u, lam, mu)
    elem = ElementTriP1() if rmesh.order == 1 else ElementTriP2()
    sb = Basis(rmesh.mesh, elem, quadrature=basis.quadrature)      # the same quadrature points as σ_h
    lu = spla.splu(_mass.assemble(sb).tocsc())
    rec = np.stack([np.asarray(sb.interpolate(lu.solve(_load.assemble(sb, s=sig[c])))) for c in range(3)])
    d = rec - sig                                      # (3, n_el, n_q)
    # C⁻¹ in the plane: ε = (σ − λ/(2(λ+μ)) tr σ I) / (2μ), for both plane strain and plane stress Lamé pairs
    tr = d[0] + d[1]
    dd = d[0] ** 2 + d[1] ** 2 + 2 * d[2] ** 2
    dens = (dd - lam / (2 * (lam + mu)) * tr ** 2) / (2 * mu)
    eta2 = np.sum(dens * basis.dx, axis=1)
    energy = float(u @ (model.system.K @ u))
    return ErrorEstimate(eta=np.sqrt(np.maximum(eta2, 0.0)), energy=energy,
                         rel_error=float(np.sqrt(eta2.sum() / energy)) if energy > 0 else 0.0)

"""A scene meshed, assembled and factorised once; then any number of contact points solved.

    model = ContactModel.build(scenes.clamped(), MeshSpec(h_contact_m=2e-3, order=2))
    sol = model.solve(penetration_m=1e-5)       # ContactSolution: force_n, half_angle_rad, ...

Cost per point after :meth:`ContactModel.build`: one mortar assembly, ``n_λ`` back-substitutions
with the stored LU factor and a dense PDAS solve of size ≤ ``n_λ``.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from contact.errors import ConvergenceError, InputError
from contact.units import check_finite
from fem_reference.plane.contact_solver import (ArcNotResolvedError, CircleSurface, ContactSolution, circle_surface,
                                          contact_half_angle, mortar_operator, solve_lcp)
from fem_reference.plane.elasticity import ElasticSystem, circle_dofs, stiffness, symmetry_dofs, vector_basis
from fem_reference.plane.mesh import BEARING, SUPPORT, MeshSpec, RingMesh, build_mesh
from fem_reference.scenes import PLANE_EQUIVALENT, Scene


def _delassus(system: ElasticSystem, Df) -> np.ndarray:
    """``Df K⁻¹ Dfᵀ`` (the contact rows' compliance), column by column: measured ~2x faster than SuperLU's
    multi-RHS solve here. Only the square matrix is kept, not the ``n_free × n_λ`` columns ``K⁻¹ Dfᵀ``
    (a level of 450k DOFs took 7.5 GB with them); the displacement is one more solve with the multipliers."""
    Bt = Df.T.tocsc()
    A = np.empty((Df.shape[0], Df.shape[0]))
    for k in range(Df.shape[0]):
        A[:, k] = Df @ system.solve_free(Bt[:, [k]].toarray().ravel())
    return A


def _dirichlet(scene: Scene, rmesh: RingMesh, basis):
    """Dirichlet DOFs and their values per unit drive displacement t (m/m)."""
    rings = scene.rings
    drive = PLANE_EQUIVALENT.get(scene.bearing_drive, scene.bearing_drive)
    hold = PLANE_EQUIVALENT.get(scene.support_hold, scene.support_hold)
    n = basis.N
    fixed = [symmetry_dofs(rmesh, basis)]
    unit = np.zeros(n)
    inner = circle_dofs(rmesh, basis, rings.inner_radius_m)
    Q = None
    if drive == "rigid-inner":
        fixed += [inner[0], inner[1]]
        unit[inner[1]] = 1.0
    elif drive == "rigid-inner-y":
        fixed += [inner[1]]
        unit[inner[1]] = 1.0
    else:  # coupled-inner: distributing coupling, mean u_y of the inner surface = t
        from fem_reference.plane.elasticity import circle_mean_weights

        Q = circle_mean_weights(rmesh, basis, rings.inner_radius_m, BEARING)[:, None]
    outer = circle_dofs(rmesh, basis, rings.support_outer_radius_m)
    y = basis.doflocs[1]
    if hold == "clamped-outer":
        fixed += [outer[0], outer[1]]
    elif hold == "clamped-outer-lower":
        keep = y[outer[0]] <= 1e-12
        fixed += [outer[0][keep], outer[1][keep]]
    elif hold == "clamped-outer-upper":
        keep = y[outer[0]] >= -1e-12
        fixed += [outer[0][keep], outer[1][keep]]
    return np.unique(np.concatenate(fixed)), unit, Q


@dataclass
class ContactModel:
    """Meshed, factorised scene ready to solve contact points."""

    scene: Scene
    spec: MeshSpec
    rmesh: RingMesh
    basis: object
    system: ElasticSystem
    u_unit: np.ndarray        # response to a unit drive without contact
    slave: CircleSurface      # support bore
    master: CircleSurface     # bearing outer surface
    build_s: float

    @classmethod
    def build(cls, scene: Scene, spec: MeshSpec = MeshSpec()) -> "ContactModel":
        t0 = time.perf_counter()
        return cls.from_mesh(scene, build_mesh(scene.rings, spec), t0)

    @classmethod
    def from_mesh(cls, scene: Scene, rmesh: RingMesh, t0: float | None = None, *,
                  nested_dissection: bool = False) -> "ContactModel":
        """The model of ``scene`` on a given mesh (e.g. :func:`fem_reference.plane.mesh.build_mesh_sized`);
        ``t0``: the :func:`time.perf_counter` its build time counts from (default: now); ``nested_dissection``:
        order the factor by :func:`fem_reference.plane.ordering.nested_dissection` (fine meshes: 465k DOFs
        factorised in 6.6 s instead of 125 s), else by SuperLU's minimum degree."""
        t0 = time.perf_counter() if t0 is None else t0
        spec = rmesh.spec
        basis = vector_basis(rmesh)
        K = stiffness(rmesh, basis, scene.plane)
        fixed, unit, Q = _dirichlet(scene, rmesh, basis)
        system = ElasticSystem.build(K, fixed, Q, basis.doflocs if nested_dissection else None)
        u_unit = system.solve(np.zeros(basis.N), unit, None if Q is None else np.ones(Q.shape[1]))
        slave = circle_surface(rmesh, basis, scene.rings.bore_radius_m, SUPPORT)
        master = circle_surface(rmesh, basis, scene.rings.outer_radius_m, BEARING)
        return cls(scene, spec, rmesh, basis, system, u_unit, slave, master, time.perf_counter() - t0)

    @property
    def ndofs(self) -> int:
        return self.system.ndofs

    def gaps(self, penetration_m: float):
        """The point's mortar operator, the drive's displacement ``u0`` [m] without contact, the weighted gaps
        ``G + D u0`` there and each slave corner node's angle from the load axis [rad] (the penetration checked:
        :meth:`solve`'s InputError)."""
        check_penetration(self.scene.rings, penetration_m)
        t = self.scene.rings.clearance_m + penetration_m
        mo = mortar_operator(self.slave, self.master, self.rmesh.order, self.system.ndofs, t)
        u0 = t * self.u_unit
        return mo, u0, mo.G + mo.D @ u0, np.pi / 2 - self.slave.node_theta[: self.slave.n_corners]

    def solve(self, penetration_m: float, *, tol: float = 1e-10) -> ContactSolution:
        """Solve one point at penetration ``Δr = t − δ0`` [m] (may be ≤ 0: no contact → 0 N).

        Raises
        ------
        InputError
            Non-finite penetration, or one that pushes the bearing centre past the bore
            (``t ≥ R_b + δ0``: the rings would not be rings any more), or a drive beyond the
            validity of the small-strain model (``|Δr| > 2 % of R_b``).
        ConvergenceError
            The contact QP did not reach its KKT tolerance, or the arc reaches the end of the
            modelled surface (contact on the symmetry line's far side), or the arc is not
            resolved by the mesh (fewer than 3 active nodes while in contact).
        """
        t0 = time.perf_counter()
        rings, sysm = self.scene.rings, self.system
        mo, u0, b_all, phi_nodes = self.gaps(penetration_m)
        t = rings.clearance_m + penetration_m
        # candidate window: the rigid-overlap half-angle + 10 deg, widened until no node
        # outside it would penetrate (checked on the full solution below)
        eps_rigid = np.arccos(min(1.0, rings.clearance_m / t)) if t > 0 else 0.0
        window = min(np.pi, max(eps_rigid + np.radians(10), np.radians(20)))
        gap_tol = tol * max(np.abs(b_all).max(), 1e-300)
        iterations = 0
        while True:
            sel = np.flatnonzero(phi_nodes <= window + 1e-12)
            Df = mo.D[sel][:, sysm.free]
            A = _delassus(sysm, Df)
            A = 0.5 * (A + A.T)
            lcp = solve_lcp(A, b_all[sel], tol=tol)
            iterations += lcp.iterations
            lam = np.zeros(len(phi_nodes))
            lam[sel] = lcp.lam
            u = u0.copy()
            u[sysm.free] += sysm.solve_free(Df.T @ lcp.lam)
            g_all = mo.G + mo.D @ u
            outside = np.setdiff1d(np.arange(len(phi_nodes)), sel)
            at_edge = lam[sel][np.argmax(phi_nodes[sel])] > 0
            if window >= np.pi or not ((g_all[outside] < -gap_tol).any() or at_edge):
                break
            window = min(np.pi, 1.5 * window + np.radians(10))
        return contact_solution(self, penetration_m, mo.D, lam, u, iterations=iterations, method=lcp.method,
                                kkt_residual=lcp.kkt_residual, t0=t0)


def check_penetration(rings, penetration_m: float) -> None:
    """Refuse a penetration [m] the model cannot solve (:meth:`ContactModel.solve`'s InputError)."""
    check_finite("penetration_m", penetration_m, "m")
    if abs(penetration_m) > 0.02 * rings.outer_radius_m:
        raise InputError(f"penetration_m = {penetration_m:g} m: |Δr| must be <= 2 % of R_b "
                         f"= {0.02 * rings.outer_radius_m:g} m (small-strain model; wrong unit?)")
    if penetration_m < -rings.clearance_m:
        raise InputError(f"penetration_m = {penetration_m:g} m: must be >= -clearance_m = "
                         f"{-rings.clearance_m:g} m (the bearing is driven along +y only; the contact "
                         "window is the upper arc)")


def contact_solution(model: "ContactModel", penetration_m: float, D, lam: np.ndarray, u: np.ndarray, *,
                     iterations: int, method: str, kkt_residual: float, t0: float) -> ContactSolution:
    """The solved point from the mortar operator ``D`` (:class:`~fem_reference.plane.contact_solver.MortarOperator`'s),
    the multipliers ``lam`` [Pa] at every slave corner node and the displacement ``u`` [m]: the force of the whole ring, the arc and its checks (:meth:`ContactModel.solve`'s ConvergenceError)."""
    rings = model.scene.rings
    fc = D.T @ lam                           # contact forces (N/m), + on support
    ydofs = model.slave.dofs[:, :, 1].ravel()
    force = 2.0 * float(np.sum(fc[np.unique(ydofs)])) * rings.width_m
    phi = np.pi / 2 - model.slave.node_theta[: model.slave.n_corners]
    order = np.argsort(phi)
    phi, p = phi[order], lam[order]
    active = np.flatnonzero(p > 0)
    if len(active) and active[-1] == len(p) - 1:
        raise ConvergenceError(f"contact arc reaches the end of the modelled bore (phi = 180 deg) at "
                               f"penetration_m = {penetration_m:g} m: the rings are too flexible or the "
                               f"load too large for this scene")
    if 0 < len(active) < 3:
        raise ArcNotResolvedError(f"contact arc not resolved by the mesh at penetration_m = {penetration_m:g} m: "
                                  f"{len(active)} active node(s), need >= 3 (reduce h_contact_m = "
                                  f"{model.spec.h_contact_m:g} m)")
    return ContactSolution(offset_m=rings.clearance_m + penetration_m, force_n=force,
                           half_angle_rad=contact_half_angle(phi, p), peak_pressure_pa=float(p.max(initial=0.0)),
                           arc_phi_rad=phi, arc_pressure_pa=p, ndofs=model.ndofs, n_multipliers=len(p),
                           iterations=iterations, method=method, kkt_residual=kkt_residual,
                           wall_s=time.perf_counter() - t0, u=u, lam=lam)

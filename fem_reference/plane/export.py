"""VTU export (meshio) of a solved point: deformed rings, contact pressure and stresses, for ParaView."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from contact.files import atomic_write_via
from fem_reference.plane.contact_solver import ContactSolution
from fem_reference.plane.mesh import BEARING, SUPPORT


def element_stresses(model, u: np.ndarray) -> dict[str, np.ndarray]:
    """Element-mean stresses [Pa]: xx, yy, xy, zz (plane strain), radial, hoop, von Mises."""
    basis = model.basis
    grad = basis.interpolate(u).grad                      # (2, 2, nel, nq)
    eps = 0.5 * (grad + np.swapaxes(grad, 0, 1))
    lam = np.empty(model.rmesh.mesh.nelements)
    mu = np.empty_like(lam)
    for b, mat in ((BEARING, model.scene.rings.bearing), (SUPPORT, model.scene.rings.support)):
        lam[model.rmesh.body == b], mu[model.rmesh.body == b] = mat.lame(model.scene.plane)
    tr = eps[0, 0] + eps[1, 1]
    sxx = (lam[:, None] * tr + 2 * mu[:, None] * eps[0, 0]).mean(axis=1)
    syy = (lam[:, None] * tr + 2 * mu[:, None] * eps[1, 1]).mean(axis=1)
    sxy = (2 * mu[:, None] * eps[0, 1]).mean(axis=1)
    szz = (lam[:, None] * tr).mean(axis=1) if model.scene.plane == "strain" else np.zeros_like(sxx)
    c = model.rmesh.mesh.p[:, model.rmesh.mesh.t].mean(axis=1)
    th = np.arctan2(c[1], c[0])
    co, si = np.cos(th), np.sin(th)
    srr = sxx * co ** 2 + syy * si ** 2 + 2 * sxy * si * co
    stt = sxx * si ** 2 + syy * co ** 2 - 2 * sxy * si * co
    vm = np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3 * sxy ** 2)
    return {"stress_xx_pa": sxx, "stress_yy_pa": syy, "stress_xy_pa": sxy, "stress_zz_pa": szz,
            "stress_rr_pa": srr, "stress_tt_pa": stt, "von_mises_pa": vm}


def write_vtu(path, model, sol: ContactSolution, warp_scale: float = 1.0) -> Path:
    """Write the mesh (undeformed coordinates) with displacement, contact pressure and stresses.

    Point data: ``displacement_m`` (3 components, use ParaView's Warp By Vector),
    ``warp_m`` (= displacement × ``warp_scale``), ``contact_pressure_pa`` (support bore nodes).
    Cell data: ``body`` (0 bearing, 1 support) and the stresses of :func:`element_stresses`.
    """
    import meshio

    mesh, basis = model.rmesh.mesh, model.basis
    order = model.rmesh.order
    nodes = mesh.doflocs                                  # vertices then mid-sides (P2)
    n = nodes.shape[1]
    dofs = basis.nodal_dofs if order == 1 else np.hstack([basis.nodal_dofs, basis.facet_dofs])
    disp = np.zeros((n, 3))
    disp[:, 0], disp[:, 1] = sol.u[dofs[0]], sol.u[dofs[1]]
    pressure = np.zeros(n)
    corner_nodes = np.unique(np.concatenate([model.slave.node[:, 0], model.slave.node[:, 1]]))
    # surface corner node k ↔ its mesh vertex (same coordinates): match by angle on the bore
    v = np.unique(mesh.facets[:, _slave_facets(model)])
    ang_v = np.arctan2(mesh.p[1, v], mesh.p[0, v])
    phi_nodes = np.pi / 2 - model.slave.node_theta[: model.slave.n_corners]
    for k in corner_nodes:
        j = v[np.argmin(np.abs(ang_v - (np.pi / 2 - phi_nodes[k])))]
        pressure[j] = sol.lam[k]
    if order == 1:
        cells = [("triangle", mesh.t.T)]
    else:
        t6 = np.vstack([mesh.t, mesh.nvertices + mesh.t2f]).T  # skfem facets 01,12,02 = gmsh 3,4,5
        cells = [("triangle6", t6)]
    pts = np.zeros((n, 3))
    pts[:, :2] = nodes.T
    cell_data = {k: [v_] for k, v_ in element_stresses(model, sol.u).items()}
    cell_data["body"] = [model.rmesh.body.astype(np.int32)]
    m = meshio.Mesh(pts, cells, point_data={"displacement_m": disp, "warp_m": disp * warp_scale,
                                              "contact_pressure_pa": pressure}, cell_data=cell_data)
    path = Path(path)
    return atomic_write_via(path, lambda tmp: meshio.write(tmp, m, file_format="vtu", binary=True))


def _slave_facets(model):
    from fem_reference.plane.mesh import facets_on_circle

    return facets_on_circle(model.rmesh.mesh, model.scene.rings.bore_radius_m,
                            element_mask=model.rmesh.body == SUPPORT)

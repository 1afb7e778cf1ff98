"""Topology checks of a rotor scene: what joins what, and what holds the rotor to ground.

Two kinds, called where they belong:

* :func:`check_scene_topology` (every analysis; :func:`rotor.model.assembly.assemble` calls it): a
  station no shaft or coupling reaches, and a ``[[supports]]`` node that is not the loose support's
  (nothing joins it to the rotor: it would be a separate mass on springs whose modes show among the
  rotor's). Either is a scene-writing mistake, so it is refused in one line naming the station.
* :func:`ground_problem` / :func:`require_ground`: whether the rotor is held against rigid-body
  motion (with the loose support locked, as at rest with both end faces stuck). The runs that
  *need* it refuse a free rotor: time integration (a free body has no rest position, the start
  :func:`rotor.dynamics.initial.linear_initial_state` solves ``K q = f`` and any static load makes it
  drift), the forced response and the linear time response (an unbalance response of a rotor with
  no bearing is almost always a forgotten ``[[bearings]]``). Modal analysis does not: a free–free
  beam is a legitimate test piece (its elastic modes are the textbook free–free ones), so ``rotor
  modes``, ``campbell`` and ``critical-speeds`` only warn that the rigid-body (0 Hz) modes are
  left out.

Three findings, checked in this order, each naming a station (a scene station or support name):
no bearing at all (no ``[[bearings]]``, ``[[boundaries]]`` or ``[[supports]]``); a group of stations
joined by shafts and couplings without any stiff connection to ground; a rotor that is tied to ground
but still moves as a rigid body (e.g. pivots about its only bearing, which has no angular stiffness),
found as a null vector of the stiffness on the constraint null space.
"""
from __future__ import annotations

import numpy as np
from scipy.linalg import null_space

from contact.errors import InputError

DOFS = ("y", "z", "θy", "θz")


def _reached(scene) -> set[str]:
    """Stations that are an end of a shaft or a node of a coupling."""
    out = set()
    for sh in scene.shafts:
        out |= {sh.start, sh.end}
    for cp in scene.couplings:
        out |= {cp.node_a, cp.node_b}
    return out


def _users(scene, station: str) -> str:
    """What sits on ``station``: ``" (disk 'd', bearing 'b')"`` or ``""``."""
    items = [f"{kind} {e.name!r}" for kind, group in (("disk", scene.disks), ("point mass", scene.point_masses),
                                                       ("bearing", scene.bearings), ("support", scene.supports))
             for e in group if e.station == station]
    items += [f"boundary condition {list(b.fixed)}" for b in scene.boundaries if b.station == station]
    return f" ({', '.join(items)})" if items else ""


def check_scene_topology(scene) -> None:
    """Refuse a station no shaft or coupling reaches, and a support the loose support does not use.

    A scene of one station and no shaft (a lumped mass on a bearing) is allowed.

    Raises
    ------
    InputError : one line naming the station (and what sits on it) or the support.
    """
    origin = scene.path or scene.name
    if scene.shafts or scene.couplings or len(scene.stations) > 1:
        reached = _reached(scene)
        for st in scene.stations:
            if st.name not in reached:
                raise InputError(f"{origin}: station {st.name!r}{_users(scene, st.name)}: no shaft or coupling "
                                 f"reaches it, so nothing joins it to the rotor; add a [[shafts]] entry from or to "
                                 f"{st.name!r}, or move what sits on it to a station on the shaft line")
    loose = scene.loose_support.support if scene.loose_support is not None else None
    for sp in scene.supports:
        if sp.name != loose:
            raise InputError(f"{origin}: supports {sp.name!r} on station {sp.station!r}: not the [loose_support] "
                             f"support, so nothing joins it to the rotor (it would be a separate mass on springs); "
                             f"name it in [loose_support].support, or model a plain support as a [[bearings]] entry")


def _components(model, lock: bool) -> list[list[str]]:
    """Groups of nodes joined by shaft elements, couplings and (``lock``) the loose-support pair."""
    parent = {n: n for n in model.node_names}

    def root(n):
        while parent[n] != n:
            parent[n] = parent[parent[n]]
            n = parent[n]
        return n

    pairs = [p for chain in model.shaft_nodes for p in zip(chain[:-1], chain[1:])]
    pairs += [(c.node_a, c.node_b) for c in model.couplings]
    if lock and model.loose_pair is not None:
        pairs.append((model.loose_pair.bearing_node, model.loose_pair.support_node))
    for a, b in pairs:
        parent[root(a)] = root(b)
    groups: dict[str, list[str]] = {}
    for n in model.node_names:
        groups.setdefault(root(n), []).append(n)
    return list(groups.values())


def _grounded_nodes(scene) -> set[str]:
    """Nodes with a lateral spring to ground or a boundary condition on y or z."""
    out = {b.station for b in scene.bearings if np.diag(b.lateral_at(0.0)[0]).max() > 0}
    out |= {sp.name for sp in scene.supports if sp.stiffness_n_m > 0}
    out |= {bc.station for bc in scene.boundaries if {"y", "z"} & set(bc.fixed)}
    return out


def _rigid_body_station(model, lock: bool) -> tuple[str, str] | None:
    """``(station, dof)`` moving most in a rigid-body mode of the stiffness on the constraint null space."""
    rows = [model.B]
    if lock and model.loose_pair is not None:
        lp = model.loose_pair
        L = np.zeros((4, model.n_dofs))
        for j, (ib, is_) in enumerate(zip(lp.bearing, lp.support)):
            L[j, ib], L[j, is_] = 1.0, -1.0
        rows.append(L)
    B = np.vstack(rows)
    T = null_space(B) if B.shape[0] else np.eye(model.n_dofs)
    K = T.T @ model.K_total @ T
    d = np.sqrt(np.abs(np.diag(K)))
    d[d == 0] = 1.0
    # diagonal scaling: m and rad DOFs side by side; singular values, since cross-coupled bearings
    # make K unsymmetric (for a symmetric K they are the eigenvalues' magnitudes)
    _, w, vt = np.linalg.svd(K / np.outer(d, d))
    if w[-1] > 1e-9 * max(w[0], 1.0):
        return None
    q = T @ (vt[-1] / d)
    names = {s.name for s in model.scene.stations} | {s.name for s in model.scene.supports}
    best = None
    for i, nm in enumerate(model.dof_names):
        node, _, dof = nm.rpartition(".")
        if node not in names:
            continue
        key = (dof in ("y", "z"), abs(q[i]))       # a lateral DOF first, then the largest
        if best is None or key > best[0]:
            best = (key, node, dof)
    return (best[1], best[2]) if best is not None else None


def ground_problem(model, *, lock_loose_support: bool = True) -> str | None:
    """One line saying what leaves the rotor free to move as a rigid body, or None if it is held.

    Parameters
    ----------
    model : :class:`rotor.model.assembly.RotorModel`.
    lock_loose_support : join the loose-support bearing and support (both end faces stuck), as
        the linear analyses and the start of a time integration do.
    """
    scene = model.scene
    origin = scene.path or scene.name
    if not (scene.bearings or scene.boundaries or scene.supports):
        return (f"{origin}: no bearing at all (no [[bearings]], [[boundaries]] or [[supports]]): station "
                f"{scene.stations[0].name!r} and every other is free")
    grounded = _grounded_nodes(scene)
    station_names = [s.name for s in scene.stations] + [s.name for s in scene.supports]
    for group in _components(model, lock_loose_support):
        if grounded & set(group):
            continue
        named = [n for n in station_names if n in group]
        others = f" or on the stations joined to it ({', '.join(map(repr, named[1:]))})" if len(named) > 1 else ""
        return (f"{origin}: station {named[0]!r}: no connection to ground (no bearing with stiffness, support or "
                f"boundary condition on it{others})")
    found = _rigid_body_station(model, lock_loose_support)
    if found is not None:
        st, dof = found
        return (f"{origin}: station {st!r}: the rotor can move there as a rigid body (its {dof} DOF, no stiffness "
                f"holds it: e.g. a single bearing without angular stiffness)")
    return None


def require_ground(model, job: str, *, lock_loose_support: bool = True) -> None:
    """Raise :class:`InputError` (one line, naming ``job`` and the station) if the rotor is not held.

    ``job``: what needs the rotor held, e.g. ``"time integration"``, ``"forced response"``.
    """
    msg = ground_problem(model, lock_loose_support=lock_loose_support)
    if msg is not None:
        raise InputError(f"{msg}; {job} needs a rotor held to ground: add a [[bearings]] entry (with "
                         f"angular_stiffness_n_m_per_rad for a single bearing) or a [[boundaries]] entry")

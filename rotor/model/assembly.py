"""Assembly of the rotor model: plain matrices, a named DOF map, constraints and loads.

Equation of motion of the linear part (Dai et al. 2025, Eqs. 42–48 and 59; SI units)::

    M q̈ + (C − Ω G) q̇ + K (q − Δq_m) + K_c q = Q(t, Ω) + F_sp(t, Ω) + F_c,nl(q) + F_sum  (+ Bᵀλ)
    B q = 0                                            (equal lateral displacement at the coupling)

* ``q`` holds 4 DOFs per node ``(y, z, θy, θz)`` (sign convention: :mod:`rotor.model.elements`);
  node order: the scene's stations in file order, then support nodes, then the interior nodes
  of subdivided shafts. With one element per shaft the order is exactly the paper's Eq. 30.
* ``K`` holds shafts, bearings and the support's ground springs; ``K_c`` the linear part
  ``a0`` of the transition-shaft angular spring (kept apart because the misalignment offset
  ``Δq_m`` shifts the structure but not the spring's reference, Eq. 46 vs Eq. 45).
* ``F_c,nl`` is the ``a1 θ²`` remainder of the spring moment (:func:`coupling_moment`).
* The contact between the loose-support bearing node and the support node is NOT in the model;
  :attr:`RotorModel.loose_pair` gives its DOF indices.

All matrices are dense ``numpy.ndarray`` (float64, n×n); n is small (28 for the paper's rotor
with one element per shaft).
"""
from __future__ import annotations

import dataclasses

import math
from dataclasses import dataclass, field

import numpy as np

from contact.errors import InputError
from rotor.model import elements as el
from rotor.model.scene import Scene
from rotor.model.topology import check_scene_topology

DOFS = el.NODE_DOFS


@dataclass(frozen=True)
class CouplingDofs:
    """DOF indices of a transition-shaft coupling: ``(y, z, θy, θz)`` of node a and node b."""
    name: str
    node_a: str
    node_b: str
    a: tuple[int, int, int, int]
    b: tuple[int, int, int, int]
    a0_n_m_rad: float
    a1_n_m_rad3: float
    shaft_mass_kg: float
    lever_m: float


@dataclass(frozen=True)
class LoosePair:
    """DOF indices ``(y, z, θy, θz)`` of the loose-support bearing node and of the support node."""
    bearing_node: str
    support_node: str
    bearing: tuple[int, int, int, int]
    support: tuple[int, int, int, int]


@dataclass(frozen=True)
class RotorModel:
    """Assembled linear rotor model (SI units, dense matrices, fixed DOFs already removed).

    Attributes
    ----------
    M, C, G, K, K_c : (n, n) arrays. Mass (kg, kg·m²); viscous damping (N·s/m, N·m·s/rad);
        gyroscopic per unit spin (kg·m², enters as ``−Ω G``); structural stiffness (N/m,
        N·m/rad); linear transition-shaft spring ``a0`` (N·m/rad).
    B : (m, n) array of linear constraint rows ``B q = 0`` (equal lateral displacement of the
        coupled nodes; names in ``constraint_names``).
    dof_names : ``"node.dof"`` for each retained DOF, e.g. ``"2.y"``, ``"s.θz"``.
    node_names, node_x_m : every node (retained or not) and its axial position (m).
    aliases : element name -> node name (``"disk1" -> "2"``), usable in :meth:`dof_index`.
    speed_bearings : ``(Bearing, (y index, z index))`` of each bearing with a speed table (index −1: a
        fixed DOF); :meth:`at_speed` takes the model to a speed.
    unit_acceleration_load : (n, 2) array, the load (N, N·m) on each retained DOF of a uniform
        acceleration of 1 m/s² along y (column 0) and z (column 1): ``M u`` with the full mass matrix,
        fixed nodes included (used by ``rotor.model.static_load``).
    """

    scene: Scene
    node_names: tuple[str, ...]
    node_x_m: np.ndarray
    dof_names: tuple[str, ...]
    M: np.ndarray
    C: np.ndarray
    G: np.ndarray
    K: np.ndarray
    K_c: np.ndarray
    B: np.ndarray
    constraint_names: tuple[str, ...]
    aliases: dict = field(default_factory=dict)
    couplings: tuple[CouplingDofs, ...] = ()
    loose_pair: LoosePair | None = None
    shaft_nodes: tuple[tuple[str, ...], ...] = ()
    _index: dict = field(default_factory=dict, repr=False)
    unit_acceleration_load: np.ndarray | None = field(default=None, repr=False)
    speed_bearings: tuple = ()

    def at_speed(self, speed_rad_s: float) -> "RotorModel":
        """This model with its speed-dependent bearings at ``speed_rad_s`` (rad/s): ``K`` and ``C`` built at rest
        (:meth:`rotor.model.scene.Bearing.lateral_at`) plus each table bearing's change from rest to that
        speed. A model without such bearings, or one already taken to a speed, is returned as it is."""
        if not self.speed_bearings:
            return self
        K, C = self.K.copy(), self.C.copy()
        for br, dofs in self.speed_bearings:
            (k0, c0), (k1, c1) = br.lateral_at(0.0), br.lateral_at(float(speed_rad_s))
            for a, ia in enumerate(dofs):
                for b, ib in enumerate(dofs):
                    if ia >= 0 and ib >= 0:
                        K[ia, ib] += k1[a, b] - k0[a, b]
                        C[ia, ib] += c1[a, b] - c0[a, b]
        return dataclasses.replace(self, K=K, C=C, speed_bearings=())

    @property
    def n_dofs(self) -> int:
        return len(self.dof_names)

    @property
    def K_total(self) -> np.ndarray:
        """``K + K_c``: the stiffness for linear analyses about the aligned state."""
        return self.K + self.K_c

    def velocity_matrix(self, speed_rad_s: float) -> np.ndarray:
        """``C − Ω G`` at spin speed ``Ω`` (rad/s)."""
        return self.C - speed_rad_s * self.G

    def node_of(self, name: str) -> str:
        """Resolve an element alias (``"disk1"``) or a node name to the node name."""
        if name in self.aliases:
            return self.aliases[name]
        if name in self.node_names:
            return name
        raise InputError(f"no node or element named {name!r}; nodes: {', '.join(self.node_names)}; "
                         f"elements: {', '.join(self.aliases)}")

    def dof_index(self, name: str) -> int:
        """Index of a DOF given as ``"node.dof"`` or ``"element.dof"`` (``"disk1.y"``, ``"5.θz"``, ``"s.tz"``)."""
        node, _, dof = name.rpartition(".")
        if not node or dof not in el.DOF_ALIASES:
            raise InputError(f"DOF name {name!r}: expected 'node.dof' with dof in y, z, θy (ty), θz (tz)")
        key = f"{self.node_of(node)}.{el.DOF_ALIASES[dof]}"
        if key not in self._index:
            raise InputError(f"DOF {name!r} ({key}) is fixed by a boundary condition")
        return self._index[key]

    def response_stations(self, primary_only: bool = False) -> tuple[str, ...]:
        """The scene's response stations by the scene's own names, one per node with free y and z.

        Its disks, the loose support's bearing station, its supports (the *primary* stations: those
        that carry mass or the loose support), then its bearings; with ``primary_only`` the first
        three kinds alone (all of them if there are none). For the Table 4 scene: ``disk1, disk2, 5,
        s`` then ``bearing1, bearing2``.
        """
        sc = self.scene
        primary = [d.name for d in sc.disks]
        if sc.loose_support is not None:
            primary.append(sc.loose_support.bearing_station)
        primary += [sp.name for sp in sc.supports]
        names = primary if primary_only and primary else primary + [b.name for b in sc.bearings]
        out, nodes = [], set()
        for name in names or [st.name for st in sc.stations]:
            node = self.node_of(name)
            if node not in nodes and f"{node}.y" in self._index and f"{node}.z" in self._index:
                nodes.add(node)
                out.append(name)
        return tuple(out)

    def node_dofs(self, name: str) -> tuple[int, int, int, int]:
        """Indices of ``(y, z, θy, θz)`` of a node or element alias (all must be free)."""
        node = self.node_of(name)
        return tuple(self.dof_index(f"{node}.{d}") for d in DOFS)  # type: ignore[return-value]


# --------------------------------------------------------------------------------------------
def _section(shaft) -> el.Section:
    m = shaft.material
    return el.Section(shaft.outer_diameter_m, shaft.inner_diameter_m, m.density_kg_m3, m.youngs_modulus_pa,
                      m.poisson_ratio)


def _node_layout(scene: Scene, elements_per_segment: int | None):
    """Every node in DOF order with its axial position, and the shaft elements.

    Returns ``names``, ``xs`` (m): the stations in file order, then the support nodes, then the
    interior nodes of subdivided shafts; ``shaft_nodes``: the node chain of each shaft;
    ``shaft_pieces``: ``(node_i, node_j, length_m, section)`` of each shaft element.
    """
    names = [s.name for s in scene.stations] + [s.name for s in scene.supports]
    xs = [s.x_m for s in scene.stations] + [scene.station(s.station).x_m for s in scene.supports]
    shaft_nodes = []
    shaft_pieces = []  # (node_i, node_j, length, section)
    for sh in scene.shafts:
        n_el = elements_per_segment or sh.elements
        x0, x1 = scene.station(sh.start).x_m, scene.station(sh.end).x_m
        chain = [sh.start]
        for k in range(1, n_el):
            nm = f"{sh.start}~{sh.end}#{k}"
            names.append(nm)
            xs.append(x0 + (x1 - x0) * k / n_el)
            chain.append(nm)
        chain.append(sh.end)
        shaft_nodes.append(tuple(chain))
        sec = _section(sh)
        for a, b in zip(chain[:-1], chain[1:]):
            shaft_pieces.append((a, b, (x1 - x0) / n_el, sec))
    return names, xs, shaft_nodes, shaft_pieces


def _full_matrices(scene: Scene, names: list[str], node_pos: dict[str, int], shaft_pieces, *, shear: bool,
                   rotary_inertia: bool, gyroscopic: bool):
    """M, C, G, K, K_c over all DOFs (none removed yet) and the element aliases (name -> node)."""
    nfull = 4 * len(names)
    M = np.zeros((nfull, nfull))
    C = np.zeros_like(M)
    G = np.zeros_like(M)
    K = np.zeros_like(M)
    Kc = np.zeros_like(M)

    def dofs(*nodes):
        return np.concatenate([np.arange(4 * node_pos[n], 4 * node_pos[n] + 4) for n in nodes])

    def add(e: el.ElementMatrices, *nodes, target_K=None):
        ix = np.ix_(dofs(*nodes), dofs(*nodes))
        M[ix] += e.M
        C[ix] += e.C
        G[ix] += e.G
        (K if target_K is None else target_K)[ix] += e.K

    for a, b, length, sec in shaft_pieces:
        add(el.timoshenko_beam(length, sec, shear=shear, rotary_inertia=rotary_inertia, gyroscopic=gyroscopic), a, b)
    aliases = {}
    for d in scene.disks:
        add(el.rigid_disk(d.mass_kg, d.polar_inertia_kg_m2 if gyroscopic else 0.0, d.diametral_inertia_kg_m2),
            d.station)
        aliases[d.name] = d.station
    for pm in scene.point_masses:
        add(el.ground_spring(0.0, mass_kg=pm.mass_kg, inertia_kg_m2=pm.diametral_inertia_kg_m2), pm.station)
        aliases[pm.name] = pm.station
    for br in scene.bearings:
        add(el.ground_bearing(*br.lateral_at(0.0), br.angular_stiffness_n_m_rad, br.angular_damping_n_m_s_rad),
            br.station)
        aliases[br.name] = br.station
    for sp in scene.supports:
        add(el.ground_spring(sp.stiffness_n_m, sp.damping_n_s_m, sp.angular_stiffness_n_m_rad,
                             sp.angular_damping_n_m_s_rad, sp.mass_kg, sp.inertia_kg_m2), sp.name)
    for cp in scene.couplings:
        add(el.node_spring(0.0, 0.0, cp.a0_n_m_rad), cp.node_a, cp.node_b, target_K=Kc)
        aliases[cp.name] = cp.node_a
    return M, C, G, K, Kc, aliases


def _free_dofs(scene: Scene, names: list[str], node_pos: dict[str, int]):
    """Boundary conditions: indices of the retained (free) DOFs and their ``"node.dof"`` names."""
    fixed = np.zeros(4 * len(names), bool)
    for bc in scene.boundaries:
        for d in bc.fixed:
            fixed[4 * node_pos[bc.station] + DOFS.index(d)] = True
    keep = np.flatnonzero(~fixed)
    full_names = [f"{n}.{d}" for n in names for d in DOFS]
    dof_names = tuple(full_names[i] for i in keep)
    return keep, dof_names


def _coupling_constraints(scene: Scene, index: dict[str, int], n_dofs: int):
    """DOFs of each coupling and the rows ``B`` (with names) of its equal-lateral constraint."""
    rows, cnames, cdofs = [], [], []
    for cp in scene.couplings:
        a = tuple(index.get(f"{cp.node_a}.{d}", -1) for d in DOFS)
        b = tuple(index.get(f"{cp.node_b}.{d}", -1) for d in DOFS)
        cdofs.append(CouplingDofs(cp.name, cp.node_a, cp.node_b, a, b, cp.a0_n_m_rad, cp.a1_n_m_rad3,
                                  cp.shaft_mass_kg, cp.lever_m))
        if cp.equal_lateral:
            for j, d in enumerate(("y", "z")):
                if a[j] < 0 or b[j] < 0:
                    continue
                row = np.zeros(n_dofs)
                row[a[j]], row[b[j]] = 1.0, -1.0
                rows.append(row)
                cnames.append(f"{cp.name}: {cp.node_a}.{d} - {cp.node_b}.{d} = 0")
    B = np.array(rows) if rows else np.zeros((0, n_dofs))
    return B, cnames, cdofs


def assemble(scene: Scene, *, elements_per_segment: int | None = None, shear: bool = True,
             rotary_inertia: bool = True, gyroscopic: bool = True) -> RotorModel:
    """Assemble M, C, G, K, K_c, B of a scene.

    Parameters
    ----------
    scene : loaded scene (:func:`rotor.model.scene.load_scene`).
    elements_per_segment : if given, overrides every shaft's ``elements`` (mesh studies).
    shear, rotary_inertia, gyroscopic : element options (Euler–Bernoulli: both False).
    """
    if elements_per_segment is not None and (int(elements_per_segment) != elements_per_segment
                                             or elements_per_segment < 1):
        raise InputError(f"elements_per_segment = {elements_per_segment!r}: must be an integer >= 1")
    check_scene_topology(scene)    # a station no shaft reaches, a support nothing joins (one line each)
    names, xs, shaft_nodes, shaft_pieces = _node_layout(scene, elements_per_segment)
    node_pos = {n: i for i, n in enumerate(names)}
    M, C, G, K, Kc, aliases = _full_matrices(scene, names, node_pos, shaft_pieces, shear=shear,
                                             rotary_inertia=rotary_inertia, gyroscopic=gyroscopic)
    keep, dof_names = _free_dofs(scene, names, node_pos)
    index = {nm: i for i, nm in enumerate(dof_names)}
    unit = np.zeros((M.shape[0], 2))
    unit[0::4, 0] = 1.0          # every node's y (DOFS order y, z, θy, θz)
    unit[1::4, 1] = 1.0
    sub = np.ix_(keep, keep)
    B, cnames, cdofs = _coupling_constraints(scene, index, len(keep))

    loose = None
    if scene.loose_support is not None:
        ls = scene.loose_support
        loose = LoosePair(ls.bearing_station, ls.support,
                          tuple(index[f"{ls.bearing_station}.{d}"] for d in DOFS),
                          tuple(index[f"{ls.support}.{d}"] for d in DOFS))
        aliases.setdefault("loose_bearing", ls.bearing_station)
    model = RotorModel(scene=scene, node_names=tuple(names), node_x_m=np.array(xs), dof_names=dof_names,
                       M=M[sub], C=C[sub], G=G[sub], K=K[sub], K_c=Kc[sub], B=B, constraint_names=tuple(cnames),
                       aliases=aliases, couplings=tuple(cdofs), loose_pair=loose, shaft_nodes=tuple(shaft_nodes),
                       _index=index, unit_acceleration_load=(M @ unit)[keep],
                       speed_bearings=tuple((br, tuple(index.get(f"{br.station}.{d}", -1) for d in ("y", "z")))
                                            for br in scene.bearings if br.speed_dependent))
    return model


# --------------------------------------------------------------------------------------------
# constraints used by the linear analyses
# --------------------------------------------------------------------------------------------
def lock_rows(model: RotorModel) -> tuple[np.ndarray, tuple[str, ...]]:
    """Rows ``q_bearing − q_support = 0`` (4 of them) tying the loose-support pair together.

    This is the "bearing and support move together" state (all end faces sticking, Dai et al.
    2025, Eqs. 50–51, with zero initial relative offset) used for linear analyses.
    """
    if model.loose_pair is None:
        return np.zeros((0, model.n_dofs)), ()
    lp = model.loose_pair
    rows = np.zeros((4, model.n_dofs))
    for j, (ib, is_) in enumerate(zip(lp.bearing, lp.support)):
        rows[j, ib], rows[j, is_] = 1.0, -1.0
    names = tuple(f"lock: {lp.bearing_node}.{d} - {lp.support_node}.{d} = 0" for d in DOFS)
    return rows, names


def constraint_basis(model: RotorModel, *, lock_loose_support: bool = True) -> np.ndarray:
    """Orthonormal basis ``T`` (n × r) of ``{q : B q = 0 (and lock rows)}``; ``q = T u``."""
    from scipy.linalg import null_space

    B = model.B
    if lock_loose_support:
        B = np.vstack([B, lock_rows(model)[0]])
    if B.shape[0] == 0:
        return np.eye(model.n_dofs)
    return null_space(B)


# --------------------------------------------------------------------------------------------
# transition-shaft spring, misalignment, unbalance (functions of the state / time)
# --------------------------------------------------------------------------------------------
def coupling_moment(model: RotorModel, q: np.ndarray, *, include_linear: bool = False):
    """Generalized force of the transition-shaft angular springs and its Jacobian.

    Moment law (Dai et al. 2025, Eqs. 32 and 44): ``M_c = k_c,θ (θ_a − θ_b)`` with
    ``k_c,θ = a0 + a1 |θ_a − θ_b|²``; it acts as ``−M_c`` on node a and ``+M_c`` on node b
    (restoring). By default only the nonlinear remainder ``a1 |Δθ|² Δθ`` is returned, because
    ``a0`` is already in ``model.K_c``.

    Parameters
    ----------
    q : (n,) state vector (m, rad).
    include_linear : also include the ``a0`` part (then do not add ``K_c q`` separately).

    Returns
    -------
    f : (n,) generalized force, right-hand side (N·m on the θ DOFs, zero elsewhere).
    J : (n, n) ``∂f/∂q`` (N·m/rad).
    """
    q = np.asarray(q, dtype=float)
    f = np.zeros(model.n_dofs)
    J = np.zeros((model.n_dofs, model.n_dofs))
    for cp in model.couplings:
        ia = [cp.a[2], cp.a[3]]
        ib = [cp.b[2], cp.b[3]]
        if min(ia + ib) < 0:
            continue
        d = q[ia] - q[ib]
        s2 = float(d @ d)
        g = cp.a1_n_m_rad3 * s2 * d
        D = cp.a1_n_m_rad3 * (s2 * np.eye(2) + 2 * np.outer(d, d))
        if include_linear:
            g = g + cp.a0_n_m_rad * d
            D = D + cp.a0_n_m_rad * np.eye(2)
        f[ia] -= g
        f[ib] += g
        J[np.ix_(ia, ia)] -= D
        J[np.ix_(ia, ib)] += D
        J[np.ix_(ib, ia)] += D
        J[np.ix_(ib, ib)] -= D
    return f, J


def _misaligned_nodes(model: RotorModel, pivot: str) -> set[str]:
    """Nodes connected to ``pivot`` through shafts (not through couplings)."""
    adj: dict[str, set[str]] = {}
    for chain in model.shaft_nodes:
        for a, b in zip(chain[:-1], chain[1:]):
            adj.setdefault(a, set()).add(b)
            adj.setdefault(b, set()).add(a)
    seen, todo = {pivot}, [pivot]
    while todo:
        n = todo.pop()
        for m in adj.get(n, ()):
            if m not in seen:
                seen.add(m)
                todo.append(m)
    return seen


def misalignment_angle(model: RotorModel) -> float:
    """Tilt ``Δθ_z,m = δ / (x_bearing − x_pivot)`` (rad) of the misaligned part (Eq. 33)."""
    mis = model.scene.misalignment
    if mis is None:
        return 0.0
    cp = next(c for c in model.couplings if c.name == mis.coupling)
    xi = model.node_x_m[model.node_names.index(cp.node_b)]
    xb = model.node_x_m[model.node_names.index(mis.bearing_station)]
    if xb == xi:
        raise InputError(f"misalignment.bearing_station {mis.bearing_station!r} is at the coupling node: "
                         f"tilt undefined")
    return mis.offset_m / (xb - xi)


def misalignment_offset(model: RotorModel) -> np.ndarray:
    """Initial displacement ``Δq_m`` (Dai et al. 2025, Eq. 33), (n,) in m and rad.

    The rotor part attached to the coupling's node b (found through the shafts) turns rigidly
    about node b so that the misaligned bearing station moves by ``δ`` in +y:
    ``Δy = δ (x − x_b)/(x_bearing − x_b)``, ``Δθz = δ/(x_bearing − x_b)``. The support node of
    the loose support moves with its bearing (``Δy_s = δ``, ``Δθ_s,z`` the same tilt).
    Zero vector if the scene has no misalignment.
    """
    dq = np.zeros(model.n_dofs)
    mis = model.scene.misalignment
    if mis is None:
        return dq
    cp = next(c for c in model.couplings if c.name == mis.coupling)
    tilt = misalignment_angle(model)
    xi = model.node_x_m[model.node_names.index(cp.node_b)]
    part = _misaligned_nodes(model, cp.node_b)
    if mis.bearing_station not in part:
        raise InputError(f"misalignment.bearing_station {mis.bearing_station!r} is not on the shaft line of "
                         f"coupling node {cp.node_b!r}")
    lp = model.loose_pair
    if lp is not None and lp.bearing_node in part:
        part = part | {lp.support_node}
    for node in part:
        x = model.node_x_m[model.node_names.index(node)]
        for dof, value in (("y", tilt * (x - xi)), ("θz", tilt)):
            key = f"{node}.{dof}"
            if key in model._index:
                dq[model._index[key]] = value
    if lp is not None and lp.support_node in part:  # support follows its bearing exactly
        for dof in ("y", "θz"):
            dq[model._index[f"{lp.support_node}.{dof}"]] = dq[model._index[f"{lp.bearing_node}.{dof}"]]
    return dq


def harmonic_loads(model: RotorModel, speed_rad_s: float) -> dict[int, tuple[np.ndarray, np.ndarray]]:
    """Periodic loads as ``{n: (a_n, b_n)}`` with ``f(t) = Σ a_n cos(nΩt) + b_n sin(nΩt)``.

    * ``n = 1``: disk unbalance and skew (Dai et al. 2025, Eqs. 39–40)::

        y: m e Ω² cos(Ωt + φ_u)      θy: (Ip − Id) τ Ω² cos(Ωt + φ_τ)
        z: m e Ω² sin(Ωt + φ_u)      θz: (Ip − Id) τ Ω² sin(Ωt + φ_τ)

      (φ_u is 0 in the paper; φ_τ is the paper's φ. In the convention of :mod:`rotor.model.elements`
      this moment belongs to a principal axis tilted by τ towards the angle Ωt + φ_τ + π/2.)
    * ``n = 2``: misalignment excitation of the misaligned coupling (Eq. 34), magnitudes::

        F = 2 m_sp L tan(Δθ/2) Ω²      (F_y with cos 2Ωt, F_z with sin 2Ωt)
        M = m_sp L² tan(Δθ/2) Ω²       (M_y with cos 2Ωt, M_z with sin 2Ωt)

      with ``Δθ`` from :func:`misalignment_angle`, placed by the scene's reading
      (``Misalignment.excitation``; see :func:`misalignment_pair`).
    """
    W = float(speed_rad_s)
    n = model.n_dofs
    a1, b1, a2, b2 = (np.zeros(n) for _ in range(4))

    def put(vec, node, dof, value):
        key = f"{node}.{dof}"
        if key in model._index:
            vec[model._index[key]] += value

    for d in model.scene.disks:
        u = d.unbalance_kg_m * W ** 2
        t = (d.polar_inertia_kg_m2 - d.diametral_inertia_kg_m2) * d.skew_rad * W ** 2
        pu, pt = d.unbalance_phase_rad, d.skew_phase_rad
        # cos(Ωt+φ) = cosφ cosΩt − sinφ sinΩt ; sin(Ωt+φ) = sinφ cosΩt + cosφ sinΩt
        put(a1, d.station, "y", u * math.cos(pu)); put(b1, d.station, "y", -u * math.sin(pu))
        put(a1, d.station, "z", u * math.sin(pu)); put(b1, d.station, "z", u * math.cos(pu))
        put(a1, d.station, "θy", t * math.cos(pt)); put(b1, d.station, "θy", -t * math.sin(pt))
        put(a1, d.station, "θz", t * math.sin(pt)); put(b1, d.station, "θz", t * math.cos(pt))
    for node, fy, mz_cos_y, mz_sin_z, couple in misalignment_pair(model, W):
        put(a2, node, "y", fy); put(b2, node, "z", fy)
        put(a2, node, "θy", mz_cos_y); put(b2, node, "θz", mz_sin_z)
        # a lateral force F_y = c cos 2Ωt acting a lever dx from the node adds θz: dx·F_y and
        # F_z = c sin 2Ωt adds θy: −dx·F_z (rigid transfer, conventions of rotor.model.elements)
        put(b2, node, "θy", -couple); put(a2, node, "θz", couple)
    return {1: (a1, b1), 2: (a2, b2)}


def misalignment_pair(model: RotorModel, speed_rad_s: float) -> list[tuple[str, float, float, float, float]]:
    """Nodal 2X loads of the misalignment excitation, ``(node, F, M_y, M_z, dx·F)`` amplitudes.

    Dai et al. (2025), text before Eq. 34: misalignment "generates a pair of additional excitations
    of equal magnitude but in the opposite direction on the connected fan shaft and turbine shaft";
    Eq. 47 puts them on nodes 3a and 3b, which Eq. 31 locks together laterally. A pair of forces on
    two rigidly joined nodes does nothing, so the reading decides what acts. ``F`` is the lateral
    force on ``node`` (y with cos 2Ωt, z with sin 2Ωt), ``M_y``/``M_z`` its moments (θy with
    cos 2Ωt, θz with sin 2Ωt) and the last entry the moment ``dx·F`` of a force that acts at a
    lever ``dx`` from the node. Readings (``Misalignment.excitation``):

    ``inertial-at-joint`` (default)
        Eq. 34's force is half the inertia force of the transition shaft:
        ``F = 2 m_sp L tan(Δθ/2) Ω² = ½ m_sp e (2Ω)²`` with ``e = L tan(Δθ/2)``, the radius of the
        2Ω orbit of a point at ``L`` from the pivot tilted by ``Δθ/2``. Each centring surface
        passes its half to its shaft, in the same direction: ``+F`` on both nodes, ``2F`` on the
        joint, reacted to ground through the bearings as an unbalance force is. The moments act as
        the opposed pair ``±M`` (as the spring's pair ``M_c``, Eq. 44). At the paper's point A
        (4 500 rpm, support stuck, linear) this is the reading whose 2X shows at every station and
        most at the 3# bearing, as the text of Fig. 13 says (reports/published/rotor-misalignment.md).
    ``opposed-at-centring-surfaces``
        The opposed pair ``±F`` acts where the transition shaft bears on each shaft: the centring
        surfaces, at ``L`` before the joint on the fan shaft (``node_a``) and ``L`` after it on the
        turbine shaft (``node_b``). Moved rigidly to the joint, the forces cancel and leave the
        couple ``2FL``, reacted through the bearings; plus the pair ``±M``.
    ``opposed-at-joint``
        The pair ``+F, +M`` on ``node_a`` and ``−F, −M`` on ``node_b`` as Eq. 47 places it (the model
        before this reading was questioned). The lateral forces cancel exactly on the locked
        joint; only the moment pair acts, across the angular spring.
    """
    mis = model.scene.misalignment
    if mis is None:
        return []
    cp = next(c for c in model.couplings if c.name == mis.coupling)
    tt = math.tan(misalignment_angle(model) / 2)
    F = 2 * cp.shaft_mass_kg * cp.lever_m * tt * speed_rad_s ** 2
    M = cp.shaft_mass_kg * cp.lever_m ** 2 * tt * speed_rad_s ** 2
    a, b = cp.node_a, cp.node_b
    if mis.excitation == "inertial-at-joint":
        return [(a, F, M, M, 0.0), (b, F, -M, -M, 0.0)]
    if mis.excitation == "opposed-at-centring-surfaces":
        L = cp.lever_m   # +F at x − L on the fan shaft, −F at x + L on the turbine shaft
        return [(a, F, M, M, -L * F), (b, -F, -M, -M, -L * F)]
    return [(a, F, M, M, 0.0), (b, -F, -M, -M, 0.0)]


def unbalance_force(model: RotorModel, t_s, speed_rad_s: float) -> np.ndarray:
    """Unbalance and skew load ``Q(t, Ω)`` (Eqs. 39–40): (n,) for scalar ``t_s``, (len(t), n) for arrays."""
    a, b = harmonic_loads(model, speed_rad_s)[1]
    ph = speed_rad_s * np.asarray(t_s, dtype=float)
    return np.multiply.outer(np.cos(ph), a) + np.multiply.outer(np.sin(ph), b)


def misalignment_force(model: RotorModel, t_s, speed_rad_s: float) -> np.ndarray:
    """Misalignment excitation ``F_sp(t, Ω)`` (Eq. 34, 2X): (n,) or (len(t), n)."""
    a, b = harmonic_loads(model, speed_rad_s)[2]
    ph = 2 * speed_rad_s * np.asarray(t_s, dtype=float)
    return np.multiply.outer(np.cos(ph), a) + np.multiply.outer(np.sin(ph), b)

"""Finite elements of the rotor: Timoshenko shaft, rigid disk, linear bearing, support node.

Sign convention (the one place it is defined; tested in ``tests/rotor/linear/test_rotor_closed_forms.py``)
----------------------------------------------------------------------------------------------------------
The shaft axis is ``x``; the rotor spins at ``Ω > 0`` about ``+x``. Every node carries four
degrees of freedom in the order ``(y, z, θy, θz)``: two lateral displacements (m) and two
small rotations of the cross-section about the ``y`` and ``z`` axes (rad, right-hand rule).
For a slender (Euler–Bernoulli) shaft the rotations are the slopes of the deflected axis::

    θz = + dy/dx          θy = − dz/dx

so a point at axial offset ``a`` from a node moves laterally by ``y + a·θz`` and ``z − a·θy``.
This is the convention of the contact-law reconstruction (``r(x) = r + x·θ·e^{−iπ/2}``) and of
Dai et al. (2025, Eq. 33: a misalignment ``δ`` in ``y`` gives a positive ``θz = δ/(l34+l45)``).
For a Timoshenko shaft ``θ`` is the rotation of the section, which differs from the slope by
the shear angle.

Equation of motion (same form as Dai et al. 2025, Eq. 42)::

    M q̈ + (C − Ω G) q̇ + K q = f(t)

``G`` is skew-symmetric. For a disk it is ``[[0, −Ip], [Ip, 0]]`` on ``(θy, θz)``, i.e. the
gyroscopic moments on the left-hand side are ``+Ip Ω θ̇z`` (θy row) and ``−Ip Ω θ̇y`` (θz row).
With this sign forward whirl (orbit turning from +y towards +z, like the spin) is stiffened
by a disk with ``Ip > 0``.

Elements are built per bending plane and mapped to the node DOFs with :func:`plane_to_node`:
the ``x–y`` plane uses ``(w, s) = (y, θz)``; the ``x–z`` plane uses ``(w, s) = (z, −θy)``.

References
----------
Friswell, Penny, Garvey & Lees (2010), *Dynamics of Rotating Machines*, Cambridge UP,
§5.4–5.5 (Timoshenko element matrices with the shear parameter Φ).
Cowper (1966), J. Appl. Mech. 33:335, shear coefficient of a hollow circular section.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from contact.errors import InputError
from contact.units import check_positive

#: local DOF names of a node, in storage order
NODE_DOFS: tuple[str, ...] = ("y", "z", "θy", "θz")
#: ASCII aliases accepted by :meth:`RotorModel.dof_index`
DOF_ALIASES = {"y": "y", "z": "z", "θy": "θy", "θz": "θz", "ty": "θy", "tz": "θz",
               "thy": "θy", "thz": "θz", "theta_y": "θy", "theta_z": "θz"}


def plane_to_node(n_nodes: int) -> np.ndarray:
    """Matrix ``T`` with ``p = T d`` from node DOFs ``d`` to plane DOFs ``p``.

    ``d`` is ``(y1, z1, θy1, θz1, y2, ...)``; ``p`` is ``(w_y1, s_y1, w_y2, s_y2, ...,
    w_z1, s_z1, ...)`` with ``w_y = y, s_y = θz`` and ``w_z = z, s_z = −θy``.
    """
    n = 4 * n_nodes
    T = np.zeros((n, n))
    half = 2 * n_nodes
    for i in range(n_nodes):
        T[2 * i, 4 * i + 0] = 1.0              # w_y = y
        T[2 * i + 1, 4 * i + 3] = 1.0          # s_y = θz
        T[half + 2 * i, 4 * i + 1] = 1.0       # w_z = z
        T[half + 2 * i + 1, 4 * i + 2] = -1.0  # s_z = −θy
    return T


def cowper_shear_coefficient(outer_diameter_m: float, inner_diameter_m: float, poisson_ratio: float) -> float:
    """Shear coefficient κ of a hollow circular section (Cowper 1966, Table 1).

    ``κ = 6(1+ν)(1+m²)² / [(7+6ν)(1+m²)² + (20+12ν)m²]`` with ``m = d/D``; 6(1+ν)/(7+6ν) for a
    solid section.
    """
    m2 = (inner_diameter_m / outer_diameter_m) ** 2
    nu = poisson_ratio
    return 6 * (1 + nu) * (1 + m2) ** 2 / ((7 + 6 * nu) * (1 + m2) ** 2 + (20 + 12 * nu) * m2)


@dataclass(frozen=True)
class Section:
    """Hollow circular cross-section and its material, in SI units."""

    outer_diameter_m: float
    inner_diameter_m: float
    density_kg_m3: float
    youngs_modulus_pa: float
    poisson_ratio: float
    shear_coefficient: float | None = None  # None: Cowper (1966)

    def __post_init__(self):
        check_positive("outer_diameter_m", self.outer_diameter_m, "m")
        check_positive("inner_diameter_m", self.inner_diameter_m, "m", allow_zero=True)
        if self.inner_diameter_m >= self.outer_diameter_m:
            raise InputError(f"inner_diameter_m = {self.inner_diameter_m:g} m: must be < outer_diameter_m = "
                             f"{self.outer_diameter_m:g} m")
        check_positive("density_kg_m3", self.density_kg_m3, "kg/m^3", allow_zero=True)
        check_positive("youngs_modulus_pa", self.youngs_modulus_pa, "Pa")
        if not (-1.0 < self.poisson_ratio < 0.5):
            raise InputError(f"poisson_ratio = {self.poisson_ratio:g}: must be in (-1, 0.5)")

    @property
    def area_m2(self) -> float:
        return math.pi / 4 * (self.outer_diameter_m ** 2 - self.inner_diameter_m ** 2)

    @property
    def second_moment_m4(self) -> float:
        """Diametral second moment of area I (m⁴); the polar one is 2I."""
        return math.pi / 64 * (self.outer_diameter_m ** 4 - self.inner_diameter_m ** 4)

    @property
    def shear_modulus_pa(self) -> float:
        return self.youngs_modulus_pa / (2 * (1 + self.poisson_ratio))

    @property
    def kappa(self) -> float:
        if self.shear_coefficient is not None:
            return self.shear_coefficient
        return cowper_shear_coefficient(self.outer_diameter_m, self.inner_diameter_m, self.poisson_ratio)


@dataclass(frozen=True)
class ElementMatrices:
    """Matrices of one element in node DOFs (``(y, z, θy, θz)`` per node, nodes in order).

    ``M`` mass (kg, kg·m²), ``G`` gyroscopic per unit spin speed (kg·m², enters as ``−Ω G``),
    ``K`` stiffness (N/m, N·m/rad), ``C`` viscous damping (N·s/m, N·m·s/rad).
    """

    M: np.ndarray
    G: np.ndarray
    K: np.ndarray
    C: np.ndarray


def _plane_beam(length_m: float, sec: Section, *, shear: bool = True, rotary_inertia: bool = True):
    """Timoshenko beam matrices in one bending plane, DOF ``(w1, s1, w2, s2)``.

    Returns ``(K, Mt, Mr)``: stiffness, translational mass and rotary-inertia mass
    (Friswell et al. 2010, Eqs. 5.45, 5.49, 5.52 with shear parameter
    ``Φ = 12 E I / (κ G A L²)``).
    """
    L = length_m
    E, I, A, rho = sec.youngs_modulus_pa, sec.second_moment_m4, sec.area_m2, sec.density_kg_m3
    phi = 12 * E * I / (sec.kappa * sec.shear_modulus_pa * A * L ** 2) if shear else 0.0
    k = E * I / (L ** 3 * (1 + phi))
    K = k * np.array([
        [12, 6 * L, -12, 6 * L],
        [6 * L, (4 + phi) * L ** 2, -6 * L, (2 - phi) * L ** 2],
        [-12, -6 * L, 12, -6 * L],
        [6 * L, (2 - phi) * L ** 2, -6 * L, (4 + phi) * L ** 2]])
    m1 = 13 / 35 + 7 * phi / 10 + phi ** 2 / 3
    m2 = 11 / 210 + 11 * phi / 120 + phi ** 2 / 24
    m3 = 9 / 70 + 3 * phi / 10 + phi ** 2 / 6
    m4 = 13 / 420 + 3 * phi / 40 + phi ** 2 / 24
    m5 = 1 / 105 + phi / 60 + phi ** 2 / 120
    m6 = 1 / 140 + phi / 60 + phi ** 2 / 120
    Mt = rho * A * L / (1 + phi) ** 2 * np.array([
        [m1, m2 * L, m3, -m4 * L],
        [m2 * L, m5 * L ** 2, m4 * L, -m6 * L ** 2],
        [m3, m4 * L, m1, -m2 * L],
        [-m4 * L, -m6 * L ** 2, -m2 * L, m5 * L ** 2]])
    if rotary_inertia:
        m7 = 6 / 5
        m8 = 1 / 10 - phi / 2
        m9 = 2 / 15 + phi / 6 + phi ** 2 / 3
        m10 = 1 / 30 + phi / 6 - phi ** 2 / 6
        Mr = rho * I / (L * (1 + phi) ** 2) * np.array([
            [m7, m8 * L, -m7, m8 * L],
            [m8 * L, m9 * L ** 2, -m8 * L, -m10 * L ** 2],
            [-m7, -m8 * L, m7, -m8 * L],
            [m8 * L, -m10 * L ** 2, -m8 * L, m9 * L ** 2]])
    else:
        Mr = np.zeros((4, 4))
    return K, Mt, Mr


def timoshenko_beam(length_m: float, section: Section, *, shear: bool = True,
                    rotary_inertia: bool = True, gyroscopic: bool = True) -> ElementMatrices:
    """Two-node Timoshenko shaft element, 8×8 matrices in node DOFs ``(y,z,θy,θz)×2``.

    Parameters
    ----------
    length_m : element length (m), > 0.
    section : cross-section and material.
    shear, rotary_inertia : switch off to obtain the Rayleigh / Euler–Bernoulli element.
    gyroscopic : include the gyroscopic matrix (polar inertia ``2ρI`` per unit length).

    Notes
    -----
    Gyroscopic matrix: with ``Mr`` the rotary-inertia matrix of one plane (built from ``ρI``),
    the left-hand gyroscopic term in plane DOFs ``(p_y; p_z)`` is ``Ω [[0, 2Mr], [−2Mr, 0]]``
    (from the virtual work of ``+Ip Ω θ̇z δθy − Ip Ω θ̇y δθz`` per unit length, ``Ip = 2ρI``);
    ``G`` is its negative, following the ``C − Ω G`` form of Dai et al. (2025).
    """
    check_positive("length_m", length_m, "m")
    K4, Mt4, Mr4 = _plane_beam(length_m, section, shear=shear, rotary_inertia=rotary_inertia)
    z4 = np.zeros((4, 4))
    Kp = np.block([[K4, z4], [z4, K4]])
    Mp = np.block([[Mt4 + Mr4, z4], [z4, Mt4 + Mr4]])
    if gyroscopic:
        _, _, Mr_g = _plane_beam(length_m, section, shear=shear, rotary_inertia=True)
        Gp_lhs = np.block([[z4, 2 * Mr_g], [-2 * Mr_g, z4]])
    else:
        Gp_lhs = np.zeros((8, 8))
    T = plane_to_node(2)
    return ElementMatrices(M=T.T @ Mp @ T, G=-(T.T @ Gp_lhs @ T), K=T.T @ Kp @ T, C=np.zeros((8, 8)))


def rigid_disk(mass_kg: float, polar_inertia_kg_m2: float, diametral_inertia_kg_m2: float) -> ElementMatrices:
    """Rigid disk on one node: ``M = diag(m, m, Id, Id)``, ``G = [[0,−Ip],[Ip,0]]`` on (θy, θz)."""
    check_positive("mass_kg", mass_kg, "kg", allow_zero=True)
    check_positive("polar_inertia_kg_m2", polar_inertia_kg_m2, "kg·m^2", allow_zero=True)
    check_positive("diametral_inertia_kg_m2", diametral_inertia_kg_m2, "kg·m^2", allow_zero=True)
    M = np.diag([mass_kg, mass_kg, diametral_inertia_kg_m2, diametral_inertia_kg_m2])
    G = np.zeros((4, 4))
    G[2, 3] = -polar_inertia_kg_m2
    G[3, 2] = polar_inertia_kg_m2
    return ElementMatrices(M=M, G=G, K=np.zeros((4, 4)), C=np.zeros((4, 4)))


def ground_spring(stiffness_n_m: float, damping_n_s_m: float = 0.0, angular_stiffness_n_m_rad: float = 0.0,
                  angular_damping_n_m_s_rad: float = 0.0, mass_kg: float = 0.0,
                  inertia_kg_m2: float = 0.0) -> ElementMatrices:
    """Isotropic linear bearing or support on one node, to ground (4×4).

    ``K = diag(k, k, kθ, kθ)``, ``C = diag(c, c, cθ, cθ)``, ``M = diag(m, m, J, J)``. Used for
    the linear bearings (``m = J = 0``) and for the support node of the loose support
    (``m_s, J_s, k_s, c_s, k_sθ, c_sθ`` of Dai et al. 2025, Eq. 52).
    """
    for name, v, unit in (("stiffness_n_m", stiffness_n_m, "N/m"), ("damping_n_s_m", damping_n_s_m, "N·s/m"),
                          ("angular_stiffness_n_m_rad", angular_stiffness_n_m_rad, "N·m/rad"),
                          ("angular_damping_n_m_s_rad", angular_damping_n_m_s_rad, "N·m·s/rad"),
                          ("mass_kg", mass_kg, "kg"), ("inertia_kg_m2", inertia_kg_m2, "kg·m^2")):
        check_positive(name, v, unit, allow_zero=True)
    return ElementMatrices(
        M=np.diag([mass_kg, mass_kg, inertia_kg_m2, inertia_kg_m2]),
        G=np.zeros((4, 4)),
        K=np.diag([stiffness_n_m, stiffness_n_m, angular_stiffness_n_m_rad, angular_stiffness_n_m_rad]),
        C=np.diag([damping_n_s_m, damping_n_s_m, angular_damping_n_m_s_rad, angular_damping_n_m_s_rad]))


def ground_bearing(stiffness_n_m, damping_n_s_m, angular_stiffness_n_m_rad: float = 0.0,
                   angular_damping_n_m_s_rad: float = 0.0) -> ElementMatrices:
    """Linear bearing on one node, to ground (4×4), with 2×2 lateral stiffness and damping matrices.

    ``stiffness_n_m = [[k_yy, k_yz], [k_zy, k_zz]]`` (N/m) and ``damping_n_s_m`` alike (N·s/m) act on
    ``(y, z)``: the force on the rotor is ``−K [y, z] − C [ẏ, ż]`` (an anisotropic bearing has
    ``k_yy ≠ k_zz``; a fluid-film bearing cross-couples, ``k_yz ≠ k_zy``: Friswell et al. 2010, §5.5).
    The tilt DOFs get the isotropic ``kθ``, ``cθ``.
    """
    K2, C2 = np.asarray(stiffness_n_m, dtype=float), np.asarray(damping_n_s_m, dtype=float)
    for name, v, unit in (("stiffness_n_m", K2, "N/m"), ("damping_n_s_m", C2, "N·s/m")):
        if v.shape != (2, 2) or not np.all(np.isfinite(v)):
            raise InputError(f"{name} = {v.tolist()}: must be a finite 2×2 matrix ({unit})")
        if v[0, 0] < 0 or v[1, 1] < 0:
            raise InputError(f"{name} = {v.tolist()} {unit}: direct terms must be >= 0")
    g = ground_spring(0.0, 0.0, angular_stiffness_n_m_rad, angular_damping_n_m_s_rad)
    K, C = g.K.copy(), g.C.copy()
    K[:2, :2], C[:2, :2] = K2, C2
    return ElementMatrices(M=g.M, G=g.G, K=K, C=C)


def disk_properties(density_kg_m3: float, outer_diameter_m: float, inner_diameter_m: float,
                    width_m: float) -> tuple[float, float, float]:
    """Mass (kg), polar and diametral inertia (kg·m²) of a uniform annular disk.

    ``m = ρ π (D² − d²) w / 4``, ``Ip = m (D² + d²) / 8``, ``Id = Ip / 2 + m w² / 12`` (a thick
    annulus about a diameter through its centre; e.g. Friswell et al. 2010, §2.4 and Example 5.9.1,
    whose disks are bored to the shaft diameter).
    """
    for name, v in (("density_kg_m3", density_kg_m3), ("outer_diameter_m", outer_diameter_m),
                    ("inner_diameter_m", inner_diameter_m), ("width_m", width_m)):
        if not math.isfinite(v) or v < 0:
            raise InputError(f"{name} = {v}: must be finite and >= 0")
    if not (inner_diameter_m < outer_diameter_m and width_m > 0):
        raise InputError(f"disk: inner_diameter_m = {inner_diameter_m} must be < outer_diameter_m = "
                         f"{outer_diameter_m} and width_m = {width_m} > 0")
    D2, d2 = outer_diameter_m ** 2, inner_diameter_m ** 2
    m = density_kg_m3 * math.pi * (D2 - d2) * width_m / 4
    ip = m * (D2 + d2) / 8
    return m, ip, ip / 2 + m * width_m ** 2 / 12


def node_spring(stiffness_n_m: float, damping_n_s_m: float = 0.0, angular_stiffness_n_m_rad: float = 0.0,
                angular_damping_n_m_s_rad: float = 0.0) -> ElementMatrices:
    """Isotropic linear spring/damper between two nodes (8×8): ``[[k, −k], [−k, k]]`` per DOF."""
    g = ground_spring(stiffness_n_m, damping_n_s_m, angular_stiffness_n_m_rad, angular_damping_n_m_s_rad)
    pair = np.array([[1.0, -1.0], [-1.0, 1.0]])
    return ElementMatrices(M=np.zeros((8, 8)), G=np.zeros((8, 8)), K=np.kron(pair, g.K), C=np.kron(pair, g.C))

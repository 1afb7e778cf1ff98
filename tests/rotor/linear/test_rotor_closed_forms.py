"""Rotor elements and modal analysis against closed forms.

Expected values come from the classical solutions cited in each test; none is taken from this
code's own output.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from rotor.model import elements as el
from rotor.model.assembly import assemble
from rotor.linear.modes import critical_speeds, modes
from rotor.model.scene import load_scene, loads_scene

E, NU, RHO = 200e9, 0.3, 7800.0
L_BEAM, D_OUT, D_IN = 1.0, 0.100, 0.060
G_MOD = E / (2 * (1 + NU))


def _beam_scene(n_el: int, bc: str, *, length=L_BEAM, d_out=D_OUT, d_in=D_IN, density=RHO) -> str:
    fixed = {"pinned": '["y", "z"]', "clamped-free": None, "free": None}[bc]
    text = f"""
schema = "ringcontact.rotor-scene/1"
name = "beam"
title = "uniform beam"
[[materials]]
name = "steel"
density_kg_m3 = {density}
youngs_modulus_gpa = {E / 1e9}
poisson_ratio = {NU}
[[stations]]
name = "A"
x_mm = 0
[[stations]]
name = "B"
x_mm = {length * 1e3}
[[shafts]]
from = "A"
to = "B"
outer_diameter_mm = {d_out * 1e3}
inner_diameter_mm = {d_in * 1e3}
material = "steel"
elements = {n_el}
"""
    if bc == "pinned":
        for st in ("A", "B"):
            text += f'[[boundaries]]\nstation = "{st}"\nfixed = {fixed}\n'
    return text


def _section(d_out=D_OUT, d_in=D_IN):
    A = math.pi / 4 * (d_out ** 2 - d_in ** 2)
    I = math.pi / 64 * (d_out ** 4 - d_in ** 4)
    kappa = el.cowper_shear_coefficient(d_out, d_in, NU)
    return A, I, kappa


def _planar(freqs: np.ndarray) -> np.ndarray:
    """At rest every bending mode appears twice (x-y and x-z planes): take one of each pair."""
    assert np.allclose(freqs[0::2], freqs[1::2], rtol=1e-9)
    return freqs[0::2]


# ------------------------------------------------------------------------------------------
# sign convention
# ------------------------------------------------------------------------------------------
def test_rotation_sign_convention_matches_slope():
    """θz = +dy/dx and θy = −dz/dx (rotor.model.elements docstring): a cantilever loaded at its tip in
    +y must turn +θz, and loaded in +z must turn −θy (Euler–Bernoulli tip slope P L²/(2EI),
    Timoshenko 1955)."""
    sec = el.Section(D_OUT, D_IN, RHO, E, NU)
    K = el.timoshenko_beam(L_BEAM, sec).K
    free = slice(4, 8)  # node 2; node 1 clamped
    I = sec.second_moment_m4
    for force_dof, rot_dof, sign in ((0, 3, +1), (1, 2, -1)):
        f = np.zeros(4)
        f[force_dof] = 1.0
        u = np.linalg.solve(K[free, free], f)
        assert u[rot_dof] == pytest.approx(sign * L_BEAM ** 2 / (2 * E * I), rel=1e-12)


def test_element_matrices_symmetry_and_rigid_body():
    """M, K symmetric, G skew; a rigid translation and a rigid rotation (y = a θz) are stress-free."""
    sec = el.Section(D_OUT, D_IN, RHO, E, NU)
    e = el.timoshenko_beam(0.3, sec)
    assert np.allclose(e.M, e.M.T) and np.allclose(e.K, e.K.T) and np.allclose(e.G, -e.G.T)
    trans = np.array([1, 0, 0, 0, 1, 0, 0, 0], float)
    rot_z = np.array([0, 0, 0, 1, 0.3, 0, 0, 1], float)      # y = x θz with θz = 1
    rot_y = np.array([0, 0, 1, 0, 0, -0.3, 1, 0], float)     # z = −x θy with θy = 1
    for v in (trans, rot_z, rot_y):
        assert np.allclose(e.K @ v, 0, atol=1e-6 * np.abs(e.K).max())
    # total mass of the element from the consistent matrix
    assert trans @ e.M @ trans == pytest.approx(RHO * sec.area_m2 * 0.3, rel=1e-12)


# ------------------------------------------------------------------------------------------
# uniform beams
# ------------------------------------------------------------------------------------------
def test_pinned_pinned_euler_bernoulli_first_four_modes():
    """ω_n = (nπ/L)² √(EI/ρA) (Euler–Bernoulli; e.g. Rao 2007, Vibration of Continuous Systems,
    Eq. 11.35). 16 elements: first four modes within 0.1 %."""
    A, I, _ = _section()
    model = assemble(loads_scene(_beam_scene(16, "pinned")), shear=False, rotary_inertia=False)
    f = _planar(modes(model, 0.0, n_modes=8).frequency_hz)
    exact = np.array([(n * math.pi / L_BEAM) ** 2 * math.sqrt(E * I / (RHO * A)) / (2 * math.pi) for n in (1, 2, 3, 4)])
    assert np.all(np.abs(f / exact - 1) < 1e-3), f / exact - 1


def _timoshenko_pinned(n: int, A, I, kappa) -> float:
    """Lower root of ρAρI ω⁴ − (κGAk²ρI + ρA EI k² + ρA κGA) ω² + κGA EI k⁴ = 0, k = nπ/L
    (Timoshenko 1921; simply supported beam, e.g. Han, Benaroya & Wei 1999, J. Sound Vib. 225:935)."""
    k = n * math.pi / L_BEAM
    kga = kappa * G_MOD * A
    a = RHO * A * RHO * I
    b = kga * k ** 2 * RHO * I + RHO * A * E * I * k ** 2 + RHO * A * kga
    c = kga * E * I * k ** 4
    w2 = (b - math.sqrt(b * b - 4 * a * c)) / (2 * a)
    return math.sqrt(w2) / (2 * math.pi)


def test_pinned_pinned_timoshenko_first_four_modes():
    """Thick hollow beam (L/D = 10, shear lowers mode 4 by ~14 %): Timoshenko closed form; 48
    elements bring the first four modes within 0.1 %. The element has constant shear strain, so
    the error falls as h² where shear matters (measured in reports/published/rotor-mesh.md)."""
    A, I, kappa = _section()
    model = assemble(loads_scene(_beam_scene(48, "pinned")))
    f = _planar(modes(model, 0.0, n_modes=8).frequency_hz)
    exact = np.array([_timoshenko_pinned(n, A, I, kappa) for n in (1, 2, 3, 4)])
    eb = np.array([(n * math.pi / L_BEAM) ** 2 * math.sqrt(E * I / (RHO * A)) / (2 * math.pi) for n in (1, 2, 3, 4)])
    assert exact[3] < 0.9 * eb[3]          # the case really tests shear and rotary inertia
    assert np.all(np.abs(f / exact - 1) < 1e-3), f / exact - 1


def test_free_free_euler_bernoulli_first_four_modes():
    """cos βL cosh βL = 1: βL = 4.7300408, 7.8532046, 10.9956078, 14.1371655 (Blevins 1979,
    Formulas for Natural Frequency and Mode Shape, Table 8-1)."""
    A, I, _ = _section()
    model = assemble(loads_scene(_beam_scene(16, "free")), shear=False, rotary_inertia=False)
    f = _planar(modes(model, 0.0, n_modes=8).frequency_hz)
    beta_l = np.array([4.73004074486, 7.85320462410, 10.9956078380, 14.1371654913])
    exact = beta_l ** 2 / L_BEAM ** 2 * math.sqrt(E * I / (RHO * A)) / (2 * math.pi)
    assert np.all(np.abs(f / exact - 1) < 1e-3), f / exact - 1


def _timoshenko_free_free(n_modes: int, A, I, kappa) -> np.ndarray:
    """Roots of the exact free–free Timoshenko frequency determinant.

    General solution w = C1 cosh ax + C2 sinh ax + C3 cos bx + C4 sin bx with a², −b² the roots
    of κGA·EI s⁴ + ω²(κGA ρI + ρA EI) s² + ρAω²(ρIω² − κGA) = 0; ψ follows from
    κGA(w'' − ψ') = −ρAω² w. Free ends: EI ψ' = 0 and κGA(w' − ψ) = 0 at x = 0, L
    (Timoshenko 1921; Huang 1961, J. Appl. Mech. 28:579).
    """
    kga, ei, L = kappa * G_MOD * A, E * I, L_BEAM

    def det(w):
        p2 = w ** 2 * (kga * RHO * I + RHO * A * ei) / (kga * ei)
        q0 = RHO * A * w ** 2 * (RHO * I * w ** 2 - kga) / (kga * ei)
        disc = math.sqrt(p2 * p2 - 4 * q0)
        a = math.sqrt((-p2 + disc) / 2)
        b = math.sqrt((p2 + disc) / 2)
        ra = (kga * a * a + RHO * A * w ** 2) / (kga * a)
        qb = (RHO * A * w ** 2 - kga * b * b) / (kga * b)

        def rows(x):
            ch, sh, c, s = math.cosh(a * x), math.sinh(a * x), math.cos(b * x), math.sin(b * x)
            # ψ = C1 ra sh + C2 ra ch + C3 qb s − C4 qb c
            dpsi = [ra * a * ch, ra * a * sh, qb * b * c, qb * b * s]
            dw = [a * sh, a * ch, -b * s, b * c]
            psi = [ra * sh, ra * ch, qb * s, -qb * c]
            return [dpsi, [dw[i] - psi[i] for i in range(4)]]

        Mx = np.array(rows(0.0) + rows(L))
        return np.linalg.det(Mx / np.abs(Mx).max(axis=1, keepdims=True))

    cutoff = math.sqrt(kga / (RHO * I))                     # second-spectrum cut-off
    top = min(0.99 * cutoff, 1.2 * 14.1372 ** 2 / L ** 2 * math.sqrt(ei / (RHO * A)))
    grid = np.linspace(1.0, top, 4000)
    vals = np.array([det(w) for w in grid])
    roots = []
    for i in np.flatnonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0):
        roots.append(brentq(det, grid[i], grid[i + 1], xtol=1e-10))
        if len(roots) == n_modes:
            break
    return np.array(roots) / (2 * math.pi)


def test_free_free_timoshenko_first_four_modes():
    """Free–free thick hollow beam against the exact Timoshenko determinant; 64 elements, 0.1 %."""
    A, I, kappa = _section()
    exact = _timoshenko_free_free(4, A, I, kappa)
    beta_l = np.array([4.73004074486, 7.85320462410, 10.9956078380, 14.1371654913])
    eb = beta_l ** 2 * math.sqrt(E * I / (RHO * A)) / (2 * math.pi)
    assert np.all(exact < eb) and exact[3] < 0.9 * eb[3]   # the root finder found the shear-lowered modes
    model = assemble(loads_scene(_beam_scene(64, "free")))
    f = _planar(modes(model, 0.0, n_modes=8).frequency_hz)
    assert np.all(np.abs(f / exact - 1) < 1e-3), f / exact - 1


# ------------------------------------------------------------------------------------------
# rotors
# ------------------------------------------------------------------------------------------
def test_jeffcott_critical_speed():
    """Jeffcott (1919): ω_c = √(k/m) with 1/k = L³/(48EI) + L/(4κGA) + 1/(2k_b) for a central
    disk on a massless shaft in two flexible bearings. The 1X forward critical speed found by the
    Campbell search must equal it."""
    L, d, m, kb = 0.8, 0.02, 10.0, 2.0e6
    A, I = math.pi / 4 * d * d, math.pi / 64 * d ** 4
    kappa = el.cowper_shear_coefficient(d, 0.0, NU)
    k = 1.0 / (L ** 3 / (48 * E * I) + L / (4 * kappa * G_MOD * A) + 1 / (2 * kb))
    w_exact = math.sqrt(k / m)
    scene = load_scene("verify-jeffcott")
    assert (scene.disks[0].mass_kg, scene.bearings[0].stiffness_n_m, scene.shafts[0].outer_diameter_m) == (m, kb, d)
    model = assemble(scene)
    crit = [c for c in critical_speeds(model, 2 * w_exact, orders=(1,), families=("forward",), n_modes=4)]
    assert crit, "no forward 1X critical speed found"
    assert crit[0].speed_rad_s == pytest.approx(w_exact, rel=1e-6)
    assert crit[0].whirl == "forward"


def _overhung_analytic(speed: float, ip: float) -> tuple[np.ndarray, np.ndarray]:
    """Forward/backward whirl of a rigid disk on a massless cantilever tip.

    Tip stiffness = inverse of the Timoshenko cantilever flexibility
    [[L³/3EI + L/κGA, L²/2EI], [L²/2EI, L/EI]] (Timoshenko & Gere 1961). With complex
    coordinates the disk's diametral inertia becomes Id ∓ Ip Ω/ω for forward/backward whirl
    (e.g. Friswell et al. 2010, §3.6; Lalanne & Ferraris 1998, §2.3), giving
    (k11 − mω²)(k22 − Id ω² ± Ip Ω ω) − k12² = 0.
    """
    L, d, m, idd = 0.3, 0.03, 8.0, 0.06
    A, I = math.pi / 4 * d * d, math.pi / 64 * d ** 4
    kappa = el.cowper_shear_coefficient(d, 0.0, NU)
    F = np.array([[L ** 3 / (3 * E * I) + L / (kappa * G_MOD * A), L ** 2 / (2 * E * I)],
                  [L ** 2 / (2 * E * I), L / (E * I)]])
    (k11, k12), (_, k22) = np.linalg.inv(F)
    out = []
    for sgn in (+1, -1):
        poly = [m * idd, -sgn * m * ip * speed, -(k11 * idd + k22 * m), sgn * k11 * ip * speed, k11 * k22 - k12 ** 2]
        r = np.roots(poly)
        r = np.sort(r[(np.abs(r.imag) < 1e-6 * np.abs(r)) & (r.real > 0)].real)
        out.append(r / (2 * math.pi))
    return out[0], out[1]


@pytest.mark.parametrize("speed_rpm", [3000.0, 12000.0])
def test_overhung_disk_gyroscopic_splitting(speed_rpm):
    """Forward whirl frequencies rise and backward fall with speed, both equal to the analytic
    roots of the overhung-disk characteristic equation to 1e-8."""
    scene = load_scene("verify-overhung-disk")
    ip = 0.11
    disk = scene.disks[0]
    assert (disk.mass_kg, disk.polar_inertia_kg_m2, disk.diametral_inertia_kg_m2) == (8.0, ip, 0.06)
    w = speed_rpm * math.pi / 30
    fwd_exact, bwd_exact = _overhung_analytic(w, ip)
    res = modes(assemble(scene), w)
    fwd = np.sort(res.frequency_hz[np.array(res.whirl) == "forward"])
    bwd = np.sort(res.frequency_hz[np.array(res.whirl) == "backward"])
    assert len(fwd) == len(fwd_exact) == 2 and len(bwd) == len(bwd_exact) == 2
    assert np.allclose(fwd, fwd_exact, rtol=1e-8) and np.allclose(bwd, bwd_exact, rtol=1e-8)
    rest_f, _ = _overhung_analytic(0.0, ip)
    assert fwd[1] > rest_f[1] * 1.01 and bwd[1] < rest_f[1] * 0.99   # real splitting of the tilt mode


def test_spinning_rayleigh_beam_gyroscopic_splitting():
    """Pinned–pinned spinning Rayleigh beam (bending + rotary inertia + gyroscopic, no shear):
    mode k = nπ/L whirls at the positive roots of (ρA + ρI k²) ω² ∓ 2ρI k² Ω ω − EI k⁴ = 0,
    upper sign forward (the distributed form of Id − Ip Ω/ω with Ip = 2ρI per unit length;
    e.g. Lalanne & Ferraris 1998, §3.3; Genta 2005, §5.7). Checks the beam's own G matrix."""
    A, I, _ = _section()
    spin = 3000.0   # rad/s, comparable to the first bending frequencies: strong splitting
    model = assemble(loads_scene(_beam_scene(16, "pinned")), shear=False, rotary_inertia=True)
    res = modes(model, spin, n_modes=6)
    fwd = np.sort(res.frequency_hz[np.array(res.whirl) == "forward"])
    bwd = np.sort(res.frequency_hz[np.array(res.whirl) == "backward"])
    for n in (1, 2, 3):
        k = n * math.pi / L_BEAM
        a, b, c = RHO * A + RHO * I * k * k, 2 * RHO * I * k * k * spin, E * I * k ** 4
        w_f = (b + math.sqrt(b * b + 4 * a * c)) / (2 * a) / (2 * math.pi)
        w_b = (-b + math.sqrt(b * b + 4 * a * c)) / (2 * a) / (2 * math.pi)
        assert (w_f - w_b) / w_b > 1e-3 * n        # the splitting is far above the tolerance below
        assert fwd[n - 1] == pytest.approx(w_f, rel=1e-4)
        assert bwd[n - 1] == pytest.approx(w_b, rel=1e-4)

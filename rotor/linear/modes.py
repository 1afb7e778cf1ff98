"""Linear analyses: natural frequencies and modes at a speed, Campbell diagram, critical speeds.

The loose support is locked for these analyses (bearing and support move together, see
:func:`rotor.model.assembly.lock_rows`), as in the paper's finite-element model of the test rotor
"neglecting the effects of bearing clearance and misalignment" (Dai et al. 2025, Section 6.1).

Whirl direction: a mode ``q(t) = Re(q̂ e^{iωt})`` (ω > 0) is split at every node into a
forward part ``(ŷ + i ẑ)`` (orbit turning from +y to +z, like the spin) and a backward part
``(ŷ − i ẑ)``; tilts enter through the slope pair ``(θz, −θy)`` times a length scale of one tenth
of the rotor length. ``forward_fraction`` = forward energy / total; label ``"forward"`` above
0.75, ``"backward"`` below 0.25, otherwise ``"mixed"`` (e.g. degenerate pairs at rest).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
from scipy.optimize import brentq

from contact.errors import ConvergenceError, InputError
from rotor.model.assembly import RotorModel, constraint_basis

TWO_PI = 2 * math.pi


@dataclass(frozen=True)
class Modes:
    """Modes of the rotor at one spin speed (undamped natural or damped frequencies).

    Attributes
    ----------
    speed_rad_s : spin speed Ω (rad/s).
    frequency_hz : (k,) whirl frequencies ω/2π in increasing order (Hz).
    damping_ratio : (k,) ``−Re(λ)/|λ|`` (0 for an undamped model).
    forward_fraction : (k,) share of forward whirl, see module notes.
    whirl : (k,) ``"forward" | "backward" | "mixed"``.
    shapes : (n, k) complex mode shapes in model DOFs, normalised to unit largest lateral amplitude.
    """

    speed_rad_s: float
    frequency_hz: np.ndarray
    damping_ratio: np.ndarray
    forward_fraction: np.ndarray
    whirl: tuple[str, ...]
    shapes: np.ndarray


def _reduced(model: RotorModel, lock: bool):
    T = constraint_basis(model, lock_loose_support=lock)
    if T.shape[0] == T.shape[1] and np.array_equal(T, np.eye(T.shape[0])):
        return T, model.M, model.C, model.G, model.K_total
    return T, T.T @ model.M @ T, T.T @ model.C @ T, T.T @ model.G @ T, T.T @ model.K_total @ T


def _whirl_measure(model: RotorModel, shapes: np.ndarray) -> np.ndarray:
    """Forward fraction of each column of ``shapes`` (n, k)."""
    names = model.dof_names
    idx = {nm: i for i, nm in enumerate(names)}
    length = float(np.ptp(model.node_x_m)) or 1.0
    scale = 0.1 * length
    fwd = np.zeros(shapes.shape[1])
    bwd = np.zeros(shapes.shape[1])
    for node in model.node_names:
        iy, iz = idx.get(f"{node}.y"), idx.get(f"{node}.z")
        if iy is not None and iz is not None:
            Y, Z = shapes[iy], shapes[iz]
            fwd += np.abs(Y + 1j * Z) ** 2
            bwd += np.abs(Y - 1j * Z) ** 2
        ity, itz = idx.get(f"{node}.θy"), idx.get(f"{node}.θz")
        if ity is not None and itz is not None:
            Y, Z = scale * shapes[itz], -scale * shapes[ity]
            fwd += np.abs(Y + 1j * Z) ** 2
            bwd += np.abs(Y - 1j * Z) ** 2
    tot = fwd + bwd
    return np.where(tot > 0, fwd / np.where(tot > 0, tot, 1.0), 0.5)


def _whirl_forms(model: RotorModel) -> tuple[np.ndarray, np.ndarray]:
    """Hermitian forms ``H`` (forward − backward)/4 and ``N`` (forward + backward)/2 on model DOFs.

    Per node pair ``(Y, Z)``: ``|Y+iZ|² − |Y−iZ|² = 4 Im(Y Z̄) = 4 vᴴ[[0, i/2], [−i/2, 0]]v`` and
    ``|Y+iZ|² + |Y−iZ|² = 2(|Y|² + |Z|²)``; tilts enter as the slope pair ``(θz, −θy)`` scaled by
    a tenth of the rotor length.
    """
    n = model.n_dofs
    idx = {nm: i for i, nm in enumerate(model.dof_names)}
    scale = 0.1 * (float(np.ptp(model.node_x_m)) or 1.0)
    H = np.zeros((n, n), complex)
    N = np.zeros((n, n))
    for node in model.node_names:
        for a, b, sa, sb in ((f"{node}.y", f"{node}.z", 1.0, 1.0), (f"{node}.θz", f"{node}.θy", scale, -scale)):
            ia, ib = idx.get(a), idx.get(b)
            if ia is None or ib is None:
                continue
            H[ia, ib] += 0.5j * sa * sb
            H[ib, ia] += -0.5j * sa * sb
            N[ia, ia] += sa * sa
            N[ib, ib] += sb * sb
    return H, N


def _split_degenerate(model: RotorModel, lam: np.ndarray, shapes: np.ndarray, rtol: float = 1e-7) -> np.ndarray:
    """Within each cluster of equal eigenvalues, rotate the shapes into pure forward/backward whirl.

    Needed at rest and for rotors without gyroscopic coupling, where forward and backward whirl
    share a frequency and the eigen-solver returns arbitrary (often planar) combinations.
    """
    H, N = _whirl_forms(model)
    out = shapes.copy()
    j = 0
    while j < len(lam):
        k = j + 1
        while k < len(lam) and abs(lam[k] - lam[j]) <= rtol * max(abs(lam[j]), 1e-300):
            k += 1
        if k - j > 1:
            V = shapes[:, j:k]
            W = V.conj().T @ H @ V
            Nm = V.conj().T @ N @ V
            if np.all(np.linalg.eigvalsh(Nm) > 1e-14 * np.trace(Nm).real):
                _, X = sla.eigh(W, Nm)
                out[:, j:k] = V @ X
        j = k
    return out


def _label(frac: float) -> str:
    return "forward" if frac > 0.75 else "backward" if frac < 0.25 else "mixed"


def modes(model: RotorModel, speed_rad_s: float = 0.0, *, n_modes: int | None = None,
          lock_loose_support: bool = True, damped: bool = False) -> Modes:
    """Whirl frequencies and mode shapes at spin speed ``speed_rad_s`` (rad/s).

    Solves the quadratic eigenproblem ``(λ²M + λ(C − ΩG) + K_total) q = 0`` on the constraint
    null space as a generalized linear one in state space (``scipy.linalg.eig``). With
    ``damped=False`` (default) ``C`` is left out, so ``frequency_hz`` are the undamped whirl
    frequencies used for Campbell diagrams and critical speeds.
    """
    if not math.isfinite(speed_rad_s):
        raise InputError(f"speed_rad_s = {speed_rad_s}: must be finite")
    model = model.at_speed(speed_rad_s)          # bearings with a speed table (rotor.model.scene.Bearing)
    T, M, C, G, K = _reduced(model, lock_loose_support)
    r = M.shape[0]
    V = (C if damped else 0 * C) - speed_rad_s * G
    if not np.any(V) and np.allclose(K, K.T, rtol=0, atol=1e-12 * abs(K).max()) and np.all(np.linalg.eigvalsh(M) > 0):
        # no gyroscopic or damping term, K symmetric (no cross-coupled bearing): K φ = ω² M φ (cheaper, real planar modes)
        w2, vec = sla.eigh(K, M)
        keep = w2 > 1e-10 * max(1.0, abs(w2).max())          # drop rigid-body modes
        lam, vec = 1j * np.sqrt(w2[keep]), vec[:, keep].astype(complex)
    else:
        A = np.block([[np.zeros((r, r)), np.eye(r)], [-K, -V]])
        Bm = np.block([[np.eye(r), np.zeros((r, r))], [np.zeros((r, r)), M]])
        lam, vec = sla.eig(A, Bm)
        fin = np.isfinite(lam)
        # rigid-body roots are ~0; singular M (massless DOFs) gives infinite or huge roots, so
        # measure "zero" against the median root, not the largest
        scale = max(1.0, float(np.median(np.abs(lam[fin])))) if np.any(fin) else 1.0
        ok = fin & (lam.imag > 1e-7 * scale)
        lam, vec = lam[ok], vec[:r, ok]
    order = np.argsort(lam.imag)
    lam, vec = lam[order], vec[:, order]
    if n_modes is not None:
        lam, vec = lam[:n_modes], vec[:, :n_modes]
    shapes = vec if T.shape[0] == T.shape[1] else T @ vec
    shapes = _split_degenerate(model, lam, shapes)
    lateral = [i for i, nm in enumerate(model.dof_names) if nm.endswith(".y") or nm.endswith(".z")]
    for j in range(shapes.shape[1]):
        sub = shapes[lateral, j] if lateral else shapes[:, j]
        k = int(np.argmax(np.abs(sub)))
        ref = sub[k] if abs(sub[k]) > 0 else 1.0
        shapes[:, j] /= ref
    frac = _whirl_measure(model, shapes)
    return Modes(speed_rad_s=float(speed_rad_s), frequency_hz=lam.imag / TWO_PI,
                 damping_ratio=-lam.real / np.abs(lam), forward_fraction=frac,
                 whirl=tuple(_label(f) for f in frac), shapes=shapes)


@dataclass(frozen=True)
class Campbell:
    """Whirl frequencies over a speed range.

    ``frequency_hz[i, j]``: j-th lowest frequency at ``speeds_rad_s[i]``; ``whirl[i][j]`` its label;
    ``damping_ratio[i, j]`` its ``ζ = −Re(λ)/|λ|`` (0 when built undamped). Log decrement: :attr:`log_decrement`.
    """

    speeds_rad_s: np.ndarray
    frequency_hz: np.ndarray
    forward_fraction: np.ndarray
    whirl: tuple[tuple[str, ...], ...]
    damping_ratio: np.ndarray | None = None

    @property
    def log_decrement(self) -> np.ndarray:
        """δ = ln(x_k / x_{k+1}) = 2πζ/√(1 − ζ²) per mode and speed (–); inf for ζ ≥ 1."""
        z = np.zeros_like(self.frequency_hz) if self.damping_ratio is None else self.damping_ratio
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(z < 1, TWO_PI * z / np.sqrt(np.clip(1 - z * z, 0, None)), np.inf)


def campbell(model: RotorModel, speeds_rad_s, *, n_modes: int = 8, lock_loose_support: bool = True,
             damped: bool = False) -> Campbell:
    """Campbell diagram data: the lowest ``n_modes`` whirl frequencies at each speed.

    ``damped``: solve with the viscous damping ``C`` (:func:`modes`), so that the frequencies are the
    damped ones and ``damping_ratio`` holds each mode's ζ; otherwise undamped, ζ = 0.
    """
    speeds = np.asarray(speeds_rad_s, dtype=float)
    F = np.full((len(speeds), n_modes), np.nan)
    R = np.full((len(speeds), n_modes), np.nan)
    Z = np.full((len(speeds), n_modes), np.nan)
    labels = []
    for i, w in enumerate(speeds):
        m = modes(model, w, n_modes=n_modes, lock_loose_support=lock_loose_support, damped=damped)
        k = len(m.frequency_hz)
        F[i, :k] = m.frequency_hz
        R[i, :k] = m.forward_fraction
        Z[i, :k] = m.damping_ratio
        labels.append(m.whirl + ("",) * (n_modes - k))
    return Campbell(speeds, F, R, tuple(labels), Z)


@dataclass(frozen=True)
class CriticalSpeed:
    """A crossing of a whirl-frequency branch with the line ``f = order · Ω/2π``."""

    order: int
    speed_rad_s: float
    frequency_hz: float
    whirl: str
    branch: int  # index of the branch among modes of the same whirl family (0 = lowest)

    @property
    def speed_rpm(self) -> float:
        return self.speed_rad_s * 30 / math.pi


def _family_freqs(model, w, family, n_modes, lock):
    m = modes(model, w, n_modes=n_modes, lock_loose_support=lock)
    sel = [f for f, lab in zip(m.frequency_hz, m.whirl) if lab == family]
    return np.array(sel)


def critical_speeds(model: RotorModel, max_speed_rad_s: float, *, orders=(1, 2), families=("forward", "backward"),
                    n_points: int = 41, n_modes: int = 12, lock_loose_support: bool = True,
                    xtol_rad_s: float = 1e-6) -> list[CriticalSpeed]:
    """Speeds where a forward/backward whirl branch crosses ``order × Ω``, up to ``max_speed_rad_s``.

    Each family's k-th lowest frequency is treated as a continuous branch; sign changes of
    ``2π f_k(Ω) − order·Ω`` on a grid of ``n_points`` speeds are refined with Brent's method
    (absolute tolerance ``xtol_rad_s``). Sorted by speed.
    """
    if not (max_speed_rad_s > 0 and math.isfinite(max_speed_rad_s)):
        raise InputError(f"max_speed_rad_s = {max_speed_rad_s}: must be > 0")
    grid = np.linspace(max_speed_rad_s * 1e-3, max_speed_rad_s, n_points)
    table = {fam: [_family_freqs(model, w, fam, n_modes, lock_loose_support) for w in grid] for fam in families}
    out: list[CriticalSpeed] = []
    for fam in families:
        kmax = min(len(f) for f in table[fam]) if table[fam] else 0
        for k in range(kmax):
            fk = np.array([f[k] for f in table[fam]])
            for order in orders:
                g = TWO_PI * fk - order * grid
                for i in np.flatnonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0):
                    def h(w, k=k, order=order, fam=fam):
                        f = _family_freqs(model, w, fam, n_modes, lock_loose_support)
                        if len(f) <= k:
                            raise ConvergenceError(f"critical speed search: branch {fam} #{k} lost at "
                                                   f"{w * 30 / math.pi:.1f} rpm")
                        return TWO_PI * f[k] - order * w
                    w0 = brentq(h, grid[i], grid[i + 1], xtol=xtol_rad_s)
                    out.append(CriticalSpeed(order, float(w0), float(order * w0 / TWO_PI), fam, k))
    return sorted(out, key=lambda c: (c.speed_rad_s, c.order))

"""A tilt correction fitted to 3D tilted FEM points: two smooth surfaces over the tilted patch, force and moment.

A calibrated law's tilted patch is integrated slice by slice (Winkler slices, ``contact._kernel._slices``): every
axial slice carries the 2D law of its own penetration. A 3D ring couples its slices along the axis (shear), so its
patch is shorter, its load sits nearer the loaded edge and its rotational stiffness is higher than the slices'
(measured on the 20 mm ring, reports/published/law-family.md: the slices' moment 2-14 % low, their force up to
4 % low). No fit of the straight law changes that. This module multiplies the slices' patch load ``P`` and its
moment ``M`` about the ring centre by ``exp(a)`` and ``exp(b)``, with ``a`` and ``b`` two surfaces fitted to the
3D points:

    P = P_slices exp(a(ξ, ψ)),   M = M_slices exp(b(ξ, ψ))

over coordinates of the patch alone (its edge penetration ``Δr_e`` > 0 and tilt ``t = |θ|`` >= 0, what the kernel
has per edge): with the mid-plane penetration ``Δr_m = Δr_e − t l0/2`` and the tilt's drop over half the width
``q = t l0/2``, the polar coordinates of the point ``(Δr_m, q)``,

    r = sqrt(Δr_m² + q²),   φ = atan2(q, Δr_m) ∈ [0, 3π/4)   (Δr_e > 0  ⇔  φ < 3π/4),
    ξ = (ln r − ln r_lo) / (ln r_hi − ln r_lo),   ψ = φ / (3π/4),   both clamped to [0, 1].

``φ = 0`` is the straight ring, ``φ = π/4`` the slices' full/partial transition (``Δr_m = q``), ``φ = π/2`` a
patch from the loaded edge to the mid-plane; ``r`` is even in θ at a fixed mid-plane penetration.

Each surface is a tensor product of uniform cubic B-splines (de Boor 1978; the uniform form of Eilers & Marx 1996)
on ``n`` intervals in ξ and ``m`` in ψ, its coefficients mirrored at the four edges (``c[−1] = c[1]``,
``c[n+1] = c[n−1]``), which makes the surface's slope across each edge zero. Hence, by construction:

* the surface is C² inside the box and C¹ everywhere with the clamp (constant beyond the box);
* at θ → 0 the slope in ψ vanishes, so ``a`` and ``b`` are even in θ at a fixed mid-plane penetration to second
  order: force and moment keep continuous first and second derivatives through θ = 0, where the kernel's active
  edge changes;
* ``a(ξ, 0) = 0`` (a linear constraint of the fit, ``4 c[i, 0] + 2 c[i, 1] = 0``): the force is the straight law's
  at zero tilt; ``b(ξ, 0)`` is free (the 3D ring's rotational stiffness over the slices'), and the moment stays odd
  in θ and zero at θ = 0 because ``M_slices`` is.

The coefficients are a penalised weighted least-squares fit (P-splines, Eilers & Marx 1996: second differences of
the coefficients along ξ and along ψ, each direction with its own weight, as tensor-product P-splines have (Eilers &
Marx 2003; Wood 2006): default :data:`SMOOTHING` in both) of ``ln(F_FEM / F_slices)`` and ``ln(M_FEM / M_slices)`` at
the 3D tilted points, each point weighted by 1/its accuracy bound (2x its stated FEM error + 0.2 %). One weight per
direction because the surfaces are not alike along them: along ψ the moment's correction rises sharply where the
slices' patch turns partial (``φ`` ≈ π/4), along ξ (``ln r``) it changes slowly; a weight shared by both smooths the
rise away (the 20 mm ring, reports/published/law-tilt-correction.md). The compiled kernel evaluates the same
surfaces with their exact derivatives (``contact._kernel_tilt``); this module is the fit and the readable numpy form
the tests compare it with.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from contact._kernel_tilt import N_TILT_SLOTS, PSI_SPAN_RAD, TILT_PSI_INTERVALS, TILT_XI_INTERVALS
from contact.errors import InputError

#: the intervals of a surface in ξ and in ψ that the kernel evaluates (a fit may use fewer, for a study only)
MAX_XI_INTERVALS = TILT_XI_INTERVALS
MAX_PSI_INTERVALS = TILT_PSI_INTERVALS
#: the kernel's slots of a correction (contact._kernel_tilt)
N_KERNEL_SLOTS = N_TILT_SLOTS
#: weight of the second-difference penalty relative to the weighted squared residuals (both directions)
SMOOTHING = 1e-3


def polar(pen_edge_m, tilt_rad, width_m: float) -> tuple[np.ndarray, np.ndarray]:
    """``(r, φ)`` (m, rad) of patches with edge penetration Δr_e > 0 (m) and tilt t >= 0 (rad) (module docstring)."""
    q = 0.5 * width_m * np.asarray(tilt_rad, dtype=float)
    mid = np.asarray(pen_edge_m, dtype=float) - q
    return np.hypot(mid, q), np.arctan2(q, mid)


def _basis(u: np.ndarray, n: int) -> np.ndarray:
    """Uniform cubic B-splines on [0, 1] with n intervals at ``u`` (clamped), mirrored ends folded in: (len, n+1)."""
    u = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
    k = np.minimum((u * n).astype(int), n - 1)
    s = u * n - k
    w = np.column_stack([(1 - s) ** 3, 3 * s ** 3 - 6 * s ** 2 + 4, -3 * s ** 3 + 3 * s ** 2 + 3 * s + 1, s ** 3]) / 6
    out = np.zeros((u.size, n + 1))
    for q in range(4):
        idx = k - 1 + q
        idx = np.where(idx < 0, -idx, np.where(idx > n, 2 * n - idx, idx))       # c[-1] = c[1], c[n+1] = c[n-1]
        np.add.at(out, (np.arange(u.size), idx), w[:, q])
    return out


@dataclass(frozen=True)
class TiltCorrection:
    """Two fitted surfaces ``a`` (force) and ``b`` (moment) over (ξ, ψ) (module docstring).

    log_r_lo, log_r_hi : float
        ``ln r`` (r in m) at ξ = 0 and ξ = 1.
    force_coefficients, moment_coefficients : ndarray (n+1, m+1)
        The free B-spline coefficients (–) of ``a`` and ``b``; n intervals in ξ, m in ψ.
    """

    log_r_lo: float
    log_r_hi: float
    force_coefficients: np.ndarray
    moment_coefficients: np.ndarray

    @property
    def intervals(self) -> tuple[int, int]:
        return self.force_coefficients.shape[0] - 1, self.force_coefficients.shape[1] - 1

    def coordinates(self, pen_edge_m, tilt_rad, width_m: float) -> tuple[np.ndarray, np.ndarray]:
        """``(ξ, ψ)`` (–, clamped to [0, 1]) of patches (edge penetration m, tilt rad)."""
        r, phi = polar(pen_edge_m, tilt_rad, width_m)
        xi = (np.log(r) - self.log_r_lo) / (self.log_r_hi - self.log_r_lo)
        return np.clip(xi, 0.0, 1.0), np.clip(phi / PSI_SPAN_RAD, 0.0, 1.0)

    def design(self, xi, psi) -> np.ndarray:
        """The tensor-product design matrix (len, (n+1)(m+1)) at (ξ, ψ)."""
        n, m = self.intervals
        bx, bp = _basis(np.ravel(xi), n), _basis(np.ravel(psi), m)
        return np.einsum("ij,ik->ijk", bx, bp).reshape(bx.shape[0], -1)

    def evaluate(self, pen_edge_m, tilt_rad, width_m: float) -> tuple[np.ndarray, np.ndarray]:
        """``(a, b)``: the log corrections (–) of the patch load and moment at edge penetrations (m) and tilts (rad)."""
        X = self.design(*self.coordinates(pen_edge_m, tilt_rad, width_m))
        return X @ self.force_coefficients.ravel(), X @ self.moment_coefficients.ravel()

    def kernel_slots(self) -> tuple:
        """The kernel's slots (``contact._kernel_tilt``): n, m, ln r_lo, ln r_hi, then the force and the moment
        coefficients row by row."""
        n, m = self.intervals
        if (n, m) != (MAX_XI_INTERVALS, MAX_PSI_INTERVALS):
            raise InputError(f"tilt correction on {n} x {m} intervals: the kernel evaluates {MAX_XI_INTERVALS} x "
                             f"{MAX_PSI_INTERVALS} only")
        return (float(n), float(m), float(self.log_r_lo), float(self.log_r_hi), *self.force_coefficients.ravel(),
                *self.moment_coefficients.ravel())

    def to_parameters(self) -> dict:
        """The law file's scalar parameters (``tilt_*``) of this correction."""
        n, m = self.intervals
        out = {"tilt_xi_intervals": float(n), "tilt_psi_intervals": float(m), "tilt_log_r_lo": float(self.log_r_lo),
               "tilt_log_r_hi": float(self.log_r_hi)}
        for name, c in (("force", self.force_coefficients), ("moment", self.moment_coefficients)):
            for k, v in enumerate(c.ravel()):
                out[f"tilt_{name}_{k:02d}"] = float(v)
        return out

    @classmethod
    def from_parameters(cls, params: dict) -> "TiltCorrection | None":
        """The correction stored in a law's parameters, or None if it has none."""
        if "tilt_xi_intervals" not in params:
            return None
        n, m = int(params["tilt_xi_intervals"]), int(params["tilt_psi_intervals"])
        size = (n + 1) * (m + 1)
        f, mo = (np.array([params[f"tilt_{name}_{k:02d}"] for k in range(size)], dtype=float).reshape(n + 1, m + 1)
                 for name in ("force", "moment"))
        f[:, 0] = -0.5 * f[:, 1]           # a(ξ, 0) = 0 exactly, whatever the file's rounding
        return cls(float(params["tilt_log_r_lo"]), float(params["tilt_log_r_hi"]), f, mo)


def check_parameters(params: dict) -> str | None:
    """What is wrong with stored ``tilt_*`` parameters (a sentence), or None (also when there are none)."""
    keys = [k for k in params if k.startswith("tilt_")]
    if not keys:
        return None
    for key, top in (("tilt_xi_intervals", MAX_XI_INTERVALS), ("tilt_psi_intervals", MAX_PSI_INTERVALS)):
        v = params.get(key)
        if not isinstance(v, (int, float)) or isinstance(v, bool) or v != top:
            return f"{key} = {v!r}: must be {top} (the kernel's surface)"
    size = (int(params["tilt_xi_intervals"]) + 1) * (int(params["tilt_psi_intervals"]) + 1)
    want = {"tilt_xi_intervals", "tilt_psi_intervals", "tilt_log_r_lo", "tilt_log_r_hi"} | {
        f"tilt_{name}_{k:02d}" for name in ("force", "moment") for k in range(size)}
    for key in sorted(want | set(keys)):
        v = params.get(key)
        if key not in want:
            return f"{key}: unknown tilt-correction parameter"
        if not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v):
            return f"{key} = {v!r}: must be a finite number"
    if not params["tilt_log_r_lo"] < params["tilt_log_r_hi"]:
        return "tilt_log_r_lo must be < tilt_log_r_hi"
    n, m = int(params["tilt_xi_intervals"]), int(params["tilt_psi_intervals"])
    force = np.array([params[f"tilt_force_{k:02d}"] for k in range(size)]).reshape(n + 1, m + 1)
    if np.any(np.abs(4 * force[:, 0] + 2 * force[:, 1]) > 1e-9 * (1 + np.abs(force).max())):
        return "tilt_force_NN: the force correction must vanish at zero tilt (4 c[i,0] + 2 c[i,1] = 0)"
    return None


def _penalty(n: int, m: int) -> tuple[np.ndarray, np.ndarray]:
    """Second differences of the (n+1, m+1) coefficients along ξ and along ψ, squared (Eilers & Marx 1996): the two
    penalty matrices ((n+1)(m+1) square each), in that order."""
    def d2(k):
        return np.diff(np.eye(k + 1), 2, axis=0) if k >= 2 else np.zeros((0, k + 1))
    dx, dp = d2(n), d2(m)
    return np.kron(dx.T @ dx, np.eye(m + 1)), np.kron(np.eye(n + 1), dp.T @ dp)


def smoothing_pair(smoothing) -> tuple[float, float]:
    """``(along ξ, along ψ)`` (–) of a smoothing given as one weight (both directions) or as that pair."""
    pair = (smoothing, smoothing) if np.isscalar(smoothing) else tuple(smoothing)
    if len(pair) != 2 or not all(isinstance(v, (int, float, np.floating)) and math.isfinite(v) and v >= 0
                                 for v in pair):
        raise InputError(f"smoothing = {smoothing!r}: must be a weight >= 0 or a pair (along ξ, along ψ) of them")
    return float(pair[0]), float(pair[1])


def _solve(X: np.ndarray, y: np.ndarray, w: np.ndarray, P: tuple, N: np.ndarray, smoothing: tuple) -> np.ndarray:
    """Coefficients ``N z`` minimising ``Σ (w (X N z − y))² + tr-scaled zᵀ Nᵀ (s_ξ P_ξ + s_ψ P_ψ) N z``, the scale
    the trace of the normal matrix over that of the unweighted ``Nᵀ (P_ξ + P_ψ) N``."""
    A = X @ N * w[:, None]
    lhs = A.T @ A
    px, pp = (N.T @ p @ N for p in P)
    scale = np.trace(lhs) / max(np.trace(px + pp), 1e-300)
    pen = smoothing[0] * px + smoothing[1] * pp
    z = np.linalg.solve(lhs + scale * pen + 1e-14 * scale * np.eye(N.shape[1]), A.T @ (w * y))
    return N @ z


def fit(pen_edge_m, tilt_rad, width_m: float, force_log_ratio, moment_log_ratio, bound_force, bound_moment, *,
        intervals: tuple[int, int] = (MAX_XI_INTERVALS, MAX_PSI_INTERVALS), log_r_range: tuple | None = None,
        smoothing: float | tuple[float, float] = SMOOTHING) -> TiltCorrection:
    """The correction fitted to tilted points (t > 0, Δr_e > 0).

    Parameters
    ----------
    pen_edge_m, tilt_rad : array_like
        The loaded edge's penetration (m) and the tilt (rad) of each point.
    width_m : float
        Ring width l0 (m).
    force_log_ratio, moment_log_ratio : array_like
        ``ln(F_FEM/F_slices)``, ``ln(M_FEM/M_slices)`` (–).
    bound_force, bound_moment : array_like
        Each point's accuracy bound (–): its residual is weighted by the inverse.
    intervals : (int, int)
        B-spline intervals in ξ and ψ (the kernel evaluates only the default, the largest).
    log_r_range : (float, float), optional
        ``ln r`` (r in m) at ξ = 0 and 1; default the points' range.
    smoothing : float or (float, float)
        Weight (–) of the second-difference penalty along ξ and along ψ (one number: both), relative to the
        weighted squared residuals.
    """
    n, m = intervals
    weights = smoothing_pair(smoothing)
    if not (1 <= n <= MAX_XI_INTERVALS and 1 <= m <= MAX_PSI_INTERVALS):
        raise InputError(f"intervals = {intervals}: must be within (1..{MAX_XI_INTERVALS}, 1..{MAX_PSI_INTERVALS})")
    pe, t = np.asarray(pen_edge_m, dtype=float), np.asarray(tilt_rad, dtype=float)
    if not (np.all(t > 0) and np.all(pe > 0)):
        raise InputError("tilt correction: fit on tilted points (t > 0) in contact (edge penetration > 0) only")
    r, _ = polar(pe, t, width_m)
    lo, hi = log_r_range if log_r_range is not None else (float(np.log(r).min()), float(np.log(r).max()))
    shape = (n + 1, m + 1)
    probe = TiltCorrection(lo, hi, np.zeros(shape), np.zeros(shape))
    X = probe.design(*probe.coordinates(pe, t, width_m))
    P = _penalty(n, m)
    # force: a(ξ, 0) = 0, i.e. 4 c[i,0] + 2 c[i,1] = 0 -> c[i,0] = -c[i,1]/2 (a basis of that subspace)
    nf = np.zeros((shape[0] * shape[1], shape[0] * m))
    for i in range(shape[0]):
        for j in range(1, m + 1):
            col = i * m + (j - 1)
            nf[i * (m + 1) + j, col] = 1.0
            if j == 1:
                nf[i * (m + 1), col] = -0.5
    cf = _solve(X, np.asarray(force_log_ratio, float), 1 / np.asarray(bound_force, float), P, nf, weights)
    cm = _solve(X, np.asarray(moment_log_ratio, float), 1 / np.asarray(bound_moment, float), P,
                np.eye(shape[0] * shape[1]), weights)
    return TiltCorrection(lo, hi, cf.reshape(shape), cm.reshape(shape))


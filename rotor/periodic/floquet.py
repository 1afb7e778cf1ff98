"""Floquet multipliers of a periodic orbit: stability and the way it is lost.

The multipliers are the eigenvalues of the monodromy matrix ``M = ∂x(T)/∂x(0)`` of the period map
(Floquet 1883; Seydel 2010, *Practical Bifurcation and Stability Analysis*, ch. 7). The orbit is stable
when every multiplier lies inside the unit circle, ``|μ| < 1``; within the tolerance ``tol`` a multiplier
on the circle counts as inside. A multiplier leaving the circle names the bifurcation:

* through ``+1`` — a fold (turning point of the branch; saddle-node), or a symmetry-breaking pitchfork;
* through ``−1`` — period doubling (flip): a branch of period ``2T`` starts here;
* a complex pair ``e^{±iθ}`` — Neimark–Sacker (secondary Hopf): a torus, quasi-periodic motion.

Neutral multipliers. A stuck end face fixes the relative *velocity* of the support, not its position, so
a periodic orbit with a face stuck throughout belongs to a continuum of orbits (the face may stick at any
offset): the monodromy has a multiplier exactly 1 in that direction. Multipliers within ``tol`` of +1 are
counted as ``n_neutral`` and left out of the stability verdict and the bifurcation labels (they neither
grow nor decay); the shooting step keeps the levels the continuum conserves
(:func:`rotor.periodic.shooting.level_step`).

Discrete multipliers. The orbit is one of the Newmark map (average acceleration, the trapezoidal rule on
the first-order system), so for a linear system the multipliers are exactly ``c(λΔt)^N`` with the Cayley
map ``c(z) = (1 + z/2)/(1 − z/2)`` of each eigenvalue λ over the ``N`` steps of the period
(:func:`trapezoidal_multipliers`), which tend to ``exp(λT)`` at second order in Δt.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: default tolerance on ``|μ|`` (and on ``|μ − 1|`` for a neutral multiplier)
MULTIPLIER_TOL = 1e-6
#: a multiplier is real when ``|Im μ| <= REAL_TOL · max(1, |μ|)``
REAL_TOL = 1e-9


@dataclass(frozen=True)
class FloquetResult:
    """Multipliers of one periodic orbit and what they say.

    Attributes
    ----------
    multipliers : (n,) complex array, sorted by decreasing modulus (–)
    period_s : float, the period T (s)
    tol : float, tolerance on the unit circle (–)
    stable : bool, every non-neutral multiplier has ``|μ| <= 1 + tol``
    n_neutral : int, multipliers within ``tol`` of +1 (stuck-face continuum, see the module docstring)
    n_out_real_positive, n_out_real_negative, n_out_complex : int, multipliers outside the circle
        (``|μ| > 1 + tol``), real above +1, real below −1, complex (both of a pair counted)
    critical : complex, the non-neutral multiplier of largest modulus (0 if none)
    kind : str, the bifurcation ``critical`` names when it lies outside the circle: "fold" (real, above +1),
        "period_doubling" (real, below −1) or "neimark_sacker" (complex pair); "none" for a stable orbit
    leading : str, the type of ``critical`` whether inside or outside: "real_positive", "real_negative" or
        "complex_pair" ("none" without non-neutral multipliers): the way a stable orbit would lose stability
        if ``critical`` reached the circle
    """

    multipliers: np.ndarray
    period_s: float
    tol: float
    stable: bool
    n_neutral: int
    n_out_real_positive: int
    n_out_real_negative: int
    n_out_complex: int
    critical: complex
    kind: str
    leading: str = "none"

    @property
    def spectral_radius(self) -> float:
        """Largest ``|μ|`` of the non-neutral multipliers (–)."""
        return float(abs(self.critical))

    def exponents(self) -> np.ndarray:
        """Floquet exponents ``log(μ)/T`` (1/s, principal branch), same order as the multipliers."""
        return np.log(self.multipliers.astype(complex)) / self.period_s

    def as_dict(self) -> dict:
        """JSON-ready summary (multipliers as ``[re, im]`` pairs)."""
        return {"multipliers": [[float(m.real), float(m.imag)] for m in self.multipliers],
                "stable": bool(self.stable), "spectral_radius": self.spectral_radius, "kind": self.kind,
                "leading": self.leading,
                "n_neutral": int(self.n_neutral), "period_s": float(self.period_s)}


_LEADING = {"fold": "real_positive", "period_doubling": "real_negative", "neimark_sacker": "complex_pair"}


def _kind(mu: complex) -> str:
    if abs(mu.imag) > REAL_TOL * max(1.0, abs(mu)):
        return "neimark_sacker"
    return "fold" if mu.real > 0 else "period_doubling"


def floquet(monodromy, period_s: float, *, tol: float = MULTIPLIER_TOL) -> FloquetResult:
    """Multipliers, stability and critical multiplier of the orbit with monodromy matrix ``monodromy``.

    Parameters
    ----------
    monodromy : (n, n) array, ``∂x(T)/∂x(0)`` of the period map (–, in any consistent state units)
    period_s : float, the period (s), for the exponents
    tol : float, tolerance on the unit circle (–)
    """
    mu = np.linalg.eigvals(np.asarray(monodromy, dtype=float)).astype(complex)
    mu = mu[np.argsort(-np.abs(mu), kind="stable")]
    neutral = np.abs(mu - 1.0) <= tol
    rest = mu[~neutral]
    out = rest[np.abs(rest) > 1.0 + tol]
    kinds = [_kind(m) for m in out]
    critical = complex(rest[0]) if len(rest) else 0j
    return FloquetResult(mu, float(period_s), float(tol), len(out) == 0, int(neutral.sum()),
                         kinds.count("fold"), kinds.count("period_doubling"), kinds.count("neimark_sacker"),
                         critical, _kind(critical) if len(out) else "none",
                         _LEADING[_kind(critical)] if len(rest) else "none")


def trapezoidal_multipliers(eigenvalues, dt_s: float, n_steps: int) -> np.ndarray:
    """``((1 + λΔt/2)/(1 − λΔt/2))^N``: the multipliers the average-acceleration Newmark scheme gives a
    linear system with eigenvalues λ (1/s) over ``N`` steps of ``Δt`` (s); ``exp(λ N Δt)`` + O(Δt²)."""
    z = np.asarray(eigenvalues, dtype=complex) * dt_s / 2.0
    return ((1.0 + z) / (1.0 - z)) ** int(n_steps)


def crossing(before: FloquetResult, after: FloquetResult) -> str | None:
    """The bifurcation between two neighbouring orbits of a branch, from the multipliers that left or
    re-entered the unit circle: "period_doubling" (a real multiplier through −1), "neimark_sacker" (a
    complex pair), "fold" (a real multiplier through +1), or None. Folds are also found from the
    branch's tangent (:mod:`rotor.periodic.continuation`), which sees them when the multiplier count
    alone cannot (a multiplier touching +1 and returning)."""
    if before.n_out_real_negative != after.n_out_real_negative:
        return "period_doubling"
    if before.n_out_complex != after.n_out_complex:
        return "neimark_sacker"
    if before.n_out_real_positive != after.n_out_real_positive:
        return "fold"
    return None

"""Geometry and material of the ring-in-ring contact problem (SI units throughout).

Two concentric bodies separated by a radial clearance (Dai et al. 2025, Table 1):

* the **bearing** outer ring ("pin"): an annulus ``inner_radius_m <= r <= outer_radius_m``;
* the **support** ("holed body"): an annulus ``outer_radius_m + clearance_m <= r <= support_outer_radius_m``.

The load axis is +y; the 2D models are half models (x >= 0) with the symmetry plane x = 0.
A solid pin is modelled as an annulus with a small core radius (the core is the surface the
load is applied through; see :mod:`fem_reference.scenes`).

Everything is a frozen dataclass with validation that names the parameter, its value and unit.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass, replace

from contact.errors import InputError
from contact.units import GPA, MM, check_finite, check_positive


@dataclass(frozen=True)
class Material:
    """Isotropic linear elastic material.

    Parameters
    ----------
    youngs_modulus_pa : float
        Young's modulus E [Pa].
    poisson_ratio : float
        Poisson's ratio nu [-], in (-1, 0.5).
    """

    youngs_modulus_pa: float
    poisson_ratio: float

    def __post_init__(self):
        check_positive("youngs_modulus_pa", self.youngs_modulus_pa, "Pa")
        if self.youngs_modulus_pa < 1e6:
            raise InputError(f"youngs_modulus_pa = {self.youngs_modulus_pa:g} Pa: must be >= 1e6 Pa "
                             "(wrong unit? GPa must be converted to Pa)")
        check_finite("poisson_ratio", self.poisson_ratio, "-")
        if not -1.0 < self.poisson_ratio < 0.5:
            raise InputError(f"poisson_ratio = {self.poisson_ratio:g} -: must be in (-1, 0.5)")

    def lame(self, plane: str) -> tuple[float, float]:
        """Lamé constants (lambda, mu) [Pa] for ``plane`` = 'strain' or 'stress' (2D)."""
        E, nu = self.youngs_modulus_pa, self.poisson_ratio
        mu = E / (2 * (1 + nu))
        lam = E * nu / ((1 + nu) * (1 - 2 * nu))
        if plane == "strain":
            return lam, mu
        if plane == "stress":
            return 2 * mu * lam / (lam + 2 * mu), mu
        raise InputError(f"plane = {plane!r}: must be 'strain' or 'stress'")

    def plane_modulus(self, plane: str) -> float:
        """E' [Pa]: E/(1-nu^2) in plane strain, E in plane stress."""
        E, nu = self.youngs_modulus_pa, self.poisson_ratio
        if plane == "strain":
            return E / (1 - nu ** 2)
        if plane == "stress":
            return E
        raise InputError(f"plane = {plane!r}: must be 'strain' or 'stress'")


STEEL = Material(204.0 * GPA, 0.3)  # Dai et al. 2025, Table 1


@dataclass(frozen=True)
class RingPair:
    """Radii, clearance, width and materials of bearing ring and support [m, Pa].

    Parameters
    ----------
    inner_radius_m : float
        Bearing ring inner radius (90 mm in Table 1); a small value models a solid pin.
    outer_radius_m : float
        Bearing ring outer radius R_b (100 mm).
    clearance_m : float
        Radial clearance delta0 (0.05 mm): support bore radius minus R_b; may be 0.
    support_outer_radius_m : float
        Support outer radius (R_b + delta0 + 10 mm in Table 1).
    width_m : float
        Axial width l0 (30 mm); 2D forces per metre are multiplied by it.
    bearing, support : Material
    """

    inner_radius_m: float = 90.0 * MM
    outer_radius_m: float = 100.0 * MM
    clearance_m: float = 0.05 * MM
    support_outer_radius_m: float = 110.05 * MM
    width_m: float = 30.0 * MM
    bearing: Material = STEEL
    support: Material = STEEL

    def __post_init__(self):
        check_positive("inner_radius_m", self.inner_radius_m, "m", upper=100.0)
        check_positive("outer_radius_m", self.outer_radius_m, "m", upper=100.0)
        check_positive("clearance_m", self.clearance_m, "m", allow_zero=True, upper=0.1 * self.outer_radius_m)
        check_positive("support_outer_radius_m", self.support_outer_radius_m, "m", upper=1000.0)
        check_positive("width_m", self.width_m, "m", upper=100.0)
        if self.inner_radius_m >= self.outer_radius_m:
            raise InputError(f"inner_radius_m = {self.inner_radius_m:g} m: must be < outer_radius_m "
                             f"= {self.outer_radius_m:g} m")
        if self.support_outer_radius_m <= self.bore_radius_m:
            raise InputError(f"support_outer_radius_m = {self.support_outer_radius_m:g} m: must be > "
                             f"bore radius {self.bore_radius_m:g} m")

    @property
    def bore_radius_m(self) -> float:
        """Support inner (bore) radius R_b + delta0 [m]."""
        return self.outer_radius_m + self.clearance_m

    def with_(self, **changes) -> "RingPair":
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)

    def to_dict(self) -> dict:
        """Plain dict (SI) for dataset metadata."""
        return asdict(self)


def table1_rings(clearance_m: float = 0.05 * MM, support_thickness_m: float = 10.0 * MM) -> RingPair:
    """The paper's Table 1 pair (Dai et al. 2025): 90/100 mm bearing ring, 10 mm support, l0 = 30 mm."""
    check_positive("support_thickness_m", support_thickness_m, "m", upper=10.0)
    R_b = 100.0 * MM
    return RingPair(90.0 * MM, R_b, clearance_m, R_b + clearance_m + support_thickness_m, 30.0 * MM)

"""Error estimates of the 3D reference: Richardson extrapolation with unequal refinement ratios.

The finest of three levels (coarse -> fine) is reported with the estimate::

    error = Fs |f2 - f3| / (r32^p - 1),     Fs = 1.25,   r32 = h2 / h3,   h = N_dofs^(-1/3),

the three-grid GCI of Roache (1998, Verification and Validation in Computational Science and
Engineering) with the generalised order equation for unequal ratios of Celik et al. (2008,
J. Fluids Eng. 130:078001): ``(f1-f2)/(f2-f3) = r32^p (r21^p - 1)/(r32^p - 1)``.

Which order ``p``: the order observed at a single point is polluted by the position of the
contact-patch edges relative to the multiplier nodes (it scattered from below 0.2 to above 6 over
the committed sweep, with the same discretisation everywhere). The order is therefore pooled:
the median of the observed orders of all monotone contracting sequences of a sweep, per quantity
(force, moment), clipped to [0.5, 2], and applied to every point of that sweep (Eca & Hoekstra
2014, J. Comput. Phys. 262:104, fit the order over many grids for the same reason). A single
point solved outside a sweep uses :data:`ASSUMED_ORDERS`, which the committed sweep's pooled
orders must not be below (tests/fem_reference/solid/test_fem3d_dataset.py). The estimate is then
checked against a finer solve at every committed point.
"""
from __future__ import annotations

import math

import numpy as np

SAFETY = 1.25
# From the committed sweep (fem_reference/data/3d/fem3d-reference.json, metadata error_orders),
# rounded down: force 0.85, moment 1.12 pooled.
ASSUMED_ORDERS = {"force": 0.8, "moment": 1.1}


def observed_order(values, ndofs) -> float | None:
    """Order of a monotone contracting three-level sequence (None otherwise), by bisection."""
    f1, f2, f3 = (float(v) for v in values)
    h1, h2, h3 = (float(n) ** (-1.0 / 3.0) for n in ndofs)
    r21, r32 = h1 / h2, h2 / h3
    d1, d2 = f1 - f2, f2 - f3
    if d2 == 0.0 or not (d1 * d2 > 0 and abs(d1) > abs(d2)):
        return None
    target = d1 / d2

    def ratio(p):
        return r32 ** p * (r21 ** p - 1.0) / (r32 ** p - 1.0)

    lo, hi = 1e-3, 12.0
    if not ratio(lo) < target < ratio(hi):
        return hi if target >= ratio(hi) else lo
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ratio(mid) < target else (lo, mid)
    return 0.5 * (lo + hi)


def richardson3(values, ndofs, order: float | None = None) -> dict:
    """Error estimate of the finest of three values (coarse -> fine).

    Parameters
    ----------
    values : sequence of 3 floats
    ndofs : sequence of 3 ints
        DOFs of each level; ``h = ndofs^(-1/3)``.
    order : float, optional
        The order to assume (pooled, see module docstring); default: the observed one, clipped
        to [0.5, 2] (for a non-monotone sequence then ``Fs max(|f1 - f2|, |f2 - f3|)``).

    Returns
    -------
    dict with ``value``, ``order`` (observed; None if not monotone), ``error_abs``, ``extrapolated``.
    """
    f1, f2, f3 = (float(v) for v in values)
    d1, d2 = f1 - f2, f2 - f3
    if d1 == 0.0 and d2 == 0.0:          # one level repeated (no estimate) or an exact value
        return {"value": f3, "order": None, "error_abs": 0.0, "extrapolated": f3}
    r32 = (float(ndofs[2]) / float(ndofs[1])) ** (1.0 / 3.0)
    p_obs = observed_order(values, ndofs)
    if order is None and p_obs is None:
        return {"value": f3, "order": None, "error_abs": SAFETY * max(abs(d1), abs(d2)), "extrapolated": f3}
    p = min(max(p_obs if order is None else order, 0.5), 2.0)
    est = abs(d2) / (r32 ** p - 1.0)
    return {"value": f3, "order": p_obs, "error_abs": SAFETY * est, "extrapolated": f3 - math.copysign(est, d2)}


def pooled_orders(rows: list[dict]) -> dict:
    """Median observed order of force and moment over the monotone sequences of a sweep's rows,
    clipped to [0.5, 2] (the assumed orders where no sequence is monotone)."""
    out = {}
    for name, key in (("force", "force_levels_n"), ("moment", "moment_levels_nm")):
        ps = [observed_order(r[key], r["ndofs_levels"]) for r in rows if name == "force" or r["tilt_rad"] != 0.0]
        ps = [p for p in ps if p is not None]
        out[name] = float(min(max(np.median(ps), 0.5), 2.0)) if ps else ASSUMED_ORDERS[name]
    return out


def apply_orders(row: dict, orders: dict) -> dict:
    """A dataset row with its error estimates (and extrapolations) recomputed for ``orders``."""
    out = dict(row)
    rf = richardson3(row["force_levels_n"], row["ndofs_levels"], orders["force"])
    rm = richardson3(row["moment_levels_nm"], row["ndofs_levels"], orders["moment"])
    out["force_error_rel"] = rf["error_abs"] / abs(row["force_n"]) if row["force_n"] else 0.0
    out["force_extrapolated_n"] = rf["extrapolated"]
    if row["tilt_rad"] != 0.0 and row["moment_nm"] != 0.0:
        out["moment_error_rel"] = rm["error_abs"] / abs(row["moment_nm"])
        out["moment_extrapolated_nm"] = rm["extrapolated"]
    return out

"""A calibrated law against the FEM it was fitted to

The paper's conformal law assumes a pin in an infinite plate; clamped 10 mm rings are far stiffer.
``contact.calibrate`` fits, per FEM boundary-condition scene, the law with the fewest parameters the
data justify. For the ``clamped`` scene it is a Winkler elastic foundation (Johnson 1985, §4.3) with
one modulus ``k_f``: ``P = k_f R l e (ε − sin ε cos ε)``, ``e = δ0 + Δr``, ``cos ε = δ0/e``.

This example loads the stored law, evaluates it at the Table 2 penetrations and sets it beside the
committed 2D FEM reference (``fem_reference/data/fem2d-reference.json``) and the paper's law. The
test checks the law against the closed form above and the FEM within the errors published in
``reports/published/accuracy-table2.md`` (calibrated, fit on all points: at most 0.27 %).
"""
from __future__ import annotations

import numpy as np

from contact.calibrate import load_calibrated
from contact.dataset import read_dataset
from contact.laws import conformal_force
from fem_reference.plane.sweep import DATASET_PATH

PENETRATIONS_M = np.array([0.01, 0.02, 0.03, 0.04, 0.05]) * 1e-3


def compare(scene: str = "clamped") -> dict:
    """Forces (N) of the calibrated law, the FEM and the paper's conformal law at ``PENETRATIONS_M``."""
    law = load_calibrated(scene)
    data = read_dataset(DATASET_PATH, kind="2d")
    by_pen = {round(p["penetration_m"], 12): p["force_n"] for p in data.select(scene=scene)}
    g = law.geometry
    paper = conformal_force(PENETRATIONS_M, clearance_m=g.clearance_m, width_m=g.width_m, bearing_E_Pa=g.bearing_E_Pa,
                            bearing_nu=g.bearing_nu, support_E_Pa=g.support_E_Pa, support_nu=g.support_nu)
    return {"law": law,
            "calibrated_N": law.force(PENETRATIONS_M, strict=True).force_N,
            "fem_N": np.array([by_pen[round(p, 12)] for p in PENETRATIONS_M]),
            "conformal_N": paper.require_in_domain()}


def main():
    """Print the comparison; return the figure (FEM, calibrated and conformal forces)."""
    import matplotlib.pyplot as plt
    r = compare()
    law = r["law"]
    print(f"{law.name}: family {law.family}, parameters {law.parameters} ({law.parameter_units})")
    print("Δr (mm)   FEM (N)   calibrated (N)  error (%)   conformal law (N)")
    for p, f, c, k in zip(PENETRATIONS_M * 1e3, r["fem_N"], r["calibrated_N"], r["conformal_N"]):
        print(f"{p:7.2f} {f:10.0f} {c:14.0f} {100 * (c - f) / f:10.2f} {k:16.0f}")
    fig, ax = plt.subplots(figsize=(6, 3.6), layout="constrained")
    mm = PENETRATIONS_M * 1e3
    ax.plot(mm, r["fem_N"] / 1e3, "ko", label="2D FEM reference")
    ax.plot(mm, r["calibrated_N"] / 1e3, "-", label=f"calibrated ({law.family})")
    ax.plot(mm, r["conformal_N"] / 1e3, "--", label="conformal law (paper)")
    ax.set(xlabel="penetration Δr (mm)", ylabel="contact force (kN)", title=f"Scene {law.name}: law against FEM")
    ax.legend()
    return fig


if __name__ == "__main__":
    main()

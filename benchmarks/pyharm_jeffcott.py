"""The Jeffcott rotor in a conformal ring, modelled in pyHarm-os (a peer harmonic-balance code, never a dependency).

Run ONLY inside pyHarm's own venv, by benchmarks/bench_hb.py: ``python pyharm_jeffcott.py params.json out.json``.
It imports nothing of this project. The model: one node with (y, z), mass, damping and shaft stiffness as pyHarm's
own linear elements, the unbalance m e Ω² as two forcings of second order in the frequency, and the ring as an
element written here against pyHarm's element API (a ``NodeToNodeElement`` with AFT residual and analytic Jacobian):
the tilt-ignored conformal line contact of Dai et al. (2025) Eq. 5, radial force ``l0 h(|r| − δ0)`` towards the
centre, with the constants the project computes for the same rotor (passed in the JSON). The Lankarani–Nikravesh
factor is left out: it is 1 on every circular orbit (zero radial velocity), so the HB solution with one harmonic
is the same. Continuation in frequency by pyHarm's FRF analysis (tangent predictor, arc-length corrector). CPU
time: ``time.process_time()`` around the analysis (building the model and jax's compilation outside, reported apart).
"""
import json
import math
import sys
import time

import numpy as np


def law(pen, p):
    """Force per unit length h (N/m) and dh/dpen of the conformal law (project's contact/_kernel.py, law code 0)."""
    d0, c3, alpha, beta = p["clearance_m"], p["c3"], p["alpha"], p["beta"]
    q = 2.0 * d0 + pen
    s = pen / q
    ds = 2.0 * d0 / (q * q)
    D = 2.0 - (1.0 - alpha) * (np.log1p(s) + 2.0 * s * s) + beta * s * (1.0 + s)
    dD = -(1.0 - alpha) * (1.0 / (1.0 + s) + 4.0 * s) + beta * (1.0 + 2.0 * s)
    g = s * (1.0 + s) / D
    dg = ((1.0 + 2.0 * s) * D - s * (1.0 + s) * dD) / (D * D)
    return c3 * g, c3 * dg * ds


def make_ring_class():
    from pyHarm.Elements.NodeToNodeElements.NodeToNodeElement import NodeToNodeElement

    class RingContact(NodeToNodeElement):
        factory_keyword: str = "RingContact"

        def __post_init__(self):
            self.p = self.data["law"]

        def __flag_update__(self):
            self.flag_nonlinear = True
            self.flag_AFT = True

        def adim(self, lc, wc):
            raise NotImplementedError("no adimensionalisation")

        def _samples(self, xg):
            x = xg[self.indices]
            rel = self.Pslave - self.Pmaster
            return x, [(self.Pdir[d] @ rel @ x) @ self.D["ft"] for d in range(2)], rel

        def evalResidual(self, xg, om):
            x, (y, z), rel = self._samples(xg)
            r = np.sqrt(y * y + z * z)
            pen = np.maximum(r - self.p["clearance_m"], 0.0)
            h, _ = law(pen, self.p)
            f = np.where(r > self.p["clearance_m"], self.p["width_m"] * h, 0.0)
            rs = np.where(r > 0, r, 1.0)
            R = np.zeros(len(x))
            for d, comp in enumerate((y, z)):
                R += rel.T @ self.Pdir[d].T @ ((f * comp / rs) @ self.D["tf"])
            self.R = R
            return R

        def evalJacobian(self, xg, om):
            x, (y, z), rel = self._samples(xg)
            r = np.sqrt(y * y + z * z)
            on = r > self.p["clearance_m"]
            pen = np.maximum(r - self.p["clearance_m"], 0.0)
            h, dh = law(pen, self.p)
            f, df = np.where(on, self.p["width_m"] * h, 0.0), np.where(on, self.p["width_m"] * dh, 0.0)
            rs = np.where(r > 0, r, 1.0)
            ny, nz = y / rs, z / rs
            # d(f n_i)/d(u_j) = df n_i n_j + f (δ_ij − n_i n_j)/r
            blocks = [[df * a * b + f * ((1.0 if i == j else 0.0) - a * b) / rs for j, b in enumerate((ny, nz))]
                      for i, a in enumerate((ny, nz))]
            J = np.zeros((len(x), len(x)))
            for i in range(2):
                for j in range(2):
                    J += rel.T @ self.Pdir[i].T @ ((self.D["ft"] * blocks[i][j]) @ self.D["tf"]) @ self.Pdir[j] @ rel
            self.J, self.dJdom = J, np.zeros(len(x))
            return self.J, self.dJdom

    return RingContact


def run_frf(data: dict, repeat: int = 2):
    """pyHarm's analysis "frf" of ``data`` run ``repeat`` times, each from a new Maestro (the first run compiles
    pyHarm's kernels: jax, numba): ``(CPU s of each run, [[ω, x] of each accepted point of the last run])``."""
    from pyHarm.Maestro import Maestro
    cpus = []
    for _ in range(int(repeat)):
        m = Maestro(data)
        c0 = time.process_time()
        m.operate()
        cpus.append(time.process_time() - c0)
    out = [[float(np.asarray(s.x)[-1]), [float(v) for v in np.asarray(s.x)[:-1]]]
           for s in m.nls["frf"].SolList if getattr(s, "flag_accepted", True)]
    return cpus, out


def main(params_path, out_path):
    p = json.load(open(params_path))
    ring = make_ring_class()
    w_lo, w_hi = p["speed0_rad_s"], p["speed1_rad_s"]
    sub = {"rotor": [0]}
    data = {
        "plugin": [ring],
        "system": {"type": "Base", "nh": 1, "nti": p["n_time"]},
        "substructures": {"rotor": {"type": "onlydofs", "nnodes": 1, "ndofs": 2}},
        "connectors": {
            "shaft": {"type": "LinearSpring", "connect": dict(sub), "dirs": [0, 1], "k": p["stiffness_N_m"]},
            "damper": {"type": "LinearDamper", "connect": dict(sub), "dirs": [0, 1], "k": p["damping_N_s_m"]},
            "mass": {"type": "GOElement", "connect": dict(sub), "dirs": [0, 1], "dto": 2, "xo": 1, "k": p["mass_kg"]},
            "unbalance_y": {"type": "GOForcing", "connect": dict(sub), "dirs": [0], "dto": 2, "ho": 1, "phi": 0.0,
                            "amp": p["mass_kg"] * p["eccentricity_m"]},
            "unbalance_z": {"type": "GOForcing", "connect": dict(sub), "dirs": [1], "dto": 2, "ho": 1,
                            "phi": math.pi / 2, "amp": p["mass_kg"] * p["eccentricity_m"]},
            "ring": {"type": "RingContact", "connect": dict(sub), "dirs": [0, 1], "law": p["law"]},
        },
        "analysis": {"frf": {"study": "frf", "puls_inf": w_lo, "puls_sup": w_hi, "ds0": p["ds0"], "ds_max": p["ds_max"],
                             "ds_min": 1e-8, "sign_ds": 1, "verbose": False}},
    }
    cpus, out = run_frf(data, p.get("repeat", 2))
    w = np.array([o[0] for o in out])
    d = np.diff(w)
    folds = [float(w[i]) for i in range(1, len(d)) if d[i - 1] * d[i] < 0]
    from importlib.metadata import version
    json.dump({"cpu_s": cpus[-1], "cold_cpu_s": cpus[0], "points": out, "folds": folds,
               "version": version("pyHarm-os")}, open(out_path, "w"))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])

"""The Jeffcott rotor in a conformal ring ON A SUPPORT NODE (rotor/periodic/jeffcott_scene.py's physics), modelled in
pyHarm-os (a peer harmonic-balance code, never a dependency).

Run ONLY inside pyHarm's own venv, by benchmarks/bench_hb_scenes.py: ``python pyharm_jeffcott_ring.py params.json
out.json``. It imports nothing of this project but its sibling benchmarks/pyharm_jeffcott.py (the conformal law and
the ring element written against pyHarm's element API). Two substructures of one node (y, z) each: the disk (mass,
damping, the station's stiffness k, the unbalance as two second-order forcings) and the support node (m_s, c_s, k_s
to ground), the ring between them. One harmonic, pyHarm's FRF continuation; CPU time ``time.process_time()``
around the analysis (the first run in the process compiles and is reported apart).
"""
import json
import math
import sys

from pyharm_jeffcott import make_ring_class, run_frf


def _node(sub, m, c, k):
    con = {"connect": {sub: [0]}, "dirs": [0, 1]}
    return {f"{sub}_k": {"type": "LinearSpring", **con, "k": k}, f"{sub}_c": {"type": "LinearDamper", **con, "k": c},
            f"{sub}_m": {"type": "GOElement", **con, "dto": 2, "xo": 1, "k": m}}


def main(params_path, out_path):
    p = json.load(open(params_path))
    me = p["mass_kg"] * p["eccentricity_m"]
    rot = {"connect": {"rotor": [0]}, "dto": 2, "ho": 1, "amp": me}
    data = {
        "plugin": [make_ring_class()],
        "system": {"type": "Base", "nh": 1, "nti": p["n_time"]},
        "substructures": {"rotor": {"type": "onlydofs", "nnodes": 1, "ndofs": 2},
                          "support": {"type": "onlydofs", "nnodes": 1, "ndofs": 2}},
        "connectors": {
            **_node("rotor", p["mass_kg"], p["damping_N_s_m"], p["stiffness_N_m"]),
            **_node("support", p["support_mass_kg"], p["support_damping_N_s_m"], p["support_stiffness_N_m"]),
            "unbalance_y": {"type": "GOForcing", **rot, "dirs": [0], "phi": 0.0},
            "unbalance_z": {"type": "GOForcing", **rot, "dirs": [1], "phi": math.pi / 2},
            "ring": {"type": "RingContact", "connect": {"rotor": [0], "support": [0]}, "dirs": [0, 1], "law": p["law"]},
        },
        "analysis": {"frf": {"study": "frf", "puls_inf": p["speed0_rad_s"], "puls_sup": p["speed1_rad_s"],
                             "ds0": p["ds0"], "ds_max": p["ds_max"], "ds_min": 1e-8, "sign_ds": 1, "verbose": False}},
    }
    cpus, out = run_frf(data, p.get("repeat", 2))
    from importlib.metadata import version
    json.dump({"cpu_s": cpus[-1], "cold_cpu_s": cpus[0], "points": out, "version": version("pyHarm-os")},
              open(out_path, "w"))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])

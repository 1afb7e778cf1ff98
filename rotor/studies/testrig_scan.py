"""Can the Table 5 test rig's loose support slip (and so reach its clearance) within the paper's stated rig data?

Dai et al. (2025) §6 run the rig at speed steps near its first two critical speeds (3 319 and 5 184 rpm, Fig. 21;
steps 3 600 and 5 500 rpm, Figs. 25–26), with the clearance δ0 0.01 and 0.05 mm (Fig. 27) and the misalignment δ
1 and 3 mm (Fig. 28; Table 5: 2 mm), preload N = 10 000 N (Table 5), and report harmonics that need the ring to
move in its bore. The ring reaches the bore only once an end face slips (rotor/studies/stick_margin.py), so the
question is whether the stuck state's face demand reaches ``μN`` anywhere in those ranges. :func:`scan` computes the
demand over speed (:data:`SPEEDS_RPM`) for every stated misalignment, under each reading of the inputs Table 5
leaves out (:data:`VARIANTS`: the frame moving or not, the front shaft fitted to the paper's critical speeds; the
Eq. 34 placements of rotor.model.assembly with the rig's sleeve and a sleeve with Table 4's ×21.95 moment factor).
The clearance does not enter (nothing touches while stuck); μ = 0.3 is Table 4's (Table 5 gives none); the
damping is the scene's assumed 200 N s/m. Records: :class:`ScanPoint`.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

SCENE = "paper-table5-testrig"
#: the speeds scanned (rpm): the scene's range (max_speed_rpm 8 000) in 10 rpm steps, both critical speeds inside
SPEEDS_RPM = tuple(float(s) for s in range(300, 8001, 10))
#: the misalignments the paper states for the rig (mm): Fig. 28's 1 and 3, Table 5's 2
MISALIGNMENTS_MM = (1.0, 2.0, 3.0)
#: Table 5's preload (N)
PRELOAD_N = 10000.0
#: the front-shaft diameter (mm) at which the rig's disk-1 critical speed is the paper's 5 184 rpm with the frame
#: not moving (reports/published/rotor-testrig.md, case C; the disk-2 mode then at 3 221 rpm against 3 319)
FITTED_FRONT_SHAFT_MM = 15.4
#: Eq. 34 placements (rotor.model.scene.MISALIGNMENT_EXCITATIONS)
PLACEMENTS = ("inertial-at-joint", "opposed-at-joint", "opposed-at-centring-surfaces")
#: the sleeve: the rig's (m_sp 0.5 kg, L 30 mm: scene) and one 2.8 times as long (m_sp and L × 2.8, m_sp L² × 21.95,
#: the factor Table 4's chosen reading carries, rotor/studies/readings.py)
SLEEVES = {"rig sleeve": 1.0, "sleeve x2.8": 2.8}


def _frame_still(scene):
    s0 = scene.supports[0]
    return dataclasses.replace(scene, supports=(dataclasses.replace(s0, mass_kg=1e-3, inertia_kg_m2=1e-6),)
                               + scene.supports[1:])


def _front_shaft(scene, d_mm: float):
    front = {("1", "2"), ("2", "3a")}
    sh = tuple(dataclasses.replace(s, outer_diameter_m=d_mm * 1e-3) if (s.start, s.end) in front
               else s for s in scene.shafts)
    return dataclasses.replace(scene, shafts=sh)


#: the readings of what Table 5 leaves out: name -> (what it assumes, scene -> scene)
VARIANTS = {
    "A as bundled": ("the scene: the 15 kg frame moves on k3 = 2e6 N/m (paper Eq. 52)", lambda s: s),
    "B frame still": ("k3 from the bearing to ground, the frame's mass not moving (rotor-testrig.md case B: the "
                      "disk-2 mode at 3 317 rpm)", _frame_still),
    "C criticals fitted": (f"B with the front shaft {FITTED_FRONT_SHAFT_MM:g} mm (case C: 3 221 / 5 184 rpm)",
                           lambda s: _front_shaft(_frame_still(s), FITTED_FRONT_SHAFT_MM)),
}


@dataclass(frozen=True)
class ScanPoint:
    """One operating point of the scan: the reading, δ (mm), speed (rpm) and the stuck state's face demand (N)."""
    variant: str
    placement: str
    sleeve: str
    misalignment_mm: float
    speed_rpm: float
    peak_face_force_N: float
    static_face_force_N: float
    limit_N: float

    @property
    def ratio(self) -> float:
        return self.peak_face_force_N / self.limit_N


def variant_scene(variant: str, placement: str, sleeve: str, damping_factor: float = 1.0):
    """The rig's scene under one reading of what Table 5 leaves out; ``damping_factor`` (–) scales the assumed
    lateral damping of every bearing and of the frame (Table 5 gives none)."""
    from rotor.model.scene import load_scene

    sc = VARIANTS[variant][1](load_scene(SCENE))
    if damping_factor != 1.0:
        sc = dataclasses.replace(
            sc, bearings=tuple(dataclasses.replace(b, damping_n_s_m=b.damping_n_s_m * damping_factor) for b in sc.bearings),
            supports=tuple(dataclasses.replace(b, damping_n_s_m=b.damping_n_s_m * damping_factor) for b in sc.supports))
    f = SLEEVES[sleeve]
    mis = sc.misalignment
    cps = tuple(dataclasses.replace(c, shaft_mass_kg=c.shaft_mass_kg * f, lever_m=c.lever_m * f)
                if c.name == mis.coupling else c for c in sc.couplings)
    return dataclasses.replace(sc, couplings=cps, misalignment=dataclasses.replace(mis, excitation=placement))


def scan_case(variant: str, placement: str, sleeve: str, misalignment_mm: float, speeds_rpm=SPEEDS_RPM,
              preload_n: float | None = None, mu: float | None = None, damping_factor: float = 1.0) -> list[ScanPoint]:
    """:class:`ScanPoint` at every speed of one reading and misalignment (``preload_n`` (N), ``mu`` (–): None keeps
    Table 5's 10 000 N and the scene's μ)."""
    from rotor.dynamics.build import at_speed, system_from_model
    from rotor.model.assembly import assemble
    from rotor.studies.stick_margin import stick_margin

    sc = variant_scene(variant, placement, sleeve, damping_factor)
    base = system_from_model(assemble(sc), sc, 1000 * math.pi / 30, misalignment_m=misalignment_mm * 1e-3,
                             preload_N=PRELOAD_N if preload_n is None else preload_n, mu=mu)            # the rig has no speed-table bearing: one build
    out = []
    for rpm in speeds_rpm:
        m = stick_margin(at_speed(base, rpm * math.pi / 30), n_samples=64)
        out.append(ScanPoint(variant, placement, sleeve, misalignment_mm, float(rpm), m.peak_face_force_N,
                             m.static_face_force_N, m.limit_N))
    return out


def scan(speeds_rpm=SPEEDS_RPM, preload_n: float | None = None, mu: float | None = None,
         damping_factor: float = 1.0) -> list[ScanPoint]:
    """Every reading (:data:`VARIANTS` × :data:`PLACEMENTS` × :data:`SLEEVES`) × :data:`MISALIGNMENTS_MM` × speeds."""
    out = []
    for v in VARIANTS:
        for p in PLACEMENTS:
            for s in SLEEVES:
                for d in MISALIGNMENTS_MM:
                    out += scan_case(v, p, s, d, speeds_rpm, preload_n, mu, damping_factor)
    return out


def largest(points) -> dict:
    """``{(variant, placement, sleeve, δ mm): the ScanPoint with the largest demand}``."""
    best: dict = {}
    for p in points:
        k = (p.variant, p.placement, p.sleeve, p.misalignment_mm)
        if k not in best or p.peak_face_force_N > best[k].peak_face_force_N:
            best[k] = p
    return best


def slip_preload_n(point: ScanPoint, mu: float) -> float:
    """The preload (N) below which the point's faces would slip (its peak demand over μ)."""
    return point.peak_face_force_N / mu


#: the variant whose disk-2 critical speed is nearest the paper's (C) and the case the scene carries
SLIP_CHECK = ("C criticals fitted", "opposed-at-joint", "rig sleeve", 2.0)


def slip_check_speed(points) -> float:
    """The speed (rpm) of the largest face demand of :data:`SLIP_CHECK` in a scan: where the fitted rig is nearest
    to slipping, run through the nonlinear steady state by ``study testrig``."""
    return largest(points)[SLIP_CHECK].speed_rpm


def write_variant_scene(folder) -> "Path":
    """The scene of :data:`SLIP_CHECK` as ``folder``/paper-table5-testrig-C.toml (a scene file run_point can load)."""
    from pathlib import Path

    from contact.files import atomic_write_text
    from rotor.model.scene_toml import scene_to_toml

    sc = dataclasses.replace(variant_scene(*SLIP_CHECK[:3]), name="paper-table5-testrig-C",
                             title="Table 5 rig, frame still, front shaft fitted (rotor-testrig.md case C)")
    return atomic_write_text(Path(folder) / "paper-table5-testrig-C.toml", scene_to_toml(sc))

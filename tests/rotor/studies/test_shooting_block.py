"""Shooting studies in contiguous speed blocks (rotor.studies.shooting_block): per-speed keys, warm starts
from the lower neighbour, resume of a deleted point from its stored neighbour, and the same orbits as
:func:`rotor.studies.orbit.cascade` over the same block.

The scene is the damped Jeffcott rotor of tests/reports/test_orbit_cli.py (the bundled ``verify-jeffcott``
with a steel shaft and bearings of 300 N s/m): one periodic orbit per speed, found warm or cold.
"""
from __future__ import annotations

import numpy as np
import pytest

from rotor.studies import shooting_block as sb
from rotor.studies.orbit import cascade
from sweep import ResultStore, load_sweep, point_tasks, run_sweep

OPTIONS = {"steps_per_rev": 256}
SPEEDS = [1000.0, 1500.0, 2000.0, 2500.0, 3000.0]
BLOCKS = [[1000.0, 1500.0, 2000.0], [2500.0, 3000.0]]       # block_speeds = 3: the last block is shorter


@pytest.fixture(scope="module")
def scene(damped_jeffcott_scene) -> str:
    return damped_jeffcott_scene(300)


@pytest.fixture(scope="module")
def study(scene, tmp_path_factory):
    """The five speeds as two block tasks, run once; the store and its points."""
    tasks = sb.shooting_block_tasks(scene, SPEEDS[::-1], options=OPTIONS, block_speeds=3)   # order given: any
    store = tmp_path_factory.mktemp("study") / "out"
    s = run_sweep(tasks, store, max_workers=2, progress=False, log=lambda m: None)
    assert not s.failed, s.failed
    return tasks, store, load_sweep(store, tasks, complete=True)


def test_partition_fixed_by_the_speeds_each_speed_under_its_own_key(study):
    tasks, _, pts = study
    assert [t.params["block_rpm"] for t in tasks] == BLOCKS
    assert sorted(pts) == sorted(f"rpm{s:.1f}" for s in SPEEDS)
    assert [t.key for t in point_tasks(tasks)] == [f"rpm{s:.1f}" for s in SPEEDS]
    for p in pts.values():
        assert p.params["method"] == "shooting" and p.params["speed_rpm"] in p.params["block_rpm"]
        assert p.info["classified_by"] == "multipliers" and p.info["classification"] == "periodic"


def test_started_from_cold_at_each_block_start_else_the_lower_neighbour(study):
    _, _, pts = study
    got = {p.params["speed_rpm"]: p.info["started_from"] for p in pts.values()}
    assert got == {1000.0: "cold", 1500.0: 1000.0, 2000.0: 1500.0, 2500.0: "cold", 3000.0: 2500.0}


def test_the_same_orbits_as_orbit_cascade_over_each_block(scene, study):
    _, _, pts = study
    for block in BLOCKS:
        for res in cascade(scene, block, steps_per_rev=OPTIONS["steps_per_rev"]):
            info = pts[f"rpm{res.speed_rpm:.1f}"].info
            assert info["newton_iterations"] == res.newton_iterations
            scale = np.max(np.abs(res.q_m))
            assert np.max(np.abs(np.array(info["phase0_q_m"]) - res.q_m)) <= 1e-12 * scale
            amps = pts[f"rpm{res.speed_rpm:.1f}"].arrays["harm_v"]           # (5, c) m/s
            ref = np.array(list(res.velocity_amplitudes_mm_s_1X_to_5X.values())).T * 1e-3
            assert np.max(np.abs(np.abs(amps) - ref)) <= 1e-9 * np.max(ref)


def test_resume_recomputes_only_the_deleted_point_from_its_stored_neighbour(study):
    tasks, store, pts = study
    before = pts["rpm2000.0"]
    ResultStore(store).json_path("rpm2000.0").unlink()
    s = run_sweep(tasks, store, max_workers=1, progress=False, log=lambda m: None)
    assert s.computed == ["rpm2000.0"] and len(s.reused) == 4 and not s.failed
    after = ResultStore(store).load("rpm2000.0", before.params)
    assert after.info["started_from"] == 1500.0
    a, b = np.abs(after.arrays["harm_v"]), np.abs(before.arrays["harm_v"])
    assert np.max(np.abs(a - b)) <= 1e-9 * np.max(b)
    s = run_sweep(tasks, store, max_workers=1, progress=False, log=lambda m: None)
    assert not s.computed and len(s.reused) == 5                 # every block stored: skipped


def test_failed_speed_falls_back_and_the_next_starts_cold(scene, monkeypatch):
    from dataclasses import replace
    real = sb.orbit

    def failing_at_1500(scene_, speed_rpm, **kw):
        res = real(scene_, speed_rpm, **kw)
        return replace(res, converged=False) if speed_rpm == 1500.0 else res

    monkeypatch.setattr(sb, "orbit", failing_at_1500)
    out = sb.run_shooting_block(scene, BLOCKS[0], options=OPTIONS)
    info = {k: v[1] for k, v in out.items()}
    assert info["rpm1500.0"]["classified_by"] == "transient fallback" and "phase0_q_m" not in info["rpm1500.0"]
    assert info["rpm1500.0"]["started_from"] == 1000.0 and info["rpm2000.0"]["started_from"] == "cold"

"""A sweep point by shooting (rotor.studies.shooting_point) gives the transient point's arrays plus Floquet fields.

The scene is a damped Jeffcott rotor (the bundled ``verify-jeffcott`` with a steel shaft and bearings of 3 000 N s/m
damping, so that the transient settles well within its cap; with 300 N s/m the transient record still carries
1e-3 of decaying free vibration):
linear, one periodic orbit per speed, so the transient steady state (:func:`run_point`) converges to the orbit
shooting finds and the two must agree to the transient detector's tolerance (1e-4 of the amplitude).
"""
from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from rotor.studies import shooting_point as sp
from rotor.periodic.floquet import floquet
from rotor.studies.steady_state import run_point

OPTIONS = {"steps_per_rev": 256, "max_revs": 1500}


@pytest.fixture(scope="module")
def scene(damped_jeffcott_scene) -> str:
    return damped_jeffcott_scene(3000)


def test_shooting_point_has_the_transient_arrays_and_agrees(scene):
    a, info = sp.run_shooting_point(scene, 1500.0, options=OPTIONS)
    b, _ = run_point(scene, 1500.0, options=OPTIONS)
    assert a.keys() == b.keys()
    for k in a:
        assert np.shape(a[k]) == np.shape(b[k]), k
    va, vb = np.abs(a["harm_v"]), np.abs(b["harm_v"])
    assert np.max(np.abs(va - vb) / vb[0]) < 1e-4          # the same orbit (transient tolerance 1e-4)
    assert info["classification"] == "periodic" and info["classified_by"] == "multipliers"
    assert info["stable"] and info["shooting_converged"] and info["converged"] and info["period_revs"] == 1
    assert max(abs(complex(*m)) for m in info["multipliers"]) < 1.0
    json.dumps(info)                                          # a sweep record must be JSON


def test_zero_speed_is_the_static_point(scene):
    _, info = sp.run_shooting_point(scene, 0.0, options=OPTIONS)
    assert info["static"] and info["classified_by"] == "static"


def test_failed_shooting_falls_back_to_the_transient_and_says_so(scene, monkeypatch):
    real = sp.orbit

    def failing(*args, **kw):
        return replace(real(*args, **kw), converged=False)

    monkeypatch.setattr(sp, "orbit", failing)
    a, info = sp.run_shooting_point(scene, 1500.0, options=OPTIONS)
    b, ref = run_point(scene, 1500.0, options=OPTIONS)
    assert info["classified_by"] == "transient fallback" and info["classification"] == "periodic"
    assert info["multipliers_note"].startswith("last Newton iterate")
    assert np.array_equal(a["harm_v"], b["harm_v"]) and info["transient_revs"] == ref["transient_revs"]
    _, info = sp.run_shooting_point(scene, 1500.0, options=OPTIONS, fallback=False)
    assert info["classification"] == "no_orbit_found" and info["classified_by"] == "none"


@pytest.mark.parametrize("mu,expected", [((0.5, 0.3), "periodic"), ((1.2, 0.3), "unstable_fold"),
                                         ((-1.2, 0.3), "period_doubling"), ((1.1j, 0.3), "quasi_periodic")])
def test_classification_follows_the_multiplier_that_leaves(mu, expected):
    first, second = mu
    if isinstance(first, complex):     # a complex pair of modulus 1.1 as a real 2x2 rotation-scaling block
        r, th = abs(first), 0.7
        M = np.zeros((3, 3))
        M[:2, :2] = r * np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
        M[2, 2] = second
    else:
        M = np.diag([first, second])
    assert sp.classify(floquet(M, 0.01)) == expected


def test_shooting_tasks_are_not_the_transient_tasks(scene):
    from rotor.studies.steady_state import sweep_tasks
    t_s = sp.shooting_sweep_tasks(scene, [1500.0], options=OPTIONS)
    t_t = sweep_tasks(scene, [1500.0], options=OPTIONS)
    assert t_s[0].key == t_t[0].key and t_s[0].params != t_t[0].params   # a transient run dir is stale for shooting

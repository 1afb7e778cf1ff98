"""The tilt correction of a calibrated law (contact/calibrate/tilt_correction.py, tilt_fit.py; compiled in
contact/_kernel_tilt.py): the kernel is the numpy surface, its Jacobian is exact, its limits are built in, a law without
a correction is unchanged, the law file keeps it, and on the 20 mm ring it holds out (issue 37, must-show 3)."""
from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from contact import calibrate as cal
from contact.calibrate import spline
from contact.calibrate import tilt_correction as tc
from contact.calibrate import tilt_fit
from contact.dataset import document_sha256, read_dataset
from contact.errors import DatasetError, InputError
from contact.loose_support import N_PARAMS, TILT_SLOT, loose_support_force, point_force_jacobian
from contact.units import ARCMIN

ROOT = Path(__file__).resolve().parents[2]
RING = ROOT / "reports" / "published" / "law-family-newcomer-20mm"
GRID = ROOT / "reports" / "published" / "law-tilt-correction"


def _published(name="newcomer-20mm-law.json", folder=RING):
    return cal.CalibratedLaw.from_json((folder / name).read_text(encoding="utf-8"))


def _foundation():
    """A shipped law of the foundation family (contact/calibrated/clamped-3d-foundation.json: the 3D Table 1 ring,
    where the foundation family meets issue 37's target; the steel-in-aluminium run's law, this case's example before,
    is a foundation-spline since the selection rule became target-first)."""
    law = _published("clamped-3d-foundation.json", ROOT / "contact" / "calibrated")
    assert law.family == "foundation"
    return law


def _random_correction(law, seed=1):
    """A correction with random (smooth enough) coefficients, the force's zero-tilt constraint kept."""
    rng = np.random.default_rng(seed)
    shape = (tc.MAX_XI_INTERVALS + 1, tc.MAX_PSI_INTERVALS + 1)
    f = rng.normal(0, 0.05, shape)
    f[:, 0] = -0.5 * f[:, 1]
    g = law.geometry
    c = tc.TiltCorrection(math.log(law.validity_penetration_m[0]),
                          math.log(math.hypot(law.validity_penetration_m[1], 8 * ARCMIN * g.width_m / 2)), f,
                          rng.normal(0.05, 0.05, shape))
    return dataclasses.replace(law, name=law.name + "-tilt", parameters={**law.parameters, **c.to_parameters()}), c


def _states(law, n, seed=2, inside=False):
    rng = np.random.default_rng(seed)
    g = law.geometry
    pen = np.exp(rng.uniform(math.log(6e-7), math.log(2.9e-5), n))
    ang, ax = rng.uniform(0, 2 * math.pi, n), rng.uniform(0, 2 * math.pi, n)
    t = rng.uniform(0.05, 8, n) * ARCMIN
    rad = g.clearance_m + (pen - 0.5 * g.width_m * t if inside else pen)
    return rad * np.cos(ang), rad * np.sin(ang), t * np.cos(ax), t * np.sin(ax)


@pytest.mark.parametrize("family_law", ["spline", "foundation"])
def test_kernel_is_the_numpy_surface(family_law):
    law = _published() if family_law == "spline" else _foundation()
    lawt, c = _random_correction(law)
    g = law.geometry
    pen = np.geomspace(law.validity_penetration_m[0], law.validity_penetration_m[1], 7)[:, None]
    t = np.array([0.3, 1.0, 2.0, 4.0, 8.0])[None, :] * ARCMIN
    pen, t = (np.array(v) for v in np.broadcast_arrays(pen, t))
    plain = loose_support_force(law.loose_support_params(), g.clearance_m + pen, 0.0, 0.0, t)
    corr = loose_support_force(lawt.loose_support_params(), g.clearance_m + pen, 0.0, 0.0, t)
    a, b = c.evaluate(pen.ravel() + 0.5 * g.width_m * t.ravel(), t.ravel(), g.width_m)
    np.testing.assert_allclose(np.ravel(corr.Fy_N), np.ravel(plain.Fy_N) * np.exp(a), rtol=1e-13)
    np.testing.assert_allclose(np.ravel(corr.Mz_Nm), np.ravel(plain.Mz_Nm) * np.exp(b), rtol=1e-13)
    assert np.ptp(a) > 0.01 and np.ptp(b) > 0.01            # the correction is not a constant


@pytest.mark.parametrize("inside", [False, True])
def test_jacobian_is_exact(inside):
    """∂(F, M)/∂(y, z, θy, θz) against central differences, one-point (outside the clearance) and two-point states."""
    law, _ = _random_correction(_published())
    p = law.loose_support_params()
    y, z, thy, thz = _states(law, 40, seed=3, inside=inside)
    jac = np.empty((4, 8))
    worst = 0.0
    for k in range(y.size):
        u = np.array([y[k], z[k], thy[k], thz[k]])
        point_force_jacobian(*u, 0.0, 0.0, 0.0, 0.0, p.kernel_args, jac)
        for j, step in enumerate((1e-11, 1e-11, 1e-9, 1e-9)):
            du = np.zeros(4)
            du[j] = step
            fp = np.array(point_force_jacobian(*(u + du), 0.0, 0.0, 0.0, 0.0, p.kernel_args, np.empty((4, 8))))
            fm = np.array(point_force_jacobian(*(u - du), 0.0, 0.0, 0.0, 0.0, p.kernel_args, np.empty((4, 8))))
            fd = (fp - fm) / (2 * step)
            scale = np.abs(jac[:, j]).max() + 1e-300
            worst = max(worst, float(np.abs(fd - jac[:, j]).max() / scale))
    assert worst < 1e-6, worst


def test_zero_tilt_limit_parity_and_smoothness():
    law = _published()
    lawt, _ = _random_correction(law)
    g = law.geometry
    pen = np.geomspace(6e-7, 2.9e-5, 9)
    p0, pt = law.loose_support_params(), lawt.loose_support_params()
    straight = loose_support_force(pt, g.clearance_m + pen, 0.0, 0.0, 0.0)
    assert np.array_equal(straight.Fy_N, loose_support_force(p0, g.clearance_m + pen, 0.0, 0.0, 0.0).Fy_N)
    assert np.all(np.abs(straight.Mz_Nm) < 1e-12 * np.abs(straight.Fy_N) * g.width_m)
    th = 3 * ARCMIN
    plus = loose_support_force(pt, g.clearance_m + pen, 0.0, 0.0, th)
    minus = loose_support_force(pt, g.clearance_m + pen, 0.0, 0.0, -th)
    np.testing.assert_allclose(minus.Fy_N, plus.Fy_N, rtol=1e-12)          # force even in θ
    np.testing.assert_allclose(minus.Mz_Nm, -plus.Mz_Nm, rtol=1e-12)       # moment odd
    # the correction is even in θ to second order at a fixed mid-plane penetration (zero slope across φ = 0): its
    # log on the force, and on the moment less its zero-tilt value, quarter when θ halves (tilts outside the edge
    # transition's band, where the kernel blends both edges: θ l0 > 0.1 µm)
    lawc = _random_correction(law)[1]
    for pm in (1e-5, 2.5e-5):
        th = 8e-5 / 2.0 ** np.arange(4)
        fc, fp = (loose_support_force(q, g.clearance_m + pm, 0.0, 0.0, th) for q in (pt, p0))
        a = np.log(fc.Fy_N / fp.Fy_N)
        b = np.log(fc.Mz_Nm / fp.Mz_Nm) - lawc.evaluate(pm, 0.0, g.width_m)[1]
        for v in (a, b):
            assert np.all(np.abs(v) > 1e-9) and np.all(np.abs(v[:-1] / v[1:] - 4.0) < 0.4), v


def _every_knot_slot():
    """The published 20 mm law refitted on its own force at as many penetrations as the kernel has knot slots
    (contact._kernel.SPLINE_MAX_KNOTS): every slot of the fixed-index spline copy in use."""
    law = _published()
    pen = np.geomspace(*law.validity_penetration_m, spline.MAX_KNOTS)
    fit = cal.fit_family(spline.FAMILY, pen, law.force(pen).force_N, law.geometry)
    assert fit.n_parameters == spline.MAX_KNOTS
    return dataclasses.replace(law, name=law.name + "-every-knot", parameters=fit.parameters)


@pytest.mark.parametrize("family_law", ["spline", "spline-every-knot", "foundation"])
def test_a_zero_correction_is_the_law_bit_for_bit(family_law):
    """A long tuple whose correction is zero runs the fixed-slot copies of the law and the slices
    (contact._kernel_tilt.law_fixed, slices_fixed) and must give the law's own numbers exactly, Jacobian included."""
    law = {"spline": _published, "spline-every-knot": _every_knot_slot, "foundation": _foundation}[family_law]()
    lawt, _ = _random_correction(law)
    args = list(lawt.loose_support_params().kernel_args)
    args[TILT_SLOT + 4:] = [0.0] * (len(args) - TILT_SLOT - 4)
    short = law.loose_support_params().kernel_args
    assert len(short) == N_PARAMS and len(args) > N_PARAMS
    for inside in (False, True):
        y, z, thy, thz = _states(law, 60, seed=5, inside=inside)
        j1, j2 = np.empty((4, 8)), np.empty((4, 8))
        for k in range(y.size):
            f1 = point_force_jacobian(y[k], z[k], thy[k], thz[k], 1e-3, -2e-3, 0.1, 0.2, short, j1)
            f2 = point_force_jacobian(y[k], z[k], thy[k], thz[k], 1e-3, -2e-3, 0.1, 0.2, tuple(args), j2)
            assert f1 == f2 and np.array_equal(j1, j2)


def _resigned(doc):
    doc.pop("sha256")
    doc["sha256"] = document_sha256(doc)
    return json.dumps(doc)


def test_law_file_round_trip_and_refusals():
    lawt, c = _random_correction(_published())
    back = cal.CalibratedLaw.from_json(lawt.to_json(), "t.json")
    np.testing.assert_allclose(back.loose_support_params().kernel_args, lawt.loose_support_params().kernel_args,
                               rtol=1e-11)
    doc = json.loads(lawt.to_json())
    for key, value, says in (("tilt_force_01", 1.0, "vanish at zero tilt"), ("tilt_psi_intervals", 5, "must be 6"),
                             ("tilt_bogus", 1.0, "unknown"), ("tilt_log_r_hi", -20.0, "tilt_log_r_lo must be <")):
        bad = json.loads(json.dumps(doc))
        bad["parameters"][key] = value
        with pytest.raises(DatasetError, match=says):
            cal.CalibratedLaw.from_json(_resigned(bad), "t.json")
    power = json.loads(json.dumps(doc))
    power["family"] = "power"
    power["parameters"] = {"coefficient_N_per_m_pow_n_plus_1": 1e12, "exponent": 1.2, **c.to_parameters()}
    with pytest.raises(DatasetError, match="slice-integrated"):
        cal.CalibratedLaw.from_json(_resigned(power), "t.json")


def test_the_rotor_refuses_a_law_with_a_correction_instead_of_dropping_it():
    from rotor.dynamics.kernels import support_law_from_params

    lawt, _ = _random_correction(_published())
    with pytest.raises(InputError, match="tilt correction"):
        support_law_from_params(lawt.loose_support_params())
    support_law_from_params(_published().loose_support_params())         # the law without one: accepted


def test_held_out_on_the_20mm_ring_force_and_moment():
    """Fitted on the training grid (its zero-tilt points for the straight law, its tilted ones for the correction),
    every committed 3D point of the ring that is not a training point is within 2x its stated FEM error + 0.2 %,
    force and moment; the published law (slices alone) is not, on the same points."""
    train = read_dataset(GRID / "fem3d-tilt-train-newcomer-20mm.json")
    straight, _ = cal.calibrate_scene(train, "newcomer-20mm", families=("foundation-spline",))
    law = tilt_fit.with_tilt_correction(straight, [p for p in train.points if p["tilt_rad"] > 0
                                                   and p["penetration_m"] > 0])
    keys = {(round(p["penetration_m"] * 1e12), round(p["tilt_rad"] * 1e12)) for p in train.points}
    held = [p for p in read_dataset(RING / "fem3d-newcomer-20mm.json").points
            if (round(p["penetration_m"] * 1e12), round(p["tilt_rad"] * 1e12)) not in keys]
    assert sum(p["tilt_rad"] > 0 for p in held) >= 16
    after, before = tilt_fit.held_out(law, held), tilt_fit.held_out(_published(), held)
    for q, b in (("force_error", "bound_force"), ("moment_error", "bound_moment")):
        assert np.all(np.abs(after[q]) <= after[b]), (q, after[q], after[b])
    assert np.any(np.abs(before["moment_error"]) > before["bound_moment"])
    zero = [p for p in held if p["tilt_rad"] == 0]
    f = law.force(np.array([p["penetration_m"] for p in zero])).force_N
    err = f / np.array([p["force_n"] for p in zero]) - 1
    assert np.all(np.abs(err) <= 2 * np.array([p["force_error_rel"] for p in zero]) + 0.002)


def _surface_points(seed=3):
    """Edge penetrations (m) and tilts (rad) spread over a correction's box, and a rough target on them."""
    rng = np.random.default_rng(seed)
    law = _published()
    g = law.geometry
    mid = np.exp(rng.uniform(math.log(6e-7), math.log(2.9e-5), 200))
    t = rng.uniform(0.2, 8, 200) * ARCMIN
    return law, mid + 0.5 * g.width_m * t, t, rng.normal(0.0, 0.05, 200)


def test_each_smoothing_weight_acts_along_its_own_direction():
    """The pair (along ξ, along ψ): a huge weight along one direction makes the fitted coefficients straight along
    it (second differences nil) and leaves the other direction free; one number is that number in both directions,
    bit for bit."""
    law, pe, t, y = _surface_points()
    w = law.geometry.width_m
    ones = np.full(y.size, 0.002)

    def moment_coefficients(smoothing):
        return tc.fit(pe, t, w, y, y, ones, ones, smoothing=smoothing).moment_coefficients

    along_xi, along_psi = moment_coefficients((1e8, 1e-6)), moment_coefficients((1e-6, 1e8))
    scale = np.abs(along_xi).max() + np.abs(along_psi).max()
    assert np.abs(np.diff(along_xi, 2, axis=0)).max() < 1e-6 * scale           # straight in ξ
    assert np.abs(np.diff(along_xi, 2, axis=1)).max() > 1e-3 * scale           # not in ψ
    assert np.abs(np.diff(along_psi, 2, axis=1)).max() < 1e-6 * scale
    assert np.abs(np.diff(along_psi, 2, axis=0)).max() > 1e-3 * scale
    assert np.array_equal(moment_coefficients(1e-2), moment_coefficients((1e-2, 1e-2)))
    for bad in (-1.0, (1e-3,), (1e-3, float("nan")), (1e-3, 1e-3, 1e-3), "0.01"):
        with pytest.raises(InputError, match="smoothing"):
            tc.fit(pe, t, w, y, y, ones, ones, smoothing=bad)


def test_choose_smoothing_searches_every_pair_of_weights():
    """The cross-validation covers every (along ξ, along ψ) pair of the grid, labelled one number when both are
    alike, and the pick is the pair of smallest worst held-out error over its bound."""
    train = read_dataset(GRID / "fem3d-tilt-train-newcomer-20mm.json")
    straight, _ = cal.calibrate_scene(train, "newcomer-20mm", families=("foundation-spline",))
    data = tilt_fit.log_ratios(straight, [p for p in train.points if p["tilt_rad"] > 0 and p["penetration_m"] > 0])
    chosen, cv = tilt_fit.choose_smoothing(straight, data)
    grid = tilt_fit.SMOOTHING_GRID
    assert len(cv) == len(grid) ** 2
    assert {f"{s:g}" for s in grid} <= set(cv) and tilt_fit.smoothing_label((grid[0], grid[1])) in cv
    assert cv[tilt_fit.smoothing_label(chosen)] == min(cv.values())
    assert chosen[0] in grid and chosen[1] in grid


def test_the_20mm_ring_s_verification_grid_holds_and_the_psi_weight_made_its_miss():
    """Issue 37, must-show 3: fitted on the training grid, every tilted point of the verification grid (penetrations
    between the training ones, other tilts) is within 2x its stated FEM error + 0.2 %, force and moment. With one
    weight for both directions (0.01, what that rule picks here) the moment at 12.78 µm and 7′ is not; lowering the
    weight along ψ alone brings it inside, lowering the one along ξ alone does not."""
    train = read_dataset(GRID / "fem3d-tilt-train-newcomer-20mm.json")
    straight, _ = cal.calibrate_scene(train, "newcomer-20mm", families=("foundation-spline",))
    tilted = [p for p in train.points if p["tilt_rad"] > 0 and p["penetration_m"] > 0]
    verify = [p for p in read_dataset(GRID / "fem3d-tilt-verify-newcomer-20mm.json").points if p["penetration_m"] > 0]
    law = tilt_fit.with_tilt_correction(straight, tilted)
    h = tilt_fit.held_out(law, verify)
    assert h["tilt_rad"].size == 48
    for q, b in (("force_error", "bound_force"), ("moment_error", "bound_moment")):
        assert np.all(np.abs(h[q]) <= h[b]), (q, h[q], h[b])
    point = [p for p in verify if abs(p["penetration_m"] - 12.78e-6) < 1e-9 and abs(p["tilt_rad"] - 7 * ARCMIN) < 1e-9]
    assert len(point) == 1

    def moment_over_bound(smoothing):
        r = tilt_fit.held_out(tilt_fit.with_tilt_correction(straight, tilted, smoothing=smoothing), point)
        return abs(r["moment_error"][0]) / r["bound_moment"][0]

    assert moment_over_bound((1e-2, 1e-2)) > 1.0
    assert moment_over_bound((1e-2, 1e-4)) < 0.6
    assert moment_over_bound((1e-4, 1e-2)) > 1.0

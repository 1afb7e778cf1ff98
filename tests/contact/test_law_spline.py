"""The flexible law family ``foundation-spline`` (contact/calibrate/spline.py): its knot slopes, its fit and
hold-out, its law file, and the compiled kernel's law code 3 (contact/_kernel.py) against the Python form.

Sources: the Fritsch–Carlson (1980) slopes as scipy's ``PchipInterpolator`` implements them; the force and its
analytic Jacobian checked against the Python law and central differences.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.interpolate import PchipInterpolator

from contact import calibrate as cal
import contact.calibrate.spline as spline
from contact.errors import DatasetError
from contact.loose_support import loose_support_force, loose_support_jacobian

GEO = cal.SceneGeometry(clearance_m=3e-5, width_m=0.02, radius_m=0.045, bearing_thickness_m=0.005,
                        support_thickness_m=0.02, bearing_E_Pa=210e9, bearing_nu=0.3, support_E_Pa=70e9,
                        support_nu=0.33, plane="3d")
PEN = np.geomspace(5e-7, 3e-5, 10)


def _curve(pen):
    """A rising force no analytic family follows: the foundation law times a slow bend in log Δr."""
    u = np.log(np.asarray(pen) / 4e-6)
    return 1.2e13 * cal.family_force("foundation", {"foundation_modulus_Pa_per_m": 1.0}, pen, GEO) \
        * np.exp(0.12 * u - 0.05 * u ** 2)


def _law(pen=PEN):
    fit = cal.fit_family(spline.FAMILY, pen, _curve(pen), GEO)
    units = {k: "-" for k in fit.parameters}
    return fit, cal.CalibratedLaw(name="t-foundation-spline", scene="t", family=spline.FAMILY,
                                  parameters=fit.parameters, parameter_std=fit.parameter_std, parameter_units=units,
                                  geometry=GEO, validity_penetration_m=(float(pen[0]), float(pen[-1])), dataset={})


def test_knot_slopes_are_scipys_pchip():
    rng = np.random.default_rng(7)
    x = np.sort(rng.uniform(-14, -10, 9))
    y = np.cumsum(rng.uniform(-0.3, 1.0, 9))          # not monotone: the limiter's sign cases too
    np.testing.assert_allclose(spline.pchip_slopes(x, y), PchipInterpolator(x, y).derivative()(x), rtol=1e-12,
                               atol=1e-12)
    xq = np.linspace(x[0], x[-1], 57)
    np.testing.assert_allclose(spline.hermite(x, y, spline.pchip_slopes(x, y), xq)[0], PchipInterpolator(x, y)(xq),
                               rtol=1e-12, atol=1e-12)


def test_spline_holds_where_no_analytic_family_does():
    f = _curve(PEN)
    fits = {fam: cal.fit_family(fam, PEN, f, GEO) for fam in cal.FAMILIES}
    assert np.max(np.abs(fits[spline.FAMILY].fit_rel_err)) < 1e-12          # through its knots
    assert np.max(np.abs(fits[spline.FAMILY].holdout_rel_err[1:-1])) < 0.01        # interpolated
    assert cal.family_holds(fits[spline.FAMILY].holdout_rel_err, 0.0)                 # the ends extrapolated
    assert not any(cal.family_holds(fits[k].holdout_rel_err, 0.0) for k in cal.ANALYTIC_FAMILIES)
    assert cal.select_family(list(fits.values())).family == spline.FAMILY
    assert spline.rises(fits[spline.FAMILY].parameters)


def test_the_spline_within_the_target_wins_where_the_flag_bound_chose_power():
    """Issue 37's generated pairs 6, 17, 21, 23 and 27 (reports/published/law-family.md): power held the flag bound,
    missed the target, and was chosen. Here a power law with a slow bend (16 points, 2-20 um, FEM error 0.05 %):
    power (2 parameters) is 1.06 % off held out, within the flag bound but not the target (0.3 %); the spline
    (16 knots, every point) is 0.18 % off. The fewest parameters among the families that hold would be power; the rule takes the
    spline, and its reason says so."""
    pen = np.geomspace(2e-6, 2e-5, 16)
    f = 1e10 * GEO.width_m * pen ** 1.2 * np.exp(0.01 * np.log(pen / math.sqrt(2e-6 * 2e-5)) ** 2)
    fem = np.full(pen.size, 5e-4)
    fits = {fam: cal.fit_family(fam, pen, f, GEO) for fam in cal.FAMILIES}
    power, flex = fits["power"], fits[spline.FAMILY]
    holding = [x for x in fits.values() if cal.family_holds(x.holdout_rel_err, fem)]
    assert min(holding, key=lambda x: (x.n_parameters, x.holdout_max)) is power         # the flag bound's choice
    assert not cal.meets_target(power.holdout_rel_err, fem) and power.holdout_max > 0.01
    assert cal.meets_target(flex.holdout_rel_err, fem) and flex.holdout_max < 0.002 and flex.n_parameters == 16
    assert cal.select_family(list(fits.values()), fem) is flex
    from contact.calibrate.fit import selection_reason
    reason = selection_reason(list(fits.values()), flex, fem)
    assert reason.startswith(f"foundation-spline met the target (16 parameters, held-out max {100 * flex.holdout_max:.3f} %)")
    assert f"power ({100 * power.holdout_max:.3f} %)" in reason and reason.endswith("no other family meets it")


def test_a_correction_that_would_make_the_force_fall_is_left_out():
    f = _curve(PEN)
    f[5] = f[4] * 1.0001                              # a plateau: the correction's slope drops below -1
    fit = cal.fit_family(spline.FAMILY, PEN, f, GEO)
    assert not np.isfinite(fit.holdout_rel_err).any()


def test_more_points_than_knots_keeps_the_others_held_out():
    pen = np.geomspace(5e-7, 3e-5, spline.MAX_KNOTS + 5)
    # a bend no cubic follows exactly (the not-a-knot spline reproduces _curve's quadratic correction everywhere)
    fit = cal.fit_family(spline.FAMILY, pen, _curve(pen) * np.exp(0.05 * np.tanh(np.log(pen / 4e-6))), GEO)
    assert fit.n_parameters == spline.MAX_KNOTS
    knots = spline.knot_indices(pen.size)
    assert np.all(np.abs(fit.fit_rel_err[knots]) < 1e-12)
    assert np.count_nonzero(np.abs(fit.fit_rel_err) > 1e-12) == 5


def test_law_file_round_trip_and_refusals():
    _, law = _law()
    back = cal.CalibratedLaw.from_json(law.to_json(), "t.json")
    np.testing.assert_allclose(back.force(PEN).force_N, law.force(PEN).force_N, rtol=1e-10)
    doc = json.loads(law.to_json())
    for key, value, says in (("knot_count", 1, "knot_count"), ("log_penetration_03", doc["parameters"]
                                                                 ["log_penetration_02"], "rise strictly")):
        bad = json.loads(law.to_json())
        bad["parameters"][key] = value
        bad.pop("sha256")
        from contact.dataset import document_sha256
        bad["sha256"] = document_sha256(bad)
        with pytest.raises(DatasetError, match=says):
            cal.CalibratedLaw.from_json(json.dumps(bad), "t.json")


def test_kernel_code_3_is_the_python_law_straight_and_tilted():
    _, law = _law()
    p = law.loose_support_params()
    pen = np.geomspace(1e-7, 6e-5, 9)             # below, inside and beyond the knots
    r = loose_support_force(p, GEO.clearance_m + pen, 0 * pen, 0 * pen, 0 * pen)
    np.testing.assert_allclose(-r.Fy_N, law.force_per_length(pen) * GEO.width_m, rtol=1e-12)
    for arcmin in (2.0, 8.0):
        th = arcmin * math.pi / 10800
        for q in (5e-7, 4e-6, 3e-5):
            fs, ms, _ = law.tilted(q, th)
            rk = loose_support_force(p, GEO.clearance_m + q, 0.0, 0.0, th)
            # the kernel's 8 Gauss points per patch against 48 (the spline is C1 only, across its knots)
            assert -float(rk.Fy_N) == pytest.approx(fs, rel=3e-4)
            assert float(rk.Mz_Nm) == pytest.approx(ms, rel=3e-4)


def test_kernel_code_3_jacobian_is_the_derivative():
    _, law = _law()
    p = law.loose_support_params(c_c_s_per_m=50.0)
    for x0 in ([GEO.clearance_m + 4e-6, 1e-6, 1e-4, 3e-4, 0.01, -0.02, 0.1, 0.2],
               [GEO.clearance_m + 2e-7, 1e-7, 0.0, 1.5e-4, 1e-3, 0.0, 0.0, 0.0]):
        x0 = np.array(x0)
        _, J = loose_support_jacobian(p, *x0)
        steps = (1e-10, 1e-10, 1e-8, 1e-8, 1e-6, 1e-6, 1e-5, 1e-5)
        fd = np.column_stack([(loose_support_jacobian(p, *(x0 + h * e))[0] - loose_support_jacobian(p, *(x0 - h * e))[0])
                              / (2 * h) for h, e in zip(steps, np.eye(8))])
        assert np.max(np.abs(J - fd)) < 1e-6 * np.max(np.abs(J))


def _stiffening(pen, width=0.2):
    """A force that stiffens sharply inside its range: the foundation law times a correction rising by 4 in ln over
    a band of about ±2 ``width`` in ln Δr about 20 µm (the shape of issue 37's generated pair 29, seed 2755664993,
    reports/published/law-family-pairs/seed-2755664993-pair-29.json)."""
    u = np.log(np.asarray(pen) / 2e-5)
    return 1e13 * cal.family_force("foundation", {"foundation_modulus_Pa_per_m": 1.0}, pen, GEO) \
        * np.exp(4.0 / (1.0 + np.exp(-u / width)))


def test_a_resolved_curve_needs_no_refinement():
    """A correction straight in ln Δr (the foundation law times a power): both interpolants are exact, no doubt."""
    pen = np.geomspace(1e-5, 8e-5, 12)
    base = cal.family_force("foundation", {"foundation_modulus_Pa_per_m": 1.0}, pen, GEO)
    f = 1e13 * base * (pen / pen[0]) ** 0.3
    assert spline.unsure_intervals(pen, f, base).max() < 1e-12
    assert spline.refinement(pen, f, base, 5e-4).size == 0


def test_refinement_at_the_thirds_of_the_doubtful_intervals_resolves_a_stiffening():
    """Closed-form truth (:func:`_stiffening`): 12 geometric points miss their 11 midpoints by up to 0.2 %; the
    refinement adds two points at the thirds of the most doubtful intervals (never at a midpoint, at most
    MAX_KNOTS points in all), and the family refitted on them is within 0.06 % at every midpoint (measured while
    writing this test: 0.197 % before, 0.048 % after)."""
    pen = np.geomspace(1e-5, 8e-5, 12)
    mid = np.sqrt(pen[:-1] * pen[1:])
    base = cal.family_force("foundation", {"foundation_modulus_Pa_per_m": 1.0}, pen, GEO)
    doubt = spline.unsure_intervals(pen, _stiffening(pen), base)
    new = spline.refinement(pen, _stiffening(pen), base, 5e-4)
    assert new.size == 12 and pen.size + new.size == spline.MAX_KNOTS
    k = np.searchsorted(pen, new) - 1                     # each new point's interval
    x, xn = np.log(pen), np.log(new)
    frac = (xn - x[k]) / (x[k + 1] - x[k])
    assert np.allclose(frac, np.tile([1 / 3, 2 / 3], 6), atol=1e-12) and np.all(k[0::2] == k[1::2])
    refined = np.unique(k)
    assert set(refined) == set(np.argsort(-doubt)[:6]) and doubt[refined].min() > 5e-4

    def worst(train):
        fit = cal.fit_family(spline.FAMILY, train, _stiffening(train), GEO)
        return np.abs(cal.family_force(spline.FAMILY, fit.parameters, mid, GEO) / _stiffening(mid) - 1.0)

    before, after = worst(pen), worst(np.sort(np.concatenate([pen, new])))
    assert before.max() > 1.5e-3 and after.max() < 6e-4
    assert np.all(after[refined] < 0.2 * before[refined])


def test_knot_slopes_are_the_rule_that_predicts_the_left_out_knots_better_and_keeps_the_force_rising():
    """The family's slopes are the not-a-knot cubic spline's (scipy's ``CubicSpline``, de Boor 1978) or PCHIP's
    (Fritsch & Carlson 1980), whichever predicts the interior knots better left out one at a time
    (contact/calibrate/spline.py ``leave_one_out``): a smooth correction takes the not-a-knot slopes (exact on a
    quadratic); a step of 3 between two knots makes that spline overshoot to a slope below −1 (the force would
    fall), and the PCHIP slopes are stored whatever the leave-one-out says."""
    from scipy.interpolate import CubicSpline

    x = np.linspace(-12.0, -10.0, 10)
    smooth = 0.3 * (x + 12.0) ** 2
    assert spline.leave_one_out(x, smooth, spline.smooth_slopes) < 1e-12 < spline.leave_one_out(x, smooth,
                                                                                                  spline.pchip_slopes)
    p = spline.parameters(np.exp(x), np.exp(smooth), np.ones(10))
    np.testing.assert_allclose(spline.knots(p)[2], CubicSpline(x, smooth)(x, 1), rtol=1e-12, atol=1e-12)
    step = np.where(np.arange(10) >= 5, 3.0, 0.0)
    assert not spline.rises(spline._stored(x, step, spline.smooth_slopes(x, step)))
    p = spline.parameters(np.exp(x), np.exp(step), np.ones(10))
    np.testing.assert_array_equal(spline.knots(p)[2], spline.pchip_slopes(x, step))
    assert spline.rises(p)


def test_each_slope_rule_wins_on_the_published_points_where_it_predicts_better():
    """Real FEM points: the 20 mm ring's 13 zero-tilt training points (reports/published/law-tilt-correction/
    fem3d-tilt-train-newcomer-20mm.json) take PCHIP's slopes (left out: 0.30 % against the not-a-knot's 0.39 %, whose
    end overshoot put a verification point 0.056 % beyond its bound), and issue 37's generated pair 29 of seed
    2755664993 (reports/published/law-family-pairs/seed-2755664993-pair-29.json, a sharp stiffening) the
    not-a-knot ones (here on ln P itself, the pair's geometry being the benchmark's: 0.027 against 0.045 in ln; on
    the correction 2.7 % against 4.1 %, and at its 11 midpoints 0.25 % against 0.51 %)."""
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    law = cal.CalibratedLaw.from_json((root / "reports/published/law-family-newcomer-20mm/newcomer-20mm-law.json")
                                      .read_text(encoding="utf-8"))
    pts = sorted((p for p in json.loads((root / "reports/published/law-tilt-correction/"
                                                "fem3d-tilt-train-newcomer-20mm.json").read_text())["points"]
                  if p["tilt_rad"] == 0.0), key=lambda p: p["penetration_m"])
    pen = np.array([p["penetration_m"] for p in pts])
    f = np.array([p["force_n"] for p in pts])
    x = np.log(pen)
    y = np.log(f) - np.log(cal.family_force("foundation", {"foundation_modulus_Pa_per_m": 1.0}, pen, law.geometry))
    loo = {rule.__name__: spline.leave_one_out(x, y, rule) for rule in (spline.pchip_slopes, spline.smooth_slopes)}
    assert pen.size == 13 and loo["pchip_slopes"] == pytest.approx(0.0030, abs=1e-4) \
        and loo["smooth_slopes"] == pytest.approx(0.0039, abs=1e-4)
    data = json.loads((root / "reports/published/law-family-pairs/seed-2755664993-pair-29.json").read_text())
    pen29 = np.array([p["penetration_m"] for p in data["train"]])
    f29 = np.array([p["force_N"] for p in data["train"]])
    x29 = np.log(pen29)
    slope = np.diff(np.log(f29)) / np.diff(x29)                 # the stiffening: log slope 1.4 -> 5.8 -> 2.5
    assert slope[0] < 1.5 and slope.max() > 5.0 and slope[-1] < 3.0
    loo29 = {rule.__name__: spline.leave_one_out(x29, np.log(f29), rule)
             for rule in (spline.pchip_slopes, spline.smooth_slopes)}
    assert loo29["smooth_slopes"] == pytest.approx(0.027, abs=1e-3) and loo29["pchip_slopes"] == pytest.approx(
        0.045, abs=1e-3)

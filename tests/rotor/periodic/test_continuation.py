"""Pseudo-arclength continuation (rotor.periodic.continuation) over the Jeffcott verification rotor's whole
response curve, against its closed form (derived in rotor/periodic/jeffcott.py: ((k − mΩ'²) r + f(r − δ0))² +
(cΩ' r)² = (m e Ω²)², with the trapezoidal rule's warped frequency Ω' = Ω tan(π/N)/(π/N) in inertia and damping).

The rotor (JeffcottParams defaults): m = 1 kg, k = 1e5 N/m (ω_n = 316.2 rad/s), c = 31.62 N s/m (ζ = 0.05),
e = 20 µm, clearance δ0 = 10 µm, ring width 10 mm, Pereira et al. (2015) law with E = 10 MPa (f ∝ pen^1.25),
c_c = 50 s/m (inactive on a circle), N = 64 steps per revolution. Closed-form folds (warped): 623.645 rad/s
(r = 7.39 δ0, jump-up) and 726.368 rad/s (r = 45.5 δ0, jump-down); unwarped 624.336 and 727.172 rad/s."""
import math

import numpy as np
import pytest

from rotor.periodic.continuation import ContinuationOptions, continue_branch, parameter_problem, speed_problem
from rotor.periodic.jeffcott import (JeffcottParams, closed_form_folds, closed_form_radius, closed_form_speeds,
                                    contact_force_N, jeffcott_system, warped_frequency)
from rotor.periodic.shooting import shoot_from_transient

P = JeffcottParams()
N = 64
SCALES = np.concatenate([np.full(4, 1e-4), np.full(4, 0.06)])    # m, m/s: orbit radii up to ~4.6e-4 m


@pytest.fixture(scope="module", params=["auto", "fd"])
def branch(request):
    """150 → 900 rad/s from rest: lower-left, upper, middle (unstable), lower-right branches."""
    pb = speed_problem(lambda w: jeffcott_system(P, w), N, backend=request.param, modes0=(0, 0))
    return continue_branch(pb, np.zeros(8), 150.0, 900.0, scales=SCALES, lam_scale=100.0,
                           options=ContinuationOptions(ds=0.1, ds_max=0.4))


def _curve_distance(w, r):
    """Relative distance of (Ω, r) from the closed-form curve: the smaller of the speed error at fixed radius
    and the radius error at fixed speed (each well conditioned where the other is not: folds, peak)."""
    speeds = closed_form_speeds(P, r, N)
    d_w = float(np.min(np.abs(speeds - w)) / w) if len(speeds) else math.inf
    if d_w < 1e-7:
        return d_w
    return min(d_w, abs(closed_form_radius(P, w, r, N) - r) / r)


def test_branch_follows_the_closed_form_through_both_folds(branch):
    assert branch.stop == "end reached"
    w = branch.parameters()
    r = np.array([math.hypot(p.state[0], p.state[1]) for p in branch.points])
    worst = max(_curve_distance(wi, ri) for wi, ri in zip(w, r))
    assert worst < 1e-6
    # circular: speed Ω' r at every point
    speed = np.array([math.hypot(p.state[4], p.state[5]) for p in branch.points])
    assert np.allclose(speed, warped_frequency(w, N) * r, rtol=1e-6)
    # the curve is covered: from below the clearance to the top near 45 δ0, back down, and beyond the folds
    assert r.min() < P.clearance_m and r.max() > 44 * P.clearance_m and abs(w[-1] / 900.0 - 1) < 1e-12   # the last orbit at the end itself
    assert np.count_nonzero(np.diff(np.sign(np.diff(w)))) == 2            # speed turns twice: two folds


def test_fold_speeds_match_the_warped_closed_form(branch):
    folds = [b for b in branch.bifurcations if b.kind == "fold"]
    expected = closed_form_folds(P, N)
    assert len(folds) == 2
    got = sorted(b.parameter for b in folds)
    for g, (w_cf, _) in zip(got, expected):
        assert abs(g / w_cf - 1) < 1e-3                                # the must-show bound (0.1 %)
        assert abs(g / w_cf - 1) < 1e-7                                # what the located folds give
    unwarped = closed_form_folds(P)
    assert abs(got[0] / unwarped[0][0] - 1) > 5e-4                     # the warping is larger than the bound


def test_middle_branch_is_unstable_with_a_real_multiplier_above_one(branch):
    folds = sorted(b.index for b in branch.bifurcations if b.kind == "fold")
    i_down, i_up = folds                                                # jump-down fold first (upper branch end)
    middle = branch.points[i_down:i_up]
    assert len(middle) >= 5
    for p in middle:
        mu = p.floquet.multipliers
        real_above = mu[(np.abs(mu.imag) < 1e-9) & (mu.real > 1 + 1e-6)]
        assert len(real_above) == 1 and not p.floquet.stable
    # the upper branch (between the contact onset and the jump-down fold) is stable
    upper = [p for p in branch.points[:i_down] if math.hypot(*p.state[:2]) > 10 * P.clearance_m]
    assert len(upper) >= 5 and all(p.floquet.stable for p in upper)
    # the lower branch below the clearance is stable too (linear rotor, ζ = 0.05)
    assert all(p.floquet.stable for p in branch.points if math.hypot(*p.state[:2]) < P.clearance_m)


def test_neimark_sacker_on_the_lower_right_branch(branch):
    """Past the jump-up fold the lower branch has a complex pair outside the unit circle, found as a
    Neimark-Sacker point within 0.01 % of the fold; the branch's last point is still NS-unstable. In the frame
    whirling with the orbit the contact spring is stiffer radially (f') than tangentially (f/r), like an
    asymmetric shaft, which is unstable between its two critical speeds: a non-synchronous whirl grows."""
    ns = [b for b in branch.bifurcations if b.kind == "neimark_sacker"]
    w_up = closed_form_folds(P, N)[0][0]
    assert ns and all(abs(b.parameter / w_up - 1) < 1e-4 for b in ns)
    assert branch.points[-1].floquet.n_out_complex == 2


def _roots_in_radius(w, clearance_m):
    """Number of orbit radii of the warped closed form at speed w and clearance (sign changes of the
    residual on a 0.14 %-spaced logarithmic grid of radii, 1 µm to 1 mm)."""
    rs = np.geomspace(1e-6, 1e-3, 5000)
    wp = float(warped_frequency(w, N))
    f = contact_force_N(P, rs, clearance_m)
    g = ((P.stiffness_N_m - P.mass_kg * wp ** 2) * rs + f) ** 2 + (P.damping_N_s_m * wp * rs) ** 2 \
        - (P.mass_kg * P.eccentricity_m * w ** 2) ** 2
    return int(np.count_nonzero(np.diff(np.sign(g))))


def test_continuation_in_clearance_at_fixed_speed():
    """At 680 rad/s (between the speed folds) the clearance is the parameter, 6 to 40 µm: the branch stays on
    the closed form (1e-6; the Pereira law's exponent itself depends on the clearance) and turns twice; at
    each located fold the closed form's number of radii changes by two within ±0.1 % of the clearance."""
    w = 680.0
    pb = parameter_problem(lambda c: jeffcott_system(P, w, clearance_m=c), w, N, "clearance_m", modes0=(0, 0))
    start = shoot_from_transient(pb.flow(6e-6), np.zeros(4), np.zeros(4), steps_per_rev=N, period_revs=1,
                                 modes0=(0, 0))
    br = continue_branch(pb, start.state, 6e-6, 4e-5, scales=SCALES, lam_scale=1e-5,
                         options=ContinuationOptions(ds=0.1, ds_max=0.4))
    assert br.stop == "end reached"
    for p in br.points:
        r = math.hypot(*p.state[:2])
        speeds = closed_form_speeds(P, r, N, clearance_m=p.parameter)
        d = float(np.min(np.abs(speeds - w)) / w) if len(speeds) else math.inf
        if d >= 1e-6:
            d = abs(closed_form_radius(P, w, r, N, clearance_m=p.parameter) - r) / r
        assert d < 1e-6
    folds = [b.parameter for b in br.bifurcations if b.kind == "fold"]
    assert len(folds) == 2
    for c in folds:
        assert abs(_roots_in_radius(w, c * (1 - 1e-3)) - _roots_in_radius(w, c * (1 + 1e-3))) == 2
    mid = 0.5 * sum(folds)                       # between the folds: three radii, no change
    assert _roots_in_radius(w, mid * (1 - 1e-3)) == _roots_in_radius(w, mid * (1 + 1e-3)) == 3


@pytest.mark.slow
def test_period_doubling_on_table4_and_the_doubled_branch():
    """Table 4 rotor (Dai et al. 2025) with the former reading of Eq. 34 (scene paper-table4-inertial: the 150 mm
    sleeve, inertial-at-joint; paper-table4's reading since section5-readings.md has no doubling here) from
    10 600 rpm up, on the member of the stuck face's continuum that the
    transient settles on (rotor/periodic/shooting.py): the complex pair near −1 leaves the circle (Neimark–Sacker
    near 10 610 rpm), then meets the real axis outside it: a real multiplier passes −1 near 10 628 rpm. Past it the multiplier is checked with the
    finite-difference monodromy (no face mode change over the period there, so both derivatives are the
    scheme's). Branch switching gives orbits of two revolutions that are not of one: x(2T) = x(0) to 1e-9 of the
    orbit scale while x(T) − x(0) is above 1e-5 of it, 10⁴ times the periodicity tolerance (measured 2.6e-4 next
    to the crossing, growing away from it), starting within 0.05 % of the located speed.

    On the step-grid map (``locate_events=False``), where this doubling was found. With events located (the
    default) the same branch reports five crossings of −1 between 10 625 and 10 638 rpm: the real multiplier near
    −1 jumps from orbit to orbit along the speed (−0.913, −0.962, −0.938 at 10 600.4, 10 601.0, 10 601.9 rpm; −1.056,
    −1.018, −0.969, −1.050 at 10 629.7 to 10 631.6 rpm), each equal to central differences of the located map at
    1e-7 and 1e-8 to 1e-4 (measured), with no face mode change in the period: the slow-slip hold's decisions
    (rotor/dynamics/friction_events.py, "Slow slips") change with the speed, and the located map is only piecewise
    smooth in it."""
    from rotor.periodic.continuation import switch_period_doubling
    from rotor.studies.orbit import branch
    from rotor.periodic.period_flow import advance, make_flow, monodromy_fd
    from rotor.studies.steady_state import point_system

    b = branch("paper-table4-inertial", 10600.0, 10680.0, options=ContinuationOptions(max_points=20), amplitudes=False,
               locate_events=False)
    pds = [x for x in b.branch.bifurcations if x.kind == "period_doubling"]
    assert len(pds) == 1 and 10600 < pds[0].parameter * 30 / math.pi < 10680
    n, modes, scales = b.start.steps_per_rev, b.start.shooting.modes, b.start.shooting.scales
    after = b.branch.points[pds[0].index]
    sysm = point_system("paper-table4-inertial", after.parameter * 30 / math.pi)[2]
    flow_fd = make_flow(sysm, 2 * math.pi / after.parameter / n, "fd", locate_events=False)
    mu = np.linalg.eigvals(monodromy_fd(flow_fd, after.state, 0.0, n, modes))
    assert np.min(mu.real[np.abs(mu.imag) < 1e-9]) < -1.0
    pb = speed_problem(lambda w: point_system("paper-table4-inertial", w * 30 / math.pi)[2], n, modes0=modes,
                       locate_events=False)
    b2 = switch_period_doubling(pb, b.branch, pds[0], 10700 * math.pi / 30, scales=scales,
                                lam_scale=8 * math.pi / 30, options=ContinuationOptions(max_points=4))
    assert b2.period_revs == 2 and len(b2.points) >= 3
    assert abs(b2.points[1].parameter / pds[0].parameter - 1) < 5e-4
    for p in b2.points[1:]:
        fl = pb.flow(p.parameter)
        x1 = advance(fl, p.state, 0.0, n, modes, jacobian=False).state
        x2 = advance(fl, x1, n * fl.dt_s, n, modes, jacobian=False).state
        assert np.max(np.abs(x2 - p.state) / scales) < 1e-9
        assert np.max(np.abs(x1 - p.state) / scales) > 1e-5


def test_smooth_branch_needs_no_restart_and_its_scales_follow_the_orbit(branch):
    """The Jeffcott map has no switch (frictionless ring): the corrector alone covers the curve, no point
    comes from a shooting restart. On the upper branch the orbit (radius up to 46 δ0 = 4.6e-4 m, peak-to-peak
    9.2e-4 m) outgrows the given 1e-4 m scale more than twice, so the scales were renewed there: with the
    start's scales and no restarts (``follow_scales``/``pass_switches`` off) the same curve takes more points."""
    assert branch.restarts == 0 and not any(p.restarted for p in branch.points)
    pb = speed_problem(lambda w: jeffcott_system(P, w), N, modes0=(0, 0))
    plain = continue_branch(pb, np.zeros(8), 150.0, 900.0, scales=SCALES, lam_scale=100.0,
                            options=ContinuationOptions(ds=0.1, ds_max=0.4, pass_switches=False, follow_scales=False))
    assert plain.stop == "end reached" and len(plain.points) > len(branch.points)


def test_rescaled_jacobian_is_the_one_evaluated_in_the_new_scales():
    """``rescale`` transforms the scaled state, tangent and bordered Jacobian to new scales without a new
    map: they equal the evaluator's own at the same point in the new scales (to round-off)."""
    from rotor.periodic.branch_types import Evaluator
    from rotor.periodic.corrector import rescale

    pb = speed_problem(lambda w: jeffcott_system(P, w), N, modes0=(0, 0))
    ev = Evaluator(pb, SCALES.copy(), 100.0)
    x, lam = np.array([2e-5, 1e-5, 0, 0, -3e-3, 6e-3, 0, 0]), 500.0
    R, J, M = ev(x, lam)
    y = np.concatenate([x / ev.s, [lam / ev.ls]])
    tau = np.ones(9) / 3.0
    y2, tau2, J2 = rescale(ev, y, tau, M, J, 10.0 * SCALES)          # the floor forces new scales: 10 × SCALES
    assert np.allclose(ev.s, 10.0 * SCALES)
    assert np.allclose(y2[:-1] * ev.s, x, rtol=1e-14, atol=0) and y2[-1] == y[-1]
    assert np.isclose(np.linalg.norm(tau2), 1.0) and np.allclose(tau2[:-1] * ev.s / (tau2[-1] * ev.ls),
                                                                 tau[:-1] * SCALES / (tau[-1] * ev.ls))
    _, J_new, _ = ev(x, lam)
    assert np.allclose(J2, J_new, rtol=1e-9, atol=1e-12 * np.abs(J_new).max())


def _fake(lam, dlam_ds, restarted=False):
    from rotor.periodic.continuation import BranchPoint
    return BranchPoint(lam, np.zeros(2), None, 0, 0.0, dlam_ds, restarted)


def test_a_fold_is_reported_only_where_the_branch_turns():
    """The parameter components of the tangents change sign between points 2 and 3 in each case; only where
    the parameter also moves along them (up into point 2, down after point 3) is it a fold."""
    from rotor.periodic.branch_events import confirmed_folds
    from rotor.periodic.continuation import Bifurcation

    fold = [Bifurcation("fold", 3, 2.5, 1.0)]
    turns = [_fake(0.0, 1), _fake(1.0, 1), _fake(2.0, 0.5), _fake(2.1, -0.5), _fake(1.5, -1)]
    assert confirmed_folds(turns, fold) == fold
    goes_on = [_fake(0.0, 1), _fake(1.0, 1), _fake(2.0, 0.5), _fake(2.1, -0.5), _fake(2.5, 1)]   # a tangent turned
    assert confirmed_folds(goes_on, fold) == []
    last = turns[:4]                                                    # nothing after: not confirmed
    assert confirmed_folds(last, fold) == []
    # ... unless the branch stopped where its next predictor, along the last tangent, crossed to another piece of
    # the map (a grazing: the crossing goes on that way): the rotor 5 of random_family(2276323539) up, its fold 61 rpm
    # above its grazing fold, straddled by a segment's last two points
    assert confirmed_folds(last, fold, open_end=True) == fold
    assert confirmed_folds(goes_on, fold, open_end=True) == []         # an open end confirms only the last pair
    jump = turns[:3] + [_fake(2.1, -0.5, True)] + turns[4:]             # reached by a restart: no tangent to compare
    assert confirmed_folds(jump, fold) == []
    other = [Bifurcation("period_doubling", 3, 2.05, -1.0)]
    assert confirmed_folds(last, other) == other


def test_a_crossing_beyond_the_end_between_the_last_orbit_and_the_one_landed_back_from_is_dropped():
    """The branch steps from 990 to 1 010 past ``lam_end`` = 1 000 and lands back at 1 000 (point 7): a crossing of
    that step at 1 005 is beyond the end, one at 995 is not; crossings at earlier points stay wherever they lie, and
    a branch run downwards drops those below its end."""
    from rotor.periodic.continuation import Bifurcation, before_end

    at = lambda lam, index=7: Bifurcation("neimark_sacker", index, lam, 1j)     # noqa: E731
    assert before_end([at(980.0, 6), at(995.0), at(1005.0)], 7, 1000.0, 1.0) == [at(980.0, 6), at(995.0)]
    assert before_end([at(1005.0, 6)], 7, 1000.0, 1.0) == [at(1005.0, 6)]
    assert before_end([at(995.0), at(1005.0)], 7, 1000.0, -1.0) == [at(1005.0)]


def test_a_refinement_trial_on_another_stretch_of_the_branch_is_told():
    """Table 4 run at commit 9feddee: a crossing between orbits at 15 850 and 15 913 rpm was placed at 16 073 rpm, on
    a later stretch of the branch. Such a trial (parameter outside the two points by more than their distance, or
    farther than ``ds`` from its predictor) is told; one inside is not, nor a fold beyond both points."""
    from rotor.periodic.branch_events import _elsewhere

    a, b = _fake(15850.0, 1.0), _fake(15913.0, 1.0)
    at = lambda rpm, x=0.0: np.array([x, rpm / 10.0])      # noqa: E731  (scaled, parameter scale 10 rpm)
    pred = at(15880.0)
    assert not _elsewhere(at(15890.0), pred, 1e4, "neimark_sacker", a, b, 10.0)
    assert _elsewhere(at(16073.0), pred, 1e4, "period_doubling", a, b, 10.0)
    assert not _elsewhere(at(16073.0), pred, 1e4, "fold", a, b, 10.0)
    assert _elsewhere(at(15890.0, x=2.0), pred, 1.5, "neimark_sacker", a, b, 10.0)


def test_fold_estimate_is_the_vertex_of_the_parabola():
    """λ(σ) = 3 − (σ − 0.3)² (scaled, λ_s = 2): dλ/dσ = 0.6 at σ = 0 and −0.2 at σ = 0.4, the vertex at
    σ = 0.3 with λ = 3 · 2 = 6, above both points (λ(0) = 5.82, λ(0.4) = 5.98)."""
    from rotor.periodic.branch_events import fold_estimate

    a, b = _fake(2.0 * (3 - 0.09), 0.6), _fake(2.0 * (3 - 0.01), -0.2)
    got = fold_estimate(a, b, 0.4, 2.0)
    assert abs(got - 6.0) < 1e-12 and got > max(a.parameter, b.parameter)


def _with_multipliers(lam, mults, events, restarted=0):
    """A point at ``lam`` whose monodromy has the multipliers ``mults`` and ``events`` switches per period."""
    from rotor.periodic.continuation import BranchPoint
    from rotor.periodic.floquet import floquet
    return BranchPoint(lam, np.zeros(len(mults)), floquet(np.diag(mults), 0.01), 0, 0.0, 1.0, restarted, events)


def test_a_multiplier_crossing_where_the_switches_change_is_a_discontinuous_bifurcation():
    """Leine & van Campen (2002): where a stick/slip switch appears between two orbits the multipliers jump (a
    saltation), here −0.5 to −1.6; reported as "discontinuous" with both sides, not as the smooth kind. A crossing
    between orbits with the same switches keeps its kind."""
    from rotor.periodic.branch_events import bifurcations_between

    a = _with_multipliers(100.0, [0.3, -0.5], 4)
    b = _with_multipliers(101.0, [0.3, -1.6], 6, restarted=1)
    (bif,) = bifurcations_between(None, a, b, 1, None, None, 0.1, None, None)
    assert bif.kind == "discontinuous" and 100.0 < bif.parameter < 101.0
    assert "period doubling" in bif.detail and "0.5 -> 1.6" in bif.detail and "4 -> 6" in bif.detail
    (same,) = bifurcations_between(None, a, _with_multipliers(101.0, [0.3, -1.6], 4, 1), 1, None, None, 0.1, None,
                                   None)
    assert same.kind == "period_doubling" and same.detail == ""
    assert bifurcations_between(None, a, _with_multipliers(101.0, [0.3, 0.5], 6, 1), 1, None, None, 0.1, None,
                                None) == []      # no crossing: nothing, switches or not


def test_the_corrector_halves_a_step_whose_residual_grew():
    """On ``R(x) = sign(x)|x|^(1/3)`` (a cusp, as a map's derivative at a switch) plain Newton doubles the
    distance each step, ``x ← −2x``, and diverges; with halving the residual falls, the corrector gives up once
    its steps stall (each halved and leaving more than half of the merit, four in a row) instead of spending its
    12 iterations, and ``ev.failure`` says why it stopped."""
    from rotor.periodic.continuation import ContinuationOptions
    from rotor.periodic.corrector import correct

    class Cusp:
        s, ls, events, failure, seen = np.ones(1), 1.0, 0, "", []

        def __call__(self, x, lam, jacobian=True):
            r = np.cbrt(x)
            self.seen.append(float(abs(r[0])))
            d = 1.0 / (3.0 * np.cbrt(x[0]) ** 2)
            return r, np.array([[d, 0.0]]), None

    ev = Cusp()
    got = correct(ev, np.array([1.0, 0.0]), np.array([0.0, 1.0]), ContinuationOptions(max_iter=12))
    assert got is None and ev.failure.startswith("no convergence in ")
    assert int(ev.failure.split()[3]) < 12          # stalled: given up before max_iter
    assert ev.seen[-1] < 0.5 * ev.seen[0]          # plain Newton: 2^(1/3) larger at every step


def test_a_corrector_held_by_phase_rows_of_an_ended_continuum_converges_without_them():
    """``R(x, λ) = x − 1``: an isolated orbit at x = 1, with a phase row that holds x at the last point's 0 (the
    level of a stuck face's continuum that has ended: the faces slip). With the row the bordered system has no
    solution and the corrector fails; the retry without it lands on x = 1 and says so
    (rotor/periodic/continuation.py, ``_corrected``)."""
    from rotor.periodic.continuation import ContinuationOptions, _corrected
    from rotor.periodic.corrector import correct

    class Isolated:
        s, ls, events, failure = np.ones(1), 1.0, 0, ""

        def __call__(self, x, lam, jacobian=True):
            return x - 1.0, np.array([[1.0, 0.0]]), np.eye(1) * 0.0

    ev, stalls = Isolated(), []
    tau, y0 = np.array([0.0, 1.0]), np.array([0.0, 0.0])
    phase = np.array([[1.0, 0.0]])
    assert correct(Isolated(), y0, tau, ContinuationOptions(), phase, y0) is None      # the rows alone: no orbit
    y, *_ = _corrected(ev, y0, tau, ContinuationOptions(), phase, y0, stalls)
    assert abs(y[0] - 1.0) < 1e-9 and abs(y[1]) < 1e-12
    assert len(stalls) == 1 and "converged without the phase rows" in stalls[0]


def test_turn_back_follows_the_middle_branch_then_jumps_past_the_fold_as_a_run_up_does():
    """``turn_back``: past the jump-down fold (726.368 rad/s warped, closed form) the branch follows the unstable
    middle branch 30 rad/s back (0.3 of λ_s = 100 rad/s), then one restart lands on the lower-right branch just
    past the fold (the run-up's jump), whose radius is the closed form's there, and goes on to the end."""
    from rotor.periodic.branch_types import COLD, TRANSIENT
    pb = speed_problem(lambda w: jeffcott_system(P, w), N, modes0=(0, 0))
    br = continue_branch(pb, np.zeros(8), 150.0, 900.0, scales=SCALES, lam_scale=100.0,
                         options=ContinuationOptions(ds=0.1, ds_max=0.4, turn_back=0.3))
    assert br.stop == "end reached" and br.restarts == 1
    (k,) = [i for i, p in enumerate(br.points) if p.restarted]
    jump, before = br.points[k], br.points[k - 1]
    w_fold = closed_form_folds(P, N)[1][0]
    assert jump.restarted in (TRANSIENT, COLD) and 0.0 < jump.parameter - w_fold < 1.5         # 1 rad/s past the fold
    assert w_fold - 40.0 < before.parameter < w_fold - 29.0 and not before.floquet.stable   # the middle branch
    r = math.hypot(jump.state[0], jump.state[1])
    # the lower-right branch: below the jump-up fold's radius (7.39 δ0), far from the upper branch (~45 δ0 here)
    assert r < closed_form_folds(P, N)[0][1] and _curve_distance(jump.parameter, r) < 1e-6
    assert "turned back at a fold" in jump.why and any("restart (" in f[2] for f in br.failures)
    assert [b.kind for b in br.bifurcations] == ["fold"] and abs(br.bifurcations[0].parameter / w_fold - 1) < 1e-6


def test_the_corrector_goes_on_past_max_iter_only_while_it_contracts():
    """``R(x) = x − 1`` with a Jacobian ``c`` times too large: Newton's residual falls by ``1 − 1/c`` each
    iteration (an inexact Jacobian's linear rate, rotor/periodic/corrector.py ``EXTRA_ITERATIONS``). At 0.2 it
    needs 13 iterations to 1e-9 from 1: past ``max_iter`` = 10 it goes on and converges; at 0.8 (slower than
    ``CONTRACTION`` = 0.7) it stops at ``max_iter``."""
    from rotor.periodic.continuation import ContinuationOptions
    from rotor.periodic.corrector import CONTRACTION, correct

    class Inexact:
        s, ls, events, failure = np.ones(1), 1.0, 0, ""

        def __init__(self, c):
            self.c = c

        def __call__(self, x, lam, jacobian=True):
            return x - 1.0, np.array([[self.c, 0.0]]), np.zeros((1, 1))

    opts = ContinuationOptions(max_iter=10)
    got = correct(Inexact(1.25), np.zeros(2), np.array([0.0, 1.0]), opts)
    assert got is not None and 10 < got[3] <= 20 and abs(got[0][0] - 1.0) < 1e-8
    assert 1.0 - 1.0 / 5.0 > CONTRACTION
    slow = Inexact(5.0)
    assert correct(slow, np.zeros(2), np.array([0.0, 1.0]), opts) is None
    assert slow.failure.startswith("no convergence in 10 iterations")


def test_a_failed_corrector_is_retried_from_the_modes_its_iterate_ended_the_period_in():
    """Started with both faces stuck (modes (1, 1)) the map has no fixed point (``R = x² + 1``) and its iterates
    end the period with the right face slipping; started so (modes (0, 1)) it has one at x = 2, which ends the
    period in those modes: the retry lands there and the branch goes on with them
    (rotor/periodic/continuation.py ``_on_end_modes``). Where that orbit ends in other modes than it started
    from, it is no orbit of either map: refused, the modes kept."""
    from rotor.periodic.continuation import ContinuationOptions, _corrected

    class TwoMaps:
        s, ls, events, failure = np.ones(1), 1.0, 0, ""

        def __init__(self, end_of_slipping):
            self.modes0, self.modes_end, self.end_of_slipping = (1, 1), None, end_of_slipping

        def __call__(self, x, lam, jacobian=True):
            if self.modes0 == (1, 1):
                R, d, self.modes_end = x ** 2 + 1.0, 2.0 * x[0], (0, 1)
            else:
                R, d, self.modes_end = x - 2.0, 1.0, self.end_of_slipping
            return R, np.array([[d, 0.0]]), np.zeros((1, 1))

    tau, y0 = np.array([0.0, 1.0]), np.array([0.3, 0.0])
    ev, stalls = TwoMaps((0, 1)), []
    y, *_ = _corrected(ev, y0, tau, ContinuationOptions(), np.zeros((0, 2)), y0, stalls)
    assert abs(y[0] - 2.0) < 1e-9 and ev.modes0 == (0, 1)
    assert "right stuck, left stuck → right slipping, left stuck" in stalls[0]
    ev, stalls = TwoMaps((1, 1)), []
    assert _corrected(ev, y0, tau, ContinuationOptions(), np.zeros((0, 2)), y0, stalls) is None
    assert ev.modes0 == (1, 1) and stalls == [] and ev.failure.startswith("no ")

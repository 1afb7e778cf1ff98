"""The allocation-free forms inside the production step loop compute exactly what the forms they replace do.

The step loop (rotor/dynamics/production_loop.py) evaluates the slip force on scalars
(``production_kernels._slip_force_scalar``) and the law through ``kernels.contact_point``; its Newton solve
(``production_kernels._solve_support``) evaluates the condensed step on packed work arrays, staged in one
loop. Each is compared here, bit for bit, with the plain form: ``constraints.slip_force``,
``kernels.contact_kernel`` and ``production_kernels._forces``/``_residual``, at the states of a Table 4 run.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from rotor.dynamics import constraints as cons
from rotor.dynamics.kernels import contact_kernel, contact_point
from rotor.dynamics.production import prepare, simulate_production
from numba import njit

from rotor.dynamics.production_kernels import (MX, NC, VG, VX, _forces, _residual, _slip_force_scalar,
                                               _solve_support, matvec_into, newton_work)
from rotor.dynamics.system import NewmarkOptions


def _run(rpm: float):
    """Table 4 at ``rpm``, 6 revolutions at T/256 from the linear start."""
    from rotor.dynamics.initial import linear_initial_state
    from rotor.studies.steady_state import point_system

    _, _, system = point_system("paper-table4", rpm)
    dt = 2 * math.pi / system.omega_rad_s / 256
    q0, v0 = linear_initial_state(system, 0.0)
    return system, dt, simulate_production(system, dt, 6 * 256, q0, v0)


@pytest.fixture(scope="module")
def run():
    """15 000 rpm: impacts from the 4th revolution on, the faces slipping."""
    return _run(15000.0)


@pytest.fixture(scope="module")
def run_stuck():
    """4 500 rpm: no impact, the faces mostly stuck."""
    return _run(4500.0)


def test_slip_force_on_scalars_is_constraints_slip_force_bit_for_bit():
    rng = np.random.default_rng(7)
    speeds = np.concatenate([np.zeros((1, 2)), rng.normal(size=(200, 2)) * 10.0 ** rng.uniform(-9, 0, (200, 1))])
    for w in speeds:
        for mu_n, w_reg in ((1500.0, 1e-6), (0.3, 1e-4)):
            f, jac = cons.slip_force(w, mu_n, w_reg)
            got = _slip_force_scalar(w[0], w[1], mu_n, w_reg)
            assert np.array_equal(np.array(got), np.concatenate([f, jac.ravel()]))


@njit
def _both_products(a, x, out):
    """``a @ x`` as numba compiles it, and :func:`matvec_into` into ``out``; also a face's (2, 4) block."""
    ref = a @ x
    matvec_into(a, x, out)
    return ref


def test_matvec_into_is_numbas_matmul_bit_for_bit():
    rng = np.random.default_rng(11)
    for rows, cols in ((6, 26), (26, 26), (2, 4), (1, 1), (7, 3)):
        a = rng.normal(size=(rows, cols)) * 10.0 ** rng.uniform(-8, 8, size=(rows, cols))
        x = rng.normal(size=cols) * 10.0 ** rng.uniform(-8, 8, size=cols)
        out = np.full(rows, np.nan)
        ref = _both_products(a, x, out)
        assert np.array_equal(ref, out)
        assert np.all(np.abs(out - a @ x) <= 1e-13 * (np.abs(a) @ np.abs(x)))   # and it is the product


def test_contact_point_is_contact_kernel_bit_for_bit(run):
    system, _, tr = run
    params = np.asarray(system.support.law.params, float)
    # the run's states (in the clearance) and states pressed 0.01–1 % of the clearance into the support
    rng = np.random.default_rng(3)
    c = system.support.law.clearance_m
    ang = rng.uniform(0.0, 2 * math.pi, 100)
    rad = c * (1.0 + 10.0 ** rng.uniform(-4, -2, 100))
    pressed = np.column_stack([rad * np.cos(ang), rad * np.sin(ang), rng.normal(size=(100, 2)) * 1e-3 * c / 0.015])
    states = list(zip(tr.u, tr.w)) + list(zip(pressed, rng.normal(size=(100, 4)) * 1e-2))
    touched = 0
    for u, w in states:
        f, ju, jv = contact_kernel(u, w, params)
        jac = np.full((4, 8), np.nan)
        got = contact_point(u[0], u[1], u[2], u[3], w[0], w[1], w[2], w[3], params, jac)
        assert np.array_equal(np.array(got), f)
        assert np.array_equal(jac, np.hstack([ju, jv]))
        touched += bool(np.any(f != 0.0))
    assert touched > 50   # pressed states carry force (unless separating fast: (1 + c_c v_n) clipped at zero)


@pytest.mark.parametrize("which", ["run", "run_stuck"])
def test_staged_newton_solve_ends_on_the_forces_and_residual_of_its_result(which, request):
    """At recorded states, _solve_support's α, forces g and face forces are those that _forces and
    _residual (the period map's entry points) give at the returned iterate, and its residual is converged."""
    system, dt, tr = request.getfixturevalue(which)
    pre = prepare(system, dt)
    opts = NewmarkOptions()
    params = np.asarray(system.support.law.params, float)
    bdt2, gdt = opts.beta * dt * dt, opts.gamma * dt
    vec, mat, face, jac = newton_work()
    checked = 0
    kinds = set()
    for i in range(1, len(tr.t), 7):
        p, v, a = pre.T.T @ tr.q[i], pre.T.T @ tr.v[i], pre.T.T @ tr.a[i]
        modes = tr.modes[i].astype(np.int64)
        alpha = pre.Bt @ a
        p_pre = p + dt * v + dt * dt * (0.5 - opts.beta) * a
        v_pre = v + dt * (1.0 - opts.gamma) * a
        u_pre, w_pre = pre.Bt @ p_pre, pre.Bt @ v_pre
        alpha_lin = pre.Bt @ (pre.Ainv @ (-pre.Dr @ v_pre - pre.Kr @ p_pre))
        freeze, fdir = np.zeros(2, dtype=np.bool_), np.zeros((2, 2))
        phi = np.zeros((2, 2))
        its, ok = _solve_support(alpha, alpha_lin, u_pre, w_pre, pre.S, pre.P, modes, tr.face_force[i], freeze, fdir,
                                 pre.limits, pre.a1, bdt2, gdt, params, opts.tol, opts.max_iter, opts.w_reg, vec,
                                 mat, face, jac, phi)
        assert ok and its >= 1
        m = NC + 2 * int(np.sum(modes == 1))
        x = vec[VX].copy()
        g, Jg, phi_f, uu, ww = np.zeros(NC), np.zeros((NC, NC)), np.zeros((2, 2)), np.zeros(NC), np.zeros(NC)
        _forces(x, u_pre, w_pre, bdt2, gdt, pre.P, modes, freeze, fdir, pre.limits, pre.a1, params, opts.w_reg,
                g, Jg, phi_f, uu, ww)
        assert np.array_equal(g, vec[VG, :NC]) and np.array_equal(phi_f, phi)
        R, J = np.zeros(MX), np.zeros((MX, MX))
        nR = _residual(x, m, alpha_lin, u_pre, w_pre, pre.S, pre.P, modes, freeze, fdir, pre.limits, pre.a1, bdt2,
                       gdt, params, opts.w_reg, g, Jg, phi_f, uu, ww, R, J)
        # Newton stopped on a step below tol·|x|: the residual is of that order (J is O(1))
        assert nR <= 1e-6 * (np.linalg.norm(x[:m]) + 1e-12)
        checked += 1
        kinds.add((m > NC, bool(np.any(tr.f_contact[i] != 0.0))))
    assert checked > 100
    # the cases met: 15 000 rpm slipping faces, in and out of contact; 4 500 rpm a stuck face
    assert kinds >= ({(False, False), (False, True)} if which == "run" else {(True, False)})

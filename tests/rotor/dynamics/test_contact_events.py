"""Contact onset and loss located inside the step (rotor.dynamics.contact_events): the crossing of an edge
penetration along the step's cubic Hermite interpolant, against closed forms of motions the cubic reproduces
exactly (the edge offsets of docs/reference/contact-laws.md §8, rotor.dynamics.constraints.edge_offsets)."""
from __future__ import annotations

import numpy as np

from contact.loose_support import LooseSupportParams
from rotor.dynamics import constraints as cons
from rotor.dynamics.contact_events import crossing_fraction, edge_crossing

PARAMS = np.array(LooseSupportParams.paper_table4().kernel_args, dtype=float)
D0, L0 = PARAMS[0], PARAMS[1]


def _ends(f, df, h):
    return np.array(f(0.0)), np.array(df(0.0)), np.array(f(h)), np.array(df(h))


def test_uniform_translation_crosses_at_the_closed_form_time():
    """y(t) = y0 + c t, no tilt: both edges reach |y| = δ0 at t* = (δ0 − y0)/c."""
    h, y0, c = 1e-4, 0.9 * D0, 0.3 * D0 / 1e-4
    u0, w0, u1, w1 = _ends(lambda t: [y0 + c * t, 0.0, 0.0, 0.0], lambda t: [c, 0.0, 0.0, 0.0], h)
    assert edge_crossing(u0, u1, PARAMS)
    assert abs(crossing_fraction(u0, w0, u1, w1, h, PARAMS) - (D0 - y0) / c / h) < 1e-13


def test_tilted_ring_first_edge_on_a_cubic_path():
    """A cubic path (reproduced exactly by the Hermite interpolant) with a tilt θy: the right edge's offset
    |(y, z − θy l0/2)| (edge_offsets) reaches δ0 first, then the left one; the located fraction is the first root
    (bisection of the closed form), and the reversed path loses contact first at the left edge's mirrored root."""
    h, th = 1e-4, 0.2 * D0 / L0

    def f(t):
        s = t / h
        return [0.0, -0.8 * D0 - 0.5 * D0 * s ** 3, th, 0.0]

    def df(t):
        return [0.0, -1.5 * D0 * (t / h) ** 2 / h, 0.0, 0.0]

    u0, w0, u1, w1 = _ends(f, df, h)
    def root(k):                          # edge k's crossing time by bisection of the closed form
        lo, hi = 0.0, h
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if cons.edge_offsets(np.array(f(mid)), L0)[k] < D0 else (lo, mid)
        return lo / h

    for k in (0, 1):
        assert cons.edge_offsets(np.array(f(0.0)), L0)[k] < D0 < cons.edge_offsets(np.array(f(h)), L0)[k]
    t1, t2 = root(0), root(1)
    assert t1 < t2
    assert abs(crossing_fraction(u0, w0, u1, w1, h, PARAMS) - t1) < 1e-12
    # the same path backwards: contact lost first at the left edge, at 1 − t2
    assert abs(crossing_fraction(u1, -w1, u0, -w0, h, PARAMS) - (1.0 - t2)) < 1e-12


def test_no_sign_change_no_event():
    h = 1e-4
    u0, w0, u1, w1 = _ends(lambda t: [0.5 * D0, 0.0, 0.0, 0.0], lambda t: [0.0] * 4, h)
    assert not edge_crossing(u0, u1, PARAMS)
    assert crossing_fraction(u0, w0, u1, w1, h, PARAMS) == 2.0

"""The contact kernel's bilateral offset (slot 14 of contact/_kernel.py): the contact piece of the map extended
across grazing, which rotor/periodic/grazing.py differentiates. Expected values from the law itself: the
linear extension ``h'(0⁺) Δr`` below zero penetration (di Bernardo et al. 2008, a smooth piece continued past
its switching surface), and the unchanged law with the offset at 0."""
from __future__ import annotations

import numpy as np
import pytest

from contact.loose_support import LooseSupportParams
from rotor.dynamics.kernels import contact_kernel

D0 = 50e-6


def _params(law: str, offset_m: float = 0.0, tilt_ignored: bool = False) -> np.ndarray:
    p = np.array(LooseSupportParams(clearance_m=D0, width_m=0.02, bearing_E_Pa=2e9, bearing_nu=0.3, support_E_Pa=2e9,
                                    support_nu=0.3, c_c_s_per_m=0.0, tilt_ignored=tilt_ignored,
                                    law=law).kernel_args, float)
    p[14] = offset_m
    return p


def _force_y(p, radius_m, tilt_rad=0.0):
    f, ju, _ = contact_kernel(np.array([radius_m, 0.0, 0.0, tilt_rad]), np.zeros(4), p)
    return f[0], ju[0, 0]


@pytest.mark.parametrize("law", ["conformal", "pereira"])
@pytest.mark.parametrize("tilt_ignored", [True, False])
def test_offset_zero_is_the_law_and_the_offset_changes_nothing_in_contact(law, tilt_ignored):
    plain, bil = _params(law, 0.0, tilt_ignored), _params(law, 0.5 * D0, tilt_ignored)
    for pen in (1e-9, 1e-6, 1e-3, 0.1, 1.0):
        r = D0 * (1.0 + pen)
        assert _force_y(bil, r) == _force_y(plain, r)          # bit for bit in contact
    assert _force_y(plain, D0 * (1.0 - 1e-6)) == (0.0, 0.0)    # no offset: a gap carries nothing


def test_below_zero_penetration_the_conformal_piece_pulls_with_its_slope_at_zero():
    plain, bil = _params("conformal"), _params("conformal", 0.5 * D0, tilt_ignored=True)
    h = 1e-9 * D0
    f_p, _ = _force_y(plain, D0 + h)
    slope0 = -f_p / h                                           # the law's own h'(0+) l0 (N/m), by its secant
    for gap in (1e-6, 1e-3, 0.1, 0.4):
        f, k = _force_y(bil, D0 * (1.0 - gap))
        assert f == pytest.approx(slope0 * gap * D0, rel=1e-6)  # pulls the ring outwards (+y), linear in the gap
        assert -k == pytest.approx(slope0, rel=1e-6)
    assert _force_y(bil, D0 * (1.0 - 0.6)) == (0.0, 0.0)        # beyond the offset: free again


def test_pereira_piece_has_zero_slope_at_zero_so_nothing_below():
    bil = _params("pereira", 0.5 * D0, tilt_ignored=True)      # h ~ Δr^1.25: h'(0) = 0, grazing is smooth
    assert _force_y(bil, D0 * (1.0 - 1e-3)) == (0.0, 0.0)

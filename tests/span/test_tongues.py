"""A tension fluctuation placed on a span's parametric tongues (drivedyn.mechanics.span.tongues):
against the span analysis's exact Mathieu boundaries, the first-order band and the damped
threshold of the principal tongue."""
from __future__ import annotations

import math

import numpy as np
import pytest

from drivedyn.mechanics.span import mathieu, tongues
from drivedyn.mechanics.span.quantities import SpanProperties, effective_tension, excitation_frequency, natural_frequency

# the seed's T10 belt (seed 002: l = 0.3 m, rhoA = 0.084 kg/m with the density read as 3e3 kg/m^3, EI = 0.045 N m^2)
SPAN = SpanProperties(0.3, 0.084, 0.045)


@pytest.mark.parametrize("n", [1, 2])
def test_undamped_edges_are_the_span_analysis_exact_boundaries(n):
    """At a speed V, mathieu.exact_boundaries gives the pretensions F0 on tongue n's edges for a
    fluctuation F1 at the tooth-passing frequency; the same span at that F0 (f1 = Omega / 2 pi, the
    one-mode frequency of seed eq. 5, depth F1 / N) has an edge of undamped_band at that frequency."""
    V, F1, z, p = 8.0, 20.0, 16, 2 * math.pi * 24e-3 / 16
    fe = float(excitation_frequency(V, z, p)) / (2 * math.pi)
    lo, hi = (float(x) for x in mathieu.exact_boundaries(V, n, SPAN, F1, z, p))
    for F0, k in ((lo, 1), (hi, 0)):      # the lower pretension edge is the upper frequency edge
        f1 = float(natural_frequency(F0, V, SPAN)) / (2 * math.pi)
        band = tongues.undamped_band(f1, F1 / float(effective_tension(F0, V, SPAN)), n)
        assert band[k] == pytest.approx(fe, rel=1e-9)


def test_small_depth_band_is_the_first_order_one():
    """Bolotin's first-order principal band omega = 2 Omega sqrt(1 +- mu), mu = e / 2 (seed eq. 6)."""
    e = 1e-3
    lo, hi = tongues.undamped_band(100.0, e, 1)
    assert lo == pytest.approx(200.0 * math.sqrt(1 - e / 2), rel=1e-6)
    assert hi == pytest.approx(200.0 * math.sqrt(1 + e / 2), rel=1e-6)


@pytest.mark.parametrize("factor,inside", [(0.9, False), (1.1, True)])
def test_damped_principal_threshold_is_four_zeta(factor, inside):
    """Damped Mathieu: the principal tongue opens at 2 f1 when the depth exceeds 4 zeta
    (Nayfeh & Mook 1979, sec. 5.2.6, to first order in zeta)."""
    zeta = 0.02
    p = tongues.place(100.0, 200.0, factor * 4 * zeta, zeta, 1)
    assert p.inside is inside
    assert p.open is inside


def test_screen_holds_the_exact_bands():
    """tongues.screen bounds every undamped band (so that a component beyond it needs no Floquet pass)."""
    for n in (1, 2):
        for e in np.linspace(0.01, 2.0, 60):
            lo, hi = tongues.undamped_band(100.0, e, n)
            c = 200.0 / n
            assert max(abs(lo / c - 1), abs(hi / c - 1)) < tongues.screen(e)


def test_damped_band_inside_the_undamped_one_and_its_edges_neutral():
    """The damped band's edges sit where the Floquet multiplier crosses 1 (within 1e-5 of the band's
    width) and inside the undamped band."""
    p = tongues.place(100.0, 200.0, 0.2, 0.02, 1)
    lo, hi = p.band
    ulo, uhi = p.band_undamped
    assert ulo < lo < 200.0 < hi < uhi
    w = hi - lo
    for f, side in ((lo, -1), (hi, 1)):
        out = float(tongues._rho(100.0, [f + side * 1e-5 * w], 0.2, 0.02)[0])
        inn = float(tongues._rho(100.0, [f - side * 1e-5 * w], 0.2, 0.02)[0])
        assert out < tongues.UNSTABLE < inn

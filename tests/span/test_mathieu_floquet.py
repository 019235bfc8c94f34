"""Reference tests of the stability boundaries: Floquet kernel vs Mathieu characteristic values,
multipliers on/off the unit circle, first order -> exact as mu -> 0, damping (Liouville).

Sources: Abramowitz & Stegun, Handbook of Mathematical Functions, table 20.1 (characteristic
values at q = 1); McLachlan (1947) ch. 4 and Bolotin (1956) for the tongue structure and the
first-order boundaries omega = 2 Omega sqrt(1 +- mu); Liouville's formula for det of the monodromy.
"""
import numpy as np
import pytest
from scipy import optimize, special

from drivedyn.span.fourier import Harmonics
from drivedyn.mechanics.span.floquet import hill_parameters, mathieu_multiplier, multipliers
from drivedyn.mechanics.span.mathieu import characteristic_values, exact_boundaries, first_order_boundaries, speed_band

PITCH = 2 * np.pi * 0.024 / 16


def test_characteristic_values_match_abramowitz_stegun():
    # A&S table 20.1, q = 1 (8 digits)
    lo1, hi1 = characteristic_values(1, 1.0)
    lo2, hi2 = characteristic_values(2, 1.0)
    assert hi1 == pytest.approx(1.85910811, abs=1e-7)
    assert lo1 == pytest.approx(-0.11024882, abs=1e-7)
    assert hi2 == pytest.approx(4.37130098, abs=1e-7)
    assert lo2 == pytest.approx(3.91702477, abs=1e-7)


@pytest.mark.parametrize("q", [0.3, 1.0, 2.5])
@pytest.mark.parametrize("n", [1, 2, 3])
def test_floquet_edges_equal_scipy_characteristic_values(n, q):
    """Bisect the Floquet stability transition in a; it must sit on b_n(q) and a_n(q)."""
    lo, hi = (float(x) for x in characteristic_values(n, q))
    mid = 0.5 * (lo + hi)
    width = hi - lo

    def unstable(a):
        # |tr| / (2 sqrt(det)) - 1: the undamped criterion |tr| > 2 with RK4's slight det < 1 divided out
        tr, det, _ = multipliers(a / 4.0, -q / 2.0, 0.0, [1.0], [0.0], 128)
        return float(abs(tr) / (2.0 * np.sqrt(det)) - 1.0)

    assert unstable(mid) > 0, "tongue centre must be unstable"
    below = special.mathieu_a(0, q) if n == 1 else characteristic_values(n - 1, q)[1]   # previous tongue's top
    above = characteristic_values(n + 1, q)[0]                                           # next tongue's bottom
    for edge, outside in ((lo, 0.5 * (lo + below)), (hi, 0.5 * (hi + above))):
        assert unstable(outside) < 0
        found = optimize.brentq(unstable, outside, mid, xtol=1e-13)
        # RK4 at 128 steps per oscillation: edges to ~1e-7 in a, well inside the thinnest tongue
        assert found == pytest.approx(edge, abs=1e-6)
        assert abs(found - edge) < 0.01 * width


def test_multipliers_on_unit_circle_outside_and_above_one_inside(seed_span):
    """Undamped Hill equation of the seed span with Phi = cos: |lambda| = 1 off the exact tongues."""
    F1 = 3.058
    harm = Harmonics(0.0, np.array([F1]), np.array([0.0]))
    V = np.linspace(0.3, 3.0, 120)
    F0 = np.linspace(5.0, 300.0, 90)
    FF, VV = np.meshgrid(F0, V, indexing="ij")
    al, be, ga = hill_parameters(FF, VV, seed_span, F1, 16, PITCH)
    rho = multipliers(al, be, ga, *harm.shape())[2]
    inside = np.zeros(FF.shape, bool)
    margin = np.full(FF.shape, np.inf)
    for n in (1, 2, 3, 4, 5):
        lo, hi = exact_boundaries(VV, n, seed_span, F1, 16, PITCH)
        inside |= (FF > lo) & (FF < hi)
        with np.errstate(divide="ignore", invalid="ignore"):   # higher tongues: width ~ 0 at high speed
            margin = np.minimum(margin, np.minimum(abs(FF - lo), abs(FF - hi)) / (hi - lo))
    clear = margin > 0.05          # keep away from the edges, where |lambda| -> 1 continuously
    assert inside[clear].sum() > 20 and (~inside[clear]).sum() > 5000
    assert np.all(np.abs(rho[clear & ~inside] - 1.0) < 1e-5)
    assert np.all(rho[clear & inside] > 1.0 + 1e-5)


def test_divergence_above_critical_speed(seed_span):
    F0, V = 100.0, 40.0             # V_cr(100 N) = 35.34 m/s
    al, be, ga = hill_parameters(F0, V, seed_span, 3.058, 16, PITCH)
    assert al < 0
    assert multipliers(al, be, ga, [1.0], [0.0])[2] > 1.0 + 1e-3


def test_first_order_converges_to_exact(seed_span):
    """Seed's boundaries vs exact ones: error / F1 -> 0 like mu (a_1 = 1 + q - q^2/8 + ...)."""
    V = np.linspace(0.5, 2.0, 7)
    errs = []
    for F1 in (3.0, 0.3, 0.03):
        ex = np.array(exact_boundaries(V, 1, seed_span, F1, 16, PITCH))
        fo = np.array(first_order_boundaries(V, seed_span, F1, 16, PITCH))
        errs.append(np.max(np.abs(ex - fo)) / F1)      # relative to the tongue width F1
    assert errs[0] < 0.05
    assert errs[1] < errs[0] / 8 and errs[2] < errs[1] / 8


def test_principal_band_first_order_vs_exact_vs_floquet(seed_span):
    from drivedyn.mechanics.span.chart import floquet_band
    from drivedyn.span.fourier import from_polynomial
    from drivedyn.span.source import Setup

    harm = from_polynomial([0.00139, 0.0337, -0.685, 2.89, -1.71, 7.29])
    ex = speed_band(100.0, 1, seed_span, harm.f1, 16, PITCH)
    fo = speed_band(100.0, 1, seed_span, harm.f1, 16, PITCH, method="first-order")
    fl = floquet_band(100.0, ex, Setup(seed_span, 100.0, 1.0, 16, PITCH, "tooth-passing"), harm, 48)
    width = ex[1] - ex[0]
    assert width > 0.01
    assert np.allclose(fo, ex, atol=0.01 * width)
    # higher harmonics of the tooth force shift the edges only slightly
    assert np.allclose(fl, ex, atol=0.02 * width)


def test_damping_det_is_liouville_and_closes_tongue(seed_span):
    import dataclasses

    damped = dataclasses.replace(seed_span, damping_ratio=0.01)
    al, be, ga = hill_parameters(100.0, 1.11, damped, 3.058, 16, PITCH)
    tr, det, rho = multipliers(al, be, ga, [1.0], [0.0])
    assert det == pytest.approx(np.exp(-2 * np.pi * ga), rel=1e-6)
    # zeta = 0.01 exceeds mu / 2 ~ 0.007: the principal tongue closes
    assert rho < 1.0
    al0, be0, ga0 = hill_parameters(100.0, 1.11, seed_span, 3.058, 16, PITCH)
    assert multipliers(al0, be0, ga0, [1.0], [0.0])[2] > 1.0


def test_mathieu_q_symmetry_used():
    """Boundaries are even in q (shift z by pi/2): our |q| convention relies on it."""
    for n in (1, 2, 3):
        a, b = special.mathieu_a(n, 0.7), special.mathieu_b(n, 0.7)
        assert float(mathieu_multiplier(0.5 * (a + b), -0.7)) > 1.0

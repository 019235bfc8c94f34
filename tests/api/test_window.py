"""The steady window's drift measure (drivedyn.core.window.drift) on signals whose drift is known."""
import numpy as np

from drivedyn.core.window import drift


def _signal(ramp):
    # a span tension at 3000 rpm: the crank's 2nd and 4th orders (100, 200 Hz), a 7th order of an
    # accessory turning 1.25 times crank speed (437.5 Hz) and the drive's period, 4 crank
    # revolutions (80 ms, 12.5 Hz), in a 0.2 s window: 2.5 periods of the slowest part
    t = np.arange(0.6, 0.8 + 1e-12, 5e-4)
    y = (418.0 + 150 * np.sin(2 * np.pi * 100 * t + 0.3) + 60 * np.sin(2 * np.pi * 200 * t)
         + 80 * np.sin(2 * np.pi * 437.5 * t + 1.0) + 40 * np.sin(2 * np.pi * 12.5 * t + 0.7))
    return t, y + ramp * 573.0 * (t - t[0]) / (t[-1] - t[0])


def test_periodic_content_does_not_read_as_drift_over_the_period():
    t, y = _signal(0.0)
    plain = drift(t, y, 573.0)[0]
    assert plain > 0.02                       # the raw fit reads the part periods as drift
    assert drift(t, y, 573.0, period=0.08)[0] < 1e-3


def test_a_real_drift_is_read_with_and_without_the_period():
    t, y = _signal(0.03)
    assert abs(drift(t, y, 573.0, period=0.08)[0] - 0.03) < 1e-3
    # a pure 3 % ramp reads 3 % either way: the moving mean keeps a linear trend's slope
    ramp = 418.0 + 0.03 * 573.0 * (t - t[0]) / (t[-1] - t[0])
    assert abs(drift(t, ramp, 573.0)[0] - 0.03) < 1e-12
    assert abs(drift(t, ramp, 573.0, period=0.08)[0] - 0.03) < 1e-12


def test_a_window_shorter_than_two_periods_is_fitted_raw():
    t, y = _signal(0.0)
    assert drift(t, y, 573.0, period=0.15)[0] == drift(t, y, 573.0)[0]

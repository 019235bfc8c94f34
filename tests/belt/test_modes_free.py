"""The rotational mode of the linearised drive (modes.py) against a free-response run of the
dynamic model: a 2 ms torque pulse on the 5PK driver, then the two pulleys swing against each other
on the spans' stiffness; the spectrum of their relative speed peaks at the mode (issue 12: 3 %)."""
import numpy as np
import pytest

import drivedyn
from drivedyn.mechanics.layout import compute_layout
from drivedyn.belt.steady.modes import modes


def test_free_response_peaks_at_the_linear_mode():
    m = drivedyn.replace(drivedyn.load(drivedyn.example_path("belt-5pk")),
                         {"pulleys.driver.torque_time": [[0, 0], [0.001, 2.0], [0.002, 2.0], [0.003, 0.0]],
                          "pulleys.driven.torque_speed": None, "simulation.duration": 0.5,
                          "output.interval": 2e-4, "output.frames": 2})
    f_lin = modes(m, compute_layout(m)).frequencies_hz
    assert len(f_lin) == 1
    r = drivedyn.run(m)
    t, w = r.ds["time"].values, r.ds["speed"].values
    x = (w[:, 0] - w[:, 1])[t > 0.01]
    x = (x - x.mean()) * np.hanning(len(x))
    n = 16 * len(x)                                   # zero padding: 0.13 Hz between bins
    f = np.fft.rfftfreq(n, t[1] - t[0])
    peak = f[np.argmax(np.abs(np.fft.rfft(x, n)))]
    assert peak == pytest.approx(f_lin[0], rel=0.03)  # measured: 33.16 against 33.02 Hz

    # the Campbell diagram marks order k crossing the mode at n = 60 f / k rpm
    from drivedyn.belt.plots import plot_campbell

    ax = plot_campbell(r.ds, f_lin, "driver", orders=(1, 2), rpm_max=3000.0)
    marks = sorted(ln.get_xdata()[0] for ln in ax.lines if ln.get_marker() == "o")
    assert len(marks) == 2 and marks == pytest.approx([30 * f_lin[0], 60 * f_lin[0]])

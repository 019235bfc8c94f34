"""The run's slip margin (pulleys.<name>.slip_margin: creep theory's load multiplier at gross slip
for the run's mean loads) is computed from the run's own tension level. A drive installed by its
belt part (examples/fead-ag0868.toml: belt.effective_length, no pretension) gave the model's
unstretched length on pitch circles to creep theory, which counts the belt sunk into the grooves:
its spans came out about 160 N slacker than the run's and A_C's margin 4.56 (4.08 in the segment
model's run) where the same loads on the run's tensions give 5.90 (check's duty row at 800 rpm printed 6.25: the difference to it is the
supplier's 10 W drag on the tensioner, which the duty row carries and the run does not).

The reference here is independent of the run: the tensioner's running balance by creep theory
(steady/running.py, the path check's duty rows take) under the run's own mean torques and speed."""
from __future__ import annotations

import numpy as np
import pytest

import drivedyn
from drivedyn.belt.geometry.drive import resolve
from drivedyn.belt.steady.running import running_balance


def test_run_slip_margin_from_the_runs_tensions():
    m = drivedyn.load(drivedyn.example_path("fead-ag0868"))
    m = drivedyn.replace(m, {"simulation.model": "rotational", "simulation.duration": 0.3,
                             "output.steady_window": [0.2, 0.3], "duty_cycle": None,
                             "pulleys.0.speed_time": [[0, 0], [0.1, -83.7758], [0.3, -83.7758]]})
    r = drivedyn.run(m)
    ds = r.ds
    sel = ds["time"].values >= 0.2
    M = ds["torque_applied"].values[sel].mean(axis=0)
    d = resolve(m)
    v = float(ds["speed"].values[sel, 0].mean() * d.layout.rho[0])
    run, why = running_balance(d.model, d.equilibrium, torques=M, speed=v)
    assert run is not None, why
    ref = run[3]
    for name in ("CRK", "A_C"):
        got = r.summary["pulleys"][name]["slip_margin"]
        assert got == pytest.approx(ref.pulleys[name].slip_margin, rel=0.02), (name, got, ref.pulleys[name].slip_margin)
    # and the state it is read from: the run's span tensions, which the reference reproduces within 1 %
    for sp, e in r.summary["spans"].items():
        assert e["tension_mean"] == pytest.approx(ref.spans[sp], rel=0.01), sp
    assert np.isfinite(r.summary["pulleys"]["A_C"]["slip_margin"])

"""A planetary stage's time integration (gears/planetary/dynamics.py) under bad input: a step that
asks for more steps than a run may take, stiffnesses that double precision cannot solve, a torque
that is round-off beside the pin errors' forces, and a constant stiffness whose force ranges are
round-off: a result or one line naming the field, before any memory is asked for, never a
traceback, and no instability read from round-off."""
import time

import pytest

import drivedyn
from drivedyn.core.errors import ModelError


def _stage(**changes):
    model = drivedyn.load(drivedyn.example_path("gears-planetary"))
    return drivedyn.replace(model, {"planetary.dynamics.sweep": False, **changes})


def _one_line(model, *words):
    t0 = time.process_time()
    with pytest.raises(ModelError) as info:
        drivedyn.run(model)
    text = str(info.value)
    assert "\n" not in text and all(w in text for w in words), text
    assert time.process_time() - t0 < 30      # refused before the integration (the run takes 1-2 s)
    return text


def test_the_runs_own_step_counts_against_the_steps_limit():
    """step = 1e-15 s asked numpy for 2.46 PiB of window forces (a MemoryError)."""
    _one_line(_stage(**{"planetary.dynamics.step": "1e-15 s"}), "planetary.dynamics", "integration steps",
              "DRIVEDYN_MAX_STEPS")


def test_the_sweep_counts_against_the_steps_limit_too(monkeypatch):
    monkeypatch.setenv("DRIVEDYN_MAX_STEPS", "1e5")
    text = _one_line(_stage(**{"planetary.dynamics.sweep": True}), "planetary.dynamics", "more than the 1e+05")
    assert "integration steps" in text


@pytest.mark.parametrize("changes", [
    {"planetary.sun_planet_stiffness": "1e-29 N/m"},         # ZeroDivisionError in the kernel
    {"planetary.ring_planet_stiffness": "1e29 N/m"},
])
def test_stiffnesses_double_precision_cannot_solve_are_refused_before_the_integration(changes):
    _one_line(_stage(**changes), "planetary.dynamics", "cannot be solved", "too far apart for double precision")


def test_a_floating_sun_on_planet_pins_of_no_stiffness_is_refused_before_the_integration():
    model = drivedyn.load(drivedyn.example_path("gears-gearbox"))
    model = drivedyn.replace(model, {"planetary.lateral.planet_bearing_stiffness": "1e-20 N/m",
                                     "planetary.dynamics": {"model": "lateral", "speed": "12.1 rpm"}})
    from drivedyn.gears.planetary.dynamics import run

    with pytest.raises(ModelError, match="planetary.dynamics: the stage's time integration cannot be solved"):
        run(model.planetary)


def test_a_torque_of_round_off_beside_the_pin_errors_ends_in_a_result():
    """The quasi-static share divided by a mean force of exactly 0 (ZeroDivisionError in the kernel)."""
    from drivedyn.gears.planetary.dynamics import run

    summary, _ = run(_stage(**{"planetary.torque": "1e-29 N*m"}).planetary)
    assert summary["kv"]["sun-planet"] > 0


def test_no_window_growth_is_read_from_round_off():
    """A constant mesh stiffness holds the forces constant to 2e-10: their ranges' ratio (1.27) read
    as a growing window, and the run warned kv-unstable."""
    import numpy as np

    from drivedyn.gears.planetary.dynamics import window_growth

    halves = np.array([[1000.0 + 2e-7, 1000.0, 1000.0 + 2.5e-7, 1000.0],     # round-off: no growth
                       [1100.0, 900.0, 1300.0, 700.0]])                      # a real range that grows
    g = window_growth(halves)
    assert np.isnan(g[0]) and g[1] == pytest.approx(3.0)
    result = drivedyn.run(_stage(**{"planetary.dynamics.stiffness_model": "constant", "planetary.position_errors": []}))
    assert "kv-unstable" not in [d.code for d in result.diagnostics]
    assert result.summary["planetary"]["dynamics"]["window_growth"] is None


@pytest.mark.parametrize("limit", [None, "inf"])
def test_a_speed_that_asks_for_more_steps_than_an_integer_holds_is_refused(monkeypatch, limit):
    """dynamics.speed = 1e-29 rpm: 1e36 window steps came back negative from int64 (ValueError:
    negative dimensions); with the limit lifted too."""
    if limit:
        monkeypatch.setenv("DRIVEDYN_MAX_STEPS", limit)
    text = _one_line(_stage(**{"planetary.dynamics.speed": "1e-29 rpm"}), "planetary.dynamics", "a higher dynamics.speed")
    assert "integration steps" in text or "GB" in text

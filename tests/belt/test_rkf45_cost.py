"""rkf45 (the seed's explicit integrator) told and counted at its real cost: its step is the friction
law's (segments/system.py, rkf45_step), not the chain's stable step, and each step is six
evaluations of the chain. The 5PK drive with rkf45, 150 segments and 0.5 ms: check said 162 steps
and the run went past 5 minutes (3.8e6 steps of six stages)."""
import pytest

import drivedyn
from drivedyn.core.errors import ModelError


def _rkf45(duration="0.5 ms"):
    model = drivedyn.load(drivedyn.example_path("belt-5pk"))
    return drivedyn.replace(model, {"simulation.method": "rkf45", "belt.segments": 150, "simulation.duration": duration,
                                    "output.segments": [], "output.steady_window": None, "output.interval": "0.1 ms"})


def test_check_gives_rkf45s_own_step_and_steps():
    line = drivedyn.check(_rkf45()).splitlines()[-1]
    assert line.startswith("integration: rkf45 (explicit, adaptive): the friction law limits its step to about 1.3e-10 s")
    assert "3.79e+06 steps of 6 stages" in line, line


def test_rkf45s_stages_count_against_the_steps_limit(monkeypatch):
    monkeypatch.setenv("DRIVEDYN_MAX_STEPS", "1e7")      # 3.8e6 steps fit; their 2.3e7 evaluations do not
    with pytest.raises(ModelError) as info:
        drivedyn.check(_rkf45())
    text = str(info.value)
    assert "simulation.method: rkf45 is explicit" in text and "3.8e+06 steps of 6 stages each (2.3e+07 counted)" in text, text

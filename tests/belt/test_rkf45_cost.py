"""rkf45 (the seed's explicit integrator) told and counted at its real cost: its step is the friction
law's (segments/system.py, rkf45_step), not the chain's stable step, and each step is six
evaluations of the chain. The 5PK drive with rkf45, 150 segments and 0.5 ms: check said 162 steps
and the run went past 5 minutes (3.8e6 steps of six stages); counted as 2.3e7 steps it still ran
10 minutes within the steps limit, as each stage evaluates all 150 segments."""
import subprocess
import sys

import pytest

import drivedyn
from drivedyn.core.errors import ModelError


def _rkf45(duration="0.5 ms"):
    model = drivedyn.load(drivedyn.example_path("belt-5pk"))
    return drivedyn.replace(model, {"simulation.method": "rkf45", "belt.segments": 150, "simulation.duration": duration,
                                    "output.segments": [], "output.steady_window": None, "output.interval": "0.1 ms"})


def test_check_gives_rkf45s_own_step_and_steps(monkeypatch):
    monkeypatch.setenv("DRIVEDYN_MAX_EVALUATIONS", "inf")
    line = drivedyn.check(_rkf45()).splitlines()[-1]
    assert line.startswith("integration: rkf45 (explicit, adaptive): the friction law limits its step to about 1.3e-10 s")
    assert "3.79e+06 steps of 6 stages" in line, line


def test_rkf45s_stages_count_against_the_steps_limit(monkeypatch):
    monkeypatch.setenv("DRIVEDYN_MAX_STEPS", "1e7")      # 3.8e6 steps fit; their 2.3e7 evaluations do not
    with pytest.raises(ModelError) as info:
        drivedyn.check(_rkf45())
    text = str(info.value)
    assert "simulation.method: rkf45 is explicit" in text and "3.8e+06 steps of 6 stages each (2.3e+07 counted)" in text, text


def test_rkf45s_segment_evaluations_are_refused_before_integrating(monkeypatch):
    """steps x stages x segments against the evaluations limit: 3.79e6 x 6 x 150 = 3.4e9 > 1e9,
    refused by check (which never integrates) and so by run before its first step."""
    monkeypatch.delenv("DRIVEDYN_MAX_EVALUATIONS", raising=False)
    monkeypatch.delenv("DRIVEDYN_MAX_STEPS", raising=False)
    model = _rkf45()
    with pytest.raises(ModelError) as info:
        drivedyn.check(model)
    text = str(info.value)
    assert text.startswith("simulation.method: rkf45 is explicit"), text
    assert "3.8e+06 steps of 6 stages of 150 segments" in text and "3.4e+09 segment evaluations" in text, text
    assert "more than the 1e+09" in text and "DRIVEDYN_MAX_EVALUATIONS" in text, text
    # the count is the segments': half of them for a tenth of the time fits (1.7e8)
    monkeypatch.setenv("DRIVEDYN_MAX_EVALUATIONS", "1.8e8")
    drivedyn.check(drivedyn.replace(_rkf45("0.05 ms"), {"belt.segments": 75}))
    monkeypatch.setenv("DRIVEDYN_MAX_EVALUATIONS", "1.6e8")
    with pytest.raises(ModelError, match="1.7e\\+08 segment evaluations"):
        drivedyn.check(drivedyn.replace(_rkf45("0.05 ms"), {"belt.segments": 75}))


def test_the_command_line_refuses_it_in_one_line(tmp_path):
    sets = ["simulation.method=rkf45", "belt.segments=150", "simulation.duration=0.5 ms", "output.interval=0.1 ms",
            "output.segments=[]"]
    cmd = [sys.executable, "-m", "drivedyn", "run", str(drivedyn.example_path("belt-5pk")), "-o", str(tmp_path / "out")]
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=120, check=False)
    assert p.returncode == 2, p.stderr
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and "simulation.method: rkf45 is explicit" in lines[0], p.stderr
    assert not (tmp_path / "out" / "results.nc").exists()

"""Bad input: one line naming the field, exit status 2; a diverging solve keeps its results."""
import pytest

import drivedyn
from drivedyn.front.cli import main

GOOD = drivedyn.example_path("belt-5pk").read_text().replace("segments = [302]", "segments = [10]")


def run_cli(tmp_path, text, capsys, cmd="check"):
    f = tmp_path / "m.toml"
    f.write_text(text)
    code = main([cmd, str(f)])
    err = capsys.readouterr().err.strip()
    return code, err


@pytest.mark.parametrize("edit, expect", [
    (('radius = "27 mm"', 'radius = "-27 mm"', 1), "pulleys[0].radius"),
    (('center = ["515 mm", "0 mm"]', 'center = ["40 mm", "0 mm"]', 1), "overlap"),
    (('pretension = "550 N"', 'length = "1.0 m"', 1), "too short"),
    (('segments = "auto"', 'segments = 150\nsegmnets = 3', 1), "did you mean 'segments'"),
    (('[contact]', '[contact\n', 1), "not valid TOML"),
    (('inertia = "0.02 kg*m^2"', 'inertia = "0.02 kg"', 1), "inertia"),
    (('segments = "auto"', 'segments = 30', 1), "too coarse"),
    (('kind = "belt-drive"', 'kind = "belt_drive"', 1), "did you mean 'belt-drive'"),
    (('kind = "belt-drive"', 'kind = "study"', 1), "study file"),
])
def test_bad_input_one_line_exit_2(tmp_path, capsys, edit, expect):
    old, new, count = edit
    code, err = run_cli(tmp_path, GOOD.replace(old, new, count), capsys)
    assert code == 2
    assert len(err.splitlines()) == 1, err
    assert expect in err
    assert "m.toml" in err              # every model error names the file, also those found while assembling


def test_missing_file(capsys):
    assert main(["run", "/nonexistent/model.toml"]) == 2
    assert "file not found" in capsys.readouterr().err


def test_diverging_solve_keeps_results(model_factory, tmp_path):
    m = model_factory(simulation__step=2e-5, simulation__duration=0.05,   # ~5x the stability limit
                      simulation__method="semi-implicit")                  # (the implicit scheme has none)
    with pytest.raises(drivedyn.SolverError, match=r"diverged at t = .* s: ") as info:
        drivedyn.run(m)
    part = info.value.partial
    assert part is not None and not part.success
    assert part.ds.sizes["time"] >= 0
    part.save(tmp_path)                    # what was computed can be written


def test_roundtrip_of_examples():
    for name in ("belt-5pk", "belt-accessory", "belt-verification"):
        m = drivedyn.load(drivedyn.example_path(name))
        assert drivedyn.loads(drivedyn.dumps(m)) == m


def _raising_after(real, calls):
    """``real`` for ``calls`` calls, then a ZeroDivisionError, as a compiled step raises when a
    state runs away (a span or joint of zero length)."""
    count = [0]

    def step(*args):
        count[0] += 1
        if count[0] > calls:
            raise ZeroDivisionError("division by zero")
        return real(*args)
    return step


def test_a_division_by_zero_in_the_step_keeps_results(model_factory, monkeypatch, tmp_path):
    from drivedyn.belt.segments import _kernels as K

    monkeypatch.setattr(K, "_advance", _raising_after(K._advance, 20))
    m = model_factory(simulation__duration=0.05, simulation__method="semi-implicit")
    with pytest.raises(drivedyn.SolverError, match=r"diverged after t = .* division by zero") as info:
        drivedyn.run(m)
    part = info.value.partial
    assert part is not None and not part.success
    assert 0 < part.ds.sizes["time"] < 0.05 / m.output.interval
    part.save(tmp_path)


@pytest.mark.parametrize("runup", ["time", "periodic"])
def test_a_division_by_zero_in_the_rotational_step_keeps_results(monkeypatch, runup):
    from drivedyn.belt.rotational import _kernels as RK

    monkeypatch.setattr(RK, "run_samples", _raising_after(RK.run_samples, 20))
    m = drivedyn.replace(drivedyn.load(drivedyn.example_path("fead-runup")),
                         {"simulation.model": "rotational", "simulation.runup": runup})
    with pytest.raises(drivedyn.SolverError, match="diverged .* division by zero") as info:
        drivedyn.run(m)
    assert info.value.partial is not None and not info.value.partial.success

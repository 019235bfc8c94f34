"""A periodic run-up solves for a period of at most 8 crank revolutions; an excitation that does not
repeat within them has no such solution, and the run is refused in one line before any work (it
ended `success` with span minima 33-45 % low against the time integration when it took 8
revolutions as the period anyway)."""
import pytest

import drivedyn
from drivedyn.belt.dynamics.runup import period_revolutions
from drivedyn.mechanics.layout import compute_layout


def _periodic(changes):
    base = drivedyn.load(drivedyn.example_path("fead-runup"))
    return drivedyn.replace(base, {"simulation.model": "rotational", "simulation.runup": "periodic", **changes})


def test_the_examples_excitation_repeats_in_four_revolutions():
    """Orders 2 and 4 of the crank and the compressor's 7th at 1.25 times the crank's speed: 8.75
    per crank revolution, whole after 4."""
    m = _periodic({})
    lay = compute_layout(m)
    assert period_revolutions(m, 0, lay.rho, strict=True) == 4


@pytest.mark.parametrize("changes", [
    {"pulleys.0.speed_orders": [{"order": 2.0625, "amplitude": 3.0}]},        # repeats after 16 revolutions
    {"pulleys.1.radius": 0.075 / 1.3},                                           # the compressor's 7th at 1.3: 9.1 per rev
])
def test_an_excitation_that_does_not_repeat_is_refused_before_any_work(changes):
    with pytest.raises(drivedyn.ModelError) as info:
        drivedyn.run(_periodic(changes))
    text = str(info.value)
    assert "simulation.runup" in text and "runup = \"time\"" in text and "\n" not in text


def test_a_crawling_crank_is_refused_before_any_work():
    """0.01-0.1 rpm: one period at each speed is millions of steps; the sweep ran without end, it is
    now refused against the limit time integrations honour (DRIVEDYN_MAX_STEPS)."""
    m = _periodic({"pulleys.0.speed_time": [[0.0, -0.001], [4.8, -0.01]], "output.runup_bin": "0.03 rpm"})
    with pytest.raises(drivedyn.ModelError) as info:
        drivedyn.run(m)
    text = str(info.value)
    assert "simulation.runup" in text and "DRIVEDYN_MAX_STEPS" in text and "\n" not in text


def test_a_sweep_past_the_memory_limit_is_refused_before_any_work(monkeypatch, tmp_path):
    """425 crank speeds of 384 samples (10 rpm bins): about 0.37 GB of recorded periods, past a
    DRIVEDYN_MAX_BYTES of 0.1 GB that the time run's own estimate (17 MB) fits; it ran past the limit."""
    from drivedyn.front.cli import main

    monkeypatch.setenv("DRIVEDYN_MAX_BYTES", "1e8")
    m = _periodic({"output.runup_bin": "10 rpm"})
    with pytest.raises(drivedyn.ModelError) as info:
        drivedyn.run(m)
    text = str(info.value)
    assert "simulation.runup" in text and "DRIVEDYN_MAX_BYTES" in text and "runup_bin" in text and "\n" not in text
    path = tmp_path / "m.toml"
    drivedyn.save(m, path)
    assert main(["run", str(path), "-o", str(tmp_path / "out")]) == 2


@pytest.mark.parametrize("table", [
    [[0.0, 83.8], [4.8, -600.0]],                   # ran, swept as -800..-5730 rpm, status success
    [[0.0, 0.0], [0.3, 83.8], [4.8, -83.8]],        # refused with "holds one speed after its spin-up"
])
def test_a_reversing_crank_is_refused_as_reversing(table):
    with pytest.raises(drivedyn.ModelError) as info:
        _periodic({"pulleys.0.speed_time": table})
    text = str(info.value)
    assert "pulleys[0].speed_time" in text and "reverses" in text and "spin-up" not in text and "\n" not in text


def test_a_drive_without_grip_ends_with_its_report(tmp_path, capfd):
    """friction.coefficient = 1e-6: the periodic run-up ends with every span slack (status warning,
    gross slip); the Campbell painter's wrap compliance failed with a singular matrix after the run
    and no report was written, and the spectrum plot warned of a log axis with no positive values."""
    from drivedyn.front.cli import main

    code = main(["run", str(drivedyn.example_path("fead-runup")), "-o", str(tmp_path / "out"), "-q",
                 "--set", "simulation.model=\"rotational\"", "--set", "simulation.runup=\"periodic\"",
                 "--set", "output.runup_bin=\"1000 rpm\"", "--set", "friction.coefficient=1e-6"])
    err = capfd.readouterr().err
    assert code == 0 and (tmp_path / "out" / "report.html").exists() and (tmp_path / "out" / "campbell.png").exists()
    assert "Traceback" not in err and "Warning" not in err, err[-800:]


@pytest.mark.parametrize("width", [1e29, "5000 rpm"])
def test_a_bin_that_leaves_one_crank_speed_is_refused(width):
    """1e29 rad/s bins: no bin at all (np.arange past float resolution), a traceback from min() of
    nothing; 5000 rpm: one held speed, whose run-up tables were left out without a word."""
    with pytest.raises(drivedyn.ModelError) as info:
        drivedyn.run(_periodic({"output.runup_bin": width}))
    assert str(info.value).startswith("output.runup_bin: ") and "at least two" in str(info.value)

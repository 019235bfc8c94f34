"""Studies with mode = "optimise": differential evolution over the ranged parameters, against a
reference found here by bisection on check's data (the 5PK drive's least pretension with a slip
margin of 1.5), the cache on a re-run, and the input errors."""
import pytest
from scipy.optimize import brentq

import drivedyn
from drivedyn.core.analyses import analysis
from drivedyn.core.errors import ModelError
from drivedyn.study.execute import run_optimisation
from drivedyn.study.spec import load_study

STUDY = """
kind = "study"
name = "least pretension, slip margin 1.5"
base = "{belt}"
mode = "optimize"

[[parameters]]
path = "belt.pretension"
range = ["200 N", "800 N"]

[optimise]
objective = "installation.spans.driver-driven.tension"
constraints = [{ key = "steady.slip_margin", min = 1.5 }, { key = "steady.pulleys.*.slip_arc", max = "3 rad" }]
evaluate = "check"
budget = 60
population = 10
"""


def _margin(T):
    m = drivedyn.replace(drivedyn.load(drivedyn.example_path("belt-5pk")), {"belt.pretension": T})
    return analysis("belt-drive").check_data(m)["steady"]["slip_margin"]


def test_optimum_against_bisection_and_the_cache(client, write_study, tmp_path):
    T_ref = brentq(lambda T: _margin(T) - 1.5, 200.0, 800.0, xtol=1e-3)
    path = write_study(STUDY)
    run = run_optimisation(load_study(path), tmp_path / "out", client=client, plots=True)
    o = run.optimum
    assert o.values is not None
    # the least tension that keeps the margin: within 1 % of bisection, never below it
    assert o.values["belt.pretension"] == pytest.approx(T_ref, rel=0.01)
    assert o.constraints["steady.slip_margin"]["value"] >= 1.5
    assert len(o.evaluations) == 60
    ds = run.ds
    assert ds.sizes["case"] == 60 and int(ds["feasible"].sum()) >= 1
    assert float(ds["objective"].min()) == pytest.approx(o.objective)
    best = drivedyn.load(tmp_path / "out" / "best.toml")
    assert best.belt.pretension == pytest.approx(o.values["belt.pretension"])
    assert (tmp_path / "out" / "plots" / "optimise.png").exists()
    # the same study again: every design from the cache, the same optimum
    again = run_optimisation(load_study(path), tmp_path / "out", client=client, plots=False)
    assert again.counts["ran"] == 0
    assert again.optimum.values == o.values


@pytest.mark.parametrize("change, message", [
    ('mode = "optimize"', ""),
    ("[optimise]", "goes with mode"),
    ('range = ["200 N", "800 N"]', "range"),
    ('constraints = [{ key = "steady.slip_margin", min = 1.5 }', "give min or max"),
])
def test_input_errors(write_study, change, message):
    text = STUDY
    if change == 'mode = "optimize"':
        text = text.replace('mode = "optimize"\n', "")           # [optimise] without the mode
        message = "goes with mode"
    elif change == "[optimise]":
        text = text.replace('mode = "optimize"\n', 'mode = "run"\n')
    elif change.startswith("range"):
        text = text.replace(change, "values = [300, 400]")
    else:
        text = text.replace('{ key = "steady.slip_margin", min = 1.5 }', '{ key = "steady.slip_margin" }')
    with pytest.raises(ModelError, match=message):
        load_study(write_study(text))


def _cached_designs(out):
    return sorted(p.name for p in (out / "cases").glob("*.json"))


def test_a_misspelt_objective_is_refused_before_the_first_generation(client, write_study, tmp_path):
    # the first design is evaluated alone and the keys read against its result: one design, not
    # a generation of ten (nor two generations, scipy asking for a second before its callback)
    path = write_study(STUDY.replace("driver-driven.tension", "driver-driven.tensoin"))
    with pytest.raises(ModelError, match="optimise.objective: .*did you mean 'installation.spans.driver-driven.tension'"):
        run_optimisation(load_study(path), tmp_path / "out", client=client, plots=False)
    assert len(_cached_designs(tmp_path / "out")) == 1


def test_a_bound_whose_unit_only_a_result_tells_is_refused_at_the_first_design(client, write_study, tmp_path):
    # a key the unit table does not list ('*.tension' is any section's): its unit comes with the
    # first design (check's data carry their units: '100 kg' was read as 100 N)
    path = write_study(STUDY.replace('{ key = "steady.slip_margin", min = 1.5 }',
                                     '{ key = "*.driver-driven.tension", min = "100 kg" }'))
    with pytest.raises(ModelError, match=r"optimise.constraints\[0\].min: '100 kg' is not compatible with 'N'"):
        run_optimisation(load_study(path), tmp_path / "out", client=client, plots=False)
    assert len(_cached_designs(tmp_path / "out")) == 1


def test_dry_run_lists_the_design_variables(write_study, tmp_path, capsys):
    from drivedyn.front.study_command import main

    assert main(write_study(STUDY), out=tmp_path / "out", dry_run=True) == 0
    assert not (tmp_path / "out" / "study.nc").exists()


def test_an_optimum_on_a_bound_is_said(client, write_study, tmp_path):
    """Without the constraints the least pretension is the range's lower end (200 N): the
    optimum may lie outside the design space, which the command prints and report.html lists
    (before, the best design was printed without a word, and the report was not written)."""
    from drivedyn.front.study_report import write_optimisation_report
    from drivedyn.study.optimise import on_bounds

    text = STUDY.replace('constraints = [{ key = "steady.slip_margin", min = 1.5 }, { key = "steady.pulleys.*.slip_arc", '
                         'max = "3 rad" }]', "constraints = []")
    study = load_study(write_study(text))
    run = run_optimisation(study, tmp_path / "out", client=client, plots=False)
    hits = on_bounds(study, run.optimum.values)
    assert [(h["name"], h["side"], h["bound"]) for h in hits] == [("belt.pretension", "lower", 200.0)]
    page = write_optimisation_report(run, study, "s.toml", tmp_path / "out", hits).read_text()
    assert "optimum-on-bound" in page and "belt.pretension" in page
    # an optimum inside its range: nothing said
    inside = dict(run.optimum.values, **{"belt.pretension": 390.0})
    assert on_bounds(study, inside) == []


def test_the_study_command_writes_an_optimisations_report_and_says_a_bound(write_study, tmp_path, capsys):
    """``drivedyn study --report`` on an optimisation: report.html written and the optimum on a
    bound said on the terminal (the option was silently ignored for an optimisation)."""
    from drivedyn.front.cli import main

    text = STUDY.replace('constraints = [{ key = "steady.slip_margin", min = 1.5 }, { key = "steady.pulleys.*.slip_arc", '
                         'max = "3 rad" }]', "constraints = []").replace("budget = 60", "budget = 20")
    out = tmp_path / "out"
    assert main(["study", str(write_study(text)), "-o", str(out), "--report", "--no-plots", "-q"]) == 0
    page = (out / "report.html").read_text()
    assert "optimum-on-bound" in page and "belt.pretension" in page
    assert "belt.pretension sits on the lower bound of its range (200 N)" in capsys.readouterr().err


OVAL = """
kind = "study"
name = "oval crank, small"
base = "{cam}"
mode = "optimise"

[overrides]
"simulation.model" = "rotational"
"simulation.runup" = "periodic"
"simulation.duration" = "1 s"
"output.runup_bin" = "500 rpm"
"pulleys.CRK.speed_time" = [["0 s", "1000 rpm"], ["1 s", "3000 rpm"]]
"pulleys.CRK.pitch_curve" = {{ kind = "oval", ovality = 0.0, phase = "0 deg" }}

[[parameters]]
path = "pulleys.CRK.pitch_curve.ovality"
range = [0.0, 0.04]

[[parameters]]
path = "pulleys.CRK.pitch_curve.phase"
range = ["0 deg", "180 deg"]

[optimise]
objective = "runup.order_peaks.span_tension.CRK-CAM1.2.amplitude"
sense = "minimise"
evaluate = "run"
budget = 6
population = 3
seed = 1
"""


def test_a_run_up_objective_is_compared_through_the_speed_range(tmp_path, capsys):
    """An optimisation whose objective is a run-up's order peak: the base file's design (the round
    sprocket) and the best design run once more in full, their order amplitude bin by bin in the
    report, a plot and the terminal; the re-runs reproduce what the optimisation's lean evaluations
    scored (the peaks are the largest bins, to round-off)."""
    from drivedyn.front.cli import main

    path = tmp_path / "oval.toml"
    path.write_text(OVAL.format(cam=drivedyn.example_path("timing-cam-drive").as_posix()))
    out = tmp_path / "out"
    assert main(["study", str(path), "-o", str(out), "--report", "-q"]) == 0
    run = run_optimisation(load_study(path), out, plots=False)        # every design from the cache
    sr, o = run.speed_range, run.optimum
    assert sr is not None and len(sr.rpm) == len(sr.base) == len(sr.best) >= 4 and sr.unit == "N"
    assert max(sr.base) == pytest.approx(o.start["objective"], rel=1e-9)
    assert max(sr.best) == pytest.approx(o.objective, rel=1e-9)
    assert max(sr.best) < max(sr.base)
    page = (out / "report.html").read_text()
    assert "Through the speed range" in page and "speed_range.png" in page
    assert (out / "plots" / "speed_range.png").exists()
    assert "through the speed range (" in capsys.readouterr().err

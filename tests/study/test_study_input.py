"""Bad study files give one-line ModelErrors before anything runs; designs are what they claim."""
from __future__ import annotations

import numpy as np
import pytest

from drivedyn import ModelError
from drivedyn.front.cli import main as cli_main
from drivedyn.study import load_study, make_design

OK = """
base = "{belt}"
[[parameters]]
path = "belt.pretension"
values = [500.0, 600.0]
"""


OPT = """
base = "{belt}"
mode = "optimise"
[[parameters]]
path = "belt.pretension"
range = [400.0, 600.0]
[optimise]
objective = "pulleys.driven.slip"
"""


@pytest.mark.parametrize("text, expect", [
    (OK.replace("belt.pretension", "belt.pretensoin"), "did you mean 'pretension'"),
    (OK.replace("belt.pretension", "pulleys.idler.radius"), "no item 'idler'"),
    (OK.replace("belt.pretension", "belt"), "whole table"),
    (OK + '[sampler]\nmethod = "latin"\n', "unknown sampler 'latin'"),
    (OK + '[sampler]\nmethod = "sobl"\nsamples = 4\n', "did you mean 'sobol'"),
    (OK.replace('base = "{belt}"', 'base = "nowhere.toml"'), "not found"),
    (OK.replace("values = [500.0, 600.0]", 'values = ["500 m"]'), "not compatible"),
    (OK.replace("values = [500.0, 600.0]", 'range = [400.0, 500.0]'), "needs num"),
    (OK + "colour = 1\n", "unknown key"),
    (OK + '[sampler]\nmethod = "lhs"\n', "needs samples"),
    # NaN and infinite bounds (a NaN constraint marked every design feasible), seeds numpy refuses,
    # populations past the cases a study may have: refused before anything runs
    (OK.replace("values = [500.0, 600.0]", 'range = ["nan", 30.0]\nnum = 2'), "must be a finite number"),
    # a reversed range (every sampled design then failed as infeasible, exit 1, late)
    (OPT.replace("range = [400.0, 600.0]", "range = [600.0, 400.0]"), "parameters[0].range: [600.0, 400.0] is [low, high]"),
    (OPT + 'constraints = [{ key = "spans.*.tension_min", max = "nan N" }]\n', "must be a finite number"),
    (OPT + 'seed = -1\n', "must lie in [0, 2^32)"),
    (OPT + 'sense = ["maximise"]\n', "optimise.sense"),       # a list: a TypeError (unhashable) before
    (OPT + 'population = 10000000\n', "more than the"),
    (OPT + 'budget = 4\n', "less than one generation, 6 designs"),
    (OPT.replace("belt.pretension", "belt.segments").replace("range = [400.0, 600.0]", "range = [150.2, 150.8]\ninteger = true"),
     "holds no integer"),
    # a bound in a unit other than its key's (a run's tension in N; check's in N): refused when read
    (OPT + 'constraints = [{ key = "spans.*.tension_min", min = "100 kg" }]\n',
     "optimise.constraints[0].min: '100 kg' is not compatible with 'N'"),
    (OPT + 'evaluate = "check"\nconstraints = [{ key = "steady.spans.*.tension", max = "2 rad" }]\n',
     "optimise.constraints[0].max: '2 rad' is not compatible with 'N'"),
    (OPT + 'constraints = [{ key = "pulleys.*.slip", max = "3 m" }]\n', "the unit of 'pulleys.*.slip' is 1"),
    (OPT + 'constraints = [{ key = "pulleys.*.slip", max = true }]\n', "must be a number or a quantity"),
])
def test_bad_study_input_is_one_line_model_error(write_study, text, expect):
    path = write_study(text)
    with pytest.raises(ModelError) as err:
        load_study(path)
    msg = str(err.value)
    assert expect in msg and "\n" not in msg and str(path) in msg


def test_cli_reports_bad_study_on_one_line(write_study, capsys):
    path = write_study(OK.replace("belt.pretension", "belt.pretensoin"))
    assert cli_main(["study", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("drivedyn: error:") and len(err.splitlines()) == 1
    assert cli_main(["study", str(path.with_name("missing.toml"))]) == 2


def test_cli_refuses_a_constraint_in_the_wrong_unit_before_any_case(write_study, tmp_path, capsys):
    path = write_study(OPT + 'constraints = [{ key = "spans.*.tension_min", min = "100 kg" }]\n')
    assert cli_main(["study", str(path), "-o", str(tmp_path / "out"), "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "optimise.constraints[0].min" in err and "kg" in err
    assert not (tmp_path / "out").exists()


def test_constraints_in_the_keys_units_are_read(write_study):
    ok = OPT + ('constraints = [{ key = "spans.*.tension_min", min = "0.1 kN" }, { key = "pulleys.*.slip", max = "1 %" },'
                ' { key = "pulleys.driven.speed_mean", min = "1500 rpm" }, { key = "no.such.key", max = 3 }]\n')
    assert load_study(write_study(ok)).spec.optimise.constraints[0].min == "0.1 kN"


def test_grid_design_and_units(write_study):
    study = load_study(write_study("""
        base = "{belt}"
        [[parameters]]
        path = "belt.pretension"
        range = ["0.4 kN", "0.7 kN"]
        num = 4
        [[parameters]]
        path = "friction.law"
        values = ["threlfall", "elastic-plastic"]
    """))
    d = make_design(study)
    assert d.grid and d.shape == (4, 2)
    assert d.axes["belt.pretension"] == [400.0, 500.0, 600.0, 700.0]
    assert d.cases[1] == {"belt.pretension": 400.0, "friction.law": "elastic-plastic"}  # last varies fastest
    assert study.units == {"belt.pretension": "N", "friction.law": ""}


@pytest.mark.parametrize("method", ["lhs", "sobol", "montecarlo"])
def test_sampled_designs_are_seeded_and_in_range(write_study, method):
    text = f"""
        base = "{{belt}}"
        [[parameters]]
        path = "belt.pretension"
        range = [400.0, 800.0]
        [[parameters]]
        path = "pulleys.driven.inertia"
        mean = 0.02
        std = 0.001
        [[parameters]]
        path = "belt.segments"
        values = [120, 150]
        integer = true
        [sampler]
        method = "{method}"
        samples = 64
        seed = 3
    """
    d1 = make_design(load_study(write_study(text)))
    d2 = make_design(load_study(write_study(text, "again.toml")))
    assert d1.cases == d2.cases and not d1.grid and d1.shape == (64,)
    pre = np.array([c["belt.pretension"] for c in d1.cases])
    inertia = np.array([c["pulleys.driven.inertia"] for c in d1.cases])
    assert ((pre >= 400) & (pre <= 800)).all()
    assert abs(inertia.mean() - 0.02) < 0.0006 and 0.0005 < inertia.std() < 0.0015
    assert {c["belt.segments"] for c in d1.cases} == {120.0, 150.0}
    if method == "lhs":  # one point per stratum
        assert np.array_equal(np.sort(np.floor((pre - 400) / (400 / 64))), np.arange(64))
    d3 = make_design(load_study(write_study(text.replace("seed = 3", "seed = 4"), "other.toml")))
    assert d3.cases != d1.cases


def test_cli_runs_a_small_study_end_to_end(write_study, tmp_path, capsys):
    path = write_study("""
        base = "{belt}"
        [overrides]
        "simulation.duration" = "5 ms"
        [[parameters]]
        path = "belt.pretension"
        values = ["500 N", "600 N"]
        [outputs]
        summary = ["pulleys.driven.slip", "no.such.key"]
    """)
    out = tmp_path / "cli-out"
    assert cli_main(["study", str(path), "-o", str(out), "--workers", "2", "-q"]) == 0
    err = capsys.readouterr().err
    import re

    counts = re.search(r"2 cases: (\d) succeeded, (\d) warned, 0 did not", " ".join(err.split()))
    assert counts and int(counts[1]) + int(counts[2]) == 2 and "no.such.key" in err
    assert err.count("warning: ") >= int(counts[2])   # each warned case listed with its diagnostics
    if int(counts[2]):
        assert "warning: belt.pretension = " in " ".join(err.split())     # named by its parameters
    assert (out / "study.nc").exists() and len(list((out / "plots").glob("*.png"))) == 1
    assert cli_main(["study", str(path), "-o", str(out), "-q"]) == 0
    assert "0 run now, 2 from the cache" in capsys.readouterr().err
    # the study shrinks: --prune drops the record (and journal) of the case no longer in it
    path.write_text(path.read_text().replace('"500 N", "600 N"', '"500 N"'))
    assert len(list((out / "cases").glob("*.json"))) == 2
    assert cli_main(["study", str(path), "-o", str(out), "-q", "--dry-run", "--prune"]) == 0
    assert "--prune would remove 1 cached case(s)" in capsys.readouterr().err
    assert cli_main(["study", str(path), "-o", str(out), "-q", "--prune"]) == 0
    err = capsys.readouterr().err
    assert re.search(r"1 cases: (1 succeeded, 0 warned|0 succeeded, 1 warned), 0 did not", " ".join(err.split()))
    assert "0 run now, 1 from the cache" in err and "pruned 1 cached case(s)" in err
    assert len(list((out / "cases").glob("*.json"))) == 1 and len(list((out / "cases").glob("*.log"))) == 1


def test_relative_file_references_in_the_base_model_become_absolute(tmp_path):
    # a case runs from its TOML text alone: a model's reference to another file must not depend
    # on the worker's folder
    from drivedyn.study.spec import _absolute_files

    (tmp_path / "drive.toml").write_text("")
    data = {"span": {"belt_model": "drive.toml", "note": "drive"}, "rows": [["missing.csv", 1.0]]}
    assert _absolute_files(data, tmp_path)
    assert data["span"]["belt_model"] == str((tmp_path / "drive.toml").resolve())
    assert data["span"]["note"] == "drive" and data["rows"][0][0] == "missing.csv"
